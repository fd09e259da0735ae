/* SPDX-License-Identifier: Apache-2.0 */
/*
 * uvms-controller: the controller node as its own process (LCM C API + the firmware, double
 * build). `uvms run` starts it with the run's private LCM URLs; it can also be started by hand:
 *
 *   uvms-controller --url 'udpm://239.255.76.67:7667?ttl=0' [--publish-url URL] [--session HEX]
 *                   [--idle-timeout-s 30] [--spin-us 0]
 *
 * --publish-url: the answers go out on that URL, and only --url is listened to (`uvms run`'s
 * private link gives each direction a URL of its own, so neither process receives its own
 * datagrams; docs/BENCHMARKS.md, "SIL: the lockstep link").
 * --session fixes the run's session (sil/msg/session.h; `uvms run` always passes it); without it the
 * node adopts the session of the first configuration it accepts.
 * It answers each controller_config_t and sensors_t by controller_node.h's rules and publish
 * order until a run_status_t ends the run (exit 0), or until nothing has arrived for
 * --idle-timeout-s seconds (exit 3: the harness is gone). Exit 2: usage or LCM could not start.
 * Counters go to stderr at exit.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "link/controller_node.h"
#include "link/lcm_pair.h"
#include "link/lcm_wait.h"
#include "msg/cli_version.h"

static uvms_ctrl_node_t g_node; /* ~8 kB: static storage, as on the flight computer */

static void usage(FILE *f) {
  fprintf(f,
          "usage: uvms-controller --url LCM_URL [--publish-url LCM_URL] [--session HEX]\n"
          "                       [--idle-timeout-s S] [--spin-us US]\n"
          "       uvms-controller --version\n"
          "  --url             LCM provider URL of the run (udpm://... or memq://)\n"
          "  --publish-url     publish the answers on this URL instead (a link whose two\n"
          "                    directions have a URL each; `uvms run` does so on its private link)\n"
          "  --session         the run's session, 1-16 hex digits, not 0 (sil/msg/session.h); without\n"
          "                    it, the session of the first configuration accepted\n"
          "  --idle-timeout-s  exit (status 3) after S seconds without any message "
          "(default 30)\n"
          "  --spin-us         busy-poll the link this long before blocking, 0.." UVMS_SPIN_US_MAX_STR " "
          "(default 0; sil/link/lcm_wait.h)\n");
}

int main(int argc, char **argv) {
  if (uvms_cli_wants_version(argc, argv)) {
    uvms_cli_print_version(stdout, "uvms-controller");
    return 0;
  }
  const char *url = NULL, *publish_url = NULL;
  double idle_timeout_s = 30.0;
  int spin_us = 0;
  int64_t session = UVMS_SESSION_NONE;
  for (int i = 1; i < argc; ++i) {
    if (strcmp(argv[i], "--url") == 0 && i + 1 < argc) {
      url = argv[++i];
    } else if (strcmp(argv[i], "--publish-url") == 0 && i + 1 < argc) {
      publish_url = argv[++i];
    } else if (strcmp(argv[i], "--session") == 0 && i + 1 < argc) {
      if (!uvms_session_parse(argv[++i], &session)) {
        fprintf(stderr, "uvms-controller: error: --session needs 1-16 hex digits, not 0\n");
        return 2;
      }
    } else if (strcmp(argv[i], "--idle-timeout-s") == 0 && i + 1 < argc) {
      char *end = NULL;
      idle_timeout_s = strtod(argv[++i], &end);
      if (end == NULL || *end != '\0' || !(idle_timeout_s > 0.0)) {
        fprintf(stderr, "uvms-controller: error: --idle-timeout-s needs a positive number\n");
        return 2;
      }
    } else if (strcmp(argv[i], "--spin-us") == 0 && i + 1 < argc) {
      if (!uvms_parse_spin_us(argv[++i], &spin_us)) {
        fprintf(stderr, "uvms-controller: error: --spin-us needs an integer in 0..%d\n",
                UVMS_SPIN_US_MAX);
        return 2;
      }
    } else if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
      usage(stdout);
      return 0;
    } else {
      fprintf(stderr, "uvms-controller: error: unexpected argument \"%s\"\n", argv[i]);
      usage(stderr);
      return 2;
    }
  }
  if (url == NULL) {
    fprintf(stderr, "uvms-controller: error: --url is required\n");
    usage(stderr);
    return 2;
  }
  uvms_lcm_pair_t lcm;
  const char *failed_url = NULL;
  if (uvms_lcm_pair_open(&lcm, url, publish_url, &failed_url) != 0) {
    fprintf(stderr, "uvms-controller: error: cannot start LCM on \"%s\"\n", failed_url);
    return 2;
  }
  uvms_ctrl_node_init(&g_node);
  uvms_ctrl_node_set_session(&g_node, session);
  if (uvms_ctrl_node_attach_split(&g_node, lcm.listen, lcm.publish) != 0) {
    fprintf(stderr, "uvms-controller: error: LCM subscription failed\n");
    uvms_lcm_pair_close(&lcm);
    return 2;
  }
  const uvms_ctrl_node_end_t end = uvms_ctrl_node_serve(&g_node, idle_timeout_s, spin_us, NULL);
  const int rc = end == UVMS_CTRL_NODE_FINISHED ? 0 : end == UVMS_CTRL_NODE_IDLE ? 3 : 2;
  fprintf(stderr,
          "uvms-controller: %lld steps; dropped: %d rejected, %d out of sequence, "
          "%d before configuration, %d of another session\n",
          (long long)g_node.steps, g_node.rx_rejected, g_node.rx_out_of_sequence,
          g_node.rx_unconfigured, g_node.rx_foreign_session);
  uvms_lcm_pair_close(&lcm);
  return rc;
}
