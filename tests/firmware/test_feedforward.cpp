// SPDX-License-Identifier: Apache-2.0
// Feedforward wrenches (SPEC §7.1) and PD feedback (SPEC §7.2) checked against physical
// identities that do not use the feedforward code's own formulas.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <random>

#include "fw_test_util.hpp"
#include "uvms/dynamics.h"
#include "uvms/feedback.h"
#include "uvms/feedforward.h"
#include "uvms/kinematics.h"
#include "uvms/trajectory.h"

using namespace fwtest;

namespace {
constexpr double kTolScale = kFloat ? 1e-4 : 1e-11;

uvms_base_state_t MovingBase() {
  uvms_base_state_t b{};
  Put(Eigen::Vector3d(0.4, -0.3, 2.0), b.position_m);
  Put(Eigen::Matrix3d(Eigen::AngleAxisd(0.5, Eigen::Vector3d(0.2, 1, -0.3).normalized()).toRotationMatrix()), b.R0);
  Put(Eigen::Vector3d(0.05, -0.02, 0.01), b.velocity_m_s);
  Put(Eigen::Vector3d(0.01, 0.02, -0.03), b.omega_rad_s);
  return b;
}
const uvms_real_t kQ[7] = {3.0f, 1.2f, 3.3f, 2.5f, 0.4f, 0.8f, 0.6f};
const uvms_real_t kQd[7] = {0.1f, -0.2f, 0.15f, 0.3f, -0.25f, 0.2f, 0.1f};
const uvms_real_t kQdd[7] = {0.3f, 0.2f, -0.4f, 0.5f, 0.1f, -0.3f, 0.6f};
}  // namespace

TEST_CASE("BarycenterAssumptionClosesNewtonsThirdLawForTheVehicle", "[feedforward]") {
  // With no external forces (ρ = 0, g = 0) and no thrust, the vehicle obeys m0·v̇0 = −f1.
  // The barycenter assumption's v̇0 (from momentum conservation of the rigid masses) must be
  // exactly the acceleration the arm's reaction f1 then imparts; and F_r,cm = 0.
  const auto m = PaperModel(10.0);
  static uvms_arm_data_t d;
  uvms_fluid_t fl{};
  const uvms_base_state_t b = MovingBase();
  uvms_feedforward_t ff;
  REQUIRE(uvms_feedforward(&m, &d, &fl, UVMS_REF_BARYCENTER, &b, kQ, kQd, kQdd, &ff) == UVMS_OK);
  const Eigen::Vector3d a0 = V(ff.base_accel_m_s2), f1 = V(ff.base_force_N);
  CHECK(a0.norm() > 1e-3);  // the arm really pushes the vehicle
  CHECK((double(m.p->vehicle.mass_kg) * a0 + f1).norm() < kTolScale * 100 * f1.norm() + 1e-12);
  CHECK(V(ff.force_barycenter_N).norm() == 0.0);
  // Vehicle reference assumes a still vehicle; F_r,0 = f1 (no drag, no weight).
  REQUIRE(uvms_feedforward(&m, &d, &fl, UVMS_REF_VEHICLE, &b, kQ, kQd, kQdd, &ff) == UVMS_OK);
  CHECK(V(ff.base_accel_m_s2).norm() == 0.0);
  CHECK((V(ff.force_vehicle_N) - V(ff.base_force_N)).norm() == 0.0);
}

TEST_CASE("AtRestBothForceFeedforwardsEqualNetWeightMinusBuoyancy", "[feedforward]") {
  // Arm and vehicle at rest in still water under gravity: every reaction is hydrostatic, so
  // [31] and [32] both equal −(total weight + total buoyancy) = (ρ·V_total − m_total)·g.
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  p.vehicle.ballast_kg = 3.5f;  // weight-only trim mass is part of the weight
  uvms_arm_model_t m;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);
  static uvms_arm_data_t d;
  uvms_fluid_t fl{};
  fl.density_kg_m3 = 1025;
  fl.gravity_m_s2[2] = uvms_real_t(-9.81);
  uvms_base_state_t b{};
  uvms_m3_identity(b.R0);
  const uvms_real_t z[7] = {0, 0, 0, 0, 0, 0, 0};
  uvms_feedforward_t ff;
  for (const auto ref : {UVMS_REF_VEHICLE, UVMS_REF_BARYCENTER}) {
    REQUIRE(uvms_feedforward(&m, &d, &fl, ref, &b, kQ, z, z, &ff) == UVMS_OK);
    double vol = 0.15, mass = 120 + 3.5 + 10;
    for (int i = 1; i <= 7; ++i) {
      vol += double(m.volume_m3[i]);
      mass += double(p.link[i - 1].mass_kg);
    }
    const Eigen::Vector3d want(0, 0, (1025 * vol - mass) * -9.81);
    CHECK((V(ff.force_vehicle_N) - want).norm() < 1e-3 * want.norm() * (kFloat ? 1 : 1e-6));
    CHECK((V(ff.force_barycenter_N) - want).norm() < 1e-3 * want.norm() * (kFloat ? 1 : 1e-6));
  }
}

TEST_CASE("AttitudeFeedforwardCancelsTheArmWeightMomentAboutTheVehicleCoM", "[feedforward]") {
  // Static arm, gravity, ρ = 0: the arm's weights pull at c_i, so the moment the arm exerts on
  // the vehicle about its CoM is Σ (c_i − r0) × m_i·g (+ payload); N_r must be its negative.
  const auto m = PaperModel(5.0);
  static uvms_arm_data_t d;
  uvms_fluid_t fl{};
  const Eigen::Vector3d g(0, 0, -9.81);
  Put(g, fl.gravity_m_s2);
  uvms_base_state_t b{};
  Put(Eigen::Vector3d(1, 2, 3), b.position_m);
  Put(Eigen::Matrix3d(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()).toRotationMatrix()), b.R0);
  const uvms_real_t z[7] = {0, 0, 0, 0, 0, 0, 0};
  uvms_feedforward_t ff;
  REQUIRE(uvms_feedforward(&m, &d, &fl, UVMS_REF_VEHICLE, &b, kQ, z, z, &ff) == UVMS_OK);
  const Eigen::Vector3d r0 = V(b.position_m);
  Eigen::Vector3d arm_moment = (V(d.payload_m) - r0).cross(5.0 * g);
  for (int i = 1; i <= 7; ++i)
    arm_moment += (V(d.com_m[i]) - r0).cross(double(m.p->link[i - 1].mass_kg) * g);
  CHECK((V(ff.moment_att_Nm) + arm_moment).norm() < kTolScale * 1e3 * arm_moment.norm());
  CHECK(arm_moment.norm() > 10.0);
}

TEST_CASE("FeedforwardRejectsBadArgumentsWithZeroOutput", "[feedforward]") {
  const auto m = PaperModel();
  static uvms_arm_data_t d;
  uvms_fluid_t fl{};
  const uvms_base_state_t b = MovingBase();
  uvms_feedforward_t ff;
  ff.force_vehicle_N[0] = 99;
  CHECK(uvms_feedforward(&m, &d, nullptr, UVMS_REF_VEHICLE, &b, kQ, kQd, kQdd, &ff) == UVMS_ERR_ARG);
  CHECK(ff.force_vehicle_N[0] == 0);
  CHECK(uvms_feedforward(&m, &d, &fl, static_cast<uvms_reference_t>(7), &b, kQ, kQd, kQdd, &ff) ==
        UVMS_ERR_ARG);
  uvms_arm_model_t not_ready{};
  CHECK(uvms_feedforward(&not_ready, &d, &fl, UVMS_REF_VEHICLE, &b, kQ, kQd, kQdd, &ff) ==
        UVMS_ERR_STATE);
}

TEST_CASE("AttitudeFeedbackTurnsTowardTheDesiredAttitude", "[feedback]") {
  uvms_pd_gains_t g;
  uvms_pd_gains_paper(&g);
  const Eigen::Matrix3d R0d =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::Vector3d axis = Eigen::Vector3d(-1, 0.5, 0.2).normalized();
  for (const double phi : {0.0, 1e-4, 0.1, M_PI / 2, M_PI - 1e-6}) {
    // Measured attitude: the desired one rotated by −phi about axis (inertial), so the error
    // rotation E = R0d·R0ᵀ is +phi about axis and N_fb = K_PN·phi·axis − K_DN·ω0.
    const Eigen::Matrix3d R0 = Eigen::AngleAxisd(-phi, axis).toRotationMatrix() * R0d;
    // The attitudes as the controller has them: quaternions (w, x, y, z), Eigen's from the
    // matrices; the measured one with another norm and sign (the same rotation).
    const Eigen::Quaterniond qd(R0d), qm(R0);
    uvms_real_t Qd[4] = {uvms_real_t(qd.w()), uvms_real_t(qd.x()), uvms_real_t(qd.y()),
                         uvms_real_t(qd.z())};
    uvms_real_t Q[4] = {uvms_real_t(-1.5 * qm.w()), uvms_real_t(-1.5 * qm.x()),
                        uvms_real_t(-1.5 * qm.y()), uvms_real_t(-1.5 * qm.z())};
    uvms_real_t w[3], N[3], e[3];
    const Eigen::Vector3d omega(0.01, -0.02, 0.005);
    Put(omega, w);
    REQUIRE(uvms_attitude_feedback(&g, Qd, Q, w, N, e) == UVMS_OK);
    const Eigen::Vector3d want = 10.0 * phi * axis - 100.0 * omega;
    INFO("phi " << phi);
    CHECK((V(N) - want).norm() < (kFloat ? 5e-3 : 1e-8));
  }
}

TEST_CASE("PositionFeedbackIsSpringAndDamper", "[feedback]") {
  uvms_pd_gains_t g;
  uvms_pd_gains_paper(&g);
  const uvms_real_t rd[3] = {1, 2, 3}, r[3] = {1.1f, 1.9f, 3}, vd[3] = {0, 0, 0},
                    v[3] = {0.01f, 0, -0.02f};
  uvms_real_t F[3];
  REQUIRE(uvms_position_feedback(&g, rd, r, vd, v, F) == UVMS_OK);
  // K_PF = 10 N/m, K_DF = 100 N·s/m: F = 10·(−0.1, 0.1, 0) + 100·(−0.01, 0, 0.02)
  CHECK(double(F[0]) == Approx(-1.0 - 1.0).margin(1e-5));
  CHECK(double(F[1]) == Approx(1.0).margin(1e-5));
  CHECK(double(F[2]) == Approx(2.0).margin(1e-5));
  CHECK(uvms_position_feedback(nullptr, rd, r, vd, v, F) == UVMS_ERR_ARG);
  CHECK(F[0] == 0);
}

TEST_CASE("ForceFeedforwardsAndVehicleBuoyancyMomentMatchTheirHandAssembly", "[feedforward]") {
  // Flow, a moving and turning vehicle, gravity, ρ > 0, trim ballast and an offset center of
  // buoyancy: every term of [31], [32] and of the attitude feedforward is non-zero. The
  // expected values are assembled here from SPEC §3, §7.1 and the workspace's f1, n1 and link
  // drags D_i (checked against hand-derived cases in test_dynamics.cpp):
  //   D0   = −½ρ·C_D0·A0·|w0|·w0, w0 = v0 − v∞, C_D0 = 1.2, A0 = 0.5 m²          (SPEC §3.2)
  //   [31] F_r,0  = f1 − D0 − (m0 + ballast)·g + β0·g,  β0 = ρ·V0, V0 = 0.15 m³
  //   [32] F_r,cm = −D0 − Σ_i D_i − (m0 + ballast + Σ m_i + m_payload)·g + (β0 + Σ ρ·V_i)·g,
  //        V_i = π·dL²/4·|l_i|, |l_i| = √(a_i² + d_i²), dL = 0.089 m                (SPEC §3.1)
  //   N_r = n1 + (R0·s0) × f1 + (R0·c_b) × (β0·g) − (R0·b_b) × (ballast·g): buoyancy −β0·g
  //        acts at c_b, the ballast weight at its own point b_b (SPEC §6.3); N_r cancels their
  //        moment about the CoM.
  constexpr double kRho = 1025, kBallast = 3.5, kPayload = 10;
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  p.payload_kg = uvms_real_t(kPayload);
  p.vehicle.ballast_kg = uvms_real_t(kBallast);
  const Eigen::Vector3d cob(0.02, -0.01, 0.05), ballast_point(-0.4, 0.15, -0.3);
  Put(cob, p.vehicle.cob_m);
  Put(ballast_point, p.vehicle.ballast_offset_m);
  uvms_arm_model_t m;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);
  static uvms_arm_data_t d;
  uvms_fluid_t fl{};
  fl.density_kg_m3 = uvms_real_t(kRho);
  const Eigen::Vector3d g(0, 0, -9.81), vinf(0.3, -0.2, 0.1);
  Put(g, fl.gravity_m_s2);
  Put(vinf, fl.flow_m_s);
  fl.angle_of_attack = 1;
  const uvms_base_state_t b = MovingBase();

  // SPEC §3.1 table: masses [kg], DH a and d [m].
  const double mass[7] = {10.77, 3.87, 1.80, 2.40, 0.12, 0.42, 0.07};
  const double a_m[7] = {0, 0, 0.045, -0.045, 0, 0, 0};
  const double d_m[7] = {0, 0, 0.550, 0, 0.300, 0, 0.060};
  double m_total = 120 + kBallast + kPayload, vol_total = 0.15;
  for (int i = 0; i < 7; ++i) {
    m_total += mass[i];
    vol_total += M_PI * 0.089 * 0.089 / 4 * std::hypot(a_m[i], d_m[i]);
  }
  const double beta0 = kRho * 0.15;
  const Eigen::Vector3d w0 = V(b.velocity_m_s) - vinf;
  const Eigen::Vector3d D0 = -0.5 * kRho * 1.2 * 0.5 * w0.norm() * w0;
  const Eigen::Matrix3d R0 = M(b.R0);
  const Eigen::Vector3d s0(0.914, 0, 0.152);

  for (const auto ref : {UVMS_REF_VEHICLE, UVMS_REF_BARYCENTER}) {
    INFO("reference " << ref);
    uvms_feedforward_t ff;
    REQUIRE(uvms_feedforward(&m, &d, &fl, ref, &b, kQ, kQd, kQdd, &ff) == UVMS_OK);
    const Eigen::Vector3d f1 = V(d.f_N[1]), n1 = V(d.n_Nm[1]);
    Eigen::Vector3d link_drag = Eigen::Vector3d::Zero();
    for (int i = 1; i <= 7; ++i) link_drag += V(d.drag_N[i]);

    const Eigen::Vector3d F31 = f1 - D0 - (120 + kBallast) * g + beta0 * g;
    const Eigen::Vector3d F32 = -D0 - link_drag - m_total * g + kRho * vol_total * g;
    const Eigen::Vector3d cob_moment =
        (R0 * cob).cross(beta0 * g) - (R0 * ballast_point).cross(kBallast * g);
    const Eigen::Vector3d Nr = n1 + (R0 * s0).cross(f1) + cob_moment;

    // Non-vacuous: each term a mutation would drop or flip is far above the tolerance.
    CHECK(D0.norm() > 10.0);         // ≈ 369·|w0|², |w0| ≈ 0.32 m/s
    CHECK(link_drag.norm() > 0.5);   // the links sit in a 0.37 m/s stream
    CHECK(cob_moment.norm() > 10.0); // ≈ 0.055 m · 1508 N and ≈ 0.5 m · 34 N
    const double tol = kFloat ? 3e-3 : 1e-9;  // [N], [N·m]; terms up to ≈ 1.6 kN
    CHECK((V(ff.force_vehicle_N) - F31).norm() < tol);
    CHECK((V(ff.force_barycenter_N) - F32).norm() < tol);
    CHECK((V(ff.moment_att_Nm) - Nr).norm() < tol);
    CHECK((V(d.drag_N[0]) - D0).norm() < tol);
  }
}

TEST_CASE("VehicleBuoyancyAndBallastMomentsAreTheirCrossProducts", "[feedforward]") {
  // An inert arm (no mass, volume or payload: f1 = n1 = 0) leaves only the vehicle's own
  // hydrostatic moment, which the attitude feedforward cancels (SPEC §7.1): buoyancy −β0·g at
  // the center of buoyancy c_b, ballast weight m_b·g at its point b_b.
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  for (size_t i = 0; i < p.num_joints; ++i) {
    p.link[i].mass_kg = 0;
    p.link[i].diameter_m = 0;
  }
  p.payload_kg = 0;
  static uvms_arm_data_t d;
  uvms_fluid_t fl{};
  fl.density_kg_m3 = 1025;
  fl.gravity_m_s2[2] = uvms_real_t(-9.81);
  const uvms_real_t z[7] = {0, 0, 0, 0, 0, 0, 0};
  const double tol = kFloat ? 1e-4 : 1e-12;  // [N·m], moments of tens of N·m
  {
    // Level, by hand: c_b = (0, 0, 0.1) m is on the vertical through the CoM, so buoyancy has
    // no moment; the 4 kg ballast at b_b = (−0.5, 0.2, −0.3) m weighs F = (0, 0, −39.24) N and
    // b_b × F = (0.2·(−39.24), −(−0.5)·(−39.24), 0) = (−7.848, −19.62, 0) N·m, so the
    // feedforward is (7.848, 19.62, 0) N·m.
    uvms_v3_set(p.vehicle.cob_m, 0, 0, uvms_real_t(0.1));
    uvms_v3_set(p.vehicle.ballast_offset_m, uvms_real_t(-0.5), uvms_real_t(0.2), uvms_real_t(-0.3));
    p.vehicle.ballast_kg = 4;
    uvms_arm_model_t m;
    REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);
    uvms_base_state_t b{};
    uvms_m3_identity(b.R0);
    uvms_feedforward_t ff;
    REQUIRE(uvms_feedforward(&m, &d, &fl, UVMS_REF_VEHICLE, &b, kQ, z, z, &ff) == UVMS_OK);
    CHECK((V(ff.moment_att_Nm) - Eigen::Vector3d(7.848, 19.62, 0)).norm() < tol);
    CHECK(V(ff.base_force_N).norm() == 0.0);  // the arm really is inert
  }
  // Tilted, and with a float (negative ballast: net buoyancy at b_b): the negative of the
  // external moment c × (−β0·g) + b × (m_b·g), both points rotated into inertial axes.
  const Eigen::Matrix3d R0 =
      Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  const Eigen::Vector3d g(0, 0, -9.81), cob(0.03, -0.02, 0.08), point(-0.6, 0.1, -0.25);
  for (const double mb : {4.0, -2.5}) {
    Put(cob, p.vehicle.cob_m);
    Put(point, p.vehicle.ballast_offset_m);
    p.vehicle.ballast_kg = uvms_real_t(mb);
    uvms_arm_model_t m;
    REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);
    uvms_base_state_t b{};
    Put(R0, b.R0);
    uvms_feedforward_t ff;
    REQUIRE(uvms_feedforward(&m, &d, &fl, UVMS_REF_VEHICLE, &b, kQ, z, z, &ff) == UVMS_OK);
    const Eigen::Vector3d external =
        (R0 * cob).cross(-1025 * 0.15 * g) + (R0 * point).cross(mb * g);
    INFO("ballast " << mb << " kg");
    CHECK((V(ff.moment_att_Nm) + external).norm() < tol * 10);
    CHECK(external.norm() > 10.0);
  }
}

TEST_CASE("AtTheTrimLevelAndStowedTheFeedforwardOfVehiclePlusArmAtRestIsZero", "[feedforward]") {
  // SPEC §6.3: trimmed, weight equals buoyancy and the center of gravity lies h below the
  // center of buoyancy, in the stowed pose θI with the nominal payload, level. At rest nothing
  // needs holding: [31], [32] and the attitude moment vanish for both references. The trim is
  // computed here from its definition, with the firmware's kinematics only for positions
  // (vehicle at the origin, level): link CoMs c_i, link mid-points μ_i = p_{i−1}* + R_i·l_i/2,
  // the payload point p_p; masses and link volumes V_i = π·dL²/4·|l_i| of SPEC §3.1:
  //   m_b = ρ·V_T − (m0 + Σ m_i + m_p),
  //   m_b·b = ρ·(V0·c_b + Σ V_i·μ_i) − ρ·V_T·h·e_z − (Σ m_i·c_i + m_p·p_p).
  constexpr double kRho = 1025, kPayload = 10, kH = 0.05;
  const double mass[7] = {10.77, 3.87, 1.80, 2.40, 0.12, 0.42, 0.07};
  const double len[7] = {0, 0, std::hypot(0.045, 0.55), 0.045, 0.3, 0, 0.06};
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  p.payload_kg = uvms_real_t(kPayload);
  uvms_arm_model_t m;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);
  static uvms_arm_data_t d;
  uvms_real_t q[7];
  const uvms_real_t *deg = uvms_joint_table_deg(UVMS_JOINT_TABLE_START);
  for (int j = 0; j < 7; ++j) q[j] = uvms_real_t(double(deg[j]) * M_PI / 180);
  const uvms_real_t origin[3] = {0, 0, 0};
  uvms_real_t level[9];
  uvms_m3_identity(level);
  REQUIRE(uvms_arm_fk(&m, &d, origin, level, q) == UVMS_OK);
  double volume = 0.15, total = 120 + kPayload;
  Eigen::Vector3d weight_moment = kPayload * V(d.payload_m), buoyancy_moment = Eigen::Vector3d::Zero();
  for (int i = 1; i <= 7; ++i) {
    const double vol = M_PI * 0.089 * 0.089 / 4 * len[i - 1];
    volume += vol;
    total += mass[i - 1];
    weight_moment += mass[i - 1] * V(d.com_m[i]);
    buoyancy_moment += kRho * vol * (V(d.p_m[i - 1]) + 0.5 * V(d.Rl_m[i]));
  }
  const double M_kg = kRho * volume, mb = M_kg - total;
  const Eigen::Vector3d b =
      (buoyancy_moment - M_kg * kH * Eigen::Vector3d::UnitZ() - weight_moment) / mb;
  p.vehicle.ballast_kg = uvms_real_t(mb);
  Put(b, p.vehicle.ballast_offset_m);
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);

  for (const double g : {9.81, 1.315}) {
    uvms_fluid_t fl{};
    fl.density_kg_m3 = uvms_real_t(kRho);
    fl.gravity_m_s2[2] = uvms_real_t(-g);
    uvms_base_state_t st{};
    Put(Eigen::Vector3d(3, -2, -40), st.position_m);
    uvms_m3_identity(st.R0);
    const uvms_real_t z[7] = {0, 0, 0, 0, 0, 0, 0};
    // Terms of size M·g (≈ 1.6 kN, 210 N) and M·g·2 m cancel: rounding of the build's real.
    const double tol = (kFloat ? 1e-5 : 1e-13) * M_kg * g;
    for (const auto ref : {UVMS_REF_VEHICLE, UVMS_REF_BARYCENTER}) {
      uvms_feedforward_t ff;
      REQUIRE(uvms_feedforward(&m, &d, &fl, ref, &st, q, z, z, &ff) == UVMS_OK);
      INFO("g " << g << " reference " << ref << " N_r " << V(ff.moment_att_Nm).transpose()
                << " F_r,0 " << V(ff.force_vehicle_N).transpose());
      std::printf("trimmed, stowed, level, at rest (g = %.3f, reference %d): |F_r,0| %.1e N, "
                  "|F_r,cm| %.1e N, |N_r| %.1e N·m\n", g, int(ref), V(ff.force_vehicle_N).norm(),
                  V(ff.force_barycenter_N).norm(), V(ff.moment_att_Nm).norm());
      CHECK(V(ff.force_vehicle_N).norm() < tol);
      CHECK(V(ff.force_barycenter_N).norm() < tol);
      CHECK(V(ff.moment_att_Nm).norm() < tol * 2);
      // Not vacuous: the arm's own moment on the vehicle about its CoM is ≈ 23 kg·m × g.
      const Eigen::Vector3d arm_moment = V(ff.base_moment_Nm) + V(d.R0s0_m).cross(V(ff.base_force_N));
      CHECK(arm_moment.norm() > 10.0 * g);
    }
  }
}

TEST_CASE("FossenDampingIsCancelledByTheForceAndAttitudeFeedforwards", "[feedforward]") {
  // An inert arm (no mass, inertia or volume: f1 = n1 = 0), no isotropic drag (C_D0 = 0),
  // g = 0, still water, the vehicle tilted, moving and turning: the only external load is
  // Fossen's damping, so F_r,0 = F_r,cm = −F and the attitude feedforward = −M, with F and M
  // assembled here per body axis (docs/MODEL.md §3.2): ν = R0ᵀ·(v0, ω0),
  // τ_k = −(D_L,k + D_Q,k·|ν_k|)·ν_k, F = R0·τ_lin, M = R0·τ_ang.
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  for (size_t i = 0; i < p.num_joints; ++i) {
    p.link[i].mass_kg = 0;
    p.link[i].diameter_m = 0;
    uvms_v3_set(p.link[i].inertia_kg_m2, 0, 0, 0);
  }
  p.payload_kg = 0;
  p.vehicle.drag_coeff = 0;
  const double DL[6] = {13.7, 2.0, 33.0, 0.5, 0.8, 0.3};
  const double DQ[6] = {141.0, 217.0, 190.0, 1.19, 0.47, 1.5};
  for (int k = 0; k < 6; ++k) {
    p.vehicle.linear_damping[k] = uvms_real_t(DL[k]);
    p.vehicle.quadratic_damping[k] = uvms_real_t(DQ[k]);
  }
  uvms_arm_model_t m;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);
  CHECK(m.vehicle_damping == 1);
  static uvms_arm_data_t d;
  uvms_fluid_t fl{};
  fl.density_kg_m3 = 1000;
  const uvms_base_state_t b = MovingBase();
  const uvms_real_t z[7] = {0, 0, 0, 0, 0, 0, 0};
  uvms_feedforward_t ff;
  REQUIRE(uvms_feedforward(&m, &d, &fl, UVMS_REF_VEHICLE, &b, kQ, z, z, &ff) == UVMS_OK);
  Eigen::Matrix3d R0;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R0(r, c) = double(b.R0[3 * r + c]);
  const Eigen::Vector3d nu_lin = R0.transpose() * V(b.velocity_m_s);
  const Eigen::Vector3d nu_ang = R0.transpose() * V(b.omega_rad_s);
  Eigen::Vector3d tau_lin, tau_ang;
  for (int k = 0; k < 3; ++k) {
    tau_lin[k] = -(DL[k] + DQ[k] * std::abs(nu_lin[k])) * nu_lin[k];
    tau_ang[k] = -(DL[k + 3] + DQ[k + 3] * std::abs(nu_ang[k])) * nu_ang[k];
  }
  const Eigen::Vector3d F = R0 * tau_lin, M = R0 * tau_ang;
  const double tol = kFloat ? 1e-5 : 1e-14;  // [N], [N·m]: loads of 0.01–1 N
  CHECK(F.norm() > 0.5);
  CHECK(M.norm() > 0.005);
  CHECK((V(ff.force_vehicle_N) + F).norm() < tol);
  CHECK((V(ff.force_barycenter_N) + F).norm() < tol);
  CHECK((V(ff.moment_att_Nm) + M).norm() < tol);
  // Without damping coefficients the same state needs no feedforward at all.
  for (int k = 0; k < 6; ++k) p.vehicle.linear_damping[k] = p.vehicle.quadratic_damping[k] = 0;
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);
  CHECK(m.vehicle_damping == 0);
  REQUIRE(uvms_feedforward(&m, &d, &fl, UVMS_REF_VEHICLE, &b, kQ, z, z, &ff) == UVMS_OK);
  CHECK(V(ff.force_vehicle_N).norm() == 0.0);
  CHECK(V(ff.moment_att_Nm).norm() == 0.0);
}
