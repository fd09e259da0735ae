// SPDX-License-Identifier: Apache-2.0
// Controller: configuration validation (one specific status and field per problem), Table X
// switches, safe outputs on bad sensors, and the consistency of one tick's outputs with the
// modules it composes (allocation reproduces the desired wrench, estimates match kinematics).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <type_traits>

#include "fw_test_util.hpp"
#include "uvms/controller.h"
#include "uvms/feedforward.h"
#include "uvms/kinematics.h"
#include "uvms/linalg.h"

using namespace fwtest;

namespace {

uvms_ctrl_sensors_t StartSensors(const uvms_ctrl_config_t &cfg) {
  uvms_ctrl_sensors_t s;
  std::memset(&s, 0, sizeof s);
  s.quaternion_wxyz[0] = 1;
  for (int j = 0; j < 7; ++j) s.joint_position_rad[j] = cfg.theta_start_rad[j];
  s.thruster_usable_mask = 0xFF;
  return s;
}

// StartSensors one tick before MidRunSensors(cfg, 1, 20.0): record times must match their
// ticks (TIME_IMPLAUSIBLE), so a first tick followed by mid-run ones is at t = 19.97 s.
uvms_ctrl_sensors_t StartSensorsBeforeMidRun(const uvms_ctrl_config_t &cfg) {
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  s.time_s = uvms_real_t(20.0 - 0.03);
  return s;
}

bool AllFinite(const uvms_ctrl_command_t &c) {
  for (double v : c.motor_voltage_V) if (!std::isfinite(v)) return false;
  for (double v : c.joint_acceleration_rad_s2) if (!std::isfinite(v)) return false;
  return true;
}

// Case IV with a Cartesian line along −x (reachable from θI; +x is not, see test_trajectory).
uvms_ctrl_config_t CartesianCaseFour() {
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  cfg.traj_mode = UVMS_TRAJ_CARTESIAN_LINE;
  cfg.cart.direction[0] = -1;
  return cfg;
}

}  // namespace

TEST_CASE("PaperConfigurationInitialisesForAllEightCases", "[controller]") {
  static uvms_ctrl_t ctrl;
  for (int c = 1; c <= 8; ++c) {
    uvms_ctrl_config_t cfg;
    REQUIRE(uvms_ctrl_config_paper(&cfg, c) == UVMS_OK);
    CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
    CHECK(ctrl.ready == 1);
    CHECK(ctrl.config_error == UVMS_CFG_OK);
  }
  uvms_ctrl_config_t cfg;
  CHECK(uvms_ctrl_config_paper(&cfg, 9) == UVMS_ERR_RANGE);
}

TEST_CASE("TableXSwitchesMatchThePaper", "[controller]") {
  // case: attitude, barycenter?, feedforward, feedback (SPEC §9 table)
  const int want[8][4] = {{0, 0, 0, 0}, {1, 1, 0, 0}, {1, 1, 1, 0}, {1, 0, 1, 1},
                          {1, 0, 0, 1}, {1, 0, 1, 0}, {1, 1, 1, 1}, {1, 1, 0, 1}};
  for (int c = 1; c <= 8; ++c) {
    uvms_switches_t sw;
    REQUIRE(uvms_switches_case(c, &sw) == UVMS_OK);
    CHECK(sw.attitude_control == want[c - 1][0]);
    CHECK((sw.position_reference == UVMS_REF_BARYCENTER) == (want[c - 1][1] == 1));
    CHECK(sw.position_feedforward == want[c - 1][2]);
    CHECK(sw.position_feedback == want[c - 1][3]);
  }
}

TEST_CASE("InitNamesTheRejectedPartOfTheConfiguration", "[controller]") {
  static uvms_ctrl_t ctrl;
  struct Case {
    const char *what;
    uvms_cfg_field_t field;
    uvms_status_t status;
    void (*mutate)(uvms_ctrl_config_t &);
  };
  const Case cases[] = {
      {"negative link mass", UVMS_CFG_ARM, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.arm.link[2].mass_kg = -1; }},
      {"NaN vehicle volume", UVMS_CFG_ARM, UVMS_ERR_NONFINITE,
       [](uvms_ctrl_config_t &c) { c.arm.vehicle.volume_m3 = uvms_real_t(NAN); }},
      {"too many joints", UVMS_CFG_ARM, UVMS_ERR_SIZE,
       [](uvms_ctrl_config_t &c) { c.arm.num_joints = 9; }},
      {"zero model density", UVMS_CFG_FLUID, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.fluid.density_kg_m3 = 0; }},
      {"infinite gravity", UVMS_CFG_FLUID, UVMS_ERR_NONFINITE,
       [](uvms_ctrl_config_t &c) { c.fluid.gravity_m_s2[2] = uvms_real_t(INFINITY); }},
      {"NaN thruster position", UVMS_CFG_THRUSTER_GEOMETRY, UVMS_ERR_NONFINITE,
       [](uvms_ctrl_config_t &c) { c.thrusters.position_m[3][1] = uvms_real_t(NAN); }},
      {"all thrusters along x", UVMS_CFG_THRUSTER_RANK, UVMS_ERR_SINGULAR,
       [](uvms_ctrl_config_t &c) {
         for (auto &u : c.thrusters.direction) { u[0] = 1; u[1] = 0; u[2] = 0; }
       }},
      {"zero motor resistance", UVMS_CFG_THRUSTER_PARAMS, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.thruster[5].resistance_ohm = 0; }},
      {"negative attitude gain", UVMS_CFG_GAINS, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.gains.kpn_Nm_rad = -1; }},
      {"NaN position gain", UVMS_CFG_GAINS, UVMS_ERR_NONFINITE,
       [](uvms_ctrl_config_t &c) { c.gains.kdf_N_s_m = uvms_real_t(NAN); }},
      {"switch value 2", UVMS_CFG_SWITCHES, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.switches.position_feedback = 2; }},
      {"negative joint gain", UVMS_CFG_JOINT_SERVO, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.joint_kqd_1_s = -3; }},
      {"zero tick", UVMS_CFG_TICK, UVMS_ERR_RANGE, [](uvms_ctrl_config_t &c) { c.tick_s = 0; }},
      {"zero duration", UVMS_CFG_TRAJECTORY, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.traj_duration_s = 0; }},
      {"NaN final angle", UVMS_CFG_TRAJECTORY, UVMS_ERR_NONFINITE,
       [](uvms_ctrl_config_t &c) { c.theta_final_rad[6] = uvms_real_t(NAN); }},
      {"unknown trajectory mode", UVMS_CFG_TRAJECTORY, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.traj_mode = static_cast<uvms_traj_mode_t>(7); }},
      {"negative speed bound", UVMS_CFG_LIMITS, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.limits.max_vehicle_speed_m_s = -1; }},
      {"NaN current bound", UVMS_CFG_LIMITS, UVMS_ERR_NONFINITE,
       [](uvms_ctrl_config_t &c) { c.limits.max_motor_current_A = uvms_real_t(NAN); }},
      {"infinite thrust limit", UVMS_CFG_LIMITS, UVMS_ERR_NONFINITE,
       [](uvms_ctrl_config_t &c) { c.limits.thrust_limit_N[7] = uvms_real_t(INFINITY); }},
      {"negative thrust limit", UVMS_CFG_LIMITS, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.limits.thrust_limit_N[2] = -5; }},
      {"quaternion tolerance above 0.5", UVMS_CFG_LIMITS, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.limits.quat_norm_tol = uvms_real_t(0.6); }},
      {"hold longer than the cap", UVMS_CFG_LIMITS, UVMS_ERR_RANGE,
       [](uvms_ctrl_config_t &c) { c.limits.sensor_hold_max_ticks = UVMS_SENSOR_HOLD_MAX_TICKS_LIMIT + 1; }},
  };
  for (const auto &cs : cases) {
    uvms_ctrl_config_t cfg;
    uvms_ctrl_config_paper(&cfg, 7);
    cs.mutate(cfg);
    INFO(cs.what);
    CHECK(uvms_ctrl_init(&ctrl, &cfg) == cs.status);
    CHECK(ctrl.config_error == cs.field);
    CHECK(ctrl.ready == 0);
    // A controller that failed init refuses to run and commands nothing.
    uvms_ctrl_sensors_t s = StartSensors(cfg);
    uvms_ctrl_command_t cmd;
    CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, nullptr) == UVMS_ERR_STATE);
    for (double v : cmd.motor_voltage_V) CHECK(v == 0);
  }
  CHECK(std::string(uvms_cfg_field_str(UVMS_CFG_THRUSTER_RANK)) == "thruster_rank");
  CHECK(std::string(uvms_cfg_field_str(UVMS_CFG_LIMITS)) == "limits");
  // All-zero limits (a configuration mapped without them) are valid: every check off.
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  std::memset(&cfg.limits, 0, sizeof cfg.limits);
  CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
}

TEST_CASE("CaseOneLeavesEveryThrusterIdleAtZeroVoltage", "[controller]") {
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 1);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  s.position_m[0] = 0.3f;  // far from anywhere: feedback would act if it were on
  s.motor_speed_rad_s[2] = -50;
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  for (int k = 0; k < 3; ++k) {
    s.tick = k;
    s.time_s = uvms_real_t(0.03 * k);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((tlm.flags & UVMS_FLAG_THRUSTERS_IDLE) != 0);
    for (double v : cmd.motor_voltage_V) CHECK(v == 0);
  }
}

TEST_CASE("NonFiniteOrBrokenSensorsGiveSafeFiniteOutputAndASpecificFlag", "[controller]") {
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 7);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  // No good record yet: nothing to hold, so each rejected record gives the safe output.
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  s.motor_current_A[4] = uvms_real_t(NAN);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_NONFINITE) != 0);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) == 0);
  CHECK(tlm.sensor_rejected_ticks == 1u);
  CHECK(AllFinite(cmd));
  for (double v : cmd.motor_voltage_V) CHECK(v == 0);

  s = StartSensors(cfg);
  s.tick = 1;
  s.quaternion_wxyz[0] = 0;  // |q| = 0
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_RANGE);
  CHECK((tlm.flags & UVMS_FLAG_QUATERNION_INVALID) != 0);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0);
  CHECK(tlm.sensor_rejected_ticks == 2u);
  CHECK(AllFinite(cmd));

  s = StartSensors(cfg);
  s.tick = 2;
  s.joint_position_rad[1] = uvms_real_t(INFINITY);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
  CHECK(AllFinite(cmd));
}

TEST_CASE("TickSequenceGapsAndRepeatsAreFlagged", "[controller]") {
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  s.tick = 0;
  s.time_s = 0;
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_REFERENCE_CAPTURED) != 0);
  s.tick = 3;
  s.time_s = uvms_real_t(0.09);  // the time of tick 3: a gap is not a time jump
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TICK_GAP) != 0);
  CHECK((tlm.flags & UVMS_FLAG_REFERENCE_CAPTURED) == 0);
  s.tick = 3;  // repeated: rejected, the last good record (tick 3's) is held
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TICK_NOT_INCREASING) != 0);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) != 0);
  CHECK((tlm.flags & UVMS_FLAG_TICK_GAP) == 0);
  s.tick = 4;  // in order again: used, and no gap (3 is the last received in order)
  s.time_s = uvms_real_t(0.12);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & (UVMS_FLAG_TICK_GAP | UVMS_FLAG_TICK_NOT_INCREASING | UVMS_FLAG_SENSOR_HELD)) == 0);
}

TEST_CASE("OneTickIsConsistentWithTheModulesItComposes", "[controller]") {
  // A displaced, turning, drifting vehicle with the arm mid-motion, case VII and case IV:
  //  - allocation: H·P equals the desired wrench in body coordinates (R0ᵀF, R0ᵀN);
  //  - desired wrench = feedforward + feedback, parts as the switches say;
  //  - EE estimate equals the kinematics at the captured reference pose ([3]) or [4];
  //  - voltages finite.
  for (const int c : {4, 7}) {
    static uvms_ctrl_t ctrl;
    uvms_ctrl_config_t cfg;
    uvms_ctrl_config_paper(&cfg, c);
    REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
    uvms_ctrl_sensors_t s = StartSensorsBeforeMidRun(cfg);
    uvms_ctrl_command_t cmd;
    uvms_ctrl_telemetry_t tlm;
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);  // captures references at rest
    s.tick = 1;
    s.time_s = 20;
    s.position_m[0] = -0.02f;
    s.position_m[2] = 0.01f;
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.05, Eigen::Vector3d(0.3, 1, 0.2).normalized()));
    s.quaternion_wxyz[0] = uvms_real_t(q.w());
    s.quaternion_wxyz[1] = uvms_real_t(q.x());
    s.quaternion_wxyz[2] = uvms_real_t(q.y());
    s.quaternion_wxyz[3] = uvms_real_t(q.z());
    s.velocity_m_s[0] = -0.004f;
    s.angular_velocity_rad_s[1] = 0.002f;
    for (int j = 0; j < 7; ++j) {
      s.joint_position_rad[j] = uvms_real_t(cfg.theta_start_rad[j] + 0.3 * (cfg.theta_final_rad[j] - cfg.theta_start_rad[j]));
      s.joint_velocity_rad_s[j] = uvms_real_t(0.02 * (j + 1));
    }
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    INFO("case " << c);
    CHECK(AllFinite(cmd));

    uvms_real_t wb[6];
    REQUIRE(uvms_alloc_wrench_body(&ctrl.alloc, tlm.thrust_des_N, wb) == UVMS_OK);
    const Eigen::Matrix3d R0 = q.toRotationMatrix();
    const Eigen::Vector3d Fb = R0.transpose() * V(tlm.force_des_N);
    const Eigen::Vector3d Nb = R0.transpose() * V(tlm.moment_des_Nm);
    const double scale = std::max(1.0, Fb.norm() + Nb.norm());
    CHECK((V(&wb[0]) - Fb).norm() < (kFloat ? 1e-4 : 1e-10) * scale);
    CHECK((V(&wb[3]) - Nb).norm() < (kFloat ? 1e-4 : 1e-10) * scale);
    CHECK(Fb.norm() > 0.01);
    CHECK((V(tlm.force_des_N) - V(tlm.force_ff_N) - V(tlm.force_fb_N)).norm() < 1e-12 + 1e-6 * Fb.norm());
    for (int j = 0; j < 8; ++j)
      CHECK(double(tlm.thrust_des_N[j]) ==
            Approx(double(tlm.thrust_pos_N[j]) + double(tlm.thrust_att_N[j])).margin(kFloat ? 1e-4 : 1e-10));

    static uvms_arm_data_t d;
    uvms_real_t Rd[9];
    uvms_m3_identity(Rd);
    const uvms_real_t origin[3] = {0, 0, 0};
    Eigen::Vector3d ee_est;
    if (c == 7) {
      uvms_real_t q0[7];
      for (int j = 0; j < 7; ++j) q0[j] = cfg.theta_start_rad[j];
      REQUIRE(uvms_arm_fk(&ctrl.model, &d, origin, Rd, q0) == UVMS_OK);
      const Eigen::Vector3d cm0 = V(d.barycenter_m);
      REQUIRE(uvms_arm_fk(&ctrl.model, &d, origin, Rd, s.joint_position_rad) == UVMS_OK);
      ee_est = cm0 + V(d.ee_m) - V(d.barycenter_m);
      CHECK(V(tlm.force_fb_N).norm() > 0);  // feedback on the barycenter is active
    } else {
      REQUIRE(uvms_arm_fk(&ctrl.model, &d, origin, Rd, s.joint_position_rad) == UVMS_OK);
      ee_est = V(d.ee_m);
    }
    CHECK((V(tlm.ee_estimate_m) - ee_est).norm() < (kFloat ? 1e-5 : 1e-12));
  }
}

// ---------------------------------------------------------------------------------------------
// Error exits, thruster health, reference capture (controller.h: the safe-output rule).

namespace {

void SetQuat(uvms_ctrl_sensors_t &s, const Eigen::Quaterniond &q) {
  s.quaternion_wxyz[0] = uvms_real_t(q.w());
  s.quaternion_wxyz[1] = uvms_real_t(q.x());
  s.quaternion_wxyz[2] = uvms_real_t(q.y());
  s.quaternion_wxyz[3] = uvms_real_t(q.z());
}

// A mid-run tick: t = 20 s of the 60 s cycloid, the joints 30 % of the way (ahead of the
// reference, which is at 19.6 %: τ − sin(2πτ)/(2π) at τ = 1/3), moving, the vehicle displaced,
// turned and drifting, the motors spinning. Every output of the tick is then non-trivial.
uvms_ctrl_sensors_t MidRunSensors(const uvms_ctrl_config_t &cfg, int64_t tick, double t_s) {
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  s.tick = tick;
  s.time_s = uvms_real_t(t_s);
  s.position_m[0] = -0.02f;
  s.position_m[1] = 0.015f;
  s.position_m[2] = 0.01f;
  SetQuat(s, Eigen::Quaterniond(Eigen::AngleAxisd(0.05, Eigen::Vector3d(0.3, 1, 0.2).normalized())));
  s.velocity_m_s[0] = -0.004f;
  s.velocity_m_s[2] = 0.003f;
  s.angular_velocity_rad_s[1] = 0.002f;
  for (int j = 0; j < 7; ++j) {
    s.joint_position_rad[j] = uvms_real_t(cfg.theta_start_rad[j] +
                             0.3 * (cfg.theta_final_rad[j] - cfg.theta_start_rad[j]));
    s.joint_velocity_rad_s[j] = uvms_real_t(0.02 * (j + 1));
  }
  for (int m = 0; m < 8; ++m) {
    s.motor_speed_rad_s[m] = uvms_real_t(-30.0 + 9.0 * m);
    s.motor_current_A[m] = uvms_real_t(0.2 * m - 0.5);
  }
  return s;
}

// Mid-run tick k at the time its tick implies after StartSensorsBeforeMidRun (tick 0).
uvms_ctrl_sensors_t MidRunTick(const uvms_ctrl_config_t &cfg, int64_t k) {
  return MidRunSensors(cfg, k, 20.0 - 0.03 + 0.03 * double(k));
}

// The safe output of controller.h, with θ_ref held at q_ref_want.
void CheckSafeOutput(const uvms_ctrl_command_t &cmd, const uvms_real_t *q_ref_want) {
  for (double v : cmd.motor_voltage_V) CHECK(v == 0);
  for (double v : cmd.motor_current_cmd_A) CHECK(v == 0);    // no current in either drive
  for (double v : cmd.motor_current_rate_A_s) CHECK(v == 0);
  for (int j = 0; j < 7; ++j) {
    INFO("joint " << j + 1);
    CHECK(cmd.joint_acceleration_rad_s2[j] == 0);
    CHECK(cmd.joint_ref_rate_rad_s[j] == 0);
    CHECK(cmd.joint_ref_accel_rad_s2[j] == 0);
    CHECK(cmd.joint_ref_rad[j] == q_ref_want[j]);
  }
}

}  // namespace

namespace {
// Case IV, references captured at rest, then the mid-run tick with thruster 5 (index 4) marked
// unusable: the other seven still span every wrench (SPEC §3.4).
uvms_status_t StepWithThruster5Unusable(uvms_ctrl_t &ctrl, uvms_ctrl_config_t &cfg,
                                        uvms_real_t speed_rad_s, uvms_real_t current_A,
                                        uvms_ctrl_command_t &cmd, uvms_ctrl_telemetry_t &tlm) {
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_sensors_t s = StartSensorsBeforeMidRun(cfg);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  s = MidRunSensors(cfg, 1, 20.0);
  s.thruster_usable_mask = 0xFFu & ~(1u << 4);
  s.motor_speed_rad_s[4] = speed_rad_s;
  s.motor_current_A[4] = current_A;
  return uvms_ctrl_step(&ctrl, &s, &cmd, &tlm);
}
}  // namespace

TEST_CASE("AnUnusableThrustersNaNSensorsDoNotStopTheOthers", "[controller]") {
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  REQUIRE(StepWithThruster5Unusable(ctrl, cfg, uvms_real_t(NAN), uvms_real_t(NAN), cmd, tlm) ==
          UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_NONFINITE) == 0);
  CHECK(AllFinite(cmd));
  CHECK(cmd.motor_voltage_V[4] == 0);
  int driven = 0;
  for (int j = 0; j < 8; ++j) driven += (j != 4 && cmd.motor_voltage_V[j] != 0) ? 1 : 0;
  CHECK(driven == 7);

  // A usable thruster's NaN sensor is still a sensor fault of the tick: the record is
  // rejected and the last good one held.
  uvms_ctrl_sensors_t s = MidRunSensors(cfg, 2, 20.03);
  s.motor_current_A[2] = uvms_real_t(NAN);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_NONFINITE) != 0);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) != 0);
  CHECK(AllFinite(cmd));
}

TEST_CASE("AnUnusableThrusterGetsZeroVoltsAndNoMotorLoop", "[controller]") {
  // Measured ω = −200 rad/s, I = 3 A: the loop for its zero thrust would command
  // V = Rm·I + Lm·İ* + km·ω, about −2000 V before the clamp, into a thruster marked unhealthy.
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  REQUIRE(StepWithThruster5Unusable(ctrl, cfg, -200, 3, cmd, tlm) == UVMS_OK);
  CHECK(cmd.motor_voltage_V[4] == 0);
  CHECK(tlm.omega_des_rad_s[4] == 0);
  CHECK(tlm.current_des_A[4] == 0);
  CHECK(tlm.thrust_des_N[4] == 0);
  CHECK(tlm.advance_speed_m_s[4] == 0);
  CHECK(tlm.current_des_A[3] != 0);  // the usable ones do run
  CHECK(tlm.advance_speed_m_s[3] != 0);
}

TEST_CASE("EveryErrorExitZeroesTheJointCommandAndHoldsTheLastGoodReference", "[controller]") {
  // Without sensor hold (a rejected record gives the safe output at once) and without the
  // vehicle speed bound (so that an absurd finite velocity reaches the allocation).
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  cfg.limits.sensor_hold_max_ticks = 0;
  cfg.limits.max_vehicle_speed_m_s = 0;
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;

  // Before the first good tick the held reference is θI.
  uvms_ctrl_sensors_t s = MidRunSensors(cfg, 0, 20.0);
  s.joint_position_rad[3] = uvms_real_t(NAN);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
  CheckSafeOutput(cmd, cfg.theta_start_rad);

  // Good ticks mid-trajectory: the reference is away from θI and the servo is active.
  s = StartSensorsBeforeMidRun(cfg);
  s.tick = 1;  // tick 0 was received (and rejected): the sequence goes on from it
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  s = MidRunSensors(cfg, 2, 20.0);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  uvms_real_t q_good[7];
  for (int j = 0; j < 7; ++j) q_good[j] = cmd.joint_ref_rad[j];
  double servo = 0, moved = 0;
  for (int j = 0; j < 7; ++j) {
    servo += std::fabs(double(cmd.joint_acceleration_rad_s2[j]));
    moved += std::fabs(double(q_good[j]) - double(cfg.theta_start_rad[j]));
  }
  REQUIRE(servo > 0.1);
  REQUIRE(moved > 0.1);

  SECTION("sensor fault") {
    s = MidRunSensors(cfg, 3, 20.03);
    s.angular_velocity_rad_s[0] = uvms_real_t(INFINITY);
    CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
    CheckSafeOutput(cmd, q_good);
  }
  SECTION("arm model / feedforward failure") {
    // Simulated corruption: the model's ready flag cleared (uvms_feedforward → STATE).
    ctrl.model.ready = 0;
    s = MidRunSensors(cfg, 3, 20.03);
    CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_STATE);
    CHECK((tlm.flags & UVMS_FLAG_MODEL_FAULT) != 0);
    CheckSafeOutput(cmd, q_good);
    ctrl.model.ready = 1;
  }
  SECTION("allocation failure") {
    // A finite but absurd velocity: K_DF·v overflows the real type, the desired force is
    // infinite and uvms_alloc_step refuses it (NONFINITE).
    s = MidRunSensors(cfg, 3, 20.03);
    s.velocity_m_s[0] = uvms_real_t(kFloat ? 1e37 : 1e307);
    CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
    CHECK((tlm.flags & UVMS_FLAG_MODEL_FAULT) != 0);
    CheckSafeOutput(cmd, q_good);
  }
  // After the fault, a good tick commands normally again.
  s = MidRunSensors(cfg, 4, 20.06);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK(AllFinite(cmd));
}

TEST_CASE("RankLossKeepsControllingTheRemainingAxesAndTheArm", "[controller]") {
  // Two identical controllers see the same ticks; one loses thrusters 5–8 (only the four
  // surge thrusters left: rank 3, spanning Fx, My, Mz of the vehicle frame). It must go on
  // (UVMS_OK, flag ALLOC_SINGULAR, rank 3, Fy Fz Mx reported lost), drive the surge thrusters
  // so that the body-frame Fx, My, Mz it delivers equal the desired ones and Fy, Fz, Mx are
  // zero, idle thrusters 5–8, and give the arm the very same command as the healthy one.
  static uvms_ctrl_t healthy, degraded;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 7);
  cfg.limits.sensor_hold_max_ticks = 0;  // the error at the end must give the safe output
  REQUIRE(uvms_ctrl_init(&healthy, &cfg) == UVMS_OK);
  REQUIRE(uvms_ctrl_init(&degraded, &cfg) == UVMS_OK);
  uvms_ctrl_command_t ch, cd;
  uvms_ctrl_telemetry_t th, td;
  uvms_ctrl_sensors_t s = StartSensorsBeforeMidRun(cfg);
  REQUIRE(uvms_ctrl_step(&healthy, &s, &ch, &th) == UVMS_OK);
  REQUIRE(uvms_ctrl_step(&degraded, &s, &cd, &td) == UVMS_OK);
  CHECK(td.alloc_rank == 6);
  CHECK(td.uncontrollable_axes == 0u);

  s = MidRunSensors(cfg, 1, 20.0);
  REQUIRE(uvms_ctrl_step(&healthy, &s, &ch, &th) == UVMS_OK);
  s.thruster_usable_mask = 0x0Fu;
  REQUIRE(uvms_ctrl_step(&degraded, &s, &cd, &td) == UVMS_OK);
  CHECK(td.status == UVMS_OK);
  CHECK((td.flags & UVMS_FLAG_ALLOC_SINGULAR) != 0);
  CHECK((th.flags & UVMS_FLAG_ALLOC_SINGULAR) == 0);
  CHECK(td.alloc_rank == 3);
  CHECK(td.uncontrollable_axes == (UVMS_AXIS_FY | UVMS_AXIS_FZ | UVMS_AXIS_MX));
  for (int j = 0; j < 8; ++j) {
    INFO("thruster " << j + 1);
    if (j < 4) CHECK(cd.motor_voltage_V[j] != 0);
    else CHECK(cd.motor_voltage_V[j] == 0);
  }
  for (int j = 0; j < 7; ++j) {
    INFO("joint " << j + 1);
    CHECK(cd.joint_acceleration_rad_s2[j] == ch.joint_acceleration_rad_s2[j]);
    CHECK(cd.joint_ref_rad[j] == ch.joint_ref_rad[j]);
    CHECK(cd.joint_ref_rate_rad_s[j] == ch.joint_ref_rate_rad_s[j]);
    CHECK(cd.joint_ref_accel_rad_s2[j] == ch.joint_ref_accel_rad_s2[j]);
  }
  double servo = 0;
  for (double a : cd.joint_acceleration_rad_s2) servo += std::fabs(a);
  CHECK(servo > 0.1);
  // The desired wrench is the healthy one; the deliverable one is its controllable part.
  CHECK((V(td.force_des_N) - V(th.force_des_N)).norm() == 0.0);
  CHECK((V(td.moment_des_Nm) - V(th.moment_des_Nm)).norm() == 0.0);
  uvms_real_t R0[9];
  REQUIRE(uvms_quat_to_rot(s.quaternion_wxyz, R0) == UVMS_OK);
  const Eigen::Matrix3d R = M(R0);
  const Eigen::Vector3d Fb = R.transpose() * V(td.force_des_N), Nb = R.transpose() * V(td.moment_des_Nm);
  const Eigen::Vector3d Fd = R.transpose() * V(td.force_deliverable_N);
  const Eigen::Vector3d Nd = R.transpose() * V(td.moment_deliverable_Nm);
  const double tol = (kFloat ? 1e-4 : 1e-10) * std::max(1.0, Fb.norm() + Nb.norm());
  CHECK(std::fabs(Fd.x() - Fb.x()) < tol);
  CHECK(std::fabs(Nd.y() - Nb.y()) < tol);
  CHECK(std::fabs(Nd.z() - Nb.z()) < tol);
  CHECK(std::fabs(Fd.y()) < tol);
  CHECK(std::fabs(Fd.z()) < tol);
  CHECK(std::fabs(Nd.x()) < tol);
  CHECK(std::fabs(Fb.x()) + std::fabs(Nb.y()) + std::fabs(Nb.z()) > 0.05);  // non-vacuous
  // The healthy controller delivers the whole desired wrench.
  CHECK((V(th.force_deliverable_N) - V(th.force_des_N)).norm() < tol);
  CHECK((V(th.moment_deliverable_Nm) - V(th.moment_des_Nm)).norm() < tol);

  // An error on the next tick holds the reference of the rank-loss tick.
  uvms_real_t q_sing[7];
  for (int j = 0; j < 7; ++j) q_sing[j] = cd.joint_ref_rad[j];
  s = MidRunSensors(cfg, 2, 20.03);
  s.thruster_usable_mask = 0x0Fu;
  s.time_s = uvms_real_t(NAN);
  CHECK(uvms_ctrl_step(&degraded, &s, &cd, &td) == UVMS_ERR_NONFINITE);
  CheckSafeOutput(cd, q_sing);
}

TEST_CASE("LosingBothHeaveThrustersLosesOnlyFzInTheController", "[controller]") {
  // SPEC §3.4 (test_allocation.cpp derives it): without thrusters 5 and 6 the rest spans
  // Fx Fy Mx My Mz; with either one the set has full rank.
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  const struct {
    uint32_t mask;
    int rank;
    uint32_t axes;
  } steps[] = {{0xFFu & ~(1u << 4), 6, 0u},
               {0xFFu & ~(1u << 5), 6, 0u},
               {0xFFu & ~0x30u, 5, UVMS_AXIS_FZ},
               {0xFFu, 6, 0u}};
  int64_t k = 1;
  for (const auto &st : steps) {
    s = MidRunSensors(cfg, k, 20.0 + 0.03 * double(k));
    ++k;
    s.thruster_usable_mask = st.mask;
    INFO("mask 0x" << std::hex << st.mask);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK(tlm.alloc_rank == st.rank);
    CHECK(tlm.uncontrollable_axes == st.axes);
    CHECK(((tlm.flags & UVMS_FLAG_ALLOC_SINGULAR) != 0) == (st.rank < 6));
    uvms_real_t R0[9];
    REQUIRE(uvms_quat_to_rot(s.quaternion_wxyz, R0) == UVMS_OK);
    const Eigen::Matrix3d R = M(R0);
    Eigen::Matrix<double, 6, 1> want, got;
    want << R.transpose() * V(tlm.force_des_N), R.transpose() * V(tlm.moment_des_Nm);
    got << R.transpose() * V(tlm.force_deliverable_N), R.transpose() * V(tlm.moment_deliverable_Nm);
    if (st.rank < 6) want(2) = 0;  // Fz is lost, every other axis still served exactly
    CHECK((got - want).norm() < (kFloat ? 1e-4 : 1e-10) * std::max(1.0, want.norm()));
  }
}

TEST_CASE("ANullCommandStillReportsItsStatus", "[controller]") {
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  s.tick = 41;
  uvms_ctrl_telemetry_t tlm;
  CHECK(uvms_ctrl_step(&ctrl, &s, nullptr, &tlm) == UVMS_ERR_ARG);
  CHECK(tlm.status == UVMS_ERR_ARG);
  CHECK(tlm.tick == 41);
  uvms_ctrl_command_t cmd;
  CHECK(uvms_ctrl_step(nullptr, &s, &cmd, &tlm) == UVMS_ERR_ARG);
  CHECK(tlm.status == UVMS_ERR_ARG);
  for (double v : cmd.joint_ref_rad) CHECK(v == 0);  // no controller: no reference known
  CHECK(uvms_ctrl_step(&ctrl, nullptr, &cmd, &tlm) == UVMS_ERR_ARG);
  CHECK(tlm.status == UVMS_ERR_ARG);
  CheckSafeOutput(cmd, cfg.theta_start_rad);
}

TEST_CASE("ACartesianLineMustReferToThePointTheCaseHolds", "[controller]") {
  // SPEC §8: the line is referenced to the vehicle or to the barycenter "as the case requires".
  static uvms_ctrl_t ctrl;
  for (const int c : {4, 7}) {
    uvms_ctrl_config_t cfg;
    uvms_ctrl_config_paper(&cfg, c);
    cfg.traj_mode = UVMS_TRAJ_CARTESIAN_LINE;
    cfg.cart.direction[0] = -1;  // reachable from θI (trajectory.h)
    INFO("case " << c);
    CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);  // the paper config matches by construction
    cfg.cart.reference = (c == 7) ? UVMS_REF_VEHICLE : UVMS_REF_BARYCENTER;
    CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_ERR_RANGE);
    CHECK(ctrl.config_error == UVMS_CFG_TRAJECTORY);
    CHECK(ctrl.ready == 0);
  }
}

TEST_CASE("ACartesianLineThatCannotStartFailsSafeAndIsRetried", "[controller]") {
  // If uvms_cart_traj_init fails at reference capture, the tick must hold (θ_ref = θI, θ̈ = 0,
  // V = 0), never servo toward a zero reference; the next tick retries the capture. The failure
  // is simulated by corrupting the start pose in the configuration the instance points to
  // (init validated the real one; an application must not change it, uvms_ctrl_init).
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg = CartesianCaseFour();
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  const uvms_real_t keep = cfg.theta_start_rad[2];
  cfg.theta_start_rad[2] = uvms_real_t(NAN);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) != UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TRAJECTORY_FAULT) != 0);
  cfg.theta_start_rad[2] = keep;
  CheckSafeOutput(cmd, cfg.theta_start_rad);

  s.tick = 1;
  s.time_s = uvms_real_t(0.03);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_REFERENCE_CAPTURED) != 0);
  CHECK(ctrl.cart.ready == 1);
  for (int j = 0; j < 7; ++j) {
    CHECK(double(cmd.joint_ref_rad[j]) == Approx(double(cfg.theta_start_rad[j])).margin(1e-3));
    CHECK(std::fabs(double(cmd.joint_acceleration_rad_s2[j])) < 1.0);
  }
}

TEST_CASE("AMidRunTrajectoryFaultHoldsTheLastGoodReferenceAtRest", "[controller]") {
  // A Cartesian line that fails after it started (simulated: the instance's ready flag cleared,
  // so uvms_cart_traj_step returns STATE with all-zero outputs) must not hand a zero reference
  // to the servo: the tick goes on (vehicle control active) with the last good reference held
  // at rest, flag TRAJECTORY_FAULT, and the servo pulling the joints to it.
  static uvms_ctrl_t ctrl;
  const uvms_ctrl_config_t cfg = CartesianCaseFour();
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  for (int k = 0; k < 3; ++k) {
    s.tick = k;
    s.time_s = uvms_real_t(0.03 * k);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  }
  uvms_real_t q_good[7];
  for (int j = 0; j < 7; ++j) q_good[j] = cmd.joint_ref_rad[j];
  ctrl.cart.ready = 0;
  s.tick = 3;
  s.time_s = uvms_real_t(0.09);
  s.joint_position_rad[1] += uvms_real_t(0.01);  // off the reference: the servo must pull joint 2 back
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TRAJECTORY_FAULT) != 0);
  for (int j = 0; j < 7; ++j) {
    INFO("joint " << j + 1);
    CHECK(cmd.joint_ref_rad[j] == q_good[j]);
    CHECK(cmd.joint_ref_rate_rad_s[j] == 0);
    CHECK(cmd.joint_ref_accel_rad_s2[j] == 0);
  }
  CHECK(double(cmd.joint_acceleration_rad_s2[1]) < -0.5);  // Kq·(−0.01 rad) = −1 rad/s²
  double volts = 0;
  for (double v : cmd.motor_voltage_V) volts += std::fabs(v);
  CHECK(volts > 0);  // the vehicle is still controlled
}

TEST_CASE("TickSequenceChecksHoldAtTheEndsOfTheIntegerRange", "[controller]") {
  // The gap test must not compute last + 1 where that overflows (UB; run under UBSan in
  // host-asan).
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  struct Step {
    int64_t tick;
    uint32_t want;
  };
  const Step steps[] = {
      {INT64_MIN, 0},
      {INT64_MIN + 1, 0},
      {INT64_MAX - 1, UVMS_FLAG_TICK_GAP},
      {INT64_MAX, 0},
      {INT64_MAX, UVMS_FLAG_TICK_NOT_INCREASING},
      {INT64_MIN, UVMS_FLAG_TICK_NOT_INCREASING},
  };
  for (const Step &st : steps) {
    s.tick = st.tick;
    INFO("tick " << st.tick);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((tlm.flags & (UVMS_FLAG_TICK_GAP | UVMS_FLAG_TICK_NOT_INCREASING)) == st.want);
  }
}

TEST_CASE("PositionReferenceFeedforwardAndFeedbackFollowTheCase", "[controller]") {
  // Cases II–VIII against independent computations with the same inputs:
  //  - r_d (position_ref_m) is the barycenter [5] of the first tick (II, III, VII, VIII) or the
  //    vehicle position of the first tick (IV, V, VI);
  //  - F_r = F_r,cm [32] (barycenter) or F_r,0 [31] (vehicle) of uvms_feedforward when the
  //    position feedforward is on, else 0; N_r = its attitude moment (attitude always on);
  //  - F_fb = K_PF·(r_d − p) + K_DF·(0 − ṗ) with (p, ṗ) the barycenter and its velocity, or the
  //    vehicle's, when the position feedback is on, else 0. The tick is built so that the
  //    vehicle and barycenter velocities differ (the joints move).
  for (int c = 2; c <= 8; ++c) {
    static uvms_ctrl_t ctrl;
    uvms_ctrl_config_t cfg;
    uvms_ctrl_config_paper(&cfg, c);
    REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
    uvms_arm_model_t model;
    REQUIRE(uvms_arm_model_init(&cfg.arm, &model) == UVMS_OK);
    static uvms_arm_data_t d;
    const bool bary = cfg.switches.position_reference == UVMS_REF_BARYCENTER;
    INFO("case " << c);

    // First tick: the vehicle away from the origin, turned, drifting, the arm moving.
    uvms_ctrl_sensors_t s = StartSensorsBeforeMidRun(cfg);
    const Eigen::Vector3d r00(0.2, -0.1, 0.05);
    Put(r00, s.position_m);
    const Eigen::Quaterniond q0(Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, -1, 2).normalized()));
    SetQuat(s, q0);
    s.velocity_m_s[1] = 0.002f;
    for (int j = 0; j < 7; ++j) s.joint_velocity_rad_s[j] = uvms_real_t(0.01 * (7 - j));
    uvms_ctrl_command_t cmd;
    uvms_ctrl_telemetry_t tlm;
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    uvms_real_t R00[9];
    Put(Eigen::Matrix3d(q0.toRotationMatrix()), R00);
    REQUIRE(uvms_arm_fk(&model, &d, s.position_m, R00, s.joint_position_rad) == UVMS_OK);
    const Eigen::Vector3d r_d = bary ? V(d.barycenter_m) : r00;
    CHECK((r_d - r00).norm() > (bary ? 0.05 : -1.0));  // the two candidates really differ
    const double tol_r = kFloat ? 1e-5 : 1e-12;
    CHECK((V(tlm.position_ref_m) - r_d).norm() < tol_r);

    // Mid-run tick.
    s = MidRunSensors(cfg, 1, 20.0);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((V(tlm.position_ref_m) - r_d).norm() < tol_r);

    uvms_base_state_t base{};
    Put(V(s.position_m), base.position_m);
    Put(Eigen::Matrix3d(Eigen::Quaterniond(double(s.quaternion_wxyz[0]), double(s.quaternion_wxyz[1]),
                                           double(s.quaternion_wxyz[2]), double(s.quaternion_wxyz[3]))
                            .normalized()
                            .toRotationMatrix()),
        base.R0);
    Put(V(s.velocity_m_s), base.velocity_m_s);
    Put(V(s.angular_velocity_rad_s), base.omega_rad_s);
    uvms_feedforward_t ff;
    REQUIRE(uvms_feedforward(&model, &d, &cfg.fluid, cfg.switches.position_reference, &base, s.joint_position_rad,
                             s.joint_velocity_rad_s, cmd.joint_acceleration_rad_s2, &ff) == UVMS_OK);
    const Eigen::Vector3d F_ff = cfg.switches.position_feedforward
                                     ? V(bary ? ff.force_barycenter_N : ff.force_vehicle_N)
                                     : Eigen::Vector3d::Zero();
    const Eigen::Vector3d N_ff = V(ff.moment_att_Nm);
    const Eigen::Vector3d p = bary ? V(d.barycenter_m) : V(s.position_m);
    const Eigen::Vector3d pd = bary ? V(d.barycenter_v_m_s) : V(s.velocity_m_s);
    if (bary) CHECK((pd - V(s.velocity_m_s)).norm() > 2e-3);  // [m/s]: K_DF makes that ≥ 0.2 N
    const Eigen::Vector3d F_fb =
        cfg.switches.position_feedback
            ? Eigen::Vector3d(double(cfg.gains.kpf_N_m) * (r_d - p) - double(cfg.gains.kdf_N_s_m) * pd)
            : Eigen::Vector3d::Zero();
    // Non-vacuous: the alternatives the switches choose between differ materially here.
    CHECK((V(ff.force_vehicle_N) - V(ff.force_barycenter_N)).norm() > 0.05);
    CHECK(N_ff.norm() > 0.05);

    const double tol = kFloat ? 2e-3 : 1e-9;  // [N], [N·m]: values are O(1–10)
    CHECK((V(tlm.force_ff_N) - F_ff).norm() < tol);
    CHECK((V(tlm.moment_ff_Nm) - N_ff).norm() < tol);
    CHECK((V(tlm.force_fb_N) - F_fb).norm() < tol);
    CHECK((V(tlm.barycenter_v_m_s) - V(d.barycenter_v_m_s)).norm() < (kFloat ? 1e-6 : 1e-13));
  }
}

// ---------------------------------------------------------------------------------------------
// Sensor faults (docs/FAULTS.md): each rejection cause has its own flag; the hold-last-good
// policy; output bounds over arbitrary records.

namespace {

// Every flag that marks a rejected record.
constexpr uint32_t kRejectFlags =
    UVMS_FLAG_SENSOR_NONFINITE | UVMS_FLAG_QUATERNION_INVALID | UVMS_FLAG_TICK_NOT_INCREASING |
    UVMS_FLAG_JOINT_LIMIT | UVMS_FLAG_VEHICLE_SPEED_IMPLAUSIBLE |
    UVMS_FLAG_ANGULAR_RATE_IMPLAUSIBLE | UVMS_FLAG_JOINT_RATE_IMPLAUSIBLE |
    UVMS_FLAG_MOTOR_SPEED_IMPLAUSIBLE | UVMS_FLAG_MOTOR_CURRENT_IMPLAUSIBLE;

struct Fault {
  const char *what;
  uint32_t flag;
  uvms_status_t status;
  void (*mutate)(uvms_ctrl_sensors_t &);
};

// One fault per cause, each just past its bound in the paper configuration (limits of
// uvms_ctrl_config_paper: 5 m/s, 10 rad/s, 10 rad/s, 2e4 rad/s, 2e5 A, 5 %, joints ±2π).
const Fault kFaults[] = {
    {"NaN position", UVMS_FLAG_SENSOR_NONFINITE, UVMS_ERR_NONFINITE,
     [](uvms_ctrl_sensors_t &s) { s.position_m[1] = uvms_real_t(NAN); }},
    {"-inf joint rate", UVMS_FLAG_SENSOR_NONFINITE, UVMS_ERR_NONFINITE,
     [](uvms_ctrl_sensors_t &s) { s.joint_velocity_rad_s[6] = -uvms_real_t(INFINITY); }},
    {"quaternion norm 1.06", UVMS_FLAG_QUATERNION_INVALID, UVMS_ERR_RANGE,
     [](uvms_ctrl_sensors_t &s) { for (auto &c : s.quaternion_wxyz) c *= uvms_real_t(1.06); }},
    {"quaternion norm 0.94", UVMS_FLAG_QUATERNION_INVALID, UVMS_ERR_RANGE,
     [](uvms_ctrl_sensors_t &s) { for (auto &c : s.quaternion_wxyz) c *= uvms_real_t(0.94); }},
    {"joint 3 past +2π", UVMS_FLAG_JOINT_LIMIT, UVMS_ERR_RANGE,
     [](uvms_ctrl_sensors_t &s) { s.joint_position_rad[2] = uvms_real_t(6.3); }},
    {"vehicle at 5.1 m/s", UVMS_FLAG_VEHICLE_SPEED_IMPLAUSIBLE, UVMS_ERR_RANGE,
     [](uvms_ctrl_sensors_t &s) { s.velocity_m_s[0] = 3; s.velocity_m_s[1] = uvms_real_t(-4.1); }},
    {"vehicle turning at 10.1 rad/s", UVMS_FLAG_ANGULAR_RATE_IMPLAUSIBLE, UVMS_ERR_RANGE,
     [](uvms_ctrl_sensors_t &s) { s.angular_velocity_rad_s[2] = uvms_real_t(10.1); }},
    {"joint 5 at 10.1 rad/s", UVMS_FLAG_JOINT_RATE_IMPLAUSIBLE, UVMS_ERR_RANGE,
     [](uvms_ctrl_sensors_t &s) { s.joint_velocity_rad_s[4] = uvms_real_t(-10.1); }},
    {"motor 2 at 2.1e4 rad/s", UVMS_FLAG_MOTOR_SPEED_IMPLAUSIBLE, UVMS_ERR_RANGE,
     [](uvms_ctrl_sensors_t &s) { s.motor_speed_rad_s[1] = uvms_real_t(-2.1e4); }},
    {"motor 8 at 2.1e5 A", UVMS_FLAG_MOTOR_CURRENT_IMPLAUSIBLE, UVMS_ERR_RANGE,
     [](uvms_ctrl_sensors_t &s) { s.motor_current_A[7] = uvms_real_t(2.1e5); }},
    {"tick repeated", UVMS_FLAG_TICK_NOT_INCREASING, UVMS_ERR_RANGE,
     [](uvms_ctrl_sensors_t &s) { s.tick -= 1; }},
};

}  // namespace

// The attitude error [44] at the tick level: the rotation from the sensed attitude to the one
// captured on the first tick, whatever the sensed quaternion's sign and norm, through a held
// record and a reset (which captures again).
TEST_CASE("TheAttitudeErrorTurnsTheSensedAttitudeToTheCapturedOne", "[controller]") {
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 7);
  cfg.limits.quat_norm_tol = uvms_real_t(0.5);  // norms 0.5 .. 1.5 accepted
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  const double tol = kFloat ? 2e-6 : 1e-14;  // [rad]
  const Eigen::Quaterniond q0(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -2, 0.5).normalized()));
  auto set = [](uvms_ctrl_sensors_t &s, const Eigen::Quaterniond &q, double k) {
    SetQuat(s, Eigen::Quaterniond(k * q.w(), k * q.x(), k * q.y(), k * q.z()));
  };
  uvms_ctrl_sensors_t s = StartSensorsBeforeMidRun(cfg);
  set(s, q0, 1.3);  // captured: its rotation, not its norm, is the reference
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_REFERENCE_CAPTURED) != 0);
  CHECK(V(tlm.attitude_error_rad).norm() < tol);

  // The same attitude as −0.7·q0: no error.
  s.tick = 1;
  s.time_s = 20;
  set(s, q0, -0.7);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK(V(tlm.attitude_error_rad).norm() < tol);

  // Turned by −0.1 rad about a second axis (inertial): the error is +0.1 rad about it, and
  // N_fb = K_PN·φ·e − K_DN·ω0 (K_PN = 10, K_DN = 100 in the paper's gains).
  const Eigen::Vector3d axis = Eigen::Vector3d(0.2, 0.9, -0.4).normalized();
  const Eigen::Quaterniond q1 = Eigen::AngleAxisd(-0.1, axis) * q0;
  s.tick = 2;
  s.time_s = uvms_real_t(20.03);
  set(s, q1, -1.2);
  s.angular_velocity_rad_s[2] = uvms_real_t(0.003);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((V(tlm.attitude_error_rad) - 0.1 * axis).norm() < tol);
  CHECK((V(tlm.moment_fb_Nm) - (1.0 * axis - 100.0 * V(s.angular_velocity_rad_s))).norm() <
        (kFloat ? 1e-4 : 1e-12));

  // A rejected record (a joint out of its limits) is held: the same error again.
  const Eigen::Vector3d held = V(tlm.attitude_error_rad);
  uvms_ctrl_sensors_t bad = s;
  bad.tick = 3;
  bad.time_s = uvms_real_t(20.06);
  set(bad, q0, 1.0);
  bad.joint_position_rad[0] = uvms_real_t(100.0);
  REQUIRE(uvms_ctrl_step(&ctrl, &bad, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) != 0);
  CHECK((V(tlm.attitude_error_rad) - held).norm() < tol);

  // After a reset the next first tick captures again: q1 is now the reference.
  uvms_ctrl_reset(&ctrl);
  uvms_ctrl_sensors_t again = StartSensorsBeforeMidRun(cfg);
  set(again, q1, 0.9);
  REQUIRE(uvms_ctrl_step(&ctrl, &again, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_REFERENCE_CAPTURED) != 0);
  CHECK(V(tlm.attitude_error_rad).norm() < tol);
}

TEST_CASE("EachRejectedRecordSetsItsOwnFlagAndIsHeldOrRefused", "[controller]") {
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  for (const Fault &f : kFaults) {
    INFO(f.what);
    // Fresh controller, one good tick (tick 1), then the faulty record as tick 2.
    REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
    uvms_ctrl_sensors_t s = MidRunSensors(cfg, 1, 20.0);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((tlm.flags & kRejectFlags) == 0);  // the baseline record is clean
    s = MidRunSensors(cfg, 2, 20.03);
    f.mutate(s);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((tlm.flags & kRejectFlags) == f.flag);  // that cause, and only it
    CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) != 0);
    CHECK(tlm.sensor_rejected_ticks == 1u);
    CHECK(AllFinite(cmd));

    // Without a good record to hold, the same record is refused with its status.
    REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
    if (f.flag != UVMS_FLAG_TICK_NOT_INCREASING) {
      CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == f.status);
      CHECK((tlm.flags & kRejectFlags) == f.flag);
      CHECK((tlm.flags & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0);
      CheckSafeOutput(cmd, cfg.theta_start_rad);
    }
  }
  // A bound of 0 switches its check off: the fast vehicle's record is then used.
  cfg.limits.max_vehicle_speed_m_s = 0;
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_sensors_t s = MidRunSensors(cfg, 1, 20.0);
  s.velocity_m_s[0] = 30;
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & (kRejectFlags | UVMS_FLAG_SENSOR_HELD)) == 0);
  // An unusable thruster's absurd motor readings are not read at all.
  s = MidRunSensors(cfg, 2, 20.03);
  s.thruster_usable_mask = 0xFFu & ~(1u << 1);
  s.motor_speed_rad_s[1] = uvms_real_t(1e30);
  s.motor_current_A[1] = uvms_real_t(-1e30);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & (kRejectFlags | UVMS_FLAG_SENSOR_HELD)) == 0);
  CHECK(cmd.motor_voltage_V[1] == 0);
}

TEST_CASE("HeldTicksRepeatTheLastGoodCommandThenExpireToTheSafeOutput", "[controller]") {
  // Policy (controller.h): up to sensor_hold_max_ticks consecutive rejected records are
  // replaced by the last good record, unchanged, so each held tick commands exactly what that
  // record commanded; the next rejection gives the safe output; a good record resumes.
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 7);
  const uint32_t hold = cfg.limits.sensor_hold_max_ticks;
  REQUIRE(hold == 5u);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd, good;
  uvms_ctrl_telemetry_t tlm;
  uvms_ctrl_sensors_t s = StartSensorsBeforeMidRun(cfg);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  s = MidRunSensors(cfg, 1, 20.0);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &good, &tlm) == UVMS_OK);
  int64_t k = 2;
  uvms_ctrl_command_t prev = good;
  for (uint32_t i = 1; i <= hold; ++i, ++k) {
    INFO("held tick " << i);
    s = MidRunTick(cfg, k);
    s.position_m[0] = uvms_real_t(NAN);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) != 0);
    CHECK(tlm.sensor_rejected_ticks == i);
    // The very same command, except the integrated current command [66], which goes on
    // along the held rate: I*_k = I*_(k−1) + İ*·tick (the current drive's ramp continues).
    for (size_t j = 0; j < 8; ++j)
      CHECK(cmd.motor_current_cmd_A[j] ==
            prev.motor_current_cmd_A[j] + prev.motor_current_rate_A_s[j] * cfg.tick_s);
    prev = cmd;
    uvms_ctrl_command_t a = cmd, b = good;
    std::memset(a.motor_current_cmd_A, 0, sizeof a.motor_current_cmd_A);
    std::memset(b.motor_current_cmd_A, 0, sizeof b.motor_current_cmd_A);
    CHECK(std::memcmp(&a, &b, sizeof a) == 0);
  }
  s = MidRunTick(cfg, k++);
  s.position_m[0] = uvms_real_t(NAN);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) == 0);
  CHECK(tlm.sensor_rejected_ticks == hold + 1);
  CheckSafeOutput(cmd, good.joint_ref_rad);
  // Still refused while the faults go on (a different cause now).
  s = MidRunTick(cfg, k++);
  s.angular_velocity_rad_s[0] = 50;
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_RANGE);
  CHECK((tlm.flags & UVMS_FLAG_ANGULAR_RATE_IMPLAUSIBLE) != 0);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0);
  // A good record: normal control, the streak reset, and a fresh hold budget.
  s = MidRunTick(cfg, k++);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK(tlm.sensor_rejected_ticks == 0u);
  CHECK((tlm.flags & (UVMS_FLAG_SENSOR_HELD | UVMS_FLAG_SENSOR_HOLD_EXPIRED)) == 0);
  s = MidRunTick(cfg, k++);
  s.joint_position_rad[0] = uvms_real_t(INFINITY);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) != 0);
  // reset forgets the held record: nothing to hold afterwards.
  uvms_ctrl_reset(&ctrl);
  s = MidRunSensors(cfg, 0, 20.0);
  s.joint_position_rad[0] = uvms_real_t(INFINITY);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0);
}

TEST_CASE("AHeldTickStillHonoursThrustersReportedUnusable", "[controller]") {
  // The incoming record is rejected (NaN joint angle), but it reports thruster 3 unusable:
  // the held tick must not drive it, although the held record had it usable.
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  uvms_ctrl_sensors_t s = MidRunSensors(cfg, 1, 20.0);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  REQUIRE(cmd.motor_voltage_V[2] != 0);
  s = MidRunSensors(cfg, 2, 20.03);
  s.joint_position_rad[0] = uvms_real_t(NAN);
  s.thruster_usable_mask = 0xFFu & ~(1u << 2);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) != 0);
  CHECK(cmd.motor_voltage_V[2] == 0);
  CHECK(tlm.thrust_des_N[2] == 0);
  CHECK(cmd.motor_voltage_V[3] != 0);
  // And it cannot switch a thruster back on: held record says unusable, incoming usable.
  s = MidRunSensors(cfg, 3, 20.06);
  s.thruster_usable_mask = 0xFFu & ~(1u << 5);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);  // good: held record now masks 6
  s = MidRunSensors(cfg, 4, 20.09);
  s.joint_position_rad[0] = uvms_real_t(NAN);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) != 0);
  CHECK(cmd.motor_voltage_V[5] == 0);
}

TEST_CASE("ThrustLimitInTheControllerKeepsDirectionsAndReportsTheShortfall", "[controller]") {
  // Case IV mid-run with a thrust limit well below the allocated thrusts: every |P_j| ≤ T,
  // flag THRUST_SATURATED, the deliverable force and moment are parallel to the desired ones
  // (cosine 1 to rounding), shortened by exactly the reported scales; attitude is fully
  // served whenever its part alone fits.
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  uvms_ctrl_sensors_t s = StartSensorsBeforeMidRun(cfg);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  s = MidRunSensors(cfg, 1, 20.0);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_THRUST_SATURATED) == 0);  // 1e6 N: never in the paper's runs
  CHECK(tlm.thrust_scale_pos == 1);
  CHECK(tlm.thrust_scale_att == 1);
  double p_max = 0, att_max = 0;
  for (int j = 0; j < 8; ++j) {
    p_max = std::max(p_max, std::fabs(double(tlm.thrust_des_N[j])));
    att_max = std::max(att_max, std::fabs(double(tlm.thrust_att_N[j])));
  }
  REQUIRE(att_max > 0);
  REQUIRE(p_max > 1.5 * att_max);  // room for the "position scaled" regime
  const double rt = kFloat ? 1e-5 : 1e-10;
  const double limits[] = {0.5 * (p_max + att_max), 0.5 * att_max};
  for (const double T : limits) {
    INFO("limit " << T << " N (largest thrust " << p_max << " N, attitude part " << att_max << " N)");
    for (uvms_real_t &limit_N : cfg.limits.thrust_limit_N) limit_N = uvms_real_t(T);
    REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
    s = StartSensorsBeforeMidRun(cfg);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    s = MidRunSensors(cfg, 1, 20.0);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((tlm.flags & UVMS_FLAG_THRUST_SATURATED) != 0);
    for (int j = 0; j < 8; ++j) CHECK(std::fabs(double(tlm.thrust_des_N[j])) <= T * (1 + 1e-6));
    const Eigen::Vector3d Fc = V(tlm.force_des_N), Fd = V(tlm.force_deliverable_N);
    const Eigen::Vector3d Nc = V(tlm.moment_des_Nm), Nd = V(tlm.moment_deliverable_Nm);
    CHECK(Nd.dot(Nc) / (Nd.norm() * Nc.norm()) > 1 - rt);
    CHECK((Nd - double(tlm.thrust_scale_att) * Nc).norm() < rt * (Fc.norm() + Nc.norm()));
    CHECK((Fd - double(tlm.thrust_scale_pos) * Fc).norm() < rt * (Fc.norm() + Nc.norm()));
    if (T > att_max) {
      CHECK(tlm.thrust_scale_att == 1);  // attitude first: whole
      CHECK(tlm.thrust_scale_pos > 0);
      CHECK(tlm.thrust_scale_pos < 1);
      CHECK(Fd.dot(Fc) / (Fd.norm() * Fc.norm()) > 1 - rt);
    } else {
      CHECK(tlm.thrust_scale_pos == 0);  // attitude alone saturates: position dropped
      CHECK(double(tlm.thrust_scale_att) == Approx(T / att_max).epsilon(1e-4));
    }
    CHECK(AllFinite(cmd));
  }
}

namespace {

// A random record: a plausible mid-run base with a random number of fields replaced by
// special or extreme values, or (one in eight) every byte random.
uvms_ctrl_sensors_t RandomSensors(std::mt19937_64 &rng, const uvms_ctrl_config_t &cfg, int64_t tick) {
  uvms_ctrl_sensors_t s;
  if (rng() % 8 == 0) {
    auto *b = reinterpret_cast<unsigned char *>(&s);
    for (size_t i = 0; i < sizeof s; ++i) b[i] = static_cast<unsigned char>(rng());
    s.tick = tick;  // (a random 64-bit tick would end the run: ticks must increase; below)
    return s;
  }
  s = MidRunSensors(cfg, tick, 0.03 * double(tick));
  std::uniform_real_distribution<double> ud(-1.0, 1.0);
  const double specials[] = {NAN, INFINITY, -INFINITY, 0.0, -0.0, 1e-40, 1e30, -1e30,
                             double(std::numeric_limits<uvms_real_t>::max()),
                             -double(std::numeric_limits<uvms_real_t>::max()), 6.3, 50.0};
  // Reals of the record, addressed uniformly.
  uvms_real_t *reals[64];
  size_t nr = 0;
  for (auto &x : s.position_m) reals[nr++] = &x;
  for (auto &x : s.quaternion_wxyz) reals[nr++] = &x;
  for (auto &x : s.velocity_m_s) reals[nr++] = &x;
  for (auto &x : s.angular_velocity_rad_s) reals[nr++] = &x;
  for (auto &x : s.joint_position_rad) reals[nr++] = &x;
  for (auto &x : s.joint_velocity_rad_s) reals[nr++] = &x;
  for (auto &x : s.motor_speed_rad_s) reals[nr++] = &x;
  for (auto &x : s.motor_current_A) reals[nr++] = &x;
  reals[nr++] = &s.time_s;
  const int edits = int(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    uvms_real_t &x = *reals[rng() % nr];
    switch (rng() % 3) {
      case 0: x = uvms_real_t(specials[rng() % (sizeof specials / sizeof specials[0])]); break;
      case 1: x = uvms_real_t(double(x) * std::pow(10.0, 6.0 * ud(rng))); break;
      default: x = uvms_real_t(double(x) + ud(rng)); break;
    }
  }
  if (rng() % 4 == 0) s.thruster_usable_mask = uint32_t(rng());
  switch (rng() % 16) {  // sequence faults
    case 0: s.tick = tick - 1 - int64_t(rng() % 3); break;
    case 1: s.tick = tick + 1 + int64_t(rng() % 5); break;
    default: break;
  }
  return s;
}

}  // namespace

TEST_CASE("EveryOutputIsFiniteAndWithinTheVoltageLimitForArbitraryRecords", "[controller]") {
  // Property over 4 configurations × 6000 random records (fixed seed): every command value is
  // finite; |V_j| ≤ voltage_limit_V; a thruster the record reports unusable gets exactly 0 V;
  // an error status comes with zero voltages; the thrust-limit scales lie in [0, 1]; the
  // rank and axes telemetry are consistent. The configurations: the paper's (hold 5, all
  // bounds on), every check off (so that absurd values reach the arithmetic), a tight voltage
  // limit (the clamp acts) and a tight thrust limit (the saturation acts), with the Cartesian
  // line in one of them.
  std::mt19937_64 rng(20240607);
  static uvms_ctrl_t ctrl;
  int statuses[7] = {0, 0, 0, 0, 0, 0, 0};
  uint32_t flags_seen = 0;
  for (int variant = 0; variant < 4; ++variant) {
    uvms_ctrl_config_t cfg;
    uvms_ctrl_config_paper(&cfg, variant == 3 ? 7 : 4);
    if (variant == 1) std::memset(&cfg.limits, 0, sizeof cfg.limits);
    if (variant == 2) {
      for (uvms_thruster_params_t &t : cfg.thruster) t.voltage_limit_V = 30;
    }
    if (variant == 3) {
      for (uvms_real_t &limit_N : cfg.limits.thrust_limit_N) limit_N = 0.2f;
      cfg.traj_mode = UVMS_TRAJ_CARTESIAN_LINE;
      cfg.cart.direction[0] = -1;
    }
    REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
    const double vmax = double(cfg.thruster[0].voltage_limit_V);
    int64_t tick = 0;
    for (int i = 0; i < 6000; ++i, ++tick) {
      if (i % 1000 == 999) {
        uvms_ctrl_reset(&ctrl);  // and the sequence restarts
        tick = 0;
      }
      const uvms_ctrl_sensors_t s = RandomSensors(rng, cfg, tick);
      if (s.tick > tick) tick = s.tick;  // a gap: the sequence goes on after it
      uvms_ctrl_command_t cmd;
      uvms_ctrl_telemetry_t tlm;
      std::memset(&cmd, 0x7F, sizeof cmd);  // garbage: every field must be written
      const uvms_status_t st = uvms_ctrl_step(&ctrl, &s, &cmd, &tlm);
      INFO("variant " << variant << " record " << i << " status " << st << " flags 0x" << std::hex
                      << tlm.flags);
      REQUIRE((st <= 0 && st >= UVMS_ERR_STATE));
      statuses[-st]++;
      flags_seen |= tlm.flags;
      REQUIRE(tlm.status == st);
      REQUIRE(AllFinite(cmd));
      for (double v : cmd.joint_ref_rad) REQUIRE(std::isfinite(v));
      for (double v : cmd.joint_ref_rate_rad_s) REQUIRE(std::isfinite(v));
      for (double v : cmd.joint_ref_accel_rad_s2) REQUIRE(std::isfinite(v));
      for (int j = 0; j < 8; ++j) {
        REQUIRE(std::fabs(double(cmd.motor_voltage_V[j])) <= vmax);
        if (((s.thruster_usable_mask >> j) & 1u) == 0u) REQUIRE(cmd.motor_voltage_V[j] == 0);
        if (st != UVMS_OK) REQUIRE(cmd.motor_voltage_V[j] == 0);
      }
      REQUIRE((tlm.thrust_scale_pos >= 0 && tlm.thrust_scale_pos <= 1));
      REQUIRE((tlm.thrust_scale_att >= 0 && tlm.thrust_scale_att <= 1));
      REQUIRE(tlm.uncontrollable_axes <= UVMS_AXIS_ALL);
      REQUIRE(((tlm.alloc_rank == 6) == (tlm.uncontrollable_axes == 0u) || tlm.alloc_rank == 0));
    }
  }
  INFO("OK " << statuses[0] << " NONFINITE " << statuses[2] << " RANGE " << statuses[4]
             << " flags seen 0x" << std::hex << flags_seen);
  // Non-vacuous: the records reach normal control, held ticks, refusals, rank loss, both
  // saturations and the voltage clamp.
  CHECK(statuses[0] > 5000);
  CHECK(statuses[2] > 100);
  CHECK(statuses[4] > 100);
  for (uint32_t f : {UVMS_FLAG_SENSOR_HELD, UVMS_FLAG_SENSOR_HOLD_EXPIRED, UVMS_FLAG_ALLOC_SINGULAR,
                     UVMS_FLAG_THRUST_SATURATED, UVMS_FLAG_VOLTAGE_SATURATED, UVMS_FLAG_MODEL_FAULT,
                     UVMS_FLAG_TICK_GAP, UVMS_FLAG_TICK_NOT_INCREASING}) {
    INFO("flag 0x" << std::hex << f);
    CHECK((flags_seen & f) != 0);
  }
}

TEST_CASE("CurrentCommandIntegratesItsRateAndRestartsFromZeroAfterASafeOutput", "[controller]") {
  // SPEC §7.4 [66] and §5 (current drive): I*_k of a tick is I*_(k−1) + İ*_(k−1)·tick, from
  // I*_0 = 0, with İ*_k = KB·(Î_k − I_k) from the measured current; after a safe output or a
  // tick on which the thruster was unusable (all zero) the command restarts from 0. Checked
  // against that recursion written out, on a mid-run sequence whose measured currents are
  // offset from the command.
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(cfg.drive == UVMS_DRIVE_CURRENT);  // the paper's reading is the default
  cfg.limits.sensor_hold_max_ticks = 0u;  // no hold: the rejected record at the end
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  double expect_A[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  for (int64_t k = 0; k < 20; ++k) {
    INFO("tick " << k);
    if (k > 0) s = MidRunSensors(cfg, k, 0.03 * double(k));
    // The measured current is not the command (an offset, as a sensor bias would give): the
    // command is the controller's own integral, never the measurement.
    for (int j = 0; j < 8; ++j) s.motor_current_A[j] = uvms_real_t(expect_A[j] + 0.05 + 0.01 * j);
    // Thruster 3 is unusable on ticks 8 and 9: no current then, and it restarts from 0.
    s.thruster_usable_mask = (k == 8 || k == 9) ? 0xFBu : 0xFFu;
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    for (int j = 0; j < 8; ++j) {
      if (j == 2 && (k == 8 || k == 9)) {
        CHECK(cmd.motor_current_cmd_A[j] == 0);
        CHECK(cmd.motor_current_rate_A_s[j] == 0);
        expect_A[j] = 0;
        continue;
      }
      CHECK(cmd.motor_current_cmd_A[j] == Approx(expect_A[j]).margin(1e-12));
      // İ* = KB·(Î − I) with the measured I (here the command's own value)
      CHECK(cmd.motor_current_rate_A_s[j] ==
            Approx(cfg.thruster[j].current_gain_1_s * (tlm.current_des_A[j] - s.motor_current_A[j]))
                .margin(1e-9));
      expect_A[j] = double(cmd.motor_current_cmd_A[j]) +
                    double(cmd.motor_current_rate_A_s[j]) * double(cfg.tick_s);
    }
  }
  double moved = 0;
  for (double x : expect_A) moved += std::abs(x);
  CHECK(moved > 1e-3);  // the sequence did command current
  // A rejected record that cannot be held (hold 0) → safe output, then the next good tick
  // starts from I* = 0.
  s = MidRunSensors(cfg, 20, 0.6);
  s.position_m[1] = uvms_real_t(NAN);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_HOLD_EXPIRED) != 0);
  for (double v : cmd.motor_current_cmd_A) CHECK(v == 0);
  for (double v : cmd.motor_current_rate_A_s) CHECK(v == 0);
  s = MidRunSensors(cfg, 21, 0.63);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  for (double v : cmd.motor_current_cmd_A) CHECK(v == 0);
}

TEST_CASE("AnUnknownDriveIsRejectedAtInitNamingTheDrive", "[controller]") {
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 7);
  cfg.drive = (uvms_drive_t)2;
  CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_ERR_RANGE);
  CHECK(ctrl.config_error == UVMS_CFG_DRIVE);
  CHECK(std::string(uvms_cfg_field_str(UVMS_CFG_DRIVE)) == "drive");
  CHECK(std::string(uvms_drive_str(UVMS_DRIVE_VOLTAGE)) == "voltage");
  cfg.drive = UVMS_DRIVE_VOLTAGE;
  CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
}

// ---- Issue 15, item 7: hardening ----------------------------------------------------------

namespace {

// A ready instance between guard bytes: a write outside the instance changes a guard.
struct GuardedCtrl {
  unsigned char before[256];
  uvms_ctrl_t ctrl;
  unsigned char after[256];
};

bool GuardsIntact(const GuardedCtrl &g) {
  for (unsigned char b : g.before) if (b != 0xA5) return false;
  for (unsigned char b : g.after) if (b != 0xA5) return false;
  return true;
}

// Every real of a telemetry record (tick and flags are integers).
bool TelemetryAllFinite(const uvms_ctrl_telemetry_t &t) {
  std::vector<double> v{double(t.time_s), double(t.thrust_scale_pos), double(t.thrust_scale_att)};
  auto add = [&v](const uvms_real_t *p, size_t n) { for (size_t i = 0; i < n; ++i) v.push_back(double(p[i])); };
  add(t.force_ff_N, 3); add(t.force_fb_N, 3); add(t.force_des_N, 3);
  add(t.moment_ff_Nm, 3); add(t.moment_fb_Nm, 3); add(t.moment_des_Nm, 3);
  add(t.thrust_des_N, UVMS_MAX_THRUSTERS); add(t.thrust_pos_N, UVMS_MAX_THRUSTERS);
  add(t.thrust_att_N, UVMS_MAX_THRUSTERS); add(t.omega_des_rad_s, UVMS_MAX_THRUSTERS);
  add(t.current_des_A, UVMS_MAX_THRUSTERS); add(t.advance_speed_m_s, UVMS_MAX_THRUSTERS);
  add(t.ee_estimate_m, 3); add(t.barycenter_m, 3); add(t.barycenter_v_m_s, 3);
  add(t.position_ref_m, 3); add(t.attitude_error_rad, 3); add(t.base_force_N, 3);
  add(t.base_moment_Nm, 3); add(t.base_accel_model_m_s2, 3);
  add(t.joint_torque_model_Nm, UVMS_MAX_JOINTS); add(t.force_deliverable_N, 3);
  add(t.moment_deliverable_Nm, 3);
  for (double x : v) if (!std::isfinite(x)) return false;
  return true;
}

// Tick k of a run at rest from the start pose, at the time its tick implies.
uvms_ctrl_sensors_t TickAt(const uvms_ctrl_config_t &cfg, int64_t k) {
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  s.tick = k;
  s.time_s = uvms_real_t(0.03 * double(k));
  return s;
}

// Initialise g on cfg and run its first tick (a good one); q_good: that tick's joint reference.
void StartWithOneGoodTick(GuardedCtrl &g, const uvms_ctrl_config_t &cfg, uvms_real_t q_good[UVMS_MAX_JOINTS]) {
  std::memset(&g, 0xA5, sizeof g);
  REQUIRE(uvms_ctrl_init(&g.ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  const uvms_ctrl_sensors_t s = TickAt(cfg, 0);
  REQUIRE(uvms_ctrl_step(&g.ctrl, &s, &cmd, &tlm) == UVMS_OK);
  std::memcpy(q_good, cmd.joint_ref_rad, sizeof(uvms_real_t) * UVMS_MAX_JOINTS);
}

// The next tick of a corrupted instance: UVMS_ERR_STATE, INSTANCE_INVALID, the safe output, finite
// telemetry and nothing written around the instance.
void CheckRefusedAsInvalid(GuardedCtrl &g, const uvms_ctrl_config_t &cfg, const uvms_real_t *q_good) {
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  const uvms_ctrl_sensors_t s = TickAt(cfg, 1);
  CHECK(uvms_ctrl_step(&g.ctrl, &s, &cmd, &tlm) == UVMS_ERR_STATE);
  CHECK((tlm.flags & UVMS_FLAG_INSTANCE_INVALID) != 0);
  CHECK(tlm.status == UVMS_ERR_STATE);
  CheckSafeOutput(cmd, q_good);
  CHECK(TelemetryAllFinite(tlm));
  CHECK(GuardsIntact(g));
}

}  // namespace

TEST_CASE("CorruptedCountsInAReadyInstanceWriteNothingOutsideAndGiveTheSafeOutput", "[controller]") {
  // cFE: validate whatever is used as an index. Each joint/thruster count of a ready instance
  // (every copy the tick reads, the caller's configuration included) set to huge values: the step returns UVMS_ERR_STATE with flag
  // INSTANCE_INVALID and the safe output, the bytes around the instance are untouched (and
  // host-asan sees no access outside), and the modules called directly with such a count stay
  // inside their arrays (their loops are clamped to the compile-time maxima).
  const size_t huge[] = {UVMS_MAX_JOINTS + UVMS_MAX_THRUSTERS, 64, 1000000, SIZE_MAX / 2, SIZE_MAX};
  const int cases[] = {4, 7};
  for (const int c : cases) {
    for (int which = 0; which < 5; ++which) {
      for (const size_t h : huge) {
        INFO("case " << c << " count " << which << " = " << h);
        static GuardedCtrl g;
        uvms_ctrl_config_t cfg;
        uvms_ctrl_config_paper(&cfg, c);
        if (which == 4) cfg.traj_mode = UVMS_TRAJ_CARTESIAN_LINE;
        uvms_real_t q_good[UVMS_MAX_JOINTS];
        StartWithOneGoodTick(g, cfg, q_good);
        switch (which) {
          case 0: g.ctrl.model.num_joints = h; break;
          case 1: g.ctrl.alloc.geom.num_thrusters = h; break;
          case 2: cfg.arm.num_joints = h; break;  // the configuration it points to
          case 3: cfg.thrusters.num_thrusters = h; break;
          default: g.ctrl.cart.n = h; break;
        }
        CheckRefusedAsInvalid(g, cfg, q_good);
      }
    }
  }
  // The modules themselves, called with a corrupted count.
  static GuardedCtrl g;
  std::memset(&g, 0xA5, sizeof g);
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 7);
  REQUIRE(uvms_ctrl_init(&g.ctrl, &cfg) == UVMS_OK);
  g.ctrl.model.num_joints = SIZE_MAX;
  g.ctrl.alloc.geom.num_thrusters = SIZE_MAX;
  uvms_real_t R0[9];
  uvms_m3_identity(R0);
  const uvms_real_t zero3[3] = {0, 0, 0};
  (void)uvms_arm_fk(&g.ctrl.model, &g.ctrl.data, zero3, R0, cfg.theta_start_rad);
  uvms_real_t J[6 * UVMS_MAX_JOINTS], Jcm[3 * UVMS_MAX_JOINTS];
  (void)uvms_arm_jacobian(&g.ctrl.model, &g.ctrl.data, J);
  (void)uvms_arm_barycenter_jacobian(&g.ctrl.model, &g.ctrl.data, Jcm);
  (void)uvms_alloc_set_usable(&g.ctrl.alloc, 0x7Fu);
  uvms_real_t P[UVMS_MAX_THRUSTERS], Pp[UVMS_MAX_THRUSTERS], Pa[UVMS_MAX_THRUSTERS];
  const uvms_real_t F[3] = {1, 2, 3}, N[3] = {0.1f, 0.2f, 0.3f};
  (void)uvms_alloc_step(&g.ctrl.alloc, R0, F, N, P, Pp, Pa);
  uvms_real_t w[6];
  (void)uvms_alloc_wrench_body(&g.ctrl.alloc, P, w);
  CHECK(GuardsIntact(g));
}

TEST_CASE("AModelThatDoesNotPointToTheConfigurationsArmIsAnInvalidInstance", "[controller]") {
  // The model reads its parameters through model.p (arm_model.h): a step whose model points
  // anywhere but cfg->arm (a corrupted pointer, or an instance copied next to another
  // configuration) returns UVMS_ERR_STATE with INSTANCE_INVALID and the safe output.
  uvms_ctrl_config_t cfg, other;
  uvms_ctrl_config_paper(&cfg, 7);
  uvms_ctrl_config_paper(&other, 7);
  const uvms_arm_params_t *const wrongs[] = {&other.arm, nullptr};
  for (const uvms_arm_params_t *wrong : wrongs) {
    static GuardedCtrl g;
    uvms_real_t q_good[UVMS_MAX_JOINTS];
    StartWithOneGoodTick(g, cfg, q_good);
    CHECK(g.ctrl.model.p == &cfg.arm);
    g.ctrl.model.p = wrong;
    CheckRefusedAsInvalid(g, cfg, q_good);
  }
}

TEST_CASE("ATimestampJumpForwardOrBackwardIsFlaggedAndHeld", "[controller]") {
  // time_s must be t_a + (tick − k_a)·tick_s (anchored at the first accepted record) within
  // UVMS_TIME_TOL_TICKS·tick_s + UVMS_TIME_TOL_ABS_S: a jump either way is TIME_IMPLAUSIBLE,
  // the record rejected and the last good one held (SENSOR_HELD, UVMS_OK) until the hold
  // budget runs out (SENSOR_HOLD_EXPIRED, UVMS_ERR_RANGE, safe output); jitter inside the
  // tolerance and tick gaps with the matching time are accepted; reset re-anchors.
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  // The anchor need not be at t = 0: the first record is tick 100 at 3.0 s.
  int64_t k = 100;
  auto at = [&](int64_t tick, double dt) {
    uvms_ctrl_sensors_t s = TickAt(cfg, tick);
    s.time_s = uvms_real_t(3.0 + 0.03 * double(tick - 100) + dt);
    return s;
  };
  uvms_ctrl_sensors_t s = at(k++, 0);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  for (const double jitter : {0.0, 0.01, -0.01, 0.015}) {
    s = at(k++, jitter);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((tlm.flags & (UVMS_FLAG_TIME_IMPLAUSIBLE | UVMS_FLAG_SENSOR_HELD)) == 0);
  }
  k += 3;  // a gap with the matching time: TICK_GAP only
  s = at(k++, 0);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TICK_GAP) != 0);
  CHECK((tlm.flags & UVMS_FLAG_TIME_IMPLAUSIBLE) == 0);
  for (const double jump : {1.0, -1.0, 0.03, -0.03, 1e9, -1e9}) {
    INFO("jump " << jump);
    s = at(k++, jump);
    CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK(tlm.flags == (UVMS_FLAG_TIME_IMPLAUSIBLE | UVMS_FLAG_SENSOR_HELD));
    CHECK(TelemetryAllFinite(tlm));
    s = at(k++, 0);  // back on the clock: accepted again
    CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((tlm.flags & (UVMS_FLAG_TIME_IMPLAUSIBLE | UVMS_FLAG_SENSOR_HELD)) == 0);
  }
  uvms_real_t q_good[UVMS_MAX_JOINTS];
  std::memcpy(q_good, cmd.joint_ref_rad, sizeof q_good);
  // A clock that stays off: held for sensor_hold_max_ticks, then the safe output.
  for (uint32_t i = 1; i <= cfg.limits.sensor_hold_max_ticks; ++i) {
    s = at(k++, 5.0);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((tlm.flags & UVMS_FLAG_SENSOR_HELD) != 0);
  }
  s = at(k++, 5.0);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_RANGE);
  CHECK(tlm.flags == (UVMS_FLAG_TIME_IMPLAUSIBLE | UVMS_FLAG_SENSOR_HOLD_EXPIRED));
  CheckSafeOutput(cmd, q_good);
  // After a restart of the sequence, reset re-anchors the clock.
  uvms_ctrl_reset(&ctrl);
  s = at(k++, 5.0);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TIME_IMPLAUSIBLE) == 0);
  // The largest tick: the tick difference is taken without signed overflow (UBSan).
  s = at(k, 0);
  s.tick = INT64_MAX;
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TIME_IMPLAUSIBLE) != 0);
}

TEST_CASE("CorrectlyRoundedTimesStayPlausibleOnLongRuns", "[controller]") {
  // time_s = k·tick_s rounded to the controller's real type must be accepted at any run length
  // (UVMS_TIME_TOL_REL): in float, from 2^17 s ≈ 36 h on, one ulp of time_s (15.6 ms) exceeds
  // half a tick, so a tolerance of 0.5 tick + 0.1 ms alone refused every record from then on
  // (tick 4,369,067 was the first refused). A jump of one second is still refused there.
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  // The sensor clock counts exact 0.03 s ticks (not cfg.tick_s, itself rounded to
  // uvms_real_t); its time is rounded once, to the record's type.
  REQUIRE(double(cfg.tick_s) == Approx(0.03).epsilon(1e-6));
  auto at = [&](int64_t tick, double dt_s) {
    uvms_ctrl_sensors_t s = TickAt(cfg, tick);
    s.time_s = uvms_real_t(double(tick) * 0.03 + dt_s);
    return s;
  };
  uvms_ctrl_sensors_t s = at(0, 0.0);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  // The first tick refused before (36.4 h) and its neighbours, then 1 year and 30 years.
  auto accepted = [&](int64_t k) {
    INFO("tick " << k);
    s = at(k, 0.0);
    CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    CHECK((tlm.flags & (UVMS_FLAG_TIME_IMPLAUSIBLE | UVMS_FLAG_SENSOR_HELD)) == 0);
  };
  for (const int64_t k : {int64_t{4369066}, int64_t{4369067}, int64_t{4369068}}) accepted(k);
  s = at(8738134, 1.0);  // after 72.8 h, a clock one second ahead: refused, held
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & (UVMS_FLAG_TIME_IMPLAUSIBLE | UVMS_FLAG_SENSOR_HELD)) ==
        (UVMS_FLAG_TIME_IMPLAUSIBLE | UVMS_FLAG_SENSOR_HELD));
  for (const int64_t k : {int64_t{8738135}, int64_t{1051200000}, int64_t{31536000000}})
    accepted(k);
}

TEST_CASE("TelemetryIsFiniteOnEveryFaultTick", "[controller]") {
  // Many fault kinds, each after a good tick, in cases I, IV and VII: whatever the status,
  // every real of the telemetry record is finite.
  using Fault = void (*)(uvms_ctrl_sensors_t &);
  const Fault faults[] = {
      [](uvms_ctrl_sensors_t &s) { s.time_s = uvms_real_t(NAN); },
      [](uvms_ctrl_sensors_t &s) { s.time_s = uvms_real_t(INFINITY); },
      [](uvms_ctrl_sensors_t &s) { s.time_s = uvms_real_t(-1e30); },
      [](uvms_ctrl_sensors_t &s) { s.position_m[1] = uvms_real_t(NAN); },
      [](uvms_ctrl_sensors_t &s) { s.position_m[0] = std::numeric_limits<uvms_real_t>::max(); },
      [](uvms_ctrl_sensors_t &s) { s.quaternion_wxyz[0] = 0; },
      [](uvms_ctrl_sensors_t &s) { s.quaternion_wxyz[2] = uvms_real_t(INFINITY); },
      [](uvms_ctrl_sensors_t &s) { s.velocity_m_s[0] = std::numeric_limits<uvms_real_t>::max(); },
      [](uvms_ctrl_sensors_t &s) { s.angular_velocity_rad_s[2] = uvms_real_t(-INFINITY); },
      [](uvms_ctrl_sensors_t &s) { s.joint_position_rad[3] = uvms_real_t(NAN); },
      [](uvms_ctrl_sensors_t &s) { s.joint_position_rad[0] = 100; },
      [](uvms_ctrl_sensors_t &s) { s.joint_velocity_rad_s[6] = std::numeric_limits<uvms_real_t>::max(); },
      [](uvms_ctrl_sensors_t &s) { s.motor_speed_rad_s[2] = uvms_real_t(NAN); },
      [](uvms_ctrl_sensors_t &s) { s.motor_current_A[5] = std::numeric_limits<uvms_real_t>::max(); },
      [](uvms_ctrl_sensors_t &s) { s.thruster_usable_mask = 0; },
      [](uvms_ctrl_sensors_t &s) { s.thruster_usable_mask = 0x0F; },
      [](uvms_ctrl_sensors_t &s) { s.tick -= 1; },
      [](uvms_ctrl_sensors_t &s) { s.tick += 1000; },
      [](uvms_ctrl_sensors_t &s) { s.time_s += 7; },
  };
  for (const int c : {1, 4, 7}) {
    for (uint32_t hold : {0u, 5u}) {
      for (size_t f = 0; f < sizeof faults / sizeof faults[0]; ++f) {
        INFO("case " << c << " hold " << hold << " fault " << f);
        static uvms_ctrl_t ctrl;
        uvms_ctrl_config_t cfg;
        uvms_ctrl_config_paper(&cfg, c);
        cfg.limits.sensor_hold_max_ticks = hold;
        // A zero bound disables a check: absurd values then reach the model and allocation.
        if (hold == 0u) {
          cfg.limits.max_vehicle_speed_m_s = 0;
          cfg.limits.max_joint_rate_rad_s = 0;
          cfg.limits.max_motor_current_A = 0;
        }
        REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
        uvms_ctrl_command_t cmd;
        uvms_ctrl_telemetry_t tlm;
        uvms_ctrl_sensors_t s = TickAt(cfg, 0);
        REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
        for (int64_t k = 1; k <= 3; ++k) {
          s = TickAt(cfg, k);
          faults[f](s);
          (void)uvms_ctrl_step(&ctrl, &s, &cmd, &tlm);
          CHECK(TelemetryAllFinite(tlm));
          CHECK(AllFinite(cmd));
        }
      }
    }
  }
}

// ---- feedforward lead (docs/MODEL.md §7.5) --------------------------------------------------

namespace {

// Tick k of a run whose arm follows the joint reference of the previous command (the sensed
// joints are last tick's θ_ref and θ̇_ref), so that the feedforward changes from tick to tick.
uvms_ctrl_sensors_t FollowingTick(const uvms_ctrl_config_t &cfg, int64_t k,
                                  const uvms_ctrl_command_t &last) {
  uvms_ctrl_sensors_t s = TickAt(cfg, k);
  if (k > 0) {
    for (int j = 0; j < 7; ++j) {
      s.joint_position_rad[j] = last.joint_ref_rad[j];
      s.joint_velocity_rad_s[j] = last.joint_ref_rate_rad_s[j];
    }
  }
  return s;
}

}  // namespace

namespace {

// A led and an unled instance stepped on the same records. After each tick, Check(gap)
// compares the led one's feedforward with W + τ·s, W the unled one's and s the slope of W
// low-passed over τ (docs/MODEL.md §7.5), written out here: this step's slope
// (W − W_last)/(gap·Δt), W_last that of the last tick that ran on a fresh record, and
// s += α·(slope − s), α = gap·Δt/(τ + gap·Δt), or s = slope when the filter restarts.
// Check(0): no lead expected; restart (first tick, failed tick, long gap) or not (held record).
struct LeadPair {
  uvms_ctrl_t off{}, on{};
  uvms_ctrl_config_t cfg_off{}, cfg_on{};
  uvms_ctrl_command_t c_off{}, c_on{};
  uvms_ctrl_telemetry_t t_off{}, t_on{}, last_fresh{};
  double tau{0}, max_rel{0}, max_lead_Nm{0}, s[6]{};
  bool have_s{false};

  explicit LeadPair(uint32_t hold_ticks) {
    uvms_ctrl_config_paper(&cfg_off, 4);
    cfg_off.fluid.gravity_m_s2[2] = uvms_real_t(-9.81);  // weight moments change as the arm moves
    cfg_off.limits.sensor_hold_max_ticks = hold_ticks;
    cfg_on = cfg_off;
    cfg_on.feedforward_lead = 1;
    REQUIRE(uvms_ctrl_init(&off, &cfg_off) == UVMS_OK);
    REQUIRE(uvms_ctrl_init(&on, &cfg_on) == UVMS_OK);
    tau = double(uvms_thruster_ramp_lag_s(&cfg_on.thruster[0]));
  }
  // Both instances on one record; returns the led one's status (the same as the other's).
  uvms_status_t Step(const uvms_ctrl_sensors_t &rec) {
    const uvms_status_t st = uvms_ctrl_step(&off, &rec, &c_off, &t_off);
    REQUIRE(uvms_ctrl_step(&on, &rec, &c_on, &t_on) == st);
    return st;
  }
  static double W(const uvms_ctrl_telemetry_t &t, int i) {
    return i < 3 ? double(t.force_ff_N[i]) : double(t.moment_ff_Nm[i - 3]);
  }
  void Check(int gap, bool restart = true) {
    if (gap == 0 && restart) have_s = false;
    const double dt = 0.03 * gap, alpha = dt / (tau + dt);
    for (int i = 0; i < 6; ++i) {
      double lead = 0;
      if (gap) {
        const double slope = (W(t_off, i) - W(last_fresh, i)) / dt;
        s[i] = have_s ? s[i] + alpha * (slope - s[i]) : slope;
        lead = tau * s[i];
      }
      const double want = W(t_off, i) + lead;
      max_rel = std::max(max_rel, std::abs(W(t_on, i) - want) / (1.0 + std::abs(want)));
      if (i >= 3) max_lead_Nm = std::max(max_lead_Nm, std::abs(lead));
    }
    if (gap) have_s = true;
  }
  void Fresh() { last_fresh = t_off; }  // this tick ran on its own record
};

const double kLeadTol = std::is_same<uvms_real_t, float>::value ? 1e-4 : 1e-10;

}  // namespace

TEST_CASE("TheFeedforwardLeadExtrapolatesTheUnledFeedforwardByTheChainsRampLag", "[controller][lead]") {
  // W_k + τ·(W_k − W_{k−1})/Δt (τ = (KB + b/J)/(KA·KB)), except on the first tick, the tick
  // after a failed one and across more than 4 ticks; over 2..4 ticks the slope is taken over
  // the ticks between the records.
  static LeadPair p(0);  // no hold: a rejected record fails its tick
  REQUIRE(p.tau == Approx(0.24).epsilon(1e-6));
  CHECK(p.on.ff_lead_s == uvms_real_t(p.tau));
  CHECK(p.off.ff_lead_s == 0);
  for (int64_t k = 0; k < 120; ++k) {
    REQUIRE(p.Step(FollowingTick(p.cfg_off, k, p.c_off)) == UVMS_OK);
    p.Check(k > 0 ? 1 : 0);
    p.Fresh();
  }
  INFO("largest lead term " << p.max_lead_Nm << " N·m");
  CHECK(p.max_lead_Nm > 1e-3);  // the arm moved: the test compares a lead that is there
  CHECK(p.max_rel <= kLeadTol);

  // A failed tick (NaN joint angle): the next good tick runs without lead, then leads again.
  uvms_ctrl_sensors_t bad = FollowingTick(p.cfg_off, 120, p.c_off);
  bad.joint_position_rad[2] = std::numeric_limits<uvms_real_t>::quiet_NaN();
  CHECK(p.Step(bad) != UVMS_OK);
  p.max_rel = 0;
  for (int64_t k = 121; k < 124; ++k) {
    REQUIRE(p.Step(FollowingTick(p.cfg_off, k, p.c_off)) == UVMS_OK);
    p.Check(k > 121 ? 1 : 0);
    p.Fresh();
  }
  // Records lost: 3 (gap 4 ticks, led over 4·Δt), then 4 (gap 5: no lead).
  REQUIRE(p.Step(FollowingTick(p.cfg_off, 127, p.c_off)) == UVMS_OK);
  p.Check(4);
  p.Fresh();
  REQUIRE(p.Step(FollowingTick(p.cfg_off, 132, p.c_off)) == UVMS_OK);
  p.Check(0);
  CHECK(p.max_rel <= kLeadTol);
}

TEST_CASE("TheLeadSkipsHeldRecordsAndIgnoresTheirTimeStamps", "[controller][lead]") {
  // With the hold on, rejected records are bridged by the last good one: those ticks run
  // without lead and are not differentiated against; the next fresh record is led by its slope
  // since the last fresh one, over the ticks between them. A record held for its implausible
  // time stamp (1 ms after the previous) changes nothing: the slope is taken over ticks.
  static LeadPair p(5);
  for (int64_t k = 0; k < 60; ++k) {
    REQUIRE(p.Step(FollowingTick(p.cfg_off, k, p.c_off)) == UVMS_OK);
    p.Check(k > 0 ? 1 : 0);
    p.Fresh();
  }
  for (int64_t k = 60; k < 62; ++k) {  // two rejected records, held
    uvms_ctrl_sensors_t bad = FollowingTick(p.cfg_off, k, p.c_off);
    bad.joint_position_rad[2] = std::numeric_limits<uvms_real_t>::quiet_NaN();
    REQUIRE(p.Step(bad) == UVMS_OK);
    REQUIRE((p.t_on.flags & UVMS_FLAG_SENSOR_HELD) != 0u);
    p.Check(0, false);  // no lead; the filter keeps its slope
  }
  REQUIRE(p.Step(FollowingTick(p.cfg_off, 62, p.c_off)) == UVMS_OK);
  p.Check(3);  // led over ticks 59 → 62
  p.Fresh();
  uvms_ctrl_sensors_t early = FollowingTick(p.cfg_off, 63, p.c_off);
  early.time_s = p.t_off.time_s + uvms_real_t(0.001);
  REQUIRE(p.Step(early) == UVMS_OK);
  REQUIRE((p.t_on.flags & UVMS_FLAG_SENSOR_HELD) != 0u);
  p.Check(0, false);
  REQUIRE(p.Step(FollowingTick(p.cfg_off, 64, p.c_off)) == UVMS_OK);
  p.Check(2);  // over ticks 62 → 64, not over the 1 ms of the held record
  INFO("largest lead term " << p.max_lead_Nm << " N·m");
  CHECK(p.max_lead_Nm > 1e-3);
  CHECK(p.max_rel <= kLeadTol);
}

TEST_CASE("TheFeedforwardLeadIsRejectedOutsideZeroOneAndWithTheVoltageDrive", "[controller][lead]") {
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  CHECK(cfg.feedforward_lead == 0);  // the paper's feedforward
  cfg.feedforward_lead = 2;
  CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_ERR_RANGE);
  CHECK(ctrl.config_error == UVMS_CFG_FEEDFORWARD_LEAD);
  CHECK(std::string(uvms_cfg_field_str(UVMS_CFG_FEEDFORWARD_LEAD)) == "feedforward_lead");
  cfg.feedforward_lead = 1;
  cfg.drive = UVMS_DRIVE_VOLTAGE;
  CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_ERR_RANGE);
  CHECK(ctrl.config_error == UVMS_CFG_FEEDFORWARD_LEAD);
  cfg.drive = UVMS_DRIVE_CURRENT;
  CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
}

TEST_CASE("TheLeadFunctionFiltersTheSlopeAndRefusesABadLeadOrInterval", "[lead]") {
  const uvms_real_t w[2] = {2, -1}, prev[2] = {1, 1};
  uvms_real_t out[2], slope[2] = {0, 0};
  // First step: the slope is this step's, (w − w_prev)/dt = (1/0.03, −2/0.03).
  REQUIRE(uvms_ff_lead(2, w, prev, uvms_real_t(0.03), uvms_real_t(0.24), slope, 0, out) == UVMS_OK);
  CHECK(double(slope[0]) == Approx(1 / 0.03));
  CHECK(double(out[0]) == Approx(2 + 0.24 / 0.03 * 1));
  CHECK(double(out[1]) == Approx(-1 + 0.24 / 0.03 * -2));
  // Next step with a zero slope: the filter moves by α = 0.03/(0.24 + 0.03) = 1/9 toward it.
  const uvms_real_t same[2] = {2, -1};
  REQUIRE(uvms_ff_lead(2, same, w, uvms_real_t(0.03), uvms_real_t(0.24), slope, 1, out) == UVMS_OK);
  CHECK(double(slope[0]) == Approx(1 / 0.03 * 8.0 / 9.0));
  CHECK(double(out[0]) == Approx(2 + 0.24 * (1 / 0.03) * 8.0 / 9.0));
  const uvms_real_t kept = slope[0];
  CHECK(uvms_ff_lead(2, w, prev, uvms_real_t(0.03), uvms_real_t(-0.1), slope, 1, out) == UVMS_ERR_RANGE);
  CHECK((out[0] == w[0] && out[1] == w[1] && slope[0] == kept));  // safe output: no lead
  CHECK(uvms_ff_lead(2, w, prev, uvms_real_t(0), uvms_real_t(0.24), slope, 1, out) == UVMS_ERR_RANGE);
  CHECK(uvms_ff_lead(2, w, prev, uvms_real_t(INFINITY), uvms_real_t(0.24), slope, 1, out) == UVMS_ERR_RANGE);
  CHECK(uvms_ff_lead(2, w, nullptr, uvms_real_t(0.03), uvms_real_t(0.24), slope, 1, out) == UVMS_ERR_ARG);
}
