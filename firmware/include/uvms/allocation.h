/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file allocation.h
 * @brief Thrust allocation by pseudoinverse, SPEC §7.3 [33–39].
 *
 * The vehicle carries n ≤ UVMS_MAX_THRUSTERS fixed thrusters; thruster j sits at a_j (vehicle
 * frame, from the vehicle CoM) and pushes along the unit vector u_j (vehicle frame) with
 * thrust P_j [N] (positive along u_j). The body-frame wrench they produce is H·P with the
 * 6×n configuration matrix [33–37]
 *
 *     H = [ u_1        …  u_n
 *           a_1 × u_1  …  a_n × u_n ]      (force rows 0..2 [N per N], moment rows 3..5 [m]).
 *
 * The allocation [38–39] maps a wrench (F; N), given in inertial coordinates about the vehicle
 * CoM, to thrusts with the minimum-norm right inverse H⁺ = Hᵀ(H·Hᵀ)⁻¹:
 *
 *     P = H⁺ · blockdiag(R0ᵀ, R0ᵀ) · (F; N).
 *
 * Rank-revealing form (thruster faults, docs/FAULTS.md). With H_u = H with the columns of the
 * unusable thrusters set to zero, G = H_u·H_uᵀ = V·Λ·Vᵀ (symmetric Jacobi eigen-decomposition,
 * linalg.h) and
 *
 *     H⁺ = H_uᵀ · V · Λ⁺ · Vᵀ,   Λ⁺_kk = 1/λ_k if λ_k > UVMS_ALLOC_REL_EIG_TOL·λ_max, else 0.
 *
 * With all six eigenvalues kept this is exactly [38] ((H·Hᵀ)⁻¹ = V·Λ⁻¹·Vᵀ). With fewer (rank
 * r < 6) it is the Moore–Penrose pseudoinverse of H_u: P = H⁺·w is the least-squares thrust
 * whose wrench H_u·P is the orthogonal projection of w onto the r-dimensional range of H_u
 * (the controllable subspace), so the axes that can still be served still are; the lost
 * directions (the eigenvectors of dropped eigenvalues) get nothing. Both norms mix units
 * ([N] and [N·m], i.e. a 1 m lever arm weighs force and moment alike), as [38] does.
 *
 * H⁺ is expensive (a 6×6 Jacobi eigen-decomposition, up to UVMS_SYM_EIG_MAX_SWEEPS sweeps) and
 * depends only on the geometry and on the set of usable thrusters, so it is computed at init
 * and again only when that set changes (PX4's _mix_update_needed pattern); the per-tick step is
 * one 3×3 rotation and one n×6 matrix-vector product, and the optional thrust-limit
 * saturation (uvms_alloc_saturate) is O(n).
 *
 * Usage: uvms_alloc_init() once; uvms_alloc_set_usable() whenever fault detection changes the
 * usable set (cheap when nothing changed); uvms_alloc_step() every controller tick, then
 * uvms_alloc_saturate() if thrusts are limited, then (mode UVMS_ALLOC_MIN_POWER)
 * uvms_alloc_min_power() (alloc_power.h) for the least-Σ|T|^1.5 thrusts with the same wrench.
 * The struct is
 * caller-owned; no allocation, no hidden state. H itself is not stored (uvms_alloc_config_matrix
 * rebuilds it from the geometry): the controller instance must fit 4 KiB.
 */
#ifndef UVMS_ALLOCATION_H
#define UVMS_ALLOCATION_H

#include "uvms/thruster.h" /* UVMS_MAX_THRUSTERS */
#include "uvms/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Rows of H: the wrench dimension (force x, y, z; moment x, y, z). */
#define UVMS_ALLOC_WRENCH_DIM 6

/**
 * An eigenvalue λ_k of G = H_u·H_uᵀ at or below this fraction of the largest one counts as zero
 * (its direction is lost: rank < 6). λ_k = σ_k², so the threshold on σ_k/σ_max is its square
 * root (3.2e-3 in float, 1e-5 in double; a usable set with cond(H_u) above ≈ 316 resp. 1e5 is
 * treated as rank deficient). G is formed in the real type, so its entries carry a relative
 * rounding error of about n·eps (8·6e-8 ≈ 5e-7 in float, 8·1e-16 in double), and the Jacobi
 * eigenvalues an absolute error of a few eps·λ_max: a truly zero eigenvalue comes out below
 * ≈ 1e-6·λ_max in float. The threshold sits well above that noise, and far below the smallest
 * relative eigenvalue of any sensible geometry (0.25 for the paper's, SPEC §3.4; ≥ 0.06 with
 * any one thruster removed).
 */
#if UVMS_REAL_IS_FLOAT
#define UVMS_ALLOC_REL_EIG_TOL UVMS_R(1e-5)
#else
#define UVMS_ALLOC_REL_EIG_TOL UVMS_R(1e-10)
#endif

/**
 * Wrench axis i (bit i of uvms_alloc_t.uncontrollable_axes) is reported uncontrollable when the
 * squared distance of the unit wrench e_i from the controllable subspace, Σ_{k lost} V_ik², is
 * above this: more than 0.1 % (in norm) of a pure unit wrench along that axis cannot be
 * produced. Eigenvector rounding contributes ≈ (eps·λ_max/gap)² ≪ 1e-6 for any geometry whose
 * kept and lost eigenvalues are separated by the threshold above.
 */
#define UVMS_ALLOC_AXIS_RESIDUAL_TOL UVMS_R(1e-6)

/** Bits of uvms_alloc_t.uncontrollable_axes: body (vehicle-frame) wrench axes, rows of H. */
#define UVMS_AXIS_FX (1u << 0) /**< force along vehicle x */
#define UVMS_AXIS_FY (1u << 1) /**< force along vehicle y */
#define UVMS_AXIS_FZ (1u << 2) /**< force along vehicle z */
#define UVMS_AXIS_MX (1u << 3) /**< moment about vehicle x (through the CoM) */
#define UVMS_AXIS_MY (1u << 4) /**< moment about vehicle y */
#define UVMS_AXIS_MZ (1u << 5) /**< moment about vehicle z */
#define UVMS_AXIS_ALL 0x3Fu

/**
 * How the controller allocates the wrench (uvms_ctrl_config_t.alloc_mode).
 *
 * UVMS_ALLOC_PSEUDOINVERSE (the default, the paper's [38]): P = H⁺·w, the least Σ P_j², then
 * the thrust limit (uvms_alloc_saturate).
 *
 * UVMS_ALLOC_MIN_POWER: the least Σ|T_j|^1.5 (the thrusters' hydrodynamic power up to a
 * constant) that delivers exactly the wrench the pseudoinverse allocation delivers
 * (alloc_power.h, uvms_alloc_min_power): P is computed and limited as above, then
 * redistributed in the null space of the usable thrusters with |T_j| ≤ T_max. The cost is
 * strictly convex, so the optimum is unique and continuous in the wrench; rank loss,
 * attitude-first saturation and the delivered wrench are those of the pseudoinverse mode. If
 * the solver cannot run (more than two null directions, numerical breakdown), P is used (flag
 * ALLOC_FALLBACK).
 *
 * Value 1 is retired and never reused: it named min_abs_thrust, an exact least-Σ|T| linear
 * program whose optimal vertex jumped between ticks (docs/MODEL.md §7.3); it is refused as
 * any unknown value is.
 */
typedef enum {
  UVMS_ALLOC_PSEUDOINVERSE = 0, /**< least Σ P² [38] (default) */
  UVMS_ALLOC_MIN_POWER = 2      /**< least Σ|T|^1.5 with the pseudoinverse's delivered wrench */
} uvms_alloc_mode_t;

/** @brief Name of an allocation mode ("pseudoinverse", "min_power"), or "invalid";
 *         never NULL. */
const char *uvms_alloc_mode_str(uvms_alloc_mode_t mode);

/**
 * @brief Check an allocation mode: one of uvms_alloc_mode_t.
 * @param[in] mode the mode
 * Writes nothing (a pure check).
 * @retval UVMS_OK        mode is UVMS_ALLOC_PSEUDOINVERSE or UVMS_ALLOC_MIN_POWER
 * @retval UVMS_ERR_RANGE any other value (also the retired 1)
 */
uvms_status_t uvms_alloc_mode_check(uvms_alloc_mode_t mode);

/**
 * @brief Check one thruster's thrust limit (uvms_alloc_saturate_each,
 *        uvms_alloc_min_power_each as configured for the controller): finite and ≥ 0, where 0
 *        means no limit.
 * @param[in] thrust_limit_N the limit |P_j| ≤ thrust_limit_N [N], or 0
 * Writes nothing (a pure check).
 * @retval UVMS_OK            finite and ≥ 0
 * @retval UVMS_ERR_NONFINITE NaN or infinite
 * @retval UVMS_ERR_RANGE     negative
 */
uvms_status_t uvms_alloc_thrust_limit_check(uvms_real_t thrust_limit_N);

/** A direction vector shorter than this (before normalisation) is rejected [dimensionless]. */
#define UVMS_ALLOC_MIN_DIRECTION_NORM UVMS_R(1e-6)

/** Thruster layout in the vehicle frame (SPEC §3.4). Entries j ≥ num_thrusters are ignored. */
typedef struct {
  size_t num_thrusters;                          /**< n, 1..UVMS_MAX_THRUSTERS */
  uvms_real_t position_m[UVMS_MAX_THRUSTERS][3]; /**< a_j [m], vehicle frame, from vehicle CoM */
  uvms_real_t direction[UVMS_MAX_THRUSTERS][3];  /**< u_j, vehicle frame; normalised by init */
} uvms_thruster_geometry_t;

/** Allocation instance (caller-owned). Read the fields; change them only through the API. */
typedef struct {
  uvms_thruster_geometry_t geom; /**< validated copy, directions normalised to unit length */
  uint32_t usable_mask;          /**< bit j set = thruster j usable; only bits < n are ever set */
  /** H⁺ [38] (rank-revealing form above), row-major n × 6: H_pinv[j·6 + r], the Moore–Penrose
   *  pseudoinverse of H restricted to the usable columns; row j is exactly zero for an
   *  unusable thruster j; all zeros when no thruster is usable. Units: [1] (force columns),
   *  [1/m] (moment columns). */
  uvms_real_t H_pinv[UVMS_MAX_THRUSTERS * UVMS_ALLOC_WRENCH_DIM];
  uint32_t pinv_computations;  /**< times H_pinv was computed (init counts once) */
  uvms_status_t pinv_status;   /**< result of the last H_pinv computation */
  int initialised;             /**< 1 after a successful uvms_alloc_init (geometry valid) */
  int ready;                   /**< 1 when H_pinv is valid and uvms_alloc_step may run */
  uint8_t rank;                /**< rank of the usable columns of H, 0..6 (6: every wrench) */
  uint8_t uncontrollable_axes; /**< UVMS_AXIS_* bits of the wrench axes outside the range of the
                                    usable columns (0 at rank 6; UVMS_AXIS_ALL at rank 0) */
  uint8_t eig_sweeps;          /**< Jacobi sweeps of the last computation (cost diagnostic) */
} uvms_alloc_t;

/**
 * @brief Fill the paper's thruster layout (SPEC §3.4 table): n = 8, a_j [m] and unit u_j in
 *        the vehicle frame; unused slots (none for this layout) are zero.
 * @param[out] geom geometry; nothing is written if NULL
 */
void uvms_thruster_geometry_paper(uvms_thruster_geometry_t *geom);

/**
 * @brief Validate a thruster geometry and compute H⁺ = Hᵀ(H·Hᵀ)⁻¹ [38] over all thrusters
 *        (H [33–37] from the geometry). All thrusters start usable (usable_mask has bits
 *        0..n−1 set). The full set must have rank 6 (a geometry that cannot produce every
 *        wrench is a configuration error); subsets may not (uvms_alloc_set_usable).
 *
 * Directions need not be unit vectors: each u_j is normalised; one shorter than
 * UVMS_ALLOC_MIN_DIRECTION_NORM cannot define a direction and is rejected.
 *
 * @param[out] alloc instance; on every error it is left in the "refused" state: all zero
 *                   (initialised = 0, ready = 0, usable_mask = 0, rank = 0, H_pinv = 0) except
 *                   pinv_status = the returned status and uncontrollable_axes = UVMS_AXIS_ALL,
 *                   so uvms_alloc_step refuses it
 * @param[in]  geom  geometry: num_thrusters in 1..UVMS_MAX_THRUSTERS, position_m [m] and
 *                   direction finite for j < num_thrusters; may be &alloc->geom
 * @retval UVMS_OK            initialised = ready = 1, rank 6, every thruster usable
 * @retval UVMS_ERR_ARG       alloc or geom is NULL, or num_thrusters is 0; writes: the refused
 *                            state (nothing if alloc is NULL)
 * @retval UVMS_ERR_SIZE      num_thrusters > UVMS_MAX_THRUSTERS; writes: the refused state
 * @retval UVMS_ERR_NONFINITE a position or direction component is NaN or infinite, or |u_j|
 *                            or an entry of H (a_j × u_j) overflows; writes: the refused state
 * @retval UVMS_ERR_RANGE     a direction has norm < UVMS_ALLOC_MIN_DIRECTION_NORM; writes: the
 *                            refused state
 * @retval UVMS_ERR_SINGULAR  H has rank < 6 (an eigenvalue of H·Hᵀ at or below
 *                            UVMS_ALLOC_REL_EIG_TOL·λ_max; the thrusters cannot produce every
 *                            wrench), or H·Hᵀ overflows; writes: the refused state
 */
uvms_status_t uvms_alloc_init(uvms_alloc_t *alloc, const uvms_thruster_geometry_t *geom);

/**
 * @brief Set the usable-thruster set; recompute H⁺ from the usable columns of H (rank-revealing
 *        form above) only if the set actually changed (or was never computed). Unusable
 *        thrusters get a zero row of H⁺, so they are always commanded exactly zero thrust.
 *
 * Bits at or above num_thrusters are ignored (cleared) before the comparison. Any usable set
 * is accepted, also one of rank < 6 (even the empty set): rank and uncontrollable_axes then say
 * which wrench axes are lost, and uvms_alloc_step serves the rest (least squares). Calling
 * again with an unchanged mask returns the stored status of the last computation without
 * recomputing.
 *
 * @param[in,out] alloc       initialised instance
 * @param[in]     usable_mask bit j set = thruster j usable
 * @retval UVMS_OK           H⁺ computed (any rank; see rank, uncontrollable_axes)
 * @retval UVMS_ERR_ARG      alloc is NULL; writes: nothing
 * @retval UVMS_ERR_STATE    alloc was never successfully initialised; writes: nothing (the
 *                           instance is unchanged)
 * @retval UVMS_ERR_SINGULAR H⁺ could not be computed: the eigen-decomposition of H_u·H_uᵀ
 *                           failed or an entry of H⁺ is not finite. Not reachable from a
 *                           geometry uvms_alloc_init accepted; only a corrupted instance (e.g.
 *                           a NaN written into geom after init) gets here. Writes: ready = 0,
 *                           H_pinv = 0, rank = 0, uncontrollable_axes = UVMS_AXIS_ALL,
 *                           pinv_status = UVMS_ERR_SINGULAR (returned again for the same mask)
 */
uvms_status_t uvms_alloc_set_usable(uvms_alloc_t *alloc, uint32_t usable_mask);

/**
 * @brief Allocate a wrench to thrusts, SPEC [38–39], with the position/attitude split of §7.3.
 *
 *   f_b = R0ᵀ·F, n_b = R0ᵀ·N (body coordinates);  P_pos = H⁺·(f_b; 0);  P_att = H⁺·(0; n_b);
 *   P = P_pos + P_att  (= H⁺·(f_b; n_b)).
 *
 * R0 is taken as orthonormal (its transpose is used as its inverse); only its finiteness is
 * checked. The three output arrays must not overlap each other or the inputs.
 *
 * @param[in]  alloc        ready instance
 * @param[in]  R0           vehicle attitude, maps vehicle to inertial coordinates, 3×3 row-major
 * @param[in]  force_N_I    force to produce at the vehicle CoM [N], inertial coordinates, [3]
 * @param[in]  moment_Nm_I  moment about the vehicle CoM [N·m], inertial coordinates, [3]
 * @param[out] thrust_N     P [N] along each u_j, [UVMS_MAX_THRUSTERS]; entries ≥ n are zero
 * @param[out] thrust_pos_N P_pos [N], [UVMS_MAX_THRUSTERS], or NULL if not wanted
 * @param[out] thrust_att_N P_att [N], [UVMS_MAX_THRUSTERS], or NULL if not wanted
 *
 * On every error, each non-NULL output array is all zeros ([UVMS_MAX_THRUSTERS] entries).
 * @retval UVMS_OK            P, P_pos, P_att written
 * @retval UVMS_ERR_ARG       alloc, R0, force_N_I, moment_Nm_I or thrust_N is NULL; writes:
 *                            the non-NULL thrust arrays all zero
 * @retval UVMS_ERR_STATE     alloc not initialised (or initialised but not ready with no
 *                            failure recorded: a corrupted instance); writes: thrust arrays
 *                            all zero
 * @retval UVMS_ERR_SINGULAR  H⁺ could not be computed (pinv_status, see uvms_alloc_set_usable);
 *                            a usable set of rank < 6 is not an error: P is the least-squares
 *                            thrust. Writes: thrust arrays all zero
 * @retval UVMS_ERR_NONFINITE an input component is NaN/inf, or a thrust overflowed; writes:
 *                            thrust arrays all zero
 */
uvms_status_t uvms_alloc_step(const uvms_alloc_t *alloc, const uvms_real_t R0[9],
                              const uvms_real_t force_N_I[3], const uvms_real_t moment_Nm_I[3],
                              uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                              uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS],
                              uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS]);

/**
 * @brief Thrust limit with attitude priority (docs/FAULTS.md): scale the position and attitude
 *        parts of an allocation so that every |P_j| ≤ thrust_limit_N while each part keeps its
 *        direction.
 *
 *   1. If the attitude part alone exceeds the limit (max_j |P_att,j| > T), it is scaled
 *      uniformly to fit, s_att = T / max_j |P_att,j|, and the position part is dropped
 *      (s_pos = 0).
 *   2. Otherwise s_att = 1 and s_pos is the largest value in [0, 1] with
 *      |P_att,j + s_pos·P_pos,j| ≤ T for every j (closed form per thruster: the room left by
 *      the attitude part on the side P_pos,j points to, divided by |P_pos,j|).
 *   3. P_att ← s_att·P_att, P_pos ← s_pos·P_pos, P = P_pos + P_att, and P clamped to ±T (a
 *      rounding-level correction only).
 *
 * Since the parts are linear in their wrenches (P_pos = H⁺·(f_b; 0), P_att = H⁺·(0; n_b)), the
 * delivered wrench is (s_pos·f_b; s_att·n_b) at full rank: the commanded force and moment
 * directions are kept exactly, only their magnitudes shrink, attitude first served. O(n): one
 * pass when nothing exceeds the limit (the usual tick), one division per thruster otherwise.
 *
 * @param[in]     alloc          initialised instance (for n)
 * @param[in]     thrust_limit_N T > 0 [N] (+inf allowed: nothing is scaled)
 * @param[in,out] thrust_pos_N   P_pos [N], [UVMS_MAX_THRUSTERS]; scaled by s_pos
 * @param[in,out] thrust_att_N   P_att [N], [UVMS_MAX_THRUSTERS]; scaled by s_att
 * @param[out]    thrust_N       P = P_pos + P_att after scaling [N], [UVMS_MAX_THRUSTERS];
 *                               may not alias the parts
 * @param[out]    scale_pos      s_pos in [0, 1] (1: position part unchanged)
 * @param[out]    scale_att      s_att in (0, 1] (1: attitude part unchanged)
 * On every error the three arrays (when non-NULL) are all zero and both scales 0.
 * @retval UVMS_OK            parts scaled, thrust_N = their sum, scales written
 * @retval UVMS_ERR_ARG       a pointer is NULL; writes: the non-NULL arrays all zero, the
 *                            non-NULL scales 0
 * @retval UVMS_ERR_STATE     alloc not initialised; writes: arrays all zero, scales 0
 * @retval UVMS_ERR_RANGE     thrust_limit_N not > 0 (or NaN); writes: arrays all zero,
 *                            scales 0
 * @retval UVMS_ERR_NONFINITE a part of a thruster j < n is NaN/inf; writes: arrays all zero,
 *                            scales 0
 */
uvms_status_t uvms_alloc_saturate(const uvms_alloc_t *alloc, uvms_real_t thrust_limit_N,
                                  uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS],
                                  uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS],
                                  uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                  uvms_real_t *scale_pos, uvms_real_t *scale_att);

/**
 * @brief uvms_alloc_saturate with a limit per thruster, |P_j| ≤ T_j: in step 1
 *        s_att = min_j T_j/|P_att,j| over the thrusters whose attitude part exceeds its limit
 *        (then s_pos = 0); in step 2 the room of thruster j is T_j − P_att,j·sign(P_pos,j); in
 *        step 3 P_j is clamped to ±T_j. Each part still keeps its direction.
 * @param[in] thrust_limit_N T_j > 0 [N] or +inf (none), [UVMS_MAX_THRUSTERS]; entries j ≥ n
 *                           are ignored
 * Other parameters as uvms_alloc_saturate, whose calls with a limit T are this function's
 * with every entry T. On every error the three arrays (when non-NULL) are all zero and both
 * scales 0.
 * @retval UVMS_OK            parts scaled, thrust_N = their sum, scales written
 * @retval UVMS_ERR_ARG       a pointer (thrust_limit_N included) is NULL; writes: the non-NULL
 *                            arrays all zero, the non-NULL scales 0
 * @retval UVMS_ERR_STATE     alloc not initialised; writes: arrays all zero, scales 0
 * @retval UVMS_ERR_RANGE     an entry j < n not > 0 (or NaN); writes: arrays all zero, scales 0
 * @retval UVMS_ERR_NONFINITE a part of a thruster j < n is NaN/inf; writes: arrays all zero,
 *                            scales 0
 */
uvms_status_t uvms_alloc_saturate_each(const uvms_alloc_t *alloc,
                                       const uvms_real_t thrust_limit_N[UVMS_MAX_THRUSTERS],
                                       uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS],
                                       uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS],
                                       uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                       uvms_real_t *scale_pos, uvms_real_t *scale_att);

/**
 * @brief The configuration matrix H [33–37] of an instance, rebuilt from its geometry (H is not
 *        stored): row-major 6 × n, H[r·n + j], column j = (u_j; a_j × u_j), all thrusters
 *        usable or not. Force rows dimensionless, moment rows [m].
 * @param[in]  alloc initialised instance
 * @param[out] H     [UVMS_ALLOC_WRENCH_DIM · UVMS_MAX_THRUSTERS]; entries past 6·n and all
 *                   entries on error are zero
 * @retval UVMS_OK        H written
 * @retval UVMS_ERR_ARG   a pointer is NULL; writes: H all zero (if non-NULL)
 * @retval UVMS_ERR_STATE alloc not initialised; writes: H all zero
 */
uvms_status_t uvms_alloc_config_matrix(const uvms_alloc_t *alloc,
                                       uvms_real_t H[UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS]);

/**
 * @brief The body-frame wrench a set of thrusts produces, H·P [33–37] (all n thrusters, usable
 *        or not: this is physics, not allocation). For reporting desired vs produced wrench.
 * @param[in]  alloc       initialised instance
 * @param[in]  thrust_N    P [N], [UVMS_MAX_THRUSTERS]; entries ≥ n are ignored
 * @param[out] wrench_body (force [N]; moment about the vehicle CoM [N·m]), vehicle frame, [6];
 *                         zeros on error
 * @pre thrust_N is not checked for NaN/inf (it propagates with UVMS_OK).
 * @retval UVMS_OK        wrench_body = H·P
 * @retval UVMS_ERR_ARG   a pointer is NULL; writes: wrench_body = 0 (if non-NULL)
 * @retval UVMS_ERR_STATE alloc not initialised; writes: wrench_body = 0
 */
uvms_status_t uvms_alloc_wrench_body(const uvms_alloc_t *alloc,
                                     const uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                     uvms_real_t wrench_body[UVMS_ALLOC_WRENCH_DIM]);

/**
 * @brief Advance speed of every thruster, SPEC §5 [47–52]:
 *        v_a,j = u_j · (R0ᵀ·(v0 + ω0 × R0·a_j − v∞)), the speed of thruster j through the
 *        fluid along its own axis.
 * @param[in]  geom           geometry (directions taken as given: pass alloc->geom, which is
 *                            normalised, so that v_a is in m/s)
 * @param[in]  R0             vehicle attitude (vehicle → inertial), 3×3 row-major
 * @param[in]  v0_m_s_I       vehicle CoM velocity [m/s], inertial, [3]
 * @param[in]  w0_rad_s_I     vehicle angular velocity [rad/s], inertial, [3]
 * @param[in]  vinf_m_s_I     fluid velocity v∞ [m/s], inertial, [3]
 * @param[out] advance_m_s    v_a,j [m/s], [UVMS_MAX_THRUSTERS]; entries ≥ n and all entries on
 *                            error are zero
 * @retval UVMS_OK            advance_m_s written
 * @retval UVMS_ERR_ARG       a pointer is NULL, or geom->num_thrusters is 0; writes:
 *                            advance_m_s = 0 (if non-NULL)
 * @retval UVMS_ERR_SIZE      geom->num_thrusters > UVMS_MAX_THRUSTERS; writes: advance_m_s = 0
 * @retval UVMS_ERR_NONFINITE an input component (R0, v0, ω0, v∞, or the geometry of a thruster
 *                            j < n) is NaN/inf, or a result overflowed; writes: advance_m_s = 0
 */
uvms_status_t uvms_thruster_advance_speeds(const uvms_thruster_geometry_t *geom,
                                           const uvms_real_t R0[9], const uvms_real_t v0_m_s_I[3],
                                           const uvms_real_t w0_rad_s_I[3],
                                           const uvms_real_t vinf_m_s_I[3],
                                           uvms_real_t advance_m_s[UVMS_MAX_THRUSTERS]);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_ALLOCATION_H */
