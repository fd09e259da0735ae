/* SPDX-License-Identifier: Apache-2.0 */
/* pil_map.c: target-side record mappings (pil_map.h). Float firmware only. */
#include "pil/pil_map.h"

#include <string.h>

_Static_assert(UVMS_REAL_IS_FLOAT, "the PIL records carry the float firmware's reals");
_Static_assert(UVMS_MAX_JOINTS == 7 && UVMS_MAX_THRUSTERS == 8,
               "record shapes follow lcmtypes (7 joints, 8 thrusters)");

#define UVMS_CONFIG_MAP_FN pil_config_from_rec
#define UVMS_CONFIG_MAP_MSG_T pil_config_rec_t
#define UVMS_CONFIG_MAP_REAL_T float
#include "msg/config_from_msg.inc"

/* Same-named float fields, copied as flat arrays (a [7][3] field is 21 contiguous floats). */
static void copy_f32(float *dst, const float *src, size_t n) {
  for (size_t i = 0; i < n; ++i) dst[i] = src[i];
}
#define PIL_COPY_FIELD_(dst, src, name) \
  copy_f32((float *)&(dst)->name, (const float *)&(src)->name, sizeof((src)->name) / sizeof(float))

void pil_sensors_from_rec(const pil_sensors_rec_t *rec, uvms_ctrl_sensors_t *s) {
  memset(s, 0, sizeof *s);
  s->tick = rec->tick;
#define PIL_SENSOR_COPY_(name, dims, unit, doc) PIL_COPY_FIELD_(s, rec, name);
  PIL_SENSOR_FIELDS(PIL_SENSOR_COPY_)
#undef PIL_SENSOR_COPY_
  s->thruster_usable_mask = rec->thruster_usable_mask;
}

void pil_output_to_rec(int64_t tick, int32_t status, const uvms_ctrl_command_t *cmd,
                       const uvms_ctrl_telemetry_t *tlm, pil_output_rec_t *rec) {
  memset(rec, 0, sizeof *rec);
  rec->tick = tick;
  rec->status = status;
  rec->flags = tlm->flags;
#define PIL_CMD_COPY_(name, dims, unit, doc) PIL_COPY_FIELD_(rec, cmd, name);
#define PIL_TLM_COPY_(name, dims, unit, doc) PIL_COPY_FIELD_(rec, tlm, name);
#define PIL_INT_COPY_(type, name, doc) rec->name = tlm->name;
  PIL_COMMAND_FIELDS(PIL_CMD_COPY_)
  PIL_TELEMETRY_FIELDS(PIL_TLM_COPY_)
  PIL_TELEMETRY_INTS(PIL_INT_COPY_)
#undef PIL_CMD_COPY_
#undef PIL_TLM_COPY_
#undef PIL_INT_COPY_
}
