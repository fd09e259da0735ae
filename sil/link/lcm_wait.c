/* SPDX-License-Identifier: Apache-2.0 */
/* lcm_wait.c: see lcm_wait.h. */
#define _POSIX_C_SOURCE 200809L
#include "link/lcm_wait.h"

#include <errno.h>
#include <poll.h>
#include <sched.h>
#include <stdlib.h>
#include <time.h>

static long long now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (long long)ts.tv_sec * 1000000000LL + (long long)ts.tv_nsec;
}

int uvms_lcm_wait(lcm_t *lcm, int timeout_ms, int spin_us) {
  if (timeout_ms < 0) timeout_ms = 0;
  if (spin_us > 0) {
    const int fd = lcm_get_fileno(lcm);
    if (fd >= 0) {
      const long long start_ns = now_ns();
      /* The spin is part of the wait: never longer than the timeout. */
      const long long spin_ns = (long long)spin_us * 1000LL;
      const long long timeout_ns = (long long)timeout_ms * 1000000LL;
      const long long end_ns = start_ns + (spin_ns < timeout_ns ? spin_ns : timeout_ns);
      /* Bounded: ends at end_ns (the clock is monotonic) or when data is ready. */
      for (;;) {
        struct pollfd p = {fd, POLLIN, 0};
        const int r = poll(&p, 1, 0);
        if (r < 0) return errno == EINTR ? 0 : -1; /* a signal: let the caller look */
        /* Readable: LCM keeps one notify byte per queued message, and only this thread
         * handles messages, so lcm_handle returns without blocking. */
        if (r > 0) return lcm_handle(lcm) == 0 ? 1 : -1;
        const long long now = now_ns();
        if (now >= end_ns) {
          timeout_ms -= (int)((now - start_ns) / 1000000LL);
          break;
        }
        sched_yield();
      }
      if (timeout_ms <= 0) return 0;
    }
  }
  return lcm_handle_timeout(lcm, timeout_ms);
}

int uvms_parse_spin_us(const char *text, int *out) {
  if (text == NULL || *text < '0' || *text > '9') return 0; /* no sign, no blanks, not empty */
  char *end = NULL;
  const long v = strtol(text, &end, 10);
  if (end == NULL || *end != '\0' || v < 0 || v > UVMS_SPIN_US_MAX) return 0;
  *out = (int)v;
  return 1;
}
