// SPDX-License-Identifier: Apache-2.0
// The controller's allocation mode (controller.h, cfg.alloc_mode): min_power against the
// default pseudoinverse on the same sensor sequence. Both instances see identical records, so
// their desired wrenches are identical; the least-Σ|T|^1.5 mode must deliver the same wrench
// with Σ|T|^1.5 no larger, inherit rank loss and attitude-first saturation, split its thrust
// into parts that sum to the total and each produce their own wrench, and never fall back.
// Also: validation of the mode (the retired value 1 refused) and the fallback paths of
// uvms_alloc_min_power. Its optimum, continuity and warm start are checked against scipy
// (test_alloc_power_scipy.py).
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "fw_test_util.hpp"
#include "sensor_sequence.h"
#include "uvms/alloc_power.h"
#include "uvms/controller.h"

using namespace fwtest;

namespace {

using Vec6 = Eigen::Matrix<double, 6, 1>;

// Body wrench H·x of thrusts x [N] on the paper's layout (SPEC §3.4, typed in again).
Vec6 PaperWrench(const uvms_real_t *x) {
  static const double a[8][3] = {{-0.5, 0.5, 0.5},  {-0.5, -0.5, 0.5}, {-0.5, 0.5, -0.5},
                                 {-0.5, -0.5, -0.5}, {0.1, 0.5, 0.0},   {0.1, -0.5, 0.0},
                                 {0.1, 0.0, 0.5},    {0.1, 0.0, -0.5}};
  static const double u[8][3] = {{1, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 0},
                                 {0, 0, 1}, {0, 0, 1}, {0, 1, 0}, {0, 1, 0}};
  Vec6 w = Vec6::Zero();
  for (int j = 0; j < 8; ++j) {
    const Eigen::Vector3d aj(a[j][0], a[j][1], a[j][2]), uj(u[j][0], u[j][1], u[j][2]);
    w.head<3>() += uj * double(x[j]);
    w.tail<3>() += aj.cross(uj) * double(x[j]);
  }
  return w;
}

// Σ|x_j|^1.5, the cost min_power minimises [N^1.5].
double PowerCost(const uvms_real_t *x) {
  double s = 0;
  for (int j = 0; j < 8; ++j) s += std::pow(std::fabs(double(x[j])), 1.5);
  return s;
}

struct RunStats {
  double sum_pinv = 0, sum_lp = 0;        // ∫Σ|P|^1.5 dt, ∫Σ|T|^1.5 dt [N^1.5·s]
  double worst_wrench_rel = 0;            // |deliverable_lp − deliverable_pinv| / |wrench|
  int ticks = 0, saturated = 0, fallbacks = 0;
};

// Runs the pseudoinverse and the min_power instance of cfg side by side over `ticks` ticks
// of the deterministic sensor sequence with the given usable mask, checking every tick.
RunStats RunSideBySide(uvms_ctrl_config_t cfg, int ticks, uint32_t usable_mask) {
  static uvms_ctrl_t pinv, lp;
  // Each instance points to its own configuration (uvms_ctrl_init keeps the pointer).
  uvms_ctrl_config_t cfg_lp = cfg;
  cfg.alloc_mode = UVMS_ALLOC_PSEUDOINVERSE;
  REQUIRE(uvms_ctrl_init(&pinv, &cfg) == UVMS_OK);
  cfg_lp.alloc_mode = UVMS_ALLOC_MIN_POWER;
  REQUIRE(uvms_ctrl_init(&lp, &cfg_lp) == UVMS_OK);
  const double tol = kFloat ? 2e-5 : 1e-10;
  RunStats st;
  for (int k = 0; k < ticks; ++k) {
    uvms_ctrl_sensors_t s;
    uvms_sensor_sequence(&cfg, k, &s);
    s.thruster_usable_mask = usable_mask;
    uvms_ctrl_command_t cmd_p, cmd_l;
    uvms_ctrl_telemetry_t tp, tl;
    REQUIRE(uvms_ctrl_step(&pinv, &s, &cmd_p, &tp) == UVMS_OK);
    REQUIRE(uvms_ctrl_step(&lp, &s, &cmd_l, &tl) == UVMS_OK);
    INFO("tick " << k);
    // Same inputs, same desired wrench, same saturation scales; no fallback.
    for (int i = 0; i < 3; ++i) {
      CHECK(tl.force_des_N[i] == tp.force_des_N[i]);
      CHECK(tl.moment_des_Nm[i] == tp.moment_des_Nm[i]);
    }
    CHECK(tl.thrust_scale_pos == tp.thrust_scale_pos);
    CHECK(tl.thrust_scale_att == tp.thrust_scale_att);
    // (Voltage saturation depends on the thrusts; the paper's 1e5 V limit is never reached.)
    const uint32_t thrust_dependent =
        UVMS_FLAG_ALLOC_FALLBACK | UVMS_FLAG_ALLOC_NOT_CONVERGED | UVMS_FLAG_VOLTAGE_SATURATED;
    CHECK((tl.flags & ~thrust_dependent) == (tp.flags & ~thrust_dependent));
    st.fallbacks += (tl.flags & (UVMS_FLAG_ALLOC_FALLBACK | UVMS_FLAG_ALLOC_NOT_CONVERGED)) != 0;
    st.saturated += (tp.flags & UVMS_FLAG_THRUST_SATURATED) != 0;
    // The same deliverable wrench (at full rank both are the pseudoinverse's scales; at
    // rank < 6 the min_power mode's is H·T, the pseudoinverse's s·(F; N) or H·P).
    const double scale = V(tp.force_des_N).norm() + V(tp.moment_des_Nm).norm();
    const double dw = (V(tl.force_deliverable_N) - V(tp.force_deliverable_N)).norm() +
                      (V(tl.moment_deliverable_Nm) - V(tp.moment_deliverable_Nm)).norm();
    CHECK(dw <= tol * scale);
    if (scale > 0) st.worst_wrench_rel = std::max(st.worst_wrench_rel, dw / scale);
    // Independently: H·T = H·P in the body frame (H typed in here).
    const Vec6 wl = PaperWrench(tl.thrust_des_N), wp = PaperWrench(tp.thrust_des_N);
    CHECK((wl - wp).norm() <= tol * std::max(scale, 1e-300));
    // Σ|T|^1.5 ≤ Σ|P|^1.5; unusable thrusters idle; |T_j| within the limit.
    const double sp = PowerCost(tp.thrust_des_N), sl = PowerCost(tl.thrust_des_N);
    CHECK(sl <= sp * (1 + 8 * kEps));
    for (int j = 0; j < 8; ++j) {
      if (((usable_mask >> j) & 1u) == 0u) CHECK(tl.thrust_des_N[j] == 0);
      if (cfg.limits.thrust_limit_N[j] > 0)
        CHECK(std::fabs(double(tl.thrust_des_N[j])) <= double(cfg.limits.thrust_limit_N[j]));
    }
    // The split: attitude part = the pseudoinverse's, position part = the rest; each produces
    // its own wrench.
    for (int j = 0; j < 8; ++j) {
      CHECK(tl.thrust_att_N[j] == tp.thrust_att_N[j]);
      CHECK(double(tl.thrust_pos_N[j]) + double(tl.thrust_att_N[j]) ==
            Approx(double(tl.thrust_des_N[j])).margin(tol * std::max(scale, 1.0)));
    }
    CHECK((PaperWrench(tl.thrust_pos_N) - PaperWrench(tp.thrust_pos_N)).norm() <=
          tol * std::max(scale, 1e-300));
    st.sum_pinv += sp * UVMS_SEQ_TICK_S;
    st.sum_lp += sl * UVMS_SEQ_TICK_S;
    ++st.ticks;
  }
  return st;
}

}  // namespace

TEST_CASE("PaperConfigurationDefaultsToThePseudoinverse", "[alloc_mode]") {
  uvms_ctrl_config_t cfg;
  REQUIRE(uvms_ctrl_config_paper(&cfg, 7) == UVMS_OK);
  CHECK(cfg.alloc_mode == UVMS_ALLOC_PSEUDOINVERSE);
  CHECK(std::string(uvms_alloc_mode_str(UVMS_ALLOC_PSEUDOINVERSE)) == "pseudoinverse");
  CHECK(std::string(uvms_alloc_mode_str(UVMS_ALLOC_MIN_POWER)) == "min_power");
  CHECK(std::string(uvms_alloc_mode_str(uvms_alloc_mode_t(1))) == "invalid");  // retired
  CHECK(std::string(uvms_alloc_mode_str(uvms_alloc_mode_t(7))) == "invalid");
}

TEST_CASE("AnUnknownAllocationModeIsRejectedAtInitNamingIt", "[alloc_mode]") {
  static uvms_ctrl_t ctrl;
  uvms_ctrl_config_t cfg;
  uvms_ctrl_config_paper(&cfg, 7);
  for (int bad : {1 /* retired: min_abs_thrust */, 3, -1, 255}) {
    cfg.alloc_mode = uvms_alloc_mode_t(bad);
    CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_ERR_RANGE);
    CHECK(ctrl.config_error == UVMS_CFG_ALLOC_MODE);
    CHECK(ctrl.ready == 0);
  }
  CHECK(std::string(uvms_cfg_field_str(UVMS_CFG_ALLOC_MODE)) == "alloc_mode");
  cfg.alloc_mode = UVMS_ALLOC_MIN_POWER;
  CHECK(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
}

TEST_CASE("MinPowerModeDeliversThePseudoinverseWrenchAtNoMoreCost", "[alloc_mode]") {
  // Every paper case with vehicle control (II–VIII), 60 s of the deterministic sequence.
  for (int c = 2; c <= 8; ++c) {
    INFO("case " << c);
    uvms_ctrl_config_t cfg;
    REQUIRE(uvms_ctrl_config_paper(&cfg, c) == UVMS_OK);
    const RunStats st = RunSideBySide(cfg, 2000, 0xFFu);
    CHECK(st.fallbacks == 0);
    CHECK(st.sum_lp <= st.sum_pinv);
    // Cases IV–VIII command wrenches that mix surge force with pitch and yaw moments, where
    // the two null directions of the layout let Σ|T|^1.5 fall: a solver that returned P
    // (no saving) fails here. Cases II and III move only along axes the null space leaves
    // at their optimum.
    if (c >= 4) CHECK(st.sum_lp < st.sum_pinv * (1 - 1e-3));
    std::printf("alloc_mode min_power, paper case %d, 60 s: ∫Σ|T|^1.5 dt %.6g vs "
                "pseudoinverse %.6g N^1.5·s (saving %.2f %%); deliverable wrench worst relative "
                "difference %.2g\n",
                c, st.sum_lp, st.sum_pinv, 100 * (1 - st.sum_lp / st.sum_pinv),
                st.worst_wrench_rel);
  }
}

TEST_CASE("MinPowerModeInheritsRankLossAndAttitudeFirstSaturation", "[alloc_mode]") {
  uvms_ctrl_config_t cfg;
  REQUIRE(uvms_ctrl_config_paper(&cfg, 7) == UVMS_OK);
  // Thrust limit below the run's largest thrusts (measured with the pseudoinverse first).
  static uvms_ctrl_t probe;
  REQUIRE(uvms_ctrl_init(&probe, &cfg) == UVMS_OK);
  double pmax = 0;
  for (int k = 0; k < 2000; ++k) {
    uvms_ctrl_sensors_t s;
    uvms_sensor_sequence(&cfg, k, &s);
    uvms_ctrl_command_t cmd;
    uvms_ctrl_telemetry_t t;
    REQUIRE(uvms_ctrl_step(&probe, &s, &cmd, &t) == UVMS_OK);
    for (int j = 0; j < 8; ++j) pmax = std::max(pmax, std::fabs(double(t.thrust_des_N[j])));
  }
  REQUIRE(pmax > 0);
  for (uvms_real_t &limit_N : cfg.limits.thrust_limit_N) limit_N = uvms_real_t(0.4 * pmax);
  struct Variant {
    const char *what;
    uint32_t mask;
  } variants[] = {{"all thrusters, saturated", 0xFFu},
                  {"thruster 5 out (rank 6), saturated", 0xEFu},
                  {"both heave thrusters out (rank 5: Fz lost), saturated", 0xCFu}};
  for (const Variant &v : variants) {
    INFO(v.what);
    const RunStats st = RunSideBySide(cfg, 2000, v.mask);
    CHECK(st.fallbacks == 0);
    CHECK(st.saturated > 100);
    CHECK(st.sum_lp <= st.sum_pinv);
    std::printf("alloc_mode min_power, case VII, limit %.3g N, %s: %d of %d ticks "
                "saturated; ∫Σ|T|^1.5 dt saving %.2f %%; deliverable wrench worst relative "
                "difference %.2g\n",
                0.4 * pmax, v.what, st.saturated, st.ticks,
                100 * (1 - st.sum_lp / st.sum_pinv), st.worst_wrench_rel);
  }
}

TEST_CASE("MinPowerFallsBackToThePseudoinverseWhenItCannotRun", "[alloc_mode]") {
  uvms_thruster_geometry_t g;
  uvms_thruster_geometry_paper(&g);
  static uvms_alloc_t al;
  REQUIRE(uvms_alloc_init(&al, &g) == UVMS_OK);
  const uvms_real_t R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const uvms_real_t F[3] = {30, -12, 8}, N[3] = {4, -6, 9};
  uvms_real_t P[8], Ppos[8], Patt[8], T[8];
  REQUIRE(uvms_alloc_step(&al, R0, F, N, P, Ppos, Patt) == UVMS_OK);
  uvms_power_info_t info;
  uvms_power_warm_t warm{};
  REQUIRE(uvms_alloc_min_power(&al, uvms_real_t(INFINITY), P, &warm, T, &info) == UVMS_OK);
  CHECK(info.null_dim == 2u);
  CHECK(info.converged == 1);
  CHECK(warm.basis_id == al.pinv_computations);
  // A rank read from RAM that leaves more than two null directions (8 usable, "rank 4"):
  // never trusted, P is returned with UVMS_ERR_SIZE and the warm start cleared.
  uvms_alloc_t bad = al;
  bad.rank = 4;
  CHECK(uvms_alloc_min_power(&bad, uvms_real_t(INFINITY), P, &warm, T, &info) == UVMS_ERR_SIZE);
  for (int j = 0; j < 8; ++j) CHECK(T[j] == P[j]);
  CHECK(warm.basis_id == 0u);
  // A corrupted H⁺ (NaN): the null space cannot be built, P with UVMS_ERR_SINGULAR.
  bad = al;
  bad.H_pinv[3] = std::numeric_limits<uvms_real_t>::quiet_NaN();
  CHECK(uvms_alloc_min_power(&bad, uvms_real_t(INFINITY), P, &warm, T, &info) ==
        UVMS_ERR_SINGULAR);
  for (int j = 0; j < 8; ++j) CHECK(T[j] == P[j]);
  // Input errors: zeros.
  CHECK(uvms_alloc_min_power(&al, 0, P, &warm, T, &info) == UVMS_ERR_RANGE);
  for (int j = 0; j < 8; ++j) CHECK(T[j] == 0);
  uvms_real_t Pbad[8];
  std::copy(P, P + 8, Pbad);
  Pbad[3] = std::numeric_limits<uvms_real_t>::quiet_NaN();
  CHECK(uvms_alloc_min_power(&al, 100, Pbad, &warm, T, &info) == UVMS_ERR_NONFINITE);
  for (int j = 0; j < 8; ++j) CHECK(T[j] == 0);
  // P above the limit it is said to respect.
  CHECK(uvms_alloc_min_power(&al, uvms_real_t(0.5), P, &warm, T, &info) == UVMS_ERR_RANGE);
  CHECK(uvms_alloc_min_power(nullptr, 100, P, &warm, T, &info) == UVMS_ERR_ARG);
  CHECK(uvms_alloc_min_power(&al, 100, nullptr, &warm, T, &info) == UVMS_ERR_ARG);
  static uvms_alloc_t blank;
  CHECK(uvms_alloc_min_power(&blank, 100, P, &warm, T, &info) == UVMS_ERR_STATE);
  // An unusable thruster's entry of P is ignored, never commanded.
  REQUIRE(uvms_alloc_set_usable(&al, 0xFEu) == UVMS_OK);
  REQUIRE(uvms_alloc_step(&al, R0, F, N, P, Ppos, Patt) == UVMS_OK);
  P[0] = 5;
  CHECK(uvms_alloc_min_power(&al, uvms_real_t(INFINITY), P, nullptr, T, &info) == UVMS_OK);
  CHECK(T[0] == 0);
  CHECK(info.null_dim == 1u);
}

TEST_CASE("MinPowerWeighsThrustersOfLargerPropellersLess", "[alloc_mode]") {
  // Thrusters of three propeller sizes (70 mm on thruster 1, 76 mm on 5 and 7, the paper's
  // 50 mm elsewhere: sizes that differ inside each null direction of the layout): the
  // controller's min_power weighs thruster j by D_1/D_j (alloc_power.h), and its thrusts cost
  // no more in that weighted cost than the unweighted optimum's, and less on most ticks
  // (checked over 60 s of case VII).
  uvms_ctrl_config_t cfg;
  REQUIRE(uvms_ctrl_config_paper(&cfg, 7) == UVMS_OK);
  const double D_m[8] = {0.07, 0.05, 0.05, 0.05, 0.076, 0.05, 0.076, 0.05};
  for (size_t j = 0; j < 8; ++j) cfg.thruster[j].diameter_m = uvms_real_t(D_m[j]);
  cfg.alloc_mode = UVMS_ALLOC_MIN_POWER;
  static uvms_ctrl_t ctrl;
  REQUIRE(uvms_ctrl_init(&ctrl, &cfg) == UVMS_OK);
  for (size_t j = 0; j < 8; ++j)
    CHECK(double(ctrl.power_weight[j]) ==
          Approx(D_m[0] / D_m[j]).epsilon(UVMS_REAL_IS_FLOAT ? 1e-6 : 1e-15));
  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t t;
  double weighted_ctrl = 0, weighted_plain = 0;
  int differ = 0;
  for (int k = 0; k < 2000; ++k) {
    uvms_ctrl_sensors_t s;
    uvms_sensor_sequence(&cfg, k, &s);
    REQUIRE(uvms_ctrl_step(&ctrl, &s, &cmd, &t) == UVMS_OK);
    // The unweighted optimum from the same pseudoinverse thrusts P = H⁺·H·T (the body wrench of
    // T, allocated again at identity attitude).
    uvms_real_t w6[6], P[8], plain[8];
    REQUIRE(uvms_alloc_wrench_body(&ctrl.alloc, t.thrust_des_N, w6) == UVMS_OK);
    static const uvms_real_t kI3[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    REQUIRE(uvms_alloc_step(&ctrl.alloc, kI3, &w6[0], &w6[3], P, nullptr, nullptr) == UVMS_OK);
    REQUIRE(uvms_alloc_min_power(&ctrl.alloc, uvms_real_t(INFINITY), P, nullptr, plain, nullptr) ==
            UVMS_OK);
    const double a = double(uvms_power_cost_weighted(8, ctrl.power_weight, t.thrust_des_N));
    const double b = double(uvms_power_cost_weighted(8, ctrl.power_weight, plain));
    weighted_ctrl += a;
    weighted_plain += b;
    if (a < b * (1 - 1e-6)) ++differ;
    CHECK(a <= b * (1 + 1e-5));
  }
  CHECK(differ > 100);
  std::printf("min_power with three propeller sizes, case VII, 60 s: Σ_k Σ_j w_j|T_j|^1.5 "
              "of the weighted optimum %.6g vs the unweighted one's %.6g N^1.5 (lower on %d of "
              "2000 ticks)\n",
              weighted_ctrl, weighted_plain, differ);
}
