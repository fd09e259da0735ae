// SPDX-License-Identifier: Apache-2.0
// UVMS_FW_SINCOS_AHEAD (firmware/src/fw_fast.h): the forward kinematics takes the joints' sines
// and cosines before its loop over the links on a 64-bit host, and one pair per link on the
// Cortex-M4F. The two orders must give the same bits: this test links the library's
// uvms_arm_fk (built as the host builds it) and kinematics.c compiled a second time as the
// target orders it (tests/firmware/CMakeLists.txt: UVMS_FW_SINCOS_AHEAD=0, its functions
// renamed *_per_link), and compares every output of both, bit for bit.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "fw_test_util.hpp"
#include "uvms/kinematics.h"

extern "C" uvms_status_t uvms_arm_fk_per_link(const uvms_arm_model_t *model,
                                              uvms_arm_data_t *data, const uvms_real_t r0_m[3],
                                              const uvms_real_t R0[9], const uvms_real_t *q_rad);

using namespace fwtest;

namespace {

void RandomRotation(std::mt19937 &rng, uvms_real_t R[9]) {
  std::normal_distribution<double> g(0.0, 1.0);
  uvms_real_t q[4];
  for (auto &c : q) c = uvms_real_t(g(rng));
  REQUIRE(uvms_quat_to_rot(q, R) == UVMS_OK);
}

void CheckSameBits(const uvms_arm_model_t &m, std::mt19937 &rng) {
  // Angles over the joints' whole range ±2π and beyond (the sine's reduction branches), the
  // vehicle anywhere.
  std::uniform_real_distribution<double> angle(-7.0, 7.0), pos(-50.0, 50.0);
  static uvms_arm_data_t a, b;
  for (int trial = 0; trial < 200; ++trial) {
    uvms_real_t q[UVMS_MAX_JOINTS], r0[3], R0[9];
    for (auto &x : q) x = uvms_real_t(angle(rng));
    for (auto &x : r0) x = uvms_real_t(pos(rng));
    RandomRotation(rng, R0);
    std::memset(&a, 0x5A, sizeof a);  // both start from the same junk
    std::memset(&b, 0x5A, sizeof b);
    REQUIRE(uvms_arm_fk(&m, &a, r0, R0, q) == UVMS_OK);
    REQUIRE(uvms_arm_fk_per_link(&m, &b, r0, R0, q) == UVMS_OK);
    INFO("trial " << trial);
    CHECK(std::memcmp(&a, &b, sizeof a) == 0);
  }
}

}  // namespace

TEST_CASE("BothSineOrdersOfTheForwardKinematicsGiveTheSameBits", "[kinematics]") {
  std::mt19937 rng(2718);
  SECTION("the paper's arm") {
    const OwnedModel m = PaperModel();
    CheckSameBits(m, rng);
  }
  SECTION("general links, a turned mount, full inertia tensors") {
    uvms_arm_params_t p;
    uvms_arm_params_paper(&p);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    for (size_t i = 0; i < 7; i += 2) {
      for (int k = 0; k < 3; ++k) {
        p.link[i].placement_m[k] = uvms_real_t(0.1 * u(rng));
        p.link[i].placement_rotvec_rad[k] = uvms_real_t(1.5 * u(rng));
      }
    }
    p.vehicle.base_rotvec_rad[1] = uvms_real_t(M_PI / 2);
    const OwnedModel m(p);
    REQUIRE(m.placed != 0u);
    REQUIRE(m.base_rotated == 1);
    CheckSameBits(m, rng);
  }
}
