// SPDX-License-Identifier: Apache-2.0
// Newton–Euler with hydrodynamics (SPEC §4) checked against independent references:
//  - momentum balance from finite differences of the chain's positions (ρ = 0, g = 0),
//  - Lagrange's equations with M(q) built from Jacobians (fixed base, gravity),
//  - hydrostatic torques as the gradient of a potential (gravity + buoyancy),
//  - hand-derived hydrodynamic cases: a single link in uniform flow at 0°, 45°, 90°, a link
//    spinning in still water (drag at the aerodynamic center), added mass in pure translation.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "fw_test_util.hpp"
#include "uvms/dynamics.h"
#include "uvms/kinematics.h"

using namespace fwtest;

namespace {

constexpr double kRho = 1025.0;  // sea water [kg/m³] (SPEC §3.2)

uvms_fluid_t Fluid(double rho, Eigen::Vector3d g = Eigen::Vector3d::Zero(), int aoa = 1,
                   Eigen::Vector3d flow = Eigen::Vector3d::Zero()) {
  uvms_fluid_t f{};
  f.density_kg_m3 = uvms_real_t(rho);
  Put(flow, f.flow_m_s);
  Put(g, f.gravity_m_s2);
  f.angle_of_attack = aoa;
  return f;
}

// A smooth test trajectory of the whole system: joints, vehicle position, and vehicle attitude
// turning about a fixed inertial axis k (so ω0 = k·φ̇ and ω̇0 = k·φ̈ exactly).
struct Trajectory {
  double q0[7] = {0.3, -0.8, 1.2, 1.9, -0.4, 0.9, 0.2};
  double A[7] = {0.5, 0.4, 0.6, 0.3, 0.7, 0.5, 0.8};
  double w[7] = {1.1, 0.7, 1.3, 0.9, 1.7, 1.5, 2.0};
  double ph[7] = {0.1, 0.5, 0.9, 1.3, 1.7, 2.1, 2.5};
  Eigen::Vector3d r00{0.5, -0.2, 1.0}, rb{0.2, 0.1, -0.15}, rc{0.9, 1.4, 0.6};
  Eigen::Vector3d k = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  Eigen::Matrix3d R00 = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();

  void q(double t, uvms_real_t *qq, uvms_real_t *qd, uvms_real_t *qdd) const {
    for (int j = 0; j < 7; ++j) {
      qq[j] = uvms_real_t(q0[j] + A[j] * std::sin(w[j] * t + ph[j]));
      qd[j] = uvms_real_t(A[j] * w[j] * std::cos(w[j] * t + ph[j]));
      qdd[j] = uvms_real_t(-A[j] * w[j] * w[j] * std::sin(w[j] * t + ph[j]));
    }
  }
  uvms_base_state_t base(double t) const {
    uvms_base_state_t b{};
    const Eigen::Vector3d s(std::sin(rc[0] * t), std::sin(rc[1] * t), std::sin(rc[2] * t));
    const Eigen::Vector3d c(std::cos(rc[0] * t), std::cos(rc[1] * t), std::cos(rc[2] * t));
    Put(Eigen::Vector3d(r00 + rb.cwiseProduct(s)), b.position_m);
    Put(Eigen::Vector3d(rb.cwiseProduct(rc).cwiseProduct(c)), b.velocity_m_s);
    Put(Eigen::Vector3d(-rb.cwiseProduct(rc).cwiseProduct(rc).cwiseProduct(s)), b.accel_m_s2);
    const double phi = 0.3 * std::sin(0.7 * t), phid = 0.21 * std::cos(0.7 * t),
                 phidd = -0.147 * std::sin(0.7 * t);
    Put(Eigen::Matrix3d(Eigen::AngleAxisd(phi, k).toRotationMatrix() * R00), b.R0);
    Put(Eigen::Vector3d(k * phid), b.omega_rad_s);
    Put(Eigen::Vector3d(k * phidd), b.alpha_rad_s2);
    return b;
  }
};

// Positions and orientations of the chain at time t (firmware FK, itself checked against an
// Eigen DH chain in test_kinematics.cpp).
struct Snapshot {
  Eigen::Vector3d c[8], payload;
  Eigen::Matrix3d R[8];
};

Snapshot Snap(const uvms_arm_model_t &m, const Trajectory &tr, double t) {
  static uvms_arm_data_t d;
  uvms_real_t q[7], qd[7], qdd[7];
  tr.q(t, q, qd, qdd);
  const uvms_base_state_t b = tr.base(t);
  REQUIRE(uvms_arm_fk(&m, &d, b.position_m, b.R0, q) == UVMS_OK);
  Snapshot s;
  for (int i = 1; i <= 7; ++i) {
    s.c[i] = V(d.com_m[i]);
    s.R[i] = M(d.R[i]);
  }
  s.payload = V(d.payload_m);
  return s;
}

// Angular momentum about the inertial origin, velocities by central differences (step h).
Eigen::Vector3d AngularMomentum(const uvms_arm_model_t &m, const Trajectory &tr, double t,
                                double h) {
  const Snapshot sm = Snap(m, tr, t - h), s0 = Snap(m, tr, t), sp = Snap(m, tr, t + h);
  Eigen::Vector3d L = Eigen::Vector3d::Zero();
  for (int i = 1; i <= 7; ++i) {
    const double mi = double(m.p->link[i - 1].mass_kg);
    const Eigen::Vector3d cd = (sp.c[i] - sm.c[i]) / (2 * h);
    const Eigen::AngleAxisd aa(sp.R[i] * sm.R[i].transpose());
    const Eigen::Vector3d w = aa.angle() * aa.axis() / (2 * h);
    const Eigen::Matrix3d I = s0.R[i] * V(m.p->link[i - 1].inertia_kg_m2).asDiagonal() *
                              s0.R[i].transpose();
    L += mi * s0.c[i].cross(cd) + I * w;
  }
  const Eigen::Vector3d pd = (sp.payload - sm.payload) / (2 * h);
  L += double(m.p->payload_kg) * s0.payload.cross(pd);
  return L;
}

}  // namespace

TEST_CASE("BaseWrenchEqualsRateOfChangeOfChainMomentum", "[dynamics]") {
  // With ρ = 0 and g = 0 the only external wrench on the chain (links + payload) is the one the
  // vehicle applies at the base point: f1 = dP/dt and n1 + p_B × f1 = dL_O/dt (about the origin).
  const auto m = PaperModel(10.0);
  const Trajectory tr;
  const uvms_fluid_t fl = Fluid(0.0);
  static uvms_arm_data_t d;
  const double h = kFloat ? 3e-2 : 1e-3;  // FD step [s]: truncation O(h²) vs roundoff eps/h²
  const double tol_f = kFloat ? 3e-2 : 1e-5;  // [N]
  const double tol_n = kFloat ? 3e-2 : 1e-5;  // [N·m]
  for (const double t : {0.0, 0.7, 1.9, 3.3}) {
    uvms_real_t q[7], qd[7], qdd[7];
    tr.q(t, q, qd, qdd);
    const uvms_base_state_t b = tr.base(t);
    REQUIRE(uvms_arm_rnea(&m, &d, &b, &fl, q, qd, qdd) == UVMS_OK);
    const Eigen::Vector3d f1 = V(d.f_N[1]), n1 = V(d.n_Nm[1]), pB = V(d.p_m[0]);

    // S(t) = Σ m_i c_i + m_payload p_payload; f1 = S̈ (second central difference).
    auto S = [&](double tt) {
      const Snapshot s = Snap(m, tr, tt);
      Eigen::Vector3d acc = double(m.p->payload_kg) * s.payload;
      for (int i = 1; i <= 7; ++i) acc += double(m.p->link[i - 1].mass_kg) * s.c[i];
      return acc;
    };
    const Eigen::Vector3d Sdd = (S(t + h) - 2 * S(t) + S(t - h)) / (h * h);
    INFO("t = " << t << " f1 = " << f1.transpose() << " S'' = " << Sdd.transpose());
    CHECK((f1 - Sdd).norm() < tol_f);
    CHECK(f1.norm() > 1.0);  // the check is not vacuous: the chain really accelerates

    const Eigen::Vector3d Ld =
        (AngularMomentum(m, tr, t + h, h) - AngularMomentum(m, tr, t - h, h)) / (2 * h);
    const Eigen::Vector3d nO = n1 + pB.cross(f1);
    INFO("n_O = " << nO.transpose() << " dL/dt = " << Ld.transpose());
    CHECK((nO - Ld).norm() < tol_n * std::max(1.0, Ld.norm()));
  }
}

TEST_CASE("JointTorquesEqualLagrangeEquationsOnFixedBase", "[dynamics]") {
  // τ = M(q)·q̈ + Ṁ·q̇ − ½·∂(q̇ᵀMq̇)/∂q + ∂V/∂q, with M(q) = Σ m_i J_ciᵀJ_ci + J_ωiᵀ I_i J_ωi
  // (+ payload) from the kinematics, its derivatives by central differences, V gravitational.
  const auto m = PaperModel(2.0);
  const Eigen::Vector3d g(0, 0, -9.81);
  const uvms_fluid_t fl = Fluid(0.0, g);
  static uvms_arm_data_t d;
  uvms_base_state_t b{};
  uvms_m3_identity(b.R0);
  using Mat7 = Eigen::Matrix<double, 7, 7>;
  using Vec7 = Eigen::Matrix<double, 7, 1>;

  auto fk = [&](const Vec7 &q) {
    uvms_real_t qq[7];
    for (int j = 0; j < 7; ++j) qq[j] = uvms_real_t(q[j]);
    REQUIRE(uvms_arm_fk(&m, &d, b.position_m, b.R0, qq) == UVMS_OK);
  };
  auto mass_matrix = [&](const Vec7 &q) {
    fk(q);
    Mat7 Mq = Mat7::Zero();
    auto add_point = [&](double mass, const Eigen::Vector3d &x, int last) {
      Eigen::Matrix<double, 3, 7> Jv = Eigen::Matrix<double, 3, 7>::Zero();
      for (int j = 1; j <= last; ++j) Jv.col(j - 1) = V(d.z[j]).cross(x - V(d.p_m[j - 1]));
      Mq += mass * Jv.transpose() * Jv;
    };
    for (int i = 1; i <= 7; ++i) {
      add_point(double(m.p->link[i - 1].mass_kg), V(d.com_m[i]), i);
      Eigen::Matrix<double, 3, 7> Jw = Eigen::Matrix<double, 3, 7>::Zero();
      for (int j = 1; j <= i; ++j) Jw.col(j - 1) = V(d.z[j]);
      const Eigen::Matrix3d I = M(d.R[i]) * V(m.p->link[i - 1].inertia_kg_m2).asDiagonal() *
                                M(d.R[i]).transpose();
      Mq += Jw.transpose() * I * Jw;
    }
    add_point(double(m.p->payload_kg), V(d.payload_m), 7);
    return Mq;
  };
  auto potential = [&](const Vec7 &q) {
    fk(q);
    double Vg = -double(m.p->payload_kg) * g.dot(V(d.payload_m));
    for (int i = 1; i <= 7; ++i) Vg -= double(m.p->link[i - 1].mass_kg) * g.dot(V(d.com_m[i]));
    return Vg;
  };

  const double h = kFloat ? 1e-2 : 1e-5;
  std::mt19937 rng(2718);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  for (int trial = 0; trial < 5; ++trial) {
    Vec7 q, qd, qdd;
    for (int j = 0; j < 7; ++j) {
      q[j] = 2 * u(rng);
      qd[j] = u(rng);
      qdd[j] = u(rng);
    }
    Mat7 dM[7];
    Vec7 dV;
    for (int k = 0; k < 7; ++k) {
      Vec7 qp = q, qm = q;
      qp[k] += h;
      qm[k] -= h;
      dM[k] = (mass_matrix(qp) - mass_matrix(qm)) / (2 * h);
      dV[k] = (potential(qp) - potential(qm)) / (2 * h);
    }
    Mat7 Mdot = Mat7::Zero();
    for (int k = 0; k < 7; ++k) Mdot += dM[k] * qd[k];
    Vec7 tau_ref = mass_matrix(q) * qdd + Mdot * qd + dV;
    for (int k = 0; k < 7; ++k) tau_ref[k] -= 0.5 * qd.dot(dM[k] * qd);

    uvms_real_t qq[7], qqd[7], qqdd[7];
    for (int j = 0; j < 7; ++j) {
      qq[j] = uvms_real_t(q[j]);
      qqd[j] = uvms_real_t(qd[j]);
      qqdd[j] = uvms_real_t(qdd[j]);
    }
    REQUIRE(uvms_arm_rnea(&m, &d, &b, &fl, qq, qqd, qqdd) == UVMS_OK);
    for (int k = 0; k < 7; ++k) {
      INFO("trial " << trial << " joint " << k + 1);
      CHECK(double(d.tau_Nm[k + 1]) == Approx(tau_ref[k]).margin(kFloat ? 5e-3 : 1e-7));
    }
  }
}

TEST_CASE("HydrostaticTorquesAreTheGradientOfWeightAndBuoyancyPotential", "[dynamics]") {
  // At rest (q̇ = q̈ = 0), τ = ∂V/∂q with V = Σ(−m_i·g·c_i + β_i·g·μ_i) − m_p·g·p_p: buoyancy
  // β_i = ρV_i acts upward at μ_i = l_i/2 [23, 25].
  const auto m = PaperModel(1.0);
  const Eigen::Vector3d g(0, 0, -1.315);  // Europa
  const uvms_fluid_t fl = Fluid(kRho, g);
  static uvms_arm_data_t d;
  uvms_base_state_t b{};
  Put(Eigen::Matrix3d(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix()), b.R0);
  const double qv[7] = {0.2, 0.9, -0.4, 1.6, 0.3, -0.7, 0.5};
  const uvms_real_t zero[7] = {0, 0, 0, 0, 0, 0, 0};
  auto potential = [&](const double *q) {
    uvms_real_t qq[7];
    for (int j = 0; j < 7; ++j) qq[j] = uvms_real_t(q[j]);
    REQUIRE(uvms_arm_fk(&m, &d, b.position_m, b.R0, qq) == UVMS_OK);
    double Vp = -double(m.p->payload_kg) * g.dot(V(d.payload_m));
    for (int i = 1; i <= 7; ++i) {
      const Eigen::Vector3d mu = V(d.p_m[i - 1]) + 0.5 * V(d.Rl_m[i]);  // μ_i = l_i/2 (SPEC §3.1)
      Vp += -double(m.p->link[i - 1].mass_kg) * g.dot(V(d.com_m[i])) +
            kRho * double(m.volume_m3[i]) * g.dot(mu);
    }
    return Vp;
  };
  uvms_real_t qq[7];
  for (int j = 0; j < 7; ++j) qq[j] = uvms_real_t(qv[j]);
  REQUIRE(uvms_arm_rnea(&m, &d, &b, &fl, qq, zero, zero) == UVMS_OK);
  double tau[8];
  for (int i = 1; i <= 7; ++i) tau[i] = double(d.tau_Nm[i]);
  const double h = kFloat ? 1e-2 : 1e-6;
  for (int k = 0; k < 7; ++k) {
    double qp[7], qm[7];
    for (int j = 0; j < 7; ++j) qp[j] = qm[j] = qv[j];
    qp[k] += h;
    qm[k] -= h;
    const double dV = (potential(qp) - potential(qm)) / (2 * h);
    INFO("joint " << k + 1);
    CHECK(tau[k + 1] == Approx(dV).margin(kFloat ? 1e-3 : 1e-8));
  }
}

namespace {
// One straight link of length L along z of frame 1 (α = 0, a = 0, d = L), mass m, CoM at L/2.
fwtest::OwnedModel OneLink(double L, double mass, double alpha = 0.0, double a = 0.0,
                         Eigen::Vector3d com_shift = Eigen::Vector3d::Zero()) {
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  p.num_joints = 1;
  p.payload_kg = 0;
  auto &l = p.link[0];
  l.alpha_rad = uvms_real_t(alpha);
  l.a_m = uvms_real_t(a);
  l.d_m = uvms_real_t(a == 0.0 ? L : 0.0);
  l.mass_kg = uvms_real_t(mass);
  l.com_m[0] = uvms_real_t(a / 2);
  l.com_m[1] = uvms_real_t(a == 0.0 ? L / 2 * std::sin(alpha) : 0.0);
  l.com_m[2] = uvms_real_t(a == 0.0 ? L / 2 * std::cos(alpha) : 0.0);
  for (int k = 0; k < 3; ++k) l.com_m[k] += uvms_real_t(com_shift[k]);
  return fwtest::OwnedModel(p);
}
}  // namespace

TEST_CASE("SingleLinkInUniformFlowAtZero45And90DegreesAngleOfAttack", "[dynamics][hydro]") {
  // Link along inertial z (q = 0, R0 = I), at rest; flow of speed U at angle β from the link
  // axis. Relative velocity w = −v∞, so D = ½ρ·C_D·A·U·v∞ along the flow [19], with
  // C_D = C_D0L·sin²β with the angle-of-attack factor [21] and C_D0L without.
  // Then f1 = −D [24] and n1 = (L/2)·ẑ × (−D) [25] (moment about the base point).
  const double L = 0.5, U = 0.4, dL = 0.089, CD0 = 1.0;
  const double area = dL * L;
  const auto m = OneLink(L, 3.0);
  static uvms_arm_data_t d;
  uvms_base_state_t b{};
  uvms_m3_identity(b.R0);
  const uvms_real_t q[1] = {0}, z1[1] = {0};
  for (const int aoa : {1, 0}) {
    for (const double beta_deg : {0.0, 45.0, 90.0}) {
      const double beta = beta_deg * M_PI / 180.0;
      const Eigen::Vector3d vinf = U * Eigen::Vector3d(std::sin(beta), 0, std::cos(beta));
      const uvms_fluid_t fl = Fluid(kRho, Eigen::Vector3d::Zero(), aoa, vinf);
      REQUIRE(uvms_arm_rnea(&m, &d, &b, &fl, q, z1, z1) == UVMS_OK);
      const double cd = aoa ? CD0 * std::pow(std::sin(beta), 2) : CD0;
      const Eigen::Vector3d D = 0.5 * kRho * cd * area * U * vinf;
      INFO("aoa " << aoa << " beta " << beta_deg << " D = " << D.transpose());
      const double tol = kFloat ? 1e-5 : 1e-12;
      CHECK((V(d.drag_N[1]) - D).norm() < tol);
      CHECK((V(d.f_N[1]) + D).norm() < tol);
      CHECK((V(d.n_Nm[1]) - Eigen::Vector3d(0, 0, L / 2).cross(-D)).norm() < tol);
    }
  }
}

TEST_CASE("SpinningLinkFeelsDragAtItsAerodynamicCenter", "[dynamics][hydro]") {
  // Link along x of frame 1 (a = L, d = 0) spinning at θ̇ about z in still water: the
  // aerodynamic center (L/2 from the joint) moves at θ̇·L/2 broadside (α = 90°), so
  // D = ½ρ·C_D0L·A·(θ̇L/2)² opposing the motion and the joint torque is τ = (L/2)·|D|.
  // Centripetal inertia and added-mass forces point along the link: no torque about z.
  const double L = 0.6, qd = 1.5, dL = 0.089, CD0 = 1.0;
  const auto m = OneLink(L, 2.0, 0.0, L);
  static uvms_arm_data_t d;
  uvms_base_state_t b{};
  uvms_m3_identity(b.R0);
  const uvms_fluid_t fl = Fluid(kRho);
  const uvms_real_t q[1] = {0}, qdv[1] = {uvms_real_t(qd)}, qdd[1] = {0};
  REQUIRE(uvms_arm_rnea(&m, &d, &b, &fl, q, qdv, qdd) == UVMS_OK);
  const double speed = qd * L / 2;
  const double Dmag = 0.5 * kRho * CD0 * dL * L * speed * speed;
  CHECK(double(d.drag_N[1][1]) == Approx(-Dmag).epsilon(kFloat ? 1e-5 : 1e-12));
  CHECK(double(d.tau_Nm[1]) == Approx(L / 2 * Dmag).epsilon(kFloat ? 1e-5 : 1e-12));
}

TEST_CASE("AddedMassUnderPureTranslation", "[dynamics][hydro]") {
  // Whole system translating with acceleration a, no rotation, nothing moving relative to the
  // vehicle, no flow relative velocity (zero velocity). Every point accelerates at a, so
  // (SPEC §3.3) F_am = R1·ρV·Ma0[0:3,0:3]·R1ᵀ·a and M_am = R1·ρV·Ma0[3:6,0:3]·R1ᵀ·a about μ.
  // Then f1 = m·a + F_am and n1 = r × m·a + μ × F_am + M_am about the base point.
  const double L = 0.55, mass = 1.8;
  // CoM off the buoyancy center, so that the added-mass moment's shift matters.
  const auto m = OneLink(L, mass, -M_PI / 2, 0.0, Eigen::Vector3d(0.03, -0.1, 0.02));
  static uvms_arm_data_t d;
  uvms_base_state_t b{};
  const Eigen::Matrix3d R0 =
      Eigen::AngleAxisd(0.8, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  Put(R0, b.R0);
  const Eigen::Vector3d a(0.7, -1.1, 0.4);
  Put(a, b.accel_m_s2);
  const uvms_fluid_t fl = Fluid(kRho);
  const uvms_real_t q[1] = {0.7f}, z1[1] = {0};
  REQUIRE(uvms_arm_rnea(&m, &d, &b, &fl, q, z1, z1) == UVMS_OK);

  Eigen::Matrix<double, 6, 6> Ma0;
  uvms_real_t ma[36];
  uvms_added_mass_paper(ma);
  for (int i = 0; i < 36; ++i) Ma0(i / 6, i % 6) = double(ma[i]);
  const Eigen::Matrix3d R1 = M(d.R[1]);
  const double rhoV = kRho * M_PI * 0.089 * 0.089 / 4 * L;
  const Eigen::Vector3d ab = R1.transpose() * a;
  const Eigen::Vector3d Fam = R1 * (rhoV * Ma0.block<3, 3>(0, 0) * ab);
  const Eigen::Vector3d Mam = R1 * (rhoV * Ma0.block<3, 3>(3, 0) * ab);
  const Eigen::Vector3d r = R1 * V(m.p->link[0].com_m), mu = R1 * (0.5 * V(m.l_m[1]));
  const Eigen::Vector3d f1 = mass * a + Fam;
  const Eigen::Vector3d n1 = r.cross(mass * a) + mu.cross(Fam) + Mam;
  const double tol = kFloat ? 1e-5 : 1e-12;
  CHECK(Fam.norm() > 0.1);  // the added mass is material here (ρV·0.1·|a| ≈ 0.45 N)
  CHECK((V(d.f_N[1]) - f1).norm() < tol);
  CHECK((V(d.n_Nm[1]) - n1).norm() < tol);
}

TEST_CASE("AddedMassOfASpinningAngularlyAcceleratingLinkActsAtItsBuoyancyCenter", "[dynamics][hydro]") {
  // One link (a = L, α = −π/2, d = 0: l = (L, 0, 0) in frame 1) on a vehicle at rest, turning
  // about its joint at θ̇ with θ̈ in still water, g = 0. In frame 1 (the link's body frame) the
  // joint axis is e = (Rz(θ)·Rx(α))ᵀ·ẑ = (0, −1, 0), ω_b = θ̇·e, ω̇_b = θ̈·e, and the buoyancy
  // center μ = l/2 (SPEC §3.1) accelerates at
  //   a_μ = ω̇_b × μ + ω_b × (ω_b × μ) = (−θ̇²·L/2, 0, θ̈·L/2)   (centripetal + tangential).
  // SPEC §3.3: the fluid's reaction is −ρV·Ma0·(a_μ; ω̇_b), so the joint must supply
  //   F_am = R1·ρV·Ma0[0:3,:]·(a_μ; ω̇_b),  M_am = R1·ρV·Ma0[3:6,:]·(a_μ; ω̇_b) about μ,
  // where ω̇_b's column of Ma0 enters both (Ma0[2][4] = −0.001 gives F_z, Ma0[4][4] the moment).
  // With the rigid-body terms (CoM r off μ) and the broadside drag at η = μ (α = 90°, C_D = C_D0L):
  //   f1 = m·a_c + F_am − D,   n1 = r × m·a_c + N_c + μ × F_am + M_am + μ × (−D)   [24–25].
  const double L = 0.6, mass = 2.0, alpha = -M_PI / 2, q = 0.4, qd = 1.5, qdd = 2.0;
  const Eigen::Vector3d shift(0.02, 0.03, -0.01);
  const auto m = OneLink(L, mass, alpha, L, shift);
  static uvms_arm_data_t d;
  uvms_base_state_t b{};
  const Eigen::Matrix3d R0 =
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(-1, 2, 0.5).normalized()).toRotationMatrix();
  Put(R0, b.R0);
  Put(Eigen::Vector3d(0.3, -1.0, 2.0), b.position_m);
  const uvms_fluid_t fl = Fluid(kRho);
  const uvms_real_t qv[1] = {uvms_real_t(q)}, qdv[1] = {uvms_real_t(qd)},
                    qddv[1] = {uvms_real_t(qdd)};
  REQUIRE(uvms_arm_rnea(&m, &d, &b, &fl, qv, qdv, qddv) == UVMS_OK);

  // SPEC §3.3, typed from the specification.
  Eigen::Matrix<double, 6, 6> Ma0;
  Ma0 << 0.1, 0, 0, 0, 0, 0,  //
      0, 0.1, -0.01, 0, 0, 0,     //
      0, -0.01, 0.1, 0, -0.001, 0,  //
      0, 0, 0, 0.01, 0, 0.001,    //
      0, 0, -0.001, 0, 0.01, 0,   //
      0, 0, 0, 0.001, 0, 0.01;
  const Eigen::Matrix3d A1 = (Eigen::AngleAxisd(q, Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(alpha, Eigen::Vector3d::UnitX()))
                                 .toRotationMatrix();
  const Eigen::Matrix3d R1 = R0 * A1;
  CHECK((M(d.R[1]) - R1).norm() < (kFloat ? 1e-6 : 1e-14));
  const Eigen::Vector3d e = A1.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d w_b = qd * e, al_b = qdd * e;
  const Eigen::Vector3d mu_b(L / 2, 0, 0);
  const Eigen::Vector3d a_mu = al_b.cross(mu_b) + w_b.cross(w_b.cross(mu_b));
  CHECK((a_mu - Eigen::Vector3d(-qd * qd * L / 2, 0, qdd * L / 2)).norm() < 1e-12);
  Eigen::Matrix<double, 6, 1> acc;
  acc << a_mu, al_b;
  const double dL = 0.089, rhoV = kRho * M_PI * dL * dL / 4 * L;
  const Eigen::Matrix<double, 6, 1> fm = rhoV * Ma0 * acc;
  const Eigen::Vector3d F_am = R1 * fm.head<3>(), M_am = R1 * fm.tail<3>();

  const Eigen::Vector3d r_b = Eigen::Vector3d(L / 2, 0, 0) + shift;
  const Eigen::Vector3d a_c = R1 * (al_b.cross(r_b) + w_b.cross(w_b.cross(r_b)));
  const Eigen::Vector3d Id(0.1349, 0.1133, 0.0905);  // SPEC §3.1, link 1 (OneLink keeps it)
  const Eigen::Vector3d N_c =
      R1 * (Id.asDiagonal() * al_b + w_b.cross(Eigen::Vector3d(Id.asDiagonal() * w_b)));
  const Eigen::Vector3d w_eta = R1 * w_b.cross(mu_b);  // still water: relative velocity
  const Eigen::Vector3d D = -0.5 * kRho * 1.0 * (dL * L) * w_eta.norm() * w_eta;
  const Eigen::Vector3d r = R1 * r_b, mu = R1 * mu_b;
  const Eigen::Vector3d f1 = mass * a_c + F_am - D;
  const Eigen::Vector3d n1 = r.cross(mass * a_c) + N_c + mu.cross(F_am) + M_am + mu.cross(-D);

  CHECK(F_am.norm() > 0.2);                      // ≈ ρV·0.1·|a_μ|, |a_μ| ≈ 0.92 m/s²
  CHECK(std::fabs(fm[1]) > 1e-3);                // the Ma0 coupling terms are exercised
  CHECK(std::fabs(rhoV * 0.001 * qdd) > 5e-3);   // the ω̇ column's force
  const double tol = kFloat ? 2e-5 : 1e-12;
  CHECK((V(d.drag_N[1]) - D).norm() < tol);
  CHECK((V(d.f_N[1]) - f1).norm() < tol * std::max(1.0, f1.norm()));
  CHECK((V(d.n_Nm[1]) - n1).norm() < tol * std::max(1.0, n1.norm()));
}

TEST_CASE("BarycenterVelocityIsTheTimeDerivativeOfTheBarycenter", "[dynamics]") {
  // ṗ_cm of the forward pass against a central difference of p_cm [5] (from the kinematics)
  // along the smooth whole-system trajectory: vehicle translating and turning, every joint
  // moving, 10 kg payload.
  const auto m = PaperModel(10.0);
  const Trajectory tr;
  static uvms_arm_data_t d;
  const double h = kFloat ? 1e-2 : 1e-5;      // FD step [s]
  const double tol = kFloat ? 5e-4 : 1e-8;    // [m/s]: O(h²) truncation vs eps/h roundoff
  auto barycenter = [&](double t) {
    uvms_real_t q[7], qd[7], qdd[7];
    tr.q(t, q, qd, qdd);
    const uvms_base_state_t b = tr.base(t);
    REQUIRE(uvms_arm_fk(&m, &d, b.position_m, b.R0, q) == UVMS_OK);
    return V(d.barycenter_m);
  };
  for (const double t : {0.0, 0.7, 1.9, 3.3}) {
    const Eigen::Vector3d fd = (barycenter(t + h) - barycenter(t - h)) / (2 * h);
    uvms_real_t q[7], qd[7], qdd[7];
    tr.q(t, q, qd, qdd);
    const uvms_base_state_t b = tr.base(t);
    REQUIRE(uvms_arm_forward(&m, &d, &b, q, qd, qdd) == UVMS_OK);
    const Eigen::Vector3d v = V(d.barycenter_v_m_s);
    INFO("t = " << t << " v = " << v.transpose() << " FD = " << fd.transpose());
    CHECK(v.norm() > 0.05);  // not vacuous
    CHECK((V(d.vc_m_s[0]) - v).norm() > 0.01);  // differs from the vehicle's own velocity
    CHECK((v - fd).norm() < tol);
  }
}

TEST_CASE("VehicleDragIsQuadraticInRelativeVelocity", "[dynamics][hydro]") {
  // D0 = −½ρ·C_D0·A0·|w0|·w0, w0 = v0 − v∞ (SPEC [31]); C_D0 = 1.2, A0 = 0.5 m².
  const auto m = PaperModel();
  static uvms_arm_data_t d;
  uvms_base_state_t b{};
  uvms_m3_identity(b.R0);
  const Eigen::Vector3d v0(0.3, -0.1, 0.05), vinf(0.02, 0.01, 0);
  Put(v0, b.velocity_m_s);
  const uvms_fluid_t fl = Fluid(kRho, Eigen::Vector3d::Zero(), 1, vinf);
  uvms_real_t q[7] = {3.14f, 1.57f, 3.14f, 3.14f, 0, 0, 0}, z7[7] = {0, 0, 0, 0, 0, 0, 0};
  REQUIRE(uvms_arm_rnea(&m, &d, &b, &fl, q, z7, z7) == UVMS_OK);
  const Eigen::Vector3d w = v0 - vinf;
  const Eigen::Vector3d D0 = -0.5 * kRho * 1.2 * 0.5 * w.norm() * w;
  CHECK((V(d.drag_N[0]) - D0).norm() < (kFloat ? 1e-5 : 1e-12));
}
