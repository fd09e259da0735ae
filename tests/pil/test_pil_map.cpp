// SPDX-License-Identifier: Apache-2.0
// The PIL record mappings against the host float build's (built against the float firmware):
// the image configures and feeds the firmware bit for bit as sil/msg/codec.c does in float.
//  - config: msg -> record (host, sil/pil/pil_host.c) -> uvms_ctrl_config_t (target side,
//    sil/pil/pil_map.c) equals uvms_config_from_msg(msg), every byte, for all eight paper cases
//    and for rejected messages;
//  - sensors: msg -> record -> uvms_ctrl_sensors_t equals uvms_sensors_from_msg(msg);
//  - outputs: command/telemetry -> record -> command/telemetry is the identity;
//  - every field of the table of configuration fields (sil/msg/config_table.h), given a distinct
//    value, survives config -> message -> config -> record -> config in float.
#include <catch2/catch.hpp>

#include <cstring>
#include <random>

#include "../sil/config_fill.hpp"
#include "msg/codec.h"
#include "pil/pil_host.h"
#include "pil/pil_map.h"

static_assert(UVMS_REAL_IS_FLOAT, "this test links the float firmware");

namespace {

uvms_controller_config_t PaperMsg(int case_number) {
  uvms_ctrl_config_t cfg;
  REQUIRE(uvms_ctrl_config_paper(&cfg, case_number) == UVMS_OK);
  uvms_controller_config_t msg;
  uvms_config_to_msg(&cfg, &msg);
  return msg;
}

// A message whose doubles are not floats: the record must round them as codec.c does.
void Perturb(uvms_controller_config_t &m, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1e-9, 1e-9);
  for (int i = 0; i < 7; ++i) {
    m.link_alpha_rad[i] += u(rng);
    m.link_com_m[i][1] += u(rng);
    m.theta_final_rad[i] += u(rng);
  }
  for (int j = 0; j < 8; ++j) m.thruster_direction[j][2] += u(rng);
  m.added_mass_coeff[7] += u(rng);
  m.tick_s += u(rng);
  m.cart_max_joint_rate_rad_s += u(rng);
}

void CheckSameConfig(const uvms_controller_config_t &msg) {
  uvms_ctrl_config_t want, got;
  const int want_rc = uvms_config_from_msg(&msg, &want);
  pil_config_rec_t rec;
  pil_config_rec_from_msg(&msg, &rec);
  const int got_rc = pil_config_from_rec(&rec, &got);
  CHECK(got_rc == want_rc);
  CHECK(std::memcmp(&want, &got, sizeof want) == 0);
}

}  // namespace

TEST_CASE("PilConfigMappingEqualsHostFloatMapping", "[pil]") {
  for (int c = 1; c <= 8; ++c) {
    INFO("case " << c);
    auto msg = PaperMsg(c);
    CheckSameConfig(msg);
    Perturb(msg, uint32_t(c));
    CheckSameConfig(msg);
  }
}

TEST_CASE("EveryConfigFieldWithADistinctValueSurvivesMessageAndRecordInFloat", "[pil]") {
  config_fill::CheckDistinctRoundTrip();  // with pil_config_from_rec: this is the float firmware
}

TEST_CASE("PilConfigMappingRejectsWhatTheHostRejects", "[pil]") {
  auto msg = PaperMsg(4);
  msg.num_joints = 8;
  CheckSameConfig(msg);
  msg = PaperMsg(4);
  msg.num_thrusters = 0;
  CheckSameConfig(msg);
  msg = PaperMsg(4);
  msg.traj_mode = 3;
  CheckSameConfig(msg);
  msg = PaperMsg(4);
  msg.position_reference = 2;
  CheckSameConfig(msg);
  msg = PaperMsg(4);
  msg.cart_reference = -1;
  CheckSameConfig(msg);
}

TEST_CASE("PilSensorsMappingEqualsHostFloatMapping", "[pil]") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int k = 0; k < 200; ++k) {
    uvms_sensors_t m{};
    m.tick = k;
    m.utime = int64_t(k) * 30000 + (k % 7);
    for (auto &v : m.position_m) v = u(rng);
    for (auto &v : m.quaternion_wxyz) v = u(rng);
    for (auto &v : m.velocity_m_s) v = u(rng);
    for (auto &v : m.angular_velocity_rad_s) v = u(rng);
    for (auto &v : m.joint_position_rad) v = u(rng);
    for (auto &v : m.joint_velocity_rad_s) v = u(rng);
    for (auto &v : m.motor_speed_rad_s) v = 100 * u(rng);
    for (auto &v : m.motor_current_A) v = u(rng);
    m.thruster_usable_mask = 0xFF ^ (k & 3);
    uvms_ctrl_sensors_t want, got;
    uvms_sensors_from_msg(&m, &want);
    pil_sensors_rec_t rec;
    pil_sensors_rec_from_msg(&m, &rec);
    pil_sensors_from_rec(&rec, &got);
    INFO("tick " << k);
    CHECK(std::memcmp(&want, &got, sizeof want) == 0);
  }
}

TEST_CASE("PilOutputRecordRoundTrips", "[pil]") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-50.0f, 50.0f);
  uvms_ctrl_command_t cmd{};
  uvms_ctrl_telemetry_t tlm{};
  auto fill = [&](float *p, size_t n) {
    for (size_t i = 0; i < n; ++i) p[i] = u(rng);
  };
  fill(reinterpret_cast<float *>(&cmd), sizeof cmd / sizeof(float));
  fill(tlm.force_ff_N, 3);
  fill(tlm.thrust_des_N, 8);
  fill(tlm.joint_torque_model_Nm, 7);
  fill(tlm.ee_estimate_m, 3);
  tlm.tick = 42;
  tlm.flags = 0x5A5;
  pil_output_rec_t rec;
  pil_output_to_rec(42, -3, &cmd, &tlm, &rec);
  CHECK(rec.tick == 42);
  CHECK(rec.status == -3);
  CHECK(rec.flags == 0x5A5u);
  uvms_ctrl_command_t cmd2;
  uvms_ctrl_telemetry_t tlm2;
  pil_output_from_rec(&rec, &cmd2, &tlm2);
  CHECK(std::memcmp(&cmd, &cmd2, sizeof cmd) == 0);
  CHECK(std::memcmp(tlm.force_ff_N, tlm2.force_ff_N, sizeof tlm.force_ff_N) == 0);
  CHECK(std::memcmp(tlm.thrust_des_N, tlm2.thrust_des_N, sizeof tlm.thrust_des_N) == 0);
  CHECK(std::memcmp(tlm.joint_torque_model_Nm, tlm2.joint_torque_model_Nm,
                    sizeof tlm.joint_torque_model_Nm) == 0);
  CHECK(std::memcmp(tlm.ee_estimate_m, tlm2.ee_estimate_m, sizeof tlm.ee_estimate_m) == 0);
  CHECK(tlm2.status == -3);
  CHECK(tlm2.flags == 0x5A5u);
}
