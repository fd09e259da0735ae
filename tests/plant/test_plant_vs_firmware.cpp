// SPDX-License-Identifier: Apache-2.0
// The cross-check the project rests on (SPEC §5, last bullet): the plant's multibody model
// (plant/src/multibody.cpp: joint-axis kinematics, per-body wrenches summed over distal bodies)
// and the firmware's Newton–Euler recursion (firmware/src/dynamics.c) are independent
// implementations of SPEC §4. With identical parameters, for many random states, vehicle
// accelerations, fluids and payloads, the arm base wrench (f1, n1) and the joint torques must
// agree to 1e-9 relative in the double build. Under gravity with the trim ballast (SPEC §6.3)
// the firmware's vehicle-reference feedforward (SPEC §7.1) must equal the plant's holding
// wrench.
#include <catch2/catch.hpp>

#include <random>

#include "uvms/dynamics.h"
#include "uvms/feedforward.h"
#include "../firmware/fw_test_util.hpp"  // OwnedModel
#include "uvms_plant/plant.hpp"
#include "uvms_plant/multibody.hpp"

using namespace uvms::plant;

namespace {

// The firmware's model from the plant's parameters (one source of numbers for both), with the
// plant's ballast (SPEC §6.3).
fwtest::OwnedModel FirmwareModel(const PlantParams &p, const Ballast &ballast = Ballast{}) {
  uvms_arm_params_t fp;
  uvms_arm_params_paper(&fp);
  fp.num_joints = p.links.size();
  for (size_t i = 0; i < p.links.size(); ++i) {
    const LinkParams &L = p.links[i];
    auto &F = fp.link[i];
    F.alpha_rad = uvms_real_t(L.alpha_rad);
    F.a_m = uvms_real_t(L.a_m);
    F.d_m = uvms_real_t(L.d_m);
    F.mass_kg = uvms_real_t(L.mass_kg);
    for (int k = 0; k < 3; ++k) {
      F.com_m[k] = uvms_real_t(L.com_m[k]);
      F.inertia_kg_m2[k] = uvms_real_t(L.inertia_kg_m2[k]);
      F.inertia_products_kg_m2[k] = uvms_real_t(L.inertia_products_kg_m2[k]);
      F.placement_m[k] = uvms_real_t(L.placement_m[k]);
      F.placement_rotvec_rad[k] = uvms_real_t(L.placement_rotvec_rad[k]);
    }
    F.diameter_m = uvms_real_t(L.diameter_m);
    F.drag_coeff = uvms_real_t(L.drag_coeff);
    for (int k = 0; k < 6; ++k) F.added_mass_kg[k] = uvms_real_t(L.added_mass_kg[k]);
  }
  fp.payload_kg = uvms_real_t(p.payload_kg);
  const VehicleParams &v = p.vehicle;
  fp.vehicle.mass_kg = uvms_real_t(v.mass_kg);
  fp.vehicle.volume_m3 = uvms_real_t(v.volume_m3);
  fp.vehicle.frontal_area_m2 = uvms_real_t(v.frontal_area_m2);
  fp.vehicle.drag_coeff = uvms_real_t(v.drag_coeff);
  fp.vehicle.ballast_kg = uvms_real_t(ballast.mass_kg);
  for (int k = 0; k < 6; ++k) {
    fp.vehicle.linear_damping[k] = uvms_real_t(v.linear_damping[k]);
    fp.vehicle.quadratic_damping[k] = uvms_real_t(v.quadratic_damping[k]);
  }
  for (int k = 0; k < 3; ++k) {
    fp.payload_offset_m[k] = uvms_real_t(p.payload_offset_m[k]);
    fp.vehicle.base_offset_m[k] = uvms_real_t(v.base_offset_m[k]);
    fp.vehicle.base_rotvec_rad[k] = uvms_real_t(v.base_rotvec_rad[k]);
    fp.vehicle.inertia_kg_m2[k] = uvms_real_t(v.inertia_kg_m2[k]);
    fp.vehicle.cob_m[k] = uvms_real_t(v.cob_m[k]);
    fp.vehicle.ballast_offset_m[k] = uvms_real_t(ballast.offset_m[k]);
  }
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) fp.added_mass_coeff[6 * r + c] = uvms_real_t(p.added_mass_coeff(r, c));
  return fwtest::OwnedModel(fp);
}

template <class V>
void Put(const V &v, uvms_real_t *out, int n) {
  for (int i = 0; i < n; ++i) out[i] = uvms_real_t(v[i]);
}

}  // namespace

TEST_CASE("PlantArmWrenchesEqualFirmwareNewtonEulerAtRandomStates", "[plant][crosscheck]") {
  // Float firmware builds compute in single precision: the comparison then tests the
  // firmware's rounding, with a tolerance of that order.
  const double rel_tol = UVMS_REAL_IS_FLOAT ? 2e-4 : 1e-9;
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> nd(0.0, 1.0);
  static uvms_arm_data_t fd;
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    PlantParams p = PaperPlantParams();
    p.payload_kg = std::array<double, 5>{0, 1, 2, 5, 10}[trial % 5];
    if (trial % 7 == 3) p.payload_offset_m = Vec3(0.02, -0.01, 0.05);
    if (trial % 2 == 1)  // links off their principal axes: I_Bi = Q·I_Bi·Qᵀ, Q random
      for (LinkParams &L : p.links) {
        const Mat3 Q = Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized().toRotationMatrix();
        const Mat3 I = Q * L.inertia_kg_m2.asDiagonal() * Q.transpose();
        L.inertia_kg_m2 = I.diagonal();
        L.inertia_products_kg_m2 = Vec3(I(0, 1), I(0, 2), I(1, 2));
      }
    if (trial % 3 == 2) {  // general links (docs/MODEL.md §2) and a turned mount
      for (LinkParams &L : p.links) {
        L.placement_m = Vec3(u(rng), u(rng), u(rng)) * 0.1;
        L.placement_rotvec_rad = Vec3(u(rng), u(rng), u(rng)) * 1.5;
      }
      p.vehicle.base_rotvec_rad = Vec3(u(rng), u(rng), u(rng)) * 1.5;
    }
    if (trial % 5 == 4)  // links 1, 3, 5, 7 with their own diagonal added mass (§3.3)
      for (size_t i = 0; i < p.links.size(); i += 2)
        for (double &x : p.links[i].added_mass_kg) x = 2.0 * (u(rng) + 1.0);
    const ArmModel am = ArmModel::FromParams(p);
    const auto fm = FirmwareModel(p);

    BaseState b;
    b.r0_m = Vec3(u(rng), u(rng), u(rng)) * 3.0;
    b.R0 = Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized().toRotationMatrix();
    b.v0_m_s = Vec3(u(rng), u(rng), u(rng)) * 0.5;
    b.w0_rad_s = Vec3(u(rng), u(rng), u(rng)) * 0.3;
    Vec6 x;
    for (int k = 0; k < 6; ++k) x[k] = u(rng) * 0.5;
    double q[7], qd[7], qdd[7];
    for (int j = 0; j < 7; ++j) {
      q[j] = u(rng) * M_PI;
      qd[j] = u(rng) * 1.0;
      qdd[j] = u(rng) * 2.0;
    }
    FluidState f;
    f.density_kg_m3 = (trial % 4 == 0) ? 0.0 : (trial % 2 ? 1025.0 : 1000.0);
    f.flow_m_s = (trial % 3 == 0) ? Vec3(Vec3::Zero()) : Vec3(Vec3(u(rng), u(rng), u(rng)) * 0.2);
    f.gravity_m_s2 = (trial % 5 == 1) ? Vec3::Zero() : Vec3(0, 0, -(trial % 2 ? 9.81 : 1.315));
    f.angle_of_attack = (trial % 6) != 5;

    ArmKinematics kin;
    ArmLoads loads;
    JointWrenches jw;
    ComputeArmKinematics(am, b, q, qd, qdd, kin);
    ComputeArmLoads(am, b, f, kin, loads);
    ComputeJointWrenches(am, b, kin, loads, x, jw);

    uvms_base_state_t fb{};
    Put(b.r0_m, fb.position_m, 3);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) fb.R0[3 * r + c] = uvms_real_t(b.R0(r, c));
    Put(b.v0_m_s, fb.velocity_m_s, 3);
    Put(b.w0_rad_s, fb.omega_rad_s, 3);
    Put(x.head<3>(), fb.accel_m_s2, 3);
    Put(x.tail<3>(), fb.alpha_rad_s2, 3);
    uvms_fluid_t ff{};
    ff.density_kg_m3 = uvms_real_t(f.density_kg_m3);
    Put(f.flow_m_s, ff.flow_m_s, 3);
    Put(f.gravity_m_s2, ff.gravity_m_s2, 3);
    ff.angle_of_attack = f.angle_of_attack ? 1 : 0;
    uvms_real_t fq[7], fqd[7], fqdd[7];
    Put(q, fq, 7);
    Put(qd, fqd, 7);
    Put(qdd, fqdd, 7);
    REQUIRE(uvms_arm_rnea(&fm, &fd, &fb, &ff, fq, fqd, fqdd) == UVMS_OK);

    const Vec3 f1(fd.f_N[1][0], fd.f_N[1][1], fd.f_N[1][2]);
    const Vec3 n1(fd.n_Nm[1][0], fd.n_Nm[1][1], fd.n_Nm[1][2]);
    const double fs = std::max(1.0, f1.norm()), ns = std::max(1.0, n1.norm());
    INFO("trial " << trial << " f1 plant " << jw.f1_N.transpose() << " firmware " << f1.transpose());
    CHECK((jw.f1_N - f1).norm() <= rel_tol * fs);
    CHECK((jw.n1_Nm - n1).norm() <= rel_tol * ns);
    worst = std::max({worst, (jw.f1_N - f1).norm() / fs, (jw.n1_Nm - n1).norm() / ns});
    double ts = 1.0;
    for (int i = 1; i <= 7; ++i) ts = std::max(ts, std::abs(double(fd.tau_Nm[i])));
    for (int i = 1; i <= 7; ++i) {
      INFO("joint " << i);
      CHECK(std::abs(jw.tau_Nm[size_t(i)] - double(fd.tau_Nm[i])) <= rel_tol * ts);
      worst = std::max(worst, std::abs(jw.tau_Nm[size_t(i)] - double(fd.tau_Nm[i])) / ts);
    }
    // Same drag on every link and on the vehicle body.
    for (int i = 1; i <= 7; ++i)
      CHECK((loads.drag_N[size_t(i)] - Vec3(fd.drag_N[i][0], fd.drag_N[i][1], fd.drag_N[i][2])).norm() <=
            rel_tol * std::max(1.0, loads.drag_N[size_t(i)].norm()));
    // Kinematics: EE and barycenter.
    CHECK((kin.ee_m - Vec3(fd.ee_m[0], fd.ee_m[1], fd.ee_m[2])).norm() <= rel_tol * 10);
    CHECK((kin.barycenter_m - Vec3(fd.barycenter_m[0], fd.barycenter_m[1], fd.barycenter_m[2])).norm() <=
          rel_tol * 10);
  }
  std::printf("plant vs firmware (%s firmware): worst relative difference %.2e over 200 states\n",
              UVMS_REAL_IS_FLOAT ? "float" : "double", worst);
}

TEST_CASE("FirmwareFeedforwardEqualsThePlantsHoldingWrenchUnderGravityAndTrim", "[plant][crosscheck]") {
  // Earth and Europa, trimmed (the plant's TrimBallast, handed to the firmware as the scenario
  // reader does), the arm moving, the vehicle translating at any attitude in a steady flow but
  // not turning (ω0 = 0: the firmware's model has no gyroscopic or added-mass velocity terms of
  // the vehicle itself, SPEC §7), every other trial with Fossen's damping. The plant's holding wrench (the thrust wrench that leaves the
  // vehicle unaccelerated: every body's weight, buoyancy, drag and inertia summed on its own)
  // must equal the firmware's F_r,0 [31] and N_r (Newton–Euler recursion plus the vehicle's
  // hydrostatic moment). Scale: the weights that cancel, M·g, and M·g·1 m.
  const double rel_tol = UVMS_REAL_IS_FLOAT ? 2e-4 : 1e-9;
  std::mt19937 rng(20261201);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> nd(0.0, 1.0);
  static uvms_arm_data_t fd;
  double worst = 0.0;
  for (const double g : {9.81, 1.315}) {
    for (int trial = 0; trial < 25; ++trial) {
      PlantParams p = PaperPlantParams();
      p.payload_kg = std::array<double, 5>{10, 0, 1, 2, 5}[trial % 5];
      p.env.gravity_m_s2 = Vec3(0, 0, -g);
      p.env.trim = true;  // for the nominal 10 kg payload, h = 0.05 m
      p.env.steady_flow_m_s = Vec3(u(rng), u(rng), u(rng)) * 0.2;
      p.contact.enabled = false;
      if (trial % 2 == 1)  // Fossen's damping too (docs/MODEL.md §3.2): its force is in F_r,0
        for (int k = 0; k < 6; ++k) {
          p.vehicle.linear_damping[k] = 50.0 * (u(rng) + 1.0);
          p.vehicle.quadratic_damping[k] = 500.0 * (u(rng) + 1.0);
        }
      Plant plant(p);
      const auto fm = FirmwareModel(p, plant.ballast());

      InitialState init;
      init.r0_m = Vec3(u(rng), u(rng), u(rng)) * 3.0;
      init.attitude = trial == 0 ? Eigen::Quaterniond::Identity()
                                 : Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized();
      init.v0_m_s = Vec3(u(rng), u(rng), u(rng)) * 0.5;
      init.q_rad.resize(7);
      init.qd_rad_s.resize(7);
      PlantInputs in;
      const size_t nt = p.thrusters.size();
      in.motor_voltage_V.assign(nt, 0.0);
      in.motor_current_cmd_A.assign(nt, 0.0);
      in.motor_current_rate_A_s.assign(nt, 0.0);
      in.joint_accel_rad_s2.resize(7);
      for (size_t j = 0; j < 7; ++j) {
        init.q_rad[j] = u(rng) * M_PI;
        init.qd_rad_s[j] = u(rng) * 1.0;
        in.joint_accel_rad_s2[j] = u(rng) * 2.0;
      }
      plant.Reset(init);
      const Wrench hold = plant.HoldingWrench(in);

      uvms_base_state_t fb{};
      const Mat3 R0 = init.attitude.toRotationMatrix();
      Put(init.r0_m, fb.position_m, 3);
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) fb.R0[3 * r + c] = uvms_real_t(R0(r, c));
      Put(init.v0_m_s, fb.velocity_m_s, 3);
      uvms_fluid_t ff{};
      ff.density_kg_m3 = uvms_real_t(p.env.density_kg_m3);
      Put(p.env.steady_flow_m_s, ff.flow_m_s, 3);
      Put(p.env.gravity_m_s2, ff.gravity_m_s2, 3);
      ff.angle_of_attack = p.env.angle_of_attack ? 1 : 0;
      uvms_real_t fq[7], fqd[7], fqdd[7];
      Put(init.q_rad, fq, 7);
      Put(init.qd_rad_s, fqd, 7);
      Put(in.joint_accel_rad_s2, fqdd, 7);
      uvms_feedforward_t w;
      REQUIRE(uvms_feedforward(&fm, &fd, &ff, UVMS_REF_VEHICLE, &fb, fq, fqd, fqdd, &w) == UVMS_OK);

      const Vec3 F(w.force_vehicle_N[0], w.force_vehicle_N[1], w.force_vehicle_N[2]);
      const Vec3 N(w.moment_att_Nm[0], w.moment_att_Nm[1], w.moment_att_Nm[2]);
      const double scale = p.env.density_kg_m3 * 0.156 * g;  // M·g ≈ ρ·V_T·g [N]
      INFO("g " << g << " trial " << trial << " force plant " << hold.force_N.transpose()
                << " firmware " << F.transpose() << " moment plant " << hold.moment_Nm.transpose()
                << " firmware " << N.transpose());
      CHECK((hold.force_N - F).norm() <= rel_tol * scale);
      CHECK((hold.moment_Nm - N).norm() <= rel_tol * scale);
      worst = std::max({worst, (hold.force_N - F).norm() / scale, (hold.moment_Nm - N).norm() / scale});
      if (trial == 0) CHECK(hold.moment_Nm.norm() > 1.0);  // level, arm moving: not trivially 0
    }
  }
  std::printf("feedforward vs plant holding wrench, gravity + trim (%s firmware): worst relative "
              "difference %.2e (of M·g) over 50 states\n", UVMS_REAL_IS_FLOAT ? "float" : "double", worst);
}

TEST_CASE("FirmwareAndPlantFossenDampingAgreeAtRandomStates", "[plant][crosscheck]") {
  // docs/MODEL.md §3.2: the firmware's uvms_vehicle_damping and the plant's FossenDamping, two
  // implementations, at random attitudes, relative velocities, rates and coefficients.
  const double rel_tol = UVMS_REAL_IS_FLOAT ? 1e-5 : 1e-13;
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> nd(0.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    VehicleParams V;
    uvms_vehicle_params_t fv{};
    for (int k = 0; k < 6; ++k) {
      V.linear_damping[k] = 20.0 * (u(rng) + 1.0);
      V.quadratic_damping[k] = 200.0 * (u(rng) + 1.0);
      fv.linear_damping[k] = uvms_real_t(V.linear_damping[k]);
      fv.quadratic_damping[k] = uvms_real_t(V.quadratic_damping[k]);
    }
    const Mat3 R0 = Eigen::Quaterniond(nd(rng), nd(rng), nd(rng), nd(rng)).normalized().toRotationMatrix();
    const Vec3 w(u(rng), u(rng), u(rng)), om = Vec3(u(rng), u(rng), u(rng)) * 0.5;
    const Wrench plant_d = FossenDamping(V, R0, w, om);
    uvms_real_t fR[9], fw[3], fom[3], F[3], M[3];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) fR[3 * r + c] = uvms_real_t(R0(r, c));
    Put(w, fw, 3);
    Put(om, fom, 3);
    uvms_vehicle_damping(&fv, fR, fw, fom, F, M);
    const double scale = plant_d.force_N.norm() + plant_d.moment_Nm.norm();
    const double diff = (plant_d.force_N - Vec3(F[0], F[1], F[2])).norm() +
                        (plant_d.moment_Nm - Vec3(M[0], M[1], M[2])).norm();
    CHECK(diff <= rel_tol * scale);
    worst = std::max(worst, diff / scale);
  }
  std::printf("Fossen damping, firmware vs plant: worst relative difference %.2e over 200 states\n", worst);
}

TEST_CASE("LinkOwnAddedMassGivesTheClosedFormReactionInBothModels", "[plant][crosscheck]") {
  // docs/MODEL.md §3.3: a link with its own diagonal added mass D (frame-i axes, at μ_i). One
  // link at rest, the vehicle accelerating by a (no rotation, no gravity, no flow, Ma0 = 0 so
  // that only D acts): the base force changes by exactly R_1·D·R_1ᵀ·a and the base moment by
  // (R_1·μ_1) × that, against the same link without D. Closed form, both models.
  const double rel_tol = UVMS_REAL_IS_FLOAT ? 1e-5 : 1e-12;
  PlantParams p = PaperPlantParams();
  p.links.resize(1);
  p.links[0].a_m = 0.4;
  p.links[0].d_m = 0.1;
  p.links[0].alpha_rad = 0.7;
  p.added_mass_coeff.setZero();
  PlantParams with = p;
  const double D[6] = {3.0, 5.0, 7.0, 0.2, 0.3, 0.4};
  for (int k = 0; k < 6; ++k) with.links[0].added_mass_kg[k] = D[k];
  BaseState b;
  b.R0 = Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized().toRotationMatrix();
  const Vec6 x = (Vec6() << 0.7, -1.1, 0.4, 0.0, 0.0, 0.0).finished();
  const double q[7] = {0.6}, zero[7] = {0.0};
  FluidState f;
  f.density_kg_m3 = 1000.0;
  const auto plant_base = [&](const PlantParams &pp, Vec3 &f1, Vec3 &n1, Mat3 &R1, Vec3 &mid) {
    const ArmModel am = ArmModel::FromParams(pp);
    ArmKinematics kin;
    ArmLoads loads;
    JointWrenches jw;
    ComputeArmKinematics(am, b, q, zero, zero, kin);
    ComputeArmLoads(am, b, f, kin, loads);
    ComputeJointWrenches(am, b, kin, loads, x, jw);
    f1 = jw.f1_N;
    n1 = jw.n1_Nm;
    R1 = kin.R[1];
    mid = kin.R[1] * am.l_m[0] / 2.0;
  };
  Vec3 f0, n0, fD, nD, mid;
  Mat3 R1;
  plant_base(p, f0, n0, R1, mid);
  plant_base(with, fD, nD, R1, mid);
  const Vec3 a = x.head<3>();
  const Vec3 dF = R1 * Eigen::Map<const Vec3>(D).asDiagonal() * R1.transpose() * a;
  const Vec3 dN = mid.cross(dF);
  CHECK((fD - f0 - dF).norm() <= 1e-12 * dF.norm());
  CHECK((nD - n0 - dN).norm() <= 1e-12 * dN.norm());
  // The firmware, from the same parameters.
  static uvms_arm_data_t fd;
  const auto firmware_base = [&](const PlantParams &pp, Vec3 &f1, Vec3 &n1) {
    const auto fm = FirmwareModel(pp);
    uvms_base_state_t fb{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) fb.R0[3 * r + c] = uvms_real_t(b.R0(r, c));
    Put(x.head<3>(), fb.accel_m_s2, 3);
    uvms_fluid_t ff{};
    ff.density_kg_m3 = uvms_real_t(f.density_kg_m3);
    ff.angle_of_attack = 1;
    uvms_real_t fq[7] = {uvms_real_t(q[0])}, fz[7] = {0};
    REQUIRE(uvms_arm_rnea(&fm, &fd, &fb, &ff, fq, fz, fz) == UVMS_OK);
    f1 = Vec3(fd.f_N[1][0], fd.f_N[1][1], fd.f_N[1][2]);
    n1 = Vec3(fd.n_Nm[1][0], fd.n_Nm[1][1], fd.n_Nm[1][2]);
  };
  Vec3 g0, m0, gD, mD;
  firmware_base(p, g0, m0);
  firmware_base(with, gD, mD);
  CHECK((gD - g0 - dF).norm() <= rel_tol * dF.norm());
  CHECK((mD - m0 - dN).norm() <= rel_tol * std::max(1.0, dN.norm()));
  std::printf("link's own added mass: |ΔF − R·D·Rᵀ·a| plant %.1e, firmware %.1e N (|ΔF| %.3f N)\n",
              (fD - f0 - dF).norm(), (gD - g0 - dF).norm(), dF.norm());
}
