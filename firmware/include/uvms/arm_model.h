/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file arm_model.h
 * @brief The vehicle-manipulator model (SPEC §2–3): parameters, the immutable model derived
 *        from them, and the caller-owned workspace the kinematics and dynamics fill.
 *
 * Model/workspace split after Pinocchio's rnea(model, data, ...): uvms_arm_model_t is built
 * once by uvms_arm_model_init() and never written afterwards (it can live in flash as const);
 * uvms_arm_data_t is the workspace every algorithm leaves its results in.
 *
 * Indexing follows SPEC: link i = 1..N is stored at index i; index 0 is the base (vehicle /
 * manipulator base frame B). Vectors named *_I are inertial-frame, *_b body/link-frame.
 */
#ifndef UVMS_ARM_MODEL_H
#define UVMS_ARM_MODEL_H

#include "uvms/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Compile-time maximum number of arm joints (the WAM has 7). */
#define UVMS_MAX_JOINTS 7
/** Per-link arrays hold links 1..N at indices 1..N and the base at index 0. */
#define UVMS_LINK_SLOTS (UVMS_MAX_JOINTS + 1)

/** One link: standard (distal) DH parameters, inertia and hydrodynamic geometry (SPEC §2, §3.1). */
typedef struct {
  uvms_real_t alpha_rad;          /**< DH twist α_i [rad] */
  uvms_real_t a_m;                /**< DH length a_i [m] */
  uvms_real_t d_m;                /**< DH offset d_i [m] */
  /** General placement (docs/MODEL.md §2 "General links"): frame i = frame i−1 ·
      Rz(θ_i)·Tz(d_i)·Tx(a_i)·Rx(α_i)·T(t_i)·Rot(ρ_i). t_i: a fixed translation in the frame
      after Rx(α_i) [m]; both 0: a standard DH link. */
  uvms_real_t placement_m[3];
  uvms_real_t placement_rotvec_rad[3]; /**< ρ_i: the fixed rotation after t_i, as a rotation
                                            vector (unit axis × angle) [rad] */
  uvms_real_t mass_kg;            /**< m_i [kg], ≥ 0 */
  uvms_real_t com_m[3];           /**< r_i: proximal joint point → CoM, frame i [m] */
  uvms_real_t inertia_kg_m2[3];   /**< diagonal of I_Bi about the CoM, frame-i axes [kg·m²] */
  uvms_real_t inertia_products_kg_m2[3]; /**< off-diagonal entries (I_xy, I_xz, I_yz) of I_Bi
                                              as they stand in the tensor (I_xy = −∫x·y dm),
                                              frame-i axes [kg·m²]; 0: principal axes */
  uvms_real_t diameter_m;         /**< hydrodynamic cylinder diameter d_L [m] (0: no hydro) */
  uvms_real_t drag_coeff;         /**< C_D0L, cross-flow drag coefficient [-] */
  /** The link's own added mass (docs/MODEL.md §3.3), diagonal on (a_b; ω̇_b) of its
      center of buoyancy μ_i in frame-i axes: kg ×3, kg·m² ×3, each ≥ 0. All zero (the
      paper's links): ρ·V_i·Ma0 (added_mass_coeff). Acts only in a fluid (ρ > 0) and on a
      link with a hydrodynamic cylinder (V_i > 0). */
  uvms_real_t added_mass_kg[6];
  uvms_real_t joint_min_rad;      /**< lower joint limit [rad] (sensor plausibility) */
  uvms_real_t joint_max_rad;      /**< upper joint limit [rad] */
} uvms_link_params_t;

/** The vehicle body (SPEC §3.2). */
typedef struct {
  uvms_real_t mass_kg;            /**< m0 [kg], > 0 */
  uvms_real_t volume_m3;          /**< V0 displaced volume [m³], ≥ 0 */
  uvms_real_t frontal_area_m2;    /**< A0 [m²], ≥ 0 */
  uvms_real_t drag_coeff;         /**< C_D0 [-], ≥ 0 */
  /** Fossen's diagonal linear damping D_L on the body velocity ν = (u, v, w, p, q, r) relative
      to the fluid (docs/MODEL.md §3.2): N·s/m for 0..2, N·m·s/rad for 3..5; each ≥ 0. */
  uvms_real_t linear_damping[6];
  /** Fossen's diagonal quadratic damping D_Q: N·s²/m² for 0..2, N·m·s²/rad² for 3..5; each
      ≥ 0. Both zero (the paper's vehicle): only the isotropic drag of C_D0 and A0 acts. */
  uvms_real_t quadratic_damping[6];
  uvms_real_t inertia_kg_m2[3];   /**< diagonal inertia about the CoM, vehicle axes [kg·m²] */
  uvms_real_t cob_m[3];           /**< center of buoyancy from the CoM, vehicle frame [m] */
  uvms_real_t base_offset_m[3];   /**< s0: CoM → manipulator base point, vehicle frame [m] */
  uvms_real_t base_rotvec_rad[3]; /**< the arm base frame's rotation from the vehicle axes,
                                       as a rotation vector [rad]; 0: parallel (SPEC §2) */
  uvms_real_t ballast_kg;         /**< trim ballast (SPEC §6.3): weight-only mass at
                                       ballast_offset_m [kg]; negative = a float; no inertia */
  uvms_real_t ballast_offset_m[3]; /**< the ballast's point from the CoM, vehicle frame [m] */
} uvms_vehicle_params_t;

/** Everything the model needs; uvms_arm_params_paper() gives SPEC §3's values. */
typedef struct {
  size_t num_joints;                         /**< N, 1..UVMS_MAX_JOINTS */
  uvms_link_params_t link[UVMS_MAX_JOINTS];  /**< link[i-1] is link i */
  uvms_vehicle_params_t vehicle;
  uvms_real_t payload_kg;                    /**< point payload m_{N+1} at the EE [kg], ≥ 0 */
  uvms_real_t payload_offset_m[3];           /**< r_{N+1}: EE → payload, frame N [m] */
  uvms_real_t added_mass_coeff[36];          /**< Ma0 of SPEC §3.3, unscaled, row-major 6×6 on
                                                  (v̇_body; ω̇_body) [-] */
} uvms_arm_params_t;

/**
 * Immutable model: quantities derived once from the parameters (SPEC §2, §3.1), and a pointer to
 * the parameters themselves.
 *
 * The model does not copy its parameters (that would cost sizeof(uvms_arm_params_t), 624 B in
 * float, in every instance): `p` points to the ones uvms_arm_model_init() was given, which must
 * outlive the model and must not change while it is in use (they may stay in flash; call
 * uvms_arm_model_init() again after changing them). `num_joints` is the model's own validated
 * copy of p->num_joints: every loop and index over the joints uses it (uvms_arm_joint_count),
 * never the count behind the pointer.
 */
typedef struct {
  const uvms_arm_params_t *p;               /**< the parameters (not copied; see above) */
  size_t num_joints;                        /**< N, 1..UVMS_MAX_JOINTS, copied at init */
  uvms_real_t l_m[UVMS_LINK_SLOTS][3];      /**< l_i = (a, d sin α, d cos α), frame i [1];
                                                 Rot(ρ_i)ᵀ·(that + t_i) for a placed link */
  uvms_real_t s_m[UVMS_LINK_SLOTS][3];      /**< s_i = l_i − r_i: CoM → distal origin [1] */
  uvms_real_t length_m[UVMS_LINK_SLOTS];    /**< |l_i| [m] */
  uvms_real_t inv_length_1_m[UVMS_LINK_SLOTS]; /**< 1/|l_i| [1/m] (0 where |l_i| = 0): the
                                                 drag's unit axis l_i/|l_i| per tick */
  uvms_real_t volume_m3[UVMS_LINK_SLOTS];   /**< V_i = π d²/4 |l_i| [m³] */
  uvms_real_t area_m2[UVMS_LINK_SLOTS];     /**< A_i = d |l_i| frontal area [m²] */
  uvms_real_t cos_alpha[UVMS_LINK_SLOTS];   /**< cos α_i [-] */
  uvms_real_t sin_alpha[UVMS_LINK_SLOTS];   /**< sin α_i [-] */
  uvms_real_t total_mass_kg;                /**< m_T = m0 + Σ m_i + m_{N+1} [5] [kg] */
  uvms_real_t inv_total_mass_1_kg;          /**< 1/m_T [1/kg] */
  uvms_real_t place_rot[UVMS_LINK_SLOTS][9]; /**< Rot(ρ_i) of a placed link, row-major */
  uvms_real_t base_rot[9];                  /**< Rot(ρ_B), the arm base's mount rotation */
  unsigned placed;                          /**< bit i set: link i has a general placement */
  int base_rotated;                         /**< 1 if ρ_B ≠ 0 */
  unsigned full_inertia;                    /**< bit i set: link i's I_Bi has off-diagonal
                                                 entries (the full 3×3 product is used) */
  unsigned own_added_mass;                  /**< bit i set: link i has its own diagonal
                                                 added_mass_kg (instead of ρ·V_i·Ma0) */
  int vehicle_damping;                      /**< 1 if a Fossen damping coefficient of the
                                                 vehicle is > 0 (docs/MODEL.md §3.2) */
  int ready;                                /**< 1 after a successful uvms_arm_model_init */
} uvms_arm_model_t;

/** The model's joint count clamped to UVMS_MAX_JOINTS: what every loop and index over the
 *  joints uses, so that a corrupted count in RAM cannot index past the arrays (init validates
 *  it; uvms_ctrl_step also rejects a corrupted instance before use). */
static inline size_t uvms_arm_joint_count(const uvms_arm_model_t *model) {
  const size_t n = model->num_joints;
  return (n < UVMS_MAX_JOINTS) ? n : UVMS_MAX_JOINTS;
}

/** Fluid and gravity seen by a model (the controller's: model density, steady flow only). */
typedef struct {
  uvms_real_t density_kg_m3;   /**< ρ [kg/m³], ≥ 0 */
  uvms_real_t flow_m_s[3];     /**< v∞, inertial [m/s] */
  uvms_real_t gravity_m_s2[3]; /**< g vector, inertial, e.g. (0, 0, −9.81) [m/s²] */
  int angle_of_attack;         /**< 1: C_D = C_D0L sin²α [21]; 0: C_D = C_D0L */
} uvms_fluid_t;

/**
 * @brief Check the fluid of a controller's model: every value finite, ρ > 0, angle_of_attack
 *        0 or 1. Stricter than what the model's algorithms accept (ρ ≥ 0): the thruster loops
 *        solve for the propeller speed with the model density and divide by it.
 * @param[in] fluid the fluid
 * Writes nothing (a pure check).
 * @retval UVMS_OK            the fluid is usable
 * @retval UVMS_ERR_ARG       fluid is NULL
 * @retval UVMS_ERR_NONFINITE the density, a flow or a gravity component is NaN or infinite
 * @retval UVMS_ERR_RANGE     the density is not > 0, or angle_of_attack is neither 0 nor 1
 */
uvms_status_t uvms_fluid_check(const uvms_fluid_t *fluid);

/** Vehicle state and acceleration the arm's kinematics and dynamics are evaluated at. */
typedef struct {
  uvms_real_t position_m[3];        /**< r0, vehicle CoM, inertial [m] */
  uvms_real_t R0[9];                /**< vehicle → inertial rotation, row-major */
  uvms_real_t velocity_m_s[3];      /**< v0, inertial [m/s] */
  uvms_real_t omega_rad_s[3];       /**< ω0, inertial [rad/s] */
  uvms_real_t accel_m_s2[3];        /**< v̇0, inertial [m/s²] */
  uvms_real_t alpha_rad_s2[3];      /**< ω̇0, inertial [rad/s²] */
} uvms_base_state_t;

/** Caller-owned workspace; every field is an output of the algorithm named in its comment. */
typedef struct {
  /* uvms_arm_fk (kinematics.h) */
  uvms_real_t R[UVMS_LINK_SLOTS][9];      /**< R_i: frame i → inertial; R[0] = R0 */
  uvms_real_t p_m[UVMS_LINK_SLOTS][3];    /**< p_i*: origin of frame i [3]; p[0] = base point */
  uvms_real_t z[UVMS_LINK_SLOTS][3];      /**< z[i]: axis of joint i = R_{i−1}·e_z [10–11] */
  uvms_real_t Rl_m[UVMS_LINK_SLOTS][3];   /**< R_i·l_i [m] */
  uvms_real_t Rr_m[UVMS_LINK_SLOTS][3];   /**< R_i·r_i [m] */
  uvms_real_t com_m[UVMS_LINK_SLOTS][3];  /**< c_i link CoM, inertial [m] */
  uvms_real_t R0s0_m[3];                  /**< R0·s0 [m] */
  uvms_real_t ee_m[3];                    /**< EE position = p_N* [m] */
  uvms_real_t payload_m[3];               /**< payload position [m] */
  uvms_real_t barycenter_m[3];            /**< p_cm [5] [m] */
  /* uvms_arm_forward (dynamics.h) */
  uvms_real_t omega_rad_s[UVMS_LINK_SLOTS][3];   /**< ω_i [8] */
  uvms_real_t alpha_rad_s2[UVMS_LINK_SLOTS][3];  /**< ω̇_i [9] */
  uvms_real_t v_m_s[UVMS_LINK_SLOTS][3];         /**< velocity of p_i* [12]; [0] = base point */
  uvms_real_t a_m_s2[UVMS_LINK_SLOTS][3];        /**< acceleration of p_i* [13] */
  uvms_real_t vc_m_s[UVMS_LINK_SLOTS][3];        /**< CoM velocity [14]; [0] = vehicle CoM */
  uvms_real_t ac_m_s2[UVMS_LINK_SLOTS][3];       /**< CoM acceleration [15]; [0] = vehicle CoM */
  uvms_real_t payload_v_m_s[3];                  /**< payload velocity [m/s] */
  uvms_real_t payload_a_m_s2[3];                 /**< payload acceleration [m/s²] */
  uvms_real_t barycenter_v_m_s[3];               /**< ṗ_cm (time derivative of [5]) [m/s] */
  /* uvms_arm_backward (dynamics.h) */
  uvms_real_t drag_N[UVMS_LINK_SLOTS][3];        /**< D_i [19]; [0] = vehicle drag D0 */
  uvms_real_t f_N[UVMS_LINK_SLOTS + 1][3];       /**< f_i [24]; f[N+1] = payload reaction */
  uvms_real_t n_Nm[UVMS_LINK_SLOTS + 1][3];      /**< n_i [25] about p_{i−1}* */
  uvms_real_t tau_Nm[UVMS_LINK_SLOTS];           /**< τ_i = n_i·z_i [29] */
} uvms_arm_data_t;

/** @brief Fill SPEC §3's parameters (Barrett WAM, 120 kg vehicle, 10 kg payload, Ma0).
 *  No status: params NULL → nothing is written. */
void uvms_arm_params_paper(uvms_arm_params_t *params);

/** @brief SPEC §3.3's unscaled added-mass matrix Ma0 (row-major 6×6).
 *  @pre Ma0 non-NULL, 36 writable reals (not checked; no status). */
void uvms_added_mass_paper(uvms_real_t Ma0[36]);

/**
 * @brief Validate parameters and derive the immutable model.
 * @param[in]  params parameters; not copied: model->p points to them, so they must outlive the
 *                    model and stay unchanged while it is in use
 * @param[out] model  the model; zeroed and not ready on error
 * @retval UVMS_OK            model->ready = 1
 * @retval UVMS_ERR_ARG       model or params is NULL; writes: *model all zero (ready = 0)
 *                            when model is non-NULL
 * @retval UVMS_ERR_SIZE      num_joints is 0 or above UVMS_MAX_JOINTS; writes: *model all
 *                            zero
 * @retval UVMS_ERR_NONFINITE a parameter is NaN or infinite; writes: *model all zero
 * @retval UVMS_ERR_RANGE     a mass, volume, area, inertia, diameter, drag or damping
 *                            coefficient or a link's own added mass (added_mass_kg) entry is
 *                            negative, a link's inertia tensor is not
 *                            positive semidefinite (a principal minor below −1e-6 of its
 *                            scale), the vehicle mass or a vehicle inertia is not positive,
 *                            or a joint's limits are not min < max; writes: *model all zero
 */
uvms_status_t uvms_arm_model_init(const uvms_arm_params_t *params, uvms_arm_model_t *model);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_ARM_MODEL_H */
