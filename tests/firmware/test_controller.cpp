// Controller: configuration validation (one specific status and field per problem), Table X
// switches, safe outputs on bad sensors, and the consistency of one tick's outputs with the
// modules it composes (allocation reproduces the desired wrench, estimates match kinematics).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
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
  s.omega_rad_s[1] = 0.002f;
  for (int j = 0; j < 7; ++j) {
    s.q_rad[j] = uvms_real_t(cfg.theta_start_rad[j] +
                             0.3 * (cfg.theta_final_rad[j] - cfg.theta_start_rad[j]));
    s.qd_rad_s[j] = uvms_real_t(0.02 * (j + 1));
  }
  for (int m = 0; m < 8; ++m) {
    s.motor_speed_rad_s[m] = uvms_real_t(-30.0 + 9.0 * m);
    s.motor_current_A[m] = uvms_real_t(0.2 * m - 0.5);
  }
  return s;
}

// The safe output of controller.h, with θ_ref held at q_ref_want.
void CheckSafeOutput(const uvms_ctrl_command_t &cmd, const uvms_real_t *q_ref_want) {
  for (double v : cmd.motor_voltage_V) CHECK(v == 0);
  for (int j = 0; j < 7; ++j) {
    INFO("joint " << j + 1);
    CHECK(cmd.joint_accel_cmd_rad_s2[j] == 0);
    CHECK(cmd.qd_ref_rad_s[j] == 0);
    CHECK(cmd.qdd_ref_rad_s2[j] == 0);
    CHECK(cmd.q_ref_rad[j] == q_ref_want[j]);
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
  uvms_ctrl_sensors_t s = StartSensors(cfg);
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

  // A usable thruster's NaN sensor is still a sensor fault of the tick.
  uvms_ctrl_sensors_t s = MidRunSensors(cfg, 2, 20.03);
  s.motor_current_A[2] = uvms_real_t(NAN);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
  CHECK((tlm.flags & UVMS_FLAG_SENSOR_NONFINITE) != 0);
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
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 4);
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;

  // Before the first good tick the held reference is θI.
  uvms_ctrl_sensors_t s = MidRunSensors(cfg, 0, 20.0);
  s.q_rad[3] = uvms_real_t(NAN);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
  CheckSafeOutput(cmd, cfg.theta_start_rad);

  // Good ticks mid-trajectory: the reference is away from θI and the servo is active.
  s = StartSensors(cfg);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  s = MidRunSensors(cfg, 1, 20.0);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  uvms_real_t q_good[7];
  for (int j = 0; j < 7; ++j) q_good[j] = cmd.q_ref_rad[j];
  double servo = 0, moved = 0;
  for (int j = 0; j < 7; ++j) {
    servo += std::fabs(double(cmd.joint_accel_cmd_rad_s2[j]));
    moved += std::fabs(double(q_good[j]) - double(cfg.theta_start_rad[j]));
  }
  REQUIRE(servo > 0.1);
  REQUIRE(moved > 0.1);

  SECTION("sensor fault") {
    s = MidRunSensors(cfg, 2, 20.03);
    s.omega_rad_s[0] = uvms_real_t(INFINITY);
    CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
    CheckSafeOutput(cmd, q_good);
  }
  SECTION("arm model / feedforward failure") {
    // Simulated corruption: the model's ready flag cleared (uvms_feedforward → STATE).
    ctrl.model.ready = 0;
    s = MidRunSensors(cfg, 2, 20.03);
    CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_STATE);
    CHECK((tlm.flags & UVMS_FLAG_MODEL_FAULT) != 0);
    CheckSafeOutput(cmd, q_good);
    ctrl.model.ready = 1;
  }
  SECTION("allocation failure") {
    // A finite but absurd velocity: K_DF·v overflows the real type, the desired force is
    // infinite and uvms_alloc_step refuses it (NONFINITE).
    s = MidRunSensors(cfg, 2, 20.03);
    s.velocity_m_s[0] = uvms_real_t(kFloat ? 1e37 : 1e307);
    CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_ERR_NONFINITE);
    CHECK((tlm.flags & UVMS_FLAG_MODEL_FAULT) != 0);
    CheckSafeOutput(cmd, q_good);
  }
  // After the fault, a good tick commands normally again.
  s = MidRunSensors(cfg, 3, 20.06);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK(AllFinite(cmd));
}

TEST_CASE("RankLossIdlesTheThrustersWhileTheArmKeepsFollowingItsTrajectory", "[controller]") {
  // Two identical controllers see the same ticks; one loses thrusters 5–8 (only the four x
  // thrusters left: rank 4 < 6). It must return UVMS_ERR_SINGULAR with every voltage 0 and the
  // very same joint command as the healthy one (controller.h: rank loss is not an arm error);
  // that command is then the last good reference an error holds.
  static uvms_ctrl_t healthy, degraded;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 7);
  REQUIRE(uvms_ctrl_init(&healthy, &cfg) == UVMS_OK);
  REQUIRE(uvms_ctrl_init(&degraded, &cfg) == UVMS_OK);
  uvms_ctrl_command_t ch, cd;
  uvms_ctrl_telemetry_t th, td;
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  REQUIRE(uvms_ctrl_step(&healthy, &s, &ch, &th) == UVMS_OK);
  REQUIRE(uvms_ctrl_step(&degraded, &s, &cd, &td) == UVMS_OK);

  s = MidRunSensors(cfg, 1, 20.0);
  REQUIRE(uvms_ctrl_step(&healthy, &s, &ch, &th) == UVMS_OK);
  s.thruster_usable_mask = 0x0Fu;
  REQUIRE(uvms_ctrl_step(&degraded, &s, &cd, &td) == UVMS_ERR_SINGULAR);
  CHECK(td.status == UVMS_ERR_SINGULAR);
  CHECK((td.flags & UVMS_FLAG_ALLOC_SINGULAR) != 0);
  for (double v : cd.motor_voltage_V) CHECK(v == 0);
  for (int j = 0; j < 7; ++j) {
    INFO("joint " << j + 1);
    CHECK(cd.joint_accel_cmd_rad_s2[j] == ch.joint_accel_cmd_rad_s2[j]);
    CHECK(cd.q_ref_rad[j] == ch.q_ref_rad[j]);
    CHECK(cd.qd_ref_rad_s[j] == ch.qd_ref_rad_s[j]);
    CHECK(cd.qdd_ref_rad_s2[j] == ch.qdd_ref_rad_s2[j]);
  }
  double servo = 0;
  for (double a : cd.joint_accel_cmd_rad_s2) servo += std::fabs(a);
  CHECK(servo > 0.1);
  // The desired wrench is still reported (what the vehicle would need).
  CHECK((V(td.force_des_N) - V(th.force_des_N)).norm() == 0.0);
  CHECK((V(td.moment_des_Nm) - V(th.moment_des_Nm)).norm() == 0.0);

  // An error on the next tick holds the reference of the rank-loss tick.
  uvms_real_t q_sing[7];
  for (int j = 0; j < 7; ++j) q_sing[j] = cd.q_ref_rad[j];
  s = MidRunSensors(cfg, 2, 20.03);
  s.thruster_usable_mask = 0x0Fu;
  s.time_s = uvms_real_t(NAN);
  CHECK(uvms_ctrl_step(&degraded, &s, &cd, &td) == UVMS_ERR_NONFINITE);
  CheckSafeOutput(cd, q_sing);
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
  for (double v : cmd.q_ref_rad) CHECK(v == 0);  // no controller: no reference known
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
  // is simulated by corrupting the stored start pose (init validated the real one).
  static uvms_ctrl_t ctrl;
  const uvms_ctrl_config_t cfg = CartesianCaseFour();
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  uvms_ctrl_sensors_t s = StartSensors(cfg);
  const uvms_real_t keep = ctrl.theta_start_rad[2];
  ctrl.theta_start_rad[2] = uvms_real_t(NAN);
  CHECK(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) != UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TRAJECTORY_FAULT) != 0);
  CheckSafeOutput(cmd, cfg.theta_start_rad);

  ctrl.theta_start_rad[2] = keep;
  s.tick = 1;
  s.time_s = uvms_real_t(0.03);
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_REFERENCE_CAPTURED) != 0);
  CHECK(ctrl.cart.ready == 1);
  for (int j = 0; j < 7; ++j) {
    CHECK(double(cmd.q_ref_rad[j]) == Approx(double(cfg.theta_start_rad[j])).margin(1e-3));
    CHECK(std::fabs(double(cmd.joint_accel_cmd_rad_s2[j])) < 1.0);
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
  for (int j = 0; j < 7; ++j) q_good[j] = cmd.q_ref_rad[j];
  ctrl.cart.ready = 0;
  s.tick = 3;
  s.time_s = uvms_real_t(0.09);
  s.q_rad[1] += uvms_real_t(0.01);  // off the reference: the servo must pull joint 2 back
  REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
  CHECK((tlm.flags & UVMS_FLAG_TRAJECTORY_FAULT) != 0);
  for (int j = 0; j < 7; ++j) {
    INFO("joint " << j + 1);
    CHECK(cmd.q_ref_rad[j] == q_good[j]);
    CHECK(cmd.qd_ref_rad_s[j] == 0);
    CHECK(cmd.qdd_ref_rad_s2[j] == 0);
  }
  CHECK(double(cmd.joint_accel_cmd_rad_s2[1]) < -0.5);  // Kq·(−0.01 rad) = −1 rad/s²
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
    uvms_ctrl_sensors_t s = StartSensors(cfg);
    const Eigen::Vector3d r00(0.2, -0.1, 0.05);
    Put(r00, s.position_m);
    const Eigen::Quaterniond q0(Eigen::AngleAxisd(0.1, Eigen::Vector3d(1, -1, 2).normalized()));
    SetQuat(s, q0);
    s.velocity_m_s[1] = 0.002f;
    for (int j = 0; j < 7; ++j) s.qd_rad_s[j] = uvms_real_t(0.01 * (7 - j));
    uvms_ctrl_command_t cmd;
    uvms_ctrl_telemetry_t tlm;
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &tlm) == UVMS_OK);
    uvms_real_t R00[9];
    Put(Eigen::Matrix3d(q0.toRotationMatrix()), R00);
    REQUIRE(uvms_arm_fk(&model, &d, s.position_m, R00, s.q_rad) == UVMS_OK);
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
    Put(V(s.omega_rad_s), base.omega_rad_s);
    uvms_feedforward_t ff;
    REQUIRE(uvms_feedforward(&model, &d, &cfg.fluid, cfg.switches.position_reference, &base, s.q_rad,
                             s.qd_rad_s, cmd.joint_accel_cmd_rad_s2, &ff) == UVMS_OK);
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
