/* SPDX-License-Identifier: Apache-2.0 */
/* codec.c: CRC-sealed LCM encode/decode and the message <-> firmware mappings (codec.h). */
#include "msg/codec.h"

#include <string.h>

#if defined(UVMS_CRC_ISAL)
#include <isa-l/crc.h>
#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif
#else
#include <zlib.h>
#endif

#include "msg/config_table.h"
#include "msg/record_table.h"

/* ---- CRC-32 (IEEE 802.3, reflected, init and final xor 0xFFFFFFFF) ----
 * From a library: Intel ISA-L's crc32_gzip_refl (carry-less multiply folding) where the build
 * found it (UVMS_CRC_ISAL, sil/CMakeLists.txt), else zlib's crc32_z. Both are this CRC (the
 * one of gzip and Ethernet); tests/sil/test_codec.cpp checks either against a bit-at-a-time
 * implementation and the catalogue check value. */

#if defined(UVMS_CRC_ISAL) && (defined(__x86_64__) || defined(__i386__))
/* ISA-L's AVX-512 CRC returns with the upper halves of the vector registers in use (it issues no
   vzeroupper: intel/isa-l#24), and every later SSE instruction of the process may then pay for
   them: on this project's AMD EPYC machines (AVX-512), the truth model of a campaign run took
   45 % more time. Clear them after
   each call, on a CPU that has AVX (the instruction does not exist without it). */
__attribute__((target("avx"))) static void avx_zero_upper(void) { _mm256_zeroupper(); }
static void after_isal(void) {
  if (__builtin_cpu_supports("avx")) avx_zero_upper();
}
#elif defined(UVMS_CRC_ISAL)
static void after_isal(void) {}
#endif

uint32_t uvms_crc32(const uint8_t *data, size_t n) {
  if (data == NULL || n == 0) return 0u;
#if defined(UVMS_CRC_ISAL)
  const uint32_t c = crc32_gzip_refl(0u, data, (uint64_t)n);
  after_isal();
  return c;
#else
  return (uint32_t)crc32_z(0ul, data, (z_size_t)n);
#endif
}

void uvms_crc_seal(uint8_t *buf, int len) {
  if (buf == NULL || len < 4) return;
  const uint32_t c = uvms_crc32(buf, (size_t)(len - 4));
  buf[len - 4] = (uint8_t)(c >> 24);
  buf[len - 3] = (uint8_t)(c >> 16);
  buf[len - 2] = (uint8_t)(c >> 8);
  buf[len - 1] = (uint8_t)c;
}

int uvms_crc_check(const uint8_t *buf, int len) {
  if (buf == NULL || len < 4) return 0;
  const uint32_t c = uvms_crc32(buf, (size_t)(len - 4));
  const uint32_t got = ((uint32_t)buf[len - 4] << 24) | ((uint32_t)buf[len - 3] << 16) |
                       ((uint32_t)buf[len - 2] << 8) | (uint32_t)buf[len - 1];
  return c == got;
}

int uvms_msg_session(const uint8_t *buf, int len, int64_t *session) {
  enum { kSessionOffset = 8 /* fingerprint */ + 8 /* utime */ + 8 /* tick */ };
  *session = 0;
  if (buf == NULL || len < kSessionOffset + 8) return 0;
  uint64_t bits = 0;
  for (int i = 0; i < 8; ++i) bits = (bits << 8) | buf[kSessionOffset + i];
  *session = (int64_t)bits;
  return 1;
}

/* ---- sealed codecs ---- */

#define UVMS_DEFINE_ENCODE(T)                                             \
  int T##_encode_sealed(const T *msg, uint8_t *buf, int capacity) {      \
    T tmp = *msg;                                                        \
    tmp.crc32 = 0;                                                       \
    const int n = T##_encode(buf, 0, capacity, &tmp);                    \
    if (n < 4) return n < 0 ? n : -1;                                    \
    uvms_crc_seal(buf, n);                                               \
    return n;                                                            \
  }
#define UVMS_DEFINE_CODEC(T)                                              \
  UVMS_DEFINE_ENCODE(T)                                                  \
  int T##_decode_checked(const uint8_t *buf, int len, T *out) {          \
    memset(out, 0, sizeof *out);                                         \
    if (buf == NULL || len <= 0) return -1;                              \
    const int n = T##_decode(buf, 0, len, out);                          \
    if (n != len) {                                                      \
      memset(out, 0, sizeof *out);                                       \
      return -1;                                                         \
    }                                                                    \
    if (!uvms_crc_check(buf, len)) {                                     \
      memset(out, 0, sizeof *out);                                       \
      return -2;                                                         \
    }                                                                    \
    return n;                                                            \
  }
UVMS_DEFINE_CODEC(uvms_sensors_t)
UVMS_DEFINE_CODEC(uvms_actuators_t)
UVMS_DEFINE_CODEC(uvms_telemetry_t)
UVMS_DEFINE_CODEC(uvms_run_status_t)
UVMS_DEFINE_CODEC(uvms_controller_config_t)
UVMS_DEFINE_ENCODE(uvms_truth_t)
UVMS_DEFINE_ENCODE(uvms_scene_t)

/* ---- configuration: generated from the table (sil/msg/config_table.h) ---- */

static void put_reals(double *dst, const uvms_real_t *src, size_t n) {
  for (size_t i = 0; i < n; ++i) dst[i] = src[i];
}

/* One row of the table -> the message field, by the row's map kind. The element counts of the
 * firmware field and the message field are checked at compile time. */
#define TO_MSG_ROW_(map, shape, fw, lcm, ...) TO_MSG_##map(shape, fw, lcm)
#define TO_MSG_REAL(shape, fw, lcm)                                                       \
  _Static_assert(sizeof cfg->fw / sizeof(uvms_real_t) == sizeof m->lcm / sizeof(double), \
                 #fw " and " #lcm " differ in size");                                     \
  put_reals((double *)(void *)&m->lcm, (const uvms_real_t *)(const void *)&cfg->fw,       \
            sizeof m->lcm / sizeof(double));
#define TO_MSG_LINK(shape, fw, lcm)                                                          \
  _Static_assert(sizeof m->lcm / sizeof m->lcm[0] == UVMS_MAX_JOINTS &&                      \
                     sizeof cfg->arm.link[0].fw / sizeof(uvms_real_t) ==                      \
                         sizeof m->lcm[0] / sizeof(double),                                  \
                 "arm.link[]." #fw " and " #lcm " differ in size");                          \
  for (size_t i_ = 0; i_ < (size_t)UVMS_MAX_JOINTS; ++i_)                                    \
    put_reals((double *)(void *)&m->lcm[i_], (const uvms_real_t *)(const void *)&cfg->arm.link[i_].fw, \
              sizeof m->lcm[0] / sizeof(double));
#define TO_MSG_THR(shape, fw, lcm)                                                           \
  _Static_assert(sizeof m->lcm / sizeof m->lcm[0] == UVMS_MAX_THRUSTERS,                     \
                 "thruster[]." #fw " and " #lcm " differ in size");                          \
  for (size_t j_ = 0; j_ < (size_t)UVMS_MAX_THRUSTERS; ++j_) m->lcm[j_] = cfg->thruster[j_].fw;
#define TO_MSG_COUNT(shape, fw, lcm) m->lcm = (__typeof__(m->lcm))cfg->fw;
#define TO_MSG_FLAG(shape, fw, lcm) m->lcm = (__typeof__(m->lcm))(cfg->fw != 0);
#define TO_MSG_SWITCH(shape, fw, lcm) m->lcm = (__typeof__(m->lcm))cfg->fw;
#define TO_MSG_ENUM(shape, fw, lcm) m->lcm = (__typeof__(m->lcm))cfg->fw;
#define TO_MSG_U32(shape, fw, lcm) m->lcm = (__typeof__(m->lcm))cfg->fw;
#define TO_MSG_NONE(shape, fw, lcm)

void uvms_config_to_msg(const uvms_ctrl_config_t *cfg, uvms_controller_config_t *m) {
  memset(m, 0, sizeof *m);
  m->utime = 0;
  m->tick = -1;
  UVMS_CONFIG_TABLE(TO_MSG_ROW_)
}

#define UVMS_CONFIG_MAP_FN uvms_config_from_msg
#define UVMS_CONFIG_MAP_MSG_T uvms_controller_config_t
#define UVMS_CONFIG_MAP_REAL_T double
#include "msg/config_from_msg.inc"

/* ---- per-tick records: generated from the table (sil/msg/record_table.h) ---- */

static void get_reals(uvms_real_t *dst, const double *src, size_t n) {
  for (size_t i = 0; i < n; ++i) dst[i] = (uvms_real_t)src[i];
}

/* The same-named real field between a message (double) and a firmware struct (uvms_real_t);
 * the element counts of both sides are checked at compile time. */
#define SAME_SHAPE_(msg, fw, name)                                                           \
  _Static_assert(sizeof(msg)->name / sizeof(double) == sizeof(fw)->name / sizeof(uvms_real_t), \
                 #name ": the message and the firmware differ in size");
#define MSG_TO_FW_(fw, msg, name)                                                            \
  SAME_SHAPE_(msg, fw, name)                                                                 \
  get_reals((uvms_real_t *)(void *)&(fw)->name, (const double *)(const void *)&(msg)->name,  \
            sizeof(msg)->name / sizeof(double));
#define FW_TO_MSG_(msg, fw, name)                                                            \
  SAME_SHAPE_(msg, fw, name)                                                                 \
  put_reals((double *)(void *)&(msg)->name, (const uvms_real_t *)(const void *)&(fw)->name,  \
            sizeof(msg)->name / sizeof(double));

void uvms_sensors_from_msg(const uvms_sensors_t *m, uvms_ctrl_sensors_t *s) {
  memset(s, 0, sizeof *s);
  s->tick = m->tick;
  s->time_s = (uvms_real_t)((double)m->utime * 1e-6);
#define SENSOR_FROM_MSG_(name, dims, unit, doc) MSG_TO_FW_(s, m, name)
  UVMS_SENSOR_FIELDS(SENSOR_FROM_MSG_)
#undef SENSOR_FROM_MSG_
  s->thruster_usable_mask = (uint32_t)m->thruster_usable_mask;
}

void uvms_outputs_to_msgs(const uvms_sensors_t *in, int32_t status,
                          const uvms_ctrl_command_t *cmd, const uvms_ctrl_telemetry_t *tlm,
                          uvms_actuators_t *act, uvms_telemetry_t *tel) {
  memset(act, 0, sizeof *act);
  memset(tel, 0, sizeof *tel);
  act->utime = tel->utime = in->utime;
  act->tick = tel->tick = in->tick;
  act->session = tel->session = in->session;
  act->status = tel->status = status;
  act->flags = tel->flags = (int32_t)tlm->flags;
#define ACTUATOR_TO_MSG_(name, dims, unit, doc) FW_TO_MSG_(act, cmd, name)
#define REFERENCE_TO_MSG_(name, dims, unit, doc) FW_TO_MSG_(tel, cmd, name)
#define TELEMETRY_TO_MSG_(name, dims, unit, doc) FW_TO_MSG_(tel, tlm, name)
  UVMS_ACTUATOR_FIELDS(ACTUATOR_TO_MSG_)
  UVMS_REFERENCE_FIELDS(REFERENCE_TO_MSG_)
  UVMS_TELEMETRY_FIELDS(TELEMETRY_TO_MSG_)
#undef ACTUATOR_TO_MSG_
#undef REFERENCE_TO_MSG_
#undef TELEMETRY_TO_MSG_
  tel->uncontrollable_axes = (int32_t)tlm->uncontrollable_axes;
  tel->alloc_rank = tlm->alloc_rank;
  tel->sensor_rejected_ticks = (int32_t)tlm->sensor_rejected_ticks;
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

const char *uvms_actuators_first_difference(const uvms_actuators_t *a, const uvms_actuators_t *b,
                                            int *index) {
  int dummy;
  if (index == NULL) index = &dummy;
  *index = -1;
  if (a->utime != b->utime) return "utime";
  if (a->tick != b->tick) return "tick";
  if (a->session != b->session) return "session";
  /* field by field in the table's order, element by element */
#define FIRST_DIFFERENCE_(name, dims, unit, doc)                                   \
  for (size_t i_ = 0; i_ < sizeof a->name / sizeof(double); ++i_) {               \
    if (!same_bits(((const double *)(const void *)&a->name)[i_],                  \
                   ((const double *)(const void *)&b->name)[i_])) {               \
      *index = (int)i_;                                                           \
      return #name;                                                               \
    }                                                                             \
  }
  UVMS_ACTUATOR_FIELDS(FIRST_DIFFERENCE_)
#undef FIRST_DIFFERENCE_
  if (a->status != b->status) return "status";
  if (a->flags != b->flags) return "flags";
  return NULL;
}
