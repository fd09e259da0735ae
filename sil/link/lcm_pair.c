/* SPDX-License-Identifier: Apache-2.0 */
/* lcm_pair.c: see lcm_pair.h. */
#include "link/lcm_pair.h"

#include <stddef.h>
#include <string.h>

int uvms_lcm_pair_open(uvms_lcm_pair_t *pair, const char *url, const char *publish_url,
                       const char **failed_url) {
  pair->listen = pair->publish = NULL;
  const int one = publish_url == NULL || strcmp(publish_url, url) == 0;
  lcm_t *listen = lcm_create(url);
  lcm_t *publish = listen == NULL ? NULL : one ? listen : lcm_create(publish_url);
  if (publish == NULL) {
    if (failed_url != NULL) *failed_url = listen == NULL ? url : publish_url;
    if (listen != NULL) lcm_destroy(listen);
    return -1;
  }
  pair->listen = listen;
  pair->publish = publish;
  return 0;
}

void uvms_lcm_pair_close(uvms_lcm_pair_t *pair) {
  if (pair->publish != NULL && pair->publish != pair->listen) lcm_destroy(pair->publish);
  if (pair->listen != NULL) lcm_destroy(pair->listen);
  pair->listen = pair->publish = NULL;
}
