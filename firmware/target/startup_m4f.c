/* SPDX-License-Identifier: Apache-2.0 */
/*
 * startup_m4f.c: minimal Cortex-M4F startup for test images on QEMU's mps2-an386 board.
 * Vector table, FPU enable (CPACR), .data copy, .bss zero, newlib semihosting init, then
 * exit(main()). Faults exit through semihosting with a distinctive code instead of hanging.
 * Not part of the firmware library: a board support stub for tests and benchmarks.
 */
#include <stdint.h>
#include <stdlib.h>

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
extern int main(void);
extern void initialise_monitor_handles(void);
extern void __libc_init_array(void);

void Reset_Handler(void);
void Fault_Handler(void);
void _init(void);
void _fini(void);

/** Exit code a test image returns when the core faults (HardFault, MemManage, BusFault, ...). */
#define UVMS_FAULT_EXIT_CODE 97

__attribute__((section(".isr_vector"), used)) static void (*const vector_table[16])(void) = {
    (void (*)(void))(&_estack), /* initial stack pointer */
    Reset_Handler,              /* reset */
    Fault_Handler,              /* NMI */
    Fault_Handler,              /* HardFault */
    Fault_Handler,              /* MemManage */
    Fault_Handler,              /* BusFault */
    Fault_Handler,              /* UsageFault */
    0, 0, 0, 0,                 /* reserved */
    Fault_Handler,              /* SVCall */
    Fault_Handler,              /* DebugMonitor */
    0,                          /* reserved */
    Fault_Handler,              /* PendSV */
    Fault_Handler,              /* SysTick */
};

void Reset_Handler(void) {
  /* Enable CP10/CP11 (the FPU) with full access before any float instruction runs. */
  volatile uint32_t *const cpacr = (volatile uint32_t *)0xE000ED88u;
  *cpacr |= (0xFu << 20);
  __asm volatile("dsb\n\tisb" ::: "memory");

  const uint32_t *src = &_sidata;
  for (uint32_t *dst = &_sdata; dst < &_edata;) *dst++ = *src++;
  for (uint32_t *dst = &_sbss; dst < &_ebss;) *dst++ = 0u;

  initialise_monitor_handles();
  __libc_init_array();
  exit(main());
}

void Fault_Handler(void) { _Exit(UVMS_FAULT_EXIT_CODE); }

void _init(void) {}
void _fini(void) {}
