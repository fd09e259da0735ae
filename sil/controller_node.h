/*
 * controller_node.h: the controller side of the SIL link (C; LCM C API + firmware).
 *
 * The node owns one firmware controller. Its message logic is transport-free
 * (uvms_ctrl_node_on_*: bytes in, messages out), so that the LCM binding
 * (uvms_ctrl_node_attach), the in-process memq runner and `uvms replay` share it exactly.
 *
 * Rules (issue 5):
 *  - A message that does not decode, fails its CRC or has the wrong size is dropped and counted
 *    (rx_rejected); nothing else happens.
 *  - controller_config_t: uvms_ctrl_init; the answer is a telemetry_t with tick -1 carrying
 *    the init status and config_error. A later config re-initialises (a new run).
 *  - sensors_t: dropped and counted (rx_unconfigured) before a valid config; dropped and
 *    counted (rx_out_of_sequence) unless its tick is after the last tick handled; otherwise one
 *    uvms_ctrl_step, answered with actuators_t then telemetry_t of the same tick. A gap in the
 *    ticks is passed on: the firmware flags it (UVMS_FLAG_TICK_GAP).
 *  - run_status_t with state FINISHED or FAILED sets `finished`.
 */
#ifndef UVMS_SIL_CONTROLLER_NODE_H
#define UVMS_SIL_CONTROLLER_NODE_H

#include <lcm/lcm.h>

#include "codec.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  uvms_ctrl_t ctrl;           /* the firmware controller */
  int configured;             /* 1 after a config that uvms_ctrl_init accepted */
  int have_last_tick;
  int64_t last_tick;          /* last sensors tick handled */
  int32_t rx_rejected;        /* dropped: undecodable / CRC / size */
  int32_t rx_out_of_sequence; /* sensors dropped: tick not after the last one */
  int32_t rx_unconfigured;    /* sensors dropped: no valid config */
  int64_t steps;              /* uvms_ctrl_step calls */
  int finished;               /* a run_status_t end state was received */
  lcm_t *lcm;                 /* set by uvms_ctrl_node_attach (NULL: not bound) */
} uvms_ctrl_node_t;

/* What one incoming message produced (published: actuators first, then telemetry). */
typedef struct {
  int has_telemetry;
  int has_actuators;
  uvms_telemetry_t telemetry;
  uvms_actuators_t actuators;
} uvms_ctrl_node_out_t;

void uvms_ctrl_node_init(uvms_ctrl_node_t *node);
void uvms_ctrl_node_on_config(uvms_ctrl_node_t *node, const uint8_t *data, int len,
                              uvms_ctrl_node_out_t *out);
void uvms_ctrl_node_on_sensors(uvms_ctrl_node_t *node, const uint8_t *data, int len,
                               uvms_ctrl_node_out_t *out);
void uvms_ctrl_node_on_status(uvms_ctrl_node_t *node, const uint8_t *data, int len);

/* Subscribe the node to the config, sensors and status channels of lcm; each answer is
 * encoded (CRC-sealed) and published on the same lcm. Returns 0, or -1 if a subscription
 * failed. */
int uvms_ctrl_node_attach(uvms_ctrl_node_t *node, lcm_t *lcm);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_SIL_CONTROLLER_NODE_H */
