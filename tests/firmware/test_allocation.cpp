// Thrust allocation (SPEC §7.3 [33–39]) checked against Eigen: H built independently from the
// SPEC §3.4 table, H⁺ against Eigen's complete-orthogonal-decomposition pseudoinverse, and the
// allocation against its defining properties (H·P = wrench, minimum norm, the pos/att split).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "uvms/allocation.h"

namespace {

// Relative tolerance of a short operation chain in the controller's real type (float ~1e-7
// per operation, double ~1e-16); H⁺ comes from a Cholesky solve of H·Hᵀ whose condition number
// is cond(H)² ≤ 12 for the paper's layout, so a few hundred eps covers it.
constexpr double kTol = UVMS_REAL_IS_FLOAT ? 2e-5 : 1e-12;

using Mat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
using MatH = Eigen::Matrix<double, 6, Eigen::Dynamic>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

// SPEC §3.4, typed in again here so that uvms_thruster_geometry_paper is checked, not trusted.
constexpr double kPaperA[8][3] = {{-0.5, 0.5, 0.5},  {-0.5, -0.5, 0.5}, {-0.5, 0.5, -0.5},
                                  {-0.5, -0.5, -0.5}, {0.1, 0.5, 0.0},   {0.1, -0.5, 0.0},
                                  {0.1, 0.0, 0.5},    {0.1, 0.0, -0.5}};
constexpr double kPaperU[8][3] = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0},
                                  {0, 0, 1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}};

// H = [u_j; a_j × u_j] from a geometry, in double, with Eigen's cross product.
MatH EigenH(const uvms_thruster_geometry_t &g) {
  const int n = static_cast<int>(g.num_thrusters);
  MatH H(6, n);
  for (int j = 0; j < n; ++j) {
    Eigen::Vector3d a(g.position_m[j][0], g.position_m[j][1], g.position_m[j][2]);
    Eigen::Vector3d u(g.direction[j][0], g.direction[j][1], g.direction[j][2]);
    u.normalize();
    H.col(j) << u, a.cross(u);
  }
  return H;
}

MatH PaperH() {
  MatH H(6, 8);
  for (int j = 0; j < 8; ++j) {
    const Eigen::Vector3d a(kPaperA[j][0], kPaperA[j][1], kPaperA[j][2]);
    const Eigen::Vector3d u(kPaperU[j][0], kPaperU[j][1], kPaperU[j][2]);
    H.col(j) << u, a.cross(u);
  }
  return H;
}

// The firmware's row-major arrays as Eigen matrices.
MatH FirmwareH(const uvms_alloc_t &al) {
  const int n = static_cast<int>(al.geom.num_thrusters);
  MatH H(6, n);
  for (int r = 0; r < 6; ++r)
    for (int j = 0; j < n; ++j) H(r, j) = static_cast<double>(al.H[r * n + j]);
  return H;
}

Eigen::MatrixXd FirmwarePinv(const uvms_alloc_t &al) {
  const int n = static_cast<int>(al.geom.num_thrusters);
  Eigen::MatrixXd P(n, 6);
  for (int j = 0; j < n; ++j)
    for (int r = 0; r < 6; ++r) P(j, r) = static_cast<double>(al.H_pinv[j * 6 + r]);
  return P;
}

Eigen::MatrixXd EigenPinv(const MatH &H) {
  return Eigen::MatrixXd(H).completeOrthogonalDecomposition().pseudoInverse();
}

Eigen::VectorXd ToVec(const uvms_real_t *x, int n) {
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = static_cast<double>(x[i]);
  return v;
}

Mat3 RandomRotation(std::mt19937 &rng) {
  std::normal_distribution<double> nd(0.0, 1.0);
  Eigen::Quaterniond q(nd(rng), nd(rng), nd(rng), nd(rng));
  q.normalize();
  return q.toRotationMatrix();
}

// The rotation rounded to the real type, and back: the reference uses exactly what the
// firmware saw.
Mat3 ToReal(const Mat3 &M, uvms_real_t R[9]) {
  Mat3 Mr;
  for (int i = 0; i < 9; ++i) {
    R[i] = static_cast<uvms_real_t>(M.data()[i]);
    Mr.data()[i] = static_cast<double>(R[i]);
  }
  return Mr;
}

Eigen::Vector3d ToReal(const Eigen::Vector3d &v, uvms_real_t out[3]) {
  Eigen::Vector3d vr;
  for (int i = 0; i < 3; ++i) {
    out[i] = static_cast<uvms_real_t>(v(i));
    vr(i) = static_cast<double>(out[i]);
  }
  return vr;
}

uvms_thruster_geometry_t RandomGeometry(std::mt19937 &rng, size_t n) {
  std::uniform_real_distribution<double> ud(-1.0, 1.0);
  std::normal_distribution<double> nd(0.0, 1.0);
  uvms_thruster_geometry_t g{};
  g.num_thrusters = n;
  for (size_t j = 0; j < n; ++j) {
    for (int k = 0; k < 3; ++k) {
      g.position_m[j][k] = static_cast<uvms_real_t>(ud(rng));
      g.direction[j][k] = static_cast<uvms_real_t>(nd(rng));
    }
  }
  return g;
}

uvms_alloc_t PaperAlloc() {
  uvms_thruster_geometry_t g;
  uvms_thruster_geometry_paper(&g);
  uvms_alloc_t al;
  REQUIRE(uvms_alloc_init(&al, &g) == UVMS_OK);
  return al;
}

void FillGarbage(uvms_real_t *x) {
  for (int j = 0; j < UVMS_MAX_THRUSTERS; ++j) x[j] = static_cast<uvms_real_t>(123.0 + j);
}

bool AllZero(const uvms_real_t *x, int n) {
  for (int j = 0; j < n; ++j)
    if (x[j] != 0) return false;
  return true;
}

}  // namespace

TEST_CASE("PaperGeometryMatchesSpecTableAndBuildsH", "[allocation]") {
  uvms_thruster_geometry_t g;
  uvms_thruster_geometry_paper(&g);
  REQUIRE(g.num_thrusters == 8);
  for (int j = 0; j < 8; ++j) {
    for (int k = 0; k < 3; ++k) {
      CHECK(static_cast<double>(g.position_m[j][k]) == Approx(kPaperA[j][k]).margin(1e-7));
      CHECK(static_cast<double>(g.direction[j][k]) == kPaperU[j][k]);
    }
  }
  const uvms_alloc_t al = PaperAlloc();
  CHECK(al.ready == 1);
  CHECK(al.usable_mask == 0xFFu);
  CHECK((FirmwareH(al) - PaperH()).cwiseAbs().maxCoeff() < 1e-7);
}

TEST_CASE("PseudoinverseMatchesEigenCompleteOrthogonalDecomposition", "[allocation]") {
  // Paper layout, then random layouts with n = 6, 7, 8 (n < 8 exercises the 6×n stride).
  {
    const uvms_alloc_t al = PaperAlloc();
    const Eigen::MatrixXd ref = EigenPinv(PaperH());
    CHECK((FirmwarePinv(al) - ref).cwiseAbs().maxCoeff() < kTol * ref.cwiseAbs().maxCoeff());
  }
  std::mt19937 rng(2024);
  for (int trial = 0; trial < 30; ++trial) {
    const size_t n = 6 + static_cast<size_t>(trial % 3);
    const uvms_thruster_geometry_t g = RandomGeometry(rng, n);
    const MatH He = EigenH(g);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(He);
    const double cond = svd.singularValues()(0) / svd.singularValues()(5);
    uvms_alloc_t al;
    const uvms_status_t st = uvms_alloc_init(&al, &g);
    INFO("trial " << trial << " n " << n << " cond " << cond);
    if (cond > 1e3) {
      // Far too ill-conditioned for a thruster layout; only ask that it is not garbage.
      CHECK((st == UVMS_OK || st == UVMS_ERR_SINGULAR));
      continue;
    }
    REQUIRE(st == UVMS_OK);
    CHECK((FirmwareH(al) - He).cwiseAbs().maxCoeff() < kTol);
    const Eigen::MatrixXd ref = EigenPinv(He);
    // The Cholesky route squares the condition number.
    CHECK((FirmwarePinv(al) - ref).cwiseAbs().maxCoeff() <
          kTol * cond * cond * ref.cwiseAbs().maxCoeff());
  }
}

TEST_CASE("AllocationReproducesBodyWrenchForRandomWrenchesAndAttitudes", "[allocation]") {
  std::mt19937 rng(31337);
  std::uniform_real_distribution<double> ud(-50.0, 50.0);
  const uvms_alloc_t paper = PaperAlloc();
  uvms_alloc_t rand7;
  {
    std::mt19937 grng(7);
    const uvms_thruster_geometry_t g = RandomGeometry(grng, 7);
    REQUIRE(uvms_alloc_init(&rand7, &g) == UVMS_OK);
  }
  const uvms_alloc_t *const instances[] = {&paper, &rand7};
  for (const uvms_alloc_t *al : instances) {
    const MatH H = FirmwareH(*al);
    const int n = static_cast<int>(al->geom.num_thrusters);
    for (int trial = 0; trial < 100; ++trial) {
      uvms_real_t R0[9], F[3], N[3], P[UVMS_MAX_THRUSTERS];
      const Mat3 R = ToReal(RandomRotation(rng), R0);
      const Eigen::Vector3d f = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), F);
      const Eigen::Vector3d m = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), N);
      REQUIRE(uvms_alloc_step(al, R0, F, N, P, nullptr, nullptr) == UVMS_OK);
      Vec6 w_body;
      w_body << R.transpose() * f, R.transpose() * m;
      const Vec6 produced = H * ToVec(P, n);
      INFO("n " << n << " trial " << trial);
      CHECK((produced - w_body).norm() < 10 * kTol * w_body.norm());
      for (int j = n; j < UVMS_MAX_THRUSTERS; ++j) CHECK(P[j] == 0);
    }
  }
}

TEST_CASE("PositionAndAttitudeSplitSumsToTotalAndReproducesEachPart", "[allocation]") {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> ud(-20.0, 20.0);
  const uvms_alloc_t al = PaperAlloc();
  const MatH H = FirmwareH(al);
  for (int trial = 0; trial < 100; ++trial) {
    uvms_real_t R0[9], F[3], N[3], P[8], Ppos[8], Patt[8];
    const Mat3 R = ToReal(RandomRotation(rng), R0);
    const Eigen::Vector3d f = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), F);
    const Eigen::Vector3d m = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), N);
    REQUIRE(uvms_alloc_step(&al, R0, F, N, P, Ppos, Patt) == UVMS_OK);
    const Eigen::VectorXd p = ToVec(P, 8), pp = ToVec(Ppos, 8), pa = ToVec(Patt, 8);
    CHECK((pp + pa - p).cwiseAbs().maxCoeff() <= kTol * p.cwiseAbs().maxCoeff());
    Vec6 w_pos, w_att;
    w_pos << R.transpose() * f, Eigen::Vector3d::Zero();
    w_att << Eigen::Vector3d::Zero(), R.transpose() * m;
    CHECK((H * pp - w_pos).norm() < 10 * kTol * (f.norm() + 1.0));
    CHECK((H * pa - w_att).norm() < 10 * kTol * (m.norm() + 1.0));
  }
}

TEST_CASE("AllocatedThrustIsMinimumNormOrthogonalToNullSpaceOfH", "[allocation]") {
  const uvms_alloc_t al = PaperAlloc();
  const MatH H = PaperH();
  // Null space of the 6×8 H: the last two right singular vectors (H has rank 6).
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(H), Eigen::ComputeFullV);
  REQUIRE(svd.rank() == 6);
  const Eigen::MatrixXd Z = svd.matrixV().rightCols(2);
  REQUIRE((H * Z).norm() < 1e-12);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> ud(-30.0, 30.0);
  for (int trial = 0; trial < 100; ++trial) {
    uvms_real_t R0[9], F[3], N[3], P[8];
    ToReal(RandomRotation(rng), R0);
    ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), F);
    ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), N);
    REQUIRE(uvms_alloc_step(&al, R0, F, N, P, nullptr, nullptr) == UVMS_OK);
    const Eigen::VectorXd p = ToVec(P, 8);
    CHECK((Z.transpose() * p).norm() < 10 * kTol * p.norm());
    // Consequence: adding any null-space thrust (same wrench) costs more thrust norm.
    const Eigen::VectorXd other = p + Z * Eigen::Vector2d(0.3, -0.2);
    CHECK(other.norm() > p.norm());
  }
}

TEST_CASE("RemovingOneThrusterKeepsWrenchWithZeroThrustOnIt", "[allocation]") {
  const MatH H = PaperH();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> ud(-20.0, 20.0);
  for (int removed = 0; removed < 8; ++removed) {
    uvms_alloc_t al = PaperAlloc();
    const uint32_t mask = 0xFFu & ~(1u << removed);
    REQUIRE(uvms_alloc_set_usable(&al, mask) == UVMS_OK);
    REQUIRE(al.ready == 1);
    CHECK(al.usable_mask == mask);
    // H⁺ equals the pseudoinverse of H with that column removed (zero row in its place).
    MatH Hu = H;
    Hu.col(removed).setZero();
    const Eigen::MatrixXd ref = EigenPinv(Hu);
    CHECK((FirmwarePinv(al) - ref).cwiseAbs().maxCoeff() < kTol * ref.cwiseAbs().maxCoeff());
    for (int trial = 0; trial < 20; ++trial) {
      uvms_real_t R0[9], F[3], N[3], P[8];
      const Mat3 R = ToReal(RandomRotation(rng), R0);
      const Eigen::Vector3d f = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), F);
      const Eigen::Vector3d m = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), N);
      REQUIRE(uvms_alloc_step(&al, R0, F, N, P, nullptr, nullptr) == UVMS_OK);
      Vec6 w_body;
      w_body << R.transpose() * f, R.transpose() * m;
      INFO("removed " << removed << " trial " << trial);
      CHECK(P[removed] == 0);  // exactly: the removed thruster's row of H⁺ is zero
      CHECK((H * ToVec(P, 8) - w_body).norm() < 10 * kTol * w_body.norm());
    }
  }
}

TEST_CASE("PseudoinverseRecomputedOnlyWhenUsableMaskChanges", "[allocation]") {
  uvms_alloc_t al = PaperAlloc();
  CHECK(al.pinv_computations == 1u);  // init
  CHECK(uvms_alloc_set_usable(&al, 0xFFu) == UVMS_OK);  // unchanged: no work
  CHECK(al.pinv_computations == 1u);
  CHECK(uvms_alloc_set_usable(&al, 0xFFFFFF00u | 0xFFu) == UVMS_OK);  // bits ≥ n ignored
  CHECK(al.pinv_computations == 1u);
  CHECK(uvms_alloc_set_usable(&al, 0xFEu) == UVMS_OK);  // changed: one recomputation
  CHECK(al.pinv_computations == 2u);
  CHECK(uvms_alloc_set_usable(&al, 0xFEu) == UVMS_OK);  // same again: none
  CHECK(uvms_alloc_set_usable(&al, 0xFEu) == UVMS_OK);
  CHECK(al.pinv_computations == 2u);
  CHECK(uvms_alloc_set_usable(&al, 0xFFu) == UVMS_OK);  // back to all: one more
  CHECK(al.pinv_computations == 3u);
  // And the restored H⁺ equals the one from init.
  const uvms_alloc_t fresh = PaperAlloc();
  CHECK((FirmwarePinv(al) - FirmwarePinv(fresh)).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("LosingRankGivesSingularNotReadyAndZeroThrusts", "[allocation]") {
  uvms_alloc_t al = PaperAlloc();
  uvms_real_t R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  uvms_real_t F[3] = {1, 2, 3}, N[3] = {0.1, -0.2, 0.3};
  uvms_real_t P[8], Ppos[8], Patt[8];
  // Without thrusters 5 and 6 (the only ones along z) no vertical force is possible.
  const uint32_t no_heave = 0xFFu & ~((1u << 4) | (1u << 5));
  CHECK(uvms_alloc_set_usable(&al, no_heave) == UVMS_ERR_SINGULAR);
  CHECK(al.ready == 0);
  CHECK(AllZero(al.H_pinv, 8 * 6));
  FillGarbage(P);
  FillGarbage(Ppos);
  FillGarbage(Patt);
  CHECK(uvms_alloc_step(&al, R0, F, N, P, Ppos, Patt) == UVMS_ERR_SINGULAR);
  CHECK(AllZero(P, 8));
  CHECK(AllZero(Ppos, 8));
  CHECK(AllZero(Patt, 8));
  // Same mask again: same status, no recomputation.
  const uint32_t count = al.pinv_computations;
  CHECK(uvms_alloc_set_usable(&al, no_heave) == UVMS_ERR_SINGULAR);
  CHECK(al.pinv_computations == count);
  // Rank loss by a linear dependence (not a zero row): surge thrusters 1 and 4 out leaves
  // 2 and 3 to span Fx, My, Mz, which two columns cannot.
  CHECK(uvms_alloc_set_usable(&al, 0xFFu & ~((1u << 0) | (1u << 3))) == UVMS_ERR_SINGULAR);
  CHECK(al.ready == 0);
  // A full-rank set again: ready, and the step works.
  CHECK(uvms_alloc_set_usable(&al, 0xFFu) == UVMS_OK);
  CHECK(al.ready == 1);
  CHECK(uvms_alloc_step(&al, R0, F, N, P, nullptr, nullptr) == UVMS_OK);
  CHECK_FALSE(AllZero(P, 8));
}

TEST_CASE("InitRejectsInvalidGeometryWithSpecificStatusAndLeavesNotReady", "[allocation]") {
  uvms_thruster_geometry_t good;
  uvms_thruster_geometry_paper(&good);
  const uvms_real_t R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const uvms_real_t F[3] = {1, 2, 3}, N[3] = {0.1, -0.2, 0.3};

  struct Case {
    const char *what;
    uvms_thruster_geometry_t g;
    uvms_status_t expected;
  };
  std::vector<Case> cases;
  {
    Case c{"NaN position", good, UVMS_ERR_NONFINITE};
    c.g.position_m[3][1] = static_cast<uvms_real_t>(NAN);
    cases.push_back(c);
  }
  {
    Case c{"infinite direction", good, UVMS_ERR_NONFINITE};
    c.g.direction[6][2] = static_cast<uvms_real_t>(INFINITY);
    cases.push_back(c);
  }
  {
    Case c{"zero direction", good, UVMS_ERR_RANGE};
    c.g.direction[2][0] = 0;
    cases.push_back(c);
  }
  {
    Case c{"direction shorter than 1e-6", good, UVMS_ERR_RANGE};
    c.g.direction[7][1] = static_cast<uvms_real_t>(5e-7);
    cases.push_back(c);
  }
  {
    Case c{"n = 0", good, UVMS_ERR_ARG};
    c.g.num_thrusters = 0;
    cases.push_back(c);
  }
  {
    Case c{"n > UVMS_MAX_THRUSTERS", good, UVMS_ERR_SIZE};
    c.g.num_thrusters = UVMS_MAX_THRUSTERS + 1;
    cases.push_back(c);
  }
  {
    Case c{"all thrusters along x (rank 3)", good, UVMS_ERR_SINGULAR};
    for (int j = 0; j < 8; ++j) {
      c.g.direction[j][0] = 1;
      c.g.direction[j][1] = 0;
      c.g.direction[j][2] = 0;
    }
    cases.push_back(c);
  }
  {
    Case c{"only five thrusters", good, UVMS_ERR_SINGULAR};
    c.g.num_thrusters = 5;
    cases.push_back(c);
  }
  for (const Case &c : cases) {
    INFO(c.what);
    uvms_alloc_t al = PaperAlloc();  // a ready instance, so "not ready" is a real change
    CHECK(uvms_alloc_init(&al, &c.g) == c.expected);
    CHECK(al.ready == 0);
    CHECK(al.initialised == 0);
    CHECK(AllZero(al.H_pinv, 8 * 6));
    uvms_real_t P[8];
    FillGarbage(P);
    CHECK(uvms_alloc_step(&al, R0, F, N, P, nullptr, nullptr) == UVMS_ERR_STATE);
    CHECK(AllZero(P, 8));
    CHECK(uvms_alloc_set_usable(&al, 0xFFu) == UVMS_ERR_STATE);
  }
  uvms_alloc_t al;
  CHECK(uvms_alloc_init(&al, nullptr) == UVMS_ERR_ARG);
  CHECK(al.ready == 0);
  CHECK(uvms_alloc_init(nullptr, &good) == UVMS_ERR_ARG);
}

TEST_CASE("InitNormalisesNonUnitDirections", "[allocation]") {
  uvms_thruster_geometry_t g;
  uvms_thruster_geometry_paper(&g);
  const uvms_real_t scale[8] = {3, 0.5, 1, 7, 0.01f, 2, 1, 100};
  for (int j = 0; j < 8; ++j)
    for (int k = 0; k < 3; ++k) g.direction[j][k] *= scale[j];
  uvms_alloc_t al;
  REQUIRE(uvms_alloc_init(&al, &g) == UVMS_OK);
  const uvms_alloc_t ref = PaperAlloc();
  CHECK((FirmwareH(al) - FirmwareH(ref)).cwiseAbs().maxCoeff() < kTol);
  CHECK((FirmwarePinv(al) - FirmwarePinv(ref)).cwiseAbs().maxCoeff() < kTol);
  for (int j = 0; j < 8; ++j) {
    const Eigen::Vector3d u(al.geom.direction[j][0], al.geom.direction[j][1],
                            al.geom.direction[j][2]);
    CHECK(std::abs(u.norm() - 1.0) < kTol);
  }
  // Re-initialising from the instance's own (normalised) geometry gives the same instance.
  uvms_alloc_t again = al;
  REQUIRE(uvms_alloc_init(&again, &again.geom) == UVMS_OK);
  CHECK((FirmwareH(again) - FirmwareH(al)).cwiseAbs().maxCoeff() < kTol);
  CHECK((FirmwarePinv(again) - FirmwarePinv(al)).cwiseAbs().maxCoeff() < kTol);
}

TEST_CASE("StepRejectsNullAndNonFiniteInputsWithZeroOutputs", "[allocation]") {
  const uvms_alloc_t al = PaperAlloc();
  uvms_real_t R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  uvms_real_t F[3] = {1, 2, 3}, N[3] = {0.1, -0.2, 0.3};
  uvms_real_t P[8], Ppos[8], Patt[8];

  const auto expect_refused = [&](uvms_status_t expected, const uvms_real_t *r,
                                  const uvms_real_t *f, const uvms_real_t *m) {
    FillGarbage(P);
    FillGarbage(Ppos);
    FillGarbage(Patt);
    CHECK(uvms_alloc_step(&al, r, f, m, P, Ppos, Patt) == expected);
    CHECK(AllZero(P, 8));
    CHECK(AllZero(Ppos, 8));
    CHECK(AllZero(Patt, 8));
  };
  expect_refused(UVMS_ERR_ARG, nullptr, F, N);
  expect_refused(UVMS_ERR_ARG, R0, nullptr, N);
  expect_refused(UVMS_ERR_ARG, R0, F, nullptr);
  R0[4] = static_cast<uvms_real_t>(NAN);
  expect_refused(UVMS_ERR_NONFINITE, R0, F, N);
  R0[4] = 1;
  F[1] = static_cast<uvms_real_t>(INFINITY);
  expect_refused(UVMS_ERR_NONFINITE, R0, F, N);
  F[1] = 2;
  N[2] = static_cast<uvms_real_t>(-INFINITY);
  expect_refused(UVMS_ERR_NONFINITE, R0, F, N);
  N[2] = static_cast<uvms_real_t>(0.3);
  // Finite but so large that the body-frame force overflows the real type: rotated by 45°
  // about z, (max, max, 0) becomes (√2·max, 0, 0).
  {
    const uvms_real_t c = static_cast<uvms_real_t>(std::sqrt(0.5));
    const uvms_real_t R45[9] = {c, -c, 0, c, c, 0, 0, 0, 1};
    const uvms_real_t big = std::numeric_limits<uvms_real_t>::max();
    const uvms_real_t Fbig[3] = {big, big, 0};
    expect_refused(UVMS_ERR_NONFINITE, R45, Fbig, N);
  }

  FillGarbage(Ppos);
  CHECK(uvms_alloc_step(&al, R0, F, N, Ppos, nullptr, nullptr) == UVMS_OK);  // split optional
  CHECK(uvms_alloc_step(&al, R0, F, N, nullptr, Ppos, Patt) == UVMS_ERR_ARG);
  CHECK(AllZero(Ppos, 8));
  CHECK(AllZero(Patt, 8));
  CHECK(uvms_alloc_step(nullptr, R0, F, N, P, nullptr, nullptr) == UVMS_ERR_ARG);

  uvms_alloc_t zeroed{};  // never initialised
  FillGarbage(P);
  CHECK(uvms_alloc_step(&zeroed, R0, F, N, P, nullptr, nullptr) == UVMS_ERR_STATE);
  CHECK(AllZero(P, 8));
  CHECK(uvms_alloc_set_usable(&zeroed, 0xFFu) == UVMS_ERR_STATE);
  CHECK(uvms_alloc_set_usable(nullptr, 0xFFu) == UVMS_ERR_ARG);
}

TEST_CASE("WrenchBodyIsHTimesThrustAndInvertsAllocation", "[allocation]") {
  const uvms_alloc_t al = PaperAlloc();
  const MatH H = PaperH();
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> ud(-10.0, 10.0);
  for (int trial = 0; trial < 20; ++trial) {
    uvms_real_t P[8], w[6];
    for (auto &x : P) x = static_cast<uvms_real_t>(ud(rng));
    REQUIRE(uvms_alloc_wrench_body(&al, P, w) == UVMS_OK);
    CHECK((ToVec(w, 6) - H * ToVec(P, 8)).norm() < 10 * kTol * ToVec(P, 8).norm());
  }
  // Round trip: allocate a wrench at identity attitude, the produced wrench is that wrench.
  const uvms_real_t I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const uvms_real_t F[3] = {3, -4, 5}, N[3] = {-0.7, 0.2, 1.1};
  uvms_real_t P[8], w[6];
  REQUIRE(uvms_alloc_step(&al, I3, F, N, P, nullptr, nullptr) == UVMS_OK);
  REQUIRE(uvms_alloc_wrench_body(&al, P, w) == UVMS_OK);
  for (int k = 0; k < 3; ++k) {
    CHECK(std::abs(double(w[k]) - double(F[k])) < 10 * kTol * 10);
    CHECK(std::abs(double(w[k + 3]) - double(N[k])) < 10 * kTol * 10);
  }
  uvms_alloc_t zeroed{};
  CHECK(uvms_alloc_wrench_body(&zeroed, P, w) == UVMS_ERR_STATE);
  CHECK(AllZero(w, 6));
}

TEST_CASE("AdvanceSpeedsAreRigidBodyVelocityThroughFluidAlongEachAxis", "[allocation]") {
  std::mt19937 rng(606);
  std::uniform_real_distribution<double> ud(-1.0, 1.0);
  uvms_thruster_geometry_t g;
  uvms_thruster_geometry_paper(&g);
  for (int trial = 0; trial < 50; ++trial) {
    uvms_real_t R0[9], v0[3], w0[3], vinf[3], va[8];
    const Mat3 R = ToReal(RandomRotation(rng), R0);
    const Eigen::Vector3d v = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), v0);
    const Eigen::Vector3d w = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), w0);
    const Eigen::Vector3d f = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), vinf);
    REQUIRE(uvms_thruster_advance_speeds(&g, R0, v0, w0, vinf, va) == UVMS_OK);
    for (int j = 0; j < 8; ++j) {
      // Velocity of the point r0 + R0·a_j relative to the fluid, projected on R0·u_j.
      const Eigen::Vector3d a_I = R * Eigen::Vector3d(kPaperA[j][0], kPaperA[j][1], kPaperA[j][2]);
      const Eigen::Vector3d u_I = R * Eigen::Vector3d(kPaperU[j][0], kPaperU[j][1], kPaperU[j][2]);
      const double expected = u_I.dot(v + w.cross(a_I) - f);
      CHECK(std::abs(double(va[j]) - expected) < 10 * kTol);
    }
  }
  uvms_real_t R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, z[3] = {0, 0, 0}, va[8];
  z[1] = static_cast<uvms_real_t>(NAN);
  FillGarbage(va);
  CHECK(uvms_thruster_advance_speeds(&g, R0, z, z, z, va) == UVMS_ERR_NONFINITE);
  CHECK(AllZero(va, 8));
  z[1] = 0;
  g.num_thrusters = 9;
  FillGarbage(va);
  CHECK(uvms_thruster_advance_speeds(&g, R0, z, z, z, va) == UVMS_ERR_SIZE);
  CHECK(AllZero(va, 8));
}
