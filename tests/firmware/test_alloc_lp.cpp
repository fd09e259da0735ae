// SPDX-License-Identifier: Apache-2.0
// Least-Σ|T| allocation (alloc_lp.h; allocation.h uvms_alloc_min_abs_thrust) against an
// independent algorithm: exhaustive enumeration of the vertices of the feasible set, in double
// with Eigen, on the paper's thruster layout typed in again from SPEC §3.4. The optimum of
//   min Σ|T_j|  s.t.  H_u·T = w,  |T_j| ≤ T_max
// is attained at a point where n_u independent constraints are active: r = rank(H_u) of the
// equations and one of T_j ∈ {−T_max, 0, +T_max} for each of the other n_u − r thrusters (the
// objective is linear on each orthant, whose boundaries are the T_j = 0). So: every set S of r
// usable thrusters whose columns span the range, every assignment of the others to
// {−T_max, 0, +T_max}, solve H_S·T_S = w − H_N·T_N, keep the solutions within the bounds, and
// take the least Σ|T|. The target w is what the firmware's own pseudoinverse allocation
// delivers, w* = H·P (P after the thrust limit), recomputed here in double.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "uvms/alloc_lp.h"
#include "uvms/allocation.h"

namespace {

using Mat68 = Eigen::Matrix<double, 6, 8>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

constexpr bool kFloat = UVMS_REAL_IS_FLOAT != 0;

// SPEC §3.4, typed in again (not read from uvms_thruster_geometry_paper).
constexpr double kPaperA[8][3] = {{-0.5, 0.5, 0.5},  {-0.5, -0.5, 0.5}, {-0.5, 0.5, -0.5},
                                  {-0.5, -0.5, -0.5}, {0.1, 0.5, 0.0},   {0.1, -0.5, 0.0},
                                  {0.1, 0.0, 0.5},    {0.1, 0.0, -0.5}};
constexpr double kPaperU[8][3] = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0},
                                  {0, 0, 1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}};

Mat68 PaperH() {
  Mat68 H;
  for (int j = 0; j < 8; ++j) {
    const Eigen::Vector3d a(kPaperA[j][0], kPaperA[j][1], kPaperA[j][2]);
    const Eigen::Vector3d u(kPaperU[j][0], kPaperU[j][1], kPaperU[j][2]);
    H.col(j) << u, a.cross(u);
  }
  return H;
}

int Rank(const Eigen::MatrixXd &A) {
  if (A.cols() == 0) return 0;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A);
  const auto &s = svd.singularValues();
  int r = 0;
  for (int i = 0; i < s.size(); ++i) r += (s(i) > 1e-9 * s(0)) ? 1 : 0;
  return r;
}

// Tolerances of the comparison (see the test's comment): relative to Σ|P|.
constexpr double kObjTol = kFloat ? 2e-5 : 1e-11;
// Row residual |H·T − w*| relative to max(|w*|∞, Σ|T|).
constexpr double kResTol = kFloat ? 2e-5 : 1e-11;

// The least Σ|T| over the vertices described at the top; +inf if none is feasible.
double EnumerateMinAbsThrust(const Mat68 &H, uint32_t mask, const Vec6 &w, double T_max,
                             int *vertices_feasible) {
  std::vector<int> us;
  for (int j = 0; j < 8; ++j)
    if ((mask >> j) & 1u) us.push_back(j);
  const int nu = static_cast<int>(us.size());
  Eigen::MatrixXd Hu(6, nu);
  for (int c = 0; c < nu; ++c) Hu.col(c) = H.col(us[c]);
  const int r = Rank(Hu);
  double best = std::numeric_limits<double>::infinity();
  *vertices_feasible = 0;
  const double scale = std::max(1.0, w.cwiseAbs().maxCoeff());
  for (uint32_t subset = 0; subset < (1u << nu); ++subset) {
    if (__builtin_popcount(subset) != r) continue;
    std::vector<int> S, N;
    for (int c = 0; c < nu; ++c) (((subset >> c) & 1u) ? S : N).push_back(us[c]);
    Eigen::MatrixXd HS(6, r);
    for (int c = 0; c < r; ++c) HS.col(c) = H.col(S[c]);
    if (Rank(HS) < r) continue;  // does not span the range
    const auto qr = HS.colPivHouseholderQr();
    int combos = 1;
    for (size_t i = 0; i < N.size(); ++i) combos *= 3;
    for (int code = 0; code < combos; ++code) {
      Eigen::VectorXd T = Eigen::VectorXd::Zero(8);
      int rest = code;
      for (int idx : N) {
        T(idx) = (rest % 3 - 1) * T_max;  // −T_max, 0, +T_max
        rest /= 3;
      }
      const Vec6 rhs = w - H * T;
      const Eigen::VectorXd TS = qr.solve(rhs);
      if ((HS * TS - rhs).cwiseAbs().maxCoeff() > 1e-9 * (scale + rhs.cwiseAbs().maxCoeff()))
        continue;  // inconsistent (w outside the range: never for w = H·P)
      bool within = true;
      for (int c = 0; c < r; ++c) {
        T(S[c]) = TS(c);
        if (std::fabs(TS(c)) > T_max * (1 + 1e-12)) within = false;
      }
      if (!within) continue;
      ++*vertices_feasible;
      best = std::min(best, T.cwiseAbs().sum());
    }
  }
  return best;
}

struct Case {
  uint32_t mask;
  double force[3], moment[3];
  double limit_fraction;  // T_max / max|P_unlimited|; 0: the paper's 1e6 N
};

double Percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(q * double(v.size() - 1) + 0.5)];
}

}  // namespace

TEST_CASE("MinAbsThrustMatchesVertexEnumerationOnRandomWrenchesFaultsAndSaturation", "[alloc_lp]") {
  // 600 cases, fixed seed: usable sets all 8, one thruster out (8 sets) and two out (28 sets,
  // among them rank-5 ones such as both heave thrusters), random wrenches (force ~20 N,
  // moment ~10 N·m per axis, and every 25th w = 0), thrust limits of 1e6 N (none), or 0.8,
  // 0.5, 0.25 of the unlimited allocation's largest |P_j| (saturated: the raw wrench is not
  // producible; P is scaled attitude first and its wrench w* is the LP's target).
  // Tolerances: the enumeration is double; the firmware LP solves in the real type from
  // w* rounded to it (float: 6e-8 relative per entry), through ≤ ~15 pivots whose B⁻¹ error is
  // ≈ cond(B)·eps per pivot (cond ≤ ~10 here): the optimum and the residual move by a few
  // hundred eps relative, i.e. ≲ 1e-5 in float and ≲ 1e-13 in double; the tolerances (2e-5
  // and 1e-11) sit above that and far below the savings measured (percent level).
  uvms_thruster_geometry_t g;
  uvms_thruster_geometry_paper(&g);
  uvms_alloc_t al;
  REQUIRE(uvms_alloc_init(&al, &g) == UVMS_OK);
  const Mat68 H = PaperH();
  std::mt19937 rng(20261216u);
  std::normal_distribution<double> nd(0.0, 1.0);
  std::uniform_int_distribution<int> pick(0, 7);
  const double fractions[4] = {0.0, 0.8, 0.5, 0.25};

  std::vector<double> savings, iters, iters_fault, sat_savings;
  double worst_obj = 0, worst_res = 0;
  int cases = 0, saturated = 0, rank5 = 0, zero_cases = 0, with_faults = 0;
  for (int c = 0; c < 600; ++c) {
    Case cs{};
    cs.mask = 0xFFu;
    const int faults = c % 3;
    if (faults >= 1) cs.mask &= ~(1u << pick(rng));
    if (faults == 2) {
      int j;
      do { j = pick(rng); } while (((cs.mask >> j) & 1u) == 0u);
      cs.mask &= ~(1u << j);
    }
    const bool zero = (c % 25 == 0);
    for (int i = 0; i < 3; ++i) {
      cs.force[i] = zero ? 0.0 : 20.0 * nd(rng);
      cs.moment[i] = zero ? 0.0 : 10.0 * nd(rng);
    }
    cs.limit_fraction = fractions[(c / 3) % 4];
    INFO("case " << c << " mask 0x" << std::hex << cs.mask << std::dec << " limit fraction "
                 << cs.limit_fraction);

    REQUIRE(uvms_alloc_set_usable(&al, cs.mask) == UVMS_OK);
    uvms_real_t R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    uvms_real_t F[3], N[3];
    for (int i = 0; i < 3; ++i) {
      F[i] = uvms_real_t(cs.force[i]);
      N[i] = uvms_real_t(cs.moment[i]);
    }
    uvms_real_t P[8], Ppos[8], Patt[8];
    REQUIRE(uvms_alloc_step(&al, R0, F, N, P, Ppos, Patt) == UVMS_OK);
    double pmax = 0;
    for (int j = 0; j < 8; ++j) pmax = std::max(pmax, std::fabs(double(P[j])));
    const double limit = (cs.limit_fraction == 0.0 || pmax == 0.0) ? 1e6 : cs.limit_fraction * pmax;
    const uvms_real_t limit_r = uvms_real_t(limit);
    uvms_real_t sp = 0, sa = 0;
    REQUIRE(uvms_alloc_saturate(&al, limit_r, Ppos, Patt, P, &sp, &sa) == UVMS_OK);
    const bool is_saturated = (sp < 1 || sa < 1);

    Eigen::VectorXd Pd(8);
    for (int j = 0; j < 8; ++j) Pd(j) = double(P[j]);
    const Vec6 w = H * Pd;  // w* = H·P in double
    const double sum_p = Pd.cwiseAbs().sum();

    uvms_real_t T[8];
    uvms_lp_info_t info;
    REQUIRE(uvms_alloc_min_abs_thrust(&al, limit_r, P, T, &info) == UVMS_OK);
    Eigen::VectorXd Td(8);
    for (int j = 0; j < 8; ++j) Td(j) = double(T[j]);
    const double sum_t = Td.cwiseAbs().sum();

    int feasible = 0;
    const double opt = EnumerateMinAbsThrust(H, cs.mask, w, double(limit_r), &feasible);
    REQUIRE(std::isfinite(opt));  // P's own wrench is always producible
    CHECK(feasible > 0);

    // Unusable thrusters exactly 0, every |T_j| within the limit (exactly: clamped).
    for (int j = 0; j < 8; ++j) {
      if (((cs.mask >> j) & 1u) == 0u) CHECK(T[j] == 0);
      CHECK(std::fabs(Td(j)) <= double(limit_r));
    }
    // Never worse than the pseudoinverse (the firmware keeps P when it is not beaten; the
    // sums here are re-added in double: a few float ulps of slack).
    CHECK(sum_t <= sum_p * (1 + (kFloat ? 4 * 6e-8 : 4e-16)));
    // The enumeration's optimum (the firmware's T may carry rounding above it, never a
    // measurable amount below it: T is feasible to kResTol).
    const double obj_err = std::fabs(sum_t - opt) / std::max(sum_p, 1e-300);
    if (sum_p > 0) {
      CHECK(obj_err <= kObjTol);
      worst_obj = std::max(worst_obj, obj_err);
    } else {
      CHECK(opt == 0);
      CHECK(sum_t == 0);
    }
    // Exactly P's wrench: H·T = w*.
    const double res_scale = std::max(w.cwiseAbs().maxCoeff(), sum_t);
    const double res = (H * Td - w).cwiseAbs().maxCoeff() / std::max(res_scale, 1e-300);
    if (res_scale > 0) {
      CHECK(res <= kResTol);
      worst_res = std::max(worst_res, res);
    }

    ++cases;
    if (zero) {
      ++zero_cases;
      CHECK(info.iterations == 0u);
      continue;
    }
    const double saving = 1.0 - sum_t / sum_p;
    savings.push_back(saving);
    iters.push_back(double(info.iterations));
    if (faults > 0) {
      ++with_faults;
      iters_fault.push_back(double(info.iterations));
    }
    if (is_saturated) {
      ++saturated;
      sat_savings.push_back(saving);
    }
    if (al.rank < 6) {
      ++rank5;
      CHECK(info.redundant_rows == uint32_t(6 - al.rank));
    }
  }
  REQUIRE(cases == 600);
  CHECK(saturated > 100);
  CHECK(rank5 > 10);
  double mean = 0;
  for (double s : savings) mean += s;
  mean /= double(savings.size());
  double sat_mean = 0;
  for (double s : sat_savings) sat_mean += s;
  sat_mean /= double(sat_savings.size());
  std::printf("min |T| LP vs enumeration (%s, %d cases: %d with faults, %d rank < 6, %d saturated, "
              "%d w = 0): Σ|T| saving vs pseudoinverse mean %.2f %%, largest %.2f %%, smallest "
              "%.2g %% (saturated cases: mean %.2f %%); |Σ|T| − enumeration| / Σ|P| worst %.2g; "
              "residual worst %.2g; iterations median %.0f, 90th pct %.0f, worst %.0f (with "
              "faults: median %.0f, worst %.0f)\n",
              kFloat ? "float" : "double", cases, with_faults, rank5, saturated, zero_cases,
              100 * mean, 100 * *std::max_element(savings.begin(), savings.end()),
              100 * *std::min_element(savings.begin(), savings.end()), 100 * sat_mean, worst_obj,
              worst_res, Percentile(iters, 0.5), Percentile(iters, 0.9),
              *std::max_element(iters.begin(), iters.end()), Percentile(iters_fault, 0.5),
              *std::max_element(iters_fault.begin(), iters_fault.end()));
  CHECK(mean > 0);
  CHECK(*std::max_element(iters.begin(), iters.end()) < double(UVMS_LP_MAX_ITERATIONS) / 4);
}
