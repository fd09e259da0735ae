// SPDX-License-Identifier: Apache-2.0
// integrator.cpp: CVODE (SUNDIALS 6.4) behind uvms::plant::Integrator.
//
// Ownership: one RAII handle per SUNDIALS object, declared in Impl so that destruction runs
// in the order SUNDIALS needs: the CVODE memory first (it refers to the solvers, the vector
// template and the context), then the nonlinear solver, linear solver, matrix, vector, and
// the SUNContext last.
//
// Errors: every flag is checked and named with CVodeGetReturnFlagName (which returns a
// malloc'd string the caller must free). CVODE's own error text is captured through an error
// handler instead of being printed to stderr, so that it ends up in Result::message. No C++
// exception ever crosses into CVODE: the rhs trampoline and the error handler catch all.
#include "uvms_plant/integrator.hpp"

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_types.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace uvms::plant {

namespace {

// ---- RAII handles ------------------------------------------------------------------------

struct ContextDeleter {
  void operator()(std::remove_pointer_t<SUNContext> *c) const {
    SUNContext ctx = c;
    SUNContext_Free(&ctx);
  }
};
struct VectorDeleter {
  void operator()(std::remove_pointer_t<N_Vector> *v) const { N_VDestroy(v); }
};
struct MatrixDeleter {
  void operator()(std::remove_pointer_t<SUNMatrix> *m) const { SUNMatDestroy(m); }
};
struct LinSolDeleter {
  void operator()(std::remove_pointer_t<SUNLinearSolver> *s) const { SUNLinSolFree(s); }
};
struct NonlinSolDeleter {
  void operator()(std::remove_pointer_t<SUNNonlinearSolver> *s) const { SUNNonlinSolFree(s); }
};
struct CvodeDeleter {
  void operator()(void *mem) const { CVodeFree(&mem); }
};

using ContextPtr = std::unique_ptr<std::remove_pointer_t<SUNContext>, ContextDeleter>;
using VectorPtr = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using MatrixPtr = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinSolPtr = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinSolDeleter>;
using NonlinSolPtr =
    std::unique_ptr<std::remove_pointer_t<SUNNonlinearSolver>, NonlinSolDeleter>;
using CvodePtr = std::unique_ptr<void, CvodeDeleter>;

// ---- flag names ----------------------------------------------------------------------------

// CVodeGetReturnFlagName / CVodeGetLinReturnFlagName malloc their result (SUNDIALS 6.4
// src/cvode/cvode.c): copy it and free it, or every failure report leaks 24 bytes.
std::string TakeCString(char *p, long flag) {
  if (p == nullptr) return "flag " + std::to_string(flag);
  std::string s(p);
  std::free(p);
  return s;
}

std::string CvodeFlagName(long flag) { return TakeCString(CVodeGetReturnFlagName(flag), flag); }
std::string CvlsFlagName(long flag) { return TakeCString(CVodeGetLinReturnFlagName(flag), flag); }

std::string FormatDouble(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// ---- vector kernels --------------------------------------------------------------------------

// The serial N_Vector's hottest operations under Adams/fixed-point (≈ 35 % of the plant's
// run time in SUNDIALS 6.4.1's build: every predictor, correction and error norm), re-written
// as plain loops that the compiler inlines and unrolls. Each reproduces the SUNDIALS serial
// kernel bit for bit: the same products and sums in the same order, including the a = ±b
// cases of N_VLinearSum_Serial that factor the scalar out; every other case of that function
// (a or b = ±1, axpy in place) equals a·x + b·y exactly, since multiplying by ±1 is exact.
void LinearSumKernel(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(x);
  const sunrealtype *xd = NV_DATA_S(x), *yd = NV_DATA_S(y);
  sunrealtype *zd = NV_DATA_S(z);
  const bool unit = a == 1.0 || a == -1.0 || b == 1.0 || b == -1.0;
  if (!unit && a == b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] + yd[i]);
  } else if (!unit && a == -b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] - yd[i]);
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
  }
}
void ScaleKernel(sunrealtype c, N_Vector x, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(x);
  const sunrealtype *xd = NV_DATA_S(x);
  sunrealtype *zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c * xd[i];
}
void ConstKernel(sunrealtype c, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(z);
  sunrealtype *zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c;
}
sunrealtype WrmsNormKernel(N_Vector x, N_Vector w) {
  const sunindextype n = NV_LENGTH_S(x);
  const sunrealtype *xd = NV_DATA_S(x), *wd = NV_DATA_S(w);
  sunrealtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    const sunrealtype p = xd[i] * wd[i];
    sum += p * p;
  }
  return std::sqrt(sum / static_cast<sunrealtype>(n));
}

}  // namespace

// ---- implementation ------------------------------------------------------------------------

struct Integrator::Impl {
  Impl(std::size_t n_in, const IntegratorParams &p, Rhs f)
      : n(n_in), params(p), rhs(std::move(f)) {}

  // The one CVRhsFn: user_data is this Impl. Returns the rhs's own code (0 / > 0 / < 0);
  // every exception becomes −1 (fatal) with its text kept for Result::message.
  static int Trampoline(sunrealtype t, N_Vector y, N_Vector ydot, void *user_data) {
    auto *self = static_cast<Impl *>(user_data);
    ++self->rhs_calls;
    try {
      const int rc = self->rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot));
      if (rc != 0) {
        if (rc < 0) self->rhs_fatal = true;
        self->NoteRhsFailure(t, "the right-hand side returned " + std::to_string(rc) +
                                    (rc > 0 ? " (recoverable)" : " (unrecoverable)"));
      }
      return rc;
    } catch (const std::exception &e) {
      self->rhs_fatal = true;
      self->NoteRhsFailure(t, std::string("the right-hand side threw: ") + e.what());
    } catch (...) {
      self->rhs_fatal = true;
      self->NoteRhsFailure(t, "the right-hand side threw an unknown exception");
    }
    return -1;
  }

  // Solve op of our fixed-point solver. SUNDIALS 6.4.1's SUNNonlinSolSolve_FixedPoint
  // breaks out of its loop on ANY non-zero return of the system function and then reports
  // SUN_NLS_CONV_RECVR: an unrecoverable rhs failure (−1) becomes a recoverable convergence
  // failure, CVODE shrinks h and retries until CV_CONV_FAILURE or, once t + h == t,
  // CV_TOO_MUCH_WORK (observed; Newton/BDF reports CV_RHSFUNC_FAIL). This wrapper restores
  // the documented meaning: if the rhs failed unrecoverably during the solve, return
  // CV_RHSFUNC_FAIL, which cvHandleNFlag passes straight out of CVode.
  static int FixedPointSolve(SUNNonlinearSolver nls, N_Vector y0, N_Vector ycor, N_Vector w,
                             sunrealtype tol, sunbooleantype call_setup, void *cvode_mem) {
    const int flag = SUNNonlinSolSolve_FixedPoint(nls, y0, ycor, w, tol, call_setup, cvode_mem);
    if (flag == SUN_NLS_SUCCESS) return flag;
    void *user_data = nullptr;
    if (CVodeGetUserData(cvode_mem, &user_data) == CV_SUCCESS && user_data != nullptr &&
        static_cast<Impl *>(user_data)->rhs_fatal) {
      return CV_RHSFUNC_FAIL;
    }
    return flag;
  }

  // CVEwtFn: the user's error weights (SetErrorWeights); −1 (CVODE fails the step) on any
  // failure, never an exception into C.
  static int EwtTrampoline(N_Vector y, N_Vector ewt, void *user_data) {
    auto *self = static_cast<Impl *>(user_data);
    try {
      return self->ewt_fn(N_VGetArrayPointer(y), N_VGetArrayPointer(ewt)) == 0 ? 0 : -1;
    } catch (...) {
      return -1;
    }
  }

  // Scalar tolerances, or the user's weights, whichever is current.
  void ApplyTolerances() {
    void *mem = cvode.get();
    if (ewt_fn) {
      Check(CVodeWFtolerances(mem, &Impl::EwtTrampoline), "CVodeWFtolerances");
    } else {
      Check(CVodeSStolerances(mem, params.rel_tol, params.abs_tol), "CVodeSStolerances");
    }
    tolerances_dirty = false;
  }

  // CVErrHandlerFn: keep CVODE's text instead of printing it (error_code < 0: error,
  // CV_WARNING: warning, e.g. "t + h = t on the next step").
  static void ErrHandler(int error_code, const char *module, const char *function, char *msg,
                         void *user_data) {
    auto *self = static_cast<Impl *>(user_data);
    try {
      std::string text = std::string(module ? module : "CVODE") + "::" +
                         (function ? function : "?") + ": " + (msg ? msg : "");
      if (error_code < 0) {
        self->cvode_error = std::move(text);
      } else {
        self->cvode_warning = std::move(text);
      }
    } catch (...) {
      // Out of memory while formatting: drop the text, the flag is still reported.
    }
  }

  void NoteRhsFailure(double t, const std::string &what) noexcept {
    try {
      // Keep the first failure of this AdvanceTo: it is the cause, later ones are retries.
      if (rhs_error.empty()) rhs_error = what + " at t = " + FormatDouble(t) + " s";
    } catch (...) {
    }
  }

  // Throw std::runtime_error for a failed setup call.
  void Check(int flag, const char *call) const {
    if (flag >= 0) return;
    std::string msg = std::string("Integrator: ") + call + " failed: " + CvodeFlagName(flag);
    if (!cvode_error.empty()) msg += " (" + cvode_error + ")";
    throw std::runtime_error(msg);
  }

  // After the first CVodeInit: tolerances, step limit, solvers. Done once; CVodeReInit keeps
  // them.
  void Configure() {
    void *mem = cvode.get();
    ApplyTolerances();
    Check(CVodeSetMaxNumSteps(mem, params.max_steps), "CVodeSetMaxNumSteps");
    Check(CVodeSetNonlinConvCoef(mem, params.nonlin_conv_coef), "CVodeSetNonlinConvCoef");
    Check(CVodeSetEtaMaxEarlyStep(mem, params.early_step_growth_max), "CVodeSetEtaMaxEarlyStep");
    if (params.method == IntegratorParams::Method::kAdams) {
      // Fixed-point (functional) iteration, no acceleration vectors: no Jacobian, no linear
      // solver. CVODE created a Newton solver in CVodeInit; attaching ours frees it.
      nls.reset(SUNNonlinSol_FixedPoint(y.get(), 0, ctx.get()));
      if (!nls || !nls->ops) {
        throw std::runtime_error("Integrator: SUNNonlinSol_FixedPoint failed");
      }
      nls->ops->solve = &Impl::FixedPointSolve;  // this object's own ops table (see above)
      Check(CVodeSetNonlinearSolver(mem, nls.get()), "CVodeSetNonlinearSolver");
    } else {
      // CVODE's default Newton solver + dense direct solver; no Jacobian function is given,
      // so CVODE uses its internal difference-quotient approximation.
      const auto nn = static_cast<sunindextype>(n);
      A.reset(SUNDenseMatrix(nn, nn, ctx.get()));
      if (!A) throw std::runtime_error("Integrator: SUNDenseMatrix failed");
      ls.reset(SUNLinSol_Dense(y.get(), A.get(), ctx.get()));
      if (!ls) throw std::runtime_error("Integrator: SUNLinSol_Dense failed");
      const int flag = CVodeSetLinearSolver(mem, ls.get(), A.get());
      if (flag != CVLS_SUCCESS) {
        throw std::runtime_error("Integrator: CVodeSetLinearSolver failed: " +
                                 CvlsFlagName(flag));
      }
    }
  }

  // CVODE's counters since the last CVodeInit/CVodeReInit (which zero them).
  Stats CurrentCounters() const {
    Stats s;
    if (!cvode_initialized) return s;
    void *mem = cvode.get();
    // These getters only fail for a null cvode_mem, excluded above; on failure the counter
    // stays 0 rather than garbage.
    long v = 0;
    if (CVodeGetNumSteps(mem, &v) == CV_SUCCESS) s.steps = v;
    v = 0;
    if (CVodeGetNumNonlinSolvIters(mem, &v) == CV_SUCCESS) s.nonlin_iters = v;
    v = 0;
    if (CVodeGetNumNonlinSolvConvFails(mem, &v) == CV_SUCCESS) s.nonlin_conv_fails = v;
    v = 0;
    if (CVodeGetNumErrTestFails(mem, &v) == CV_SUCCESS) s.err_test_fails = v;
    return s;
  }

  std::size_t n;
  IntegratorParams params;
  Rhs rhs;
  ErrorWeights ewt_fn;            // empty: scalar tolerances
  double init_step_s{0.0};        // SetInitStep: applied at every Reset (0: CVODE estimates)
  bool tolerances_dirty{false};   // SetErrorWeights since the last ApplyTolerances

  // Destroyed bottom-up: cvode first, ctx last (see the file comment).
  ContextPtr ctx;
  VectorPtr y;  // CVODE's y0 / yout vector; always holds the last known state
  MatrixPtr A;
  LinSolPtr ls;
  NonlinSolPtr nls;
  CvodePtr cvode;

  bool cvode_initialized{false};  // CVodeInit succeeded (later restarts use CVodeReInit)
  bool configured{false};         // Configure() succeeded
  bool ready{false};              // the last Reset succeeded: AdvanceTo may run
  double t_current_s{0.0};

  bool rhs_fatal{false};      // the rhs failed unrecoverably in the current AdvanceTo
  std::string rhs_error;      // first rhs failure of the current AdvanceTo
  std::string cvode_error;    // CVODE's last error text
  std::string cvode_warning;  // CVODE's last warning text

  long rhs_calls{0};  // every Trampoline call since construction
  long reinits{0};
  Stats before_restart;  // CVODE counters summed over previous Init/ReInit intervals
};

// ---- public API ----------------------------------------------------------------------------

Integrator::Integrator(std::size_t n, const IntegratorParams &params, Rhs rhs) {
  if (n == 0) throw std::invalid_argument("Integrator: n (number of states) must be > 0");
  if (n > static_cast<std::size_t>(std::numeric_limits<sunindextype>::max())) {
    throw std::invalid_argument("Integrator: n (number of states) is too large");
  }
  if (!(std::isfinite(params.rel_tol) && params.rel_tol > 0.0)) {
    throw std::invalid_argument("Integrator: IntegratorParams::rel_tol must be finite and > 0, "
                                "got " + FormatDouble(params.rel_tol));
  }
  if (!(std::isfinite(params.abs_tol) && params.abs_tol > 0.0)) {
    throw std::invalid_argument("Integrator: IntegratorParams::abs_tol must be finite and > 0, "
                                "got " + FormatDouble(params.abs_tol));
  }
  if (!(std::isfinite(params.nonlin_conv_coef) && params.nonlin_conv_coef > 0.0)) {
    throw std::invalid_argument("Integrator: IntegratorParams::nonlin_conv_coef must be finite "
                                "and > 0, got " + FormatDouble(params.nonlin_conv_coef));
  }
  if (!(std::isfinite(params.early_step_growth_max) && params.early_step_growth_max > 1.0)) {
    throw std::invalid_argument("Integrator: IntegratorParams::early_step_growth_max must be "
                                "finite and > 1, got " + FormatDouble(params.early_step_growth_max));
  }
  if (params.max_steps <= 0) {
    throw std::invalid_argument("Integrator: IntegratorParams::max_steps must be > 0, got " +
                                std::to_string(params.max_steps));
  }
  if (params.method != IntegratorParams::Method::kAdams &&
      params.method != IntegratorParams::Method::kBdf) {
    throw std::invalid_argument("Integrator: IntegratorParams::method is not kAdams or kBdf");
  }
  if (!rhs) throw std::invalid_argument("Integrator: rhs (right-hand side) is empty");

  impl_ = std::make_unique<Impl>(n, params, std::move(rhs));
  Impl &m = *impl_;

  SUNContext ctx = nullptr;
  if (SUNContext_Create(nullptr, &ctx) != 0 || ctx == nullptr) {
    throw std::runtime_error("Integrator: SUNContext_Create failed");
  }
  m.ctx.reset(ctx);

  m.y.reset(N_VNew_Serial(static_cast<sunindextype>(n), m.ctx.get()));
  if (!m.y) throw std::runtime_error("Integrator: N_VNew_Serial failed");
  // This vector's own ops table (N_VNew_Serial allocates one per vector); CVODE and the
  // fixed-point solver clone their work vectors from it, ops included.
  m.y->ops->nvlinearsum = &LinearSumKernel;
  m.y->ops->nvscale = &ScaleKernel;
  m.y->ops->nvwrmsnorm = &WrmsNormKernel;
  m.y->ops->nvconst = &ConstKernel;
  N_VConst(0.0, m.y.get());

  const int lmm = params.method == IntegratorParams::Method::kAdams ? CV_ADAMS : CV_BDF;
  m.cvode.reset(CVodeCreate(lmm, m.ctx.get()));
  if (!m.cvode) throw std::runtime_error("Integrator: CVodeCreate failed");
  // Impl lives on the heap: this pointer stays valid when the Integrator is moved.
  m.Check(CVodeSetErrHandlerFn(m.cvode.get(), &Impl::ErrHandler, &m), "CVodeSetErrHandlerFn");
  m.Check(CVodeSetUserData(m.cvode.get(), &m), "CVodeSetUserData");
}

Integrator::~Integrator() = default;
Integrator::Integrator(Integrator &&) noexcept = default;
Integrator &Integrator::operator=(Integrator &&) noexcept = default;

std::size_t Integrator::size() const { return impl_ ? impl_->n : 0; }

void Integrator::Reset(double t0_s, const double *y0) {
  if (!impl_) throw std::logic_error("Integrator::Reset on a moved-from Integrator");
  Impl &m = *impl_;
  if (y0 == nullptr) throw std::invalid_argument("Integrator::Reset: y0 is null");
  if (!std::isfinite(t0_s)) {
    throw std::invalid_argument("Integrator::Reset: t0 is not finite: " + FormatDouble(t0_s));
  }
  for (std::size_t i = 0; i < m.n; ++i) {
    if (!std::isfinite(y0[i])) {
      throw std::invalid_argument("Integrator::Reset: y0[" + std::to_string(i) +
                                  "] is not finite: " + FormatDouble(y0[i]));
    }
  }

  m.ready = false;
  m.cvode_error.clear();
  m.cvode_warning.clear();
  m.rhs_error.clear();
  m.rhs_fatal = false;

  sunrealtype *y = N_VGetArrayPointer(m.y.get());
  for (std::size_t i = 0; i < m.n; ++i) y[i] = y0[i];

  if (!m.cvode_initialized) {
    m.Check(CVodeInit(m.cvode.get(), &Impl::Trampoline, t0_s, m.y.get()), "CVodeInit");
    m.cvode_initialized = true;
  } else {
    // CVodeReInit zeroes CVODE's counters: bank them first so that GetStats is cumulative.
    const Stats c = m.CurrentCounters();
    m.Check(CVodeReInit(m.cvode.get(), t0_s, m.y.get()), "CVodeReInit");
    m.before_restart.steps += c.steps;
    m.before_restart.nonlin_iters += c.nonlin_iters;
    m.before_restart.nonlin_conv_fails += c.nonlin_conv_fails;
    m.before_restart.err_test_fails += c.err_test_fails;
  }
  if (!m.configured) {
    m.Configure();
    m.configured = true;
  } else if (m.tolerances_dirty) {
    m.ApplyTolerances();
  }
  m.Check(CVodeSetInitStep(m.cvode.get(), m.init_step_s), "CVodeSetInitStep");
  m.t_current_s = t0_s;
  m.ready = true;
  ++m.reinits;
}

Integrator::Result Integrator::AdvanceTo(double t_stop_s, double *y_out) {
  Result r;
  try {
    if (!impl_) {
      r.flag = CV_MEM_NULL;
      r.flag_name = CvodeFlagName(r.flag);
      r.message = "Integrator::AdvanceTo on a moved-from Integrator";
      return r;
    }
    Impl &m = *impl_;
    r.t_reached = m.t_current_s;
    if (y_out == nullptr) {
      r.flag = CV_ILL_INPUT;
      r.flag_name = CvodeFlagName(r.flag);
      r.message = "Integrator::AdvanceTo: y_out is null";
      return r;
    }
    const sunrealtype *y = N_VGetArrayPointer(m.y.get());
    auto copy_state = [&] {
      for (std::size_t i = 0; i < m.n; ++i) y_out[i] = y[i];
    };
    if (!m.ready) {
      copy_state();
      r.flag = CV_NO_MALLOC;
      r.flag_name = CvodeFlagName(r.flag);
      r.message = "Integrator::AdvanceTo: no successful Reset since construction or since the "
                  "last failure; call Reset(t0, y0) first";
      return r;
    }
    if (!std::isfinite(t_stop_s) || !(t_stop_s > m.t_current_s)) {
      copy_state();
      r.flag = CV_ILL_INPUT;
      r.flag_name = CvodeFlagName(r.flag);
      r.message = "Integrator::AdvanceTo: t_stop = " + FormatDouble(t_stop_s) +
                  " s must be finite and later than the current time " +
                  FormatDouble(m.t_current_s) + " s";
      return r;
    }

    m.rhs_error.clear();
    m.rhs_fatal = false;
    m.cvode_error.clear();
    m.cvode_warning.clear();

    // The stop time is set for every call: CVODE disables it once reached, and a restart
    // does not set a new one.
    int flag = CVodeSetStopTime(m.cvode.get(), t_stop_s);
    sunrealtype t_ret = m.t_current_s;
    if (flag == CV_SUCCESS) {
      flag = CVode(m.cvode.get(), t_stop_s, m.y.get(), &t_ret, CV_NORMAL);
    }
    // On failure CVODE leaves in y its last accepted state at t_ret (or, for errors caught
    // before stepping, the state it started from).
    copy_state();
    r.flag = flag;
    r.flag_name = CvodeFlagName(flag);
    // CV_TSTOP_RETURN is the normal exit; CV_SUCCESS means tout (= t_stop) was reached
    // exactly, which round-off can produce. Either way CVODE returns y at t_stop itself.
    if ((flag == CV_TSTOP_RETURN || flag == CV_SUCCESS) && t_ret == t_stop_s) {
      r.ok = true;
      r.t_reached = t_stop_s;
      m.t_current_s = t_stop_s;
      return r;
    }

    r.ok = false;
    r.t_reached = t_ret;
    m.t_current_s = t_ret;
    m.ready = false;  // a failed interval needs a Reset before the next AdvanceTo
    std::ostringstream msg;
    msg << "CVODE stopped at t = " << FormatDouble(r.t_reached) << " s, short of t_stop = "
        << FormatDouble(t_stop_s) << " s: " << r.flag_name;
    if (flag >= 0) msg << " (returned before t_stop, at t = " << FormatDouble(t_ret) << " s)";
    if (!m.cvode_error.empty()) msg << "; " << m.cvode_error;
    if (!m.rhs_error.empty()) msg << "; " << m.rhs_error;
    if (!m.cvode_warning.empty()) msg << "; last warning: " << m.cvode_warning;
    r.message = msg.str();
    return r;
  } catch (const std::exception &e) {
    // Only allocation can throw above; report it rather than letting it escape.
    r.ok = false;
    if (r.flag >= 0) {
      r.flag = CV_MEM_FAIL;
      r.flag_name = "CV_MEM_FAIL";
    }
    r.message = std::string("Integrator::AdvanceTo: ") + e.what();
    if (impl_) impl_->ready = false;
    return r;
  }
}

void Integrator::SetErrorWeights(ErrorWeights ewt) {
  if (!impl_) return;
  impl_->ewt_fn = std::move(ewt);
  impl_->tolerances_dirty = true;
}

void Integrator::SetInitStep(double h_s) {
  if (!(std::isfinite(h_s) && h_s >= 0.0)) {
    throw std::invalid_argument("Integrator::SetInitStep: h must be finite and >= 0, got " +
                                FormatDouble(h_s));
  }
  if (impl_) impl_->init_step_s = h_s;
}

double Integrator::LastStep() const {
  sunrealtype h = 0.0;
  if (!impl_ || !impl_->cvode_initialized) return 0.0;
  return CVodeGetLastStep(impl_->cvode.get(), &h) == CV_SUCCESS ? h : 0.0;
}

double Integrator::NextStep() const {
  sunrealtype h = 0.0;
  if (!impl_ || !impl_->cvode_initialized) return 0.0;
  return CVodeGetCurrentStep(impl_->cvode.get(), &h) == CV_SUCCESS ? h : 0.0;
}

Integrator::Stats Integrator::GetStats() const {
  Stats s;
  if (!impl_) return s;
  const Impl &m = *impl_;
  const Stats c = m.CurrentCounters();
  s.steps = m.before_restart.steps + c.steps;
  s.rhs_evals = m.rhs_calls;
  s.nonlin_iters = m.before_restart.nonlin_iters + c.nonlin_iters;
  s.nonlin_conv_fails = m.before_restart.nonlin_conv_fails + c.nonlin_conv_fails;
  s.err_test_fails = m.before_restart.err_test_fails + c.err_test_fails;
  s.reinits = m.reinits;
  return s;
}

}  // namespace uvms::plant
