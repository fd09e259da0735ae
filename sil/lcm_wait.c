/* lcm_wait.c: see lcm_wait.h. */
#define _POSIX_C_SOURCE 200809L
#include "lcm_wait.h"

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
  if (spin_us > 0) {
    const int fd = lcm_get_fileno(lcm);
    if (fd >= 0) {
      const long long end_ns = now_ns() + (long long)spin_us * 1000LL;
      /* Bounded: ends at end_ns (the clock is monotonic) or when data is ready. */
      do {
        struct pollfd p = {fd, POLLIN, 0};
        const int r = poll(&p, 1, 0);
        if (r < 0) break; /* EINTR and the like: fall through to the blocking wait */
        if (r > 0) return lcm_handle(lcm) == 0 ? 1 : -1;
        sched_yield();
      } while (now_ns() < end_ns);
    }
  }
  return lcm_handle_timeout(lcm, timeout_ms);
}

int uvms_parse_spin_us(const char *text, int *out) {
  if (text == NULL || *text < '0' || *text > '9') return 0; /* no sign, no blanks, not empty */
  char *end = NULL;
  const long v = strtol(text, &end, 10);
  if (end == NULL || *end != '\0' || v < 0 || v > 100000) return 0;
  *out = (int)v;
  return 1;
}
