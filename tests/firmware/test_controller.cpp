// Controller: configuration validation (one specific status and field per problem), Table X
// switches, safe outputs on bad sensors, and the consistency of one tick's outputs with the
// modules it composes (allocation reproduces the desired wrench, estimates match kinematics).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "fw_test_util.hpp"
#include "uvms/controller.h"
#include "uvms/kinematics.h"

using namespace fwtest;

namespace {

uvms_ctrl_sensors_t StartSensors(const uvms_ctrl_config_t &cfg) {
  uvms_ctrl_sensors_t s;
  std::memset(&s, 0, sizeof s);
  s.quaternion_wxyz[0] = 1;
  for (int j = 0; j < 7; ++j) s.q_rad[j] = cfg.theta_start_rad[j];
  s.thruster_usable_mask = 0xFF;
  return s;
}

bool AllFinite(const uvms_ctrl_command_t &c) {
  for (double v : c.motor_voltage_V) if (!std::isfinite(v)) return false;
  for (double v : c.joint_accel_cmd_rad_s2) if (!std::isfinite(v)) return false;
  return true;
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
       [](uvms_ctrl_config_t &c) { c.thruster.resistance_ohm = 0; }},
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
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  s.motor_current_A[4] = uvms_real_t(NAN);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_NONFINITE) != 0);
  CHECK(AllFinite(cmd));
  for (double v : cmd.motor_voltage_V) CHECK(v == 0);

  s = StartSensors(cfg);
  s.quaternion_wxyz[0] = 0;  // |q| = 0
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_RANGE);
  CHECK((tlm.flags & UVMS_FLAG_QUATERNION_INVALID) != 0);
  CHECK(AllFinite(cmd));

  s = StartSensors(cfg);
  s.q_rad[1] = uvms_real_t(INFINITY);
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
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_REFERENCE_CAPTURED) != 0);
  s.tick = 3;
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TICK_GAP) != 0);
  CHECK((tlm.flags & UVMS_FLAG_REFERENCE_CAPTURED) == 0);
  s.tick = 3;
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TICK_NOT_INCREASING) != 0);
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
    uvms_ctrl_sensors_t s = StartSensors(cfg);
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
    s.omega_rad_s[1] = 0.002f;
    for (int j = 0; j < 7; ++j) {
      s.q_rad[j] = uvms_real_t(cfg.theta_start_rad[j] + 0.3 * (cfg.theta_final_rad[j] - cfg.theta_start_rad[j]));
      s.qd_rad_s[j] = uvms_real_t(0.02 * (j + 1));
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
      REQUIRE(uvms_arm_fk(&ctrl.model, &d, origin, Rd, s.q_rad) == UVMS_OK);
      ee_est = cm0 + V(d.ee_m) - V(d.barycenter_m);
      CHECK(V(tlm.force_fb_N).norm() > 0);  // feedback on the barycenter is active
    } else {
      REQUIRE(uvms_arm_fk(&ctrl.model, &d, origin, Rd, s.q_rad) == UVMS_OK);
      ee_est = V(d.ee_m);
    }
    CHECK((V(tlm.ee_estimate_m) - ee_est).norm() < (kFloat ? 1e-5 : 1e-12));
  }
}
