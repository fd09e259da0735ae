// SPDX-License-Identifier: Apache-2.0
// Run verdicts (issue 15 item 1; sil/run_metrics.hpp, docs/FAULTS.md "Run verdicts"): a run
// that completes its ticks is judged: too many controller error ticks, a non-finite metric or a
// divergence beyond its limit makes it failed, and a maximum over samples that include NaN is
// NaN, never 0.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "codec.h"
#include "run_metrics.hpp"

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
