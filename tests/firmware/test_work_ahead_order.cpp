// SPDX-License-Identifier: Apache-2.0
// UVMS_FW_WORK_AHEAD (firmware/src/fw_fast.h): on a 64-bit host three loops of the tick take
// their independent, long-latency work ahead of the chained work that uses it (the joints'
// sines and cosines in the forward kinematics, the links' own loads in the Newton–Euler inward
// pass, the thrusters' desired speeds in the thruster loops); the Cortex-M4F keeps one order.
// The two orders must give the same bits: this test links the library (built as the host
// builds it) and kinematics.c, dynamics.c and controller.c compiled a second time as the
// target orders them (tests/firmware/CMakeLists.txt: UVMS_FW_WORK_AHEAD=0, their functions
// renamed *_in_order), and compares every output of both, bit for bit.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <random>

#include "fw_test_util.hpp"
#include "sensor_sequence.h"
#include "uvms/controller.h"
#include "uvms/dynamics.h"
#include "uvms/kinematics.h"

extern "C" {
uvms_status_t uvms_arm_fk_in_order(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                                   const uvms_real_t r0_m[3], const uvms_real_t R0[9],
                                   const uvms_real_t *q_rad);
uvms_status_t uvms_arm_rnea_in_order(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                                     const uvms_base_state_t *base, const uvms_fluid_t *fluid,
                                     const uvms_real_t *q_rad, const uvms_real_t *qd_rad_s,
                                     const uvms_real_t *qdd_rad_s2);
uvms_status_t uvms_ctrl_config_paper_in_order(uvms_ctrl_config_t *cfg, int case_number);
uvms_status_t uvms_ctrl_init_in_order(uvms_ctrl_t *ctrl, const uvms_ctrl_config_t *cfg);
uvms_status_t uvms_ctrl_step_in_order(uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *sensors,
                                      uvms_ctrl_command_t *cmd, uvms_ctrl_telemetry_t *tlm);
}

using namespace fwtest;

namespace {

void RandomRotation(std::mt19937 &rng, uvms_real_t R[9]) {
  std::normal_distribution<double> g(0.0, 1.0);
  uvms_real_t q[4];
  for (auto &c : q) c = uvms_real_t(g(rng));
  REQUIRE(uvms_quat_to_rot(q, R) == UVMS_OK);
}

void RandomVector(std::mt19937 &rng, double scale, uvms_real_t v[3]) {
  std::uniform_real_distribution<double> u(-scale, scale);
  for (int k = 0; k < 3; ++k) v[k] = uvms_real_t(u(rng));
}

// The paper's arm with general links, a turned mount, full inertia tensors and, on two links,
// their own added mass: every branch of the kinematics and of the inward pass.
uvms_arm_params_t GeneralParams(std::mt19937 &rng) {
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
  p.link[1].inertia_products_kg_m2[0] = uvms_real_t(0.001);
  p.link[3].inertia_products_kg_m2[2] = uvms_real_t(-0.0005);
  for (int k = 0; k < 6; ++k) {
    p.link[2].added_mass_kg[k] = uvms_real_t(0.5 + 0.1 * k);
    p.link[5].added_mass_kg[k] = uvms_real_t(0.2);
  }
  return p;
}

void CheckFkSameBits(const uvms_arm_model_t &m, std::mt19937 &rng) {
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
    REQUIRE(uvms_arm_fk_in_order(&m, &b, r0, R0, q) == UVMS_OK);
    INFO("trial " << trial);
    CHECK(std::memcmp(&a, &b, sizeof a) == 0);
  }
}

// The whole Newton–Euler (forward pass, then the inward pass whose order differs) at random
// states, rates and accelerations, in a fluid with and without the angle of attack's drag
// factor, with a flow, and in vacuum.
void CheckRneaSameBits(const uvms_arm_model_t &m, std::mt19937 &rng) {
  std::uniform_real_distribution<double> angle(-7.0, 7.0), rate(-2.0, 2.0), acc(-5.0, 5.0);
  static uvms_arm_data_t a, b;
  const double densities[] = {1000.0, 1025.0, 0.0};
  for (int trial = 0; trial < 300; ++trial) {
    uvms_real_t q[UVMS_MAX_JOINTS], qd[UVMS_MAX_JOINTS], qdd[UVMS_MAX_JOINTS];
    for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) {
      q[j] = uvms_real_t(angle(rng));
      qd[j] = uvms_real_t(rate(rng));
      qdd[j] = uvms_real_t(acc(rng));
    }
    uvms_base_state_t base{};
    RandomVector(rng, 20.0, base.position_m);
    RandomRotation(rng, base.R0);
    RandomVector(rng, 1.0, base.velocity_m_s);
    RandomVector(rng, 0.5, base.omega_rad_s);
    RandomVector(rng, 2.0, base.accel_m_s2);
    RandomVector(rng, 1.0, base.alpha_rad_s2);
    uvms_fluid_t fluid{};
    fluid.density_kg_m3 = uvms_real_t(densities[trial % 3]);
    RandomVector(rng, 0.5, fluid.flow_m_s);
    fluid.gravity_m_s2[2] = uvms_real_t((trial % 2) ? -9.81 : -1.315);
    fluid.angle_of_attack = (trial / 3) % 2;
    std::memset(&a, 0x5A, sizeof a);
    std::memset(&b, 0x5A, sizeof b);
    REQUIRE(uvms_arm_rnea(&m, &a, &base, &fluid, q, qd, qdd) == UVMS_OK);
    REQUIRE(uvms_arm_rnea_in_order(&m, &b, &base, &fluid, q, qd, qdd) == UVMS_OK);
    INFO("trial " << trial << ", density " << densities[trial % 3] << " kg/m³, angle of attack "
                  << fluid.angle_of_attack);
    CHECK(std::memcmp(&a, &b, sizeof a) == 0);
  }
}

struct TickPaths {
  int saturated = 0;  // ticks with a saturated voltage
  int fault[3] = {};  // ticks with a failed thruster loop: speed stage, drive stage, not ready
};

// Both instances' thruster loops made to fail in one of their stages, from inside (a test
// reaching into the instance): no motor density (the speed stage: UVMS_ERR_RANGE), an
// overflowing current gain of thruster 3 (the drive stage: UVMS_ERR_NONFINITE), the motors
// not ready (UVMS_ERR_STATE).
void Perturb(uvms_ctrl_t &c, int tick, const uvms_ctrl_t &reference) {
  c.motor.density_kg_m3 = (tick >= 1100 && tick < 1200) ? uvms_real_t(0.0)
                                                         : reference.motor.density_kg_m3;
  c.motor.coef[3].inv_km_A_Nm = (tick >= 1300 && tick < 1400)
                                    ? uvms_real_t(UVMS_REAL_IS_FLOAT ? 1e37 : 1e307)
                                    : reference.motor.coef[3].inv_km_A_Nm;
  c.motor.ready = (tick >= 1500 && tick < 1510) ? 0 : reference.motor.ready;
}

// Two controllers, one per order, over one case's 60 s sensor sequence: every command and
// telemetry record the same bytes. Thrusters 2 and 5 are reported unusable between ticks 300
// and 700, thrusters 0 and 1 have a voltage limit low enough to saturate now and then, and the
// loops fail in each of their stages (Perturb).
TickPaths CheckTicksSameBits(int case_number) {
  static uvms_ctrl_config_t cfg_a, cfg_b;
  static uvms_ctrl_t ca, cb;
  REQUIRE(uvms_ctrl_config_paper(&cfg_a, case_number) == UVMS_OK);
  REQUIRE(uvms_ctrl_config_paper_in_order(&cfg_b, case_number) == UVMS_OK);
  REQUIRE(std::memcmp(&cfg_a, &cfg_b, sizeof cfg_a) == 0);
  for (int j = 0; j < 2; ++j)
    cfg_a.thruster[j].voltage_limit_V = cfg_b.thruster[j].voltage_limit_V = uvms_real_t(0.05);
  REQUIRE(uvms_ctrl_init(&ca, &cfg_a) == UVMS_OK);
  REQUIRE(uvms_ctrl_init_in_order(&cb, &cfg_b) == UVMS_OK);
  static uvms_ctrl_t reference;
  reference = ca;  // the motor constants Perturb restores
  uvms_ctrl_sensors_t s;
  uvms_ctrl_command_t cmd_a, cmd_b;
  uvms_ctrl_telemetry_t tlm_a, tlm_b;
  TickPaths paths;
  int unusable_ticks = 0;
  for (int k = 0; k < 2000; ++k) {
    uvms_sensor_sequence(&cfg_a, k, &s);
    if (k >= 300 && k < 700) {
      s.thruster_usable_mask &= ~((1u << 2) | (1u << 5));
      ++unusable_ticks;
    }
    Perturb(ca, k, reference);
    Perturb(cb, k, reference);
    std::memset(&cmd_a, 0x7F, sizeof cmd_a);
    std::memset(&cmd_b, 0x7F, sizeof cmd_b);
    std::memset(&tlm_a, 0x7F, sizeof tlm_a);
    std::memset(&tlm_b, 0x7F, sizeof tlm_b);
    const uvms_status_t sa = uvms_ctrl_step(&ca, &s, &cmd_a, &tlm_a);
    const uvms_status_t sb = uvms_ctrl_step_in_order(&cb, &s, &cmd_b, &tlm_b);
    INFO("case " << case_number << ", tick " << k);
    REQUIRE(sa == sb);
    REQUIRE(std::memcmp(&cmd_a, &cmd_b, sizeof cmd_a) == 0);
    REQUIRE(std::memcmp(&tlm_a, &tlm_b, sizeof tlm_a) == 0);
    if (tlm_a.flags & UVMS_FLAG_VOLTAGE_SATURATED) ++paths.saturated;
    if (tlm_a.flags & UVMS_FLAG_MOTOR_FAULT)
      ++paths.fault[k < 1200 ? 0 : k < 1400 ? 1 : 2];
  }
  // The state the next tick starts from: the integrated current commands.
  CHECK(std::memcmp(ca.motor.current_cmd_A, cb.motor.current_cmd_A,
                    sizeof ca.motor.current_cmd_A) == 0);
  CHECK(unusable_ticks == 400);
  return paths;
}

}  // namespace

TEST_CASE("BothSineOrdersOfTheForwardKinematicsGiveTheSameBits", "[kinematics]") {
  std::mt19937 rng(2718);
  SECTION("the paper's arm") {
    const OwnedModel m = PaperModel();
    CheckFkSameBits(m, rng);
  }
  SECTION("general links, a turned mount, full inertia tensors") {
    const OwnedModel m(GeneralParams(rng));
    REQUIRE(m.placed != 0u);
    REQUIRE(m.base_rotated == 1);
    CheckFkSameBits(m, rng);
  }
}

TEST_CASE("BothOrdersOfTheInwardPassGiveTheSameBits", "[dynamics]") {
  std::mt19937 rng(3141);
  SECTION("the paper's arm") {
    const OwnedModel m = PaperModel();
    CheckRneaSameBits(m, rng);
  }
  SECTION("general links, full inertia tensors, links with their own added mass") {
    const OwnedModel m(GeneralParams(rng));
    REQUIRE(m.full_inertia != 0u);
    REQUIRE(m.own_added_mass != 0u);
    CheckRneaSameBits(m, rng);
  }
}

TEST_CASE("BothOrdersOfTheThrusterLoopsGiveTheSameTicks", "[controller]") {
  TickPaths all;
  for (int c = 1; c <= 8; ++c) {
    const TickPaths p = CheckTicksSameBits(c);
    all.saturated += p.saturated;
    for (int f = 0; f < 3; ++f) all.fault[f] += p.fault[f];
  }
  CHECK(all.saturated > 0);  // the drive stage's saturated branch was taken
  INFO("failed loops: speed stage " << all.fault[0] << ", drive stage " << all.fault[1]
                                    << ", not ready " << all.fault[2] << " ticks");
  CHECK(all.fault[0] > 0);  // and each way a loop fails
  CHECK(all.fault[1] > 0);
  CHECK(all.fault[2] > 0);
}
