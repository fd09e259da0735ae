/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file alloc_lp.h
 * @brief Least-Σ|T| thrust allocation: an exact small linear program (docs/MODEL.md §7.3),
 *        solved in fixed memory with a bounded iteration count.
 *
 * With the paper's motors the electrical power of thruster j is almost proportional to |T_j|
 * (friction-dominated, ω² ∝ |T|), so the energy-optimal allocation of a body wrench w is
 *
 *     minimise Σ_j |T_j|   subject to   H·T = w,   |T_j| ≤ T_max (usable j),   T_j = 0 (others)
 *
 * (H: the 6 × n configuration matrix of allocation.h, columns h_j = (u_j; a_j × u_j)). The
 * pseudoinverse [38] minimises Σ T_j² instead, which spreads thrust over every thruster.
 *
 * Formulation. T_j = T⁺_j − T⁻_j with 0 ≤ T⁺_j, T⁻_j ≤ T_max for the usable thrusters (columns
 * h_j and −h_j, cost 1 each); the unusable ones' variables are fixed at 0 and never priced.
 * At most 2·UVMS_MAX_THRUSTERS = 16 structural variables, 6 equality rows, plus one artificial
 * variable per row (22 in all). At an optimum T⁺_j·T⁻_j = 0, so Σ(T⁺ + T⁻) = Σ|T|.
 *
 * Method: bounded-variable revised primal simplex with an explicit 6 × 6 basis inverse B⁻¹
 * (no tableau; per iteration: duals y = c_Bᵀ·B⁻¹, reduced costs d = c − y·a for the n
 * thrusters (the T⁻ column is the negative of the T⁺ one: one dot product serves both), the
 * entering column B⁻¹·a, the ratio test over the basic variables' two bounds and the
 * entering variable's own range (a bound flip when that is the shortest step), and a
 * product-form update of B⁻¹).
 *   - Scaling: w and T_max are divided by σ = max_i |w_i|, so every right-hand side is in
 *     [−1, 1] and the tolerances below are relative to the wrench. w = 0 returns T = 0 at once
 *     (the optimum: Σ|T| ≥ 0).
 *   - Phase I: artificial basis (artificial i has column sign(w_i)·e_i, value |w_i|), costs 1
 *     on the artificials. An artificial that leaves the basis never re-enters. At the Phase I
 *     optimum the sum of the artificials must be ≤ UVMS_LP_TOL_FEAS, else the wrench is not
 *     producible within the bounds (UVMS_ERR_RANGE).
 *   - Artificials still basic at the end of Phase I (at level ≤ UVMS_LP_TOL_FEAS: rounding)
 *     are set to 0 and pivoted out on the structural column with the largest entry in their
 *     row (a degenerate pivot). If every such entry is ≤ UVMS_LP_TOL_PIVOT, the row is a
 *     linear combination of the others: the usable thrusters have rank < 6 (thruster faults).
 *     The artificial then stays basic with bounds [0, 0] (it never moves), so a rank-deficient
 *     set serves exactly the wrench directions it spans (the caller passes a w in its range).
 *   - Phase II: costs 1 on the structural variables, 0 on the artificials.
 *   - Pricing and anti-cycling: Dantzig's rule (largest reduced-cost violation) as long as
 *     every step is non-degenerate (step length > UVMS_LP_TOL_FEAS), Bland's rule (entering:
 *     the eligible variable of smallest index; leaving: among the tied ratios the basic
 *     variable of smallest index) from the first degenerate step to the end of that phase.
 *     Every Dantzig step strictly lowers the objective, so no basis (with its bound states)
 *     repeats before the switch, and Bland's rule cannot cycle (Bland 1977, also for bounded
 *     variables): each phase terminates in exact arithmetic.
 *   - Result check: T finite, |T_j| ≤ T_max·(1 + UVMS_LP_TOL_FEAS) (then clamped to ±T_max),
 *     unusable T_j exactly 0 and every row residual |(H·T − w)_i| ≤ UVMS_LP_TOL_RESIDUAL·(σ +
 *     Σ_j |H_ij·T_j|); anything else is reported as a failure, never returned as a result.
 *
 * Iteration bound. The simplex has no useful polynomial worst case; in exact arithmetic the
 * number of bases, C(22, 6) = 74,613, bounds it. The firmware caps the iterations (basis
 * changes, bound flips and the pivots that drive artificials out, both phases together) at
 * UVMS_LP_MAX_ITERATIONS and reports UVMS_ERR_RANGE beyond it: the caller then keeps its
 * feasible fallback (allocation.h, uvms_alloc_min_abs_thrust: the pseudoinverse thrusts). A
 * feasible 6-row problem needs at least rank(H_u) pivots (one per row to leave the artificial
 * basis). Measured, paper layout, double and float alike: 600 random wrenches with one or two
 * thrusters out (rank 5 among them) and saturated targets (tests/firmware/test_alloc_lp.cpp):
 * median 7, 90th percentile 10, worst 13; the paper's runs (60 s of cases IV and VII, every
 * tick): median 6, worst 11 (Phase I takes 6 of them: the optimum's basis is usually found
 * there). The cap leaves a factor of about 5 over the worst case seen.
 *
 * Cost: per iteration ≈ 160 multiply-adds and up to 7 divisions (y: 36, reduced costs 6·n,
 * B⁻¹·a: 36, B⁻¹ update: 36, ratio test), ≈ 1,300 Cortex-M4F instructions; a solve of the
 * paper's runs ≈ 10.4 k instructions (median), 15.4 k (worst) (QEMU icount, float, -O3).
 * No allocation, no recursion, every loop bounded by a compile-time constant (the rows,
 * UVMS_MAX_THRUSTERS, or UVMS_LP_MAX_ITERATIONS). Working memory: one local struct of 55 reals
 * (B⁻¹, basic values, scaled wrench) and 28 bytes of basis and bound states, on the caller's
 * stack (+660 B of stack peak per controller tick on the Cortex-M4F). Each solve starts cold
 * (no state is kept between ticks).
 */
#ifndef UVMS_ALLOC_LP_H
#define UVMS_ALLOC_LP_H

#include "uvms/thruster.h" /* UVMS_MAX_THRUSTERS */
#include "uvms/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Equality rows: the wrench dimension (force x, y, z; moment x, y, z), = UVMS_ALLOC_WRENCH_DIM. */
#define UVMS_LP_ROWS 6

/** Most simplex iterations of one solve (both phases; see the file comment for the measured
 *  median and worst case). */
#define UVMS_LP_MAX_ITERATIONS 64u

/**
 * Tolerances, all in the scaled problem (right-hand sides in [−1, 1], H's entries O(1): unit
 * directions and lever arms of the order of a metre), so they are relative to the wrench.
 *
 * UVMS_LP_TOL_PIVOT: an entry of B⁻¹·a at or below this in magnitude counts as zero (not a
 * pivot in the ratio test, not a column that can drive an artificial out). B⁻¹·a is computed
 * with a relative error of about cond(B)·eps (cond(B) ≤ ~100 for the bases of a sensible
 * thruster layout: float 6e-6, double 1e-14), so the threshold sits above that noise and far
 * below the entries that matter (O(0.1–1) for the paper's layout).
 *
 * UVMS_LP_TOL_OPT: a reduced cost must violate optimality by more than this to enter. Costs
 * are 1 and the duals O(1), so the rounding of d is a few eps; stopping at a violation below
 * this changes the optimum by at most this fraction of a step (a relative 1e-5 in float,
 * 1e-9 in double).
 *
 * UVMS_LP_TOL_FEAS: Phase I residual accepted as feasible, the bound slack of the result, the
 * step length below which a step counts as degenerate and the tie width of the ratio test.
 * The caller's w is H·P rounded in the real type: its component outside the range of a
 * rank-deficient H_u is ≈ n·eps·|H||P|/σ (≤ ~1e-6 in float, 1e-15 in double), which Phase I
 * cannot remove; the tolerance is well above that and far below any physically meaningful
 * wrench error.
 *
 * UVMS_LP_TOL_RESIDUAL: accepted |(H·T − w)_i| relative to σ + Σ_j |H_ij·T_j| in the result
 * check (a gross-error detector: a correct solve lands near eps times the number of pivots).
 */
#if UVMS_REAL_IS_FLOAT
#define UVMS_LP_TOL_PIVOT UVMS_R(1e-5)
#define UVMS_LP_TOL_OPT UVMS_R(1e-5)
#define UVMS_LP_TOL_FEAS UVMS_R(1e-5)
#define UVMS_LP_TOL_RESIDUAL UVMS_R(1e-4)
#else
#define UVMS_LP_TOL_PIVOT UVMS_R(1e-9)
#define UVMS_LP_TOL_OPT UVMS_R(1e-9)
#define UVMS_LP_TOL_FEAS UVMS_R(1e-9)
#define UVMS_LP_TOL_RESIDUAL UVMS_R(1e-10)
#endif

/** What one solve did (diagnostics and the tests' iteration statistics). */
typedef struct {
  uint32_t iterations;        /**< simplex iterations, both phases (≤ UVMS_LP_MAX_ITERATIONS
                                   on success; a failed solve stops within 6 more) */
  uint32_t phase1_iterations; /**< of which Phase I and the drive-out of artificials */
  uint32_t redundant_rows;    /**< rows found dependent: 6 − rank of the usable columns */
  uvms_real_t objective_N;    /**< Σ_j |T_j| of the result [N] (0 on failure) */
} uvms_lp_info_t;

/**
 * @brief Least Σ|T_j| thrusts that produce the body wrench w exactly within |T_j| ≤ T_max
 *        (method above).
 *
 * @param[in]  n              thrusters, 1..UVMS_MAX_THRUSTERS
 * @param[in]  H              configuration matrix, row-major 6 × n: H[r·n + j] (force rows
 *                            [1], moment rows [m]; allocation.h, uvms_alloc_config_matrix)
 * @param[in]  usable_mask    bit j set = thruster j may be used; bits ≥ n ignored
 * @param[in]  wrench_body    w = (force [N]; moment [N·m]), vehicle frame, [6]; must lie in the
 *                            range of the usable columns (e.g. H·P of a feasible P)
 * @param[in]  thrust_limit_N T_max > 0 [N], or +inf (no limit)
 * @param[out] thrust_N       T [N], [UVMS_MAX_THRUSTERS]; entries ≥ n and of unusable
 *                            thrusters exactly 0; all zeros on every error
 * @param[out] info           iterations and objective, or NULL; zeroed on entry
 * @pre H's entries O(1) (unit directions, lever arms of about a metre): the tolerances are
 *      absolute in the scaled problem (see above).
 * @retval UVMS_OK            thrust_N = T (T = 0 when w = 0)
 * @retval UVMS_ERR_ARG       H, wrench_body or thrust_N is NULL, or n is 0; writes: thrust_N = 0
 *                            (if non-NULL), info zeroed
 * @retval UVMS_ERR_SIZE      n > UVMS_MAX_THRUSTERS; writes: thrust_N = 0, info zeroed
 * @retval UVMS_ERR_NONFINITE an entry of H (j < n) or of w is NaN/inf; writes: thrust_N = 0,
 *                            info zeroed
 * @retval UVMS_ERR_RANGE     thrust_limit_N not > 0 (or NaN); w not producible within the
 *                            bounds (Phase I residual above UVMS_LP_TOL_FEAS); more than
 *                            UVMS_LP_MAX_ITERATIONS iterations; or the result check failed.
 *                            Writes: thrust_N = 0; info keeps the iteration counts of a solve
 *                            that ran (objective_N = 0)
 * @retval UVMS_ERR_SINGULAR  a ratio test found no bound (an unbounded ray cannot exist for
 *                            a cost ≥ 0: numerical breakdown, e.g. a column of H with every
 *                            entry below UVMS_LP_TOL_PIVOT and T_max = +inf); writes:
 *                            thrust_N = 0, info as for UVMS_ERR_RANGE
 */
uvms_status_t uvms_lp_min_abs_thrust(size_t n,
                                     const uvms_real_t H[UVMS_LP_ROWS * UVMS_MAX_THRUSTERS],
                                     uint32_t usable_mask,
                                     const uvms_real_t wrench_body[UVMS_LP_ROWS],
                                     uvms_real_t thrust_limit_N,
                                     uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                     uvms_lp_info_t *info);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_ALLOC_LP_H */
