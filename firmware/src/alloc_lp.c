/* SPDX-License-Identifier: Apache-2.0 */
/* alloc_lp.c: least-Σ|T| allocation by a bounded-variable revised primal simplex (alloc_lp.h).
 * No allocation, no recursion, no file-scope mutable state; every loop is bounded by
 * LP_M (6), UVMS_MAX_THRUSTERS, LP_NV or UVMS_LP_MAX_ITERATIONS. Variable indices come from
 * the solver's own local state and are still checked against LP_NV before use. */
#include "uvms/alloc_lp.h"

#include <math.h>
#include <string.h>

enum {
  LP_M = UVMS_LP_ROWS,             /* equality rows */
  LP_NS = 2 * UVMS_MAX_THRUSTERS,  /* structural variables: T⁺_j = 2j, T⁻_j = 2j + 1 */
  LP_NV = LP_NS + UVMS_LP_ROWS     /* and artificial i = LP_NS + i */
};

_Static_assert(UVMS_MAX_THRUSTERS <= 31, "usable_mask holds one bit per thruster");
_Static_assert(LP_NV <= 255, "variable indices are stored as uint8_t");

/* Bound state of a variable. FIXED: never priced (an unusable thruster's T±_j, an artificial
   that left the basis, or a basic artificial of a dependent row, which stays at 0). */
typedef enum { VAR_LOWER = 0, VAR_UPPER = 1, VAR_BASIC = 2, VAR_FIXED = 3 } lp_var_state_t;

/* Result of one simplex iteration. */
typedef enum { LP_STEPPED = 0, LP_OPTIMAL = 1 } lp_step_t;

/* The whole solver state: on the caller's stack. */
typedef struct {
  const uvms_real_t *H;       /* 6 × n, row-major H[r·n + j] (not scaled) */
  size_t n;                   /* thrusters, 1..UVMS_MAX_THRUSTERS */
  uvms_real_t w[LP_M];        /* w / σ */
  uvms_real_t art_sign[LP_M]; /* artificial i has column art_sign[i]·e_i */
  uvms_real_t upper;          /* T_max / σ, +inf when unlimited */
  uvms_real_t Binv[LP_M][LP_M];
  uvms_real_t xB[LP_M];       /* values of the basic variables */
  uint8_t basis[LP_M];        /* variable of each row */
  uint8_t state[LP_NV];       /* lp_var_state_t */
  int phase;                  /* 1 or 2 */
  int bland;                  /* Bland's rule from the first degenerate step of the phase */
  uint32_t iterations;
} lp_t;

static uvms_real_t lp_inf(void) { return (uvms_real_t)INFINITY; }

static void zero_thrusts(uvms_real_t *out) {
  if (out == NULL) return;
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) out[j] = UVMS_R(0.0);
}

/* Cost of variable k in the current phase: Phase I prices the artificials, Phase II Σ|T|. */
static uvms_real_t lp_cost(const lp_t *lp, size_t k) {
  const int artificial = (k >= LP_NS);
  return (lp->phase == 1) == artificial ? UVMS_R(1.0) : UVMS_R(0.0);
}

/* Upper bound of variable k (lower bounds are all 0): T_max/σ for T±; +inf for an artificial
   in Phase I, 0 in Phase II. */
static uvms_real_t lp_upper(const lp_t *lp, size_t k) {
  if (k < LP_NS) return lp->upper;
  return (lp->phase == 1) ? lp_inf() : UVMS_R(0.0);
}

/* Column a_k of variable k: ±h_j for T±_j, art_sign[i]·e_i for artificial i; zero for an
   index outside the variables (never produced; checked all the same). */
static void lp_column(const lp_t *lp, size_t k, uvms_real_t a[LP_M]) {
  for (size_t r = 0; r < LP_M; ++r) a[r] = UVMS_R(0.0);
  if (k < LP_NS) {
    const size_t j = k / 2u;
    if (j >= lp->n || j >= UVMS_MAX_THRUSTERS) return;
    const uvms_real_t sgn = (k & 1u) ? UVMS_R(-1.0) : UVMS_R(1.0);
    for (size_t r = 0; r < LP_M; ++r) a[r] = sgn * lp->H[r * lp->n + j];
  } else if (k < LP_NV) {
    a[k - LP_NS] = lp->art_sign[k - LP_NS];
  }
}

/* Value of a nonbasic variable: 0 at its lower bound (or fixed), its upper bound at upper. */
static uvms_real_t lp_nonbasic_value(const lp_t *lp, size_t k) {
  return (lp->state[k] == VAR_UPPER) ? lp_upper(lp, k) : UVMS_R(0.0);
}

/* Scaled problem and the artificial starting basis: B = diag(sign(w_i)), x_B = |w_i|; every
   usable thruster's T±_j at 0, the others fixed. */
static void lp_setup(lp_t *lp, size_t n, const uvms_real_t *H, uint32_t usable_mask,
                     const uvms_real_t w[LP_M], uvms_real_t sigma, uvms_real_t limit_N) {
  /* Every field set explicitly (a byte-wise memset of the struct costs more on the target). */
  lp->H = H;
  lp->n = n;
  lp->upper = limit_N / sigma; /* +inf stays +inf; an overflow to +inf means "no limit" too */
  lp->phase = 1;
  lp->bland = 0;
  lp->iterations = 0u;
  for (size_t i = 0; i < LP_M; ++i)
    for (size_t r = 0; r < LP_M; ++r) lp->Binv[i][r] = UVMS_R(0.0);
  for (size_t k = 0; k < LP_NS; ++k) {
    const size_t j = k / 2u;
    const int usable = (j < n) && (((usable_mask >> (uint32_t)j) & 1u) != 0u);
    lp->state[k] = (uint8_t)(usable ? VAR_LOWER : VAR_FIXED);
  }
  for (size_t i = 0; i < LP_M; ++i) {
    lp->w[i] = w[i] / sigma;
    lp->art_sign[i] = (lp->w[i] < UVMS_R(0.0)) ? UVMS_R(-1.0) : UVMS_R(1.0);
    lp->Binv[i][i] = lp->art_sign[i]; /* diag(s)⁻¹ = diag(s) */
    lp->xB[i] = uvms_fabs(lp->w[i]);
    lp->basis[i] = (uint8_t)(LP_NS + i);
    lp->state[LP_NS + i] = (uint8_t)VAR_BASIC;
  }
}

/* Duals y = c_Bᵀ·B⁻¹. */
static void lp_duals(const lp_t *lp, uvms_real_t y[LP_M]) {
  for (size_t r = 0; r < LP_M; ++r) y[r] = UVMS_R(0.0);
  for (size_t i = 0; i < LP_M; ++i) {
    const uvms_real_t c = lp_cost(lp, lp->basis[i] < LP_NV ? lp->basis[i] : 0u);
    if (c == UVMS_R(0.0)) continue;
    for (size_t r = 0; r < LP_M; ++r) y[r] += c * lp->Binv[i][r];
  }
}

/* Pricing: the entering variable (LP_NV if the basis is optimal) and its direction (+1 from
   the lower bound, −1 from the upper). d = c − y·a; a variable at its lower bound improves
   when d < −tol, at its upper bound when d > tol. Dantzig: the largest violation; Bland:
   the smallest eligible index. Only T±_j are priced (artificials never re-enter). */
static size_t lp_price(const lp_t *lp, const uvms_real_t y[LP_M], int *dir) {
  size_t best = LP_NV;
  uvms_real_t best_violation = UVMS_LP_TOL_OPT;
  for (size_t j = 0; j < lp->n && j < UVMS_MAX_THRUSTERS; ++j) {
    uvms_real_t z = UVMS_R(0.0);
    for (size_t r = 0; r < LP_M; ++r) z += y[r] * lp->H[r * lp->n + j];
    for (size_t s = 0; s < 2u; ++s) {
      const size_t k = 2u * j + s;
      const uint8_t st = lp->state[k];
      if (st != VAR_LOWER && st != VAR_UPPER) continue;
      const uvms_real_t d = lp_cost(lp, k) - (s ? -z : z);
      const uvms_real_t violation = (st == VAR_LOWER) ? -d : d;
      if (!(violation > best_violation)) continue;
      best = k;
      *dir = (st == VAR_LOWER) ? 1 : -1;
      if (lp->bland) return best; /* smallest eligible index */
      best_violation = violation;
    }
  }
  return best;
}

/* alpha = B⁻¹·a_k. */
static void lp_ftran(const lp_t *lp, size_t k, uvms_real_t alpha[LP_M]) {
  uvms_real_t a[LP_M];
  lp_column(lp, k, a);
  for (size_t i = 0; i < LP_M; ++i) {
    uvms_real_t s = UVMS_R(0.0);
    for (size_t r = 0; r < LP_M; ++r) s += lp->Binv[i][r] * a[r];
    alpha[i] = s;
  }
}

/* Does row i (limit theta_i) replace the current choice (row p, limit theta) in the ratio
   test? A clearly shorter step wins; within the tie width Bland takes the smaller variable
   index, Dantzig the larger pivot (better conditioned). A bound flip (p < 0) loses only to
   a clearly shorter step. */
static int lp_ratio_better(const lp_t *lp, size_t i, uvms_real_t theta_i, uvms_real_t pivot_i,
                           int p, uvms_real_t theta, const uvms_real_t alpha[LP_M]) {
  if (theta_i < theta - UVMS_LP_TOL_FEAS) return 1;
  if (p < 0 || theta_i > theta + UVMS_LP_TOL_FEAS) return 0;
  if (lp->bland) return lp->basis[i] < lp->basis[p];
  return uvms_fabs(pivot_i) > uvms_fabs(alpha[p]);
}

/* Ratio test for entering k moving in direction dir (x_B changes by −dir·θ·alpha): the
   largest step θ that keeps every basic variable within [0, its upper bound] and the entering
   one within its own range. Returns the leaving row, −1 for a bound flip of k, −2 when
   nothing bounds the step. */
static int lp_ratio(const lp_t *lp, size_t k, int dir, const uvms_real_t alpha[LP_M],
                    uvms_real_t *theta) {
  int p = -1;
  uvms_real_t best = lp_upper(lp, k); /* bound flip: from one bound to the other */
  for (size_t i = 0; i < LP_M; ++i) {
    const uvms_real_t a = (dir > 0) ? alpha[i] : -alpha[i];
    uvms_real_t limit;
    if (a > UVMS_LP_TOL_PIVOT) {
      limit = lp->xB[i] / a; /* decreases to its lower bound 0 */
    } else if (a < -UVMS_LP_TOL_PIVOT) {
      const uvms_real_t up = lp_upper(lp, lp->basis[i] < LP_NV ? lp->basis[i] : 0u);
      if (!uvms_isfinite(up)) continue;
      limit = (up - lp->xB[i]) / -a; /* increases to its upper bound */
    } else {
      continue;
    }
    if (limit < UVMS_R(0.0)) limit = UVMS_R(0.0); /* a basic value a rounding outside */
    if (lp_ratio_better(lp, i, limit, alpha[i], p, best, alpha)) {
      best = limit;
      p = (int)i;
    }
  }
  *theta = best;
  if (p < 0 && !uvms_isfinite(best)) return -2;
  return p;
}

/* Basis change: entering k replaces the basic variable of row p (pivot alpha[p]); B⁻¹ by the
   product-form update (row p divided by the pivot, eliminated from the other rows). */
static void lp_pivot(lp_t *lp, size_t k, size_t p, const uvms_real_t alpha[LP_M],
                     uvms_real_t entering_value, uint8_t leaving_state) {
  const size_t leaving = lp->basis[p];
  if (leaving < LP_NS) lp->state[leaving] = leaving_state;
  else if (leaving < LP_NV) lp->state[leaving] = (uint8_t)VAR_FIXED; /* never re-enters */
  const uvms_real_t inv_pivot = UVMS_R(1.0) / alpha[p];
  for (size_t r = 0; r < LP_M; ++r) lp->Binv[p][r] *= inv_pivot;
  for (size_t i = 0; i < LP_M; ++i) {
    if (i == p || alpha[i] == UVMS_R(0.0)) continue;
    for (size_t r = 0; r < LP_M; ++r) lp->Binv[i][r] -= alpha[i] * lp->Binv[p][r];
  }
  lp->basis[p] = (uint8_t)k;
  lp->state[k] = (uint8_t)VAR_BASIC;
  lp->xB[p] = entering_value;
  lp->iterations += 1u;
}

/* One iteration of the current phase. */
static uvms_status_t lp_iterate(lp_t *lp, lp_step_t *result) {
  uvms_real_t y[LP_M], alpha[LP_M];
  int dir = 1;
  lp_duals(lp, y);
  const size_t k = lp_price(lp, y, &dir);
  *result = LP_OPTIMAL;
  if (k >= LP_NV) return UVMS_OK;
  *result = LP_STEPPED;
  lp_ftran(lp, k, alpha);
  uvms_real_t theta = UVMS_R(0.0);
  const int p = lp_ratio(lp, k, dir, alpha, &theta);
  if (p == -2) return UVMS_ERR_SINGULAR;
  if (!(theta > UVMS_LP_TOL_FEAS)) lp->bland = 1; /* degenerate: Bland from here on */
  const uvms_real_t step = (dir > 0) ? theta : -theta;
  for (size_t i = 0; i < LP_M; ++i) lp->xB[i] -= step * alpha[i];
  if (p < 0) { /* bound flip: no basis change */
    lp->state[k] = (uint8_t)((lp->state[k] == VAR_LOWER) ? VAR_UPPER : VAR_LOWER);
    lp->iterations += 1u;
    return UVMS_OK;
  }
  const size_t row = (size_t)p;
  const uvms_real_t a = (dir > 0) ? alpha[row] : -alpha[row];
  const uint8_t leaving_state = (uint8_t)((a > UVMS_R(0.0)) ? VAR_LOWER : VAR_UPPER);
  const uvms_real_t entering_value = (dir > 0) ? theta : lp_upper(lp, k) - theta;
  lp_pivot(lp, k, row, alpha, entering_value, leaving_state);
  return UVMS_OK;
}

/* Iterate the current phase to its optimum within the shared iteration budget. */
static uvms_status_t lp_run_phase(lp_t *lp) {
  lp->bland = 0;
  for (uint32_t guard = 0; guard < UVMS_LP_MAX_ITERATIONS; ++guard) {
    if (lp->iterations >= UVMS_LP_MAX_ITERATIONS) return UVMS_ERR_RANGE;
    lp_step_t result = LP_STEPPED;
    const uvms_status_t st = lp_iterate(lp, &result);
    if (st != UVMS_OK) return st;
    if (result == LP_OPTIMAL) return UVMS_OK;
  }
  return UVMS_ERR_RANGE;
}

/* Sum of the basic artificials: the Phase I objective. */
static uvms_real_t lp_infeasibility(const lp_t *lp) {
  uvms_real_t s = UVMS_R(0.0);
  for (size_t i = 0; i < LP_M; ++i)
    if (lp->basis[i] >= LP_NS) s += uvms_fabs(lp->xB[i]);
  return s;
}

/* After Phase I: each artificial still basic (at rounding level) is set to 0 and pivoted out
   on the nonbasic usable thruster with the largest entry in its row of B⁻¹·H (degenerate
   pivot, the thruster keeps its current value); when no entry exceeds the pivot tolerance
   the row is dependent and its artificial stays basic, fixed at 0. Returns the number of
   dependent rows. */
static uint32_t lp_drive_out_artificials(lp_t *lp) {
  uint32_t dependent = 0u;
  for (size_t p = 0; p < LP_M; ++p) {
    if (lp->basis[p] < LP_NS) continue;
    lp->xB[p] = UVMS_R(0.0);
    size_t best_k = LP_NV;
    uvms_real_t best = UVMS_LP_TOL_PIVOT;
    for (size_t j = 0; j < lp->n && j < UVMS_MAX_THRUSTERS; ++j) {
      const size_t kp = 2u * j, km = kp + 1u;
      const uint8_t sp = lp->state[kp], sm = lp->state[km];
      if (sp == VAR_BASIC || sm == VAR_BASIC || sp == VAR_FIXED) continue;
      uvms_real_t e = UVMS_R(0.0);
      for (size_t r = 0; r < LP_M; ++r) e += lp->Binv[p][r] * lp->H[r * lp->n + j];
      if (uvms_fabs(e) > best) {
        best = uvms_fabs(e);
        best_k = (sm == VAR_UPPER) ? km : kp; /* the one carrying the value, if any */
      }
    }
    if (best_k >= LP_NV) {
      ++dependent; /* stays basic at 0; Phase II gives it bounds [0, 0] */
      continue;
    }
    uvms_real_t alpha[LP_M];
    lp_ftran(lp, best_k, alpha);
    lp_pivot(lp, best_k, p, alpha, lp_nonbasic_value(lp, best_k), (uint8_t)VAR_FIXED);
  }
  return dependent;
}

/* x_B = B⁻¹·(w − Σ_{nonbasic at upper} u_k·a_k), afresh (no drift from the updates). */
static void lp_refresh_values(lp_t *lp) {
  uvms_real_t rhs[LP_M], a[LP_M];
  for (size_t r = 0; r < LP_M; ++r) rhs[r] = lp->w[r];
  for (size_t k = 0; k < LP_NS; ++k) {
    if (lp->state[k] != VAR_UPPER) continue;
    lp_column(lp, k, a);
    for (size_t r = 0; r < LP_M; ++r) rhs[r] -= lp->upper * a[r];
  }
  for (size_t i = 0; i < LP_M; ++i) {
    uvms_real_t s = UVMS_R(0.0);
    for (size_t r = 0; r < LP_M; ++r) s += lp->Binv[i][r] * rhs[r];
    lp->xB[i] = s;
  }
}

/* T_j = σ·(T⁺_j − T⁻_j), each part clamped into [0, T_max/σ] (rounding). */
static void lp_extract(const lp_t *lp, uvms_real_t sigma, uvms_real_t T[UVMS_MAX_THRUSTERS]) {
  uvms_real_t x[LP_NS];
  for (size_t k = 0; k < LP_NS; ++k) x[k] = lp_nonbasic_value(lp, k);
  for (size_t i = 0; i < LP_M; ++i) {
    const size_t k = lp->basis[i];
    if (k < LP_NS) x[k] = lp->xB[i];
  }
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    uvms_real_t v[2];
    for (size_t s = 0; s < 2u; ++s) {
      v[s] = x[2u * j + s];
      if (v[s] < UVMS_R(0.0)) v[s] = UVMS_R(0.0);
      if (v[s] > lp->upper) v[s] = lp->upper;
    }
    T[j] = (lp->state[2u * j] == VAR_FIXED) ? UVMS_R(0.0) : sigma * (v[0] - v[1]);
  }
}

/* The result check of alloc_lp.h: finite, within the bounds (slack UVMS_LP_TOL_FEAS, then
   clamped), and H·T = w row by row within UVMS_LP_TOL_RESIDUAL·(σ + Σ_j |H_ij·T_j|). */
static uvms_status_t lp_verify(size_t n, const uvms_real_t *H, const uvms_real_t w[LP_M],
                               uvms_real_t sigma, uvms_real_t limit_N,
                               uvms_real_t T[UVMS_MAX_THRUSTERS]) {
  const uvms_real_t slack_N = limit_N * (UVMS_R(1.0) + UVMS_LP_TOL_FEAS);
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    if (!uvms_isfinite(T[j]) || uvms_fabs(T[j]) > slack_N) return UVMS_ERR_RANGE;
    if (T[j] > limit_N) T[j] = limit_N;
    if (T[j] < -limit_N) T[j] = -limit_N;
  }
  for (size_t r = 0; r < LP_M; ++r) {
    uvms_real_t s = -w[r], mag = sigma;
    for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
      s += H[r * n + j] * T[j];
      mag += uvms_fabs(H[r * n + j] * T[j]);
    }
    if (!(uvms_fabs(s) <= UVMS_LP_TOL_RESIDUAL * mag)) return UVMS_ERR_RANGE;
  }
  return UVMS_OK;
}

/* Arguments and inputs; σ = max_i |w_i|. */
static uvms_status_t lp_check_inputs(size_t n, const uvms_real_t *H, const uvms_real_t *w,
                                     uvms_real_t limit_N, uvms_real_t *sigma) {
  if (H == NULL || w == NULL || n == 0) return UVMS_ERR_ARG;
  if (n > UVMS_MAX_THRUSTERS) return UVMS_ERR_SIZE;
  if (!uvms_all_finite(H, LP_M * n) || !uvms_all_finite(w, LP_M)) return UVMS_ERR_NONFINITE;
  if (!(limit_N > UVMS_R(0.0))) return UVMS_ERR_RANGE;
  *sigma = UVMS_R(0.0);
  for (size_t i = 0; i < LP_M; ++i)
    if (uvms_fabs(w[i]) > *sigma) *sigma = uvms_fabs(w[i]);
  return UVMS_OK;
}

/* Both phases on the set-up problem; info->phase1_iterations and redundant_rows filled. */
static uvms_status_t lp_solve(lp_t *lp, uvms_lp_info_t *info) {
  uvms_status_t st = lp_run_phase(lp);
  if (st != UVMS_OK) return st;
  if (!(lp_infeasibility(lp) <= UVMS_LP_TOL_FEAS)) return UVMS_ERR_RANGE;
  info->redundant_rows = lp_drive_out_artificials(lp); /* ≤ 6 pivots */
  info->phase1_iterations = lp->iterations;
  if (lp->iterations > UVMS_LP_MAX_ITERATIONS) return UVMS_ERR_RANGE;
  lp->phase = 2;
  st = lp_run_phase(lp);
  if (st != UVMS_OK) return st;
  lp_refresh_values(lp);
  return UVMS_OK;
}

uvms_status_t uvms_lp_min_abs_thrust(size_t n,
                                     const uvms_real_t H[UVMS_LP_ROWS * UVMS_MAX_THRUSTERS],
                                     uint32_t usable_mask,
                                     const uvms_real_t wrench_body[UVMS_LP_ROWS],
                                     uvms_real_t thrust_limit_N,
                                     uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                     uvms_lp_info_t *info) {
  uvms_lp_info_t local;
  uvms_lp_info_t *inf = (info != NULL) ? info : &local;
  memset(inf, 0, sizeof *inf);
  zero_thrusts(thrust_N); /* safe output: zero thrust */
  if (thrust_N == NULL) return UVMS_ERR_ARG;
  uvms_real_t sigma = UVMS_R(0.0);
  uvms_status_t st = lp_check_inputs(n, H, wrench_body, thrust_limit_N, &sigma);
  if (st != UVMS_OK) return st;
  if (sigma == UVMS_R(0.0)) return UVMS_OK; /* w = 0: T = 0 is optimal */

  lp_t lp;
  lp_setup(&lp, n, H, usable_mask, wrench_body, sigma, thrust_limit_N);
  st = lp_solve(&lp, inf);
  inf->iterations = lp.iterations;
  uvms_real_t T[UVMS_MAX_THRUSTERS];
  if (st == UVMS_OK) {
    lp_extract(&lp, sigma, T);
    st = lp_verify(n, H, wrench_body, sigma, thrust_limit_N, T);
  }
  if (st != UVMS_OK) return st;
  uvms_real_t objective_N = UVMS_R(0.0);
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    thrust_N[j] = (j < n) ? T[j] : UVMS_R(0.0);
    objective_N += uvms_fabs(thrust_N[j]);
  }
  inf->objective_N = objective_N;
  return UVMS_OK;
}
