/* SPDX-License-Identifier: Apache-2.0 */
/*
 * controller_node.h: the controller side of the SIL link (C; LCM C API + firmware).
 *
 * The one controller-node core: its message rules are written here once and are shared by the
 * host controller (uvms-controller, the in-process memq runner, `uvms replay`) and the PIL
 * bridge (uvms-controller-pil, sil/pil/pil_bridge_main.c). What differs is only the compute
 * step behind the rules (uvms_ctrl_node_compute_t): by default the node's own firmware
 * controller (uvms_ctrl_init / uvms_ctrl_step on node->ctrl); in the PIL bridge, the Cortex-M4F
 * target behind sil/pil/pil_host.h. The message logic is transport-free (uvms_ctrl_node_on_*:
 * bytes in, messages out; uvms_ctrl_node_handle: bytes in, answers published through a given
 * function); uvms_ctrl_node_attach binds it to LCM.
 *
 * Rules:
 *  - A message that does not decode, fails its CRC or has the wrong size is dropped and counted
 *    (rx_rejected); nothing else happens.
 *  - Sessions (session.h): a message whose session is not the node's is dropped and counted
 *    (rx_foreign_session); nothing else happens. A message without a session (0) is always
 *    foreign. The node's session is the one
 *    uvms_ctrl_node_set_session fixed (`uvms run` passes --session), else the session of the
 *    first configuration the compute step accepted; until then every status and sensors
 *    record is foreign or unconfigured, and a configuration of any session may configure it.
 *  - controller_config_t: the compute step's configure (uvms_ctrl_init); the answer is a
 *    telemetry_t with tick -1 carrying the init status and config_error. A later config of the
 *    same session re-initialises.
 *  - sensors_t: dropped and counted (rx_unconfigured) before a valid config; dropped and
 *    counted (rx_out_of_sequence) unless its tick is after the last tick handled (0 or more
 *    first) and at most UVMS_CTRL_NODE_TICK_WINDOW ticks past the expected one (a
 *    bounded window, so one far-future record cannot lock out the run); otherwise one
 *    compute step (uvms_ctrl_step), answered with actuators_t and telemetry_t of the same tick
 *    (telemetry carries the node's counters and the step's target_instructions). A gap in the
 *    ticks is passed on: the firmware flags it (UVMS_FLAG_TICK_GAP).
 *  - run_status_t of the node's session with state FINISHED or FAILED sets `finished`.
 *  - A compute step that fails (the PIL target stopped answering) sets `failed`: the node then
 *    ignores every message and answers nothing more (its serving loop ends).
 *
 * Publish order (the one place it is written down; lcmtypes/telemetry_t.lcm, the plant node
 * and the PIL bridge point here): the answer to a sensors message is published as
 *     1. actuators_t (UVMS_ACTUATORS), then
 *     2. telemetry_t (UVMS_TELEMETRY) of the same tick;
 * a configuration's answer is the telemetry_t of tick -1 alone. Actuators first, because the
 * plant node integrates the next tick as soon as they arrive and collects the telemetry after
 * its step: the run's log order (sensors k, actuators k, telemetry k, truth k+1, ...) depends
 * on it (tests/sil/golden/paper_logs.sha256 pins it).
 */
#ifndef UVMS_SIL_CONTROLLER_NODE_H
#define UVMS_SIL_CONTROLLER_NODE_H

#include <lcm/lcm.h>
#include <signal.h>

#include "msg/codec.h"
#include "msg/session.h"

/* Sensors more than this many ticks past the expected tick are dropped as out of sequence
   (the link's own losses stay far below it: link.max_missed consecutive misses end the run
   long before in the paper scenarios). */
#define UVMS_CTRL_NODE_TICK_WINDOW 1000

#ifdef __cplusplus
extern "C" {
#endif

/* The compute step behind the node's rules. Each function returns 0, or -1 when the compute
 * backend itself failed (it has said why on stderr): the node then sets `failed`. */
typedef struct {
  /* Apply a decoded configuration: *status = the init status (uvms_status_t), *config_error =
   * the part it rejected (uvms_cfg_field_t, 0 = none). */
  int (*configure)(void *ctx, const uvms_controller_config_t *msg, int32_t *status,
                   int32_t *config_error);
  /* One step on a decoded, in-sequence sensors record: *status (uvms_status_t), the command and
   * the telemetry (zeroed by the node before the call), and the step's instruction count on
   * the target (*target_instructions, 0 by default). */
  int (*step)(void *ctx, const uvms_sensors_t *msg, int32_t *status, uvms_ctrl_command_t *cmd,
              uvms_ctrl_telemetry_t *tlm, int64_t *target_instructions);
  void *ctx;
} uvms_ctrl_node_compute_t;

typedef struct {
  uvms_ctrl_t ctrl;           /* the firmware controller (the default compute step's) */
  uvms_ctrl_config_t cfg;     /* the configuration ctrl points to (uvms_ctrl_init): lives as
                                 long as the node, rewritten only while ctrl is not ready */
  uvms_ctrl_node_compute_t compute; /* set by init to the firmware on ctrl */
  const char *name;           /* program name for messages ("uvms-controller") */
  int configured;             /* 1 after a config the compute step accepted */
  int64_t session;            /* the run's session (UVMS_SESSION_NONE: not fixed yet) */
  int have_last_tick;
  int64_t last_tick;          /* last sensors tick handled */
  int32_t rx_rejected;        /* dropped: undecodable / CRC / size */
  int32_t rx_out_of_sequence; /* sensors dropped: tick not after the last one */
  int32_t rx_unconfigured;    /* sensors dropped: no valid config */
  int32_t rx_foreign_session; /* dropped: another session's message (or none adopted yet) */
  int64_t steps;              /* compute steps (uvms_ctrl_step calls) */
  int finished;               /* a run_status_t end state was received */
  int failed;                 /* the compute step failed: nothing more is handled */
  lcm_t *lcm;                 /* set by uvms_ctrl_node_attach (NULL: not bound) */
  lcm_t *publish_lcm;         /* where the answers go: lcm, or another URL's (attach_split) */
  lcm_subscription_t *subs[3]; /* config, sensors, status (uvms_ctrl_node_detach) */
} uvms_ctrl_node_t;

/* What one incoming message produced (published in the order above). */
typedef struct {
  int has_telemetry;
  int has_actuators;
  uvms_telemetry_t telemetry;
  uvms_actuators_t actuators;
} uvms_ctrl_node_out_t;

/* Clear the node; its compute step is the firmware on node->ctrl. */
void uvms_ctrl_node_init(uvms_ctrl_node_t *node);
/* Fix the node's session (after init): only messages carrying it are handled. */
void uvms_ctrl_node_set_session(uvms_ctrl_node_t *node, int64_t session);
/* Replace the compute step (after init). */
void uvms_ctrl_node_set_compute(uvms_ctrl_node_t *node, const uvms_ctrl_node_compute_t *compute);

/* Bytes in: decode (counting what does not), then the rules below. */
void uvms_ctrl_node_on_config(uvms_ctrl_node_t *node, const uint8_t *data, int len,
                              uvms_ctrl_node_out_t *out);
void uvms_ctrl_node_on_sensors(uvms_ctrl_node_t *node, const uint8_t *data, int len,
                               uvms_ctrl_node_out_t *out);
void uvms_ctrl_node_on_status(uvms_ctrl_node_t *node, const uint8_t *data, int len);

/* Decoded messages in: configure / sequence, count, compute, answer. */
void uvms_ctrl_node_configure(uvms_ctrl_node_t *node, const uvms_controller_config_t *msg,
                              uvms_ctrl_node_out_t *out);
void uvms_ctrl_node_step(uvms_ctrl_node_t *node, const uvms_sensors_t *msg,
                         uvms_ctrl_node_out_t *out);

/* Where a node's answers go: publish(ctx, channel, bytes, len) returns 0, or nonzero when it
 * failed (the node warns on stderr and goes on). */
typedef int (*uvms_ctrl_node_publish_fn)(void *ctx, const char *channel, const uint8_t *data,
                                         int len);

/* One message of `channel` in: config, sensors or status (the on_* functions above), each answer
 * encoded (CRC-sealed) and published through publish(ctx, ...) in the order above. Returns 1, or
 * 0 (nothing done) for a channel that is not the node's. The LCM binding below is this function
 * with lcm_publish; the in-process transport of `uvms run --transport memq`
 * (sil/run/inprocess_bus.hpp) calls it with its own queue. Single-threaded: one message at a
 * time. */
int uvms_ctrl_node_handle(uvms_ctrl_node_t *node, const char *channel, const uint8_t *data,
                          int len, uvms_ctrl_node_publish_fn publish, void *ctx);

/* Subscribe the node to the config, sensors and status channels of lcm; each answer is
 * encoded (CRC-sealed) and published on the same lcm in the order above. Returns 0, or -1 if a
 * subscription failed (those made are released again). */
int uvms_ctrl_node_attach(uvms_ctrl_node_t *node, lcm_t *lcm);
/* As uvms_ctrl_node_attach, but the answers are published on publish_lcm: a link whose two
 * directions are two LCM URLs (the private link of `uvms run`: then neither process receives
 * its own datagrams). publish_lcm is not subscribed to, so LCM opens no receive socket on it. */
int uvms_ctrl_node_attach_split(uvms_ctrl_node_t *node, lcm_t *lcm, lcm_t *publish_lcm);
/* Release the node's subscriptions (safe when not attached). */
void uvms_ctrl_node_detach(uvms_ctrl_node_t *node);

/* How uvms_ctrl_node_serve ended. */
typedef enum {
  UVMS_CTRL_NODE_FINISHED = 0, /* a run_status_t end state arrived */
  UVMS_CTRL_NODE_WAIT_ERROR,   /* waiting for LCM messages failed */
  UVMS_CTRL_NODE_IDLE,         /* nothing arrived for idle_timeout_s */
  UVMS_CTRL_NODE_STOPPED,      /* *stop became nonzero (a signal) */
  UVMS_CTRL_NODE_FAILED        /* the compute step failed */
} uvms_ctrl_node_end_t;

/* Serve an attached node until the run ends: handle messages (sil/link/lcm_wait.h, busy-poll
 * spin_us) until `finished`, `failed`, *stop (if stop is not NULL), a wait error, or
 * idle_timeout_s without any message. Says why on stderr (prefixed with node->name) unless it
 * finished. */
uvms_ctrl_node_end_t uvms_ctrl_node_serve(uvms_ctrl_node_t *node, double idle_timeout_s,
                                          int spin_us, const volatile sig_atomic_t *stop);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_SIL_CONTROLLER_NODE_H */
