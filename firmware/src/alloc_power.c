/* SPDX-License-Identifier: Apache-2.0 */
/* alloc_power.c: minimum-power thrust allocation, least Σ|T_j|^1.5 with the pseudoinverse's
 * wrench within the thrust limit (alloc_power.h, docs/MODEL.md §7.3). A primal active-set
 * Newton method in the null space of the usable thrusters' H (at most 2 dimensions).
 * No allocation, no recursion, no file-scope mutable state; every loop is bounded by
 * UVMS_MAX_THRUSTERS, UVMS_POWER_MAX_NULL_DIM, UVMS_ALLOC_WRENCH_DIM or the iteration and
 * halving caps. */
#include "uvms/alloc_power.h"

#include <string.h>

#include "uvms/linalg.h"

enum { D_MAX = UVMS_POWER_MAX_NULL_DIM, W = UVMS_ALLOC_WRENCH_DIM, NT = UVMS_MAX_THRUSTERS };
_Static_assert(UVMS_POWER_MAX_NULL_DIM == 2, "the step and multiplier solves are 1×1 or 2×2");

/* A basis column whose remaining squared norm is at or below this is not a null direction
   (Π_jj ∈ [0, 1]; a direction of the null space has Π_jj ≥ 1/n_u on some usable j). */
#define BASIS_MIN_NORM_SQ UVMS_R(1e-3)

/* A row of N (thruster j's share of the null directions) at or below this in every entry is
   rounding: thruster j takes no part in any null direction, its thrust is fixed at P_j, and
   its bound must not block a step (a rounding-level slope against a thrust on its bound would
   stop every step at length 0). The projector's entries carry a rounding of ~n·eps. */
#if UVMS_REAL_IS_FLOAT
#define NULL_ROW_TOL UVMS_R(1e-5)
#else
#define NULL_ROW_TOL UVMS_R(1e-11)
#endif

/* Relative rounding of a sum of n = 8 terms in the real type (≈ 8·eps): the line search's
   floor on |φ'| (relative to Σ|φ'_j·v_j|) and on its bracket's width (relative to α). */
#if UVMS_REAL_IS_FLOAT
#define LINE_ROUNDING UVMS_R(1e-6)
#else
#define LINE_ROUNDING UVMS_R(2e-15)
#endif

/* A slope v_j = (N·step)_j at or below this fraction of max|v| is rounding: it cannot carry a
   thrust onto its bound (ratio test). */
#if UVMS_REAL_IS_FLOAT
#define SLOPE_TOL UVMS_R(1e-5)
#else
#define SLOPE_TOL UVMS_R(1e-11)
#endif

/* The problem of one call: P, the null-space basis N (row j = thruster j), the limit. */
typedef struct {
  size_t n;              /* thrusters (clamped to NT) */
  uint32_t usable;       /* usable set */
  size_t d;              /* null-space dimension */
  int limited;           /* 1: some usable thruster has a finite limit_N[j] */
  uvms_real_t limit_N[NT]; /* T_max,j [N] (+inf: none); +inf for j ≥ n */
  uvms_real_t w[NT];     /* cost weights w_j > 0 (1: equal thrusters) [1] */
  uvms_real_t sqrt_floor; /* √δ [√N]: the curvature floor (alloc_power.h) */
  uvms_real_t P[NT];     /* pseudoinverse thrusts, unusable 0 [N] */
  uvms_real_t N[NT][D_MAX]; /* orthonormal null-space basis, unusable rows 0 [1] */
} problem_t;

/* Bounds held active: thruster j at side s (s·T_j = T_max), at most d of them. */
typedef struct {
  size_t count;
  size_t j[D_MAX];
  uvms_real_t s[D_MAX];
} active_t;

static int usable_j(uint32_t mask, size_t j) { return ((mask >> (uint32_t)j) & 1u) != 0u; }

static void zero_thrusts(uvms_real_t *t) {
  if (t == NULL) return;
  for (size_t j = 0; j < NT; ++j) t[j] = UVMS_R(0.0);
}

uvms_real_t uvms_power_cost(size_t n, const uvms_real_t thrust_N[UVMS_MAX_THRUSTERS]) {
  return uvms_power_cost_weighted(n, NULL, thrust_N);
}

uvms_real_t uvms_power_cost_weighted(size_t n, const uvms_real_t weight[UVMS_MAX_THRUSTERS],
                                     const uvms_real_t thrust_N[UVMS_MAX_THRUSTERS]) {
  if (thrust_N == NULL) return UVMS_R(0.0);
  uvms_real_t c = UVMS_R(0.0);
  for (size_t j = 0; j < n && j < NT; ++j) {
    const uvms_real_t a = uvms_fabs(thrust_N[j]);
    const uvms_real_t w = (weight != NULL) ? weight[j] : UVMS_R(1.0);
    c += w * a * uvms_sqrt(a);
  }
  return c;
}

uvms_status_t uvms_power_weights(const uvms_thruster_params_t thruster[UVMS_MAX_THRUSTERS],
                                 size_t n, uvms_real_t weight[UVMS_MAX_THRUSTERS]) {
  if (weight == NULL) return UVMS_ERR_ARG;
  for (size_t j = 0; j < NT; ++j) weight[j] = UVMS_R(1.0);
  if (thruster == NULL) return UVMS_ERR_ARG;
  if (n < 1u || n > NT) return UVMS_ERR_RANGE;
  for (size_t j = 0; j < n; ++j) {
    const uvms_real_t D_m = thruster[j].diameter_m;
    if (!uvms_isfinite(D_m) || !(D_m > UVMS_R(0.0))) {
      for (size_t i = 0; i < NT; ++i) weight[i] = UVMS_R(1.0);
      return UVMS_ERR_RANGE;
    }
    weight[j] = thruster[0].diameter_m / D_m;
  }
  return UVMS_OK;
}

/* v = N·z, the thrust change of a move z in the null space (unusable rows are 0 in N). */
static void null_move(const problem_t *p, const uvms_real_t z[D_MAX], uvms_real_t v[NT]) {
  for (size_t j = 0; j < NT; ++j) {
    uvms_real_t t = UVMS_R(0.0);
    for (size_t k = 0; k < p->d && k < D_MAX; ++k) t += p->N[j][k] * z[k];
    v[j] = t;
  }
}

/* T = P + N·z over the usable thrusters (unusable 0: P and N are 0 there). */
static void thrusts_at(const problem_t *p, const uvms_real_t z[D_MAX], uvms_real_t T[NT]) {
  null_move(p, z, T);
  for (size_t j = 0; j < NT; ++j) T[j] += p->P[j];
}

/* h_j = (u_j; a_j × u_j), column j of H [33–37], from the (validated, normalised) geometry. */
static void config_column(const uvms_thruster_geometry_t *g, size_t j, uvms_real_t h[W]) {
  uvms_v3_copy(g->direction[j], h);
  uvms_v3_cross(g->position_m[j], g->direction[j], h + 3);
}

/* Row i of H⁺ (n × 6 row-major) times h. */
static uvms_real_t pinv_row_dot(const uvms_alloc_t *alloc, size_t i, const uvms_real_t h[W]) {
  const uvms_real_t *row = &alloc->H_pinv[i * W];
  return row[0] * h[0] + row[1] * h[1] + row[2] * h[2] + row[3] * h[3] + row[4] * h[4] +
         row[5] * h[5];
}

/* The null-space basis N: pivoted Gram–Schmidt on the columns Π·e_j = e_j − H⁺·h_j of the
   projector Π = D_u − H⁺·H_u (alloc_power.h), whose diagonal is Π_jj = 1 − (H⁺·h_j)_j. */
static uvms_status_t null_basis(const uvms_alloc_t *alloc, problem_t *p) {
  uvms_real_t h[NT][W];
  uvms_real_t rem[NT]; /* Π_jj minus the squared entries of the columns taken so far */
  for (size_t j = 0; j < NT; ++j) {
    rem[j] = UVMS_R(0.0);
    if (j >= p->n || !usable_j(p->usable, j)) continue;
    config_column(&alloc->geom, j, h[j]);
    rem[j] = UVMS_R(1.0) - pinv_row_dot(alloc, j, h[j]);
  }
  for (size_t k = 0; k < p->d && k < D_MAX; ++k) {
    size_t jp = 0;
    for (size_t j = 1; j < NT; ++j)
      if (rem[j] > rem[jp]) jp = j;
    if (!(rem[jp] > BASIS_MIN_NORM_SQ)) return UVMS_ERR_SINGULAR; /* also NaN */
    uvms_real_t c[NT];
    for (size_t i = 0; i < NT; ++i) {
      const int in = i < p->n && usable_j(p->usable, i);
      c[i] = in ? ((i == jp) ? UVMS_R(1.0) : UVMS_R(0.0)) - pinv_row_dot(alloc, i, h[jp])
                : UVMS_R(0.0);
    }
    for (size_t q = 0; q < k; ++q) { /* orthogonal to the columns taken */
      uvms_real_t dot = UVMS_R(0.0);
      for (size_t i = 0; i < NT; ++i) dot += p->N[i][q] * c[i];
      for (size_t i = 0; i < NT; ++i) c[i] -= dot * p->N[i][q];
    }
    uvms_real_t nsq = UVMS_R(0.0);
    for (size_t i = 0; i < NT; ++i) nsq += c[i] * c[i];
    if (!(nsq > BASIS_MIN_NORM_SQ) || !uvms_isfinite(nsq)) return UVMS_ERR_SINGULAR;
    const uvms_real_t inv = UVMS_R(1.0) / uvms_sqrt(nsq);
    for (size_t i = 0; i < NT; ++i) {
      p->N[i][k] = c[i] * inv;
      rem[i] -= p->N[i][k] * p->N[i][k];
    }
  }
  for (size_t i = 0; i < NT; ++i) { /* rows of thrusters fixed by the wrench: exactly 0 */
    int fixed = 1;
    for (size_t k = 0; k < p->d && k < D_MAX; ++k)
      if (uvms_fabs(p->N[i][k]) > NULL_ROW_TOL) fixed = 0;
    if (fixed)
      for (size_t k = 0; k < D_MAX; ++k) p->N[i][k] = UVMS_R(0.0);
  }
  return UVMS_OK;
}

/* Cost Σ w_j·|T_j|^1.5, its gradient g = Nᵀ·φ'(T) and (floored) Hessian Hs = Nᵀ·diag(φ'')·N
   in z. */
static uvms_real_t cost_grad_hess(const problem_t *p, const uvms_real_t T[NT],
                                  uvms_real_t g[D_MAX], uvms_real_t Hs[D_MAX][D_MAX]) {
  uvms_real_t cost = UVMS_R(0.0);
  for (size_t k = 0; k < D_MAX; ++k) {
    g[k] = UVMS_R(0.0);
    for (size_t l = 0; l < D_MAX; ++l) Hs[k][l] = UVMS_R(0.0);
  }
  for (size_t j = 0; j < p->n && j < NT; ++j) {
    if (!usable_j(p->usable, j)) continue;
    const uvms_real_t a = uvms_fabs(T[j]);
    const uvms_real_t sa = uvms_sqrt(a);
    const uvms_real_t w = p->w[j];
    cost += w * a * sa;
    const uvms_real_t d1 = w * ((T[j] < UVMS_R(0.0)) ? UVMS_R(-1.5) * sa : UVMS_R(1.5) * sa);
    const uvms_real_t d2 = w * UVMS_R(0.75) / ((sa > p->sqrt_floor) ? sa : p->sqrt_floor);
    for (size_t k = 0; k < p->d && k < D_MAX; ++k) {
      g[k] += d1 * p->N[j][k];
      for (size_t l = 0; l < p->d && l < D_MAX; ++l) Hs[k][l] += d2 * p->N[j][k] * p->N[j][l];
    }
  }
  return cost;
}

/* The Newton step in the directions the active bounds leave free. Returns 0 on a Hessian that
   is not positive along them (breakdown). */
static int newton_step(const problem_t *p, const active_t *act, const uvms_real_t g[D_MAX],
                       uvms_real_t Hs[D_MAX][D_MAX], uvms_real_t step[D_MAX]) {
  step[0] = step[1] = UVMS_R(0.0);
  if (act->count >= p->d) return 1; /* a vertex: nothing free */
  if (p->d == 1) {
    if (!(Hs[0][0] > UVMS_R(0.0))) return 0;
    step[0] = -g[0] / Hs[0][0];
    return 1;
  }
  if (act->count == 0) { /* d = 2, free: −Hs⁻¹·g */
    const uvms_real_t det = Hs[0][0] * Hs[1][1] - Hs[0][1] * Hs[1][0];
    if (!(det > UVMS_R(0.0)) || !(Hs[0][0] > UVMS_R(0.0))) return 0;
    step[0] = -(Hs[1][1] * g[0] - Hs[0][1] * g[1]) / det;
    step[1] = -(Hs[0][0] * g[1] - Hs[1][0] * g[0]) / det;
    return 1;
  }
  /* d = 2, one bound active: along its tangent t ⟂ a (a = row j of N). */
  if (act->j[0] >= NT) return 0; /* a corrupted working set: breakdown */
  const size_t ja = act->j[0];
  const uvms_real_t t0 = -p->N[ja][1], t1 = p->N[ja][0];
  const uvms_real_t curv = t0 * (Hs[0][0] * t0 + Hs[0][1] * t1) + t1 * (Hs[1][0] * t0 + Hs[1][1] * t1);
  if (!(curv > UVMS_R(0.0))) return 0;
  const uvms_real_t s = -(t0 * g[0] + t1 * g[1]) / curv;
  step[0] = s * t0;
  step[1] = s * t1;
  return 1;
}

/* At a point where the free directions are optimal: the active bounds' multipliers μ_k from
   g + Σ μ_k·s_k·a_k = 0. Returns the index of the bound to release (the most negative μ below
   −tolerance), or act->count when every μ ≥ −tolerance (KKT holds). */
static size_t bound_to_release(const problem_t *p, const active_t *act, const uvms_real_t g[D_MAX],
                               uvms_real_t g_scale) {
  uvms_real_t mu[D_MAX] = {UVMS_R(0.0), UVMS_R(0.0)};
  uvms_real_t a[D_MAX][D_MAX]; /* a[k] = s_k·(row j_k of N) */
  for (size_t k = 0; k < act->count && k < D_MAX; ++k) {
    const size_t j = act->j[k] < NT ? act->j[k] : 0u;
    for (size_t l = 0; l < D_MAX; ++l) a[k][l] = act->s[k] * p->N[j][l];
  }
  if (act->count == 1) {
    const uvms_real_t aa = a[0][0] * a[0][0] + a[0][1] * a[0][1];
    if (aa > UVMS_R(0.0)) mu[0] = -(g[0] * a[0][0] + g[1] * a[0][1]) / aa;
  } else if (act->count == 2) { /* [a_0 a_1]·μ = −g */
    const uvms_real_t det = a[0][0] * a[1][1] - a[1][0] * a[0][1];
    const uvms_real_t n0 = a[0][0] * a[0][0] + a[0][1] * a[0][1];
    const uvms_real_t n1 = a[1][0] * a[1][0] + a[1][1] * a[1][1];
    if (det * det > SLOPE_TOL * n0 * n1) { /* not (nearly) parallel */
      mu[0] = -(g[0] * a[1][1] - g[1] * a[1][0]) / det;
      mu[1] = -(a[0][0] * g[1] - a[0][1] * g[0]) / det;
    }
  }
  size_t worst = act->count;
  uvms_real_t worst_mu = -uvms_sqrt(UVMS_POWER_TOL_DECREMENT) * g_scale;
  for (size_t k = 0; k < act->count && k < D_MAX; ++k) {
    if (mu[k] < worst_mu) {
      worst_mu = mu[k];
      worst = k;
    }
  }
  return worst;
}

static void release_bound(active_t *act, size_t k) {
  for (size_t q = k; q + 1u < act->count && q + 1u < D_MAX; ++q) {
    act->j[q] = act->j[q + 1u];
    act->s[q] = act->s[q + 1u];
  }
  if (act->count > 0u) act->count -= 1u;
}

static int is_active(const active_t *act, size_t j) {
  for (size_t k = 0; k < act->count && k < D_MAX; ++k)
    if (act->j[k] == j) return 1;
  return 0;
}

/* Largest α ∈ [0, cap] with every inactive bound kept along T + α·v (v = N·step); *block is
   the bound that stops it (j, side), or NT when none does. */
static uvms_real_t ratio_test(const problem_t *p, const active_t *act, const uvms_real_t T[NT],
                              const uvms_real_t v[NT], uvms_real_t cap, size_t *block,
                              uvms_real_t *side) {
  uvms_real_t alpha = cap;
  *block = NT;
  *side = UVMS_R(0.0);
  if (!p->limited) return alpha;
  uvms_real_t v_max = UVMS_R(0.0);
  for (size_t j = 0; j < NT; ++j)
    if (uvms_fabs(v[j]) > v_max) v_max = uvms_fabs(v[j]);
  const uvms_real_t v_tol = SLOPE_TOL * v_max;
  for (size_t j = 0; j < p->n && j < NT; ++j) {
    if (!usable_j(p->usable, j) || is_active(act, j) || !(uvms_fabs(v[j]) > v_tol)) continue;
    const uvms_real_t s = (v[j] > UVMS_R(0.0)) ? UVMS_R(1.0) : UVMS_R(-1.0);
    uvms_real_t room = p->limit_N[j] - s * T[j];
    if (room < UVMS_R(0.0)) room = UVMS_R(0.0);
    const uvms_real_t a = room / uvms_fabs(v[j]);
    if (a < alpha) {
      alpha = a;
      *block = j;
      *side = s;
    }
  }
  return alpha;
}

/* The warm start: the last z if it belongs to this usable set's basis, shrunk towards z = 0
   (P, feasible) until every bound holds. */
static void warm_start(const problem_t *p, const uvms_alloc_t *alloc, const uvms_power_warm_t *warm,
                       uvms_real_t z[D_MAX]) {
  z[0] = z[1] = UVMS_R(0.0);
  if (warm == NULL || warm->basis_id == 0u || warm->basis_id != alloc->pinv_computations) return;
  for (size_t k = 0; k < p->d && k < D_MAX; ++k) z[k] = warm->z[k];
  if (!uvms_isfinite(z[0]) || !uvms_isfinite(z[1])) {
    z[0] = z[1] = UVMS_R(0.0);
    return;
  }
  uvms_real_t v[NT];
  null_move(p, z, v);
  const active_t none = {0u, {0u, 0u}, {UVMS_R(0.0), UVMS_R(0.0)}};
  size_t block;
  uvms_real_t side;
  const uvms_real_t alpha = ratio_test(p, &none, p->P, v, UVMS_R(1.0), &block, &side);
  for (size_t k = 0; k < D_MAX; ++k) z[k] *= alpha;
}

/* φ'(α) and φ''(α) of φ(α) = cost(T + α·v), the cost along a line (curvature floored), and
   the rounding floor of φ': a few eps times Σ_j |φ'_j·v_j| (the sum's terms cancel near the
   minimiser, so its rounding is relative to their magnitudes, not to φ' itself). */
static void line_slope(const problem_t *p, const uvms_real_t T[NT], const uvms_real_t v[NT],
                       uvms_real_t alpha, uvms_real_t *d1, uvms_real_t *d2, uvms_real_t *floor) {
  uvms_real_t s1 = UVMS_R(0.0), s2 = UVMS_R(0.0), sabs = UVMS_R(0.0);
  for (size_t j = 0; j < p->n && j < NT; ++j) {
    if (v[j] == UVMS_R(0.0)) continue; /* unusable and fixed thrusters: N's row is 0 */
    const uvms_real_t t = T[j] + alpha * v[j];
    const uvms_real_t sa = uvms_sqrt(uvms_fabs(t));
    const uvms_real_t term = p->w[j] * ((t < UVMS_R(0.0)) ? -sa : sa) * v[j];
    s1 += term;
    sabs += uvms_fabs(term);
    s2 += p->w[j] * v[j] * v[j] / ((sa > p->sqrt_floor) ? sa : p->sqrt_floor);
  }
  *d1 = UVMS_R(1.5) * s1;
  *d2 = UVMS_R(0.75) * s2;
  *floor = UVMS_R(1.5) * LINE_ROUNDING * sabs;
}

/* Exact line search: the minimiser of the convex φ(α) on [0, a_max] (alloc_power.h). At α = 0
   the slope is −dec and the curvature dec (the Newton step's own model), so Newton's method on
   φ'(α) = 0 starts at α = min(1, a_max): near the optimum one evaluation ends it. The bracket
   [lo, hi] holds φ'(lo) < 0; hi is a_max until a point with φ' ≥ 0 is seen. A point with
   φ' < 0 below an unseen a_max is followed by a_max itself (if φ' < 0 there too, a_max is the
   answer and the bound that stops the step joins the active set); otherwise a Newton point
   outside the bracket, or one that does not halve |φ'|, is replaced by the midpoint. Stops
   when |φ'| ≤ max(UVMS_POWER_TOL_SLOPE·dec, its rounding floor), when the bracket is below
   LINE_ROUNDING·hi, or after UVMS_POWER_MAX_LINE_STEPS evaluations, at lo (where the cost is
   below φ(0); 0 when no evaluation found φ' < 0). */
static uvms_real_t line_search(const problem_t *p, const uvms_real_t T[NT], const uvms_real_t v[NT],
                               uvms_real_t dec, uvms_real_t a_max) {
  uvms_real_t lo = UVMS_R(0.0), hi = a_max, prev = dec;
  int hi_seen = 0;
  uvms_real_t alpha = (a_max < UVMS_R(1.0)) ? a_max : UVMS_R(1.0);
  for (uint32_t k = 0; k < UVMS_POWER_MAX_LINE_STEPS; ++k) {
    uvms_real_t d1, d2, floor;
    line_slope(p, T, v, alpha, &d1, &d2, &floor);
    const uvms_real_t tol = UVMS_POWER_TOL_SLOPE * dec;
    if (uvms_fabs(d1) <= ((tol > floor) ? tol : floor)) return alpha;
    if (d1 < UVMS_R(0.0)) {
      if (alpha >= a_max) return a_max;
      lo = alpha;
    } else {
      hi = alpha;
      hi_seen = 1;
    }
    if (hi - lo <= LINE_ROUNDING * hi) return lo;
    uvms_real_t next = (d2 > UVMS_R(0.0)) ? alpha - d1 / d2 : lo - UVMS_R(1.0);
    if (!hi_seen && !(next < hi)) next = hi; /* try the bound itself */
    else if (!(next > lo && next < hi) || uvms_fabs(d1) > UVMS_R(0.5) * prev)
      next = UVMS_R(0.5) * (lo + hi);
    prev = uvms_fabs(d1);
    alpha = next;
  }
  return lo;
}

/* Validate the arguments and fill P and the limit; thrust_N is zeroed first. */
static uvms_status_t set_up(const uvms_alloc_t *alloc, const uvms_real_t *thrust_limit_N,
                            const uvms_real_t *weight, const uvms_real_t *thrust_pinv_N,
                            problem_t *p, uvms_real_t *p_max) {
  if (!alloc->initialised || !alloc->ready || alloc->rank > W) return UVMS_ERR_STATE;
  memset(p, 0, sizeof *p);
  p->n = (alloc->geom.num_thrusters < NT) ? alloc->geom.num_thrusters : NT;
  for (size_t j = 0; j < NT; ++j) {
    p->limit_N[j] = (uvms_real_t)INFINITY;
    p->w[j] = UVMS_R(1.0);
    if (j >= p->n) continue;
    if (!(thrust_limit_N[j] > UVMS_R(0.0))) return UVMS_ERR_RANGE;
    p->limit_N[j] = thrust_limit_N[j];
    if (weight == NULL) continue;
    if (!uvms_isfinite(weight[j])) return UVMS_ERR_NONFINITE;
    if (!(weight[j] > UVMS_R(0.0))) return UVMS_ERR_RANGE;
    p->w[j] = weight[j];
  }
  p->usable = alloc->usable_mask;
  *p_max = UVMS_R(0.0);
  size_t n_usable = 0;
  for (size_t j = 0; j < p->n && j < NT; ++j) {
    if (!usable_j(p->usable, j)) continue;
    ++n_usable;
    if (!uvms_isfinite(thrust_pinv_N[j])) return UVMS_ERR_NONFINITE;
    const uvms_real_t a = uvms_fabs(thrust_pinv_N[j]);
    if (uvms_isfinite(p->limit_N[j])) {
      p->limited = 1;
      if (a > p->limit_N[j] * (UVMS_R(1.0) + UVMS_POWER_TOL_BOUND)) return UVMS_ERR_RANGE;
    }
    p->P[j] = thrust_pinv_N[j];
    if (a > *p_max) *p_max = a;
  }
  p->d = (n_usable > (size_t)alloc->rank) ? n_usable - (size_t)alloc->rank : 0u;
  p->sqrt_floor = uvms_sqrt(UVMS_POWER_CURVATURE_FLOOR * *p_max);
  return UVMS_OK;
}

/* The iteration (alloc_power.h) from z; info gets the counts. Returns UVMS_OK (converged or
   not) or UVMS_ERR_SINGULAR. */
static uvms_status_t iterate(const problem_t *p, uvms_real_t z[D_MAX], uvms_real_t g_scale,
                             uvms_power_info_t *info) {
  active_t act = {0u, {0u, 0u}, {UVMS_R(0.0), UVMS_R(0.0)}};
  uvms_real_t T[NT], g[D_MAX], Hs[D_MAX][D_MAX], cost = UVMS_R(0.0);
  int at_z = 0; /* T, cost, g, Hs are those of the current z (a release or a null step keeps z) */
  for (uint32_t it = 0; it < UVMS_POWER_MAX_ITERATIONS; ++it) {
    uvms_real_t step[D_MAX];
    if (!at_z) {
      thrusts_at(p, z, T);
      cost = cost_grad_hess(p, T, g, Hs);
      if (!uvms_isfinite(cost)) return UVMS_ERR_SINGULAR;
      at_z = 1;
    }
    if (!newton_step(p, &act, g, Hs, step)) return UVMS_ERR_SINGULAR;
    const uvms_real_t dec = -(g[0] * step[0] + g[1] * step[1]);
    info->iterations = it + 1u;
    info->active_bounds = (uint32_t)act.count;
    if (!(dec > UVMS_POWER_TOL_DECREMENT * cost)) {
      const size_t k = bound_to_release(p, &act, g, g_scale);
      if (k >= act.count) {
        info->converged = 1;
        return UVMS_OK;
      }
      release_bound(&act, k);
      continue;
    }
    uvms_real_t v[NT];
    null_move(p, step, v);
    size_t block;
    uvms_real_t side;
    const uvms_real_t alpha_max =
        ratio_test(p, &act, T, v, UVMS_POWER_MAX_STEP, &block, &side);
    const uvms_real_t alpha = line_search(p, T, v, dec, alpha_max);
    if (alpha == UVMS_R(0.0) && !(alpha_max == UVMS_R(0.0) && block < NT)) {
      return UVMS_OK; /* no progress along the step: stop here (info->converged = 0) */
    }
    z[0] += alpha * step[0];
    z[1] += alpha * step[1];
    at_z = (alpha == UVMS_R(0.0));
    if (alpha == alpha_max && block < NT && act.count < p->d && act.count < D_MAX) {
      act.j[act.count] = block;
      act.s[act.count] = side;
      act.count += 1u;
    }
    info->active_bounds = (uint32_t)act.count;
  }
  return UVMS_OK; /* iterations ran out: the last iterate (info->converged = 0) */
}

/* P restricted to the usable thrusters: the fallback output. */
static void write_fallback(const problem_t *p, uvms_real_t thrust_N[NT]) {
  for (size_t j = 0; j < NT; ++j) thrust_N[j] = p->P[j];
}

uvms_status_t uvms_alloc_min_power(const uvms_alloc_t *alloc, uvms_real_t thrust_limit_N,
                                   const uvms_real_t thrust_pinv_N[UVMS_MAX_THRUSTERS],
                                   uvms_power_warm_t *warm,
                                   uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                   uvms_power_info_t *info) {
  uvms_real_t limits_N[NT];
  for (size_t j = 0; j < NT; ++j) limits_N[j] = thrust_limit_N;
  return uvms_alloc_min_power_each(alloc, limits_N, NULL, thrust_pinv_N, warm, thrust_N, info);
}

uvms_status_t uvms_alloc_min_power_each(const uvms_alloc_t *alloc,
                                        const uvms_real_t thrust_limit_N[UVMS_MAX_THRUSTERS],
                                        const uvms_real_t weight[UVMS_MAX_THRUSTERS],
                                        const uvms_real_t thrust_pinv_N[UVMS_MAX_THRUSTERS],
                                        uvms_power_warm_t *warm,
                                        uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                        uvms_power_info_t *info) {
  uvms_power_info_t local;
  uvms_power_info_t *inf = (info != NULL) ? info : &local;
  memset(inf, 0, sizeof *inf);
  if (thrust_N != NULL && thrust_N == thrust_pinv_N) { /* T would overwrite P as it is read */
    if (warm != NULL) memset(warm, 0, sizeof *warm);
    zero_thrusts(thrust_N);
    return UVMS_ERR_ARG;
  }
  zero_thrusts(thrust_N);
  uvms_power_warm_t prev = {{UVMS_R(0.0), UVMS_R(0.0)}, 0u};
  if (warm != NULL) {
    prev = *warm;
    memset(warm, 0, sizeof *warm);
  }
  if (alloc == NULL || thrust_limit_N == NULL || thrust_pinv_N == NULL || thrust_N == NULL)
    return UVMS_ERR_ARG;
  problem_t p;
  uvms_real_t p_max;
  uvms_status_t st = set_up(alloc, thrust_limit_N, weight, thrust_pinv_N, &p, &p_max);
  if (st != UVMS_OK) return st;
  inf->null_dim = (uint32_t)p.d;
  inf->cost_pinv = uvms_power_cost_weighted(p.n, p.w, p.P);
  if (p.d > (size_t)D_MAX) {
    write_fallback(&p, thrust_N);
    return UVMS_ERR_SIZE;
  }
  uvms_real_t z[D_MAX] = {UVMS_R(0.0), UVMS_R(0.0)};
  if (p.d > 0u && p_max > UVMS_R(0.0)) {
    st = null_basis(alloc, &p);
    if (st == UVMS_OK) {
      warm_start(&p, alloc, &prev, z);
      st = iterate(&p, z, uvms_sqrt(p_max), inf);
    }
    if (st != UVMS_OK) {
      memset(inf, 0, sizeof *inf);
      inf->null_dim = (uint32_t)p.d;
      inf->cost_pinv = uvms_power_cost_weighted(p.n, p.w, p.P);
      write_fallback(&p, thrust_N);
      return UVMS_ERR_SINGULAR;
    }
  } else {
    inf->converged = 1; /* unique (d = 0) or zero (P = 0): T = P */
  }
  uvms_real_t T[NT];
  thrusts_at(&p, z, T);
  for (size_t j = 0; j < NT; ++j) {
    if (T[j] > p.limit_N[j]) T[j] = p.limit_N[j];
    if (T[j] < -p.limit_N[j]) T[j] = -p.limit_N[j];
    if (!uvms_isfinite(T[j])) {
      write_fallback(&p, thrust_N);
      inf->converged = 0;
      return UVMS_ERR_SINGULAR;
    }
  }
  inf->cost = uvms_power_cost_weighted(p.n, p.w, T);
  if (!(inf->cost < inf->cost_pinv)) { /* P was optimal already (within rounding): keep it */
    for (size_t j = 0; j < NT; ++j) T[j] = p.P[j];
    z[0] = z[1] = UVMS_R(0.0);
    inf->cost = inf->cost_pinv;
  }
  for (size_t j = 0; j < NT; ++j) thrust_N[j] = T[j];
  if (warm != NULL) {
    warm->z[0] = z[0];
    warm->z[1] = z[1];
    warm->basis_id = alloc->pinv_computations;
  }
  return UVMS_OK;
}
