/* SPDX-License-Identifier: Apache-2.0 */
/*
 * board.h: what the flight-loop application (app.c) needs from a board. Two boards implement
 * it: board_m4f.c (Cortex-M4F on QEMU's mps2-an386: SysTick, CMSDK UART0, semihosting exit)
 * and board_host.c (a host process: a simulated timer stepped by the sleep call, stdout).
 * The application logic is the same on both; only this layer differs.
 */
#ifndef FLIGHT_LOOP_BOARD_H
#define FLIGHT_LOOP_BOARD_H

#include <stddef.h>
#include <stdint.h>

/** Set up the clock tree and the telemetry UART. Called once, first thing in main(). */
void board_init(void);

/** The core clock the tick timer counts [Hz] (board_m4f.c: 25 MHz, mps2-an386's SYSCLK). */
uint32_t board_core_clock_hz(void);

/**
 * Start the periodic tick timer: app_timer_isr() is called every period_cycles core clock
 * cycles (from the SysTick exception on the M4F). Returns 0, or -1 when the period does not
 * fit the timer (SysTick: 24-bit reload, 1..2^24 cycles).
 */
int board_timer_start(uint32_t period_cycles);

/** Sleep (WFI) until *flag is non-zero. The flag is tested with interrupts masked, so a tick
 *  that arrives between the test and the WFI still wakes the core (no lost wake-up). */
void board_sleep_until_set(volatile const uint32_t *flag);

/** Core clock cycles since board_timer_start() (monotonic; tick count × period + the timer's
 *  progress in the current period). */
uint64_t board_now_cycles(void);

/** Busy-wait n core clock cycles with interrupts enabled (stands in for work that overruns). */
void board_busy_wait_cycles(uint32_t n);

/** Send n bytes over the telemetry UART (blocking). */
void board_uart_write(const char *s, size_t n);

/** The run's options string (semihosting command line on the M4F, argv on the host) into
 *  buf (NUL-terminated); "" when there is none. */
void board_cmdline(char *buf, size_t cap);

/** End the run with an exit code (QEMU: semihosting exit; host: exit()). */
_Noreturn void board_exit(int code);

/** The application's tick handler, called by the board's timer interrupt. */
void app_timer_isr(void);

#endif /* FLIGHT_LOOP_BOARD_H */
