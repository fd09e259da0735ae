/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lcm_wait.h: wait for LCM traffic with a bounded busy-poll before blocking.
 *
 * Why: LCM's udpm provider hands each datagram from its receive thread to the handling thread
 * through a pipe, so every lockstep hand-over is two thread wake-ups. On a virtual machine
 * whose idle vCPUs halt (these machines), waking a halted vCPU costs hundreds of
 * microseconds: measured 1.2 ms per tick over udpm against 0.15 ms per tick in one process
 * (memq) for the same scenario. Polling the LCM file descriptor for a short while before
 * blocking keeps the waiting node's vCPU awake while its peer computes the tick, which the
 * peer's answer then finds running. The poll yields the CPU on every round (sched_yield), so
 * a runnable thread on the same CPU (LCM's receive thread, the peer) gets it; the cost is
 * bounded by spin_us per wait.
 *
 * Used by both nodes in udpm runs (link.spin_us, docs/SCENARIOS.md); memq runs do not use LCM
 * (sil/run/inprocess_bus.hpp).
 */
#ifndef UVMS_SIL_LCM_WAIT_H
#define UVMS_SIL_LCM_WAIT_H

#include <lcm/lcm.h>

#include "msg/link_limits.h" /* UVMS_SPIN_US_MAX */

#ifdef __cplusplus
extern "C" {
#endif


/*
 * Handle at most one LCM message: poll the LCM file descriptor without blocking for up to
 * spin_us microseconds (0: not at all), then block for what is left of timeout_ms
 * milliseconds (lcm_handle_timeout): the whole wait never exceeds timeout_ms (up to the
 * clock's granularity). Returns > 0 when a message was handled, 0 on timeout or when a
 * signal interrupted the poll (the caller re-checks its state), < 0 on error.
 */
int uvms_lcm_wait(lcm_t *lcm, int timeout_ms, int spin_us);

/* Parse a command-line spin budget: a whole number of microseconds in 0..UVMS_SPIN_US_MAX (the
 * range the scenario key link.spin_us allows). Returns 1 and sets *out, or 0 and leaves it. */
int uvms_parse_spin_us(const char *text, int *out);

#ifdef __cplusplus
}
#endif

#endif /* UVMS_SIL_LCM_WAIT_H */
