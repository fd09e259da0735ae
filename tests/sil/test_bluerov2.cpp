// SPDX-License-Identifier: Apache-2.0
// The second vehicle (docs/MODEL.md §12, sil/scenarios/bluerov2/bluerov2_heavy_alpha5.toml) in
// both models, as the scenario reader builds them: the firmware's feedforward equals the
// plant's holding wrench at random states (the cross-check of tests/plant/
// test_plant_vs_firmware.cpp, on this description: 4 DH links, Fossen damping, Earth gravity,
// trim ballast), and with no fluid and no gravity the barycenter stays put while the arm moves.
#include <catch2/catch.hpp>

#include <cstdio>
#include <random>

#include "scenario/scenario.hpp"
#include "uvms/arm_model.h"
#include "uvms/dynamics.h"
#include "uvms/feedforward.h"
#include "uvms_plant/plant.hpp"

using namespace uvms;
using plant::Mat3;
using plant::Vec3;

namespace {

const std::string kScenario = std::string(UVMS_SOURCE_DIR) + "/sil/scenarios/bluerov2/bluerov2_heavy_alpha5.toml";

template <class V>
void Put(const V &v, uvms_real_t *out, int n) {
  for (int i = 0; i < n; ++i) out[i] = uvms_real_t(v[i]);
}

/// A random joint state inside each joint's limits.
std::vector<double> RandomAngles(const sil::Scenario &s, std::mt19937 &rng) {
  std::vector<double> q;
  for (size_t i = 0; i < s.controller.arm.num_joints; ++i) {
    const auto &L = s.controller.arm.link[i];
    std::uniform_real_distribution<double> u(double(L.joint_min_rad), double(L.joint_max_rad));
    q.push_back(u(rng));
  }
  return q;
}

}  // namespace

TEST_CASE("BlueROV2FeedforwardEqualsThePlantsHoldingWrench", "[bluerov2][crosscheck]") {
  const sil::Scenario s = sil::LoadScenario(kScenario, {});
  REQUIRE(s.controller.arm.num_joints == 4);
  REQUIRE(s.controller.thrusters.num_thrusters == 8);
  REQUIRE(s.controller.arm.vehicle.ballast_kg != 0);  // trimmed at Earth gravity
  uvms_arm_model_t fm;
  REQUIRE(uvms_arm_model_init(&s.controller.arm, &fm) == UVMS_OK);
  REQUIRE(fm.vehicle_damping == 1);
  const double rel_tol = UVMS_REAL_IS_FLOAT ? 2e-4 : 1e-9;
  const double scale = (13.734 + 1.038 + 0.5) * 9.81;  // the weights that cancel, M·g [N]
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> nd(0.0, 1.0);
  static uvms_arm_data_t fd;
  double worst = 0.0;
  for (int trial = 0; trial < 50; ++trial) {
    plant::PlantParams p = s.plant;
    p.env.steady_flow_m_s = Vec3(u(rng), u(rng), u(rng)) * 0.1;
    p.contact.enabled = false;
    plant::Plant pl(p);
    plant::InitialState init;
    init.attitude = trial == 0 ? Eigen::Quaterniond::Identity()
                               : Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized();
    init.v0_m_s = Vec3(u(rng), u(rng), u(rng)) * 0.3;  // ω0 = 0: SPEC §7's model of the vehicle
    init.q_rad = RandomAngles(s, rng);
    plant::PlantInputs in;
    in.motor_voltage_V.assign(8, 0.0);
    in.motor_current_cmd_A.assign(8, 0.0);
    in.motor_current_rate_A_s.assign(8, 0.0);
    for (size_t j = 0; j < 4; ++j) {
      init.qd_rad_s.push_back(u(rng) * 0.5);
      in.joint_accel_rad_s2.push_back(u(rng) * 1.0);
    }
    pl.Reset(init);
    const plant::Wrench hold = pl.HoldingWrench(in);

    uvms_base_state_t fb{};
    const Mat3 R0 = init.attitude.toRotationMatrix();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) fb.R0[3 * r + c] = uvms_real_t(R0(r, c));
    Put(init.v0_m_s, fb.velocity_m_s, 3);
    uvms_fluid_t ff = s.controller.fluid;
    Put(p.env.steady_flow_m_s, ff.flow_m_s, 3);
    uvms_real_t q[4], qd[4], qdd[4];
    Put(init.q_rad, q, 4);
    Put(init.qd_rad_s, qd, 4);
    Put(in.joint_accel_rad_s2, qdd, 4);
    uvms_feedforward_t w;
    REQUIRE(uvms_feedforward(&fm, &fd, &ff, UVMS_REF_VEHICLE, &fb, q, qd, qdd, &w) == UVMS_OK);
    const Vec3 F(w.force_vehicle_N[0], w.force_vehicle_N[1], w.force_vehicle_N[2]);
    const Vec3 N(w.moment_att_Nm[0], w.moment_att_Nm[1], w.moment_att_Nm[2]);
    INFO("trial " << trial << " force plant " << hold.force_N.transpose() << " firmware "
                  << F.transpose() << " moment plant " << hold.moment_Nm.transpose()
                  << " firmware " << N.transpose());
    CHECK((hold.force_N - F).norm() <= rel_tol * scale);
    CHECK((hold.moment_Nm - N).norm() <= rel_tol * scale);
    worst = std::max({worst, (hold.force_N - F).norm() / scale, (hold.moment_Nm - N).norm() / scale});
    if (trial == 0) CHECK(hold.force_N.norm() > 1.0);  // the damping and the arm: not trivially 0
  }
  std::printf("BlueROV2 + Alpha 5: feedforward vs plant holding wrench, worst relative difference "
              "%.2e (of M·g) over 50 states\n", worst);
}

TEST_CASE("BlueROV2BarycenterStaysPutWithoutFluidOrGravity", "[bluerov2][conservation]") {
  // ρ = 0 (no buoyancy, drag, damping or added mass), g = 0, no thrust: only internal forces,
  // so the barycenter of vehicle + arm + payload stays where it was while the arm makes the
  // scenario's motion (SPEC §5's conservation check, on this description).
  const sil::Scenario s = sil::LoadScenario(kScenario, {});
  plant::PlantParams p = s.plant;
  p.env.density_kg_m3 = 0.0;
  p.env.gravity_m_s2 = Vec3::Zero();
  p.env.trim = false;
  p.vehicle.added_mass_kg.reset();
  for (int k = 0; k < 6; ++k) p.vehicle.linear_damping[k] = p.vehicle.quadratic_damping[k] = 0.0;
  p.contact.enabled = false;
  plant::Plant pl(p);
  plant::InitialState init;
  init.q_rad = s.initial.q_rad;
  pl.Reset(init);
  const Vec3 cm0 = pl.truth().barycenter_m;
  plant::PlantInputs in;
  in.motor_voltage_V.assign(8, 0.0);
  in.motor_current_cmd_A.assign(8, 0.0);
  in.motor_current_rate_A_s.assign(8, 0.0);
  const double tF = 5.0, dt = 0.03;
  double drift = 0.0, moved = 0.0;
  for (int k = 0; k < 167; ++k) {
    // A cycloid of every joint from θI towards θF over tF: q̈ = Δ·2π/tF²·sin(2πt/tF).
    const double t = (k + 0.5) * dt;
    in.joint_accel_rad_s2.clear();
    for (size_t j = 0; j < 4; ++j) {
      const double delta = double(s.controller.theta_final_rad[j] - s.controller.theta_start_rad[j]);
      in.joint_accel_rad_s2.push_back(delta * 2.0 * M_PI / (tF * tF) * std::sin(2.0 * M_PI * t / tF));
    }
    REQUIRE(pl.Step(in, dt).ok());
    drift = std::max(drift, (pl.truth().barycenter_m - cm0).norm());
    moved = std::max(moved, pl.truth().r0_m.norm());
  }
  std::printf("BlueROV2 + Alpha 5 without fluid or gravity: barycenter drift %.2e m, vehicle "
              "moved %.4f m\n", drift, moved);
  CHECK(moved > 0.005);  // the arm really pushed the 14 kg vehicle
  CHECK(drift < 1e-6);   // the integrator's tolerance (rel 1e-8) over 167 restarts
}
