/*
 * uvms-controller-pil: processor-in-the-loop drop-in for uvms-controller (issue 8). Same LCM
 * behaviour (sil/controller_node.h's rules: subscribes UVMS_CONFIG, UVMS_SENSORS, UVMS_STATUS;
 * answers with UVMS_TELEMETRY then UVMS_ACTUATORS, CRC-sealed; drops and counts bad messages),
 * but the controller is the Cortex-M4F image firmware/target/pil_m4f.c running in QEMU
 * mps2-an386 under -icount shift=0, fed through sil/pil/pil_protocol.h frames. Each telemetry
 * carries target_instructions: the guest instructions of that tick's uvms_ctrl_step, counted
 * exactly by tools/bench/qemu_icount_plugin.c.
 *
 *   uvms-controller-pil --url URL [--idle-timeout-s S] [--elf PATH] [--qemu PATH]
 *                       [--plugin PATH | --no-icount] [--reply-timeout-s S]
 *
 * Defaults: the image of the cortex-m4f preset (UVMS_PIL_DEFAULT_ELF, baked in by CMake:
 * <source>/build/cortex-m4f/firmware/target/uvms_pil_m4f.elf; the environment variable
 * UVMS_PIL_ELF overrides it), the plugin of this build tree, qemu-system-arm from PATH.
 * Exit: 0 after a run_status_t end state, 2 usage / LCM / PIL start failure, 3 idle timeout,
 * 4 the PIL link failed mid-run. Counters go to stderr at exit.
 */
#define _POSIX_C_SOURCE 200809L
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "codec.h"
#include "lcm_wait.h"
#include "pil_host.h"

#ifndef UVMS_PIL_DEFAULT_ELF
#define UVMS_PIL_DEFAULT_ELF "build/cortex-m4f/firmware/target/uvms_pil_m4f.elf"
#endif
#ifndef UVMS_PIL_DEFAULT_PLUGIN
#define UVMS_PIL_DEFAULT_PLUGIN ""
#endif

#define ME "uvms-controller-pil"

/* The node: controller_node.c's rules, with the step done by the target. */
typedef struct {
  pil_link_t link;
  lcm_t *lcm;
  int configured;
  int have_last_tick;
  int64_t last_tick;
  int32_t rx_rejected, rx_out_of_sequence, rx_unconfigured;
  int64_t steps;
  int64_t instr_max;
  int finished;
  int link_failed;
} pil_node_t;

static pil_node_t g_node; /* static storage, as the host controller node */
static volatile sig_atomic_t g_stop;

static void on_signal(int sig) {
  (void)sig;
  g_stop = 1;
}

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void fill_counters(const pil_node_t *n, uvms_telemetry_t *t) {
  t->rx_rejected = n->rx_rejected;
  t->rx_out_of_sequence = n->rx_out_of_sequence;
  t->rx_unconfigured = n->rx_unconfigured;
}

static void publish(pil_node_t *n, const uvms_telemetry_t *tel, const uvms_actuators_t *act) {
  uint8_t buf[UVMS_MAX_MSG_BYTES];
  int len = uvms_telemetry_t_encode_sealed(tel, buf, (int)sizeof buf);
  if (len > 0 && lcm_publish(n->lcm, UVMS_CH_TELEMETRY, buf, (unsigned)len) != 0)
    fprintf(stderr, ME ": warning: publishing telemetry of tick %lld failed\n",
            (long long)tel->tick);
  if (act == NULL) return;
  len = uvms_actuators_t_encode_sealed(act, buf, (int)sizeof buf);
  if (len > 0 && lcm_publish(n->lcm, UVMS_CH_ACTUATORS, buf, (unsigned)len) != 0)
    fprintf(stderr, ME ": warning: publishing actuators of tick %lld failed\n",
            (long long)act->tick);
}

static void on_config(const lcm_recv_buf_t *rb, const char *ch, void *user) {
  (void)ch;
  pil_node_t *n = (pil_node_t *)user;
  static uvms_controller_config_t msg;
  static pil_config_rec_t rec;
  if (n->link_failed) return;
  if (uvms_controller_config_t_decode_checked((const uint8_t *)rb->data, (int)rb->data_size,
                                              &msg) < 0) {
    ++n->rx_rejected;
    return;
  }
  n->configured = 0;
  n->have_last_tick = 0;
  pil_config_rec_from_msg(&msg, &rec);
  pil_config_ack_rec_t ack;
  char err[300];
  if (pil_link_config(&n->link, &rec, &ack, err, sizeof err) != 0) {
    fprintf(stderr, ME ": error: %s\n", err);
    n->link_failed = 1;
    return;
  }
  n->configured = (ack.status == 0);
  uvms_telemetry_t tel;
  memset(&tel, 0, sizeof tel);
  tel.utime = msg.utime;
  tel.tick = -1;
  tel.status = ack.status;
  tel.config_error = ack.config_error;
  fill_counters(n, &tel);
  publish(n, &tel, NULL);
}

static void on_sensors(const lcm_recv_buf_t *rb, const char *ch, void *user) {
  (void)ch;
  pil_node_t *n = (pil_node_t *)user;
  static uvms_sensors_t msg;
  static pil_sensors_rec_t rec;
  static pil_output_rec_t out;
  static uvms_ctrl_command_t cmd;
  static uvms_ctrl_telemetry_t tlm;
  static uvms_actuators_t act;
  static uvms_telemetry_t tel;
  if (n->link_failed) return;
  if (uvms_sensors_t_decode_checked((const uint8_t *)rb->data, (int)rb->data_size, &msg) < 0) {
    ++n->rx_rejected;
    return;
  }
  if (!n->configured) {
    ++n->rx_unconfigured;
    return;
  }
  if (n->have_last_tick && msg.tick <= n->last_tick) {
    ++n->rx_out_of_sequence;
    return;
  }
  n->have_last_tick = 1;
  n->last_tick = msg.tick;
  pil_sensors_rec_from_msg(&msg, &rec);
  int64_t instr = 0;
  char err[300];
  if (pil_link_step(&n->link, &rec, &out, &instr, err, sizeof err) != 0) {
    fprintf(stderr, ME ": error: tick %lld: %s\n", (long long)msg.tick, err);
    n->link_failed = 1;
    return;
  }
  ++n->steps;
  if (instr > n->instr_max) n->instr_max = instr;
  pil_output_from_rec(&out, &cmd, &tlm);
  uvms_outputs_to_msgs(&msg, out.status, &cmd, &tlm, &act, &tel);
  fill_counters(n, &tel);
  tel.target_instructions = instr;
  publish(n, &tel, &act);
}

static void on_status(const lcm_recv_buf_t *rb, const char *ch, void *user) {
  (void)ch;
  pil_node_t *n = (pil_node_t *)user;
  uvms_run_status_t msg;
  if (uvms_run_status_t_decode_checked((const uint8_t *)rb->data, (int)rb->data_size, &msg) < 0) {
    ++n->rx_rejected;
    return;
  }
  if (msg.state == UVMS_RUN_STATUS_T_FINISHED || msg.state == UVMS_RUN_STATUS_T_FAILED)
    n->finished = 1;
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: " ME " --url LCM_URL [--idle-timeout-s S] [--elf PATH] [--qemu PATH]\n"
          "                           [--plugin PATH | --no-icount] [--reply-timeout-s S]\n"
          "                           [--spin-us US]\n"
          "The controller node of `uvms run --controller pil`: the Cortex-M4F firmware image in\n"
          "QEMU mps2-an386 (-icount shift=0) behind the usual LCM channels.\n"
          "  --url              LCM provider URL of the run\n"
          "  --idle-timeout-s   exit (status 3) after S seconds without any message (default 30)\n"
          "  --elf              the PIL image (default: $UVMS_PIL_ELF, else\n"
          "                     " UVMS_PIL_DEFAULT_ELF ")\n"
          "  --qemu             qemu-system-arm to run (default: from PATH)\n"
          "  --plugin           instruction-counting plugin (default: this build's\n"
          "                     libqemu_icount_plugin.so); --no-icount: none, counts are 0\n"
          "  --reply-timeout-s  wait for one answer of the target before resending (default 2)\n"
          "  --spin-us          busy-poll the link this long before blocking, 0.." UVMS_SPIN_US_MAX_STR
          " (default 0;\n"
          "                     sil/lcm_wait.h)\n");
}

static int positive(const char *s, double *out) {
  char *end = NULL;
  *out = strtod(s, &end);
  return end != NULL && *end == '\0' && *out > 0.0;
}

int main(int argc, char **argv) {
  const char *url = NULL;
  double idle_timeout_s = 30.0;
  int spin_us = 0;
  pil_link_options_t opt;
  pil_link_options_default(&opt);
  const char *env_elf = getenv("UVMS_PIL_ELF");
  opt.elf = env_elf != NULL && *env_elf ? env_elf : UVMS_PIL_DEFAULT_ELF;
  opt.plugin = UVMS_PIL_DEFAULT_PLUGIN[0] ? UVMS_PIL_DEFAULT_PLUGIN : NULL;
  for (int i = 1; i < argc; ++i) {
    const char *a = argv[i];
    const int has_value = i + 1 < argc;
    if (strcmp(a, "--url") == 0 && has_value) {
      url = argv[++i];
    } else if (strcmp(a, "--idle-timeout-s") == 0 && has_value) {
      if (!positive(argv[++i], &idle_timeout_s)) {
        fprintf(stderr, ME ": error: --idle-timeout-s needs a positive number\n");
        return 2;
      }
    } else if (strcmp(a, "--reply-timeout-s") == 0 && has_value) {
      if (!positive(argv[++i], &opt.reply_timeout_s)) {
        fprintf(stderr, ME ": error: --reply-timeout-s needs a positive number\n");
        return 2;
      }
    } else if (strcmp(a, "--spin-us") == 0 && has_value) {
      if (!uvms_parse_spin_us(argv[++i], &spin_us)) {
        fprintf(stderr, ME ": error: --spin-us needs an integer in 0..%d\n", UVMS_SPIN_US_MAX);
        return 2;
      }
    } else if (strcmp(a, "--elf") == 0 && has_value) {
      opt.elf = argv[++i];
    } else if (strcmp(a, "--qemu") == 0 && has_value) {
      opt.qemu = argv[++i];
    } else if (strcmp(a, "--plugin") == 0 && has_value) {
      opt.plugin = argv[++i];
    } else if (strcmp(a, "--no-icount") == 0) {
      opt.plugin = NULL;
    } else if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
      usage(stdout);
      return 0;
    } else {
      fprintf(stderr, ME ": error: unexpected argument \"%s\"\n", a);
      usage(stderr);
      return 2;
    }
  }
  if (url == NULL) {
    fprintf(stderr, ME ": error: --url is required\n");
    usage(stderr);
    return 2;
  }
  if (opt.plugin != NULL && access(opt.plugin, R_OK) != 0) {
    fprintf(stderr, ME ": warning: plugin %s not found: no instruction counts (build the "
                    "qemu_icount_plugin target, or pass --no-icount)\n", opt.plugin);
    opt.plugin = NULL;
  }

  struct sigaction sa;
  memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_signal;
  sigaction(SIGTERM, &sa, NULL);
  sigaction(SIGINT, &sa, NULL);
  signal(SIGPIPE, SIG_IGN); /* a dead QEMU shows up as a write error, not a signal */

  /* The target first: the plant's configuration must find it ready. */
  char err[400];
  if (pil_link_start(&g_node.link, &opt, err, sizeof err) != 0) {
    fprintf(stderr, ME ": error: %s\n", err);
    return 2;
  }
  lcm_t *lcm = lcm_create(url);
  if (lcm == NULL) {
    fprintf(stderr, ME ": error: cannot start LCM on \"%s\"\n", url);
    pil_link_stop(&g_node.link);
    return 2;
  }
  g_node.lcm = lcm;
  if (lcm_subscribe(lcm, UVMS_CH_CONFIG, on_config, &g_node) == NULL ||
      lcm_subscribe(lcm, UVMS_CH_SENSORS, on_sensors, &g_node) == NULL ||
      lcm_subscribe(lcm, UVMS_CH_STATUS, on_status, &g_node) == NULL) {
    fprintf(stderr, ME ": error: LCM subscription failed\n");
    lcm_destroy(lcm);
    pil_link_stop(&g_node.link);
    return 2;
  }
  double last_rx_s = now_s();
  int rc = 0;
  while (!g_node.finished) {
    if (g_stop) {
      fprintf(stderr, ME ": stopped by a signal\n");
      rc = 3;
      break;
    }
    if (g_node.link_failed) {
      rc = 4;
      break;
    }
    const int r = uvms_lcm_wait(lcm, 100, spin_us);
    if (r < 0) {
      if (g_stop) continue;
      fprintf(stderr, ME ": error: waiting for LCM messages failed\n");
      rc = 2;
      break;
    }
    if (r > 0) {
      last_rx_s = now_s();
    } else if (now_s() - last_rx_s > idle_timeout_s) {
      fprintf(stderr, ME ": error: no message for %.1f s; exiting\n", idle_timeout_s);
      rc = 3;
      break;
    }
  }
  const pil_link_t *l = &g_node.link;
  const uint32_t retransmits = l->retransmits, naks = l->naks, stale = l->stale_frames;
  const uint32_t host_rx_err = pil_rx_errors(&l->rx), missing = l->icount_missing;
  const int qemu_rc = pil_link_stop(&g_node.link);
  fprintf(stderr,
          ME ": %lld steps on the target (max %lld instructions per step); dropped: %d rejected, "
             "%d out of sequence, %d before configuration; link: %u retransmits, %u NAKs, "
             "%u stale frames, %u host-side frame errors, %u steps without a count; QEMU "
             "exit %d\n",
          (long long)g_node.steps, (long long)g_node.instr_max, g_node.rx_rejected,
          g_node.rx_out_of_sequence, g_node.rx_unconfigured, retransmits, naks, stale,
          host_rx_err, missing, qemu_rc);
  lcm_destroy(lcm);
  return rc;
}
