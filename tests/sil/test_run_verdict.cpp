// SPDX-License-Identifier: Apache-2.0
// Run verdicts (issue 15 item 1; sil/run/run_metrics.hpp, docs/FAULTS.md "Run verdicts"): a run
// that completes its ticks is judged: too many controller error ticks, a non-finite metric,
// commanded thrust not produced for longer than its limit, or a divergence beyond its limit
// makes it failed, and a maximum over samples that include NaN is NaN, never 0.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "msg/codec.h"
#include "run/run_metrics.hpp"

using namespace uvms::sil;
using Catch::Matchers::Contains;

namespace {

// n ticks of a vehicle at rest, the controller returning `status`; attitude rotated by `angle`
// about z from tick `from` on.
Verdict Judge(int n, int32_t status, double angle = 0.0, int from = 0, double ee_err = 0.0) {
  uvms::plant::Truth t0;
  RunMetrics m(t0);
  for (int k = 0; k < n; ++k) {
    uvms_actuators_t a{};
    a.status = status;
    m.OnActuators(a);
    uvms::plant::Truth t = t0;
    if (k >= from) t.attitude = Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitZ()));
    m.OnTruth(t);
    uvms_telemetry_t tl{};
    tl.ee_estimate_m[0] = ee_err;
    m.OnTelemetry(t.ee_m, &tl);
  }
  return m.Judge(VerdictLimits{}, n, t0);
}

// One tick of the thrust-loss measure: tick k (t_k = k·kTick_s) commands `commanded_N` on each
// of the 8 thrusters with the controller's `status` and `flags`, and the plant produces
// `produced_N` on each at t_k+1.
constexpr double kTick_s = 0.03;  // the paper's tick (SPEC §3.5)
void ThrustTick(RunMetrics &m, int k, double commanded_N, double produced_N, int32_t status = 0,
                int32_t flags = 0) {
  uvms::plant::Truth t;
  t.time_s = k * kTick_s;
  m.OnTruth(t);
  uvms_telemetry_t tl{};
  tl.status = status;
  tl.flags = flags;
  for (double &p : tl.thrust_des_N) p = commanded_N;
  m.OnTelemetry(t.ee_m, &tl);
  uvms::plant::Truth after;
  after.time_s = (k + 1) * kTick_s;
  after.thrust_N.assign(8, produced_N);
  m.OnTickIntegrated(after, &tl, 0xFFu);
}

double MaxThrustLoss_s(const RunMetrics &m) {
  RunSummary s;
  m.WriteTo(uvms::plant::Truth{}, &s);
  return s.max_thrust_loss_s;
}

}  // namespace

TEST_CASE("ARunWhoseEveryTickTheControllerRejectedFails", "[verdict]") {
  const Verdict v = Judge(100, 1);
  CHECK(v.code == UVMS_RUN_STATUS_T_CONTROLLER_ERRORS);
  CHECK_THAT(v.reason, Contains("100 of 100 ticks"));
  CHECK(Judge(100, 0).code == UVMS_RUN_STATUS_T_OK);
}

TEST_CASE("AVehicleThatTumbledFailsAsDiverged", "[verdict]") {
  const Verdict v = Judge(50, 0, 2.2, 10);
  CHECK(v.code == UVMS_RUN_STATUS_T_DIVERGED);
  CHECK_THAT(v.reason, Contains("max_attitude_error_rad 2.2"));
  CHECK(Judge(50, 0, 0.3, 10).code == UVMS_RUN_STATUS_T_OK);  // the paper's worst is 0.24 rad
}

TEST_CASE("AnEndEffectorErrorBeyondItsLimitFailsAsDiverged", "[verdict]") {
  CHECK(Judge(20, 0, 0.0, 0, 4.6).code == UVMS_RUN_STATUS_T_DIVERGED);
}

TEST_CASE("AMaximumOverSamplesWithNanIsNanAndTheRunFailsAsNonFinite", "[verdict]") {
  const Verdict v = Judge(20, 0, std::nan(""), 5);
  CHECK(v.code == UVMS_RUN_STATUS_T_NON_FINITE);
  CHECK_THAT(v.reason, Contains("max_attitude_error_rad is nan"));
  uvms::plant::Truth t0;
  RunMetrics m(t0);
  uvms::plant::Truth bad = t0;
  bad.attitude = Eigen::Quaterniond(std::nan(""), 0, 0, 0);
  m.OnTruth(bad);
  m.OnTruth(t0);  // a later finite sample does not hide it
  RunSummary s;
  m.WriteTo(t0, &s);
  CHECK(std::isnan(s.max_attitude_error_rad));
}

TEST_CASE("TheSummarysClearanceIsTheSmallestOverTheRunNotTheLastTicks", "[verdict]") {
  uvms::plant::Truth t0;
  t0.min_clearance_m = 0.9;
  RunMetrics m(t0);
  for (double c : {0.9, 0.05, 0.4}) {  // closest at the second tick, farther again later
    uvms::plant::Truth t = t0;
    t.min_clearance_m = c;
    m.OnTruth(t);
  }
  uvms::plant::Truth end = t0;
  end.min_clearance_m = 0.7;
  RunSummary s;
  m.WriteTo(end, &s);
  CHECK(s.min_clearance_m == 0.05);
  end.min_clearance_m = 0.01;  // the final sample counts too
  m.WriteTo(end, &s);
  CHECK(s.min_clearance_m == 0.01);
  RunMetrics off(t0);  // the monitor disabled: inf throughout
  uvms::plant::Truth inf = t0;
  inf.min_clearance_m = std::numeric_limits<double>::infinity();
  off.OnTruth(inf);
  off.WriteTo(inf, &s);
  CHECK(std::isinf(s.min_clearance_m));
}

// Verdicts cover a vehicle that cannot push (docs/FAULTS.md "Run verdicts"): thrust commanded on
// every tick and none produced (every motor loop failed, MOTOR_FAULT: V_j = 0; or a propeller
// too small to push) fails the run as thrust_lost, whatever its other metrics say (0 J of
// thruster energy is then no result).
TEST_CASE("AVehicleWhoseThrustersProduceNothingFailsAsThrustLost", "[verdict]") {
  constexpr int kTicks = 100;  // 3 s
  RunMetrics m(uvms::plant::Truth{});
  for (int k = 0; k < kTicks; ++k) ThrustTick(m, k, 1.0, 0.0, 0, int32_t(UVMS_FLAG_MOTOR_FAULT));
  const Verdict v = m.Judge(VerdictLimits{}, kTicks, uvms::plant::Truth{});
  CHECK(v.code == UVMS_RUN_STATUS_T_THRUST_LOST);
  CHECK_THAT(v.reason, Contains("max_thrust_loss_s 3 exceeds its limit 1"));
  CHECK(MaxThrustLoss_s(m) == Approx(kTicks * kTick_s));
  CHECK(std::string(FailureName(v.code)) == "thrust_lost");
  // The limit is the verdict key's: 3 s of loss pass a 5 s limit.
  VerdictLimits lenient;
  lenient.max_thrust_loss_s = 5.0;
  CHECK(m.Judge(lenient, kTicks, uvms::plant::Truth{}).code == UVMS_RUN_STATUS_T_OK);
}

TEST_CASE("ThrustLostIsUnderOnePercentOfTheCommandedThrust", "[verdict]") {
  // Just under and just over the share, for 2 s each: only the first is a loss.
  const double commanded_N = 2.0;
  for (const auto &[share, lost] : {std::pair{0.99 * RunMetrics::kLostThrustShare, true},
                                    std::pair{1.01 * RunMetrics::kLostThrustShare, false}}) {
    RunMetrics m(uvms::plant::Truth{});
    for (int k = 0; k < 67; ++k) ThrustTick(m, k, commanded_N, share * commanded_N);
    INFO("produced share " << share);
    CHECK((m.Judge(VerdictLimits{}, 67, uvms::plant::Truth{}).code == UVMS_RUN_STATUS_T_THRUST_LOST) == lost);
    CHECK(MaxThrustLoss_s(m) == Approx(lost ? 67 * kTick_s : 0.0).margin(1e-12));
  }
}

TEST_CASE("TheLongestStretchOfThrustLossIsJudgedNotTheirSum", "[verdict]") {
  // 0.9 s lost, one tick produced, 0.9 s lost again: 1.8 s in all, never 1 s at a stretch (a
  // motor spinning up twice is not a vehicle that cannot push).
  constexpr int kStretch = 30;  // 0.9 s
  RunMetrics m(uvms::plant::Truth{});
  int k = 0;
  for (int i = 0; i < kStretch; ++i) ThrustTick(m, k++, 1.0, 0.0);
  ThrustTick(m, k++, 1.0, 1.0);
  for (int i = 0; i < kStretch; ++i) ThrustTick(m, k++, 1.0, 0.0);
  CHECK(MaxThrustLoss_s(m) == Approx(kStretch * kTick_s));
  CHECK(m.Judge(VerdictLimits{}, k, uvms::plant::Truth{}).code == UVMS_RUN_STATUS_T_OK);
  ThrustTick(m, k++, 1.0, 0.0);  // a 31st tick: 0.93 s
  for (int i = 0; i < 3; ++i) ThrustTick(m, k++, 1.0, 0.0);  // 1.02 s > 1 s
  CHECK(m.Judge(VerdictLimits{}, k, uvms::plant::Truth{}).code == UVMS_RUN_STATUS_T_THRUST_LOST);
}

TEST_CASE("NoThrustCommandedIsNoThrustLost", "[verdict]") {
  // Case I (thrusters idle: nothing commanded), a command below kMinCommandedThrust_N in total,
  // and the safe output of a failed step (status ≠ UVMS_OK): nothing produced, nothing lost.
  const double below_N = 0.9 * RunMetrics::kMinCommandedThrust_N / 8.0;  // per thruster
  for (const auto &[commanded_N, status] : {std::pair{0.0, 0}, std::pair{below_N, 0},
                                            std::pair{1.0, int(UVMS_ERR_RANGE)}}) {
    RunMetrics m(uvms::plant::Truth{});
    for (int k = 0; k < 100; ++k) ThrustTick(m, k, commanded_N, 0.0, status);
    INFO("commanded " << commanded_N << " N, status " << status);
    CHECK(MaxThrustLoss_s(m) == 0.0);
  }
  // A tick without telemetry ends a stretch (no command is known).
  RunMetrics m(uvms::plant::Truth{});
  for (int k = 0; k < 20; ++k) ThrustTick(m, k, 1.0, 0.0);
  uvms::plant::Truth after;
  after.time_s = 21 * kTick_s;
  after.thrust_N.assign(8, 0.0);
  m.OnTickIntegrated(after, nullptr, 0xFFu);
  for (int k = 21; k < 41; ++k) ThrustTick(m, k, 1.0, 0.0);
  CHECK(MaxThrustLoss_s(m) == Approx(20 * kTick_s));
}
