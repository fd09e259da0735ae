// SPDX-License-Identifier: Apache-2.0
// Firmware linear algebra checked against Eigen (an independent implementation).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "uvms/linalg.h"
#include "eigen_reference.hpp"

namespace {

// Tolerance of one operation chain in the controller's real type: float builds carry ~1e-7
// relative rounding per operation, double ~1e-16; a few dozen operations per result.
constexpr double kTol = UVMS_REAL_IS_FLOAT ? 2e-5 : 1e-12;

using Mat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

Mat3 ToEigen(const uvms_real_t R[9]) {
  Mat3 M;
  for (int i = 0; i < 9; ++i) M.data()[i] = static_cast<double>(R[i]);
  return M;
}

Eigen::Quaterniond RandomQuat(std::mt19937 &rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q;
}

}  // namespace

TEST_CASE("QuatToRotMatchesEigen", "[linalg]") {
  std::mt19937 rng(12345);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Quaterniond q = RandomQuat(rng);
    const uvms_real_t qf[4] = {uvms_real_t(q.w()), uvms_real_t(q.x()), uvms_real_t(q.y()),
                               uvms_real_t(q.z())};
    uvms_real_t R[9];
    REQUIRE(uvms_quat_to_rot(qf, R) == UVMS_OK);
    CHECK((ToEigen(R) - q.toRotationMatrix()).cwiseAbs().maxCoeff() < kTol);
  }
}

TEST_CASE("QuatToRotRejectsNonFiniteAndZeroWithIdentity", "[linalg]") {
  uvms_real_t R[9] = {5, 5, 5, 5, 5, 5, 5, 5, 5};
  const uvms_real_t qnan[4] = {uvms_real_t(NAN), 0, 0, 0};
  CHECK(uvms_quat_to_rot(qnan, R) == UVMS_ERR_NONFINITE);
  CHECK(ToEigen(R).isIdentity(0.0));
  const uvms_real_t qzero[4] = {0, 0, 0, 0};
  R[1] = 7;
  CHECK(uvms_quat_to_rot(qzero, R) == UVMS_ERR_RANGE);
  CHECK(ToEigen(R).isIdentity(0.0));
}

TEST_CASE("RotToQuatRoundTripIncludingNearPi", "[linalg]") {
  std::mt19937 rng(777);
  for (int trial = 0; trial < 200; ++trial) {
    Eigen::Quaterniond q = RandomQuat(rng);
    if (trial % 4 == 0) {  // rotations within 1e-3 rad of pi exercise the non-trace branches
      const Eigen::Vector3d axis = q.vec().normalized();
      q = Eigen::Quaterniond(Eigen::AngleAxisd(M_PI - 1e-3 * (trial % 7) / 7.0, axis));
    }
    if (q.w() < 0) q.coeffs() *= -1.0;
    Mat3 M = q.toRotationMatrix();
    uvms_real_t R[9], qo[4];
    for (int i = 0; i < 9; ++i) R[i] = uvms_real_t(M.data()[i]);
    uvms_rot_to_quat(R, qo);
    // q and -q are the same rotation; at w = 0 exactly both signs are valid.
    const double s = (double(qo[0]) * q.w() + double(qo[1]) * q.x() + double(qo[2]) * q.y() +
                      double(qo[3]) * q.z()) < 0 ? -1.0 : 1.0;
    CHECK(std::abs(s * qo[0] - q.w()) < 10 * kTol);
    CHECK(std::abs(s * qo[1] - q.x()) < 10 * kTol);
    CHECK(std::abs(s * qo[2] - q.y()) < 10 * kTol);
    CHECK(std::abs(s * qo[3] - q.z()) < 10 * kTol);
  }
}

TEST_CASE("CrossAndMatrixProductsMatchEigen", "[linalg]") {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int trial = 0; trial < 50; ++trial) {
    uvms_real_t a[3], b[3], A[9], B[9], c[3], AB[9], ABt[9], Atb[3];
    for (auto &x : a) x = uvms_real_t(u(rng));
    for (auto &x : b) x = uvms_real_t(u(rng));
    for (auto &x : A) x = uvms_real_t(u(rng));
    for (auto &x : B) x = uvms_real_t(u(rng));
    const Eigen::Vector3d ea(a[0], a[1], a[2]), eb(b[0], b[1], b[2]);
    uvms_v3_cross(a, b, c);
    CHECK((Eigen::Vector3d(c[0], c[1], c[2]) - ea.cross(eb)).norm() < kTol * 10);
    uvms_m3_mul(A, B, AB);
    CHECK((ToEigen(AB) - ToEigen(A) * ToEigen(B)).cwiseAbs().maxCoeff() < kTol * 10);
    uvms_m3_mul_t(A, B, ABt);
    CHECK((ToEigen(ABt) - ToEigen(A) * ToEigen(B).transpose()).cwiseAbs().maxCoeff() < kTol * 10);
    uvms_m3t_mul_v3(A, b, Atb);
    CHECK((Eigen::Vector3d(Atb[0], Atb[1], Atb[2]) - ToEigen(A).transpose() * eb).norm() <
          kTol * 10);
    // Aliasing: output overwriting an input gives the same result.
    uvms_real_t a2[3] = {a[0], a[1], a[2]};
    uvms_v3_cross(a2, b, a2);
    CHECK((Eigen::Vector3d(a2[0], a2[1], a2[2]) - ea.cross(eb)).norm() < kTol * 10);
  }
}

TEST_CASE("RotationVectorAtZeroSmallHalfPiAndNearPi", "[linalg]") {
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, -2.0, 0.5).normalized();
  // Angles: exactly 0, tiny (series branch), small, pi/2, and within 1e-6 of pi.
  for (const double phi : {0.0, 1e-9, 1e-5, 1e-3, M_PI / 2, 3.0, M_PI - 1e-6}) {
    const Mat3 M = Eigen::AngleAxisd(phi, axis).toRotationMatrix();
    uvms_real_t R[9], rv[3];
    for (int i = 0; i < 9; ++i) R[i] = uvms_real_t(M.data()[i]);
    uvms_rot_to_rotvec(R, rv);
    const Eigen::Vector3d got(rv[0], rv[1], rv[2]);
    // Float rounding of R itself (1e-7) limits the angle near pi to ~sqrt(1e-7)-ish in axis;
    // the vector error is bounded by the matrix rounding amplified by at most ~1/sin(phi/2).
    const double tol = UVMS_REAL_IS_FLOAT ? 1e-3 : 1e-9;
    INFO("phi = " << phi);
    CHECK((got - phi * axis).norm() < tol);
  }
}

// uvms_quat_error_rotvec against two other routes: Eigen's angle-axis of the exact error
// rotation (independent), and the firmware's matrix route (E = R(q_d)·R(q)ᵀ, then Shepperd's
// quaternion in uvms_rot_to_rotvec), which the controller's attitude feedback used before
// 0.10.0; that route shares only the last step, quaternion to rotation vector (linalg.c).
TEST_CASE("QuaternionErrorIsTheRotationVectorOfRdRt", "[linalg]") {
  std::mt19937 rng(31337);
  std::uniform_real_distribution<double> log_norm(-3.0, 3.0);  // norms 1e-3 .. 1e3
  std::normal_distribution<double> gauss(0.0, 1.0);
  // [rad] per unit of angle (at least 1 rad): the inputs' rounding, 1e-16 (double) or 6e-8
  // (float) relative. In float the tiny angles below are at the inputs' resolution: there they
  // only show that no 0/0 arises.
  const double tol = UVMS_REAL_IS_FLOAT ? 2e-6 : 1e-14;
  const double angles[] = {0.0, 1e-12, 1e-7, 1e-3, 0.5, M_PI / 2, 3.0, M_PI - 1e-6, M_PI};
  const int kFixed = int(sizeof angles / sizeof angles[0]);
  for (int trial = 0; trial < 400; ++trial) {
    const Eigen::Quaterniond qm = RandomQuat(rng);
    const Eigen::Vector3d axis =
        Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    // The error angle: the fixed set (0, tiny, small, π/2, near and at π) twice, once with
    // each sign of e_w, then random ones.
    const double phi = trial < 2 * kFixed
                           ? angles[trial % kFixed]
                           : M_PI * std::uniform_real_distribution<double>(0, 1)(rng);
    // q_d = (phi about axis) ∘ q, so E = R(q_d)·R(q)ᵀ is phi about axis (inertial).
    const Eigen::Quaterniond qd = Eigen::AngleAxisd(phi, axis) * qm;
    // Norms from 1e-3 to 1e3 and either sign of each quaternion (the same rotations); in the
    // fixed set's second pass q_d is negated, which flips the sign of e_w.
    const double sd = trial < kFixed ? 1.0 : trial < 2 * kFixed ? -1.0 : (trial % 3 ? 1.0 : -1.0);
    const double sm = trial < 2 * kFixed ? 1.0 : (trial % 5 ? 1.0 : -1.0);
    const double kd = sd * std::pow(10.0, log_norm(rng)), km = sm * std::pow(10.0, log_norm(rng));
    const uvms_real_t qd4[4] = {uvms_real_t(kd * qd.w()), uvms_real_t(kd * qd.x()),
                                uvms_real_t(kd * qd.y()), uvms_real_t(kd * qd.z())};
    const uvms_real_t q4[4] = {uvms_real_t(km * qm.w()), uvms_real_t(km * qm.x()),
                               uvms_real_t(km * qm.y()), uvms_real_t(km * qm.z())};
    uvms_real_t rv[3];
    uvms_quat_error_rotvec(qd4, q4, rv);
    const Eigen::Vector3d got(rv[0], rv[1], rv[2]);
    INFO("trial " << trial << ", phi = " << phi);
    // Only at exactly pi are both axis signs the same rotation.
    const Eigen::Vector3d want = phi * axis;
    const double err =
        std::min((got - want).norm(), phi == M_PI ? (got + want).norm() : 1e300);
    CHECK(err < tol * std::max(1.0, phi));
    // The matrix route, from the same (rounded) quaternions.
    uvms_real_t Rd[9], Rm[9], E[9], rv_m[3];
    REQUIRE(uvms_quat_to_rot(qd4, Rd) == UVMS_OK);
    REQUIRE(uvms_quat_to_rot(q4, Rm) == UVMS_OK);
    uvms_m3_mul_t(Rd, Rm, E);
    uvms_rot_to_rotvec(E, rv_m);
    const Eigen::Vector3d via_matrix(rv_m[0], rv_m[1], rv_m[2]);
    const double err_m = std::min((got - via_matrix).norm(),
                                  phi == M_PI ? (got + via_matrix).norm() : 1e300);
    CHECK(err_m < 4 * tol * std::max(1.0, phi));
  }
  // Exactly the same attitude: exactly zero, whatever the norms.
  const uvms_real_t a[4] = {uvms_real_t(0.5), uvms_real_t(-0.5), uvms_real_t(0.5), uvms_real_t(0.5)};
  const uvms_real_t b[4] = {uvms_real_t(-2.0), uvms_real_t(2.0), uvms_real_t(-2.0), uvms_real_t(-2.0)};
  uvms_real_t rv0[3] = {1, 1, 1};
  uvms_quat_error_rotvec(a, b, rv0);
  CHECK(rv0[0] == 0);
  CHECK(rv0[1] == 0);
  CHECK(rv0[2] == 0);
}

// Below a half-angle tangent t = |v|/|w| of 2^-6 (an angle of 0.0312 rad) the rotation vector
// takes φ/|v| from the series of atan(t)/t instead of sqrt and atan2 (linalg.c). Against long
// double (2·atan2l of the quaternion's own, rounded components), for angles from 1e-30 rad to
// 0.06 rad and densely on both sides of the switch, random axes, norms and signs of w: within
// two ulp of the real type on either route, so the two agree where they meet (without the
// series' t⁸ term the worst was 2.6 ulp). The error is measured against |φ|, over the vector;
// the reference is x86-64's 80-bit long double, 11 bits past double.
TEST_CASE("SmallAngleSeriesMatchesAtan2OnBothSidesOfTheSwitch", "[linalg]") {
  std::mt19937 rng(4242);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> log_norm(-3.0, 3.0), u01(0.0, 1.0);
  const double eps = UVMS_REAL_IS_FLOAT ? 1.1920929e-7 : 2.220446049250313e-16;
  const double phi_switch = 2.0 * std::atan(1.0 / 64.0);
  std::vector<double> angles;
  for (int e = -300; e <= -12; ++e) angles.push_back(std::pow(10.0, 0.1 * e));  // 1e-30 .. 0.063
  for (int i = -200; i <= 200; ++i) angles.push_back(phi_switch * (1.0 + 1e-4 * i));
  const uvms_real_t identity[4] = {uvms_real_t(1), uvms_real_t(0), uvms_real_t(0), uvms_real_t(0)};
  double worst_series = 0.0, worst_atan2 = 0.0;
  int series = 0, general = 0;
  // Norms: random from 1e-3 to 1e3, and every third angle at an end of the range linalg.h
  // states (1e±15 in float, 1e±150 in double). Where |v|'s squares underflow (tiny angles), the
  // series still gives (2/|w|)·v.
  const double range_end = UVMS_REAL_IS_FLOAT ? 15.0 : 150.0;
  int at_range_ends = 0;
  for (size_t a = 0; a < angles.size(); ++a) {
    const double phi = angles[a];
    const Eigen::Vector3d axis = Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)).normalized();
    double exponent = log_norm(rng);
    if (a % 3 == 0) {
      exponent = (a % 2 ? 1.0 : -1.0) * range_end;
      ++at_range_ends;
    }
    const double k = (u01(rng) < 0.5 ? -1.0 : 1.0) * std::pow(10.0, exponent);
    // e = q_d ⊗ conj(identity) = q_d: the quaternion goes to the rotation vector unchanged.
    const uvms_real_t qd[4] = {uvms_real_t(k * std::cos(phi / 2)),
                               uvms_real_t(k * std::sin(phi / 2) * axis.x()),
                               uvms_real_t(k * std::sin(phi / 2) * axis.y()),
                               uvms_real_t(k * std::sin(phi / 2) * axis.z())};
    uvms_real_t rv[3];
    uvms_quat_error_rotvec(qd, identity, rv);
    const long double w = qd[0], x = qd[1], y = qd[2], z = qd[3];
    const long double sv = std::sqrt(x * x + y * y + z * z);
    const long double ratio = 2.0L * std::atan2(sv, std::fabs(w)) / sv * (w < 0 ? -1.0L : 1.0L);
    const long double ref[3] = {ratio * x, ratio * y, ratio * z};
    const long double ref_norm = std::fabs(2.0L * std::atan2(sv, std::fabs(w)));
    double err = 0.0;
    for (int c = 0; c < 3; ++c) err = std::max(err, double(std::fabs(rv[c] - ref[c]) / ref_norm));
    const bool in_series = double(sv) <= std::fabs(double(w)) / 64.0;
    double &worst = in_series ? worst_series : worst_atan2;
    worst = std::max(worst, err);
    (in_series ? series : general) += 1;
    INFO("phi = " << phi << ", |q| = " << std::fabs(k) << ", error " << err / eps << " ulp");
    CHECK(err < 2.0 * eps);
  }
  INFO("worst relative error: series " << worst_series / eps << " ulp, atan2 "
                                        << worst_atan2 / eps << " ulp");
  CHECK(series > 300);  // both routes were taken
  CHECK(general > 150);
  CHECK(at_range_ends > 100);
  // Outside that range the result is wrong (linalg.h) but never NaN for finite input: a norm
  // whose squares underflow gives 0, one whose squares overflow gives a finite vector.
  const double tiny = UVMS_REAL_IS_FLOAT ? 1e-25 : 1e-160;
  const double huge = UVMS_REAL_IS_FLOAT ? 1e25 : 1e160;
  const uvms_real_t outside[][4] = {
      {uvms_real_t(tiny), 0, 0, 0},
      {uvms_real_t(-tiny), uvms_real_t(tiny * 1e-8), 0, 0},
      {uvms_real_t(huge), uvms_real_t(huge * 1e-3), 0, 0},
      {uvms_real_t(-huge), uvms_real_t(huge), uvms_real_t(huge), 0}};
  for (const auto &q : outside) {
    uvms_real_t rv[3];
    uvms_quat_error_rotvec(q, identity, rv);
    INFO("q = (" << q[0] << ", " << q[1] << ", " << q[2] << ", " << q[3] << ")");
    for (const uvms_real_t c : rv) CHECK(std::isfinite(double(c)));
  }
}

TEST_CASE("SpdSolveMatchesEigenLltAndRejectsSingular", "[linalg]") {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::Matrix<double, 6, 8> H;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 8; ++j) H(i, j) = u(rng);
  const Eigen::Matrix<double, 6, 6> G = H * H.transpose();
  const Eigen::Matrix<double, 6, 8> Bm = H;
  uvms_real_t A[36], B[48], X[48];
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) A[6 * i + j] = uvms_real_t(G(i, j));
    for (int j = 0; j < 8; ++j) B[8 * i + j] = uvms_real_t(Bm(i, j));
  }
  REQUIRE(uvms_spd_solve(6, A, 8, B, X, uvms_real_t(1e-7)) == UVMS_OK);
  const Eigen::Matrix<double, 6, 8> Xe = G.llt().solve(Bm);
  double err = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 8; ++j) err = std::max(err, std::abs(double(X[8 * i + j]) - Xe(i, j)));
  CHECK(err < (UVMS_REAL_IS_FLOAT ? 1e-3 : 1e-10) * Xe.cwiseAbs().maxCoeff());

  // Rank-deficient Gram matrix (two identical rows of H): singular status, zero output.
  Eigen::Matrix<double, 6, 8> H2 = H;
  H2.row(5) = H2.row(4);
  const Eigen::Matrix<double, 6, 6> G2 = H2 * H2.transpose();
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j) A[6 * i + j] = uvms_real_t(G2(i, j));
  CHECK(uvms_spd_solve(6, A, 8, B, X, uvms_real_t(1e-7)) == UVMS_ERR_SINGULAR);
  for (int i = 0; i < 48; ++i) CHECK(X[i] == 0);
  CHECK(uvms_spd_solve(0, A, 1, B, X, uvms_real_t(1e-7)) == UVMS_ERR_ARG);
  CHECK(uvms_spd_solve(6, nullptr, 1, B, X, uvms_real_t(1e-7)) == UVMS_ERR_ARG);
}

TEST_CASE("StatusNamesAreDistinct", "[status]") {
  CHECK(std::string(uvms_status_str(UVMS_OK)) == "UVMS_OK");
  CHECK(std::string(uvms_status_str(UVMS_ERR_SINGULAR)) == "UVMS_ERR_SINGULAR");
  CHECK(std::string(uvms_status_str(static_cast<uvms_status_t>(-99))) == "UVMS_ERR_UNKNOWN");
}

// ---------------------------------------------------------------------------------------------
// Symmetric eigen-decomposition (Jacobi) against Eigen's SelfAdjointEigenSolver, which uses a
// different algorithm (tridiagonalisation + implicit QL): eigenvalues equal after sorting,
// and the firmware's own V is orthogonal with A·V = V·Λ.

namespace {

using MatX = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Runs uvms_sym_eig on A (rounded to the real type) and checks it against Eigen on the same
// rounded matrix. Returns the sweeps used.
uint32_t CheckSymEig(const MatX &A_in) {
  const int n = static_cast<int>(A_in.rows());
  std::vector<uvms_real_t> A(static_cast<size_t>(n * n));
  MatX Ar(n, n);
  for (int i = 0; i < n * n; ++i) {
    A[static_cast<size_t>(i)] = static_cast<uvms_real_t>(A_in.data()[i]);
    Ar.data()[i] = static_cast<double>(A[static_cast<size_t>(i)]);
  }
  std::vector<uvms_real_t> lam(static_cast<size_t>(n)), V(static_cast<size_t>(n * n));
  uint32_t sweeps = 99;
  REQUIRE(uvms_sym_eig(static_cast<size_t>(n), A.data(), lam.data(), V.data(), &sweeps) == UVMS_OK);
  CHECK(sweeps <= UVMS_SYM_EIG_MAX_SWEEPS);
  Eigen::VectorXd l(n);
  MatX Vm(n, n);
  for (int i = 0; i < n; ++i) l(i) = static_cast<double>(lam[static_cast<size_t>(i)]);
  for (int i = 0; i < n * n; ++i) Vm.data()[i] = static_cast<double>(V[static_cast<size_t>(i)]);
  const double scale = std::max(1.0, Ar.norm());
  Eigen::VectorXd ls = l;
  std::sort(ls.data(), ls.data() + n);
  CHECK((ls - uvms_test::SymmetricEigenvalues(Ar)).cwiseAbs().maxCoeff() < 50 * kTol * scale);
  CHECK((Vm.transpose() * Vm - MatX::Identity(n, n)).cwiseAbs().maxCoeff() < 50 * kTol);
  CHECK((Ar * Vm - Vm * l.asDiagonal()).cwiseAbs().maxCoeff() < 50 * kTol * scale);
  return sweeps;
}

}  // namespace

TEST_CASE("SymmetricEigenMatchesEigenSelfAdjointSolver", "[linalg]") {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> ud(-3.0, 3.0);
  uint32_t max_sweeps = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % UVMS_SPD_MAX_N;
    MatX B(n, n);
    for (int i = 0; i < n * n; ++i) B.data()[i] = ud(rng);
    MatX A = B + B.transpose();  // general symmetric, indefinite
    if (trial % 3 == 1) A = B * B.transpose();  // positive semidefinite
    if (trial % 3 == 2 && n > 2) {
      // Rank-deficient PSD, as a Gram matrix H_u·H_uᵀ with lost directions: rank n − 2.
      const MatX C = B.leftCols(n - 2);
      A = C * C.transpose();
    }
    INFO("trial " << trial << " n " << n);
    max_sweeps = std::max(max_sweeps, CheckSymEig(A));
  }
  INFO("most sweeps " << max_sweeps);
  CHECK(max_sweeps <= 10);
  // Degenerate inputs: zero, diagonal (no rotation needed), repeated eigenvalues.
  CHECK(CheckSymEig(MatX::Zero(6, 6)) == 0);
  MatX D = MatX::Zero(6, 6);
  D.diagonal() << 3, -1, 0, 2, 2, 5;
  CHECK(CheckSymEig(D) == 0);
  CheckSymEig(MatX::Identity(6, 6) + MatX::Ones(6, 6));  // eigenvalues 7, 1×5
}

TEST_CASE("SymmetricEigenRejectsBadArgumentsWithZeroOutputs", "[linalg]") {
  uvms_real_t A[4] = {1, 2, 2, 1}, lam[2] = {7, 7}, V[4] = {7, 7, 7, 7};
  uint32_t sweeps = 5;
  A[3] = static_cast<uvms_real_t>(NAN);
  CHECK(uvms_sym_eig(2, A, lam, V, &sweeps) == UVMS_ERR_NONFINITE);
  CHECK((lam[0] == 0 && lam[1] == 0 && V[0] == 0 && V[3] == 0 && sweeps == 0));
  A[3] = 1;
  CHECK(uvms_sym_eig(0, A, lam, V, &sweeps) == UVMS_ERR_ARG);
  CHECK(uvms_sym_eig(UVMS_SPD_MAX_N + 1, A, lam, V, &sweeps) == UVMS_ERR_ARG);
  CHECK(uvms_sym_eig(2, nullptr, lam, V, &sweeps) == UVMS_ERR_ARG);
  CHECK(uvms_sym_eig(2, A, lam, V, nullptr) == UVMS_OK);  // sweeps optional
}
