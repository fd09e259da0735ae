// SPDX-License-Identifier: Apache-2.0
// Kinematics checked against an independent homogeneous-transform DH chain (Eigen), finite
// differences (Jacobians), and SPEC §8's joint-angle table intent.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <random>

#include "fw_test_util.hpp"
#include "uvms/kinematics.h"

using namespace fwtest;

namespace {

// Eigen's angle-axis of a rotation vector (identity for 0).
Eigen::AngleAxisd AngleAxisOf(const uvms_real_t rotvec[3]) {
  const Eigen::Vector3d v = V(rotvec);
  return v.norm() > 0 ? Eigen::AngleAxisd(v.norm(), v.normalized()) : Eigen::AngleAxisd::Identity();
}

// Standard DH: T_i = Rz(θ)·Tz(d)·Tx(a)·Rx(α), then a general link's T(t_i)·Rot(ρ_i), computed
// with Eigen's transforms (independent of the firmware's closed-form A_i and its l_i); frame 0
// is the base B, turned by the mount's Rot(ρ_B). Returns every frame's transform.
std::vector<Eigen::Isometry3d> DhChain(const uvms_arm_params_t &p, const Eigen::Vector3d &r0,
                                       const Eigen::Matrix3d &R0, const std::vector<double> &q) {
  std::vector<Eigen::Isometry3d> T(p.num_joints + 1);
  T[0] = Eigen::Isometry3d::Identity();
  T[0].linear() = R0 * AngleAxisOf(p.vehicle.base_rotvec_rad).toRotationMatrix();
  T[0].translation() = r0 + R0 * V(p.vehicle.base_offset_m);
  for (size_t i = 1; i <= p.num_joints; ++i) {
    const auto &L = p.link[i - 1];
    Eigen::Isometry3d A = Eigen::Isometry3d::Identity();
    A.rotate(Eigen::AngleAxisd(q[i - 1], Eigen::Vector3d::UnitZ()));
    A.translate(Eigen::Vector3d(0, 0, double(L.d_m)));
    A.translate(Eigen::Vector3d(double(L.a_m), 0, 0));
    A.rotate(Eigen::AngleAxisd(double(L.alpha_rad), Eigen::Vector3d::UnitX()));
    A.translate(V(L.placement_m));
    A.rotate(AngleAxisOf(L.placement_rotvec_rad));
    T[i] = T[i - 1] * A;
  }
  return T;
}

std::vector<double> RandomQ(std::mt19937 &rng) {
  std::uniform_real_distribution<double> u(-M_PI, M_PI);
  std::vector<double> q(7);
  for (auto &x : q) x = u(rng);
  return q;
}

Eigen::Matrix3d RandomRot(std::mt19937 &rng) {
  std::normal_distribution<double> n(0, 1);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

struct Fk {
  uvms_arm_data_t d;
};

void RunFk(const uvms_arm_model_t &m, uvms_arm_data_t &d, const Eigen::Vector3d &r0,
           const Eigen::Matrix3d &R0, const std::vector<double> &q) {
  uvms_real_t r[3], R[9], qq[7];
  Put(r0, r);
  Put(R0, R);
  for (int i = 0; i < 7; ++i) qq[i] = uvms_real_t(q[i]);
  REQUIRE(uvms_arm_fk(&m, &d, r, R, qq) == UVMS_OK);
}

}  // namespace

TEST_CASE("ForwardKinematicsMatchesHomogeneousDhChain", "[kinematics]") {
  const auto m = PaperModel();
  std::mt19937 rng(31);
  static uvms_arm_data_t d;
  const double tol = kFloat ? 2e-5 : 1e-12;  // positions of O(1 m) after ~50 operations
  for (int trial = 0; trial < 50; ++trial) {
    const auto q = RandomQ(rng);
    const Eigen::Matrix3d R0 = RandomRot(rng);
    const Eigen::Vector3d r0(0.3, -1.2, 2.0);
    RunFk(m, d, r0, R0, q);
    const auto T = DhChain(*m.p, r0, R0, q);
    for (size_t i = 0; i <= 7; ++i) {
      CHECK((V(d.p_m[i]) - T[i].translation()).norm() < tol);
      CHECK((M(d.R[i]) - T[i].linear()).cwiseAbs().maxCoeff() < tol);
    }
    double msum = double(m.p->vehicle.mass_kg) + double(m.p->payload_kg);
    Eigen::Vector3d mc = double(m.p->vehicle.mass_kg) * r0 +
                         double(m.p->payload_kg) * T[7].translation();
    for (size_t i = 1; i <= 7; ++i) {
      // c_i = p_{i−1}* + R_i·r_i (SPEC §2)
      const Eigen::Vector3d c = T[i - 1].translation() + T[i].linear() * V(m.p->link[i - 1].com_m);
      CHECK((V(d.com_m[i]) - c).norm() < tol);
      mc += double(m.p->link[i - 1].mass_kg) * c;
      msum += double(m.p->link[i - 1].mass_kg);
    }
    CHECK((V(d.ee_m) - T[7].translation()).norm() < tol);
    CHECK((V(d.barycenter_m) - mc / msum).norm() < tol);
  }
}

TEST_CASE("GeneralLinksAndAMountRotationMatchTheHomogeneousChain", "[kinematics]") {
  // docs/MODEL.md §2 "General links": the paper's arm with a random fixed placement (t_i, ρ_i)
  // after every other link's DH transform and a turned mount, against Eigen's transforms.
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  for (size_t i = 0; i < 7; i += 2) {
    Put(Eigen::Vector3d(Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.1), p.link[i].placement_m);
    Put(Eigen::Vector3d(Eigen::Vector3d(u(rng), u(rng), u(rng)) * 1.5), p.link[i].placement_rotvec_rad);
  }
  Put(Eigen::Vector3d(0.0, M_PI / 2, 0.0), p.vehicle.base_rotvec_rad);  // joint 1 along +x
  const OwnedModel m(p);
  REQUIRE(m.placed == 0xAAu);  // links 1, 3, 5, 7
  REQUIRE(m.base_rotated == 1);
  static uvms_arm_data_t d;
  const double tol = kFloat ? 2e-5 : 1e-12;
  for (int trial = 0; trial < 50; ++trial) {
    const auto q = RandomQ(rng);
    const Eigen::Matrix3d R0 = RandomRot(rng);
    const Eigen::Vector3d r0(0.3, -1.2, 2.0);
    RunFk(m, d, r0, R0, q);
    const auto T = DhChain(p, r0, R0, q);
    for (size_t i = 0; i <= 7; ++i) {
      CHECK((V(d.p_m[i]) - T[i].translation()).norm() < tol);
      CHECK((M(d.R[i]) - T[i].linear()).cwiseAbs().maxCoeff() < tol);
    }
    for (size_t i = 1; i <= 7; ++i) {
      const Eigen::Vector3d c = T[i - 1].translation() + T[i].linear() * V(p.link[i - 1].com_m);
      CHECK((V(d.com_m[i]) - c).norm() < tol);
      CHECK((V(d.z[i]) - T[i - 1].linear().col(2)).norm() < tol);  // joint i's axis
    }
  }
}

TEST_CASE("JacobiansMatchCentralFiniteDifferences", "[kinematics]") {
  const auto m = PaperModel(5.0);
  std::mt19937 rng(5);
  static uvms_arm_data_t d;
  // Central differences: truncation ~h²·|x'''|/6, roundoff ~eps·|x|/h.
  const double h = kFloat ? 1e-2 : 1e-6;
  const double tol = kFloat ? 2e-3 : 1e-8;
  for (int trial = 0; trial < 20; ++trial) {
    const auto q = RandomQ(rng);
    const Eigen::Matrix3d R0 = RandomRot(rng);
    const Eigen::Vector3d r0(1, 2, 3);
    RunFk(m, d, r0, R0, q);
    uvms_real_t J[6 * 7], Jcm[3 * 7];
    REQUIRE(uvms_arm_jacobian(&m, &d, J) == UVMS_OK);
    REQUIRE(uvms_arm_barycenter_jacobian(&m, &d, Jcm) == UVMS_OK);
    for (int j = 0; j < 7; ++j) {
      auto qp = q, qm = q;
      qp[j] += h;
      qm[j] -= h;
      RunFk(m, d, r0, R0, qp);
      const Eigen::Vector3d ep = V(d.ee_m), cp = V(d.barycenter_m);
      const Eigen::Matrix3d Rp = M(d.R[7]);
      RunFk(m, d, r0, R0, qm);
      const Eigen::Vector3d em = V(d.ee_m), cm = V(d.barycenter_m);
      const Eigen::Matrix3d Rm = M(d.R[7]);
      const Eigen::Vector3d dv = (ep - em) / (2 * h);
      const Eigen::Vector3d dcm = (cp - cm) / (2 * h);
      // Angular column: the rotation vector of Rp·Rmᵀ over 2h.
      const Eigen::AngleAxisd aa(Rp * Rm.transpose());
      const Eigen::Vector3d dw = aa.angle() * aa.axis() / (2 * h);
      for (int r = 0; r < 3; ++r) {
        CHECK(std::abs(double(J[r * 7 + j]) - dv[r]) < tol);
        CHECK(std::abs(double(J[(r + 3) * 7 + j]) - dw[r]) < tol);
        CHECK(std::abs(double(Jcm[r * 7 + j]) - dcm[r]) < tol);
      }
    }
  }
}

TEST_CASE("VirtualManipulatorOffsetIsIndependentOfVehiclePosition", "[kinematics]") {
  const auto m = PaperModel();
  std::mt19937 rng(8);
  static uvms_arm_data_t d;
  const auto q = RandomQ(rng);
  const Eigen::Matrix3d R0 = RandomRot(rng);
  uvms_real_t R[9], qq[7], rel[3];
  Put(R0, R);
  for (int i = 0; i < 7; ++i) qq[i] = uvms_real_t(q[i]);
  REQUIRE(uvms_arm_ee_minus_barycenter(&m, &d, R, qq, rel) == UVMS_OK);
  for (const Eigen::Vector3d &r0 : {Eigen::Vector3d(5, -3, 2), Eigen::Vector3d(-100, 0, 7)}) {
    RunFk(m, d, r0, R0, q);
    CHECK((V(d.ee_m) - V(d.barycenter_m) - V(rel)).norm() < (kFloat ? 1e-4 : 1e-12));
  }
}

TEST_CASE("ModelInitRejectsInvalidParametersWithSpecificStatus", "[kinematics]") {
  uvms_arm_params_t p;
  uvms_arm_model_t m;
  uvms_arm_params_paper(&p);
  REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);
  CHECK(m.ready == 1);

  auto expect = [&](uvms_status_t want, auto mutate) {
    uvms_arm_params_t q;
    uvms_arm_params_paper(&q);
    mutate(q);
    CHECK(uvms_arm_model_init(&q, &m) == want);
    CHECK(m.ready == 0);
  };
  expect(UVMS_ERR_SIZE, [](uvms_arm_params_t &q) { q.num_joints = 0; });
  expect(UVMS_ERR_SIZE, [](uvms_arm_params_t &q) { q.num_joints = UVMS_MAX_JOINTS + 1; });
  expect(UVMS_ERR_NONFINITE, [](uvms_arm_params_t &q) { q.link[3].d_m = uvms_real_t(NAN); });
  expect(UVMS_ERR_NONFINITE, [](uvms_arm_params_t &q) { q.vehicle.cob_m[1] = uvms_real_t(INFINITY); });
  expect(UVMS_ERR_NONFINITE, [](uvms_arm_params_t &q) { q.added_mass_coeff[35] = uvms_real_t(NAN); });
  expect(UVMS_ERR_RANGE, [](uvms_arm_params_t &q) { q.vehicle.mass_kg = 0; });
  expect(UVMS_ERR_RANGE, [](uvms_arm_params_t &q) { q.link[0].mass_kg = -1; });
  expect(UVMS_ERR_RANGE, [](uvms_arm_params_t &q) { q.vehicle.volume_m3 = -0.1f; });
  expect(UVMS_ERR_RANGE, [](uvms_arm_params_t &q) { q.payload_kg = -2; });
  expect(UVMS_ERR_RANGE, [](uvms_arm_params_t &q) { q.link[2].joint_min_rad = q.link[2].joint_max_rad; });
  CHECK(uvms_arm_model_init(nullptr, &m) == UVMS_ERR_ARG);
}

TEST_CASE("LinkHydroGeometryFollowsSpec31", "[kinematics]") {
  const auto m = PaperModel();
  // Links 1, 2, 6 have |l_i| = 0 (a = d = 0): no volume or area (SPEC §3.1).
  for (int i : {1, 2, 6}) {
    CHECK(m.length_m[i] == 0);
    CHECK(m.volume_m3[i] == 0);
  }
  // Link 3: |l| = sqrt(0.045² + 0.55²); V = π·0.089²/4·|l|; A = 0.089·|l|.
  const double len3 = std::sqrt(0.045 * 0.045 + 0.55 * 0.55);
  CHECK(double(m.length_m[3]) == Approx(len3).epsilon(1e-6));
  CHECK(double(m.volume_m3[3]) == Approx(M_PI * 0.089 * 0.089 / 4 * len3).epsilon(1e-6));
  CHECK(double(m.area_m2[3]) == Approx(0.089 * len3).epsilon(1e-6));
  // m_T = 120 + Σ m_i (19.45) + 10
  CHECK(double(m.total_mass_kg) == Approx(120 + 19.45 + 10).epsilon(1e-6));
}
