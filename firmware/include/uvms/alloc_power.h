/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file alloc_power.h
 * @brief Minimum-power thrust allocation: the least Σ_j |T_j|^1.5 that delivers the
 *        pseudoinverse's wrench within the thrust limit (docs/MODEL.md §7.3), in fixed memory
 *        with a bounded iteration count and a warm start from the last tick.
 *
 * Cost. A propeller at bollard pull delivers |T| ∝ ω² and absorbs shaft power ∝ ω³ ∝ |T|^1.5,
 * so Σ|T_j|^1.5 is the hydrodynamic power of the thrusters up to one constant when they are
 * alike. Propellers of different diameters D_j (thruster types) need |T_j|^1.5/√(2ρ·A_d,j),
 * A_d,j = πD_j²/4, at least (momentum theory): uvms_alloc_min_power_each then weighs thruster
 * j by w_j = D_1/D_j (uvms_power_weights; the controller passes these), and the cost is
 * Σ w_j·|T_j|^1.5; the
 * statements below hold for any weights w_j > 0. The pseudoinverse [38] minimises Σ T_j²
 * instead. |t|^1.5 is strictly convex (its derivative 1.5·sign(t)·√|t| is
 * strictly increasing), so the problem
 *
 *     minimise Σ_{j usable} |T_j|^1.5   subject to   H_u·T = H_u·P,   |T_j| ≤ T_max,
 *                                                     T_j = 0 for the unusable thrusters
 *
 * has exactly one solution T*, and T* is a continuous function of the wrench (a strictly
 * convex cost over a feasible set that moves continuously). P is the pseudoinverse thrust
 * after the thrust limit (allocation.h: uvms_alloc_step, uvms_alloc_saturate), so rank loss,
 * attitude-first saturation and the delivered wrench are those of the pseudoinverse; P is
 * feasible, so T* exists and Σ|T*|^1.5 ≤ Σ|P|^1.5.
 *
 * Null space. Every T with H_u·T = H_u·P is T = P + N·z, where the d columns of N are an
 * orthonormal basis of the null space of H_u within the usable thrusters, d = n_u − rank
 * (2 for the paper's eight thrusters, 1 with one of them out at rank 6). N comes from the
 * projector Π = D_u − H⁺·H_u (D_u: 1 on the usable diagonal), whose column j is Π·e_j with
 * |Π·e_j|² = Π_jj: the column with the largest Π_jj, normalised, then the column with the
 * largest remaining diagonal Π_jj − N_j1², orthogonalised and normalised (a pivoted
 * Gram–Schmidt of Π's columns; deterministic for a given usable set, so z carries over from
 * one tick to the next). N is rebuilt each call from H⁺ and the geometry (≈ 200
 * multiply-adds), not stored.
 *
 * Method: a primal active-set Newton method in z (at most UVMS_POWER_MAX_NULL_DIM = 2
 * dimensions):
 *   - gradient g = Nᵀ·φ'(T), Hessian Nᵀ·diag(φ''(T))·N with φ'(t) = 1.5·sign(t)·√|t| and
 *     φ''(t) = 0.75/√max(|t|, δ) (δ = UVMS_POWER_CURVATURE_FLOOR · max|P|: the true curvature
 *     is infinite at t = 0; any positive definite matrix gives a descent direction);
 *   - working set: the thrust bounds held active (at most d of them); the Newton step is taken
 *     in the directions they leave free;
 *   - step length: an exact line search along the step, up to the first inactive bound (or
 *     UVMS_POWER_MAX_STEP Newton steps): the cost along a line is convex, so its slope is
 *     increasing and its zero is found by Newton's method safeguarded by bisection (at most
 *     UVMS_POWER_MAX_LINE_STEPS slope evaluations). A plain Newton step would overshoot across
 *     T_j = 0, where the curvature of |t|^1.5 is infinite, and oscillate about an optimum with
 *     a thrust near zero; the line search lands on it. A step stopped by a bound adds it to
 *     the working set;
 *   - optimality: when the Newton decrement −gᵀ·step ≤ UVMS_POWER_TOL_DECREMENT·cost, the
 *     bounds' multipliers are checked (KKT); a bound with a negative multiplier is released and
 *     the iteration goes on, else the result is optimal (info.converged = 1);
 *   - warm start: z of the last result (uvms_power_warm_t), shrunk towards 0 (P) until every
 *     bound holds if the new P makes it infeasible; a new usable set (H⁺ recomputed) starts at
 *     z = 0.
 * Every iterate is feasible, and from the (warm) start on the cost never increases; a result
 * costlier than P (a warm start far from this tick's optimum, or P optimal to rounding) is
 * replaced by P itself, so the result is never costlier than P. At most
 * UVMS_POWER_MAX_ITERATIONS iterations (Newton steps and releases); when they run out, or a
 * line search makes no progress, the last iterate is returned with info.converged = 0
 * (status UVMS_OK; the next tick's warm start continues from it).
 *
 * Fallback. A usable set with more than UVMS_POWER_MAX_NULL_DIM null directions (a layout of
 * more than rank + 2 thrusters), or a numerical breakdown, returns P itself with an error
 * status (the controller flags ALLOC_FALLBACK and uses P).
 *
 * Cost per call: the basis ≈ 200 multiply-adds and two square roots; each iteration n square
 * roots and ≈ 60 multiply-adds, plus n square roots and ≈ 3·n multiply-adds per slope
 * evaluation of its line search. No
 * allocation, no recursion, every loop bounded by a compile-time constant.
 */
#ifndef UVMS_ALLOC_POWER_H
#define UVMS_ALLOC_POWER_H

#include "uvms/allocation.h"
#include "uvms/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Most null-space directions the solver handles (d = n_u − rank; 2 for the paper's layout). */
#define UVMS_POWER_MAX_NULL_DIM 2

/** Most iterations (Newton steps and bound releases) of one call. */
#define UVMS_POWER_MAX_ITERATIONS 16u

/** Most evaluations of the cost's slope in one exact line search. */
#define UVMS_POWER_MAX_LINE_STEPS 24u

/** Longest step searched, in Newton steps (the line search's range when no bound is nearer). */
#define UVMS_POWER_MAX_STEP UVMS_R(4.0)

/**
 * Tolerances. UVMS_POWER_TOL_DECREMENT: the Newton decrement −gᵀ·step, relative to the cost, at
 * which an iterate counts as optimal. Near T* the decrement is ≈ ¾·Σ (ΔT_j)²/√|T_j|, i.e. about
 * (ΔT/T)² relative to the cost: 1e-12 in double (thrusts good to ~1e-6 relative) and 1e-9 in
 * float (~3e-5; the float cost and slope carry a relative rounding of ~n·6e-8).
 * UVMS_POWER_TOL_SLOPE: the line search stops where the slope along the line is below this
 * fraction of its value at the start (or below the slope's own rounding, a few eps times the
 * magnitudes of its terms). UVMS_POWER_CURVATURE_FLOOR: δ above, relative to
 * max|P_j|. UVMS_POWER_TOL_BOUND: a usable |P_j| above T_max by more than this fraction is
 * refused (P must be the limited allocation).
 */
#if UVMS_REAL_IS_FLOAT
#define UVMS_POWER_TOL_DECREMENT UVMS_R(1e-9)
#define UVMS_POWER_TOL_SLOPE UVMS_R(1e-4)
#define UVMS_POWER_CURVATURE_FLOOR UVMS_R(1e-6)
#define UVMS_POWER_TOL_BOUND UVMS_R(1e-6)
#else
#define UVMS_POWER_TOL_DECREMENT UVMS_R(1e-12)
#define UVMS_POWER_TOL_SLOPE UVMS_R(1e-8)
#define UVMS_POWER_CURVATURE_FLOOR UVMS_R(1e-9)
#define UVMS_POWER_TOL_BOUND UVMS_R(1e-12)
#endif

/** Warm start carried from one call to the next (caller-owned; zero it to start cold). */
typedef struct {
  uvms_real_t z[UVMS_POWER_MAX_NULL_DIM]; /**< null-space coordinates of the last result [N] */
  uint32_t basis_id; /**< the allocation's pinv_computations when z was stored; 0: none */
} uvms_power_warm_t;

/** What one call did. */
typedef struct {
  uint32_t iterations;    /**< Newton steps and bound releases */
  uint32_t null_dim;      /**< d, null-space directions of the usable set */
  uint32_t active_bounds; /**< thrust bounds active at the result */
  int converged;          /**< 1: optimal within the tolerances; 0: iterations ran out */
  uvms_real_t cost_pinv;  /**< Σ|P_j|^1.5 of the pseudoinverse thrusts [N^1.5] */
  uvms_real_t cost;       /**< Σ|T_j|^1.5 of the result [N^1.5] */
} uvms_power_info_t;

/**
 * @brief Σ_{j < n} |T_j|^1.5, the cost the minimum-power allocation minimises [N^1.5].
 * @param[in] n        thrusters; clamped to UVMS_MAX_THRUSTERS
 * @param[in] thrust_N T [N], [UVMS_MAX_THRUSTERS]
 * @return the cost, or 0 if thrust_N is NULL (NaN propagates)
 */
uvms_real_t uvms_power_cost(size_t n, const uvms_real_t thrust_N[UVMS_MAX_THRUSTERS]);

/**
 * @brief Σ_{j < n} w_j·|T_j|^1.5, the cost uvms_alloc_min_power_each minimises [N^1.5].
 * @param[in] n        thrusters; clamped to UVMS_MAX_THRUSTERS
 * @param[in] weight   w_j [1], [UVMS_MAX_THRUSTERS], or NULL (every w_j = 1: uvms_power_cost)
 * @param[in] thrust_N T [N], [UVMS_MAX_THRUSTERS]
 * @return the cost, or 0 if thrust_N is NULL (NaN propagates)
 */
uvms_real_t uvms_power_cost_weighted(size_t n, const uvms_real_t weight[UVMS_MAX_THRUSTERS],
                                     const uvms_real_t thrust_N[UVMS_MAX_THRUSTERS]);

/**
 * @brief The least-Σ|T|^1.5 thrusts delivering the wrench of the pseudoinverse thrusts P
 *        within |T_j| ≤ thrust_limit_N (method above).
 * @param[in]     alloc          ready instance (allocation.h): geometry, usable set, H⁺
 * @param[in]     thrust_limit_N T_max > 0 [N], or +inf (no limit)
 * @param[in]     thrust_pinv_N  P [N], [UVMS_MAX_THRUSTERS], finite, |P_j| ≤ T_max (after
 *                               uvms_alloc_saturate); entries of unusable thrusters are ignored
 * @param[in,out] warm           warm start, or NULL (cold: z = 0); on UVMS_OK it holds this
 *                               result's z, on every error it is cleared (basis_id = 0)
 * @param[out]    thrust_N       T [N], [UVMS_MAX_THRUSTERS]; unusable and j ≥ n exactly 0;
 *                               must not be thrust_pinv_N
 * @param[out]    info           what the call did, or NULL; zeroed on entry
 * @retval UVMS_OK            thrust_N = T (converged, or the best iterate: info->converged)
 * @retval UVMS_ERR_ARG       alloc, thrust_pinv_N or thrust_N is NULL, or thrust_N is
 *                            thrust_pinv_N; writes: thrust_N = 0 (if non-NULL), warm cleared
 * @retval UVMS_ERR_STATE     alloc not initialised or not ready, or its rank above 6 (a
 *                            corrupted instance); writes: thrust_N = 0, warm cleared
 * @retval UVMS_ERR_RANGE     thrust_limit_N not > 0 (or NaN), or a usable |P_j| above
 *                            T_max·(1 + UVMS_POWER_TOL_BOUND); writes: thrust_N = 0, warm
 *                            cleared
 * @retval UVMS_ERR_NONFINITE a usable P_j is NaN or infinite; writes: thrust_N = 0, warm
 *                            cleared
 * @retval UVMS_ERR_SIZE      the usable set has more than UVMS_POWER_MAX_NULL_DIM null
 *                            directions; writes: thrust_N = P (unusable 0), the fallback, warm
 *                            cleared
 * @retval UVMS_ERR_SINGULAR  numerical breakdown (a basis column or a Hessian that is not
 *                            positive, a non-finite iterate); writes: thrust_N = P (unusable
 *                            0), the fallback, warm cleared
 */
uvms_status_t uvms_alloc_min_power(const uvms_alloc_t *alloc, uvms_real_t thrust_limit_N,
                                   const uvms_real_t thrust_pinv_N[UVMS_MAX_THRUSTERS],
                                   uvms_power_warm_t *warm,
                                   uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                   uvms_power_info_t *info);

/**
 * @brief The cost weights of thrusters whose propellers differ: w_j = D_1/D_j (the actuator-disk
 *        power |T|^1.5/√(2ρ·πD²/4) ∝ |T|^1.5/D, relative to thruster 1's), exactly 1 for a
 *        thruster like thruster 1; w_j = 1 for j ≥ n.
 * @param[in]  thruster [UVMS_MAX_THRUSTERS] parameter sets (only diameter_m of j < n is read)
 * @param[in]  n        thrusters, 1..UVMS_MAX_THRUSTERS
 * @param[out] weight   [UVMS_MAX_THRUSTERS] w_j [1]; all 1 on error
 * @retval UVMS_OK        weight written
 * @retval UVMS_ERR_ARG   thruster or weight is NULL; writes: weight all 1 (if non-NULL)
 * @retval UVMS_ERR_RANGE n is 0 or above UVMS_MAX_THRUSTERS, or a diameter D_j (j < n) is not
 *                        finite and > 0; writes: weight all 1
 */
uvms_status_t uvms_power_weights(const uvms_thruster_params_t thruster[UVMS_MAX_THRUSTERS],
                                 size_t n, uvms_real_t weight[UVMS_MAX_THRUSTERS]);

/**
 * @brief uvms_alloc_min_power with a limit and a cost weight per thruster: the least
 *        Σ w_j·|T_j|^1.5 with |T_j| ≤ thrust_limit_N[j].
 * @param[in] thrust_limit_N T_max,j > 0 [N] or +inf (none), [UVMS_MAX_THRUSTERS]; entries
 *                           j ≥ n are ignored; a usable |P_j| above T_max,j·(1 +
 *                           UVMS_POWER_TOL_BOUND) is refused
 * @param[in] weight         w_j > 0 [1], [UVMS_MAX_THRUSTERS] (entries j ≥ n ignored), or
 *                           NULL (every w_j = 1); info's costs are weighted by them
 * Other parameters as uvms_alloc_min_power, whose calls with a limit T are this function's
 * with every entry T.
 * @retval UVMS_OK            thrust_N = T (converged, or the best iterate: info->converged)
 * @retval UVMS_ERR_ARG       alloc, thrust_limit_N, thrust_pinv_N or thrust_N is NULL, or
 *                            thrust_N is thrust_pinv_N; writes: thrust_N = 0 (if non-NULL),
 *                            warm cleared
 * @retval UVMS_ERR_STATE     alloc not initialised or not ready, or its rank above 6; writes:
 *                            thrust_N = 0, warm cleared
 * @retval UVMS_ERR_RANGE     a limit or weight j < n not > 0 (a limit NaN), or a usable |P_j|
 *                            above T_max,j·(1 + UVMS_POWER_TOL_BOUND); writes: thrust_N = 0,
 *                            warm cleared
 * @retval UVMS_ERR_NONFINITE a weight j < n or a usable P_j is NaN or infinite; writes:
 *                            thrust_N = 0, warm cleared
 * @retval UVMS_ERR_SIZE      more than UVMS_POWER_MAX_NULL_DIM null directions; writes:
 *                            thrust_N = P (unusable 0), warm cleared
 * @retval UVMS_ERR_SINGULAR  numerical breakdown; writes: thrust_N = P (unusable 0), warm
 *                            cleared
 */
uvms_status_t uvms_alloc_min_power_each(const uvms_alloc_t *alloc,
                                        const uvms_real_t thrust_limit_N[UVMS_MAX_THRUSTERS],
                                        const uvms_real_t weight[UVMS_MAX_THRUSTERS],
                                        const uvms_real_t thrust_pinv_N[UVMS_MAX_THRUSTERS],
                                        uvms_power_warm_t *warm,
                                        uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                        uvms_power_info_t *info);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_ALLOC_POWER_H */
