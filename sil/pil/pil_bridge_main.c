/* SPDX-License-Identifier: Apache-2.0 */
/*
 * uvms-controller-pil: processor-in-the-loop drop-in for uvms-controller. The same
 * controller node (sil/link/controller_node.h: its decode, count, sequence and answer rules and its
 * publish order are that node's code, not a copy), with another compute step: the controller is
 * the Cortex-M4F image sil/pil/target/pil_m4f.c running in QEMU mps2-an386 under -icount
 * shift=0, fed through sil/pil/pil_protocol.h frames. Each telemetry carries
 * target_instructions: the guest instructions of that tick's uvms_ctrl_step, counted exactly by
 * bench/qemu_icount_plugin.c.
 *
 *   uvms-controller-pil --url URL [--publish-url URL] [--session HEX] [--idle-timeout-s S]
 *                       [--elf PATH] [--qemu PATH] [--plugin PATH | --no-icount]
 *                       [--reply-timeout-s S]
 *
 * Defaults: the image of the cortex-m4f preset (UVMS_PIL_DEFAULT_ELF, baked in by CMake:
 * <source>/build/cortex-m4f/sil/pil/target/uvms_pil_m4f.elf; the environment variable
 * UVMS_PIL_ELF overrides it), the plugin of this build tree, qemu-system-arm from PATH.
 * Exit: 0 after a run_status_t end state, 2 usage / LCM / PIL start failure, 3 idle timeout,
 * 4 the PIL link failed mid-run. Counters go to stderr at exit.
 */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "link/controller_node.h"
#include "link/lcm_pair.h"
#include "link/lcm_wait.h"
#include "msg/cli_version.h"
#include "msg/codec.h"
#include "pil/pil_host.h"

#ifndef UVMS_PIL_DEFAULT_ELF
#define UVMS_PIL_DEFAULT_ELF "build/cortex-m4f/sil/pil/target/uvms_pil_m4f.elf"
#endif
#ifndef UVMS_PIL_DEFAULT_PLUGIN
#define UVMS_PIL_DEFAULT_PLUGIN ""
#endif

#define ME "uvms-controller-pil"

/* The compute step of the node: the target behind the PIL link. */
typedef struct {
  pil_link_t link;
  int64_t instr_max; /* most instructions of one step */
} pil_compute_t;

static uvms_ctrl_node_t g_node;   /* static storage, as the host controller node */
static pil_compute_t g_target;
static volatile sig_atomic_t g_stop;

static void on_signal(int sig) {
  (void)sig;
  g_stop = 1;
}

static int target_configure(void *ctx, const uvms_controller_config_t *msg, int32_t *status,
                            int32_t *config_error) {
  pil_compute_t *t = (pil_compute_t *)ctx;
  static pil_config_rec_t rec;
  pil_config_rec_from_msg(msg, &rec);
  pil_config_ack_rec_t ack;
  char err[300];
  if (pil_link_config(&t->link, &rec, &ack, err, sizeof err) != 0) {
    fprintf(stderr, ME ": error: %s\n", err);
    return -1;
  }
  *status = ack.status;
  *config_error = ack.config_error;
  return 0;
}

static int target_step(void *ctx, const uvms_sensors_t *msg, int32_t *status,
                       uvms_ctrl_command_t *cmd, uvms_ctrl_telemetry_t *tlm,
                       int64_t *target_instructions) {
  pil_compute_t *t = (pil_compute_t *)ctx;
  static pil_sensors_rec_t rec;
  static pil_output_rec_t out;
  pil_sensors_rec_from_msg(msg, &rec);
  char err[300];
  if (pil_link_step(&t->link, &rec, &out, target_instructions, err, sizeof err) != 0) {
    fprintf(stderr, ME ": error: tick %lld: %s\n", (long long)msg->tick, err);
    return -1;
  }
  if (*target_instructions > t->instr_max) t->instr_max = *target_instructions;
  pil_output_from_rec(&out, cmd, tlm);
  *status = out.status;
  return 0;
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: " ME " --url LCM_URL [--publish-url LCM_URL] [--session HEX]\n"
          "                           [--idle-timeout-s S] [--elf PATH]\n"
          "                           [--qemu PATH] [--plugin PATH | --no-icount]\n"
          "                           [--reply-timeout-s S]\n"
          "                           [--spin-us US]\n"
          "       " ME " --version\n"
          "The controller node of `uvms run --controller pil`: the Cortex-M4F firmware image in\n"
          "QEMU mps2-an386 (-icount shift=0) behind the usual LCM channels.\n"
          "  --url              LCM provider URL of the run\n"
          "  --publish-url      publish the answers on this URL instead (`uvms run`'s private\n"
          "                     link gives each direction a URL of its own)\n"
          "  --session          the run's session, 1-16 hex digits, not 0 (sil/msg/session.h);\n"
          "                     without it, the session of the first configuration accepted\n"
          "  --idle-timeout-s   exit (status 3) after S seconds without any message (default 30)\n"
          "  --elf              the PIL image (default: $UVMS_PIL_ELF, else\n"
          "                     " UVMS_PIL_DEFAULT_ELF ")\n"
          "  --qemu             qemu-system-arm to run (default: from PATH)\n"
          "  --plugin           instruction-counting plugin (default: this build's\n"
          "                     libqemu_icount_plugin.so); --no-icount: none, counts are 0\n"
          "  --reply-timeout-s  wait for one answer of the target before resending (default 2)\n"
          "  --spin-us          busy-poll the link this long before blocking, 0.." UVMS_SPIN_US_MAX_STR
          " (default 0;\n"
          "                     sil/link/lcm_wait.h)\n");
}

static int positive(const char *s, double *out) {
  char *end = NULL;
  *out = strtod(s, &end);
  return end != NULL && *end == '\0' && *out > 0.0;
}

/* The command line. */
typedef struct {
  const char *url;
  const char *publish_url; /* NULL: answers on url */
  int64_t session; /* UVMS_SESSION_NONE: adopt the first accepted configuration's */
  double idle_timeout_s;
  int spin_us;
  pil_link_options_t link;
} bridge_args_t;

/* Parse argv into *a. Returns -1 to go on, else the exit status (0 after --help). */
static int parse_args(int argc, char **argv, bridge_args_t *a) {
  memset(a, 0, sizeof *a);
  if (uvms_cli_wants_version(argc, argv)) {
    uvms_cli_print_version(stdout, ME);
    return 0;
  }
  a->idle_timeout_s = 30.0;
  pil_link_options_default(&a->link);
  const char *env_elf = getenv("UVMS_PIL_ELF");
  a->link.elf = env_elf != NULL && *env_elf ? env_elf : UVMS_PIL_DEFAULT_ELF;
  a->link.plugin = UVMS_PIL_DEFAULT_PLUGIN[0] ? UVMS_PIL_DEFAULT_PLUGIN : NULL;
  for (int i = 1; i < argc; ++i) {
    const char *o = argv[i];
    const int has_value = i + 1 < argc;
    if (strcmp(o, "--url") == 0 && has_value) {
      a->url = argv[++i];
    } else if (strcmp(o, "--publish-url") == 0 && has_value) {
      a->publish_url = argv[++i];
    } else if (strcmp(o, "--session") == 0 && has_value) {
      if (!uvms_session_parse(argv[++i], &a->session)) {
        fprintf(stderr, ME ": error: --session needs 1-16 hex digits, not 0\n");
        return 2;
      }
    } else if (strcmp(o, "--idle-timeout-s") == 0 && has_value) {
      if (!positive(argv[++i], &a->idle_timeout_s)) {
        fprintf(stderr, ME ": error: --idle-timeout-s needs a positive number\n");
        return 2;
      }
    } else if (strcmp(o, "--reply-timeout-s") == 0 && has_value) {
      if (!positive(argv[++i], &a->link.reply_timeout_s)) {
        fprintf(stderr, ME ": error: --reply-timeout-s needs a positive number\n");
        return 2;
      }
    } else if (strcmp(o, "--spin-us") == 0 && has_value) {
      if (!uvms_parse_spin_us(argv[++i], &a->spin_us)) {
        fprintf(stderr, ME ": error: --spin-us needs an integer in 0..%d\n", UVMS_SPIN_US_MAX);
        return 2;
      }
    } else if (strcmp(o, "--elf") == 0 && has_value) {
      a->link.elf = argv[++i];
    } else if (strcmp(o, "--qemu") == 0 && has_value) {
      a->link.qemu = argv[++i];
    } else if (strcmp(o, "--plugin") == 0 && has_value) {
      a->link.plugin = argv[++i];
    } else if (strcmp(o, "--no-icount") == 0) {
      a->link.plugin = NULL;
    } else if (strcmp(o, "-h") == 0 || strcmp(o, "--help") == 0) {
      usage(stdout);
      return 0;
    } else {
      fprintf(stderr, ME ": error: unexpected argument \"%s\"\n", o);
      usage(stderr);
      return 2;
    }
  }
  if (a->url == NULL) {
    fprintf(stderr, ME ": error: --url is required\n");
    usage(stderr);
    return 2;
  }
  if (a->link.plugin != NULL && access(a->link.plugin, R_OK) != 0) {
    fprintf(stderr, ME ": warning: plugin %s not found: no instruction counts (build the "
                    "qemu_icount_plugin target, or pass --no-icount)\n", a->link.plugin);
    a->link.plugin = NULL;
  }
  return -1;
}

int main(int argc, char **argv) {
  bridge_args_t args;
  const int usage_rc = parse_args(argc, argv, &args);
  if (usage_rc >= 0) return usage_rc;
  const char *url = args.url;

  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigaction(SIGTERM, &sa, NULL);
  sigaction(SIGINT, &sa, NULL);
  signal(SIGPIPE, SIG_IGN); /* a dead QEMU shows up as a write error, not a signal */

  /* The target first: the plant's configuration must find it ready. */
  char err[400];
  if (pil_link_start(&g_target.link, &args.link, err, sizeof err) != 0) {
    fprintf(stderr, ME ": error: %s\n", err);
    return 2;
  }
  uvms_lcm_pair_t lcm;
  const char *failed_url = NULL;
  if (uvms_lcm_pair_open(&lcm, url, args.publish_url, &failed_url) != 0) {
    fprintf(stderr, ME ": error: cannot start LCM on \"%s\"\n", failed_url);
    pil_link_stop(&g_target.link);
    return 2;
  }
  uvms_ctrl_node_init(&g_node);
  g_node.name = ME;
  uvms_ctrl_node_set_session(&g_node, args.session);
  const uvms_ctrl_node_compute_t target = {target_configure, target_step, &g_target};
  uvms_ctrl_node_set_compute(&g_node, &target);
  if (uvms_ctrl_node_attach_split(&g_node, lcm.listen, lcm.publish) != 0) {
    fprintf(stderr, ME ": error: LCM subscription failed\n");
    uvms_lcm_pair_close(&lcm);
    pil_link_stop(&g_target.link);
    return 2;
  }
  static const int kExit[] = {[UVMS_CTRL_NODE_FINISHED] = 0, [UVMS_CTRL_NODE_WAIT_ERROR] = 2,
                              [UVMS_CTRL_NODE_IDLE] = 3, [UVMS_CTRL_NODE_STOPPED] = 3,
                              [UVMS_CTRL_NODE_FAILED] = 4};
  const int rc = kExit[uvms_ctrl_node_serve(&g_node, args.idle_timeout_s, args.spin_us, &g_stop)];
  const pil_link_t *l = &g_target.link;
  const uint32_t retransmits = l->retransmits, naks = l->naks, stale = l->stale_frames;
  const uint32_t host_rx_err = pil_rx_errors(&l->rx), missing = l->icount_missing;
  const int qemu_rc = pil_link_stop(&g_target.link);
  fprintf(stderr,
          ME ": %lld steps on the target (max %lld instructions per step); dropped: %d rejected, "
             "%d out of sequence, %d before configuration, %d of another session; link: %u retransmits, %u NAKs, "
             "%u stale frames, %u host-side frame errors, %u steps without a count; QEMU "
             "exit %d\n",
          (long long)g_node.steps, (long long)g_target.instr_max, g_node.rx_rejected,
          g_node.rx_out_of_sequence, g_node.rx_unconfigured, g_node.rx_foreign_session, retransmits, naks, stale,
          host_rx_err, missing, qemu_rc);
  uvms_lcm_pair_close(&lcm);
  return rc;
}
