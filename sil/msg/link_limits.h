/* SPDX-License-Identifier: Apache-2.0 */
/*
 * link_limits.h: limits of the lockstep link that both the link (link/lcm_wait.h) and the
 * scenario schema (scenario key link.spin_us) state, defined once below both.
 */
#ifndef UVMS_SIL_LINK_LIMITS_H
#define UVMS_SIL_LINK_LIMITS_H

/* Largest busy-poll budget accepted anywhere (scenario key link.spin_us, --spin-us) [µs]. */
#define UVMS_SPIN_US_MAX 100000
#define UVMS_SPIN_US_STR_(x) #x
#define UVMS_SPIN_US_STR(x) UVMS_SPIN_US_STR_(x)
#define UVMS_SPIN_US_MAX_STR UVMS_SPIN_US_STR(UVMS_SPIN_US_MAX) /* for usage texts */

#endif /* UVMS_SIL_LINK_LIMITS_H */
