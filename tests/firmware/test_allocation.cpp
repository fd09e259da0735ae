// SPDX-License-Identifier: Apache-2.0
// Thrust allocation (SPEC §7.3 [33–39]) checked against Eigen: H built independently from the
// SPEC §3.4 table, H⁺ against Eigen's complete-orthogonal-decomposition pseudoinverse, and the
// allocation against its defining properties (H·P = wrench, minimum norm, the pos/att split).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "uvms/allocation.h"
#include "uvms/alloc_power.h"
#include "eigen_reference.hpp"

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

// The firmware's row-major arrays as Eigen matrices (H is rebuilt by the firmware from its
// geometry: uvms_alloc_config_matrix).
MatH FirmwareH(const uvms_alloc_t &al) {
  const int n = static_cast<int>(al.geom.num_thrusters);
  uvms_real_t Hf[UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS];
  REQUIRE(uvms_alloc_config_matrix(&al, Hf) == UVMS_OK);
  MatH H(6, n);
  for (int r = 0; r < 6; ++r)
    for (int j = 0; j < n; ++j) H(r, j) = static_cast<double>(Hf[r * n + j]);
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
  return uvms_test::PseudoInverse(H);
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
    const uvms_test::Svd svd = uvms_test::SvdOf(He);
    const double cond = svd.singular_values(0) / svd.singular_values(5);
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
  const uvms_test::Svd svd = uvms_test::SvdOf(H);
  REQUIRE(svd.rank == 6);
  const Eigen::MatrixXd Z = svd.V.rightCols(2);
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
    CHECK(al.rank == 6);     // SPEC §3.4: no single thruster is essential
    CHECK(al.uncontrollable_axes == 0u);
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

// ---------------------------------------------------------------------------------------------
// Rank loss (docs/FAULTS.md): the usable set may lose rank; H⁺ is then the Moore–Penrose
// pseudoinverse of the usable columns (checked against Eigen's complete orthogonal
// decomposition), the allocated thrust reproduces the projection of the wrench onto the range
// of H_u, and the uncontrollable axes are those unit wrenches outside that range.

namespace {

// Columns not in mask set to zero.
MatH Masked(const MatH &H, uint32_t mask) {
  MatH Hu = H;
  for (int j = 0; j < H.cols(); ++j)
    if (((mask >> j) & 1u) == 0u) Hu.col(j).setZero();
  return Hu;
}

struct RangeInfo {
  int rank;
  uint32_t axes;       // axes e_i with ‖(I − P_range)·e_i‖ > 1e-3
  Eigen::MatrixXd P;   // orthogonal projector onto range(H_u)
  double cond;         // σ_max / smallest kept σ
};

// Independent of the firmware: SVD in double of the exact (double) H_u.
RangeInfo RangeOf(const MatH &Hu) {
  const uvms_test::Svd svd = uvms_test::SvdOf(Hu);
  const Eigen::VectorXd &sv = svd.singular_values;
  RangeInfo info{0, 0u, Eigen::MatrixXd::Zero(6, 6), 1.0};
  for (int k = 0; k < sv.size(); ++k) {
    if (sv(k) > 1e-9 * std::max(sv(0), 1e-300)) {
      ++info.rank;
      info.P += svd.U.col(k) * svd.U.col(k).transpose();
      info.cond = sv(0) / sv(k);
    }
  }
  for (int i = 0; i < 6; ++i) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(6, i);
    if ((e - info.P * e).norm() > 1e-3) info.axes |= 1u << i;
  }
  return info;
}

}  // namespace

TEST_CASE("EveryUsableSubsetGetsTheMoorePenroseInverseAndItsLostAxes", "[allocation]") {
  // All 256 usable sets of the paper's thrusters: rank, lost axes and H⁺ against Eigen.
  const MatH H = PaperH();
  uvms_alloc_t al = PaperAlloc();
  int deficient = 0;
  for (uint32_t mask = 0; mask < 256u; ++mask) {
    INFO("mask 0x" << std::hex << mask);
    REQUIRE(uvms_alloc_set_usable(&al, mask) == UVMS_OK);
    REQUIRE(al.ready == 1);
    const MatH Hu = Masked(H, mask);
    const RangeInfo ref = RangeOf(Hu);
    CHECK(int(al.rank) == ref.rank);
    CHECK(uint32_t(al.uncontrollable_axes) == ref.axes);
    CHECK((ref.rank == 6) == (ref.axes == 0u));
    deficient += (ref.rank < 6) ? 1 : 0;
    const Eigen::MatrixXd pinv = EigenPinv(Hu);
    const double scale = std::max(1.0, pinv.cwiseAbs().maxCoeff());
    CHECK((FirmwarePinv(al) - pinv).cwiseAbs().maxCoeff() < 10 * kTol * ref.cond * ref.cond * scale);
    for (int j = 0; j < 8; ++j)
      if (((mask >> j) & 1u) == 0u)
        for (int r = 0; r < 6; ++r) CHECK(al.H_pinv[j * 6 + r] == 0);  // exactly
  }
  CHECK(deficient > 100);  // most subsets of fewer than 6 thrusters, and some of 6 or 7
}

TEST_CASE("LosingOneHeaveThrusterKeepsFullRankLosingBothLosesOnlyFz", "[allocation]") {
  // SPEC §3.4: thrusters 5 and 6 (indices 4, 5) are the only ones along z. Their columns are
  // (0,0,1, ±0.5,−0.1,0): one of them alone still gives Fz, since Mx (sway pair 7/8, columns
  // (0,1,0, ∓0.5,0,0.1)) and My (surge quartet, moments (0, ±0.5, ±0.5)) come from elsewhere:
  // rank 6. Without both, no column has a z-force component, and the other six span exactly
  // Fx, Fy, Mx, My, Mz: rank 5, only Fz lost.
  std::mt19937 rng(56);
  std::uniform_real_distribution<double> ud(-20.0, 20.0);
  for (const int lost : {4, 5}) {
    uvms_alloc_t al = PaperAlloc();
    REQUIRE(uvms_alloc_set_usable(&al, 0xFFu & ~(1u << lost)) == UVMS_OK);
    CHECK(al.rank == 6);
    CHECK(al.uncontrollable_axes == 0u);
  }
  uvms_alloc_t al = PaperAlloc();
  const uint32_t no_heave = 0xFFu & ~((1u << 4) | (1u << 5));
  REQUIRE(uvms_alloc_set_usable(&al, no_heave) == UVMS_OK);
  CHECK(al.ready == 1);
  CHECK(al.rank == 5);
  CHECK(al.uncontrollable_axes == UVMS_AXIS_FZ);
  const MatH H = PaperH();
  for (int trial = 0; trial < 50; ++trial) {
    uvms_real_t R0[9], F[3], N[3], P[8], Ppos[8], Patt[8];
    const Mat3 R = ToReal(RandomRotation(rng), R0);
    const Eigen::Vector3d f = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), F);
    const Eigen::Vector3d m = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), N);
    REQUIRE(uvms_alloc_step(&al, R0, F, N, P, Ppos, Patt) == UVMS_OK);
    CHECK(P[4] == 0);
    CHECK(P[5] == 0);
    Vec6 w;
    w << R.transpose() * f, R.transpose() * m;
    const Vec6 produced = H * ToVec(P, 8);
    // Every axis but Fz is served exactly; Fz gets nothing (not some other axis's share).
    Vec6 want = w;
    want(2) = 0;
    INFO("trial " << trial);
    CHECK((produced - want).norm() < 10 * kTol * w.norm());
  }
}

TEST_CASE("RankLossByLinearDependenceReportsTheCoupledAxes", "[allocation]") {
  // Surge thrusters 1 and 4 out: 2 and 3 give (1,0,0, 0,±0.5,±0.5), i.e. Fx and My+Mz only.
  // With the heave columns (Fz − 0.1·My, Mx) and sway columns (Fy + 0.1·Mz, Mx) the usable
  // span has rank 5; the lost direction w satisfies w·(every column) = 0:
  //   w_Fx = 0, w_Mx = 0, w_My + w_Mz = 0, w_Fz = 0.1·w_My, w_Fy = −0.1·w_Mz
  //   ⇒ w ∝ (0, 0.1, 0.1, 0, 1, −1). Axes with a component along it: Fy, Fz, My, Mz.
  uvms_alloc_t al = PaperAlloc();
  REQUIRE(uvms_alloc_set_usable(&al, 0xFFu & ~((1u << 0) | (1u << 3))) == UVMS_OK);
  CHECK(al.rank == 5);
  CHECK(al.uncontrollable_axes == (UVMS_AXIS_FY | UVMS_AXIS_FZ | UVMS_AXIS_MY | UVMS_AXIS_MZ));
  // Pure Fx and pure Mx stay exact; a wrench along the lost direction gives zero thrust.
  const uvms_real_t I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const MatH H = PaperH();
  uvms_real_t P[8];
  {
    const uvms_real_t F[3] = {7, 0, 0}, N[3] = {-3, 0, 0};
    REQUIRE(uvms_alloc_step(&al, I3, F, N, P, nullptr, nullptr) == UVMS_OK);
    Vec6 want;
    want << 7, 0, 0, -3, 0, 0;
    CHECK((H * ToVec(P, 8) - want).norm() < 100 * kTol);
  }
  {
    const uvms_real_t F[3] = {0, uvms_real_t(0.1), uvms_real_t(0.1)}, N[3] = {0, 1, -1};
    REQUIRE(uvms_alloc_step(&al, I3, F, N, P, nullptr, nullptr) == UVMS_OK);
    CHECK(ToVec(P, 8).norm() < 100 * kTol);
  }
  // Only the surge quartet: Fx, My, Mz (rank 3); Fy, Fz, Mx lost.
  REQUIRE(uvms_alloc_set_usable(&al, 0x0Fu) == UVMS_OK);
  CHECK(al.rank == 3);
  CHECK(al.uncontrollable_axes == (UVMS_AXIS_FY | UVMS_AXIS_FZ | UVMS_AXIS_MX));
}

TEST_CASE("NoUsableThrusterGivesRankZeroAndZeroThrusts", "[allocation]") {
  uvms_alloc_t al = PaperAlloc();
  uvms_real_t R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  uvms_real_t F[3] = {1, 2, 3}, N[3] = {0.1, -0.2, 0.3};
  uvms_real_t P[8], Ppos[8], Patt[8];
  REQUIRE(uvms_alloc_set_usable(&al, 0u) == UVMS_OK);
  CHECK(al.ready == 1);
  CHECK(al.rank == 0);
  CHECK(al.uncontrollable_axes == UVMS_AXIS_ALL);
  CHECK(AllZero(al.H_pinv, 8 * 6));
  FillGarbage(P);
  FillGarbage(Ppos);
  FillGarbage(Patt);
  CHECK(uvms_alloc_step(&al, R0, F, N, P, Ppos, Patt) == UVMS_OK);
  CHECK(AllZero(P, 8));
  CHECK(AllZero(Ppos, 8));
  CHECK(AllZero(Patt, 8));
  // Same mask again: no recomputation. Back to all: full rank, the step works.
  const uint32_t count = al.pinv_computations;
  CHECK(uvms_alloc_set_usable(&al, 0u) == UVMS_OK);
  CHECK(al.pinv_computations == count);
  CHECK(uvms_alloc_set_usable(&al, 0xFFu) == UVMS_OK);
  CHECK(al.rank == 6);
  CHECK(al.uncontrollable_axes == 0u);
  CHECK(uvms_alloc_step(&al, R0, F, N, P, nullptr, nullptr) == UVMS_OK);
  CHECK_FALSE(AllZero(P, 8));
}

// ---------------------------------------------------------------------------------------------
// Thrust limit with attitude priority (uvms_alloc_saturate).

namespace {

double Cosine(const Eigen::Vector3d &a, const Eigen::Vector3d &b) {
  return a.dot(b) / (a.norm() * b.norm());
}

}  // namespace

TEST_CASE("ThrustLimitKeepsForceAndMomentDirectionsAndServesAttitudeFirst", "[allocation]") {
  // Random wrenches, attitudes and limits spanning all three regimes: no saturation, position
  // part scaled, attitude part alone too large. Checked, independently of the algorithm's
  // steps: |P_j| ≤ T; the delivered wrench H·P equals (s_pos·f_b; s_att·n_b), so the cosine of
  // the angle between commanded and delivered force (moment) is 1 to rounding; attitude is
  // fully served whenever it fits alone (s_att = 1); s_pos is the largest that fits (some
  // thruster sits at the limit when s_pos < 1); position is dropped only when attitude alone
  // saturates (s_pos = 0 ⇔ s_att < 1).
  const uvms_alloc_t al = PaperAlloc();
  const MatH H = PaperH();
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> ud(-20.0, 20.0);
  std::uniform_real_distribution<double> ulog(-1.0, 2.0);
  const double rt = UVMS_REAL_IS_FLOAT ? 2e-5 : 1e-11;  // rounding of the chain, relative
  int regime[3] = {0, 0, 0};
  for (int trial = 0; trial < 2000; ++trial) {
    uvms_real_t R0[9], F[3], N[3], P[8], Ppos[8], Patt[8];
    const Mat3 R = ToReal(RandomRotation(rng), R0);
    const Eigen::Vector3d f = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), F);
    const Eigen::Vector3d m = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), N);
    REQUIRE(uvms_alloc_step(&al, R0, F, N, P, Ppos, Patt) == UVMS_OK);
    const Eigen::VectorXd att0 = ToVec(Patt, 8);
    const uvms_real_t T = static_cast<uvms_real_t>(std::pow(10.0, ulog(rng)));
    uvms_real_t s_pos = -1, s_att = -1;
    REQUIRE(uvms_alloc_saturate(&al, T, Ppos, Patt, P, &s_pos, &s_att) == UVMS_OK);
    INFO("trial " << trial << " T " << T << " s_pos " << s_pos << " s_att " << s_att);
    const Eigen::VectorXd p = ToVec(P, 8);
    CHECK(p.cwiseAbs().maxCoeff() <= double(T));
    CHECK((p - ToVec(Ppos, 8) - ToVec(Patt, 8)).cwiseAbs().maxCoeff() <= rt * double(T));
    const Eigen::Vector3d fb = R.transpose() * f, nb = R.transpose() * m;
    const Vec6 w = H * p;
    const double wscale = fb.norm() + nb.norm();
    CHECK((w.head<3>() - double(s_pos) * fb).norm() < rt * wscale);
    CHECK((w.tail<3>() - double(s_att) * nb).norm() < rt * wscale);
    if (s_pos > 0) CHECK(Cosine(w.head<3>(), fb) > 1.0 - rt);
    CHECK(Cosine(w.tail<3>(), nb) > 1.0 - rt);
    const bool att_fits = att0.cwiseAbs().maxCoeff() <= double(T);
    CHECK(att_fits == (s_att == 1));
    CHECK((s_pos == 0) == !att_fits);
    if (s_pos < 1) CHECK(p.cwiseAbs().maxCoeff() > double(T) * (1.0 - rt));
    regime[s_pos == 1 ? 0 : (att_fits ? 1 : 2)]++;
  }
  INFO("unsaturated " << regime[0] << " position scaled " << regime[1] << " attitude scaled "
                      << regime[2]);
  CHECK(regime[0] > 100);
  CHECK(regime[1] > 100);
  CHECK(regime[2] > 100);
}

TEST_CASE("PerThrusterLimitsHoldEachBoundKeepDirectionsAndAreTight", "[allocation]") {
  // uvms_alloc_saturate_each with a different limit T_j per thruster (some +inf), checked by
  // the properties that define the result, not by its formulas: |P_j| ≤ T_j; the delivered
  // wrench is (s_pos·f_b; s_att·n_b); nothing scaled when P fits; else attitude whole
  // whenever it fits alone (every |P_att,j| ≤ T_j ⇔ s_att = 1), otherwise s_pos = 0 and some
  // attitude part sits at its limit;
  // s_pos < 1 only with some thruster at its limit (s_pos is the largest that fits). With
  // every T_j equal it is uvms_alloc_saturate bit for bit. Then the minimum-power allocation
  // with the same limits keeps each bound and the wrench.
  const uvms_alloc_t al = PaperAlloc();
  const MatH H = PaperH();
  std::mt19937 rng(20261205);
  std::uniform_real_distribution<double> ud(-20.0, 20.0);
  std::uniform_real_distribution<double> ulog(0.3, 1.8);
  const double rt = UVMS_REAL_IS_FLOAT ? 2e-5 : 1e-11;
  int regime[3] = {0, 0, 0};
  for (int trial = 0; trial < 2000; ++trial) {
    uvms_real_t R0[9], F[3], N[3], P[8], Ppos[8], Patt[8], T[8];
    const Mat3 R = ToReal(RandomRotation(rng), R0);
    const Eigen::Vector3d f = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), F);
    const Eigen::Vector3d m = ToReal(Eigen::Vector3d(ud(rng), ud(rng), ud(rng)), N);
    REQUIRE(uvms_alloc_step(&al, R0, F, N, P, Ppos, Patt) == UVMS_OK);
    for (int j = 0; j < 8; ++j)
      T[j] = (trial + j) % 5 == 0 ? uvms_real_t(INFINITY) : uvms_real_t(std::pow(10.0, ulog(rng)));
    const Eigen::VectorXd att0 = ToVec(Patt, 8), pos0 = ToVec(Ppos, 8);
    uvms_real_t s_pos = -1, s_att = -1;
    REQUIRE(uvms_alloc_saturate_each(&al, T, Ppos, Patt, P, &s_pos, &s_att) == UVMS_OK);
    INFO("trial " << trial << " s_pos " << s_pos << " s_att " << s_att);
    const Eigen::VectorXd p = ToVec(P, 8), lim = ToVec(T, 8);
    bool sum_fits = true, att_fits = true, at_limit = false, att_at_limit = false;
    for (int j = 0; j < 8; ++j) {
      CHECK(std::fabs(p[j]) <= lim[j]);
      sum_fits = sum_fits && std::fabs(double(uvms_real_t(pos0[j]) + uvms_real_t(att0[j]))) <= lim[j];
      att_fits = att_fits && std::fabs(att0[j]) <= lim[j];
      at_limit = at_limit || std::fabs(p[j]) > lim[j] * (1.0 - rt);
      att_at_limit = att_at_limit || std::fabs(double(Patt[j])) > lim[j] * (1.0 - rt);
    }
    const Eigen::Vector3d fb = R.transpose() * f, nb = R.transpose() * m;
    const Vec6 w = H * p;
    const double wscale = fb.norm() + nb.norm();
    CHECK((w.head<3>() - double(s_pos) * fb).norm() < rt * wscale);
    CHECK((w.tail<3>() - double(s_att) * nb).norm() < rt * wscale);
    if (sum_fits) CHECK((s_pos == 1 && s_att == 1));
    else CHECK(att_fits == (s_att == 1));
    if (!sum_fits && !att_fits) CHECK((s_pos == 0 && att_at_limit));
    if (s_pos < 1) CHECK(at_limit);
    regime[sum_fits ? 0 : (att_fits ? 1 : 2)]++;
    // Equal limits: the scalar function, bit for bit.
    uvms_real_t pp[8], pa[8], pp2[8], pa2[8], Q[8], Q2[8], Tu[8], sp1, sa1, sp2, sa2;
    for (int j = 0; j < 8; ++j) {
      pp[j] = pp2[j] = uvms_real_t(pos0[j]);
      pa[j] = pa2[j] = uvms_real_t(att0[j]);
      Tu[j] = T[1];
    }
    REQUIRE(uvms_alloc_saturate(&al, T[1], pp, pa, Q, &sp1, &sa1) == UVMS_OK);
    REQUIRE(uvms_alloc_saturate_each(&al, Tu, pp2, pa2, Q2, &sp2, &sa2) == UVMS_OK);
    CHECK((sp1 == sp2 && sa1 == sa2 && std::equal(Q, Q + 8, Q2)));
    // Minimum power within the same per-thruster limits: each bound, the same wrench.
    if (trial % 10 == 0) {
      uvms_real_t Topt[8];
      uvms_power_info_t info;
      REQUIRE(uvms_alloc_min_power_each(&al, T, nullptr, P, nullptr, Topt, &info) == UVMS_OK);
      const Eigen::VectorXd t = ToVec(Topt, 8);
      for (int j = 0; j < 8; ++j) CHECK(std::fabs(t[j]) <= lim[j]);
      CHECK((H * t - w).norm() <= 1e3 * rt * std::max(1.0, w.norm()));
      CHECK(double(info.cost) <= double(info.cost_pinv) * (1.0 + rt));
    }
  }
  INFO("unsaturated " << regime[0] << " position scaled " << regime[1] << " attitude scaled "
                      << regime[2]);
  CHECK(regime[0] > 50);
  CHECK(regime[1] > 50);
  CHECK(regime[2] > 50);
  // Bad limits: a NULL array, an entry j < n not > 0.
  uvms_real_t P[8], Ppos[8] = {1}, Patt[8] = {1}, T[8], s_pos, s_att;
  for (uvms_real_t &x : T) x = 10;
  CHECK(uvms_alloc_saturate_each(&al, nullptr, Ppos, Patt, P, &s_pos, &s_att) == UVMS_ERR_ARG);
  T[6] = 0;
  CHECK(uvms_alloc_saturate_each(&al, T, Ppos, Patt, P, &s_pos, &s_att) == UVMS_ERR_RANGE);
  uvms_real_t Topt[8];
  CHECK(uvms_alloc_min_power_each(&al, T, nullptr, P, nullptr, Topt, nullptr) == UVMS_ERR_RANGE);
  CHECK(uvms_alloc_min_power_each(&al, nullptr, nullptr, P, nullptr, Topt, nullptr) == UVMS_ERR_ARG);
}

TEST_CASE("ThrustLimitPrefersAttitudeOverUniformScaling", "[allocation]") {
  // A wrench whose attitude part fits with room to spare but whose total does not: attitude
  // is kept whole (s_att = 1), only the position part shrinks. Uniform scaling of P would
  // shrink the moment too; this checks the moment is exactly the commanded one.
  const uvms_alloc_t al = PaperAlloc();
  const uvms_real_t I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const uvms_real_t F[3] = {40, 0, 0}, N[3] = {0, 0, 2};  // surge + yaw: same thrusters
  uvms_real_t P[8], Ppos[8], Patt[8], s_pos, s_att, w[6];
  REQUIRE(uvms_alloc_step(&al, I3, F, N, P, Ppos, Patt) == UVMS_OK);
  // Surge 40 N over 4 thrusters: 10 N each; yaw 2 N·m by ±0.5 m arms: ±1 N each. Limit 8 N.
  REQUIRE(uvms_alloc_saturate(&al, 8, Ppos, Patt, P, &s_pos, &s_att) == UVMS_OK);
  CHECK(s_att == 1);
  // Largest s with 10·s + 1 ≤ 8: s = 0.7.
  CHECK(double(s_pos) == Approx(0.7).epsilon(1e-5));
  REQUIRE(uvms_alloc_wrench_body(&al, P, w) == UVMS_OK);
  CHECK(double(w[5]) == Approx(2.0).epsilon(1e-5));
  CHECK(double(w[0]) == Approx(28.0).epsilon(1e-5));
}

TEST_CASE("ThrustLimitLeavesUnsaturatedThrustsUntouchedAndRejectsBadLimits", "[allocation]") {
  const uvms_alloc_t al = PaperAlloc();
  const uvms_real_t I3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const uvms_real_t F[3] = {3, -4, 5}, N[3] = {-0.7, 0.2, 1.1};
  uvms_real_t P[8], Ppos[8], Patt[8], P2[8], s_pos, s_att;
  REQUIRE(uvms_alloc_step(&al, I3, F, N, P, Ppos, Patt) == UVMS_OK);
  for (const uvms_real_t T : {uvms_real_t(1e6), uvms_real_t(INFINITY)}) {
    uvms_real_t pp[8], pa[8];
    std::copy(Ppos, Ppos + 8, pp);
    std::copy(Patt, Patt + 8, pa);
    REQUIRE(uvms_alloc_saturate(&al, T, pp, pa, P2, &s_pos, &s_att) == UVMS_OK);
    CHECK(s_pos == 1);
    CHECK(s_att == 1);
    for (int j = 0; j < 8; ++j) CHECK(P2[j] == P[j]);  // bitwise: same sum, no scaling
  }
  for (const uvms_real_t T : {uvms_real_t(0), uvms_real_t(-1), uvms_real_t(NAN)}) {
    uvms_real_t pp[8], pa[8];
    std::copy(Ppos, Ppos + 8, pp);
    std::copy(Patt, Patt + 8, pa);
    FillGarbage(P2);
    CHECK(uvms_alloc_saturate(&al, T, pp, pa, P2, &s_pos, &s_att) == UVMS_ERR_RANGE);
    CHECK((AllZero(P2, 8) && AllZero(pp, 8) && AllZero(pa, 8)));
    CHECK((s_pos == 0 && s_att == 0));
  }
  uvms_real_t pp[8], pa[8];
  std::copy(Ppos, Ppos + 8, pp);
  std::copy(Patt, Patt + 8, pa);
  pa[3] = uvms_real_t(NAN);
  CHECK(uvms_alloc_saturate(&al, 5, pp, pa, P2, &s_pos, &s_att) == UVMS_ERR_NONFINITE);
  CHECK(AllZero(P2, 8));
  CHECK(uvms_alloc_saturate(&al, 5, nullptr, pa, P2, &s_pos, &s_att) == UVMS_ERR_ARG);
  uvms_alloc_t zeroed{};
  CHECK(uvms_alloc_saturate(&zeroed, 5, pp, pa, P2, &s_pos, &s_att) == UVMS_ERR_STATE);
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
