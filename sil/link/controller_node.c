/* SPDX-License-Identifier: Apache-2.0 */
/* controller_node.c: the controller node's message rules, LCM binding and serving loop
 * (controller_node.h). */
#define _POSIX_C_SOURCE 200809L
#include "link/controller_node.h"

#include <stdio.h>
#include <string.h>
#include <time.h>

#include "link/lcm_wait.h"

/* ---- the default compute step: the firmware on node->ctrl ---- */

/* The controller points to node->cfg (uvms_ctrl_init's lifetime rule): the instance is
   cleared (not ready) before the configuration it pointed to is rewritten. */
static int firmware_configure(void *ctx, const uvms_controller_config_t *msg, int32_t *status,
                              int32_t *config_error) {
  uvms_ctrl_node_t *node = (uvms_ctrl_node_t *)ctx;
  uvms_ctrl_t *ctrl = &node->ctrl;
  uvms_status_t st = UVMS_ERR_RANGE;
  memset(ctrl, 0, sizeof *ctrl);
  if (uvms_config_from_msg(msg, &node->cfg) == 0) st = uvms_ctrl_init(ctrl, &node->cfg);
  *status = (int32_t)st;
  *config_error = (int32_t)ctrl->config_error;
  return 0;
}

static int firmware_step(void *ctx, const uvms_sensors_t *msg, int32_t *status,
                         uvms_ctrl_command_t *cmd, uvms_ctrl_telemetry_t *tlm,
                         int64_t *target_instructions) {
  uvms_ctrl_sensors_t s;
  uvms_sensors_from_msg(msg, &s);
  *status = (int32_t)uvms_ctrl_step(&((uvms_ctrl_node_t *)ctx)->ctrl, &s, cmd, tlm);
  *target_instructions = 0;
  return 0;
}

void uvms_ctrl_node_init(uvms_ctrl_node_t *node) {
  memset(node, 0, sizeof *node);
  node->compute.configure = firmware_configure;
  node->compute.step = firmware_step;
  node->compute.ctx = node;
  node->name = "uvms-controller";
}

void uvms_ctrl_node_set_session(uvms_ctrl_node_t *node, int64_t session) {
  node->session = session;
}

void uvms_ctrl_node_set_compute(uvms_ctrl_node_t *node, const uvms_ctrl_node_compute_t *compute) {
  node->compute = *compute;
}

/* ---- the rules ---- */

static void fill_counters(const uvms_ctrl_node_t *node, uvms_telemetry_t *t) {
  t->rx_rejected = node->rx_rejected;
  t->rx_out_of_sequence = node->rx_out_of_sequence;
  t->rx_unconfigured = node->rx_unconfigured;
  t->rx_foreign_session = node->rx_foreign_session;
}

/* Whether a message of `session` is the node's: counted as foreign when it is not. A message
   without a session is never the node's; a node without a session yet takes a configuration of
   any session (configure adopts it). */
static int own_session(uvms_ctrl_node_t *node, int64_t session, int is_config) {
  if (session != UVMS_SESSION_NONE &&
      (session == node->session || (is_config && node->session == UVMS_SESSION_NONE)))
    return 1;
  ++node->rx_foreign_session;
  return 0;
}

void uvms_ctrl_node_configure(uvms_ctrl_node_t *node, const uvms_controller_config_t *msg,
                              uvms_ctrl_node_out_t *out) {
  memset(out, 0, sizeof *out);
  if (node->failed || !own_session(node, msg->session, 1)) return;
  int32_t status = (int32_t)UVMS_ERR_RANGE, config_error = 0;
  node->configured = 0;
  node->have_last_tick = 0;
  if (node->compute.configure(node->compute.ctx, msg, &status, &config_error) != 0) {
    node->failed = 1;
    return;
  }
  node->configured = (status == (int32_t)UVMS_OK);
  if (node->configured) node->session = msg->session; /* adopted (or already the same) */
  out->has_telemetry = 1;
  out->telemetry.utime = msg->utime;
  out->telemetry.tick = -1;
  out->telemetry.session = msg->session;
  out->telemetry.status = status;
  out->telemetry.config_error = config_error;
  fill_counters(node, &out->telemetry);
}

void uvms_ctrl_node_step(uvms_ctrl_node_t *node, const uvms_sensors_t *msg,
                         uvms_ctrl_node_out_t *out) {
  memset(out, 0, sizeof *out);
  if (node->failed) return;
  if (node->session != UVMS_SESSION_NONE && !own_session(node, msg->session, 0)) return;
  if (!node->configured) {
    ++node->rx_unconfigured;
    return;
  }
  /* The expected tick is the one after the last handled (0 first); a record before it, or
     more than UVMS_CTRL_NODE_TICK_WINDOW ticks past it, is out of sequence: a forged or foreign
     far-future tick cannot make the node drop every genuine record after it. */
  const int64_t expected = node->have_last_tick ? node->last_tick + 1 : 0;
  if (msg->tick < expected || msg->tick - expected > UVMS_CTRL_NODE_TICK_WINDOW) {
    ++node->rx_out_of_sequence;
    return;
  }
  node->have_last_tick = 1;
  node->last_tick = msg->tick;
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  memset(&cmd, 0, sizeof cmd);
  memset(&tlm, 0, sizeof tlm);
  int32_t status = (int32_t)UVMS_ERR_RANGE;
  int64_t instructions = 0;
  if (node->compute.step(node->compute.ctx, msg, &status, &cmd, &tlm, &instructions) != 0) {
    node->failed = 1;
    return;
  }
  ++node->steps;
  uvms_outputs_to_msgs(msg, status, &cmd, &tlm, &out->actuators, &out->telemetry);
  fill_counters(node, &out->telemetry);
  out->telemetry.target_instructions = instructions;
  out->has_telemetry = 1;
  out->has_actuators = 1;
}

/* Start of a handler that may answer: clears the output; 0 when the node has failed (it answers
   nothing more). */
static int node_answers(const uvms_ctrl_node_t *node, uvms_ctrl_node_out_t *out) {
  memset(out, 0, sizeof *out);
  return !node->failed;
}

/* 1 when a message decoded (rc, the decoder's return, >= 0); one that did not is counted and
   otherwise ignored. */
static int decoded(uvms_ctrl_node_t *node, int rc) {
  if (rc < 0) ++node->rx_rejected;
  return rc >= 0;
}

void uvms_ctrl_node_on_config(uvms_ctrl_node_t *node, const uint8_t *data, int len,
                              uvms_ctrl_node_out_t *out) {
  uvms_controller_config_t msg;
  if (node_answers(node, out) && decoded(node, uvms_controller_config_t_decode_checked(data, len, &msg)))
    uvms_ctrl_node_configure(node, &msg, out);
}

void uvms_ctrl_node_on_sensors(uvms_ctrl_node_t *node, const uint8_t *data, int len,
                               uvms_ctrl_node_out_t *out) {
  uvms_sensors_t msg;
  if (node_answers(node, out) && decoded(node, uvms_sensors_t_decode_checked(data, len, &msg)))
    uvms_ctrl_node_step(node, &msg, out);
}

void uvms_ctrl_node_on_status(uvms_ctrl_node_t *node, const uint8_t *data, int len) {
  uvms_run_status_t msg;
  if (!decoded(node, uvms_run_status_t_decode_checked(data, len, &msg))) return;
  if (!own_session(node, msg.session, 0)) return; /* another run's status is not obeyed */
  if (msg.state == UVMS_RUN_STATUS_T_FINISHED || msg.state == UVMS_RUN_STATUS_T_FAILED) {
    node->finished = 1;
  }
}

/* ---- answers, through a publish function ---- */

static void publish_one(const uvms_ctrl_node_t *node, uvms_ctrl_node_publish_fn publish,
                        void *ctx, const char *channel, const char *what, const uint8_t *buf,
                        int n, int64_t tick) {
  if (n > 0 && publish(ctx, channel, buf, n) != 0) {
    fprintf(stderr, "%s: warning: publishing %s of tick %lld failed\n", node->name, what,
            (long long)tick);
  }
}

/* The publish order of controller_node.h: actuators, then telemetry. */
static void publish_out(const uvms_ctrl_node_t *node, const uvms_ctrl_node_out_t *out,
                        uvms_ctrl_node_publish_fn publish, void *ctx) {
  uint8_t buf[UVMS_MAX_MSG_BYTES];
  if (out->has_actuators) {
    const int n = uvms_actuators_t_encode_sealed(&out->actuators, buf, (int)sizeof buf);
    publish_one(node, publish, ctx, UVMS_CH_ACTUATORS, "actuators", buf, n, out->actuators.tick);
  }
  if (out->has_telemetry) {
    const int n = uvms_telemetry_t_encode_sealed(&out->telemetry, buf, (int)sizeof buf);
    publish_one(node, publish, ctx, UVMS_CH_TELEMETRY, "telemetry", buf, n, out->telemetry.tick);
  }
}

int uvms_ctrl_node_handle(uvms_ctrl_node_t *node, const char *channel, const uint8_t *data,
                          int len, uvms_ctrl_node_publish_fn publish, void *ctx) {
  static uvms_ctrl_node_out_t out; /* single-threaded handling: static keeps the stack small */
  if (strcmp(channel, UVMS_CH_SENSORS) == 0) {
    uvms_ctrl_node_on_sensors(node, data, len, &out);
  } else if (strcmp(channel, UVMS_CH_CONFIG) == 0) {
    uvms_ctrl_node_on_config(node, data, len, &out);
  } else if (strcmp(channel, UVMS_CH_STATUS) == 0) {
    uvms_ctrl_node_on_status(node, data, len);
    return 1;
  } else {
    return 0;
  }
  publish_out(node, &out, publish, ctx);
  return 1;
}

/* ---- LCM binding ---- */

static int lcm_publisher(void *ctx, const char *channel, const uint8_t *data, int len) {
  return lcm_publish((lcm_t *)ctx, channel, data, (unsigned)len);
}

/* The one handler of the node's three subscriptions (exact channel names, no patterns). */
static void on_message_raw(const lcm_recv_buf_t *rbuf, const char *channel, void *user) {
  uvms_ctrl_node_t *node = (uvms_ctrl_node_t *)user;
  (void)uvms_ctrl_node_handle(node, channel, (const uint8_t *)rbuf->data, (int)rbuf->data_size,
                              lcm_publisher, node->publish_lcm);
}

int uvms_ctrl_node_attach(uvms_ctrl_node_t *node, lcm_t *lcm) {
  return uvms_ctrl_node_attach_split(node, lcm, lcm);
}

int uvms_ctrl_node_attach_split(uvms_ctrl_node_t *node, lcm_t *lcm, lcm_t *publish_lcm) {
  node->lcm = lcm;
  node->publish_lcm = publish_lcm;
  node->subs[0] = lcm_subscribe(lcm, UVMS_CH_CONFIG, on_message_raw, node);
  node->subs[1] = lcm_subscribe(lcm, UVMS_CH_SENSORS, on_message_raw, node);
  node->subs[2] = lcm_subscribe(lcm, UVMS_CH_STATUS, on_message_raw, node);
  if (node->subs[0] == NULL || node->subs[1] == NULL || node->subs[2] == NULL) {
    uvms_ctrl_node_detach(node);
    return -1;
  }
  return 0;
}

void uvms_ctrl_node_detach(uvms_ctrl_node_t *node) {
  for (int i = 0; i < 3; ++i) {
    if (node->subs[i] != NULL) lcm_unsubscribe(node->lcm, node->subs[i]);
    node->subs[i] = NULL;
  }
}

/* ---- serving loop ---- */

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

uvms_ctrl_node_end_t uvms_ctrl_node_serve(uvms_ctrl_node_t *node, double idle_timeout_s,
                                          int spin_us, const volatile sig_atomic_t *stop) {
  double last_rx_s = now_s();
  while (!node->finished) {
    if (stop != NULL && *stop) {
      fprintf(stderr, "%s: stopped by a signal\n", node->name);
      return UVMS_CTRL_NODE_STOPPED;
    }
    if (node->failed) return UVMS_CTRL_NODE_FAILED; /* the compute step said why */
    const int r = uvms_lcm_wait(node->lcm, 100, spin_us);
    if (r < 0) {
      if (stop != NULL && *stop) continue;
      fprintf(stderr, "%s: error: waiting for LCM messages failed\n", node->name);
      return UVMS_CTRL_NODE_WAIT_ERROR;
    }
    if (r > 0) {
      last_rx_s = now_s();
    } else if (now_s() - last_rx_s > idle_timeout_s) {
      fprintf(stderr, "%s: error: no message for %.1f s; exiting\n", node->name, idle_timeout_s);
      return UVMS_CTRL_NODE_IDLE;
    }
  }
  return UVMS_CTRL_NODE_FINISHED;
}
