/* SPDX-License-Identifier: Apache-2.0 */
/*
 * pil_map.h: PIL records <-> the firmware's structures, on the target side (compiled into the
 * Cortex-M4F image with the float firmware; also into host tests against a float firmware
 * build). No LCM. The host side (LCM messages <-> records) is pil_host.h.
 */
#ifndef UVMS_PIL_MAP_H
#define UVMS_PIL_MAP_H

#include "pil/pil_protocol.h"
#include "uvms/controller.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Record -> configuration: sil/msg/codec.c's uvms_config_from_msg, the same code (the shared
 *  sil/msg/config_from_msg.inc) applied to the float record. Returns 0, or -1 (cfg zeroed) if a
 *  count or an enum is out of range. */
int pil_config_from_rec(const pil_config_rec_t *rec, uvms_ctrl_config_t *cfg);

/** Record -> the firmware's sensors (a copy: the record already holds the float values). */
void pil_sensors_from_rec(const pil_sensors_rec_t *rec, uvms_ctrl_sensors_t *s);

/** One step's outputs -> output record. */
void pil_output_to_rec(int64_t tick, int32_t status, const uvms_ctrl_command_t *cmd,
                       const uvms_ctrl_telemetry_t *tlm, pil_output_rec_t *rec);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_PIL_MAP_H */
