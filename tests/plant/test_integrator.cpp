// SPDX-License-Identifier: Apache-2.0
// uvms::plant::Integrator (CVODE) checked against closed-form solutions, used the way the plant
// uses it: ticks of 0.03 s, a clean Reset at every tick boundary. Like SUNDIALS' cv_kpr
// example, every accuracy test prints its error against the true solution.
#include <catch2/catch.hpp>

#include <cvode/cvode.h>  // CV_* flag values

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "uvms_plant/integrator.hpp"
#include "uvms_plant/params.hpp"

using uvms::plant::Integrator;
using uvms::plant::IntegratorParams;
using Method = IntegratorParams::Method;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTick_s = 0.03;  // controller tick (SPEC: inputs held over a tick) [s]

// Tolerances of the accuracy tests: IntegratorParams' defaults.
constexpr double kRelTol = 1e-8;
constexpr double kAbsTol = 1e-10;

// Error bound factor. CVODE controls the local error of each step to about
// rel_tol·|y| + abs_tol (weighted RMS norm ≤ 1); the global error after hundreds of restarted
// ticks is a modest multiple of that. A wrong method, a missed stop time or a lost restart
// state gives errors of order the tick's increment (≥ 1e-3 here), far above this bound.
constexpr double kErrorFactor = 100.0;
// The oscillator does not damp errors: those of 334 restarted ticks accumulate as a phase
// drift instead of decaying, so its bound allows 10× more.
constexpr double kOscillatorErrorFactor = 1000.0;

IntegratorParams Params(Method method, double rel_tol = kRelTol, double abs_tol = kAbsTol,
                        long max_steps = 5000) {
  IntegratorParams p;
  p.method = method;
  p.rel_tol = rel_tol;
  p.abs_tol = abs_tol;
  p.max_steps = max_steps;
  return p;
}

const char *Name(Method m) { return m == Method::kAdams ? "Adams/fixed-point" : "BDF/dense"; }

// Integrate over n_ticks ticks of kTick_s from t = 0, Reset at every tick boundary (the
// plant's pattern), and return the largest |y_i − exact_i(t)| seen at the tick ends.
// exact(t, y) writes the true solution into y.
template <class Exact>
double MaxTickErrorWithResets(Integrator &integ, std::size_t n, int n_ticks, Exact exact,
                              double *max_abs_y = nullptr) {
  std::vector<double> y(n), y_true(n);
  exact(0.0, y.data());
  double max_err = 0.0, max_y = 0.0;
  for (int k = 0; k < n_ticks; ++k) {
    const double t0 = k * kTick_s;
    const double t1 = (k + 1) * kTick_s;
    integ.Reset(t0, y.data());
    const Integrator::Result r = integ.AdvanceTo(t1, y.data());
    INFO("tick " << k << ": " << r.flag_name << " " << r.message);
    REQUIRE(r.ok);
    REQUIRE(r.t_reached == t1);
    exact(t1, y_true.data());
    for (std::size_t i = 0; i < n; ++i) {
      max_err = std::max(max_err, std::abs(y[i] - y_true[i]));
      max_y = std::max(max_y, std::abs(y_true[i]));
    }
  }
  if (max_abs_y) *max_abs_y = max_y;
  return max_err;
}

// Harmonic oscillator ẍ = −ω²·x, x(0) = 1, ẋ(0) = 0: x = cos ωt, ẋ = −ω·sin ωt.
constexpr double kOmega_rad_s = 2.0 * kPi * 0.5;  // period 2 s
int Oscillator(double, const double *y, double *ydot) {
  ydot[0] = y[1];
  ydot[1] = -kOmega_rad_s * kOmega_rad_s * y[0];
  return 0;
}
void OscillatorExact(double t, double *y) {
  y[0] = std::cos(kOmega_rad_s * t);
  y[1] = -kOmega_rad_s * std::sin(kOmega_rad_s * t);
}

}  // namespace

TEST_CASE("ExponentialDecayWithResetEveryTickMatchesExp", "[integrator]") {
  // ẏ = −k·y, y(0) = 1: y = exp(−k·t). 200 ticks = 6 s, y falls to e^−12.
  constexpr double kDecay_1_s = 2.0;
  constexpr int kTicks = 200;
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  Integrator integ(1, Params(method), [](double, const double *y, double *ydot) {
    ydot[0] = -kDecay_1_s * y[0];
    return 0;
  });
  double max_y = 0.0;
  const double err = MaxTickErrorWithResets(
      integ, 1, kTicks, [](double t, double *y) { y[0] = std::exp(-kDecay_1_s * t); }, &max_y);
  const double bound = kErrorFactor * (kRelTol * max_y + kAbsTol);
  const auto st = integ.GetStats();
  std::printf("decay      %-18s max |y - exp(-kt)| = %.3e  (bound %.1e)  steps %ld  rhs %ld\n",
              Name(method), err, bound, st.steps, st.rhs_evals);
  CHECK(err < bound);
  CHECK(st.reinits == kTicks);
}

TEST_CASE("HarmonicOscillatorWithResetEveryTickMatchesCosSin", "[integrator]") {
  // 334 ticks ≈ 10 s = 5 periods; bound relative to the largest state, ω = π rad/s.
  constexpr int kTicks = 334;
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  Integrator integ(2, Params(method), Oscillator);
  double max_y = 0.0;
  const double err = MaxTickErrorWithResets(integ, 2, kTicks, OscillatorExact, &max_y);
  const double bound = kOscillatorErrorFactor * (kRelTol * max_y + kAbsTol);
  const auto st = integ.GetStats();
  std::printf("oscillator %-18s max |y - (cos, -w sin)| = %.3e  (bound %.1e)  steps %ld  "
              "rhs %ld\n",
              Name(method), err, bound, st.steps, st.rhs_evals);
  CHECK(err < bound);
}

TEST_CASE("QuadraticDragCoastingMatchesClosedForm", "[integrator]") {
  // Coasting with quadratic drag (the plant's drag law with no thrust):
  //   v̇ = −k·|v|·v, ẋ = v  ⇒  v = v0/(1 + k·v0·t),  x = ln(1 + k·v0·t)/k   (v0 > 0).
  // k = ρ·C_D·A/(2·m) [1/m]; 0.5 1/m and v0 = 2 m/s halve the speed in 1 s. 100 ticks = 3 s.
  constexpr double kDrag_1_m = 0.5;
  constexpr double kV0_m_s = 2.0;
  constexpr int kTicks = 100;
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  Integrator integ(2, Params(method), [](double, const double *y, double *ydot) {
    ydot[0] = -kDrag_1_m * std::abs(y[0]) * y[0];
    ydot[1] = y[0];
    return 0;
  });
  double max_y = 0.0;
  const double err = MaxTickErrorWithResets(
      integ, 2, kTicks,
      [](double t, double *y) {
        y[0] = kV0_m_s / (1.0 + kDrag_1_m * kV0_m_s * t);
        y[1] = std::log1p(kDrag_1_m * kV0_m_s * t) / kDrag_1_m;
      },
      &max_y);
  const double bound = kErrorFactor * (kRelTol * max_y + kAbsTol);
  std::printf("drag       %-18s max |(v, x) - exact| = %.3e  (bound %.1e)\n", Name(method), err,
              bound);
  CHECK(err < bound);
}

TEST_CASE("RhsIsNeverEvaluatedPastTheStopTime", "[integrator]") {
  // ẏ = u_k on tick k, u_k drawn once per tick (fixed seed): the rhs checks that it is only
  // called inside the tick whose input it holds. y is then exactly Σ u_k·Δt (polynomial of
  // degree 1: every CVODE order integrates it to round-off).
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  const bool reset_every_tick = GENERATE(true, false);
  constexpr int kTicks = 300;
  std::mt19937 rng(20261101u);
  std::uniform_real_distribution<double> input(-1.0, 1.0);

  double u = 0.0, tick_start_s = 0.0, tick_stop_s = 0.0;
  double max_t_seen = -1.0, min_t_seen = 1e300;
  Integrator integ(1, Params(method), [&](double t, const double *, double *ydot) {
    max_t_seen = std::max(max_t_seen, t);
    min_t_seen = std::min(min_t_seen, t);
    ydot[0] = u;
    return 0;
  });
  double y = 0.0, y_exact = 0.0, worst_overshoot_s = -1.0, max_err = 0.0;
  integ.Reset(0.0, &y);
  for (int k = 0; k < kTicks; ++k) {
    tick_start_s = k * kTick_s;
    tick_stop_s = (k + 1) * kTick_s;
    u = input(rng);
    if (reset_every_tick) integ.Reset(tick_start_s, &y);
    max_t_seen = -1.0;
    min_t_seen = 1e300;
    const Integrator::Result r = integ.AdvanceTo(tick_stop_s, &y);
    INFO("tick " << k << ": " << r.message);
    REQUIRE(r.ok);
    worst_overshoot_s = std::max(worst_overshoot_s, max_t_seen - tick_stop_s);
    // Nothing outside [t_k, t_k+1]: 4 ulp of slack for the last step's (t_stop − t)(1 − 4u).
    const double slack_s = 4.0 * std::numeric_limits<double>::epsilon() * tick_stop_s;
    REQUIRE(max_t_seen <= tick_stop_s + slack_s);
    REQUIRE(min_t_seen >= tick_start_s - slack_s);
    y_exact += u * kTick_s;
    max_err = std::max(max_err, std::abs(y - y_exact));
  }
  std::printf("stop time  %-18s reset each tick: %-3s  max(t_rhs - t_stop) = %.3e s, "
              "|y - sum u dt| = %.3e\n",
              Name(method), reset_every_tick ? "yes" : "no", worst_overshoot_s, max_err);
  CHECK(worst_overshoot_s <= 0.0);
  // Round-off of 300 sums plus CVODE's error estimate noise, not truncation error.
  CHECK(max_err < 1e-9);
}

TEST_CASE("TighterToleranceReducesTheError", "[integrator]") {
  // Same oscillator, tolerances 100× tighter: the error must fall by at least 10×.
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  constexpr int kTicks = 334;
  Integrator loose(2, Params(method, 1e-6, 1e-8), Oscillator);
  Integrator tight(2, Params(method, 1e-8, 1e-10), Oscillator);
  const double err_loose = MaxTickErrorWithResets(loose, 2, kTicks, OscillatorExact);
  const double err_tight = MaxTickErrorWithResets(tight, 2, kTicks, OscillatorExact);
  std::printf("convergence %-17s rtol 1e-6: %.3e   rtol 1e-8: %.3e   ratio %.1f  "
              "(steps %ld -> %ld)\n",
              Name(method), err_loose, err_tight, err_loose / err_tight, loose.GetStats().steps,
              tight.GetStats().steps);
  CHECK(err_tight < err_loose / 10.0);
  CHECK(tight.GetStats().steps > loose.GetStats().steps);
}

TEST_CASE("FatalRhsFailureIsReportedAndResetRecovers", "[integrator]") {
  // ẏ = −y, the rhs fails (−1) for t > 0.5 s while `failing` is set.
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  constexpr double kFailAfter_s = 0.5;
  bool failing = true;
  Integrator integ(1, Params(method), [&](double t, const double *y, double *ydot) {
    if (failing && t > kFailAfter_s) return -1;
    ydot[0] = -y[0];
    return 0;
  });
  double y = 1.0, t = 0.0;
  integ.Reset(t, &y);
  Integrator::Result r;
  int k = 0;
  for (; k < 100; ++k) {
    r = integ.AdvanceTo((k + 1) * kTick_s, &y);
    if (!r.ok) break;
    t = r.t_reached;
  }
  INFO(r.message);
  REQUIRE_FALSE(r.ok);
  CHECK(k == static_cast<int>(kFailAfter_s / kTick_s));  // the tick that crosses 0.5 s
  CHECK(r.flag == CV_RHSFUNC_FAIL);
  CHECK(r.flag_name == "CV_RHSFUNC_FAIL");
  CHECK_THAT(r.message, Catch::Contains("returned -1"));
  CHECK(r.t_reached <= (k + 1) * kTick_s);
  CHECK(r.t_reached >= k * kTick_s);
  CHECK(std::isfinite(y));
  std::printf("rhs -1     %-18s %s\n", Name(method), r.message.c_str());

  // Without a Reset the integrator refuses to continue.
  const Integrator::Result again = integ.AdvanceTo((k + 1) * kTick_s, &y);
  CHECK_FALSE(again.ok);
  CHECK(again.flag == CV_NO_MALLOC);

  // After the failure: Reset from the last good state and carry on to t = 1 s.
  failing = false;
  y = std::exp(-t);
  integ.Reset(t, &y);
  const Integrator::Result after = integ.AdvanceTo(1.0, &y);
  INFO(after.message);
  REQUIRE(after.ok);
  CHECK(std::abs(y - std::exp(-1.0)) < kErrorFactor * (kRelTol + kAbsTol));
}

TEST_CASE("ThrowingRhsBecomesAFailureWithItsMessage", "[integrator]") {
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  bool throwing = true;
  Integrator integ(1, Params(method), [&](double t, const double *y, double *ydot) {
    if (throwing && t > 0.1) throw std::runtime_error("boom");
    ydot[0] = -y[0];
    return 0;
  });
  double y = 1.0;
  integ.Reset(0.0, &y);
  const Integrator::Result r = integ.AdvanceTo(1.0, &y);
  std::printf("rhs throws %-18s %s: %s\n", Name(method), r.flag_name.c_str(), r.message.c_str());
  CHECK_FALSE(r.ok);
  CHECK(r.flag == CV_RHSFUNC_FAIL);
  CHECK_THAT(r.message, Catch::Contains("boom"));
  CHECK(r.t_reached <= 0.1 + 1e-12);

  throwing = false;
  integ.Reset(0.0, &(y = 1.0));
  const Integrator::Result ok = integ.AdvanceTo(1.0, &y);
  REQUIRE(ok.ok);
  CHECK(std::abs(y - std::exp(-1.0)) < kErrorFactor * (kRelTol + kAbsTol));
}

TEST_CASE("RecoverableRhsFailureIsRetriedWithASmallerStep", "[integrator]") {
  // The rhs refuses (+1) the first call past 0.2 s; CVODE cuts the step and succeeds.
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  int refusals = 0;
  Integrator integ(1, Params(method), [&](double t, const double *y, double *ydot) {
    if (refusals == 0 && t > 0.2) {
      ++refusals;
      return 1;
    }
    ydot[0] = -y[0];
    return 0;
  });
  double y = 1.0;
  integ.Reset(0.0, &y);
  const Integrator::Result r = integ.AdvanceTo(1.0, &y);
  INFO(r.message);
  REQUIRE(r.ok);
  CHECK(refusals == 1);
  CHECK(std::abs(y - std::exp(-1.0)) < kErrorFactor * (kRelTol + kAbsTol));
}

TEST_CASE("TooMuchWorkIsReportedNotFatal", "[integrator]") {
  // ẏ = −1000·(y − cos t) over 10 s: stiff, fast transient then tracking cos t; far more
  // than 5 steps for either method.
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  Integrator integ(1, Params(method, kRelTol, kAbsTol, 5), [](double t, const double *y,
                                                              double *ydot) {
    ydot[0] = -1000.0 * (y[0] - std::cos(t));
    return 0;
  });
  double y = 0.0;
  integ.Reset(0.0, &y);
  const Integrator::Result r = integ.AdvanceTo(10.0, &y);
  std::printf("mxstep 5   %-18s %s: %s\n", Name(method), r.flag_name.c_str(), r.message.c_str());
  CHECK_FALSE(r.ok);
  CHECK(r.flag == CV_TOO_MUCH_WORK);
  CHECK(r.flag_name == "CV_TOO_MUCH_WORK");
  CHECK_THAT(r.message, Catch::Contains("mxstep"));
  CHECK(r.t_reached > 0.0);
  CHECK(r.t_reached < 10.0);
  CHECK(std::isfinite(y));
  CHECK(integ.GetStats().steps == 5);
}

TEST_CASE("StatsAreCumulativeAcrossResets", "[integrator]") {
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  long calls = 0;
  Integrator integ(2, Params(method), [&](double t, const double *y, double *ydot) {
    ++calls;
    return Oscillator(t, y, ydot);
  });
  const Integrator::Stats s0 = integ.GetStats();
  CHECK(s0.steps == 0);
  CHECK(s0.rhs_evals == 0);
  CHECK(s0.reinits == 0);

  double y[2] = {1.0, 0.0};
  integ.Reset(0.0, y);
  REQUIRE(integ.AdvanceTo(kTick_s, y).ok);
  const Integrator::Stats s1 = integ.GetStats();
  CHECK(s1.steps > 0);
  CHECK(s1.rhs_evals > s1.steps);  // at least one evaluation per step plus the initial ones
  CHECK(s1.rhs_evals == calls);    // every call of the rhs counted, Jacobian columns included
  CHECK(s1.nonlin_iters >= s1.steps);
  CHECK(s1.reinits == 1);

  integ.Reset(kTick_s, y);
  const Integrator::Stats s2 = integ.GetStats();  // CVodeReInit zeroes CVODE's own counters
  CHECK(s2.steps == s1.steps);
  CHECK(s2.nonlin_iters == s1.nonlin_iters);
  CHECK(s2.reinits == 2);

  REQUIRE(integ.AdvanceTo(2.0 * kTick_s, y).ok);
  const Integrator::Stats s3 = integ.GetStats();
  CHECK(s3.steps > s2.steps);
  CHECK(s3.rhs_evals > s2.rhs_evals);
  CHECK(s3.rhs_evals == calls);
  CHECK(s3.nonlin_iters > s2.nonlin_iters);
  CHECK(s3.err_test_fails >= s2.err_test_fails);
  CHECK(s3.nonlin_conv_fails >= s2.nonlin_conv_fails);
  CHECK(s3.reinits == 2);
  std::printf("stats      %-18s 2 ticks: steps %ld rhs %ld nonlin iters %ld conv fails %ld "
              "err fails %ld reinits %ld\n",
              Name(method), s3.steps, s3.rhs_evals, s3.nonlin_iters, s3.nonlin_conv_fails,
              s3.err_test_fails, s3.reinits);
}

TEST_CASE("InvalidParamsThrowNamingTheSetting", "[integrator]") {
  const Integrator::Rhs rhs = [](double, const double *, double *ydot) {
    ydot[0] = 0.0;
    return 0;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(Integrator(0, Params(Method::kAdams), rhs), std::invalid_argument);
  CHECK_THROWS_WITH(Integrator(0, Params(Method::kAdams), rhs), Catch::Contains("n (number"));
  CHECK_THROWS_AS(Integrator(1, Params(Method::kAdams, 0.0), rhs), std::invalid_argument);
  CHECK_THROWS_WITH(Integrator(1, Params(Method::kAdams, 0.0), rhs), Catch::Contains("rel_tol"));
  CHECK_THROWS_WITH(Integrator(1, Params(Method::kBdf, nan), rhs), Catch::Contains("rel_tol"));
  CHECK_THROWS_AS(Integrator(1, Params(Method::kAdams, 1e-8, -1.0), rhs), std::invalid_argument);
  CHECK_THROWS_WITH(Integrator(1, Params(Method::kAdams, 1e-8, -1.0), rhs),
                    Catch::Contains("abs_tol"));
  CHECK_THROWS_WITH(Integrator(1, Params(Method::kAdams, 1e-8, 0.0), rhs),
                    Catch::Contains("abs_tol"));
  CHECK_THROWS_AS(Integrator(1, Params(Method::kAdams, 1e-8, 1e-10, 0), rhs),
                  std::invalid_argument);
  CHECK_THROWS_WITH(Integrator(1, Params(Method::kAdams, 1e-8, 1e-10, 0), rhs),
                    Catch::Contains("max_steps"));
  CHECK_THROWS_WITH(Integrator(1, Params(Method::kAdams), Integrator::Rhs{}),
                    Catch::Contains("rhs"));
  IntegratorParams bad_coef = Params(Method::kAdams);
  bad_coef.nonlin_conv_coef = 0.0;
  CHECK_THROWS_WITH(Integrator(1, bad_coef, rhs), Catch::Contains("nonlin_conv_coef"));
  CHECK_NOTHROW(Integrator(1, Params(Method::kAdams), rhs));
}

TEST_CASE("InvalidCallsAreRejectedCleanly", "[integrator]") {
  Integrator integ(2, Params(Method::kAdams), Oscillator);
  double y[2] = {1.0, 0.0};

  // Before any Reset: a failure result, y_out gets the (zero) state, nothing thrown.
  Integrator::Result r = integ.AdvanceTo(1.0, y);
  CHECK_FALSE(r.ok);
  CHECK(r.flag == CV_NO_MALLOC);
  CHECK(y[0] == 0.0);

  y[0] = 1.0;
  double bad[2] = {1.0, std::numeric_limits<double>::quiet_NaN()};
  CHECK_THROWS_AS(integ.Reset(0.0, bad), std::invalid_argument);
  CHECK_THROWS_WITH(integ.Reset(0.0, bad), Catch::Contains("y0[1]"));
  CHECK_THROWS_AS(integ.Reset(std::numeric_limits<double>::infinity(), y),
                  std::invalid_argument);
  CHECK_THROWS_AS(integ.Reset(0.0, nullptr), std::invalid_argument);

  integ.Reset(1.0, y);
  r = integ.AdvanceTo(1.0, y);  // not later than the current time
  CHECK_FALSE(r.ok);
  CHECK(r.flag == CV_ILL_INPUT);
  r = integ.AdvanceTo(0.5, y);  // backwards
  CHECK_FALSE(r.ok);
  CHECK(r.flag == CV_ILL_INPUT);
  r = integ.AdvanceTo(2.0, nullptr);
  CHECK_FALSE(r.ok);
  CHECK(r.flag == CV_ILL_INPUT);
  // Rejected calls leave the integrator usable.
  r = integ.AdvanceTo(1.0 + kTick_s, y);
  CHECK(r.ok);
}

TEST_CASE("MovedIntegratorKeepsWorking", "[integrator]") {
  // CVODE holds a pointer to the private implementation as user_data: moves must not
  // invalidate it.
  Integrator a(2, Params(Method::kAdams), Oscillator);
  double y[2];
  OscillatorExact(0.0, y);
  a.Reset(0.0, y);
  REQUIRE(a.AdvanceTo(0.5, y).ok);
  Integrator b(std::move(a));
  REQUIRE(b.AdvanceTo(1.0, y).ok);
  std::vector<Integrator> v;
  v.push_back(std::move(b));
  REQUIRE(v[0].AdvanceTo(1.5, y).ok);
  double y_true[2];
  OscillatorExact(1.5, y_true);
  CHECK(std::abs(y[0] - y_true[0]) < kErrorFactor * (kRelTol * kOmega_rad_s + kAbsTol));
  CHECK(std::abs(y[1] - y_true[1]) < kErrorFactor * (kRelTol * kOmega_rad_s + kAbsTol));
  CHECK(v[0].GetStats().reinits == 1);
}

TEST_CASE("InitStepIsTheFirstStepAfterEveryResetAndSavesRhsEvaluations", "[integrator]") {
  // The oscillator over 334 restarted ticks, once with CVODE's own first step and once with
  // SetInitStep(0.002 · the previous tick's NextStep()), as the plant does. The first rhs
  // evaluation after a Reset is at t_k; with an initial step h0 the next one is at t_k + h0
  // exactly. The given step skips CVODE's estimate (which evaluates the rhs for it): fewer
  // evaluations, the same step count to within a few per cent, and the error still within
  // the accuracy tests' bound.
  constexpr int kTicks = 334;
  constexpr double kFraction = 0.002;
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  std::vector<double> t_calls;
  auto rhs = [&](double t, const double *y, double *ydot) {
    t_calls.push_back(t);
    return Oscillator(t, y, ydot);
  };
  auto run = [&](bool use_init_step, Integrator::Stats &stats, bool &first_steps_as_set) {
    Integrator integ(2, Params(method), rhs);
    std::vector<double> y(2), y_true(2);
    OscillatorExact(0.0, y.data());
    double max_err = 0.0;
    first_steps_as_set = true;
    for (int k = 0; k < kTicks; ++k) {
      const double t0 = k * kTick_s, t1 = (k + 1) * kTick_s;
      const double h0 = use_init_step ? kFraction * integ.NextStep() : 0.0;
      integ.SetInitStep(h0);
      integ.Reset(t0, y.data());
      t_calls.clear();
      const Integrator::Result r = integ.AdvanceTo(t1, y.data());
      REQUIRE(r.ok);
      CHECK(integ.LastStep() > 0.0);
      CHECK(integ.LastStep() <= kTick_s);
      CHECK(integ.NextStep() > 0.0);
      if (h0 > 0.0) {
        // The first evaluation is at t0; the first one past it is the first step's.
        auto later = std::find_if(t_calls.begin(), t_calls.end(), [&](double t) { return t > t0; });
        REQUIRE(later != t_calls.end());
        if (*later != t0 + h0) first_steps_as_set = false;
      }
      OscillatorExact(t1, y_true.data());
      for (int i = 0; i < 2; ++i) max_err = std::max(max_err, std::abs(y[i] - y_true[i]));
    }
    stats = integ.GetStats();
    return max_err;
  };
  Integrator::Stats own{}, given{};
  bool unused = true, as_set = false;
  const double err_own = run(false, own, unused);
  const double err_given = run(true, given, as_set);
  const double bound = kOscillatorErrorFactor * (kRelTol * kOmega_rad_s + kAbsTol);
  std::printf("init step  %-18s CVODE's h0: rhs %ld steps %ld err %.3e | %.3f x next step: "
              "rhs %ld steps %ld err %.3e\n",
              Name(method), own.rhs_evals, own.steps, err_own, kFraction, given.rhs_evals,
              given.steps, err_given);
  CHECK(as_set);
  CHECK(given.rhs_evals < own.rhs_evals);
  CHECK(std::abs(double(given.steps - own.steps)) < 0.1 * double(own.steps));
  CHECK(err_given < bound);
}

TEST_CASE("SetInitStepRejectsBadStepsAndZeroRestoresTheEstimate", "[integrator]") {
  Integrator integ(2, Params(Method::kAdams), Oscillator);
  CHECK(integ.LastStep() == 0.0);  // before any Reset
  CHECK(integ.NextStep() == 0.0);
  CHECK_THROWS_AS(integ.SetInitStep(-1e-3), std::invalid_argument);
  CHECK_THROWS_WITH(integ.SetInitStep(std::numeric_limits<double>::quiet_NaN()),
                    Catch::Contains("SetInitStep"));
  CHECK_THROWS_AS(integ.SetInitStep(std::numeric_limits<double>::infinity()),
                  std::invalid_argument);
  // 0 after a given step: the next interval is bit for bit the one of a fresh integrator
  // that never had one.
  double y[2], y_fresh[2];
  OscillatorExact(0.0, y);
  OscillatorExact(0.0, y_fresh);
  integ.SetInitStep(1e-5);
  integ.Reset(0.0, y);
  REQUIRE(integ.AdvanceTo(kTick_s, y).ok);
  integ.SetInitStep(0.0);
  OscillatorExact(0.0, y);
  integ.Reset(0.0, y);
  REQUIRE(integ.AdvanceTo(kTick_s, y).ok);
  Integrator fresh(2, Params(Method::kAdams), Oscillator);
  fresh.Reset(0.0, y_fresh);
  REQUIRE(fresh.AdvanceTo(kTick_s, y_fresh).ok);
  CHECK(y[0] == y_fresh[0]);
  CHECK(y[1] == y_fresh[1]);
}

TEST_CASE("ErrorWeightsReplaceTheScalarTolerances", "[integrator]") {
  // SetErrorWeights with CVODE's own formula 1/(rel·|y| + abs) reproduces the scalar
  // tolerances bit for bit; 100× larger weights (100× tighter tolerances) take more steps and
  // cut the error; a failing weight function fails the interval; an empty one restores the
  // scalar tolerances.
  constexpr int kTicks = 100;
  const Method method = GENERATE(Method::kAdams, Method::kBdf);
  auto weights = [](double scale) {
    return [scale](const double *y, double *ewt) {
      for (int i = 0; i < 2; ++i) ewt[i] = scale / (kRelTol * std::abs(y[i]) + kAbsTol);
      return 0;
    };
  };
  auto run = [&](Integrator &integ, std::vector<double> &y) {
    OscillatorExact(0.0, y.data());
    return MaxTickErrorWithResets(integ, 2, kTicks, OscillatorExact);
  };
  std::vector<double> y_scalar(2), y_same(2), y_tight(2), y_restored(2);
  Integrator scalar(2, Params(method), Oscillator);
  const double err_scalar = run(scalar, y_scalar);
  // MaxTickErrorWithResets restarts from the exact solution: recompute the end states.
  auto end_state = [&](Integrator &integ, std::vector<double> &y) {
    OscillatorExact(0.0, y.data());
    for (int k = 0; k < kTicks; ++k) {
      integ.Reset(k * kTick_s, y.data());
      REQUIRE(integ.AdvanceTo((k + 1) * kTick_s, y.data()).ok);
    }
  };
  Integrator a(2, Params(method), Oscillator), b(2, Params(method), Oscillator);
  end_state(a, y_scalar);
  b.SetErrorWeights(weights(1.0));
  end_state(b, y_same);
  CHECK(y_same[0] == y_scalar[0]);
  CHECK(y_same[1] == y_scalar[1]);
  CHECK(b.GetStats().steps == a.GetStats().steps);
  CHECK(b.GetStats().rhs_evals == a.GetStats().rhs_evals);

  Integrator tight(2, Params(method), Oscillator);
  tight.SetErrorWeights(weights(100.0));
  const double err_tight = run(tight, y_tight);
  std::printf("ewt        %-18s scalar err %.3e steps %ld | weights x100 err %.3e steps %ld\n",
              Name(method), err_scalar, scalar.GetStats().steps, err_tight,
              tight.GetStats().steps);
  CHECK(tight.GetStats().steps > scalar.GetStats().steps);
  CHECK(err_tight < err_scalar / 10.0);

  Integrator failing(2, Params(method), Oscillator);
  failing.SetErrorWeights([](const double *, double *) { return -1; });
  double y[2];
  OscillatorExact(0.0, y);
  failing.Reset(0.0, y);
  const Integrator::Result r = failing.AdvanceTo(kTick_s, y);
  CHECK_FALSE(r.ok);
  CHECK(std::isfinite(y[0]));
  failing.SetErrorWeights({});  // back to rel_tol / abs_tol
  end_state(failing, y_restored);
  CHECK(y_restored[0] == y_scalar[0]);
  CHECK(y_restored[1] == y_scalar[1]);
}
