// SPDX-License-Identifier: Apache-2.0
// fuzz_lcm_decode: arbitrary bytes through every decoder the harness runs on a received
// message: lcm-gen's C decoder (uvms_<type>_decode, what runs first), the checked decoder
// (sil/msg/codec.h: fingerprint, length, CRC), and lcm-gen's C++ decoder (uvms::<type>::decode)
// as a second opinion, for the five types C or C++ code of the project decodes: sensors_t,
// actuators_t, telemetry_t, run_status_t, controller_config_t. (truth_t is decoded only by the
// Python tools; tests/fuzz/README.md says why its C/C++ decoders are left out.)
//
// Input: byte 0 picks the type (b % 5); when bit 7 is set the last 4 bytes of the rest are
// overwritten by their CRC first (uvms_crc_seal), so that inputs reach past the CRC gate. The
// rest, exactly as long as it is, is the message.
//
// Properties:
//   - the C and C++ decoders agree: same length consumed or both fail;
//   - a decoded message re-encodes (C and C++) to exactly the bytes it was decoded from;
//   - the checked decoder accepts exactly the messages that decode to the whole buffer and
//     carry a valid CRC, and then re-sealing gives the input back.
#include <cstring>
#include <vector>

#include "msg/codec.h"
#include "fuzz_support.h"
#include "uvms/actuators_t.hpp"
#include "uvms/controller_config_t.hpp"
#include "uvms/run_status_t.hpp"
#include "uvms/sensors_t.hpp"
#include "uvms/telemetry_t.hpp"

namespace {

template <typename C, typename Cpp>
struct Codec {
  const char *name;
  int (*c_decode)(const void *, int, int, C *);
  int (*c_encode)(void *, int, int, const C *);
  int (*checked)(const uint8_t *, int, C *);
  int (*sealed)(const C *, uint8_t *, int);
};

template <typename C, typename Cpp>
void Check(const Codec<C, Cpp> &k, const uint8_t *buf, int len) {
  C c;
  std::memset(&c, 0, sizeof c);
  const int n_c = k.c_decode(buf, 0, len, &c);
  Cpp cpp;
  const int n_cpp = cpp.decode(buf, 0, len);
  FUZZ_REQUIRE(n_c == n_cpp || (n_c < 0 && n_cpp < 0), "%s: C decoder %d, C++ decoder %d",
               k.name, n_c, n_cpp);
  FUZZ_REQUIRE(n_c <= len, "%s: decoded %d of %d bytes", k.name, n_c, len);
  if (n_c >= 0) {
    std::vector<uint8_t> again(static_cast<size_t>(n_c) + 16);
    const int e_c = k.c_encode(again.data(), 0, int(again.size()), &c);
    FUZZ_REQUIRE(e_c == n_c && std::memcmp(again.data(), buf, size_t(n_c)) == 0,
                 "%s: C re-encoding differs (%d of %d bytes)", k.name, e_c, n_c);
    const int e_cpp = cpp.encode(again.data(), 0, int(again.size()));
    FUZZ_REQUIRE(e_cpp == n_c && std::memcmp(again.data(), buf, size_t(n_c)) == 0,
                 "%s: C++ re-encoding differs (%d of %d bytes)", k.name, e_cpp, n_c);
  }
  C chk;
  std::memset(&chk, 0, sizeof chk);
  const int n_chk = k.checked(buf, len, &chk);
  const bool should = n_c == len && uvms_crc_check(buf, len) == 1;
  FUZZ_REQUIRE((n_chk == len) == should && (n_chk == len || n_chk == -1 || n_chk == -2),
               "%s: checked decoder %d on %d bytes (plain decoder %d, CRC %d)", k.name, n_chk,
               len, n_c, uvms_crc_check(buf, len));
  if (n_chk == len) {
    std::vector<uint8_t> sealed(static_cast<size_t>(len) + 16);
    const int e = k.sealed(&chk, sealed.data(), int(sealed.size()));
    FUZZ_REQUIRE(e == len && std::memcmp(sealed.data(), buf, size_t(len)) == 0,
                 "%s: sealed re-encoding differs (%d of %d bytes)", k.name, e, len);
  }
}

#define UVMS_FUZZ_CODEC(T) \
  Codec<uvms_##T, uvms::T> { #T, uvms_##T##_decode, uvms_##T##_encode, uvms_##T##_decode_checked, \
                             uvms_##T##_encode_sealed }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1 || size - 1 > size_t(UVMS_MAX_MSG_BYTES) * 4) return 0;
  const uint8_t sel = data[0];
  const int len = int(size - 1);
  // An exact-size heap copy: AddressSanitizer then sees any read past the message.
  std::vector<uint8_t> msg(data + 1, data + size);
  if ((sel & 0x80) != 0 && len >= 4) uvms_crc_seal(msg.data(), len);
  const uint8_t *buf = msg.empty() ? nullptr : msg.data();
  switch (sel % 5) {
    case 0: Check(UVMS_FUZZ_CODEC(sensors_t), buf, len); break;
    case 1: Check(UVMS_FUZZ_CODEC(actuators_t), buf, len); break;
    case 2: Check(UVMS_FUZZ_CODEC(telemetry_t), buf, len); break;
    case 3: Check(UVMS_FUZZ_CODEC(run_status_t), buf, len); break;
    default: Check(UVMS_FUZZ_CODEC(controller_config_t), buf, len); break;
  }
  return 0;
}
