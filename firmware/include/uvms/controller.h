/**
 * @file controller.h
 * @brief The station-keeping controller: one caller-owned instance, init(config) then one
 *        step(sensors) per tick (SPEC §7–8). Data flows one way through a tick:
 *
 *   sensors → validate → joint reference (§8) → joint servo → arm model + feedforward (§4, §7.1)
 *           → PD feedback (§7.2) → Table X switches → allocation (§7.3)
 *           → thruster speed/current loops → motor voltages (§7.4) → command + telemetry
 *
 * No dynamic allocation: uvms_ctrl_t holds every buffer, sized by compile-time maxima.
 */
#ifndef UVMS_CONTROLLER_H
#define UVMS_CONTROLLER_H

#include "uvms/allocation.h"
#include "uvms/arm_model.h"
#include "uvms/feedback.h"
#include "uvms/feedforward.h"
#include "uvms/thruster.h"
#include "uvms/trajectory.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Table X of the paper (SPEC §7.2, §9). */
typedef struct {
  int attitude_control;                /**< 1: attitude PD + attitude feedforward */
  uvms_reference_t position_reference; /**< vehicle CoM or barycenter */
  int position_feedforward;            /**< 1: F_r,0 [31] or F_r,cm [32] */
  int position_feedback;               /**< 1: position PD [45] */
} uvms_switches_t;

/** How the joint reference is produced (SPEC §8). */
typedef enum {
  UVMS_TRAJ_HOLD = 0,           /**< hold θ_start */
  UVMS_TRAJ_JOINT_CYCLOID = 1,  /**< cycloid θ_start → θ_final over duration_s */
  UVMS_TRAJ_CARTESIAN_LINE = 2  /**< straight EE line by resolved-rate DLS IK */
} uvms_traj_mode_t;

/** Which part of a configuration uvms_ctrl_init() rejected (uvms_ctrl_t.config_error). */
typedef enum {
  UVMS_CFG_OK = 0,
  UVMS_CFG_ARM,              /**< arm/vehicle/payload parameters (uvms_arm_model_init) */
  UVMS_CFG_FLUID,            /**< model density < 0 or non-finite, flow or gravity non-finite */
  UVMS_CFG_THRUSTER_GEOMETRY,/**< thruster positions/directions invalid */
  UVMS_CFG_THRUSTER_RANK,    /**< thrusters cannot produce every wrench (rank < 6) */
  UVMS_CFG_THRUSTER_PARAMS,  /**< propeller/motor parameters (uvms_thruster_params_validate) */
  UVMS_CFG_GAINS,            /**< PD gains negative or non-finite */
  UVMS_CFG_SWITCHES,         /**< switches not 0/1 or unknown reference */
  UVMS_CFG_JOINT_SERVO,      /**< joint servo gains negative or non-finite */
  UVMS_CFG_TICK,             /**< tick period not > 0 or non-finite */
  UVMS_CFG_TRAJECTORY        /**< trajectory mode, angles, times or Cartesian parameters */
} uvms_cfg_field_t;

/** @brief Name of a configuration field ("arm", "thruster_rank", ...); never NULL. */
const char *uvms_cfg_field_str(uvms_cfg_field_t field);

/** Everything the controller is configured with. uvms_ctrl_config_paper() gives SPEC's. */
typedef struct {
  uvms_arm_params_t arm;                /**< the controller's model of vehicle, arm, payload */
  uvms_fluid_t fluid;                   /**< model density, steady flow v∞0, gravity, AoA */
  uvms_thruster_geometry_t thrusters;   /**< SPEC §3.4 layout */
  uvms_thruster_params_t thruster;      /**< propeller, motor, KA, KB, voltage limit */
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
  uvms_cart_traj_params_t cart;         /**< Cartesian line (its duration_s is tF there) */
} uvms_ctrl_config_t;

/** One tick's sensor record (the firmware's view; the SIL maps LCM messages onto it). */
typedef struct {
  int64_t tick;                                  /**< sequence number k */
  uvms_real_t time_s;                            /**< time since run start [s] */
  uvms_real_t position_m[3];                     /**< r0, inertial [m] */
  uvms_real_t quaternion_wxyz[4];                /**< R0 (vehicle → inertial), scalar first */
  uvms_real_t velocity_m_s[3];                   /**< v0, inertial [m/s] */
  uvms_real_t omega_rad_s[3];                    /**< ω0, inertial [rad/s] */
  uvms_real_t q_rad[UVMS_MAX_JOINTS];            /**< θ [rad] */
  uvms_real_t qd_rad_s[UVMS_MAX_JOINTS];         /**< θ̇ [rad/s] */
  uvms_real_t motor_speed_rad_s[UVMS_MAX_THRUSTERS]; /**< ω_j [rad/s] */
  uvms_real_t motor_current_A[UVMS_MAX_THRUSTERS];   /**< I_j [A] */
  uint32_t thruster_usable_mask;                 /**< bit j = thruster j healthy/usable */
} uvms_ctrl_sensors_t;

/** The actuator command of one tick. */
typedef struct {
  uvms_real_t motor_voltage_V[UVMS_MAX_THRUSTERS];      /**< V_j [V] [53] */
  uvms_real_t joint_accel_cmd_rad_s2[UVMS_MAX_JOINTS];  /**< θ̈_cmd [rad/s²] (§8) */
  uvms_real_t q_ref_rad[UVMS_MAX_JOINTS];               /**< θ_ref [rad] */
  uvms_real_t qd_ref_rad_s[UVMS_MAX_JOINTS];            /**< θ̇_ref [rad/s] */
  uvms_real_t qdd_ref_rad_s2[UVMS_MAX_JOINTS];          /**< θ̈_ref [rad/s²] */
} uvms_ctrl_command_t;

/** Status flags of a tick (uvms_ctrl_telemetry_t.flags). */
#define UVMS_FLAG_SENSOR_NONFINITE    (1u << 0)  /**< a sensor value was NaN/inf: safe output */
#define UVMS_FLAG_QUATERNION_INVALID  (1u << 1)  /**< |q| far from 1: safe output */
#define UVMS_FLAG_ALLOC_SINGULAR      (1u << 2)  /**< usable thrusters have rank < 6 */
#define UVMS_FLAG_VOLTAGE_SATURATED   (1u << 3)  /**< a motor voltage was clamped */
#define UVMS_FLAG_THRUSTERS_IDLE      (1u << 4)  /**< no vehicle control (case I): V = 0 */
#define UVMS_FLAG_TICK_GAP            (1u << 5)  /**< tick > previous + 1 (ticks were lost) */
#define UVMS_FLAG_TICK_NOT_INCREASING (1u << 6)  /**< tick ≤ previous: stale/out of order */
#define UVMS_FLAG_MOTOR_FAULT         (1u << 7)  /**< a thruster's motor loop failed: its V = 0 */
#define UVMS_FLAG_MODEL_FAULT         (1u << 8)  /**< arm model/feedforward failed: safe output */
#define UVMS_FLAG_TRAJECTORY_FAULT    (1u << 9)  /**< trajectory failed: reference held */
#define UVMS_FLAG_REFERENCE_CAPTURED  (1u << 10) /**< this tick captured r_d, R0d (first tick) */
#define UVMS_FLAG_JOINT_LIMIT         (1u << 11) /**< a measured joint is outside its limits */

/** Every intermediate quantity a report plots (inertial frame unless named _b). */
typedef struct {
  int64_t tick;
  uvms_real_t time_s;
  int32_t status;                                   /**< uvms_status_t of the step */
  uint32_t flags;                                   /**< UVMS_FLAG_* */
  uvms_real_t force_ff_N[3], force_fb_N[3], force_des_N[3];        /**< F_r, F_fb, F_P0 */
  uvms_real_t moment_ff_Nm[3], moment_fb_Nm[3], moment_des_Nm[3]; /**< N_r, N_fb, N_P0 */
  uvms_real_t thrust_des_N[UVMS_MAX_THRUSTERS];     /**< P [38] */
  uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS];     /**< P_pos */
  uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS];     /**< P_att */
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
} uvms_ctrl_telemetry_t;

/** A controller instance (caller-owned; keep it in static storage on a microcontroller). */
typedef struct {
  uvms_arm_model_t model;           /**< the controller's model (immutable after init) */
  uvms_arm_data_t data;             /**< Newton–Euler workspace */
  uvms_alloc_t alloc;               /**< allocation with H⁺ */
  uvms_cart_traj_t cart;            /**< Cartesian trajectory state */
  uvms_fluid_t fluid;
  uvms_thruster_params_t thruster;
  uvms_pd_gains_t gains;
  uvms_switches_t switches;
  uvms_real_t joint_kq_1_s2, joint_kqd_1_s, tick_s;
  uvms_traj_mode_t traj_mode;
  uvms_real_t theta_start_rad[UVMS_MAX_JOINTS], theta_final_rad[UVMS_MAX_JOINTS];
  uvms_real_t traj_start_s, traj_duration_s;
  /* Run state */
  int references_captured;          /**< r_d, R0d captured on the first valid tick */
  uvms_real_t r_d_m[3];             /**< position reference (vehicle CoM or barycenter) [m] */
  uvms_real_t R0d[9];               /**< attitude reference */
  uvms_real_t r0d_m[3];             /**< initial vehicle position (EE estimate [3]) [m] */
  uvms_real_t barycenter0_m[3];     /**< initial barycenter (EE estimate [4]) [m] */
  int64_t last_tick;
  int have_last_tick;
  uvms_cfg_field_t config_error;    /**< what init rejected (UVMS_CFG_OK when ready) */
  int ready;
} uvms_ctrl_t;

/**
 * @brief SPEC's paper configuration for one of the cases I–VIII (Table X), 10 kg payload, the
 *        joint cycloid from θI to the case's θF column over 60 s, ρ = 1025, g = 0.
 * @param[in] case_number 1..8 (I..VIII)
 * @retval UVMS_OK, UVMS_ERR_ARG (null), UVMS_ERR_RANGE (case outside 1..8; cfg still gets
 *         case IV's values)
 */
uvms_status_t uvms_ctrl_config_paper(uvms_ctrl_config_t *cfg, int case_number);

/** @brief Table X switches of case 1..8 (I..VIII); UVMS_ERR_RANGE (all off) otherwise. */
uvms_status_t uvms_switches_case(int case_number, uvms_switches_t *sw);

/**
 * @brief Validate the whole configuration and prepare the instance (H⁺, model).
 * @param[out] ctrl  instance; not ready on error, with ctrl->config_error naming the part
 * @param[in]  cfg   configuration (copied)
 * @retval UVMS_OK
 * @retval UVMS_ERR_ARG, UVMS_ERR_NONFINITE, UVMS_ERR_RANGE, UVMS_ERR_SIZE, UVMS_ERR_SINGULAR
 *         as reported by the part named in config_error
 */
uvms_status_t uvms_ctrl_init(uvms_ctrl_t *ctrl, const uvms_ctrl_config_t *cfg);

/** @brief Forget captured references and tick history (the next step re-captures them). */
void uvms_ctrl_reset(uvms_ctrl_t *ctrl);

/**
 * @brief One controller tick.
 * @param[in,out] ctrl   a ready instance
 * @param[in]  sensors   this tick's measurements
 * @param[out] cmd       actuator command; on any error: zero voltages, θ̈_cmd = 0 and the
 *                       reference held at its last value (θ̇_ref = θ̈_ref = 0)
 * @param[out] tlm       telemetry (may be NULL); status and flags always filled
 * @retval UVMS_OK
 * @retval UVMS_ERR_ARG        null pointer
 * @retval UVMS_ERR_STATE      ctrl not initialised
 * @retval UVMS_ERR_NONFINITE  a sensor value is NaN/inf (flag SENSOR_NONFINITE)
 * @retval UVMS_ERR_RANGE      quaternion norm outside [0.5, 1.5] (flag QUATERNION_INVALID)
 * @retval UVMS_ERR_SINGULAR   usable thrusters lost rank (flag ALLOC_SINGULAR): zero voltages
 */
uvms_status_t uvms_ctrl_step(uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *sensors,
                             uvms_ctrl_command_t *cmd, uvms_ctrl_telemetry_t *tlm);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_CONTROLLER_H */
