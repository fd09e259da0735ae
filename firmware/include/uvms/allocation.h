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
 * H⁺ is expensive (a 6×6 Cholesky factorisation) and depends only on the geometry and on the
 * set of usable thrusters, so it is computed at init and again only when that set changes
 * (PX4's _mix_update_needed pattern); the per-tick step is one 3×3 rotation and one n×6
 * matrix-vector product.
 *
 * Usage: uvms_alloc_init() once; uvms_alloc_set_usable() whenever fault detection changes the
 * usable set (cheap when nothing changed); uvms_alloc_step() every controller tick. The struct
 * is caller-owned; no allocation, no hidden state.
 */
#ifndef UVMS_ALLOCATION_H
#define UVMS_ALLOCATION_H

#include "uvms/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest number of thrusters the allocation handles (the paper's vehicle has 8, SPEC §3.4). */
#define UVMS_MAX_THRUSTERS 8

/** Rows of H: the wrench dimension (force x, y, z; moment x, y, z). */
#define UVMS_ALLOC_WRENCH_DIM 6

/**
 * A pivot of the Cholesky factorisation of H·Hᵀ below this fraction of its largest diagonal
 * entry counts as rank loss (UVMS_ERR_SINGULAR). H·Hᵀ is formed in the real type, so its
 * entries carry a relative rounding error of about n·eps (8·6e-8 ≈ 5e-7 in float, 8·1e-16 in
 * double); the threshold sits well above that noise, and far below the smallest relative
 * pivot of any sensible geometry (0.25 for the paper's geometry, SPEC §3.4; 0.125 with any one
 * thruster removed; cond(H) ≤ 3.4 in all those cases).
 */
#if UVMS_REAL_IS_FLOAT
#define UVMS_ALLOC_REL_PIVOT_TOL UVMS_R(1e-5)
#else
#define UVMS_ALLOC_REL_PIVOT_TOL UVMS_R(1e-10)
#endif

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
  /** H [33–37], row-major 6 × n: H[r·n + j], rows (u_j; a_j × u_j). Force rows dimensionless,
   *  moment rows [m]. All thrusters, usable or not. */
  uvms_real_t H[UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS];
  /** H⁺ [38], row-major n × 6: H_pinv[j·6 + r], the pseudoinverse of H restricted to the
   *  usable columns; row j is exactly zero for an unusable thruster j; all zeros when the
   *  usable set has rank < 6. Units: [1] (force columns), [1/m] (moment columns). */
  uvms_real_t H_pinv[UVMS_MAX_THRUSTERS * UVMS_ALLOC_WRENCH_DIM];
  uint32_t pinv_computations;  /**< times H_pinv was computed (init counts once) */
  uvms_status_t pinv_status;   /**< result of the last H_pinv computation */
  int initialised;             /**< 1 after a successful uvms_alloc_init (geometry valid) */
  int ready;                   /**< 1 when H_pinv is valid and uvms_alloc_step may run */
} uvms_alloc_t;

/**
 * @brief Fill the paper's thruster layout (SPEC §3.4 table): n = 8, a_j [m] and unit u_j in
 *        the vehicle frame; unused slots (none for this layout) are zero.
 * @param[out] geom geometry; nothing is written if NULL
 */
void uvms_thruster_geometry_paper(uvms_thruster_geometry_t *geom);

/**
 * @brief Validate a thruster geometry, build H [33–37] and H⁺ = Hᵀ(H·Hᵀ)⁻¹ [38] over all
 *        thrusters. All thrusters start usable (usable_mask has bits 0..n−1 set).
 *
 * Directions need not be unit vectors: each u_j is normalised; one shorter than
 * UVMS_ALLOC_MIN_DIRECTION_NORM cannot define a direction and is rejected.
 *
 * @param[out] alloc instance; on every error it is left all-zero except pinv_status
 *                   (initialised = 0, ready = 0, H = H_pinv = 0), so uvms_alloc_step refuses it
 * @param[in]  geom  geometry: num_thrusters in 1..UVMS_MAX_THRUSTERS, position_m [m] and
 *                   direction finite for j < num_thrusters; may be &alloc->geom
 * @retval UVMS_OK
 * @retval UVMS_ERR_ARG       alloc or geom is NULL, or num_thrusters is 0
 * @retval UVMS_ERR_SIZE      num_thrusters > UVMS_MAX_THRUSTERS
 * @retval UVMS_ERR_NONFINITE a position or direction component is NaN or infinite
 * @retval UVMS_ERR_RANGE     a direction has norm < UVMS_ALLOC_MIN_DIRECTION_NORM
 * @retval UVMS_ERR_SINGULAR  H has rank < 6 (H·Hᵀ not numerically positive definite): the
 *                            thrusters cannot produce every wrench
 */
uvms_status_t uvms_alloc_init(uvms_alloc_t *alloc, const uvms_thruster_geometry_t *geom);

/**
 * @brief Set the usable-thruster set; recompute H⁺ from the usable columns of H only if the
 *        set actually changed (or was never computed). Unusable thrusters get a zero row of H⁺,
 *        so they are always commanded exactly zero thrust.
 *
 * Bits at or above num_thrusters are ignored (cleared) before the comparison. When the usable
 * set has rank < 6 the instance is left not ready (H_pinv = 0, uvms_alloc_step refuses it
 * with UVMS_ERR_SINGULAR) until a later call restores a full-rank set. Calling again with an
 * unchanged mask returns the stored status of the last computation without recomputing.
 *
 * @param[in,out] alloc       initialised instance
 * @param[in]     usable_mask bit j set = thruster j usable
 * @retval UVMS_OK
 * @retval UVMS_ERR_ARG      alloc is NULL
 * @retval UVMS_ERR_STATE    alloc was never successfully initialised (nothing is changed)
 * @retval UVMS_ERR_SINGULAR the usable thrusters span fewer than 6 wrench directions
 *                           (ready = 0, H_pinv = 0)
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
 * On every error, each non-NULL output array is all zeros.
 * @retval UVMS_OK
 * @retval UVMS_ERR_ARG       alloc, R0, force_N_I, moment_Nm_I or thrust_N is NULL
 * @retval UVMS_ERR_STATE     alloc not initialised
 * @retval UVMS_ERR_SINGULAR  the usable set has rank < 6 (see uvms_alloc_set_usable)
 * @retval UVMS_ERR_NONFINITE an input component is NaN/inf, or a thrust overflowed
 */
uvms_status_t uvms_alloc_step(const uvms_alloc_t *alloc, const uvms_real_t R0[9],
                              const uvms_real_t force_N_I[3], const uvms_real_t moment_Nm_I[3],
                              uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                              uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS],
                              uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS]);

/**
 * @brief The body-frame wrench a set of thrusts produces, H·P [33–37] (all n thrusters, usable
 *        or not: this is physics, not allocation). For reporting desired vs produced wrench.
 * @param[in]  alloc       initialised instance
 * @param[in]  thrust_N    P [N], [UVMS_MAX_THRUSTERS]; entries ≥ n are ignored
 * @param[out] wrench_body (force [N]; moment about the vehicle CoM [N·m]), vehicle frame, [6];
 *                         zeros on error
 * @retval UVMS_OK
 * @retval UVMS_ERR_ARG   a pointer is NULL
 * @retval UVMS_ERR_STATE alloc not initialised
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
 * @retval UVMS_OK
 * @retval UVMS_ERR_ARG       a pointer is NULL, or geom->num_thrusters is 0
 * @retval UVMS_ERR_SIZE      geom->num_thrusters > UVMS_MAX_THRUSTERS
 * @retval UVMS_ERR_NONFINITE an input component (including geometry) is NaN/inf, or a
 *                            result overflowed
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
