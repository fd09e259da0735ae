// SPDX-License-Identifier: Apache-2.0
// config_fill.hpp: a firmware configuration whose every field of the table of configuration
// fields (sil/msg/config_table.h) has a distinct value, and checks that a controller_config_t
// message and a PIL record carry exactly those values (shared by sil.config_table and
// pil.map, so that the round trip runs in double and in float).
//
// Values: reals 100·r + e + 0.25 (r = row index, e = element index; exact in float and
// double); counts 1 + r mod max; switches 2 + r (int8); enums their largest value; flags 1;
// the hold count 1 + r. A field that one direction of a mapping drops comes back as 0.
#pragma once

#include <catch2/catch.hpp>

#include <cstddef>
#include <cstring>

#include "msg/codec.h"
#include "msg/config_table.h"
#include "pil/pil_host.h"
#include "pil/pil_protocol.h"
#if UVMS_REAL_IS_FLOAT
#include "pil/pil_map.h"  // the record -> configuration leg is the float image's code
#endif

namespace config_fill {

inline double Distinct(int row, std::size_t element) {
  return 100.0 * row + static_cast<double>(element) + 0.25;
}

// ---- the configuration --------------------------------------------------------------------

#define CONFIG_FILL_ROW_(map, shape, fw, lcm, ...) \
  ++row;                                           \
  CONFIG_FILL_##map(shape, fw, lcm)
#define CONFIG_FILL_REAL(shape, fw, lcm)                                            \
  {                                                                                 \
    auto *p = reinterpret_cast<uvms_real_t *>(&cfg->fw);                            \
    for (std::size_t e = 0; e < sizeof cfg->fw / sizeof(uvms_real_t); ++e)          \
      p[e] = static_cast<uvms_real_t>(Distinct(row, e));                            \
  }
#define CONFIG_FILL_LINK(shape, fw, lcm)                                            \
  {                                                                                 \
    const std::size_t n = sizeof cfg->arm.link[0].fw / sizeof(uvms_real_t);         \
    for (std::size_t i = 0; i < UVMS_MAX_JOINTS; ++i) {                             \
      auto *p = reinterpret_cast<uvms_real_t *>(&cfg->arm.link[i].fw);              \
      for (std::size_t k = 0; k < n; ++k)                                           \
        p[k] = static_cast<uvms_real_t>(Distinct(row, i * n + k));                  \
    }                                                                               \
  }
#define CONFIG_FILL_THR(shape, fw, lcm)                                             \
  for (std::size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j)                              \
    cfg->thruster[j].fw = static_cast<uvms_real_t>(Distinct(row, j));
#define CONFIG_FILL_COUNT(shape, fw, lcm) cfg->fw = 1 + static_cast<std::size_t>(row) % (shape);
#define CONFIG_FILL_FLAG(shape, fw, lcm) cfg->fw = 1;
#define CONFIG_FILL_SWITCH(shape, fw, lcm) cfg->fw = 2 + row;
#define CONFIG_FILL_ENUM(shape, fw, lcm) cfg->fw = shape;
#define CONFIG_FILL_U32(shape, fw, lcm) cfg->fw = static_cast<uint32_t>(1 + row);
#define CONFIG_FILL_NONE(shape, fw, lcm)

/// Every field of the table a distinct value; everything else (padding included) zero.
inline void FillDistinct(uvms_ctrl_config_t *cfg) {
  std::memset(cfg, 0, sizeof *cfg);
  int row = 0;
  UVMS_CONFIG_TABLE(CONFIG_FILL_ROW_)
}

// ---- the message or the record ------------------------------------------------------------

#define WIRE_CHECK_ROW_(map, shape, fw, lcm, ...) \
  ++row;                                          \
  WIRE_CHECK_##map(shape, fw, lcm)
#define WIRE_CHECK_REALS_(lcm, expected)                                  \
  {                                                                       \
    INFO(#lcm);                                                           \
    const auto *p = reinterpret_cast<const Real *>(&m.lcm);               \
    for (std::size_t e = 0; e < sizeof m.lcm / sizeof(Real); ++e)         \
      CHECK(p[e] == static_cast<Real>(expected));                         \
  }
#define WIRE_CHECK_REAL(shape, fw, lcm) WIRE_CHECK_REALS_(lcm, Distinct(row, e))
#define WIRE_CHECK_LINK(shape, fw, lcm) WIRE_CHECK_REALS_(lcm, Distinct(row, e))
#define WIRE_CHECK_THR(shape, fw, lcm) WIRE_CHECK_REALS_(lcm, Distinct(row, e))
#define WIRE_CHECK_INT_(lcm, expected) \
  {                                    \
    INFO(#lcm);                        \
    CHECK(m.lcm == (expected));        \
  }
#define WIRE_CHECK_COUNT(shape, fw, lcm) WIRE_CHECK_INT_(lcm, 1 + row % static_cast<int>(shape))
#define WIRE_CHECK_FLAG(shape, fw, lcm) WIRE_CHECK_INT_(lcm, 1)
#define WIRE_CHECK_SWITCH(shape, fw, lcm) WIRE_CHECK_INT_(lcm, 2 + row)
#define WIRE_CHECK_ENUM(shape, fw, lcm) WIRE_CHECK_INT_(lcm, static_cast<int>(shape))
#define WIRE_CHECK_U32(shape, fw, lcm) WIRE_CHECK_INT_(lcm, 1 + row)
#define WIRE_CHECK_NONE(shape, fw, lcm)

/// Every field of a controller_config_t (Real = double) or a pil_config_rec_t (Real = float)
/// holds the value FillDistinct gave its row.
template <class Real, class Wire>
void CheckDistinct(const Wire &m) {
  int row = 0;
  UVMS_CONFIG_TABLE(WIRE_CHECK_ROW_)
}

/// Bytes of the encoded controller_config_t that the table's fields account for: its LCM
/// fingerprint (8), utime and tick (8 + 8), crc32 (4) and every row's field. Equal to the
/// encoded size only if every field of lcmtypes/controller_config_t.lcm has a row.
inline std::size_t EncodedBytesOfTheTable() {
  uvms_controller_config_t m;
  std::size_t bytes = 8 + sizeof m.utime + sizeof m.tick + sizeof m.session + sizeof m.crc32;
#define CONFIG_BYTES_ROW_(map, shape, fw, lcm, ...) CONFIG_BYTES_##map(lcm)
#define CONFIG_BYTES_FIELD_(lcm) bytes += sizeof m.lcm;
#define CONFIG_BYTES_REAL CONFIG_BYTES_FIELD_
#define CONFIG_BYTES_LINK CONFIG_BYTES_FIELD_
#define CONFIG_BYTES_THR CONFIG_BYTES_FIELD_
#define CONFIG_BYTES_COUNT CONFIG_BYTES_FIELD_
#define CONFIG_BYTES_FLAG CONFIG_BYTES_FIELD_
#define CONFIG_BYTES_SWITCH CONFIG_BYTES_FIELD_
#define CONFIG_BYTES_ENUM CONFIG_BYTES_FIELD_
#define CONFIG_BYTES_U32 CONFIG_BYTES_FIELD_
#define CONFIG_BYTES_NONE(lcm)
  UVMS_CONFIG_TABLE(CONFIG_BYTES_ROW_)
  return bytes;
}

/// The byte offset where two configurations first differ (-1: identical).
inline long FirstDifference(const uvms_ctrl_config_t &a, const uvms_ctrl_config_t &b) {
  const auto *x = reinterpret_cast<const unsigned char *>(&a);
  const auto *y = reinterpret_cast<const unsigned char *>(&b);
  for (std::size_t i = 0; i < sizeof a; ++i)
    if (x[i] != y[i]) return static_cast<long>(i);
  return -1;
}

/// FillDistinct's configuration -> message (every field checked) -> encoded bytes -> message
/// -> configuration (equal byte for byte) -> PIL record (every field checked) and, with a
/// float firmware, -> configuration again (equal byte for byte).
inline void CheckDistinctRoundTrip() {
  uvms_ctrl_config_t cfg;
  FillDistinct(&cfg);
  uvms_controller_config_t msg;
  uvms_config_to_msg(&cfg, &msg);
  CheckDistinct<double>(msg);
  uint8_t buf[UVMS_MAX_MSG_BYTES];
  const int n = uvms_controller_config_t_encode_sealed(&msg, buf, int(sizeof buf));
  REQUIRE(n > 0);
  uvms_controller_config_t decoded;
  REQUIRE(uvms_controller_config_t_decode_checked(buf, n, &decoded) == n);
  uvms_ctrl_config_t back;
  REQUIRE(uvms_config_from_msg(&decoded, &back) == 0);
  CHECK(FirstDifference(cfg, back) == -1);
  pil_config_rec_t rec;
  pil_config_rec_from_msg(&decoded, &rec);
  CheckDistinct<float>(rec);
#if UVMS_REAL_IS_FLOAT
  uvms_ctrl_config_t from_rec;
  REQUIRE(pil_config_from_rec(&rec, &from_rec) == 0);
  CHECK(FirstDifference(cfg, from_rec) == -1);
#endif
}

}  // namespace config_fill
