/* SPDX-License-Identifier: Apache-2.0 */
/*
 * board_host.c: the board layer as a host process, to run the same application (app.c) on a
 * workstation. The tick timer is simulated: time is a cycle counter at the same stated core
 * clock as the M4F board, advanced to the next tick by the sleep call (so a run takes no wall
 * time) and by board_busy_wait_cycles, which fires the tick handler for every period it
 * spans, exactly where the SysTick exception would interrupt the work. The controller step
 * itself takes no simulated time here (the M4F run measures it). Telemetry goes to stdout;
 * the options are the program's arguments.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "board.h"

#define BOARD_CORE_CLOCK_HZ 25000000u /* simulated core clock [Hz], as board_m4f.c */

extern int app_main(void); /* app.c */

static uint64_t g_sim_cycles;    /* simulated time since board_timer_start [cycles] */
static uint32_t g_period_cycles; /* tick period [cycles]; 0: timer not started */
static int g_argc;
static char **g_argv;

/** Advance simulated time by n cycles, calling the tick handler at every period boundary. */
static void advance(uint64_t n) {
  const uint64_t end = g_sim_cycles + n;
  if (g_period_cycles == 0u) {
    g_sim_cycles = end;
    return;
  }
  for (;;) {
    const uint64_t next = (g_sim_cycles / g_period_cycles + 1u) * g_period_cycles;
    if (next > end) break;
    g_sim_cycles = next;
    app_timer_isr();
  }
  g_sim_cycles = end;
}

void board_init(void) { setvbuf(stdout, NULL, _IOFBF, 1u << 16); }

uint32_t board_core_clock_hz(void) { return BOARD_CORE_CLOCK_HZ; }

int board_timer_start(uint32_t period_cycles) {
  if (period_cycles == 0u || period_cycles > (1u << 24)) return -1; /* as SysTick's reload */
  g_period_cycles = period_cycles;
  g_sim_cycles = 0u;
  return 0;
}

void board_sleep_until_set(volatile const uint32_t *flag) {
  if (g_period_cycles == 0u) return; /* no timer: nothing would ever set the flag */
  while (*flag == 0u) advance(g_period_cycles - g_sim_cycles % g_period_cycles);
}

uint64_t board_now_cycles(void) { return g_sim_cycles; }

void board_busy_wait_cycles(uint32_t n) { advance(n); }

void board_uart_write(const char *s, size_t n) { (void)fwrite(s, 1u, n, stdout); }

void board_cmdline(char *buf, size_t cap) {
  if (cap == 0u) return;
  buf[0] = '\0';
  size_t len = 0u;
  for (int i = 1; i < g_argc; ++i) {
    const size_t n = strlen(g_argv[i]);
    if (len + n + 2u > cap) break;
    if (len > 0u) buf[len++] = ' ';
    memcpy(buf + len, g_argv[i], n);
    len += n;
    buf[len] = '\0';
  }
}

_Noreturn void board_exit(int code) {
  (void)fflush(stdout);
  exit(code);
}

int main(int argc, char **argv) {
  g_argc = argc;
  g_argv = argv;
  board_exit(app_main());
}
