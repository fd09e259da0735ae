/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lcm_pair.h: the LCM instances of one end of a link, opened and closed together. The end
 * listens on `url` and publishes on `publish_url`: on the private link of `uvms run` each
 * direction has a URL of its own, and an instance that only publishes (nobody subscribes on it)
 * gets no receive socket from LCM, so the process never receives its own datagrams. With no
 * publish_url, or the same URL, both are one instance.
 *
 * Used by uvms-plant, uvms-controller and uvms-controller-pil.
 */
#ifndef UVMS_SIL_LCM_PAIR_H
#define UVMS_SIL_LCM_PAIR_H

#include <lcm/lcm.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  lcm_t *listen;  /* subscribe and wait here */
  lcm_t *publish; /* publish here: listen itself, or an instance of its own */
} uvms_lcm_pair_t;

/* Open the pair (publish_url NULL or equal to url: one instance). Returns 0, or -1 with nothing
 * left open, both members NULL and *failed_url (if not NULL) the URL LCM could not start on. */
int uvms_lcm_pair_open(uvms_lcm_pair_t *pair, const char *url, const char *publish_url,
                       const char **failed_url);

/* Close what the pair holds (safe on a pair that failed to open, and twice). */
void uvms_lcm_pair_close(uvms_lcm_pair_t *pair);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_SIL_LCM_PAIR_H */
