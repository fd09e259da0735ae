/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file trajectory.h
 * @brief Manipulator trajectories and the joint servo (SPEC §8).
 *
 *   uvms_cycloid_eval()       joint-space cycloid θI → θF over tF (SPEC §8, corrected [69–71])
 *   uvms_joint_servo()        θ̈_cmd = θ̈_ref + Kq·(θ_ref − θ) + Kqd·(θ̇_ref − θ̇)     (SPEC §8)
 *   uvms_cosine_line_eval()   straight EE line with the cosine profile [78]
 *   uvms_cart_traj_*()        that line tracked by resolved-rate damped-least-squares inverse
 *                             kinematics on the arm, referenced to the vehicle ([3]) or to the
 *                             barycenter (virtual manipulator [4]) (SPEC §8, §10)
 *
 * Time t_s is trajectory time: 0 at the start of the motion, in seconds. Every evaluator
 * clamps τ = t/tF to [0, 1]: before the start the output holds the start, after tF it holds
 * the end, and rates and accelerations are zero outside [0, tF].
 *
 * Output arrays must not alias input arrays (nor, for the Cartesian step, point into the
 * instance): safe outputs are written before the inputs are read.
 *
 * Safe outputs on error (types.h: every error writes a defined output): the evaluators
 * "hold the start" (position = start value where that is finite, else 0; rates and
 * accelerations 0); the servo falls back to feed-forward only or to zero (see it); the
 * Cartesian step "holds" its stored reference with zero rate and acceleration.
 */
#ifndef UVMS_TRAJECTORY_H
#define UVMS_TRAJECTORY_H

#include "uvms/arm_model.h"
#include "uvms/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Columns of SPEC §8's joint-angle table (docs/MODEL.md §8): the stowed start pose θI, the
 * final pose "Veh." for a vehicle reference, and the final poses for a barycenter reference by
 * payload. Written once, in uvms_joint_table_deg(); everything else (the paper configuration,
 * the scenario reader's "auto" column, tests, benchmarks) reads it there.
 */
typedef enum {
  UVMS_JOINT_TABLE_START = 0,     /**< θI */
  UVMS_JOINT_TABLE_VEHICLE = 1,   /**< θF, "Veh." */
  UVMS_JOINT_TABLE_BARY_0KG = 2,  /**< θF, "Bary. 0 kg" */
  UVMS_JOINT_TABLE_BARY_1KG = 3,  /**< θF, "Bary. 1 kg" */
  UVMS_JOINT_TABLE_BARY_2KG = 4,  /**< θF, "Bary. 2 kg" */
  UVMS_JOINT_TABLE_BARY_5KG = 5,  /**< θF, "Bary. 5 kg" */
  UVMS_JOINT_TABLE_BARY_10KG = 6, /**< θF, "Bary. 10 kg" (joint 1 corrected: see below) */
  UVMS_JOINT_TABLE_COLUMNS = 7
} uvms_joint_table_column_t;

/**
 * The paper's printed joint 1 of the "Bary. 10 kg" column [deg]. The table carries 173.19°
 * instead (docs/MODEL.md C26): the printed value misses the column's EE target by 35 mm and
 * breaks the column's trend; 173.19° meets the target within 0.3 mm. Scenario value
 * `trajectory.theta_final_deg = "printed"` runs the printed column.
 */
#define UVMS_JOINT_TABLE_BARY_10KG_J1_PRINTED_DEG 176.19

/** Joints of the table (the WAM's 7). */
#define UVMS_JOINT_TABLE_JOINTS 7

/**
 * @brief One column of SPEC §8's joint-angle table [deg], joints 1..7 at [0..6], in the real
 *        type (each entry UVMS_R(printed value); one correction, see
 *        UVMS_JOINT_TABLE_BARY_10KG_J1_PRINTED_DEG).
 * @return the column, or NULL for a column outside 0..UVMS_JOINT_TABLE_COLUMNS − 1
 */
const uvms_real_t *uvms_joint_table_deg(uvms_joint_table_column_t column);

/**
 * @brief Payload [kg] a barycenter column of the table was computed for (0, 1, 2, 5, 10), or
 *        −1 for θI, "Veh." and invalid columns.
 */
uvms_real_t uvms_joint_table_payload_kg(uvms_joint_table_column_t column);

/**
 * Recommended joint-servo gains (SPEC §8 leaves them to configuration: "stiff enough that
 * tracking error is far below the EE errors being measured"). Error dynamics
 * ë + Kqd·ė + Kq·e = 0 with Kq = ωn², Kqd = 2ζωn, ωn = 10 rad/s, ζ = 1 (critically damped,
 * no overshoot): settling in ≈ 0.6 s, two orders faster than the 6–120 s trajectories of
 * SPEC §9, and ωn·T = 0.3 at the 0.03 s controller period, so the sampled loop (acceleration
 * held over a tick) keeps real, well-damped poles (0.80 and 0.56 per tick).
 */
#define UVMS_JOINT_SERVO_KQ_DEFAULT_1_S2 UVMS_R(100.0)
/** See UVMS_JOINT_SERVO_KQ_DEFAULT_1_S2: Kqd = 2·ζ·ωn = 2·1·10 1/s. */
#define UVMS_JOINT_SERVO_KQD_DEFAULT_1_S UVMS_R(20.0)

/** A line direction shorter than this (before normalisation) is rejected [-]. */
#define UVMS_TRAJ_MIN_DIRECTION_NORM UVMS_R(1e-6)

/**
 * Largest accepted gain·dt of the Cartesian step (both the position and the null-space gain).
 * The reference error obeys ė = −K·e; Heun's method multiplies it by 1 − h + h²/2 per tick
 * (h = K·dt), stable for h < 2; h ≤ 1 keeps the decay monotone with margin. The defaults give
 * h = 5·0.03 = 0.15.
 */
#define UVMS_CART_TRAJ_MAX_GAIN_DT UVMS_R(1.0)

/**
 * @brief Joint-space cycloid (SPEC §8, the corrected [69–71]). With τ = clamp(t/tF, 0, 1) and
 *        Δ = θF − θI, per joint:
 *          θ  = θI + Δ·(τ − sin(2πτ)/(2π))
 *          θ̇  = (Δ/tF)·(1 − cos 2πτ)
 *          θ̈  = (2πΔ/tF²)·sin 2πτ
 *        θ̇ = θ̈ = 0 at both ends and outside [0, tF]; θ = θI for t ≤ 0 and θ = θF exactly for
 *        t ≥ tF.
 * @param[in]  n               number of joints, 1..UVMS_MAX_JOINTS
 * @param[in]  theta_start_rad θI [rad] (n)
 * @param[in]  theta_final_rad θF [rad] (n)
 * @param[in]  duration_s      tF [s], > 0
 * @param[in]  t_s             trajectory time [s] (any finite value; clamped)
 * @param[out] q_rad           θ(t) [rad] (n)
 * @param[out] qd_rad_s        θ̇(t) [rad/s] (n)
 * @param[out] qdd_rad_s2      θ̈(t) [rad/s²] (n)
 *
 * Safe output on error (every non-NULL output, min(n, UVMS_MAX_JOINTS) entries; nothing for
 * n = 0): hold the start, q = θI (0 for a joint whose θI is NaN/inf or when theta_start_rad
 * is NULL), θ̇ = θ̈ = 0.
 * @retval UVMS_OK            q, θ̇, θ̈ of the cycloid at t
 * @retval UVMS_ERR_ARG       a pointer is NULL; writes: the hold-the-start output in the
 *                            non-NULL outputs
 * @retval UVMS_ERR_SIZE      n is 0 or above UVMS_MAX_JOINTS (as uvms_arm_model_init); writes:
 *                            the hold-the-start output in the first min(n, UVMS_MAX_JOINTS)
 *                            entries (nothing for n = 0)
 * @retval UVMS_ERR_NONFINITE θI, θF, tF or t is NaN or infinite; writes: the hold-the-start
 *                            output (q = θI where finite, else 0; θ̇ = θ̈ = 0)
 * @retval UVMS_ERR_RANGE     tF ≤ 0, or tF so small (or Δ so large) that a result overflows;
 *                            writes: the hold-the-start output
 */
uvms_status_t uvms_cycloid_eval(size_t n, const uvms_real_t *theta_start_rad,
                                const uvms_real_t *theta_final_rad, uvms_real_t duration_s,
                                uvms_real_t t_s, uvms_real_t *q_rad, uvms_real_t *qd_rad_s,
                                uvms_real_t *qdd_rad_s2);

/**
 * @brief Joint servo (SPEC §8): θ̈_cmd = θ̈_ref + Kq·(θ_ref − θ) + Kqd·(θ̇_ref − θ̇), per joint.
 *        θ̈_cmd goes to the plant and into the feedforward model.
 * @param[in]  n            number of joints, 1..UVMS_MAX_JOINTS
 * @param[in]  q_ref_rad    θ_ref [rad] (n)
 * @param[in]  qd_ref_rad_s θ̇_ref [rad/s] (n)
 * @param[in]  qdd_ref_rad_s2 θ̈_ref [rad/s²] (n)
 * @param[in]  q_rad        measured θ [rad] (n)
 * @param[in]  qd_rad_s     measured θ̇ [rad/s] (n)
 * @param[in]  kq_1_s2      position gain Kq [1/s²], ≥ 0 (default UVMS_JOINT_SERVO_KQ_DEFAULT_1_S2)
 * @param[in]  kqd_1_s      rate gain Kqd [1/s], ≥ 0 (default UVMS_JOINT_SERVO_KQD_DEFAULT_1_S)
 * @param[out] qdd_cmd_rad_s2 θ̈_cmd [rad/s²] (n); must not alias any input array (it is
 *                          zeroed, the safe output, before the inputs are read: an in-place
 *                          call with qdd_cmd_rad_s2 == qdd_ref_rad_s2 would lose θ̈_ref)
 *
 * Safe output on error (min(n, UVMS_MAX_JOINTS) entries; nothing for n = 0):
 *  - a measured θ or θ̇ is NaN/inf (all references and gains valid): θ̈_cmd = θ̈_ref for every
 *    joint, i.e. feed-forward only, no feedback on a corrupt measurement. That is the
 *    acceleration of the reference itself, so it is safe while the measurement is held or
 *    bad: it neither reacts to garbage nor stops the planned motion abruptly.
 *  - finite inputs whose feedback overflows (absurd gains): θ̈_cmd = θ̈_ref, as above.
 *  - any other error (NULL, bad n, non-finite reference or gain, negative gain): θ̈_cmd = 0.
 * @retval UVMS_OK            θ̈_cmd written
 * @retval UVMS_ERR_ARG       a pointer is NULL; writes: θ̈_cmd = 0 (if non-NULL)
 * @retval UVMS_ERR_SIZE      n is 0 or above UVMS_MAX_JOINTS; writes: θ̈_cmd = 0
 *                            (min(n, UVMS_MAX_JOINTS) entries)
 * @retval UVMS_ERR_NONFINITE a reference or gain is NaN or infinite; writes: θ̈_cmd = 0. Or
 *                            (references and gains valid) a measured θ or θ̇ is NaN/inf;
 *                            writes: θ̈_cmd = θ̈_ref (feed-forward only)
 * @retval UVMS_ERR_RANGE     a gain is negative; writes: θ̈_cmd = 0. Or the feedback overflowed;
 *                            writes: θ̈_cmd = θ̈_ref
 */
uvms_status_t uvms_joint_servo(size_t n, const uvms_real_t *q_ref_rad,
                               const uvms_real_t *qd_ref_rad_s, const uvms_real_t *qdd_ref_rad_s2,
                               const uvms_real_t *q_rad, const uvms_real_t *qd_rad_s,
                               uvms_real_t kq_1_s2, uvms_real_t kqd_1_s,
                               uvms_real_t *qdd_cmd_rad_s2);

/**
 * @brief Check the joint servo's gains (uvms_joint_servo): both finite and ≥ 0.
 * @param[in] kq_1_s2 position gain Kq [1/s²]
 * @param[in] kqd_1_s rate gain Kqd [1/s]
 * Writes nothing (a pure check).
 * @retval UVMS_OK            both gains finite and ≥ 0
 * @retval UVMS_ERR_NONFINITE a gain is NaN or infinite
 * @retval UVMS_ERR_RANGE     a gain is negative
 */
uvms_status_t uvms_joint_servo_gains_check(uvms_real_t kq_1_s2, uvms_real_t kqd_1_s);

/**
 * @brief Straight line with the cosine profile [78]: with τ = clamp(t/tF, 0, 1), unit u,
 *          r = r_start + u·(rΔ/2)·(1 − cos πτ)
 *          ṙ = u·(π·rΔ/(2·tF))·sin πτ
 *          r̈ = u·(π²·rΔ/(2·tF²))·cos πτ
 *        inside (0, tF); for t ≤ 0 and t ≥ tF, r is exactly the start or the end point and
 *        ṙ = r̈ = 0. The profile is only C¹: r̈ jumps between 0 and ±π²rΔ/(2tF²) at both
 *        ends (the value at t = 0 and t = tF themselves is the outside value, 0).
 * @param[in]  r_start_m  start point, inertial [m] (3)
 * @param[in]  direction  line direction (3), any norm ≥ UVMS_TRAJ_MIN_DIRECTION_NORM;
 *                        normalised here
 * @param[in]  distance_m rΔ [m], finite; negative moves against direction
 * @param[in]  duration_s tF [s], > 0
 * @param[in]  t_s        trajectory time [s] (any finite value; clamped)
 * @param[out] r_m        position r(t), inertial [m] (3)
 * @param[out] v_m_s      velocity ṙ(t) [m/s] (3)
 * @param[out] a_m_s2     acceleration r̈(t) [m/s²] (3)
 *
 * Safe output on error (every non-NULL output): hold the start, r = r_start (0 in a
 * component that is NaN/inf or when r_start_m is NULL), ṙ = r̈ = 0.
 * @retval UVMS_OK            r, ṙ, r̈ of the line at t
 * @retval UVMS_ERR_ARG       a pointer is NULL; writes: the hold-the-start output in the
 *                            non-NULL outputs
 * @retval UVMS_ERR_NONFINITE an input is NaN or infinite; writes: the hold-the-start output
 *                            (r = r_start where finite, else 0; ṙ = r̈ = 0)
 * @retval UVMS_ERR_RANGE     tF ≤ 0 (or tF, rΔ so extreme that a result overflows), or
 *                            |direction| below UVMS_TRAJ_MIN_DIRECTION_NORM; writes: the
 *                            hold-the-start output
 */
uvms_status_t uvms_cosine_line_eval(const uvms_real_t r_start_m[3], const uvms_real_t direction[3],
                                    uvms_real_t distance_m, uvms_real_t duration_s,
                                    uvms_real_t t_s, uvms_real_t r_m[3], uvms_real_t v_m_s[3],
                                    uvms_real_t a_m_s2[3]);

/** Configuration of a Cartesian straight-line motion (SPEC §8, travel-distance experiment). */
typedef struct {
  uvms_real_t distance_m;         /**< rΔ [m], finite */
  uvms_real_t direction[3];       /**< line direction, inertial; normalised by init */
  uvms_real_t duration_s;         /**< tF [s], > 0 */
  uvms_reference_t reference;     /**< UVMS_REF_VEHICLE: EE by [3] at (r0d, R0d);
                                       UVMS_REF_BARYCENTER: EE by [4] (virtual manipulator) */
  uvms_real_t damping_m;          /**< DLS damping λ [m] (units of the linear Jacobian's
                                       singular values, m/rad), > 0 */
  uvms_real_t position_gain_1_s;  /**< K [1/s], ≥ 0: closes the loop on the EE error of the
                                       integrated reference (CLIK) */
  uvms_real_t nullspace_gain_1_s; /**< k0 [1/s], ≥ 0: null-space pull toward the start pose */
  uvms_real_t max_joint_rate_rad_s; /**< > 0: if any |θ̇_i| of the rate law exceeds it, the
                                         whole θ̇ is scaled down uniformly (direction kept)
                                         [rad/s]; only active at singularities or for
                                         unreachable lines */
} uvms_cart_traj_params_t;

/**
 * Cartesian trajectory instance (caller-owned; CMSIS-style init/step). Read the fields;
 * change them only through the API. The state is the joint reference q_ref at time t_state_s.
 */
typedef struct {
  uvms_cart_traj_params_t p;             /**< validated copy, direction unit length */
  size_t n;                              /**< joints, = model num_joints */
  uvms_real_t q_start_rad[UVMS_MAX_JOINTS];  /**< start pose θI [rad]; null-space target */
  uvms_real_t q_ref_rad[UVMS_MAX_JOINTS];    /**< state: reference θ at t_state_s [rad] */
  uvms_real_t qd_ref_rad_s[UVMS_MAX_JOINTS]; /**< last emitted θ̇_ref [rad/s] */
  uvms_real_t qdd_ref_rad_s2[UVMS_MAX_JOINTS]; /**< last emitted θ̈_ref [rad/s²] */
  uvms_real_t t_state_s;                 /**< time the stored q_ref belongs to [s]:
                                              0 after init, t_s + dt_s after a step
                                              (informational) */
  uvms_real_t r_start_m[3];              /**< start of the line: EE estimate at q_start [m] */
  uvms_real_t r0d_m[3];                  /**< reference vehicle position, inertial [m] */
  uvms_real_t R0d[9];                    /**< reference vehicle attitude, row-major */
  uvms_real_t barycenter0_m[3];          /**< barycenter at (r0d, R0d, q_start) [5] [m] */
  uvms_real_t r_est_m[3];                /**< EE estimate at the last emitted q_ref [m] */
  uvms_real_t r_des_m[3];                /**< line point r(t) of the last step [m] */
  int ready;                             /**< 1 after a successful uvms_cart_traj_init */
} uvms_cart_traj_t;

/**
 * @brief Defaults: x direction, rΔ = 0.3 m, tF = 60 s (the paper's run), vehicle reference,
 *        λ = 0.01 m, K = 5 1/s, k0 = 1 1/s, joint-rate limit 1 rad/s.
 *
 * Why: λ = 0.01 m is small against the singular values of the WAM's linear Jacobian along
 * these paths (≳ 0.1 m/rad, so the damped solution loses ≤ λ²/σ² ≈ 1 % of the task velocity,
 * which the K loop restores), yet bounds the joint rates by |v|/(2λ) at a singularity.
 * K = 5 1/s: 0.2 s time constant of the reference's EE error, far below tF, with K·dt = 0.15
 * at the 0.03 s tick. k0 = 1 1/s: a slow pull of the redundant self-motion toward the start
 * pose (time constant 1 s), below K and the joint servo's 10 rad/s so it never dominates the
 * joint rates. Rate limit 1 rad/s: a reachable line of the travel experiment (≤ 1 m over
 * 60 s, peak EE speed π·rΔ/(2tF) ≤ 0.026 m/s) needs a few tenths of a rad/s at most, so the
 * limit is inactive there; when a line leaves the workspace (λ alone then allows |v|/(2λ),
 * tens of rad/s) it keeps the reference's step per 0.03 s tick ≤ 0.03 rad, where the
 * linearisation of the step still holds.
 * Caution (workspace): from the stowed pose θI of SPEC §8 a line along +x is reachable for
 * only ≈ 2 cm (the EE would pass 0.09 m from the shoulder, inside the arm's minimum reach of
 * ≈ 0.15–0.19 m); along −x it is reachable for ≈ 0.7 m. A +x travel of 0.1–1 m needs another
 * start pose, e.g. the EE at the sampling point moving back along −x (x ≈ 1.51 → 0.51 m for
 * the "Veh." pose). Choose direction and start pose per scenario.
 * @param[out] params defaults; nothing is written if NULL
 */
void uvms_cart_traj_params_default(uvms_cart_traj_params_t *params);

/**
 * @brief Validate the parameters and start a Cartesian line at the start pose.
 *        The line starts at the EE estimate at q_start: by [3] at (r0d, R0d) for the vehicle
 *        reference; for the barycenter reference barycenter0 + (p_EE − p_cm)(R0d, q_start)
 *        [4] with barycenter0 the barycenter [5] at (r0d, R0d, q_start), which is the same
 *        point. Sets q_ref = q_start, θ̇_ref = θ̈_ref = 0, t_state_s = 0.
 * @param[out] traj     instance; all zero and not ready on error
 * @param[in]  params   configuration (copied; direction normalised). Every input may point
 *                      into traj itself (re-init with &traj->p, traj->q_start_rad, ...)
 * @param[in]  model    a ready model (its num_joints is the trajectory's n)
 * @param[in,out] work  workspace; its kinematic fields are overwritten
 * @param[in]  q_start_rad start pose θI [rad] (num_joints)
 * @param[in]  r0d_m    reference vehicle position, inertial [m] (3)
 * @param[in]  R0d      reference vehicle attitude, vehicle → inertial, row-major (9)
 * @retval UVMS_OK            traj ready at q_start
 * @retval UVMS_ERR_ARG       a pointer is NULL; writes: *traj all zero, ready = 0 (if traj is
 *                            non-NULL)
 * @retval UVMS_ERR_STATE     model not ready; writes: *traj all zero
 * @retval UVMS_ERR_NONFINITE a parameter, q_start, r0d or R0d is NaN or infinite; writes:
 *                            *traj all zero
 * @retval UVMS_ERR_RANGE     tF ≤ 0, λ ≤ 0, a gain < 0, rate limit ≤ 0, |direction| below
 *                            UVMS_TRAJ_MIN_DIRECTION_NORM, or reference not one of the enum;
 *                            writes: *traj all zero
 */
uvms_status_t uvms_cart_traj_init(uvms_cart_traj_t *traj, const uvms_cart_traj_params_t *params,
                                  const uvms_arm_model_t *model, uvms_arm_data_t *work,
                                  const uvms_real_t *q_start_rad, const uvms_real_t r0d_m[3],
                                  const uvms_real_t R0d[9]);

/**
 * @brief The resolved-rate law (SPEC §8), the right-hand side the step integrates:
 *          q̇ = J⁺·(ṙ_d(t) + K·(r_d(t) − r̂(q))) + (I − J⁺J)·k0·(q_start − q),
 *          J⁺ = Jᵀ(J·Jᵀ + λ²I)⁻¹ (damped least squares),
 *        where r_d is the line [78], r̂(q) the EE estimate of the reference and J its 3×N
 *        Jacobian: J_EE,linear at (r0d, R0d) (vehicle), or J_EE,linear − J_cm (barycenter,
 *        [4]). Computed as q̇ = z + Jᵀ·(J·Jᵀ + λ²I)⁻¹·(v − J·z) with z = k0·(q_start − q),
 *        v = ṙ_d + K·(r_d − r̂): one 3×3 SPD solve. With λ > 0 the null-space term leaks
 *        λ²(J·Jᵀ + λ²I)⁻¹·J·z into the EE velocity (relative size ≤ λ²/(σ_min² + λ²)).
 *        Finally q̇ is scaled by min(1, max_joint_rate / max_i |q̇_i|).
 * @param[in]  traj     a ready instance (its state is not used or changed)
 * @param[in]  model    the model traj was initialised with
 * @param[in,out] work  workspace; kinematic fields overwritten (FK at (r0d, R0d, q))
 * @param[in]  t_s      trajectory time [s]
 * @param[in]  q_rad    joint angles to evaluate at [rad] (n)
 * @param[out] qd_rad_s q̇ [rad/s] (UVMS_MAX_JOINTS entries: n used, the rest 0); zeros on error
 * @param[out] r_est_m  optional (may be NULL): r̂(q), inertial [m] (3); zeros on error
 * On every error: qd_rad_s[0..UVMS_MAX_JOINTS) = 0 and r_est_m = 0 (those that are non-NULL).
 * @retval UVMS_OK            qd_rad_s = q̇, r_est_m = r̂(q)
 * @retval UVMS_ERR_ARG       a pointer other than r_est_m is NULL, or model's num_joints
 *                            differs from traj->n; writes: qd_rad_s = 0, r_est_m = 0
 * @retval UVMS_ERR_STATE     traj or model not ready; writes: qd_rad_s = 0, r_est_m = 0
 * @retval UVMS_ERR_NONFINITE t or q is NaN or infinite, or the result is not finite; writes:
 *                            qd_rad_s = 0, r_est_m = 0
 * @retval UVMS_ERR_RANGE     the line [78] at t overflows (uvms_cosine_line_eval: e.g. a tiny
 *                            tF with a huge rΔ, which init does not bound); writes:
 *                            qd_rad_s = 0, r_est_m = 0
 * @retval UVMS_ERR_SINGULAR  J·Jᵀ + λ²I not numerically positive definite (λ far too small at
 *                            a singular pose); writes: qd_rad_s = 0, r_est_m = 0
 */
uvms_status_t uvms_cart_traj_rate(const uvms_cart_traj_t *traj, const uvms_arm_model_t *model,
                                  uvms_arm_data_t *work, uvms_real_t t_s,
                                  const uvms_real_t *q_rad, uvms_real_t *qd_rad_s,
                                  uvms_real_t r_est_m[3]);

/**
 * @brief One controller tick: emit the joint reference at t_s and advance it to t_s + dt_s.
 *
 * Outputs belong to time t_s: θ_ref(t_s) is the stored state (q_start on the first call after
 * init, which should have t_s = 0), θ̇_ref(t_s) = f(t_s, θ_ref) with f the rate law of
 * uvms_cart_traj_rate, and θ̈_ref(t_s) = (f(t_s + dt, θ_pred) − f(t_s, θ_ref))/dt, the
 * predictor θ_pred = θ_ref + dt·θ̇_ref. The state then advances by Heun's method
 * (explicit trapezoid, 2nd order):
 *          θ_ref(t_s + dt) = θ_ref + dt/2·(f(t_s, θ_ref) + f(t_s + dt, θ_pred))
 *                          = θ_ref + dt·θ̇_ref + dt²/2·θ̈_ref,
 * so the emitted triple is exactly the constant-acceleration motion over the tick that a
 * plant integrating a held θ̈ follows. Why Heun: it costs two evaluations of f per tick, the
 * same as Euler plus the derivative needed for θ̈_ref; it is 2nd-order accurate, so with the
 * K loop the EE error of the reference stays at the micrometre level over a 60 s run at
 * 0.03 s ticks (explicit Euler's would be ≈ dt·|r̈|/(2K), tens of micrometres); and its
 * error amplification 1 − h + h²/2 (h = K·dt) is stable and monotone for h ≤ 1.
 * The caller passes t_s = previous t_s + previous dt_s; another t_s only shifts the time
 * base of the line (the K loop absorbs it). The workspace's kinematic fields are
 * overwritten.
 * @param[in,out] traj  a ready instance
 * @param[in]  model    the model traj was initialised with
 * @param[in,out] work  workspace
 * @param[in]  t_s      trajectory time of the outputs [s], finite
 * @param[in]  dt_s     tick length [s], > 0, with max(K, k0)·dt ≤ UVMS_CART_TRAJ_MAX_GAIN_DT
 * @param[out] q_ref_rad      θ_ref(t_s) [rad] (UVMS_MAX_JOINTS entries: n used, rest 0)
 * @param[out] qd_ref_rad_s   θ̇_ref(t_s) [rad/s] (UVMS_MAX_JOINTS entries)
 * @param[out] qdd_ref_rad_s2 θ̈_ref(t_s) [rad/s²] (UVMS_MAX_JOINTS entries)
 *
 * Safe output on error: hold — θ_ref = the stored reference (unchanged state), θ̇_ref =
 * θ̈_ref = 0, nothing advanced. When traj is NULL, not ready or does not match the model,
 * all outputs are zero.
 * @retval UVMS_OK            θ_ref, θ̇_ref, θ̈_ref at t_s; state advanced to t_s + dt_s
 * @retval UVMS_ERR_ARG       a pointer is NULL, or model's num_joints differs from traj->n;
 *                            writes: the non-NULL outputs all zero (UVMS_MAX_JOINTS entries)
 * @retval UVMS_ERR_STATE     traj or model not ready; writes: outputs all zero
 * @retval UVMS_ERR_NONFINITE t_s or dt_s NaN/inf, or a non-finite result; writes: the hold
 *                            (θ_ref = stored reference, θ̇_ref = θ̈_ref = 0), state unchanged
 * @retval UVMS_ERR_RANGE     dt_s ≤ 0 or max(K, k0)·dt_s > UVMS_CART_TRAJ_MAX_GAIN_DT, or the
 *                            line overflows (as uvms_cart_traj_rate); writes: the hold, state
 *                            unchanged
 * @retval UVMS_ERR_SINGULAR  from uvms_cart_traj_rate (J·Jᵀ + λ²I not positive definite);
 *                            writes: the hold, state unchanged
 */
uvms_status_t uvms_cart_traj_step(uvms_cart_traj_t *traj, const uvms_arm_model_t *model,
                                  uvms_arm_data_t *work, uvms_real_t t_s, uvms_real_t dt_s,
                                  uvms_real_t *q_ref_rad, uvms_real_t *qd_ref_rad_s,
                                  uvms_real_t *qdd_ref_rad_s2);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_TRAJECTORY_H */
