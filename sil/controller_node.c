/* controller_node.c: the controller node's message logic and LCM binding (controller_node.h). */
#include "controller_node.h"

#include <stdio.h>
#include <string.h>

void uvms_ctrl_node_init(uvms_ctrl_node_t *node) { memset(node, 0, sizeof *node); }

static void fill_counters(const uvms_ctrl_node_t *node, uvms_telemetry_t *t) {
  t->rx_rejected = node->rx_rejected;
  t->rx_out_of_sequence = node->rx_out_of_sequence;
  t->rx_unconfigured = node->rx_unconfigured;
}

void uvms_ctrl_node_on_config(uvms_ctrl_node_t *node, const uint8_t *data, int len,
                              uvms_ctrl_node_out_t *out) {
  memset(out, 0, sizeof *out);
  uvms_controller_config_t msg;
  if (uvms_controller_config_t_decode_checked(data, len, &msg) < 0) {
    ++node->rx_rejected;
    return;
  }
  uvms_ctrl_config_t cfg;
  uvms_status_t st = UVMS_ERR_RANGE;
  node->configured = 0;
  node->have_last_tick = 0;
  if (uvms_config_from_msg(&msg, &cfg) == 0) {
    st = uvms_ctrl_init(&node->ctrl, &cfg);
  } else {
    memset(&node->ctrl, 0, sizeof node->ctrl);
  }
  node->configured = (st == UVMS_OK);
  out->has_telemetry = 1;
  out->telemetry.utime = msg.utime;
  out->telemetry.tick = -1;
  out->telemetry.status = (int32_t)st;
  out->telemetry.config_error = (int32_t)node->ctrl.config_error;
  fill_counters(node, &out->telemetry);
}

void uvms_ctrl_node_on_sensors(uvms_ctrl_node_t *node, const uint8_t *data, int len,
                               uvms_ctrl_node_out_t *out) {
  memset(out, 0, sizeof *out);
  uvms_sensors_t msg;
  if (uvms_sensors_t_decode_checked(data, len, &msg) < 0) {
    ++node->rx_rejected;
    return;
  }
  if (!node->configured) {
    ++node->rx_unconfigured;
    return;
  }
  if (node->have_last_tick && msg.tick <= node->last_tick) {
    ++node->rx_out_of_sequence;
    return;
  }
  node->have_last_tick = 1;
  node->last_tick = msg.tick;
  uvms_ctrl_sensors_t s;
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  memset(&cmd, 0, sizeof cmd);
  memset(&tlm, 0, sizeof tlm);
  uvms_sensors_from_msg(&msg, &s);
  const uvms_status_t st = uvms_ctrl_step(&node->ctrl, &s, &cmd, &tlm);
  ++node->steps;
  uvms_outputs_to_msgs(&msg, (int32_t)st, &cmd, &tlm, &out->actuators, &out->telemetry);
  fill_counters(node, &out->telemetry);
  out->has_telemetry = 1;
  out->has_actuators = 1;
}

void uvms_ctrl_node_on_status(uvms_ctrl_node_t *node, const uint8_t *data, int len) {
  uvms_run_status_t msg;
  if (uvms_run_status_t_decode_checked(data, len, &msg) < 0) {
    ++node->rx_rejected;
    return;
  }
  if (msg.state == UVMS_RUN_STATUS_T_FINISHED || msg.state == UVMS_RUN_STATUS_T_FAILED) {
    node->finished = 1;
  }
}

/* ---- LCM binding ---- */

/* Actuators first: the plant can integrate the next tick while the telemetry is on its way
 * (the plant node collects it after its step, so the log order stays fixed). */
static void publish_out(uvms_ctrl_node_t *node, const uvms_ctrl_node_out_t *out) {
  uint8_t buf[UVMS_MAX_MSG_BYTES];
  if (out->has_actuators) {
    const int n = uvms_actuators_t_encode_sealed(&out->actuators, buf, (int)sizeof buf);
    if (n > 0 && lcm_publish(node->lcm, UVMS_CH_ACTUATORS, buf, (unsigned)n) != 0) {
      fprintf(stderr, "uvms-controller: warning: publishing actuators of tick %lld failed\n",
              (long long)out->actuators.tick);
    }
  }
  if (out->has_telemetry) {
    const int n = uvms_telemetry_t_encode_sealed(&out->telemetry, buf, (int)sizeof buf);
    if (n > 0 && lcm_publish(node->lcm, UVMS_CH_TELEMETRY, buf, (unsigned)n) != 0) {
      fprintf(stderr, "uvms-controller: warning: publishing telemetry of tick %lld failed\n",
              (long long)out->telemetry.tick);
    }
  }
}

static void on_config_raw(const lcm_recv_buf_t *rbuf, const char *channel, void *user) {
  (void)channel;
  uvms_ctrl_node_t *node = (uvms_ctrl_node_t *)user;
  static uvms_ctrl_node_out_t out; /* single-threaded handler: static keeps the stack small */
  uvms_ctrl_node_on_config(node, (const uint8_t *)rbuf->data, (int)rbuf->data_size, &out);
  publish_out(node, &out);
}

static void on_sensors_raw(const lcm_recv_buf_t *rbuf, const char *channel, void *user) {
  (void)channel;
  uvms_ctrl_node_t *node = (uvms_ctrl_node_t *)user;
  static uvms_ctrl_node_out_t out;
  uvms_ctrl_node_on_sensors(node, (const uint8_t *)rbuf->data, (int)rbuf->data_size, &out);
  publish_out(node, &out);
}

static void on_status_raw(const lcm_recv_buf_t *rbuf, const char *channel, void *user) {
  (void)channel;
  uvms_ctrl_node_on_status((uvms_ctrl_node_t *)user, (const uint8_t *)rbuf->data,
                           (int)rbuf->data_size);
}

int uvms_ctrl_node_attach(uvms_ctrl_node_t *node, lcm_t *lcm) {
  node->lcm = lcm;
  if (lcm_subscribe(lcm, UVMS_CH_CONFIG, on_config_raw, node) == NULL) return -1;
  if (lcm_subscribe(lcm, UVMS_CH_SENSORS, on_sensors_raw, node) == NULL) return -1;
  if (lcm_subscribe(lcm, UVMS_CH_STATUS, on_status_raw, node) == NULL) return -1;
  return 0;
}
