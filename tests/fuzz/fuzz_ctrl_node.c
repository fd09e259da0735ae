/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_ctrl_node: the controller node's message handlers (sil/link/controller_node.h) driven by a
 * sequence of (channel, bytes) records carved from the input, as the LCM binding would call
 * them: one node, many messages, in order.
 *
 * Record layout (repeated until the input ends, at most FUZZ_MAX_RECORDS):
 *   byte h     channel = h & 3:
 *                0 UVMS_CONFIG  1 UVMS_SENSORS  2 UVMS_STATUS: then 2 bytes of length L
 *                  (big-endian, clipped to what is left) and L message bytes. Delivered as
 *                  they are, or, when bit 7 of h is set, with the last 4 bytes overwritten by
 *                  their CRC (uvms_crc_seal) so they pass the integrity gate and reach the
 *                  decoder's checks, the mapping and the firmware;
 *                3 a valid sealed paper configuration of session FUZZ_SESSION: 1 byte,
 *                  case = 1 + (b & 7).
 *
 * Properties after each record (controller_node.h's rules):
 *   - config: a telemetry answer exactly when it decoded and was of the node's session (or the
 *     node had none yet), else rx_rejected or rx_foreign_session grows by one; never actuators;
 *     the answer's status is UVMS_OK exactly when the node is now configured; an accepted
 *     configuration fixes the node's session, which never changes after that;
 *   - sensors: exactly one of rx_rejected, rx_foreign_session, rx_unconfigured,
 *     rx_out_of_sequence, steps grows by one; actuators (with telemetry of the same tick) exactly when a step ran, and then
 *     every motor voltage is finite with |V| ≤ the configured limit, every joint acceleration
 *     finite;
 *   - status: no answer; `finished` never goes back to 0, and is set only by the node's session;
 *   - counters never decrease.
 */
#include <math.h>
#include <string.h>

#include "link/controller_node.h"
#include "fuzz_support.h"

enum { FUZZ_MAX_RECORDS = 64 };

/* Deliver one message on a channel; returns nothing, checks the node's rules. */
static void deliver(uvms_ctrl_node_t *node, int channel, const uint8_t *msg, int len,
                    uvms_ctrl_node_out_t *out) {
  const uvms_ctrl_node_t before = *node;
  memset(out, 0xFF, sizeof *out); /* the handler must clear what it does not fill */
  if (channel == 0) {
    uvms_ctrl_node_on_config(node, msg, len, out);
    FUZZ_REQUIRE(!out->has_actuators, "config answered with actuators");
    const long dropped = (long)(node->rx_rejected - before.rx_rejected) +
                         (long)(node->rx_foreign_session - before.rx_foreign_session);
    if (dropped == 1) {
      FUZZ_REQUIRE(!out->has_telemetry, "dropped config answered");
      FUZZ_REQUIRE(node->configured == before.configured, "dropped config changed the node");
    } else {
      FUZZ_REQUIRE(dropped == 0, "a config moved the drop counters by %ld", dropped);
      FUZZ_REQUIRE(out->has_telemetry == 1, "decoded config not answered");
      FUZZ_REQUIRE(out->telemetry.tick == -1, "config answer tick %lld",
                   (long long)out->telemetry.tick);
      FUZZ_REQUIRE((out->telemetry.status == 0) == (node->configured == 1),
                   "answer status %d, configured %d", (int)out->telemetry.status,
                   node->configured);
    }
  } else if (channel == 1) {
    uvms_ctrl_node_on_sensors(node, msg, len, out);
    const long grew = (long)(node->rx_rejected - before.rx_rejected) +
                      (long)(node->rx_foreign_session - before.rx_foreign_session) +
                      (long)(node->rx_unconfigured - before.rx_unconfigured) +
                      (long)(node->rx_out_of_sequence - before.rx_out_of_sequence) +
                      (long)(node->steps - before.steps);
    FUZZ_REQUIRE(grew == 1, "sensors message moved the counters by %ld", grew);
    const int stepped = node->steps == before.steps + 1;
    FUZZ_REQUIRE(out->has_actuators == stepped && out->has_telemetry == stepped,
                 "stepped %d, has_actuators %d, has_telemetry %d", stepped,
                 out->has_actuators, out->has_telemetry);
    if (stepped) {
      FUZZ_REQUIRE(out->actuators.tick == out->telemetry.tick, "actuators tick %lld, telemetry %lld",
                   (long long)out->actuators.tick, (long long)out->telemetry.tick);
      const size_t n = node->ctrl.alloc.geom.num_thrusters;
      for (int j = 0; j < UVMS_ACTUATORS_T_NUM_THRUSTERS; ++j) {
        /* Each thruster within its own supply (its motor set, firmware 0.8.0); a slot past the
           layout is never driven. */
        const double vmax =
            (size_t)j < n ? (double)node->ctrl.cfg->thruster[j].voltage_limit_V : 0.0;
        const double v = out->actuators.motor_voltage_V[j];
        FUZZ_REQUIRE(isfinite(v) && fabs(v) <= vmax, "V[%d] = %g V, limit %g V (status %d)", j,
                     v, vmax, (int)out->actuators.status);
      }
      for (int i = 0; i < UVMS_ACTUATORS_T_NUM_JOINTS; ++i) {
        FUZZ_REQUIRE(isfinite(out->actuators.joint_acceleration_rad_s2[i]),
                     "joint %d acceleration %g (status %d)", i,
                     out->actuators.joint_acceleration_rad_s2[i], (int)out->actuators.status);
      }
    }
  } else {
    uvms_ctrl_node_on_status(node, msg, len);
    FUZZ_REQUIRE(node->finished >= before.finished, "finished went back to 0");
    FUZZ_REQUIRE(node->configured == before.configured && node->steps == before.steps,
                 "a status message changed the controller");
    FUZZ_REQUIRE(node->finished == before.finished || node->session != UVMS_SESSION_NONE,
                 "a status ended a node without a session");
  }
  FUZZ_REQUIRE(before.session == UVMS_SESSION_NONE || node->session == before.session,
               "the node's session changed");
  FUZZ_REQUIRE(node->rx_rejected >= before.rx_rejected &&
                   node->rx_unconfigured >= before.rx_unconfigured &&
                   node->rx_out_of_sequence >= before.rx_out_of_sequence &&
                   node->rx_foreign_session >= before.rx_foreign_session &&
                   node->steps >= before.steps,
               "a counter decreased");
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static uvms_ctrl_node_t node; /* static: it holds a whole controller */
  static uvms_ctrl_node_out_t out;
  uvms_ctrl_node_init(&node);
  size_t pos = 0;
  for (int r = 0; r < FUZZ_MAX_RECORDS && pos < size; ++r) {
    const uint8_t h = data[pos++];
    const int channel = h & 3;
    if (channel == 3) {
      if (pos >= size) break;
      const int case_number = 1 + (data[pos++] & 7);
      uvms_ctrl_config_t cfg;
      uvms_controller_config_t msg;
      static uint8_t buf[UVMS_MAX_MSG_BYTES];
      FUZZ_REQUIRE(uvms_ctrl_config_paper(&cfg, case_number) == UVMS_OK, "case %d", case_number);
      uvms_config_to_msg(&cfg, &msg);
      msg.session = FUZZ_SESSION;
      const int n = uvms_controller_config_t_encode_sealed(&msg, buf, (int)sizeof buf);
      FUZZ_REQUIRE(n > 0, "paper configuration does not encode: %d", n);
      const int64_t session_before = node.session;
      deliver(&node, 0, buf, n, &out);
      FUZZ_REQUIRE(node.configured == 1 || (session_before != UVMS_SESSION_NONE &&
                                            session_before != FUZZ_SESSION),
                   "paper case %d refused by the node", case_number);
      continue;
    }
    if (size - pos < 2) break;
    size_t len = ((size_t)data[pos] << 8) | data[pos + 1];
    pos += 2;
    if (len > size - pos) len = size - pos;
    /* An exact-size heap copy: AddressSanitizer then sees any read past the message. */
    uint8_t *msg = malloc(len > 0 ? len : 1);
    FUZZ_REQUIRE(msg != NULL, "out of memory (%zu bytes)", len);
    memcpy(msg, data + pos, len);
    pos += len;
    if ((h & 0x80) != 0 && len >= 4) uvms_crc_seal(msg, (int)len);
    deliver(&node, channel, msg, (int)len, &out);
    free(msg);
  }
  return 0;
}
