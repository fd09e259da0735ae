// SPDX-License-Identifier: Apache-2.0
// integrator.hpp: the plant's ODE integrator, SUNDIALS CVODE behind a small C++ seam
// (SPEC §5: "Integrate with SUNDIALS CVODE ... stop the integrator at every tick boundary and
// restart it cleanly after inputs change").
//
// Use per controller tick (inputs are piecewise constant over a tick):
//
//   Integrator integ(n, params.integrator, rhs);
//   integ.Reset(t0, y);                     // once, and again after every input change
//   for each tick k:
//     set the held inputs the rhs reads
//     integ.Reset(t_k, y);                  // clean restart: the old history is discarded
//     auto r = integ.AdvanceTo(t_k + dt, y);
//     if (!r.ok) stop the run, reporting r.flag_name and r.message
//
// AdvanceTo never evaluates the right-hand side beyond t_stop (CVodeSetStopTime), so an rhs
// that reads the tick's inputs never sees the next tick's time.
//
// SUNDIALS stays out of this header (the library links it privately): the CVODE objects
// live in a private implementation, which also keeps the pointer CVODE holds as user_data
// stable when an Integrator is moved.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "uvms_plant/params.hpp"

namespace uvms::plant {

class Integrator {
 public:
  /// Right-hand side ẏ = f(t, y).
  /// @param t    time [s]
  /// @param y    [in] state, n values (valid only during the call)
  /// @param ydot [out] derivative, n values
  /// @return 0 success; > 0 recoverable failure (CVODE retries with a smaller step);
  ///         < 0 unrecoverable failure (AdvanceTo returns ok = false). A thrown exception is
  ///         treated as < 0 and its what() is reported in Result::message.
  using Rhs = std::function<int(double t, const double *y, double *ydot)>;

  /// Outcome of AdvanceTo.
  struct Result {
    bool ok{false};         ///< true iff t_reached == t_stop and y_out is the solution there
    int flag{0};            ///< CVODE's return flag (CV_TSTOP_RETURN on success; < 0 failure)
    std::string flag_name;  ///< CVodeGetReturnFlagName(flag), e.g. "CV_TOO_MUCH_WORK"
    std::string message;    ///< readable account of a failure (CVODE's own text, the rhs's
                            ///< exception or return code); empty on success
    double t_reached{0.0};  ///< time of y_out [s]: t_stop on success, the last time CVODE
                            ///< reached on failure
  };

  /// Counters, cumulative over every Reset/AdvanceTo since construction (CVODE's own
  /// counters restart at every CVodeReInit; these are summed across restarts).
  struct Stats {
    long steps{0};              ///< internal steps (CVodeGetNumSteps)
    long rhs_evals{0};          ///< calls of the rhs: CVodeGetNumRhsEvals, plus the
                                ///< finite-difference Jacobian's (CVodeGetNumLinRhsEvals, BDF)
    long nonlin_iters{0};       ///< nonlinear solver iterations (CVodeGetNumNonlinSolvIters)
    long nonlin_conv_fails{0};  ///< nonlinear convergence failures
                                ///< (CVodeGetNumNonlinSolvConvFails)
    long err_test_fails{0};     ///< local error test failures (CVodeGetNumErrTestFails)
    long reinits{0};            ///< Reset calls that succeeded (the first is CVodeInit, the
                                ///< others CVodeReInit)
  };

  /// Create the CVODE objects for an n-state system.
  /// Method::kAdams: CV_ADAMS with the fixed-point nonlinear solver, no linear solver
  /// (TOOLCHAIN.md: 3–4× faster than BDF on the plant). Method::kBdf: CV_BDF, Newton, dense
  /// linear solver with CVODE's finite-difference Jacobian. Scalar tolerances rel_tol, abs_tol;
  /// at most max_steps internal steps per AdvanceTo (CVodeSetMaxNumSteps).
  /// @param n      number of states, > 0
  /// The nonlinear convergence coefficient is params.nonlin_conv_coef (CVodeSetNonlinConvCoef),
  /// the early steps' growth limit params.early_step_growth_max (CVodeSetEtaMaxEarlyStep).
  /// The serial vector's LinearSum, Scale, Const and WrmsNorm run in this library's own loops, bit for
  /// bit the SUNDIALS kernels (integrator.cpp).
  /// @param params rel_tol > 0, abs_tol > 0, nonlin_conv_coef > 0, early_step_growth_max > 1
  ///               (finite), max_steps > 0
  /// @param rhs    the right-hand side (non-empty); it is copied and owned
  /// @throws std::invalid_argument naming the offending argument or setting
  /// @throws std::runtime_error if a SUNDIALS object cannot be created or configured
  Integrator(std::size_t n, const IntegratorParams &params, Rhs rhs);
  ~Integrator();

  Integrator(const Integrator &) = delete;
  Integrator &operator=(const Integrator &) = delete;
  Integrator(Integrator &&) noexcept;
  Integrator &operator=(Integrator &&) noexcept;

  /// (Re)start at time t0 from state y0: CVodeInit the first time, CVodeReInit afterwards.
  /// A clean restart (order 1, new initial step, no history of the previous interval), which
  /// is right when piecewise-constant inputs jump at tick boundaries. Also the way to recover
  /// after a failed AdvanceTo.
  /// @param t0_s time [s], finite
  /// @param y0   [in] initial state, n finite values
  /// @throws std::invalid_argument if t0 or a y0 entry is not finite, or y0 is null
  /// @throws std::runtime_error if CVODE refuses (flag name in the message)
  void Reset(double t0_s, const double *y0);

  /// Integrate from the current time to exactly t_stop (CVodeSetStopTime + CV_NORMAL): the
  /// right-hand side is never evaluated past t_stop. Never throws, never aborts.
  /// @param t_stop_s end time [s], finite, > the current time
  /// @param y_out    [out] n values: the state at Result::t_reached (on failure, the last
  ///                 state CVODE reached, or the state before the call if it never started)
  /// @return ok = true with flag CV_TSTOP_RETURN on success; ok = false with the CVODE flag
  ///         (e.g. CV_RHSFUNC_FAIL, CV_TOO_MUCH_WORK, CV_CONV_FAILURE), or CV_NO_MALLOC if
  ///         there was no Reset since construction or since the last failed AdvanceTo (a
  ///         failure always needs a Reset), or CV_ILL_INPUT for a bad t_stop / null y_out.
  Result AdvanceTo(double t_stop_s, double *y_out);

  /// Error weights: fill ewt (n values, each > 0) from the state y for CVODE's error norm,
  /// in place of 1/(rel_tol·|y_i| + abs_tol). Return 0, or −1 if a weight cannot be formed.
  using ErrorWeights = std::function<int(const double *y, double *ewt)>;
  /// Use ewt for the local error test (CVodeWFtolerances) from the next Reset on; an empty
  /// function restores the scalar tolerances. Never throws on a valid Integrator.
  void SetErrorWeights(ErrorWeights ewt);

  /// First step size of every following Reset's interval (CVodeSetInitStep), in place of
  /// CVODE's own estimate, which costs extra rhs evaluations and, on the plant, one error-test
  /// failure per restart. 0 restores the estimate (the default). Takes effect at the next
  /// Reset; CVODE still shrinks a first step that fails its error test.
  /// @param h_s step [s], finite and ≥ 0
  /// @throws std::invalid_argument if h_s is negative or not finite
  void SetInitStep(double h_s);

  /// Size of the last internal step taken since the last Reset [s] (CVodeGetLastStep; a step
  /// that CVODE cut short to land on t_stop counts with its shortened length); 0 before the
  /// first step.
  double LastStep() const;

  /// Size CVODE would attempt for its next internal step [s] (CVodeGetCurrentStep): after an
  /// interval that ended on t_stop, the step its error control would take next, whatever the
  /// length of the final, stop-time-limited step; 0 before the first Reset.
  double NextStep() const;

  /// Cumulative counters (see Stats).
  Stats GetStats() const;

  /// Number of states.
  std::size_t size() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace uvms::plant
