/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file controller.h
 * @brief The station-keeping controller: one caller-owned instance, init(config) then one
 *        step(sensors) per tick (SPEC §7–8). Data flows one way through a tick:
 *
 *   sensors → validate (or hold the last good record) → joint reference (§8) → joint servo → arm model + feedforward (§4, §7.1)
 *           → PD feedback (§7.2) → Table X switches → allocation (§7.3)
 *           → thruster speed/current loops (§7.4) → the drive's command (current command and
 *             its rate, and the voltage [53]; §5 "Motors") → command + telemetry
 *
 * No dynamic allocation: uvms_ctrl_t holds every buffer, sized by compile-time maxima.
 */
#ifndef UVMS_CONTROLLER_H
#define UVMS_CONTROLLER_H

#include "uvms/alloc_power.h"
#include "uvms/allocation.h"
#include "uvms/arm_model.h"
#include "uvms/feedback.h"
#include "uvms/feedforward.h"
#include "uvms/thruster.h"
#include "uvms/trajectory.h"

#ifdef __cplusplus
extern "C" {
#endif

/** How the joint reference is produced (SPEC §8). */
typedef enum {
  UVMS_TRAJ_HOLD = 0,           /**< hold θ_start */
  UVMS_TRAJ_JOINT_CYCLOID = 1,  /**< cycloid θ_start → θ_final over duration_s */
  UVMS_TRAJ_CARTESIAN_LINE = 2  /**< straight EE line by resolved-rate DLS IK */
} uvms_traj_mode_t;

/** Which part of a configuration uvms_ctrl_init() rejected (uvms_ctrl_t.config_error). Each
 *  part is checked by the module that owns it (named below); init calls the checks in this
 *  order and records the first part that fails. */
typedef enum {
  UVMS_CFG_OK = 0,
  UVMS_CFG_ARM,              /**< arm/vehicle/payload parameters (uvms_arm_model_init) */
  UVMS_CFG_FLUID,            /**< model density not > 0, a value non-finite or angle_of_attack
                                  not 0/1 (uvms_fluid_check) */
  UVMS_CFG_THRUSTER_GEOMETRY,/**< thruster positions/directions invalid (uvms_alloc_init) */
  UVMS_CFG_THRUSTER_RANK,    /**< thrusters cannot produce every wrench (rank < 6;
                                  uvms_alloc_init) */
  UVMS_CFG_THRUSTER_PARAMS,  /**< propeller/motor parameters (uvms_thruster_params_validate) */
  UVMS_CFG_GAINS,            /**< PD gains negative or non-finite (uvms_pd_gains_check) */
  UVMS_CFG_SWITCHES,         /**< switches not 0/1 or unknown reference (uvms_switches_check) */
  UVMS_CFG_JOINT_SERVO,      /**< joint servo gains negative or non-finite
                                  (uvms_joint_servo_gains_check) */
  UVMS_CFG_TICK,             /**< tick period not > 0 or non-finite (the controller's) */
  UVMS_CFG_TRAJECTORY,       /**< trajectory mode, angles, times (the controller's) or
                                  Cartesian parameters (uvms_cart_traj_init) */
  UVMS_CFG_LIMITS,           /**< plausibility bounds or hold count (the controller's), or
                                  thrust limit (uvms_alloc_thrust_limit_check) */
  UVMS_CFG_DRIVE,            /**< drive not one of uvms_drive_t (uvms_drive_check) */
  UVMS_CFG_ALLOC_MODE,       /**< alloc_mode not one of uvms_alloc_mode_t
                                  (uvms_alloc_mode_check) */
  UVMS_CFG_FEEDFORWARD_LEAD  /**< feedforward_lead not 0/1, or 1 with the voltage drive
                                  (uvms_ff_lead_check) */
} uvms_cfg_field_t;

/** @brief Name of a configuration field ("arm", "thruster_rank", ...); never NULL. A value
 *         that is not a uvms_cfg_field_t enumerator gives "unknown". */
const char *uvms_cfg_field_str(uvms_cfg_field_t field);

/** Largest accepted uvms_ctrl_limits_t.sensor_hold_max_ticks (3 s at the paper's 0.03 s tick):
 *  a stale estimate must not stand in for the vehicle's state indefinitely. */
#define UVMS_SENSOR_HOLD_MAX_TICKS_LIMIT 100u

/**
 * Fault handling settings (docs/FAULTS.md, "Controller"): sensor plausibility bounds, the
 * hold-last-good policy and the per-thruster thrust limit.
 *
 * Every bound is checked only when > 0; 0 disables that check. Hence an all-zero struct (what a
 * configuration mapped without these fields holds) keeps the behaviour the controller had
 * before they existed: no plausibility bounds beyond the fixed ones, no hold (a rejected record
 * gives the safe output at once), no thrust limit. uvms_ctrl_config_paper() sets every field.
 * init rejects a negative or non-finite value, quat_norm_tol > 0.5 and a hold count above
 * UVMS_SENSOR_HOLD_MAX_TICKS_LIMIT (UVMS_CFG_LIMITS).
 */
typedef struct {
  uvms_real_t max_vehicle_speed_m_s;  /**< bound on |v0| [m/s] (VEHICLE_SPEED_IMPLAUSIBLE) */
  uvms_real_t max_vehicle_rate_rad_s; /**< bound on |ω0| [rad/s] (ANGULAR_RATE_IMPLAUSIBLE) */
  uvms_real_t max_joint_rate_rad_s;   /**< bound on each |θ̇_i| [rad/s] (JOINT_RATE_IMPLAUSIBLE) */
  uvms_real_t max_motor_speed_rad_s;  /**< bound on |ω_j| of usable thrusters [rad/s]
                                           (MOTOR_SPEED_IMPLAUSIBLE) */
  uvms_real_t max_motor_current_A;    /**< bound on |I_j| of usable thrusters [A]
                                           (MOTOR_CURRENT_IMPLAUSIBLE) */
  uvms_real_t quat_norm_tol;          /**< bound on ||q| − 1| [1], ≤ 0.5 (QUATERNION_INVALID);
                                           |q| ∉ [0.5, 1.5] is always rejected */
  uint32_t sensor_hold_max_ticks;     /**< consecutive rejected records that the last good
                                           record may replace (SENSOR_HELD) before the safe
                                           output (SENSOR_HOLD_EXPIRED) [ticks] */
  uvms_real_t thrust_limit_N[UVMS_MAX_THRUSTERS]; /**< |P_j| bound of thruster j [N], 0: none
                                           (THRUST_SATURATED; uvms_alloc_saturate_each:
                                           attitude first) */
} uvms_ctrl_limits_t;

/** Everything the controller is configured with. uvms_ctrl_config_paper() gives SPEC's. */
typedef struct {
  uvms_arm_params_t arm;                /**< the controller's model of vehicle, arm, payload */
  uvms_fluid_t fluid;                   /**< model density, steady flow v∞0, gravity, AoA */
  uvms_thruster_geometry_t thrusters;   /**< SPEC §3.4 layout */
  uvms_thruster_params_t thruster[UVMS_MAX_THRUSTERS]; /**< thruster j's propeller, motor,
                                             KA, KB, voltage limit (j < num_thrusters; the
                                             sets differ between thruster types) */
  uvms_drive_t drive;                   /**< motor power stage (SPEC §5; 0 = current) */
  uvms_alloc_mode_t alloc_mode;         /**< thrust allocation (allocation.h; 0 = the
                                             pseudoinverse [38], 2 = least Σ|T|^1.5;
                                             1 retired) */
  int feedforward_lead;                 /**< 1: the feedforward wrench is led by the thruster
                                             chain's ramp lag (docs/MODEL.md §7.5; current
                                             drive only); 0: the paper's, no lead */
  uvms_pd_gains_t gains;                /**< K_PF, K_DF, K_PN, K_DN */
  uvms_switches_t switches;             /**< Table X */
  uvms_real_t joint_kq_1_s2;            /**< joint servo position gain Kq [1/s²] */
  uvms_real_t joint_kqd_1_s;            /**< joint servo rate gain Kqd [1/s] */
  uvms_real_t tick_s;                   /**< controller period [s] (SPEC §3.5: 0.03) */
  uvms_traj_mode_t traj_mode;
  uvms_real_t theta_start_rad[UVMS_MAX_JOINTS]; /**< θI [rad] (start pose; hold pose) */
  uvms_real_t theta_final_rad[UVMS_MAX_JOINTS]; /**< θF [rad] (joint cycloid) */
  uvms_real_t traj_start_s;             /**< time the motion begins [s] */
  uvms_real_t traj_duration_s;          /**< tF [s] (joint cycloid) */
  uvms_cart_traj_params_t cart;         /**< Cartesian line (its duration_s is tF there); its
                                             reference must equal switches.position_reference */
  uvms_ctrl_limits_t limits;            /**< fault handling (docs/FAULTS.md); 0 = check off */
} uvms_ctrl_config_t;

/** One tick's sensor record (the firmware's view; the SIL maps LCM messages onto it). */
typedef struct {
  int64_t tick;                                  /**< sequence number k */
  uvms_real_t time_s;                            /**< time since run start [s] */
  uvms_real_t position_m[3];                     /**< r0, inertial [m] */
  uvms_real_t quaternion_wxyz[4];                /**< R0 (vehicle → inertial), scalar first */
  uvms_real_t velocity_m_s[3];                   /**< v0, inertial [m/s] */
  uvms_real_t angular_velocity_rad_s[3];         /**< ω0, inertial [rad/s] */
  uvms_real_t joint_position_rad[UVMS_MAX_JOINTS]; /**< θ [rad] */
  uvms_real_t joint_velocity_rad_s[UVMS_MAX_JOINTS]; /**< θ̇ [rad/s] */
  uvms_real_t motor_speed_rad_s[UVMS_MAX_THRUSTERS]; /**< ω_j [rad/s]; read (and checked
                                                          finite) for usable thrusters only */
  uvms_real_t motor_current_A[UVMS_MAX_THRUSTERS];   /**< I_j [A]; as motor_speed_rad_s */
  uint32_t thruster_usable_mask;                 /**< bit j = thruster j healthy/usable; an
                                                      unusable thruster gets V_j = 0 and no
                                                      motor loop; bits ≥ n ignored. Honoured
                                                      even when the rest of the record is
                                                      rejected (a held tick uses the AND of
                                                      this and the held record's mask) */
} uvms_ctrl_sensors_t;

/** The actuator command of one tick. Both drives' quantities are always filled; the power
 *  stage uses those of the configured drive (SPEC §5 "Motors"). */
typedef struct {
  uvms_real_t motor_voltage_V[UVMS_MAX_THRUSTERS];      /**< V_j [V] [53]: what the voltage
                                                             drive holds over the tick */
  uvms_real_t motor_current_cmd_A[UVMS_MAX_THRUSTERS];  /**< I*_j at the start of the tick
                                                             [A]: the controller's integrated
                                                             current command [66] */
  uvms_real_t motor_current_rate_A_s[UVMS_MAX_THRUSTERS]; /**< İ*_j [A/s] [66]: the current
                                                             drive makes I(t) = I*_j +
                                                             İ*_j·(t − t_k) over the tick */
  uvms_real_t joint_acceleration_rad_s2[UVMS_MAX_JOINTS]; /**< θ̈_cmd [rad/s²] (§8) */
  uvms_real_t joint_ref_rad[UVMS_MAX_JOINTS];           /**< θ_ref [rad] */
  uvms_real_t joint_ref_rate_rad_s[UVMS_MAX_JOINTS];    /**< θ̇_ref [rad/s] */
  uvms_real_t joint_ref_accel_rad_s2[UVMS_MAX_JOINTS];  /**< θ̈_ref [rad/s²] */
} uvms_ctrl_command_t;

/** Status flags of a tick (uvms_ctrl_telemetry_t.flags). Every bit, its cause and the
 *  controller's response are tabulated in docs/FAULTS.md. "Rejected" below: the record is not
 *  used; the last good one is held (SENSOR_HELD) or, when that is not allowed, the step gives
 *  the safe output (SENSOR_HOLD_EXPIRED). */
#define UVMS_FLAG_SENSOR_NONFINITE    (1u << 0)  /**< a sensor value was NaN/inf: rejected */
#define UVMS_FLAG_QUATERNION_INVALID  (1u << 1)  /**< ||q| − 1| > limits.quat_norm_tol or |q| ∉
                                                      [0.5, 1.5]: rejected */
#define UVMS_FLAG_ALLOC_SINGULAR      (1u << 2)  /**< usable thrusters have rank < 6: the axes
                                                      in uncontrollable_axes get no wrench, the
                                                      others are still controlled */
#define UVMS_FLAG_VOLTAGE_SATURATED   (1u << 3)  /**< a motor voltage was clamped */
#define UVMS_FLAG_THRUSTERS_IDLE      (1u << 4)  /**< no vehicle control (case I): V = 0 */
#define UVMS_FLAG_TICK_GAP            (1u << 5)  /**< tick > previous + 1 (ticks were lost; the
                                                      record itself is fresh and used) */
#define UVMS_FLAG_TICK_NOT_INCREASING (1u << 6)  /**< tick ≤ previous: stale/out of order:
                                                      rejected */
#define UVMS_FLAG_MOTOR_FAULT         (1u << 7)  /**< a thruster's motor loop failed: its V = 0 */
#define UVMS_FLAG_MODEL_FAULT         (1u << 8)  /**< arm model/feedforward failed: safe output */
#define UVMS_FLAG_TRAJECTORY_FAULT    (1u << 9)  /**< trajectory failed: last good reference
                                                      held at rest (mid-run), or the Cartesian
                                                      line could not start (safe output) */
#define UVMS_FLAG_REFERENCE_CAPTURED  (1u << 10) /**< this tick captured r_d, R0d, q0d (first tick) */
#define UVMS_FLAG_JOINT_LIMIT         (1u << 11) /**< a measured joint is outside its limits
                                                      (joint_min/max_rad): rejected */
#define UVMS_FLAG_VEHICLE_SPEED_IMPLAUSIBLE  (1u << 12) /**< |v0| > max_vehicle_speed: rejected */
#define UVMS_FLAG_ANGULAR_RATE_IMPLAUSIBLE   (1u << 13) /**< |ω0| > max_vehicle_rate: rejected */
#define UVMS_FLAG_JOINT_RATE_IMPLAUSIBLE     (1u << 14) /**< a |θ̇_i| > max_joint_rate: rejected */
#define UVMS_FLAG_MOTOR_SPEED_IMPLAUSIBLE    (1u << 15) /**< a usable |ω_j| > max_motor_speed:
                                                             rejected */
#define UVMS_FLAG_MOTOR_CURRENT_IMPLAUSIBLE  (1u << 16) /**< a usable |I_j| > max_motor_current:
                                                             rejected */
#define UVMS_FLAG_SENSOR_HELD         (1u << 17) /**< the record was rejected and this tick ran
                                                      on the last good record (status UVMS_OK) */
#define UVMS_FLAG_SENSOR_HOLD_EXPIRED (1u << 18) /**< the record was rejected and may not be
                                                      replaced (no good record yet, hold count
                                                      0, or more than sensor_hold_max_ticks
                                                      consecutive rejections): safe output */
#define UVMS_FLAG_THRUST_SATURATED    (1u << 19) /**< a thrust exceeded limits.thrust_limit_N:
                                                      parts scaled (thrust_scale_pos/att) */
#define UVMS_FLAG_TIME_IMPLAUSIBLE    (1u << 20) /**< time_s jumped: it differs from the time
                                                      the tick implies, t_a + (tick − k_a)·tick_s
                                                      (t_a, k_a: the first accepted record since
                                                      init/reset), by more than
                                                      UVMS_TIME_TOL_TICKS·tick_s +
                                                      UVMS_TIME_TOL_ABS_S +
                                                      UVMS_TIME_TOL_REL·|t|, forward or
                                                      backward: rejected */
#define UVMS_FLAG_INSTANCE_INVALID    (1u << 21) /**< the instance's own counts are corrupt
                                                      (joint or thruster count out of range, or
                                                      its copies, those of the configuration
                                                      it points to included, disagree; or no
                                                      configuration; or the model does not
                                                      point to its arm): nothing is indexed with
                                                      them; status UVMS_ERR_STATE, safe
                                                      output */
#define UVMS_FLAG_ALLOC_FALLBACK      (1u << 22) /**< alloc_mode min_power: the minimum-power
                                                      solver refused or could not run (any
                                                      status but UVMS_OK of
                                                      uvms_alloc_min_power: more than two null
                                                      directions, a numerical breakdown, a P
                                                      it cannot take): this tick used the
                                                      pseudoinverse thrusts P (feasible, same
                                                      wrench), status UVMS_OK */
#define UVMS_FLAG_ALLOC_NOT_CONVERGED (1u << 23) /**< alloc_mode min_power: the solver stopped
                                                      short of the optimum (its iterations ran
                                                      out, or a line search made no progress;
                                                      alloc_power.h): this tick used its last
                                                      iterate (feasible, same wrench, no
                                                      costlier than P), the next tick goes on
                                                      from it; status UVMS_OK */

/** Timestamp plausibility (UVMS_FLAG_TIME_IMPLAUSIBLE): tolerance in ticks, an absolute part
 *  that covers the µs rounding of the SIL's utime, and a part relative to the expected time
 *  that covers the rounding of time_s and of t_a + (tick − k_a)·tick_s in uvms_real_t (four
 *  units of its epsilon: in float, from t ≈ 2^17 s ≈ 36 h on, one ulp of time_s is 15.6 ms,
 *  more than half a tick; without this part every correctly rounded time_s would be refused
 *  from then on). Tolerance = UVMS_TIME_TOL_TICKS·tick_s + UVMS_TIME_TOL_ABS_S +
 *  UVMS_TIME_TOL_REL·|expected|. */
#define UVMS_TIME_TOL_TICKS UVMS_R(0.5)
#define UVMS_TIME_TOL_ABS_S UVMS_R(1.0e-4)
#if UVMS_REAL_IS_FLOAT
#define UVMS_TIME_TOL_REL (4.0f * 1.1920929e-7f) /* 4·2^-23 */
#else
#define UVMS_TIME_TOL_REL (4.0 * 2.220446049250313e-16) /* 4·2^-52 */
#endif

/** Every intermediate quantity a report plots (inertial frame unless named _b). Per-thruster
 *  entries of an unusable thruster (thruster_usable_mask) are zero; quantities a failed tick
 *  did not reach are zero. Every real is finite on every tick: a non-finite sensor time_s is
 *  reported as 0, and a quantity that overflowed (on a failed tick, or a model output of an
 *  absurd but accepted record) reads 0 (docs/FAULTS.md, "Hardening"). */
typedef struct {
  int64_t tick;
  uvms_real_t time_s;
  int32_t status;                                   /**< uvms_status_t of the step */
  uint32_t flags;                                   /**< UVMS_FLAG_* */
  uvms_real_t force_ff_N[3], force_fb_N[3], force_des_N[3];        /**< F_r, F_fb, F_P0 */
  uvms_real_t moment_ff_Nm[3], moment_fb_Nm[3], moment_des_Nm[3]; /**< N_r, N_fb, N_P0 */
  uvms_real_t thrust_des_N[UVMS_MAX_THRUSTERS];     /**< the commanded thrusts [N]: P [38]
                                                         (after the thrust limit); in
                                                         alloc_mode min_power its T */
  uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS];     /**< position part [N]: P_pos = H⁺·(F; 0)
                                                         (scaled by s_pos); in min_power
                                                         T − P_att */
  uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS];     /**< attitude part [N]: P_att = H⁺·(0; N)
                                                         (scaled by s_att), in both modes. The
                                                         parts always sum to thrust_des_N and
                                                         each produces its own wrench (the
                                                         position resp. attitude part of the
                                                         deliverable one); in min_power
                                                         only their sum is least-Σ|T|^1.5 */
  uvms_real_t omega_des_rad_s[UVMS_MAX_THRUSTERS];  /**< ω̂ [57–63] */
  uvms_real_t current_des_A[UVMS_MAX_THRUSTERS];    /**< Î [65] */
  uvms_real_t advance_speed_m_s[UVMS_MAX_THRUSTERS];/**< model v_a */
  uvms_real_t ee_estimate_m[3];       /**< p̂_EE: [3] at (r0d, R0d) or [4] (SPEC §10) */
  uvms_real_t barycenter_m[3];        /**< p_cm from sensed state [5] */
  uvms_real_t barycenter_v_m_s[3];    /**< ṗ_cm from sensed state */
  uvms_real_t position_ref_m[3];      /**< r_d (vehicle or barycenter, captured at start) */
  uvms_real_t attitude_error_rad[3];  /**< φ·e of E = R0d·R0ᵀ [44] */
  uvms_real_t base_force_N[3];        /**< f1 [24] */
  uvms_real_t base_moment_Nm[3];      /**< n1 about the base point [25] */
  uvms_real_t base_accel_model_m_s2[3]; /**< v̇0 assumed by the model (§7) */
  uvms_real_t joint_torque_model_Nm[UVMS_MAX_JOINTS]; /**< τ_i of the model [29] */
  /* Fault handling (docs/FAULTS.md). */
  uvms_real_t force_deliverable_N[3];   /**< R0·(H·P)_force: the force the commanded thrusts
                                             P produce, inertial [N]; equals force_des_N unless
                                             rank loss or the thrust limit cut it; 0 when no
                                             allocation ran this tick. At rank 6 it is computed
                                             as thrust_scale_pos·force_des_N (H·H⁺ = I; in
                                             alloc_mode min_power T delivers H·P to
                                             rounding, in float within ~1e-5·|T|), at
                                             rank < 6 as H·P of the commanded thrusts */
  uvms_real_t moment_deliverable_Nm[3]; /**< R0·(H·P)_moment about the vehicle CoM, inertial
                                             [N·m]; as force_deliverable_N */
  uvms_real_t thrust_scale_pos;         /**< s_pos ∈ [0, 1] applied to P_pos by the thrust
                                             limit (1: none); 0 when no allocation ran */
  uvms_real_t thrust_scale_att;         /**< s_att ∈ (0, 1] applied to P_att; as above */
  uint32_t uncontrollable_axes;         /**< UVMS_AXIS_* bits (Fx Fy Fz Mx My Mz, vehicle
                                             frame) the usable thrusters cannot produce */
  int32_t alloc_rank;                   /**< rank of the usable thrusters' H, 0..6 */
  uint32_t sensor_rejected_ticks;       /**< consecutive rejected records up to and including
                                             this one (0: this record was used) */
} uvms_ctrl_telemetry_t;

/** A controller instance (caller-owned; keep it in static storage on a microcontroller).
 *  Read the fields; change them only through the API.
 *
 *  The instance does not hold its configuration: it points to the caller's (uvms_ctrl_init,
 *  "Configuration lifetime"), which can stay in flash. */
typedef struct {
  const uvms_ctrl_config_t *cfg;    /**< the configuration init validated, caller-owned (NULL
                                         when not ready): every setting is read from it */
  uint32_t cfg_crc32;               /**< CRC-32 of *cfg's bytes at init
                                         (uvms_ctrl_config_verify) */
  uvms_arm_model_t model;           /**< the controller's model of cfg->arm (immutable after
                                         init) */
  uvms_arm_data_t data;             /**< Newton–Euler workspace */
  uvms_alloc_t alloc;               /**< allocation of cfg->thrusters, with H⁺ */
  uvms_cart_traj_t cart;            /**< Cartesian line (cfg->traj_mode CARTESIAN_LINE):
                                         started at reference capture from cart.p, which init
                                         sets to cfg->cart and which is kept while the line is
                                         not running */
  uvms_motor_t motor;               /**< thruster motor loops (cfg->thruster[], model density,
                                         tick) and the integrated current commands I*_j: the
                                         next tick's I*_j = this tick's I*_j + İ*_j·tick_s (0
                                         after a safe output, init and reset: the current
                                         drive's I(t) ends there; SPEC §7.4 [66]) */
  /* Run state */
  int references_captured;          /**< r_d, R0d, q0d captured on the first valid tick */
  uvms_real_t r_d_m[3];             /**< position reference (vehicle CoM or barycenter) [m] */
  uvms_real_t R0d[9];               /**< attitude reference (EE estimate, Cartesian line) */
  uvms_real_t q0d_wxyz[4];          /**< the same attitude reference as the sensed quaternion
                                         it was captured from (attitude feedback [44]) */
  uvms_real_t r0d_m[3];             /**< initial vehicle position (EE estimate [3]) [m] */
  uvms_real_t barycenter0_m[3];     /**< initial barycenter (EE estimate [4]) [m] */
  uvms_real_t q_ref_last_rad[UVMS_MAX_JOINTS]; /**< last good joint reference θ_ref [rad]:
                                       of the last tick whose joint command stood (UVMS_OK or
                                       UVMS_ERR_SINGULAR); θI after init; kept by reset */
  uvms_ctrl_sensors_t last_good;    /**< the last accepted sensor record (held when a record
                                         is rejected; docs/FAULTS.md) */
  int have_last_good;               /**< last_good is valid (0 after init and reset) */
  uint32_t rejected_streak;         /**< consecutive rejected records (saturates) */
  int64_t last_tick;                /**< last tick received in order (accepted or rejected
                                         for its values) */
  int have_last_tick;
  int have_time_anchor;             /**< time_anchor_* hold the first accepted record since
                                         init/reset (TIME_IMPLAUSIBLE check) */
  int64_t time_anchor_tick;         /**< its tick k_a */
  uvms_real_t time_anchor_s;        /**< its time_s t_a [s] */
  uvms_real_t thrust_limit_N[UVMS_MAX_THRUSTERS]; /**< the allocation's limits: cfg's, 0 →
                                         +inf, set by init [N] */
  int thrust_limited;               /**< 1 if a thruster j < n has a limit (cfg entry > 0) */
  uvms_real_t power_weight[UVMS_MAX_THRUSTERS]; /**< min_power's w_j = D_1/D_j (alloc_power.h),
                                         1 for thrusters alike, set by init [1] */
  uvms_real_t ff_lead_s;            /**< lead of the feedforward wrench (the mean uvms_thruster_ramp_lag_s
                                         when cfg->feedforward_lead, else 0) [s] */
  uvms_real_t ff_prev[6];           /**< the last good tick's feedforward force and moment before
                                         the lead, inertial [N, N·m] (lead on) */
  int64_t ff_prev_tick;             /**< the tick of the record it was computed from */
  uvms_real_t ff_slope[6];          /**< its filtered slope (uvms_ff_lead) [N/s, N·m/s] */
  int have_ff_prev;                 /**< ff_prev valid (0 after init, reset and a failed tick) */
  int have_ff_slope;                /**< ff_slope valid (0 also after a gap the lead skips) */
  uvms_power_warm_t power_warm;     /**< the last good tick's minimum-power solution, the warm
                                         start of the next (alloc_mode min_power; zero after
                                         init, reset, a failed tick, or a tick without it) */
  uvms_cfg_field_t config_error;    /**< what init rejected (UVMS_CFG_OK when ready) */
  int ready;
} uvms_ctrl_t;

/**
 * @brief SPEC's paper configuration for one of the cases I–VIII (Table X), 10 kg payload, the
 *        joint cycloid from θI to the case's θF column (uvms_joint_table_deg: "Veh." for a
 *        vehicle reference, "Bary. 10 kg" for a barycenter reference) over 60 s, ρ = 1025, g = 0. The
 *        Cartesian line (unused in this mode) gets the defaults, its reference set to the
 *        case's position reference. Fault handling (limits; not in the paper, see
 *        docs/FAULTS.md for the reasoning): |v0| ≤ 5 m/s, |ω0| ≤ 10 rad/s, |θ̇_i| ≤ 10 rad/s,
 *        |ω_j| ≤ 2·V_lim/km, |I_j| ≤ 2·V_lim/Rm (2e4 rad/s and 2e5 A with the paper's
 *        effectively unlimited supply), ||q| − 1| ≤ 0.05, hold 5 ticks, thrust limit 1e6 N
 *        (effectively unlimited: the paper limits no thrust).
 * @param[out] cfg        the configuration
 * @param[in] case_number 1..8 (I..VIII)
 * @retval UVMS_OK        *cfg = the case's configuration
 * @retval UVMS_ERR_ARG   cfg is NULL; writes: nothing
 * @retval UVMS_ERR_RANGE case outside 1..8; writes: *cfg = case IV's configuration (a valid
 *                        one, identical to uvms_ctrl_config_paper(cfg, 4))
 */
uvms_status_t uvms_ctrl_config_paper(uvms_ctrl_config_t *cfg, int case_number);

/**
 * @brief Validate the whole configuration and prepare the instance (H⁺, model).
 * @param[out] ctrl  instance; not ready on error, with ctrl->config_error naming the part
 * @param[in]  cfg   configuration; on success the instance keeps this pointer (not a copy)
 *
 * Each part of the configuration is checked by the module that owns it (uvms_cfg_field_t
 * names the check), in the uvms_cfg_field_t order; the first part that fails is recorded.
 *
 * Configuration lifetime. The instance reads its settings from *cfg on every step, so:
 *  - *cfg must outlive every use of the instance (static storage, or const data in flash);
 *  - *cfg must not change while the instance is in use. To change the configuration, call
 *    uvms_ctrl_init again with the new one (the instance is reset, as after a first init).
 * A change is not detected by uvms_ctrl_step (a CRC-32 of the whole configuration costs more
 * instructions than the rest of a tick on a Cortex-M4F, docs/BENCHMARKS.md);
 * uvms_ctrl_config_verify compares it with the CRC-32 taken here, for the application to call
 * where it can afford it. What a
 * step indexes with is still checked on every step: the joint and thruster counts read
 * from *cfg must equal the instance's own validated copies, and the model must point to
 * cfg->arm (flag INSTANCE_INVALID), and every
 * loop is bounded by the compile-time maxima, so a changed or corrupted configuration cannot
 * make a step read or write outside its arrays.
 *
 * On every error with ctrl non-NULL: *ctrl all zero (ready = 0, cfg = NULL, so uvms_ctrl_step
 * refuses it with UVMS_ERR_STATE) except config_error, the first part (uvms_cfg_field_t
 * order) that failed.
 * @retval UVMS_OK            ready = 1, config_error = UVMS_CFG_OK, ctrl->cfg = cfg
 * @retval UVMS_ERR_ARG       ctrl or cfg is NULL (writes: nothing, resp. *ctrl all zero with
 *                            config_error = UVMS_CFG_OK), or thrusters.num_thrusters is 0
 *                            (writes: *ctrl all zero, config_error = UVMS_CFG_THRUSTER_GEOMETRY)
 * @retval UVMS_ERR_SIZE      arm.num_joints 0 or above UVMS_MAX_JOINTS (UVMS_CFG_ARM), or
 *                            thrusters.num_thrusters above UVMS_MAX_THRUSTERS
 *                            (UVMS_CFG_THRUSTER_GEOMETRY); writes: *ctrl all zero, config_error
 * @retval UVMS_ERR_NONFINITE a NaN/inf in the part named by config_error (arm, fluid, thruster
 *                            geometry or parameters, gains, joint servo, tick, trajectory,
 *                            limits); writes: *ctrl all zero, config_error
 * @retval UVMS_ERR_RANGE     a value outside its range in the part named by config_error; with
 *                            UVMS_CFG_TRAJECTORY among others a Cartesian line whose
 *                            cart.reference differs from switches.position_reference (SPEC §8:
 *                            the line refers to the vehicle or to the barycenter as the case
 *                            requires); UVMS_CFG_DRIVE, UVMS_CFG_ALLOC_MODE for an unknown
 *                            enumerator; UVMS_CFG_FEEDFORWARD_LEAD (uvms_ff_lead_check); writes: *ctrl all zero, config_error
 * @retval UVMS_ERR_SINGULAR  the thrusters cannot produce every wrench (rank < 6,
 *                            UVMS_CFG_THRUSTER_RANK); writes: *ctrl all zero, config_error
 */
uvms_status_t uvms_ctrl_init(uvms_ctrl_t *ctrl, const uvms_ctrl_config_t *cfg);
#if !defined(UVMS_FIRMWARE_BUILD)
/* Outside the library every call also reads the precision marker (uvms/types.h), so a program
 * built against a header of the other precision fails to link, even with --gc-sections. */
#define uvms_ctrl_init(ctrl, cfg) (uvms_abi_check(), uvms_ctrl_init((ctrl), (cfg)))
#endif

/**
 * @brief Check that the configuration a ready instance points to is unchanged since
 *        uvms_ctrl_init: its bytes still have the CRC-32 taken there (IEEE 802.3 polynomial;
 *        padding bytes included, so rewrite a configuration only through uvms_ctrl_init).
 *        uvms_ctrl_step does not do this (uvms_ctrl_init, "Configuration lifetime"): call it
 *        where the application can afford it, e.g. once per second or in the idle loop, and
 *        stop or initialise again on an error.
 * @param[in] ctrl  the instance
 * Writes nothing (a pure check; it does not stop the instance).
 * @retval UVMS_OK        ready, and *ctrl->cfg unchanged
 * @retval UVMS_ERR_ARG   ctrl is NULL
 * @retval UVMS_ERR_STATE ctrl not ready (not initialised, or refused by init), or *ctrl->cfg
 *                        changed since init
 */
uvms_status_t uvms_ctrl_config_verify(const uvms_ctrl_t *ctrl);

/** @brief Forget captured references, tick history and the held sensor record (the next step
 *         re-captures the references and restarts a Cartesian line). The last good joint
 *         reference is kept; every integrated current command I*_j = 0.
 *  No status: ctrl NULL → nothing. An instance that is not ready is reset all the same (it
 *  stays not ready; uvms_ctrl_step still refuses it). */
void uvms_ctrl_reset(uvms_ctrl_t *ctrl);

/**
 * @brief One controller tick.
 *
 * Stages, in the order data flows (controller.c): sensors (validation, hold-last-good) →
 * thruster set (H⁺ of the usable thrusters) → reference (capture, joint reference, servo) →
 * model (arm model, feedforward) → feedback (PD, Table X) → allocation (thrust limit,
 * deliverable wrench, advance speeds) → thruster loops → estimate (EE estimate, the model's
 * reported quantities) → finish (commit, or the safe output) → publish. The stages pass their
 * results to each other in a work record of the tick (on the stack, not in the instance);
 * the telemetry record is written once, by the publish stage, from that work: no stage reads
 * it, and with tlm NULL it is not written at all.
 *
 * Safe output (one rule for every error return except UVMS_ERR_SINGULAR): every motor
 * voltage, current command and current rate 0 (no motor torque in either drive), θ̈_cmd = 0,
 * θ̇_ref = θ̈_ref = 0, and θ_ref held at the last good reference: that of
 * the last tick whose joint command stood (UVMS_OK or UVMS_ERR_SINGULAR), θI before the first
 * one, 0 if ctrl is NULL or not initialised. The held θ_ref is reported, not servoed: with
 * θ̈_cmd = 0 the joints keep their current rates for that tick.
 *
 * Sensor records (docs/FAULTS.md). A record is rejected when a value is non-finite, the
 * quaternion is not unit (limits.quat_norm_tol), a joint is outside its limits, a speed or
 * current exceeds its plausibility bound (limits), its tick is not above the last one
 * received (out of order/repeated), or its time_s is not the time its tick implies
 * (TIME_IMPLAUSIBLE: t_a + (tick − k_a)·tick_s within UVMS_TIME_TOL_TICKS·tick_s +
 * UVMS_TIME_TOL_ABS_S + UVMS_TIME_TOL_REL·|t|, anchored at the first accepted record since
 * init/reset); each cause
 * sets its own flag, all that apply. A rejected
 * record is not used at all (except its thruster_usable_mask, which can only switch thrusters
 * off). Instead, if a good record has been seen since init/reset and at most
 * limits.sensor_hold_max_ticks consecutive records have been rejected, the tick runs on the
 * last good record, unchanged (including its time, so the joint reference does not advance):
 * flag SENSOR_HELD, status UVMS_OK, outputs those of the held estimate. Otherwise the safe
 * output, flag SENSOR_HOLD_EXPIRED, status NONFINITE (a non-finite value) or RANGE. The next
 * accepted record resumes normal control. A tick gap (TICK_GAP) is reported, and its record
 * used. After a sequence restart (ticks going backwards for good), call uvms_ctrl_reset.
 *
 * Thruster faults: when the usable thrusters span fewer than 6 wrench directions (flag
 * ALLOC_SINGULAR; alloc_rank < 6; uncontrollable_axes names the lost axes), the allocation is
 * the least-squares one (allocation.h): the controllable part of the desired wrench is still
 * produced, the lost directions get nothing, and the step returns UVMS_OK. The arm is not
 * affected. (UVMS_ERR_SINGULAR remains only for an allocation that could not be computed at
 * all: every voltage 0, the joint command normal.)
 *
 * Thrust limit: when limits.thrust_limit_N > 0 and an allocated thrust exceeds it, the position
 * and attitude parts are scaled, attitude first, each keeping its direction
 * (uvms_alloc_saturate; flag THRUST_SATURATED; thrust_scale_pos/att). Telemetry's
 * force/moment_deliverable is the wrench the final thrusts produce, to compare with
 * force/moment_des.
 *
 * Allocation mode (cfg.alloc_mode): the pseudoinverse P above, or (UVMS_ALLOC_MIN_POWER)
 * the least Σ|T_j|^1.5 thrusts T that deliver exactly P's body wrench within |T_j| ≤
 * limits.thrust_limit_N (unlimited when 0): uvms_alloc_min_power after the thrust limit, warm
 * started from the last good tick's solution, so rank loss and attitude-first saturation are
 * those of P, and Σ|T|^1.5 ≤ Σ|P|^1.5. Telemetry: thrust_des_N = T, thrust_att_N = P_att,
 * thrust_pos_N = T − P_att. If the solver cannot run the tick uses P (flag ALLOC_FALLBACK,
 * status UVMS_OK).
 *
 * Current command (SPEC §7.4 [66], §5 current drive): I*_j of this tick is the controller's
 * integrated command, motor.current_cmd_A (I* of the last tick + İ*·tick_s; 0 at start and
 * after a safe output or an idle/unusable thruster), and İ*_j = KB·(Î_j − I_j) uses the
 * measured current, as in the paper. Both drives compute the same loops; the voltage drive
 * uses V_j, the current drive I*_j and İ*_j.
 *
 * Unusable thrusters (bit j of thruster_usable_mask clear): V_j = I*_j = İ*_j = 0, no motor loop, their
 * motor sensors are not read, their telemetry is 0. A trajectory that fails mid-run is not an
 * error: the last good reference is held at rest (θ̇_ref = θ̈_ref = 0), the servo brings the
 * joints to it, the vehicle control goes on, flag TRAJECTORY_FAULT.
 *
 * @param[in,out] ctrl   a ready instance
 * @param[in]  sensors   this tick's measurements
 * @param[out] cmd       actuator command (the safe output above on error)
 * @param[out] tlm       telemetry (may be NULL); status and flags always filled, tick and
 *                       time whenever sensors is not NULL
 * Every error return writes the safe output above into cmd (when non-NULL), sets
 * tlm->status, leaves every telemetry real finite, and the next tick's I*_j = 0.
 * @retval UVMS_OK             the tick's command (also a held record: SENSOR_HELD)
 * @retval UVMS_ERR_ARG        ctrl, sensors or cmd is NULL; writes: the safe output in cmd
 *                             (if non-NULL; θ_ref = 0 when ctrl is NULL), tlm->status (cmd
 *                             NULL: nothing commanded)
 * @retval UVMS_ERR_STATE      ctrl not initialised (writes: the safe output with θ_ref = 0),
 *                             or its joint/thruster counts or its model's parameter
 *                             pointer corrupt (flag INSTANCE_INVALID;
 *                             checked on every step before any use, and every loop is also
 *                             bounded by the compile-time maxima; writes: the safe output), or
 *                             an instance inside ctrl corrupt (allocation not initialised,
 *                             model not ready: flag MODEL_FAULT; writes: the safe output)
 * @retval UVMS_ERR_NONFINITE  rejected record with a NaN/inf value (flag SENSOR_NONFINITE)
 *                             that could not be held (SENSOR_HOLD_EXPIRED; motor sensors count
 *                             only for usable thrusters), or a module failed on an overflow
 *                             (flag MODEL_FAULT: e.g. the desired wrench of an absurd accepted
 *                             record overflows in the allocation); writes: the safe output
 * @retval UVMS_ERR_RANGE      rejected record (quaternion, joint limit, implausible speed or
 *                             current, tick not increasing, time jump) that could not be held
 *                             (SENSOR_HOLD_EXPIRED), or a Cartesian line that could not start at
 *                             reference capture (flag TRAJECTORY_FAULT; retried next tick);
 *                             writes: the safe output
 * @retval UVMS_ERR_SINGULAR   H⁺ of the usable set could not be computed (flag ALLOC_SINGULAR;
 *                             not reachable from a configuration init accepted, only from a
 *                             corrupted allocation instance); writes: every motor voltage,
 *                             current command and rate 0 (thrusters idle), the joint command
 *                             of the tick stands (θ_ref committed as the last good reference)
 */
uvms_status_t uvms_ctrl_step(uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *sensors,
                             uvms_ctrl_command_t *cmd, uvms_ctrl_telemetry_t *tlm);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_CONTROLLER_H */
