/* SPDX-License-Identifier: Apache-2.0 */
/*
 * codec.h: the harness's message layer (C, shared by the C controller node, the C++ plant
 * node and `uvms replay`).
 *
 * Integrity: every uvms LCM message ends with an int32 crc32 field, which LCM encodes as the
 * last 4 bytes (big-endian). It holds the CRC-32 (IEEE 802.3, reflected, poly 0xEDB88320) of
 * every encoded byte before it, LCM fingerprint included. A receiver rejects a message whose
 * CRC, fingerprint or length does not check out (uvms_*_decode_checked); LCM's own decoder
 * only catches a wrong fingerprint or a short buffer, not a flipped bit inside a double.
 *
 * Mapping: the LCM messages <-> the firmware's structures (uvms_ctrl_config_t,
 * uvms_ctrl_sensors_t, uvms_ctrl_command_t, uvms_ctrl_telemetry_t). Pure functions: no LCM
 * transport here.
 */
#ifndef UVMS_SIL_CODEC_H
#define UVMS_SIL_CODEC_H

#include <stddef.h>
#include <stdint.h>

#include "uvms/controller.h"
#include "uvms_actuators_t.h"
#include "uvms_controller_config_t.h"
#include "uvms_run_status_t.h"
#include "uvms_scene_t.h"
#include "uvms_sensors_t.h"
#include "uvms_telemetry_t.h"
#include "uvms_truth_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* LCM channel names (a private LCM link per run, or the run's session on a shared URL, so
   fixed names never mix runs). */
#define UVMS_CH_CONFIG "UVMS_CONFIG"       /* controller_config_t, harness -> controller */
#define UVMS_CH_SENSORS "UVMS_SENSORS"     /* sensors_t, plant -> controller */
#define UVMS_CH_ACTUATORS "UVMS_ACTUATORS" /* actuators_t, controller -> plant */
#define UVMS_CH_TELEMETRY "UVMS_TELEMETRY" /* telemetry_t, controller -> harness */
#define UVMS_CH_TRUTH "UVMS_TRUTH"         /* truth_t, plant -> log */
#define UVMS_CH_STATUS "UVMS_STATUS"       /* run_status_t, harness -> everyone */
#define UVMS_CH_SCENE "UVMS_SCENE"         /* scene_t, plant -> log, once at the start */

/* Largest encoded message the harness handles (controller_config_t is ~3.6 kB) [bytes]. */
#define UVMS_MAX_MSG_BYTES 8192

/** CRC-32 (IEEE 802.3) of n bytes (0 for n == 0; data may be NULL only then). */
uint32_t uvms_crc32(const uint8_t *data, size_t n);
/** Write the CRC of buf[0, len-4) into buf[len-4, len) (big-endian). Needs len >= 4. */
void uvms_crc_seal(uint8_t *buf, int len);
/** 1 if len >= 4 and the trailing CRC matches, 0 otherwise. */
int uvms_crc_check(const uint8_t *buf, int len);
/** The session of any encoded uvms message (every lcmtypes/ struct begins with utime, tick and
 *  session: after the 8-byte fingerprint, bytes [24, 32), big-endian), without decoding the
 *  rest; 1 and *session, or 0 when len is too short. Check the CRC first to trust it. */
int uvms_msg_session(const uint8_t *buf, int len, int64_t *session);

/* Sealed encode: returns the encoded length, or < 0 if buf is too small.
 * Checked decode: returns the length on success; -1 undecodable (fingerprint, truncated or
 * trailing bytes), -2 CRC mismatch. Nothing is allocated (fixed-size types only). */
#define UVMS_DECLARE_CODEC(T)                                            \
  int T##_encode_sealed(const T *msg, uint8_t *buf, int capacity);      \
  int T##_decode_checked(const uint8_t *buf, int len, T *out);
UVMS_DECLARE_CODEC(uvms_sensors_t)
UVMS_DECLARE_CODEC(uvms_actuators_t)
UVMS_DECLARE_CODEC(uvms_telemetry_t)
UVMS_DECLARE_CODEC(uvms_run_status_t)
UVMS_DECLARE_CODEC(uvms_controller_config_t)
/* truth_t has a string (never decoded by C code): sealed encode only. */
int uvms_truth_t_encode_sealed(const uvms_truth_t *msg, uint8_t *buf, int capacity);
/* scene_t has strings and variable-length arrays (never decoded by C code): sealed encode only. */
int uvms_scene_t_encode_sealed(const uvms_scene_t *msg, uint8_t *buf, int capacity);

/** Firmware configuration -> message (utime 0, tick -1). */
void uvms_config_to_msg(const uvms_ctrl_config_t *cfg, uvms_controller_config_t *msg);
/** Message -> firmware configuration. Returns 0, or -1 if a count exceeds the firmware's
 *  maxima or an enum is out of range (cfg is then zeroed; uvms_ctrl_init rejects it). */
int uvms_config_from_msg(const uvms_controller_config_t *msg, uvms_ctrl_config_t *cfg);

/** Sensors message -> firmware sensors (time_s = utime · 1e-6). */
void uvms_sensors_from_msg(const uvms_sensors_t *msg, uvms_ctrl_sensors_t *s);
/** One step's outputs -> actuators and telemetry messages (tick and utime of the sensors). */
void uvms_outputs_to_msgs(const uvms_sensors_t *in, int32_t status,
                          const uvms_ctrl_command_t *cmd, const uvms_ctrl_telemetry_t *tlm,
                          uvms_actuators_t *act, uvms_telemetry_t *tel);

/** Name of the first field where two actuator messages differ bit for bit, with its element
 *  index in *index (-1 for scalars); NULL when identical. */
const char *uvms_actuators_first_difference(const uvms_actuators_t *a, const uvms_actuators_t *b,
                                            int *index);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_SIL_CODEC_H */
