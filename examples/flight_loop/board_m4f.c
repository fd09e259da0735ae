/* SPDX-License-Identifier: Apache-2.0 */
/*
 * board_m4f.c: the board layer for QEMU's mps2-an386 (ARM Cortex-M4F, FPv4-SP FPU): vector
 * table and reset handler, SysTick as the tick timer, the CMSDK APB UART0 for telemetry, and
 * semihosting only to read the command line and to exit with a code (what a test harness
 * needs; a flight computer would reset or idle instead). Nothing here allocates, and no
 * newlib system call is used (no stdio, no rdimon/nosys): the image links libc_nano only for
 * memcpy/memset, libm for sinf/cosf/atan2f and libgcc for __aeabi_ul2f (README "Cross-compiling
 * for Cortex-M4F").
 *
 * Clock. BOARD_CORE_CLOCK_HZ is the frequency SysTick counts with CLKSOURCE = processor clock:
 * the board's SYSCLK, 25 MHz on mps2-an386 (QEMU models it so). The tick period in cycles
 * (app.c: 0.03 s → 750 000 cycles, reload 749 999) must fit SysTick's 24-bit reload.
 * Under QEMU the timer runs on the emulator's virtual clock: real time without -icount, or
 * 2^shift ns per instruction with -icount shift=N (deterministic; sleep=off lets WFI skip the
 * idle time at once). examples/README.md says which options the tests use and why.
 */
#include <stdint.h>

#include "board.h"

#define BOARD_CORE_CLOCK_HZ 25000000u /* mps2-an386 SYSCLK [Hz] */
#define BOARD_UART_BAUD 115200u       /* telemetry link [bit/s] (QEMU ignores the rate) */

/* ---- Cortex-M4 system registers (ARMv7-M ARM, B3.2, B3.3) ------------------------------- */
#define SCB_CPACR (*(volatile uint32_t *)0xE000ED88u) /* coprocessor access: CP10/CP11 = FPU */
#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)  /* SysTick control and status */
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)  /* SysTick reload value (24 bit) */
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)  /* SysTick current value (counts down) */
#define SYST_CSR_ENABLE (1u << 0)
#define SYST_CSR_TICKINT (1u << 1)
#define SYST_CSR_CLKSOURCE_CPU (1u << 2)
#define SYST_RELOAD_MAX 0x00FFFFFFu

/* ---- CMSDK APB UART0 of the MPS2 FPGA images (QEMU: -serial ... is this UART) ------------ */
#define UART0_BASE 0x40004000u
#define UART0_DATA (*(volatile uint32_t *)(UART0_BASE + 0x000u))
#define UART0_STATE (*(volatile uint32_t *)(UART0_BASE + 0x004u)) /* bit 0: TX buffer full */
#define UART0_CTRL (*(volatile uint32_t *)(UART0_BASE + 0x008u))  /* bit 0: TX enable */
#define UART0_BAUDDIV (*(volatile uint32_t *)(UART0_BASE + 0x010u))

/* ---- semihosting (ARM semihosting v2, BKPT 0xAB in Thumb state) --------------------------- */
#define SYS_GET_CMDLINE 0x15
#define SYS_EXIT_EXTENDED 0x20
#define ADP_STOPPED_APPLICATION_EXIT 0x20026u

static int semihost(int op, void *block) {
  register int r0 __asm("r0") = op;
  register void *r1 __asm("r1") = block;
  __asm volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

/* ---- startup ------------------------------------------------------------------------------ */
extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack; /* mps2_an386.ld */
extern int app_main(void); /* app.c */
void Reset_Handler(void);
void Fault_Handler(void);
void SysTick_Handler(void);

/** Exit code when the core faults (HardFault, MemManage, BusFault, UsageFault, ...). */
#define BOARD_FAULT_EXIT_CODE 97

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
    SysTick_Handler,            /* SysTick: the controller tick */
};

void Reset_Handler(void) {
  SCB_CPACR |= (0xFu << 20); /* CP10, CP11 full access: the FPU, before any float instruction */
  __asm volatile("dsb\n\tisb" ::: "memory");
  const uint32_t *src = &_sidata;
  for (uint32_t *dst = &_sdata; dst < &_edata;) *dst++ = *src++;
  for (uint32_t *dst = &_sbss; dst < &_ebss;) *dst++ = 0u;
  board_exit(app_main());
}

void Fault_Handler(void) { board_exit(BOARD_FAULT_EXIT_CODE); }

/* ---- the tick timer ----------------------------------------------------------------------- */
static volatile uint32_t g_timer_ticks;  /* SysTick wraps since start [ticks] */
static uint32_t g_period_cycles;         /* reload + 1 [cycles] */

void SysTick_Handler(void) {
  g_timer_ticks = g_timer_ticks + 1u;
  app_timer_isr();
}

void board_init(void) {
  UART0_BAUDDIV = BOARD_CORE_CLOCK_HZ / BOARD_UART_BAUD;
  UART0_CTRL = 1u; /* TX enable */
}

uint32_t board_core_clock_hz(void) { return BOARD_CORE_CLOCK_HZ; }

int board_timer_start(uint32_t period_cycles) {
  if (period_cycles == 0u || period_cycles - 1u > SYST_RELOAD_MAX) return -1;
  g_period_cycles = period_cycles;
  SYST_CSR = 0u;
  SYST_RVR = period_cycles - 1u; /* the counter runs reload → 0: period_cycles per wrap */
  SYST_CVR = 0u;                 /* any write clears the counter (and COUNTFLAG) */
  SYST_CSR = SYST_CSR_CLKSOURCE_CPU | SYST_CSR_TICKINT | SYST_CSR_ENABLE;
  return 0;
}

void board_sleep_until_set(volatile const uint32_t *flag) {
  /* With PRIMASK set a pending interrupt still ends WFI; it is taken at the cpsie. */
  __asm volatile("cpsid i" ::: "memory");
  while (*flag == 0u) {
    __asm volatile("wfi" ::: "memory");
    __asm volatile("cpsie i\n\tisb\n\tcpsid i" ::: "memory");
  }
  __asm volatile("cpsie i" ::: "memory");
}

uint64_t board_now_cycles(void) {
  uint32_t ticks, value;
  /* Re-read when a wrap (and its handler) came between the two reads: bounded, since a wrap
     takes a whole period. */
  for (int attempt = 0; attempt < 4; ++attempt) {
    ticks = g_timer_ticks;
    value = SYST_CVR;
    if (ticks == g_timer_ticks) break;
  }
  return (uint64_t)ticks * g_period_cycles + (uint64_t)(g_period_cycles - 1u - value);
}

void board_busy_wait_cycles(uint32_t n) {
  const uint64_t start = board_now_cycles();
  while (board_now_cycles() - start < n) {
  }
}

void board_uart_write(const char *s, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    while ((UART0_STATE & 1u) != 0u) {
    }
    UART0_DATA = (uint8_t)s[i];
  }
}

void board_cmdline(char *buf, size_t cap) {
  if (cap == 0u) return;
  buf[0] = '\0';
  uint32_t block[2] = {(uint32_t)(uintptr_t)buf, (uint32_t)cap};
  if (semihost(SYS_GET_CMDLINE, block) != 0) buf[0] = '\0';
  buf[cap - 1u] = '\0';
}

_Noreturn void board_exit(int code) {
  uint32_t block[2] = {ADP_STOPPED_APPLICATION_EXIT, (uint32_t)code};
  (void)semihost(SYS_EXIT_EXTENDED, block);
  for (;;) __asm volatile("wfi");
}
