// SPDX-License-Identifier: Apache-2.0
// The tick analyses (sil/run/tick_analyses.hpp): the task-space line
// reference against the firmware's own commanded line point, the task error's sampling rules
// (at t_F, the hold after it, a run ending before t_F), and the exact additivity of the
// propulsive-energy split, checked against the allocation the firmware performs.
#include <catch2/catch.hpp>

#include <cmath>
#include <memory>
#include <string>

#include "run/run_metrics.hpp"
#include "scenario/scenario.hpp"
#include "run/tick_analyses.hpp"
#include "uvms/allocation.h"
#include "uvms/controller.h"
#include "uvms/trajectory.h"
#include "uvms_plant/propulsion.hpp"

using namespace uvms::sil;
using uvms::plant::Vec3;

namespace {

// The firmware's real type: float builds agree with the plant's double to float rounding.
constexpr bool kFloat = UVMS_REAL_IS_FLOAT != 0;
constexpr double kLineTol_m = kFloat ? 1e-6 : 1e-12;

Scenario Load(const char *file, std::vector<std::string> overrides) {
  return LoadScenario(std::string(UVMS_SCENARIO_DIR) + "/" + file, overrides);
}

}  // namespace

// The metric's line r(t) (C++, from the plant's EE at t = 0) is the firmware's commanded point
// (C: uvms_cart_traj_init's r_start from its own kinematics at the captured pose and θI, then
// uvms_cosine_line_eval, as cart_rate evaluates it), before, during and after the motion.
TEST_CASE("LineReferenceIsTheFirmwaresCommandedPoint", "[tick_analyses]") {
  for (const char *ref : {"vehicle", "barycenter"}) {
    const bool bary = std::string(ref) == "barycenter";
    const Scenario sc = Load(bary ? "case_VII_stagnant.toml" : "case_IV_stagnant.toml",
                             {"trajectory.mode=\"cartesian_line\"", "trajectory.start_s=0.5",
                              "trajectory.duration_s=4", "trajectory.cartesian.distance_m=0.6",
                              "trajectory.cartesian.direction=[1.0, 0.5, 0.0]"});
    REQUIRE(sc.controller.switches.position_reference ==
            (bary ? UVMS_REF_BARYCENTER : UVMS_REF_VEHICLE));
    uvms::plant::Plant plant(sc.plant);
    plant.Reset(sc.initial);
    const TaskReference line = MakeTaskReference(sc.controller, sc.metrics.ee_target_m, plant.truth().ee_m);
    REQUIRE(line.line);

    auto ctrl = std::make_unique<uvms_ctrl_t>();
    REQUIRE(uvms_ctrl_init(ctrl.get(), &sc.controller) == UVMS_OK);
    // The pose the controller captures on its first tick: the sensed (here: true) r0 and R0.
    const uvms::plant::Mat3 R0 = sc.initial.attitude.toRotationMatrix();
    uvms_real_t r0d[3], R0d[9];
    for (int a = 0; a < 3; ++a) r0d[a] = sc.initial.r0_m[a];
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) R0d[3 * r + c] = R0(r, c);  // row-major (uvms/linalg.h)
    auto traj = std::make_unique<uvms_cart_traj_t>();
    REQUIRE(uvms_cart_traj_init(traj.get(), &sc.controller.cart, &ctrl->model, &ctrl->data,
                                sc.controller.theta_start_rad, r0d, R0d) == UVMS_OK);
    for (double t : {0.0, 0.3, 0.5, 0.51, 1.0, 2.5, 3.9, 4.5, 4.6, 10.0}) {
      uvms_real_t r[3], v[3], acc[3];
      REQUIRE(uvms_cosine_line_eval(traj->r_start_m, traj->p.direction, traj->p.distance_m,
                                    traj->p.duration_s, t - sc.controller.traj_start_s, r, v, acc) ==
              UVMS_OK);
      const Vec3 mine = line.At(t);
      INFO(ref << " t = " << t);
      // Two kinematics implementations (plant C++, firmware C) of one pose: rounding only.
      CHECK((mine - Vec3(r[0], r[1], r[2])).norm() < kLineTol_m);
    }
    // The line's end: r_start + rΔ·u, the unit direction of (1, 0.5, 0).
    const Vec3 end = line.At(line.end_s());
    CHECK((end - plant.truth().ee_m).norm() == Approx(0.6).epsilon(kFloat ? 1e-6 : 1e-12));
    CHECK((end - plant.truth().ee_m).normalized().dot(Vec3(1, 0.5, 0).normalized()) == Approx(1.0));
  }
}

// Sampling rules: at t_F is the first sample with t ≥ t_F, the hold mean averages t > t_F, and a
// run that ends before t_F has neither (NaN: null in summary.json); the final value is the end.
TEST_CASE("TaskErrorAtTfHoldAndShortRun", "[tick_analyses]") {
  TaskReference ref;
  ref.target_m = Vec3(1, 0, 0);
  ref.start_s = 1.0;
  ref.duration_s = 2.0;  // t_F = 3 s
  const double tick = 0.5;
  auto feed = [&](TaskError &te, int ticks) {
    for (int k = 0; k < ticks; ++k) te.OnSample(k * tick, Vec3(1, 0, k * tick));  // e = t
    uvms::plant::Truth end;
    end.time_s = ticks * tick;
    end.ee_m = Vec3(1, 0, end.time_s);
    RunSummary s;
    te.WriteTo(end, &s);
    return s;
  };
  {
    TaskError te(ref);
    const RunSummary s = feed(te, 9);  // samples 0, 0.5, ..., 4.0, end 4.5
    CHECK(s.task_error_reference == "target");
    CHECK(s.task_error_at_tf_m == Approx(3.0));
    CHECK(s.task_error_hold_mean_m == Approx((3.5 + 4.0 + 4.5) / 3));
    CHECK(s.task_error_final_m == Approx(4.5));
    CHECK(s.task_error_max_m == Approx(4.5));
    CHECK(s.task_error_mean_m == Approx(2.25));
  }
  {
    TaskError te(ref);
    const RunSummary s = feed(te, 6);  // the run ends at t_F = 3 s exactly: at t_F, no hold
    CHECK(s.task_error_at_tf_m == Approx(3.0));
    CHECK(std::isnan(s.task_error_hold_mean_m));
  }
  {
    TaskError te(ref);
    const RunSummary s = feed(te, 4);  // ends at 2 s < t_F
    CHECK(std::isnan(s.task_error_at_tf_m));
    CHECK(std::isnan(s.task_error_hold_mean_m));
    CHECK(s.task_error_final_m == Approx(2.0));
  }
}

// H⁺ of the plant's layout applied to (R0ᵀF, R0ᵀN) is what the firmware's allocation gives
// (uvms_alloc_step's P_pos and P_att), so T_ff + T_fb of the split is the commanded thrust;
// under a non-full usable set the split's H⁺ is that set's.
TEST_CASE("SplitCommandIsTheFirmwaresAllocation", "[tick_analyses]") {
  const Scenario sc = Load("case_IV_stagnant.toml", {});
  PropulsiveSplit split(sc.plant, true);
  auto ctrl = std::make_unique<uvms_ctrl_t>();
  REQUIRE(uvms_ctrl_init(ctrl.get(), &sc.controller) == UVMS_OK);
  const Eigen::Matrix3d R0 =
      Eigen::AngleAxisd(0.3, Vec3(0.2, -1.0, 0.5).normalized()).toRotationMatrix();
  uvms_real_t R0f[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) R0f[3 * r + c] = R0(r, c);
  uvms_telemetry_t tl{};
  const double F_ff[3] = {3, -1, 2}, F_fb[3] = {-5, 0.5, 1}, N_ff[3] = {0.2, 1, -0.3},
               N_fb[3] = {-0.4, 0.1, 0.6};
  for (int a = 0; a < 3; ++a) {
    tl.force_ff_N[a] = F_ff[a];
    tl.force_fb_N[a] = F_fb[a];
    tl.moment_ff_Nm[a] = N_ff[a];
    tl.moment_fb_Nm[a] = N_fb[a];
  }
  for (std::uint32_t mask : {0xFFu, 0xFFu & ~(1u << 2)}) {
    REQUIRE(uvms_alloc_set_usable(&ctrl->alloc, mask) == UVMS_OK);
    uvms_real_t F[3], N[3], P[UVMS_MAX_THRUSTERS], Ppos[UVMS_MAX_THRUSTERS], Patt[UVMS_MAX_THRUSTERS];
    for (int a = 0; a < 3; ++a) {
      F[a] = F_ff[a] + F_fb[a];
      N[a] = N_ff[a] + N_fb[a];
    }
    REQUIRE(uvms_alloc_step(&ctrl->alloc, R0f, F, N, P, Ppos, Patt) == UVMS_OK);
    Eigen::VectorXd t_ff, t_fb;
    REQUIRE(split.SplitCommand(tl, R0, mask, &t_ff, &t_fb));
    for (int j = 0; j < 8; ++j) {
      INFO("mask " << mask << " thruster " << j + 1);
      CHECK(t_ff[j] + t_fb[j] == Approx(P[j]).margin(1e-12));
    }
  }
  CHECK(split.group(0) == "x");
  CHECK(split.group(4) == "z");
  CHECK(split.group(6) == "y");
}
