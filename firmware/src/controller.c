/* SPDX-License-Identifier: Apache-2.0 */
/* controller.c: the controller tick (SPEC §7–8), configuration and validation. */
#include "uvms/controller.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#include "uvms/kinematics.h"
#include "uvms/linalg.h"
#include "fw_fast.h"
#include "thruster_tick.h"

const char *uvms_cfg_field_str(uvms_cfg_field_t field) {
  switch (field) {
    case UVMS_CFG_OK: return "ok";
    case UVMS_CFG_ARM: return "arm";
    case UVMS_CFG_FLUID: return "fluid";
    case UVMS_CFG_THRUSTER_GEOMETRY: return "thruster_geometry";
    case UVMS_CFG_THRUSTER_RANK: return "thruster_rank";
    case UVMS_CFG_THRUSTER_PARAMS: return "thruster_params";
    case UVMS_CFG_GAINS: return "gains";
    case UVMS_CFG_SWITCHES: return "switches";
    case UVMS_CFG_JOINT_SERVO: return "joint_servo";
    case UVMS_CFG_TICK: return "tick";
    case UVMS_CFG_TRAJECTORY: return "trajectory";
    case UVMS_CFG_LIMITS: return "limits";
    case UVMS_CFG_DRIVE: return "drive";
    case UVMS_CFG_ALLOC_MODE: return "alloc_mode";
    case UVMS_CFG_FEEDFORWARD_LEAD: return "feedforward_lead";
    default: return "unknown";
  }
}

uvms_status_t uvms_ctrl_config_paper(uvms_ctrl_config_t *cfg, int case_number) {
  if (cfg == NULL) return UVMS_ERR_ARG;
  memset(cfg, 0, sizeof *cfg);
  uvms_arm_params_paper(&cfg->arm);
  cfg->fluid.density_kg_m3 = UVMS_R(1025.0); /* SPEC §3.2; 1000 under "density error" */
  cfg->fluid.angle_of_attack = 1;
  /* flow (0,0,0) and gravity g = 0 for the paper's experiments (SPEC §6.3). */
  uvms_thruster_geometry_paper(&cfg->thrusters);
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) uvms_thruster_params_paper(&cfg->thruster[j]);
  cfg->alloc_mode = UVMS_ALLOC_PSEUDOINVERSE; /* [38], the paper's allocation */
  cfg->feedforward_lead = 0;                  /* the paper's feedforward, not led */
  uvms_pd_gains_paper(&cfg->gains);
  cfg->joint_kq_1_s2 = UVMS_JOINT_SERVO_KQ_DEFAULT_1_S2;
  cfg->joint_kqd_1_s = UVMS_JOINT_SERVO_KQD_DEFAULT_1_S;
  cfg->tick_s = UVMS_R(0.03);
  cfg->traj_mode = UVMS_TRAJ_JOINT_CYCLOID;
  cfg->traj_start_s = UVMS_R(0.0);
  cfg->traj_duration_s = UVMS_R(60.0);
  uvms_cart_traj_params_default(&cfg->cart);
  const uvms_status_t st = uvms_switches_case(case_number, &cfg->switches);
  if (st != UVMS_OK) (void)uvms_switches_case(4, &cfg->switches);
  /* A Cartesian line must refer to the point the case holds (SPEC §8; checked by init). */
  cfg->cart.reference = cfg->switches.position_reference;
  /* SPEC §8 table: θI; θF "Veh." for vehicle reference, "Bary. 10 kg" for barycenter. */
  const uvms_real_t *start = uvms_joint_table_deg(UVMS_JOINT_TABLE_START);
  const uvms_real_t *fin = uvms_joint_table_deg(cfg->switches.position_reference ==
                                                        UVMS_REF_BARYCENTER
                                                    ? UVMS_JOINT_TABLE_BARY_10KG
                                                    : UVMS_JOINT_TABLE_VEHICLE);
  const uvms_real_t deg = UVMS_PI / UVMS_R(180.0);
  for (int j = 0; j < UVMS_JOINT_TABLE_JOINTS; ++j) {
    cfg->theta_start_rad[j] = start[j] * deg;
    cfg->theta_final_rad[j] = fin[j] * deg;
  }
  /* Fault handling (docs/FAULTS.md). Not in the paper; bounds that only physically impossible
     readings exceed, so that they never trip in its runs:
     - 5 m/s, 10 rad/s: no vehicle of this size (120 kg, SPEC §3.2) moves or turns that fast;
     - 10 rad/s per joint: several times any WAM joint's top speed (the paper's cycloids peak
       at 2·Δθ/tF < 0.1 rad/s);
     - motor: with |V| ≤ V_lim the no-load speed is V_lim/km and the stall current V_lim/Rm; a
       factor 2 covers back-EMF adding to the supply in transients;
     - quaternion: the plant's is unit to rounding, so 5 % is a broken record, not noise;
     - hold 5 ticks (0.15 s at the paper's tick): a few lost or corrupt records ride through,
       a dead sensor stops the thrusters within a fraction of a second;
     - thrust 1e6 N: effectively unlimited, like the voltage limit (thruster.h). */
  uvms_ctrl_limits_t *lim = &cfg->limits;
  lim->max_vehicle_speed_m_s = UVMS_R(5.0);
  lim->max_vehicle_rate_rad_s = UVMS_R(10.0);
  lim->max_joint_rate_rad_s = UVMS_R(10.0);
  lim->max_motor_speed_rad_s =
      UVMS_R(2.0) * cfg->thruster[0].voltage_limit_V / cfg->thruster[0].torque_constant_Nm_A;
  lim->max_motor_current_A =
      UVMS_R(2.0) * cfg->thruster[0].voltage_limit_V / cfg->thruster[0].resistance_ohm;
  lim->quat_norm_tol = UVMS_R(0.05);
  lim->sensor_hold_max_ticks = 5u;
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) lim->thrust_limit_N[j] = UVMS_R(1.0e6);
  return st;
}

/* ---------------------------------------------------------------------------------------- */
/* Configuration: one check per part, in the order init applies them (uvms_cfg_field_t).     */
/* Each module checks the part it owns (arm_model.c: arm and fluid; allocation.c: thruster   */
/* geometry, allocation mode and thrust limit; thruster.c: motor parameters and drive;       */
/* feedback.c: PD gains and Table X switches; trajectory.c: joint servo gains and the         */
/* Cartesian line); the controller checks its own: tick, trajectory selection, sensor limits. */

/* Tick period: finite and > 0. */
static uvms_status_t tick_check(uvms_real_t tick_s) {
  if (!uvms_isfinite(tick_s)) return UVMS_ERR_NONFINITE;
  return (tick_s > UVMS_R(0.0)) ? UVMS_OK : UVMS_ERR_RANGE;
}

/* Trajectory: mode, finite angles and times, the mode's own parameters (a Cartesian line is
   tried at the start pose in ctrl->cart, with the model already built), and a start pose
   inside the joint limits (outside, the sensor check would reject every tick). */
static uvms_status_t trajectory_check(uvms_ctrl_t *ctrl, const uvms_ctrl_config_t *cfg) {
  const size_t n = cfg->arm.num_joints; /* validated by the arm check */
  if (!uvms_all_finite(cfg->theta_start_rad, n) || !uvms_all_finite(cfg->theta_final_rad, n) ||
      !uvms_isfinite(cfg->traj_start_s) || !uvms_isfinite(cfg->traj_duration_s))
    return UVMS_ERR_NONFINITE;
  if (cfg->traj_mode == UVMS_TRAJ_JOINT_CYCLOID) {
    if (!(cfg->traj_duration_s > UVMS_R(0.0))) return UVMS_ERR_RANGE;
  } else if (cfg->traj_mode == UVMS_TRAJ_CARTESIAN_LINE) {
    /* SPEC §8: the line is referenced to the vehicle or to the barycenter "as the case
       requires", i.e. to the point the position loop holds; anything else would move the EE
       along a line that the vehicle (or the barycenter) is not kept still for. */
    if (cfg->cart.reference != cfg->switches.position_reference) return UVMS_ERR_RANGE;
    const uvms_real_t origin[3] = {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0)};
    uvms_real_t I3[9];
    uvms_m3_identity(I3);
    const uvms_status_t st = uvms_cart_traj_init(&ctrl->cart, &cfg->cart, &ctrl->model,
                                                 &ctrl->data, cfg->theta_start_rad, origin, I3);
    if (st != UVMS_OK) return st;
  } else if (cfg->traj_mode != UVMS_TRAJ_HOLD) {
    return UVMS_ERR_RANGE;
  }
  for (size_t j = 0; j < n && j < UVMS_MAX_JOINTS; ++j) {
    const uvms_link_params_t *L = &cfg->arm.link[j];
    if (cfg->theta_start_rad[j] < L->joint_min_rad || cfg->theta_start_rad[j] > L->joint_max_rad)
      return UVMS_ERR_RANGE;
  }
  return UVMS_OK;
}

/* Sensor plausibility settings (the sensor stage's): each bound finite and ≥ 0 (0 = check
   off), the quaternion tolerance at most 0.5 (beyond it the fixed [0.5, 1.5] check decides),
   the hold count bounded. */
static uvms_status_t sensor_limits_check(const uvms_ctrl_limits_t *l) {
  const uvms_real_t v[6] = {l->max_vehicle_speed_m_s, l->max_vehicle_rate_rad_s,
                            l->max_joint_rate_rad_s,  l->max_motor_speed_rad_s,
                            l->max_motor_current_A,   l->quat_norm_tol};
  if (!uvms_all_finite(v, 6)) return UVMS_ERR_NONFINITE;
  for (int k = 0; k < 6; ++k)
    if (v[k] < UVMS_R(0.0)) return UVMS_ERR_RANGE;
  if (l->quat_norm_tol > UVMS_R(0.5)) return UVMS_ERR_RANGE;
  if (l->sensor_hold_max_ticks > UVMS_SENSOR_HOLD_MAX_TICKS_LIMIT) return UVMS_ERR_RANGE;
  return UVMS_OK;
}

/* The limits part: the sensor settings and the thrust limit (allocation.c). A NaN/inf in
   either reports UVMS_ERR_NONFINITE before any range error, as for every other part. */
static uvms_status_t limits_check(const uvms_ctrl_limits_t *l) {
  const uvms_status_t sensors = sensor_limits_check(l);
  uvms_status_t thrust = UVMS_OK; /* NONFINITE of any entry first, else the first error */
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    const uvms_status_t st = uvms_alloc_thrust_limit_check(l->thrust_limit_N[j]);
    if (st == UVMS_ERR_NONFINITE) thrust = st;
    else if (thrust == UVMS_OK) thrust = st;
  }
  if (sensors == UVMS_ERR_NONFINITE || thrust == UVMS_ERR_NONFINITE) return UVMS_ERR_NONFINITE;
  return (sensors != UVMS_OK) ? sensors : thrust;
}

/* The thruster parameters: each of the num_thrusters sets (count checked by
   uvms_alloc_init before). */
static uvms_status_t thruster_params_check(const uvms_ctrl_config_t *cfg) {
  for (size_t j = 0; j < cfg->thrusters.num_thrusters && j < UVMS_MAX_THRUSTERS; ++j) {
    const uvms_status_t st = uvms_thruster_params_validate(&cfg->thruster[j]);
    if (st != UVMS_OK) return st;
  }
  return UVMS_OK;
}

/* Checks every part of cfg in the uvms_cfg_field_t order, building the model and the
   allocation in ctrl on the way; returns the first part that fails (its status in *st), or
   UVMS_CFG_OK. */
static uvms_cfg_field_t config_validate(uvms_ctrl_t *ctrl, const uvms_ctrl_config_t *cfg,
                                        uvms_status_t *st) {
  *st = uvms_arm_model_init(&cfg->arm, &ctrl->model);
  if (*st != UVMS_OK) return UVMS_CFG_ARM;
  *st = uvms_fluid_check(&cfg->fluid);
  if (*st != UVMS_OK) return UVMS_CFG_FLUID;
  *st = uvms_alloc_init(&ctrl->alloc, &cfg->thrusters);
  if (*st == UVMS_ERR_SINGULAR) return UVMS_CFG_THRUSTER_RANK;
  if (*st != UVMS_OK) return UVMS_CFG_THRUSTER_GEOMETRY;
  *st = thruster_params_check(cfg);
  if (*st != UVMS_OK) return UVMS_CFG_THRUSTER_PARAMS;
  *st = uvms_pd_gains_check(&cfg->gains);
  if (*st != UVMS_OK) return UVMS_CFG_GAINS;
  *st = uvms_switches_check(&cfg->switches);
  if (*st != UVMS_OK) return UVMS_CFG_SWITCHES;
  *st = uvms_joint_servo_gains_check(cfg->joint_kq_1_s2, cfg->joint_kqd_1_s);
  if (*st != UVMS_OK) return UVMS_CFG_JOINT_SERVO;
  *st = tick_check(cfg->tick_s);
  if (*st != UVMS_OK) return UVMS_CFG_TICK;
  *st = trajectory_check(ctrl, cfg);
  if (*st != UVMS_OK) return UVMS_CFG_TRAJECTORY;
  *st = limits_check(&cfg->limits);
  if (*st != UVMS_OK) return UVMS_CFG_LIMITS;
  *st = uvms_drive_check(cfg->drive);
  if (*st != UVMS_OK) return UVMS_CFG_DRIVE;
  *st = uvms_alloc_mode_check(cfg->alloc_mode);
  if (*st != UVMS_OK) return UVMS_CFG_ALLOC_MODE;
  *st = uvms_ff_lead_check(cfg->feedforward_lead, cfg->drive);
  if (*st != UVMS_OK) return UVMS_CFG_FEEDFORWARD_LEAD;
  return UVMS_CFG_OK;
}


/* The feedforward's lead (docs/MODEL.md §7.5): the mean of the thrusters' ramp lags, taken
   about thruster 1's (so exactly its lag when every thruster has the same chain). */
static uvms_real_t ramp_lag_mean_s(const uvms_ctrl_config_t *cfg) {
  const size_t n = cfg->thrusters.num_thrusters;
  const uvms_real_t lag0_s = uvms_thruster_ramp_lag_s(&cfg->thruster[0]);
  uvms_real_t excess_s = UVMS_R(0.0);
  for (size_t j = 1; j < n && j < UVMS_MAX_THRUSTERS; ++j)
    excess_s += uvms_thruster_ramp_lag_s(&cfg->thruster[j]) - lag0_s;
  return lag0_s + excess_s / (uvms_real_t)n;
}

/* The allocation's per-thruster limits from cfg (0: none → +inf), whether any of the n
   thrusters has one (the saturation then runs each tick), and min_power's weights. */
static void thrust_limits_set(uvms_ctrl_t *ctrl, const uvms_ctrl_config_t *cfg) {
  const size_t n = cfg->thrusters.num_thrusters;
  ctrl->thrust_limited = 0;
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    const uvms_real_t limit_N = cfg->limits.thrust_limit_N[j];
    ctrl->thrust_limit_N[j] = (limit_N > UVMS_R(0.0)) ? limit_N : (uvms_real_t)INFINITY;
    if (j < n && limit_N > UVMS_R(0.0)) ctrl->thrust_limited = 1;
  }
  /* Diameters validated by init before: cannot fail. */
  (void)uvms_power_weights(cfg->thruster, n, ctrl->power_weight);
}

/* CRC-32 (IEEE 802.3, reflected, as zlib's crc32) of n bytes, four bits per step from a
   16-entry table. Used at init and by uvms_ctrl_config_verify, never per tick. */
static uint32_t crc32_bytes(const void *data, size_t n) {
  static const uint32_t kNibble[16] = {
      0x00000000u, 0x1DB71064u, 0x3B6E20C8u, 0x26D930ACu, 0x76DC4190u, 0x6B6B51F4u,
      0x4DB26158u, 0x5005713Cu, 0xEDB88320u, 0xF00F9344u, 0xD6D6A3E8u, 0xCB61B38Cu,
      0x9B64C2B0u, 0x86D3D2D4u, 0xA00AE278u, 0xBDBDF21Cu};
  const unsigned char *b = (const unsigned char *)data;
  uint32_t crc = 0xFFFFFFFFu;
  for (size_t i = 0; i < n; ++i) {
    crc ^= b[i];
    crc = (crc >> 4) ^ kNibble[crc & 0x0Fu];
    crc = (crc >> 4) ^ kNibble[crc & 0x0Fu];
  }
  return crc ^ 0xFFFFFFFFu;
}

static uvms_status_t fail_cfg(uvms_ctrl_t *ctrl, uvms_cfg_field_t field, uvms_status_t st) {
  memset(ctrl, 0, sizeof *ctrl);
  ctrl->config_error = field;
  return st;
}

uvms_status_t uvms_ctrl_init(uvms_ctrl_t *ctrl, const uvms_ctrl_config_t *cfg) {
  if (ctrl == NULL) return UVMS_ERR_ARG;
  memset(ctrl, 0, sizeof *ctrl);
  if (cfg == NULL) return UVMS_ERR_ARG;
  uvms_status_t st = UVMS_OK;
  const uvms_cfg_field_t bad = config_validate(ctrl, cfg, &st);
  if (bad != UVMS_CFG_OK) return fail_cfg(ctrl, bad, st);
  ctrl->cfg = cfg; /* caller-owned: uvms_ctrl_init's lifetime rule (controller.h) */
  ctrl->cfg_crc32 = crc32_bytes(cfg, sizeof *cfg);
  /* Parameters, density and tick validated above: cannot fail. */
  (void)uvms_motor_init_each(&ctrl->motor, cfg->thruster, cfg->thrusters.num_thrusters,
                             cfg->fluid.density_kg_m3, cfg->tick_s);
  ctrl->ff_lead_s = cfg->feedforward_lead ? ramp_lag_mean_s(cfg) : UVMS_R(0.0);
  thrust_limits_set(ctrl, cfg);
  /* The line is started at the first tick with the captured pose, from cart.p (not ready
     until then; the capture restores p when uvms_cart_traj_init fails and zeroes it). */
  memset(&ctrl->cart, 0, sizeof ctrl->cart);
  ctrl->cart.p = cfg->cart;
  for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) ctrl->q_ref_last_rad[j] = cfg->theta_start_rad[j];
  ctrl->config_error = UVMS_CFG_OK;
  ctrl->ready = 1;
  return UVMS_OK;
}

uvms_status_t uvms_ctrl_config_verify(const uvms_ctrl_t *ctrl) {
  if (ctrl == NULL) return UVMS_ERR_ARG;
  if (!ctrl->ready || ctrl->cfg == NULL) return UVMS_ERR_STATE;
  return (crc32_bytes(ctrl->cfg, sizeof *ctrl->cfg) == ctrl->cfg_crc32) ? UVMS_OK
                                                                         : UVMS_ERR_STATE;
}

/* Forget what carries from one tick to the next in the feedforward lead and the allocation's
   warm start: both start afresh (after a reset, and after a failed tick). */
static void forget_tick_history(uvms_ctrl_t *ctrl) {
  ctrl->have_ff_prev = 0; /* the lead differentiates within one run of good ticks only */
  memset(&ctrl->power_warm, 0, sizeof ctrl->power_warm); /* the allocation starts cold */
}

void uvms_ctrl_reset(uvms_ctrl_t *ctrl) {
  if (ctrl == NULL) return;
  /* q_ref_last_rad is kept: it is the reference the arm was last commanded, which is what an
     error before the next good tick must hold (controller.h). */
  ctrl->references_captured = 0;
  ctrl->have_last_tick = 0;
  ctrl->last_tick = 0;
  ctrl->have_last_good = 0; /* a record of the old sequence must not stand in for the new */
  ctrl->have_time_anchor = 0; /* the new sequence's clock is anchored afresh */
  ctrl->rejected_streak = 0u;
  forget_tick_history(ctrl);
  uvms_motor_reset(&ctrl->motor);
}

/* ---------------------------------------------------------------------------------------- */
/* The tick (uvms_ctrl_step): stages in the order data flows, each reading what the ones     */
/* before it left in the tick's work (tick_t, on the stack of uvms_ctrl_step) and writing    */
/* its own results there; the command record receives the joint and motor commands; the     */
/* telemetry record is written once, at the end, from the work (stage_publish_telemetry).   */

/* What the tick reports, each group written by the stage named. Its layout is that of
   uvms_ctrl_telemetry_t from force_ff_N on (checked below), so that the telemetry is published
   with one block copy. Cleared at the start of every tick: a quantity whose stage was not
   reached reads 0. */
typedef struct {
  /* feedback: the desired wrench [46], [41] and its parts, inertial */
  uvms_real_t force_ff_N[3], force_fb_N[3], force_des_N[3];
  uvms_real_t moment_ff_Nm[3], moment_fb_Nm[3], moment_des_Nm[3];
  /* allocation: the commanded thrusts P (or T) and their parts */
  uvms_real_t thrust_des_N[UVMS_MAX_THRUSTERS];
  uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS];
  uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS];
  /* thruster loops: desired speed and current of each loop that ran */
  uvms_real_t omega_des_rad_s[UVMS_MAX_THRUSTERS];
  uvms_real_t current_des_A[UVMS_MAX_THRUSTERS];
  /* allocation: the thrusters' advance speeds */
  uvms_real_t advance_speed_m_s[UVMS_MAX_THRUSTERS];
  /* estimate: p̂_EE and the model's quantities (when the model stage succeeded) */
  uvms_real_t ee_estimate_m[3], barycenter_m[3], barycenter_v_m_s[3], position_ref_m[3];
  uvms_real_t attitude_error_rad[3]; /* feedback: φ·e [44] */
  uvms_real_t base_force_N[3], base_moment_Nm[3], base_accel_model_m_s2[3];
  uvms_real_t joint_torque_model_Nm[UVMS_MAX_JOINTS];
  /* allocation: the wrench the thrusts deliver, the thrust limit's scales */
  uvms_real_t force_deliverable_N[3], moment_deliverable_Nm[3];
  uvms_real_t thrust_scale_pos, thrust_scale_att;
  /* thruster set: what the usable thrusters cannot produce, their rank */
  uint32_t uncontrollable_axes;
  int32_t alloc_rank;
  uint32_t sensor_rejected_ticks; /* sensors: consecutive rejected records */
} tick_report_t;

/* tick_report_t is uvms_ctrl_telemetry_t from force_ff_N on, field for field. */
#define TLM_AT(f) (offsetof(uvms_ctrl_telemetry_t, f) - offsetof(uvms_ctrl_telemetry_t, force_ff_N))
#define SAME_PLACE(f) \
  _Static_assert(offsetof(tick_report_t, f) == TLM_AT(f), "tick_report_t mirrors telemetry: " #f)
SAME_PLACE(force_fb_N); SAME_PLACE(force_des_N); SAME_PLACE(moment_ff_Nm);
SAME_PLACE(moment_fb_Nm); SAME_PLACE(moment_des_Nm); SAME_PLACE(thrust_des_N);
SAME_PLACE(thrust_pos_N); SAME_PLACE(thrust_att_N); SAME_PLACE(omega_des_rad_s);
SAME_PLACE(current_des_A); SAME_PLACE(advance_speed_m_s); SAME_PLACE(ee_estimate_m);
SAME_PLACE(barycenter_m); SAME_PLACE(barycenter_v_m_s); SAME_PLACE(position_ref_m);
SAME_PLACE(attitude_error_rad); SAME_PLACE(base_force_N); SAME_PLACE(base_moment_Nm);
SAME_PLACE(base_accel_model_m_s2); SAME_PLACE(joint_torque_model_Nm);
SAME_PLACE(force_deliverable_N); SAME_PLACE(moment_deliverable_Nm); SAME_PLACE(thrust_scale_pos);
SAME_PLACE(thrust_scale_att); SAME_PLACE(uncontrollable_axes); SAME_PLACE(alloc_rank);
SAME_PLACE(sensor_rejected_ticks);
/* ... and nothing else: the header (tick, time_s, status, flags) ends where force_ff_N starts,
   and the report ends the record (a field added anywhere else changes a size below). */
#define ROUND_UP(x, a) (((x) + (a) - 1u) / (a) * (a))
_Static_assert(offsetof(uvms_ctrl_telemetry_t, force_ff_N) ==
                   ROUND_UP(offsetof(uvms_ctrl_telemetry_t, flags) + sizeof(uint32_t),
                            _Alignof(uvms_real_t)),
               "a telemetry field before force_ff_N: publish it in stage_publish_telemetry");
_Static_assert(sizeof(uvms_ctrl_telemetry_t) ==
                   ROUND_UP(offsetof(uvms_ctrl_telemetry_t, force_ff_N) + sizeof(tick_report_t),
                            _Alignof(uvms_ctrl_telemetry_t)),
               "a telemetry field not in tick_report_t: add it there");
#undef ROUND_UP
#undef SAME_PLACE
#undef TLM_AT

/* The tick's work: what its stages pass on to the next ones, and what it reports. */
typedef struct {
  const uvms_ctrl_sensors_t *S; /* the record this tick runs on: the controller's copy of the
                                   one received (ctrl->last_good) or, when that was rejected,
                                   the held last good one */
  uint32_t usable;              /* thrusters usable this tick (bit j) */
  uvms_base_state_t base;       /* vehicle state of S */
  uvms_status_t alloc_st;       /* H⁺ of the usable set: UVMS_OK, or UVMS_ERR_SINGULAR when it
                                   could not be computed (no vehicle control, arm still runs) */
  uvms_feedforward_t ff;        /* arm model and feedforward (valid when model_ok) */
  uvms_real_t ff_unled[6];      /* the feedforward force [N] and moment [N·m] before the lead,
                                   inertial (stage_feedback; the next tick's lead
                                   differentiates against it) */
  uvms_real_t ff_slope[6];      /* its filtered slope after this tick [N/s, N·m/s] (lead) */
  int ff_slope_ok;              /* ff_slope was updated this tick */
  uvms_power_warm_t power_warm; /* the minimum-power solution of this tick, the next one's warm
                                   start (alloc_mode min_power; cleared when none) */
  int model_ok;                 /* the model stage succeeded: its quantities may be reported */
  int thrusters_on;             /* the allocation ran: the thruster loops run */
  int rep_nonfinite;            /* a reported real may be non-finite (made 0 when published) */
  uvms_status_t status;         /* the tick's status if no stage fails: UVMS_OK, or
                                   UVMS_ERR_SINGULAR (see alloc_st) */
  int64_t tick;                 /* the record's tick (begin) */
  uvms_real_t time_s;           /* its time, 0 when not finite (begin) */
  uint32_t flags;               /* UVMS_FLAG_* (every stage) */
  tick_report_t rep;            /* what the tick reports */
} tick_t;

/* Per-thruster outputs of one tick: motor voltage, current command and its rate 0 (no motor
   torque in either drive) and the motor-loop results 0 (no loop ran for thruster j). Used for
   unusable thrusters and on every exit that idles the thrusters. */
static void thruster_off(size_t j, uvms_ctrl_command_t *cmd, tick_report_t *out) {
  cmd->motor_voltage_V[j] = UVMS_R(0.0);
  cmd->motor_current_cmd_A[j] = UVMS_R(0.0);
  cmd->motor_current_rate_A_s[j] = UVMS_R(0.0);
  out->omega_des_rad_s[j] = UVMS_R(0.0);
  out->current_des_A[j] = UVMS_R(0.0);
}

/*
 * The one safe output of uvms_ctrl_step (controller.h), written on entry and by every error
 * exit: every motor voltage 0 (and its loop results 0), θ̈_cmd = 0, θ̇_ref = θ̈_ref = 0 and
 * θ_ref = the last good reference (θI before the first good tick; 0 when ctrl is NULL or not
 * initialised, when no reference is known). Returns status.
 */
/* The safe command alone (cmd != NULL): all zero but θ_ref = the last good reference. */
static void safe_command(const uvms_ctrl_t *ctrl, uvms_ctrl_command_t *cmd) {
  uvms_clear_record(cmd, sizeof *cmd);
  if (ctrl != NULL && ctrl->ready)
    for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) cmd->joint_ref_rad[j] = ctrl->q_ref_last_rad[j];
}

static uvms_status_t fail_safe(const uvms_ctrl_t *ctrl, uvms_ctrl_command_t *cmd, tick_t *k,
                               uvms_status_t status) {
  if (cmd != NULL) {
    safe_command(ctrl, cmd);
    for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) thruster_off(j, cmd, &k->rep);
  }
  return status;
}

/* The tick's joint command stands (UVMS_OK, or UVMS_ERR_SINGULAR: controller.h): its
   reference becomes the last good one. */
static void commit_reference(uvms_ctrl_t *ctrl, const uvms_ctrl_command_t *cmd) {
  for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) ctrl->q_ref_last_rad[j] = cmd->joint_ref_rad[j];
}

/* bound > 0 (the check is on) and value above it. */
static int exceeds(uvms_real_t value, uvms_real_t bound) {
  return bound > UVMS_R(0.0) && value > bound;
}

/* A bound of 0 (check off) as +inf, so that |x| > bound is one comparison. */
static uvms_real_t bound_or_inf(uvms_real_t bound) {
  return (bound > UVMS_R(0.0)) ? bound : (uvms_real_t)INFINITY;
}

/* The bound flags of a record as if all its values were finite (then they are the flags
   sensors_bounds_general gives it), and in *probe the sum of 0·x over every value read. */
static uint32_t sensors_bounds_finite(const uvms_ctrl_t *ctrl, size_t n, size_t nt,
                                      const uvms_ctrl_sensors_t *s, uint32_t usable,
                                      uvms_real_t *probe) {
  const uvms_ctrl_limits_t *lim = &ctrl->cfg->limits;
  uint32_t f = 0u;
  uvms_real_t pr = UVMS_R(0.0) * s->time_s;
  pr = uvms_nonfinite_probe(s->position_m, 3, pr);
  pr = uvms_nonfinite_probe(s->quaternion_wxyz, 4, pr);
  pr = uvms_nonfinite_probe(s->velocity_m_s, 3, pr);
  pr = uvms_nonfinite_probe(s->angular_velocity_rad_s, 3, pr);
  const uvms_real_t qd_max = bound_or_inf(lim->max_joint_rate_rad_s);
  for (size_t j = 0; j < n && j < UVMS_MAX_JOINTS; ++j) {
    const uvms_link_params_t *L = &ctrl->model.p->link[j];
    const uvms_real_t q_rad = s->joint_position_rad[j], qd_rad_s = s->joint_velocity_rad_s[j];
    pr += UVMS_R(0.0) * q_rad + UVMS_R(0.0) * qd_rad_s;
    if (q_rad < L->joint_min_rad || q_rad > L->joint_max_rad) f |= UVMS_FLAG_JOINT_LIMIT;
    if (uvms_fabs(qd_rad_s) > qd_max) f |= UVMS_FLAG_JOINT_RATE_IMPLAUSIBLE;
  }
  const uvms_real_t w_max = bound_or_inf(lim->max_motor_speed_rad_s);
  const uvms_real_t i_max = bound_or_inf(lim->max_motor_current_A);
  for (size_t j = 0; j < nt && j < UVMS_MAX_THRUSTERS; ++j) {
    if (((usable >> j) & 1u) == 0u) continue;
    const uvms_real_t w_rad_s = s->motor_speed_rad_s[j], i_A = s->motor_current_A[j];
    pr += UVMS_R(0.0) * w_rad_s + UVMS_R(0.0) * i_A;
    if (uvms_fabs(w_rad_s) > w_max) f |= UVMS_FLAG_MOTOR_SPEED_IMPLAUSIBLE;
    if (uvms_fabs(i_A) > i_max) f |= UVMS_FLAG_MOTOR_CURRENT_IMPLAUSIBLE;
  }
  *probe = pr;
  /* Speeds compared squared (no square root); an overflowing |v|² is +inf > bound²: still
     caught. */
  const uvms_real_t vmax = lim->max_vehicle_speed_m_s, wmax = lim->max_vehicle_rate_rad_s;
  if (exceeds(uvms_v3_dot(s->velocity_m_s, s->velocity_m_s), vmax * vmax))
    f |= UVMS_FLAG_VEHICLE_SPEED_IMPLAUSIBLE;
  if (exceeds(uvms_v3_dot(s->angular_velocity_rad_s, s->angular_velocity_rad_s), wmax * wmax))
    f |= UVMS_FLAG_ANGULAR_RATE_IMPLAUSIBLE;
  return f;
}

/* The bound flags of a record with a NaN/inf somewhere: each bound is checked on finite values
   only (NaN fails no limit comparison; an infinite rate is SENSOR_NONFINITE only, so the rate
   bound asks for finiteness last). */
static uint32_t sensors_bounds_general(const uvms_ctrl_t *ctrl, size_t n, size_t nt,
                                       const uvms_ctrl_sensors_t *s, uint32_t usable) {
  const uvms_ctrl_limits_t *lim = &ctrl->cfg->limits;
  uint32_t f = 0u;
  const uvms_real_t qd_max = lim->max_joint_rate_rad_s;
  for (size_t j = 0; j < n && j < UVMS_MAX_JOINTS; ++j) {
    const uvms_link_params_t *L = &ctrl->model.p->link[j];
    const uvms_real_t q_rad = s->joint_position_rad[j], qd_rad_s = s->joint_velocity_rad_s[j];
    if (q_rad < L->joint_min_rad || q_rad > L->joint_max_rad) f |= UVMS_FLAG_JOINT_LIMIT;
    if (exceeds(uvms_fabs(qd_rad_s), qd_max) && uvms_isfinite(qd_rad_s))
      f |= UVMS_FLAG_JOINT_RATE_IMPLAUSIBLE;
  }
  for (size_t j = 0; j < nt && j < UVMS_MAX_THRUSTERS; ++j) {
    if (((usable >> j) & 1u) == 0u) continue;
    const uvms_real_t w_rad_s = s->motor_speed_rad_s[j], i_A = s->motor_current_A[j];
    const uvms_real_t pj = UVMS_R(0.0) * w_rad_s + UVMS_R(0.0) * i_A;
    if (exceeds(uvms_fabs(w_rad_s), lim->max_motor_speed_rad_s) && pj == UVMS_R(0.0))
      f |= UVMS_FLAG_MOTOR_SPEED_IMPLAUSIBLE;
    if (exceeds(uvms_fabs(i_A), lim->max_motor_current_A) && pj == UVMS_R(0.0))
      f |= UVMS_FLAG_MOTOR_CURRENT_IMPLAUSIBLE;
  }
  /* For finite components an overflowing |v|² is +inf > bound²: still caught. */
  const uvms_real_t vmax = lim->max_vehicle_speed_m_s, wmax = lim->max_vehicle_rate_rad_s;
  if (exceeds(uvms_v3_dot(s->velocity_m_s, s->velocity_m_s), vmax * vmax) &&
      uvms_v3_isfinite(s->velocity_m_s))
    f |= UVMS_FLAG_VEHICLE_SPEED_IMPLAUSIBLE;
  if (exceeds(uvms_v3_dot(s->angular_velocity_rad_s, s->angular_velocity_rad_s), wmax * wmax) &&
      uvms_v3_isfinite(s->angular_velocity_rad_s))
    f |= UVMS_FLAG_ANGULAR_RATE_IMPLAUSIBLE;
  return f;
}

/*
 * Validation of one record (docs/FAULTS.md): every cause that applies sets its flag; returns
 * UVMS_ERR_NONFINITE if any value is NaN/inf, else UVMS_ERR_RANGE if any other check failed,
 * else UVMS_OK. Motor speed and current are checked for usable thrusters only: an unusable
 * thruster's sensors are not read at all (its loop does not run), so a failed one cannot stop
 * the rest. The plausibility bounds apply to finite values only, so that a non-finite value
 * sets SENSOR_NONFINITE and nothing else (each flag names one cause).
 *
 * One pass (sensors_bounds_finite) checks the bounds as if every value were finite and sums
 * 0·x over every value read (fw_fast.h: 0 exactly when all are finite); that is the answer
 * for a finite record (every tick of a healthy run). A record with a NaN/inf is checked again
 * by sensors_bounds_general, with a finiteness test per value.
 */
static uvms_status_t sensors_check(const uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *s,
                                   uint32_t usable, uint32_t *flags) {
  const size_t n = ctrl->model.num_joints;
  const size_t nt = ctrl->alloc.geom.num_thrusters;
  const uvms_ctrl_limits_t *lim = &ctrl->cfg->limits;
  /* Quaternion: |q| ∈ [0.5, 1.5] always (a rotation must be inferable), and within
     quat_norm_tol of 1 when that is set. Compared on |q|² to spare a square root:
     ||q| − 1| ≤ tol ⇔ (1 − tol)² ≤ |q|² ≤ (1 + tol)². */
  const uvms_real_t *q = s->quaternion_wxyz;
  const uvms_real_t n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  const uvms_real_t tol = lim->quat_norm_tol;
  const uvms_real_t lo = (tol > UVMS_R(0.0)) ? (UVMS_R(1.0) - tol) * (UVMS_R(1.0) - tol) : UVMS_R(0.25);
  const uvms_real_t hi = (tol > UVMS_R(0.0)) ? (UVMS_R(1.0) + tol) * (UVMS_R(1.0) + tol) : UVMS_R(2.25);
  uint32_t f = (n2 < lo || n2 > hi) ? UVMS_FLAG_QUATERNION_INVALID : 0u;
  uvms_real_t probe = UVMS_R(0.0);
  const uint32_t f_finite = sensors_bounds_finite(ctrl, n, nt, s, usable, &probe);
  if (probe == UVMS_R(0.0))
    f |= f_finite;
  else
    f |= UVMS_FLAG_SENSOR_NONFINITE | sensors_bounds_general(ctrl, n, nt, s, usable);
  *flags |= f;
  if ((f & UVMS_FLAG_SENSOR_NONFINITE) != 0u) return UVMS_ERR_NONFINITE;
  return (f != 0u) ? UVMS_ERR_RANGE : UVMS_OK;
}

/* Counts used as indices (cFE: validate whatever is used as an index): the joint and
   thruster counts of every copy the tick reads, the caller's configuration included, are in
   range and agree, and the model's parameter pointer is the configuration's arm, so that a
   corrupted instance or a changed configuration is stopped before anything is indexed with
   them (the loops are also bounded by the compile-time maxima). */
static int instance_counts_ok(const uvms_ctrl_t *ctrl) {
  if (ctrl->cfg == NULL) return 0;
  const size_t n = ctrl->cfg->arm.num_joints, nt = ctrl->cfg->thrusters.num_thrusters;
  if (n < 1u || n > UVMS_MAX_JOINTS || nt < 1u || nt > UVMS_MAX_THRUSTERS) return 0;
  if (ctrl->model.num_joints != n || ctrl->alloc.geom.num_thrusters != nt) return 0;
  /* The model reads its parameters through a pointer: it must be the configuration's. */
  if (ctrl->model.p != &ctrl->cfg->arm) return 0;
  /* A running Cartesian line indexes with its own copy. */
  if (ctrl->cfg->traj_mode == UVMS_TRAJ_CARTESIAN_LINE && ctrl->cart.ready && ctrl->cart.n != n)
    return 0;
  return 1;
}

/* 0. Begin: the tick's work cleared (tick and time of the record kept), the safe output
      written first (every error exit re-establishes it through fail_safe), the arguments
      checked. */
static uvms_status_t stage_begin(const uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *sensors,
                                 uvms_ctrl_command_t *cmd, tick_t *k) {
  k->model_ok = 0;
  k->thrusters_on = 0;
  k->rep_nonfinite = 0;
  k->status = UVMS_OK;
  k->tick = 0;
  k->time_s = UVMS_R(0.0);
  k->flags = 0u;
  k->ff_slope_ok = 0; /* ff_slope is written, and read, only when the lead runs */
  memset(&k->power_warm, 0, sizeof k->power_warm);
  uvms_clear_record(&k->rep, sizeof k->rep);
  if (sensors != NULL) {
    k->tick = sensors->tick;
    /* Telemetry stays finite on every tick: a non-finite time (SENSOR_NONFINITE) reads 0. */
    k->time_s = uvms_isfinite(sensors->time_s) ? sensors->time_s : UVMS_R(0.0);
  }
  /* = fail_safe without the mark: the loop results were just cleared. */
  if (cmd != NULL) safe_command(ctrl, cmd);
  if (cmd == NULL || ctrl == NULL || sensors == NULL) return UVMS_ERR_ARG;
  if (!ctrl->ready) return UVMS_ERR_STATE;
  if (!instance_counts_ok(ctrl)) {
    k->flags |= UVMS_FLAG_INSTANCE_INVALID;
    return UVMS_ERR_STATE;
  }
  return UVMS_OK;
}

/* Sequence check: returns 1 for a record whose tick is not above the last one received (it is
   rejected). In the gap test tick > last ≥ INT64_MIN, so tick − 1 cannot overflow by itself
   (last + 1 was safe only through the branch before it). Any in-order record advances
   last_tick, also when its values are rejected (it was received: the next one is no gap). */
static int sequence_check(uvms_ctrl_t *ctrl, int64_t tick, uint32_t *flags) {
  int out_of_order = 0;
  if (ctrl->have_last_tick) {
    if (tick <= ctrl->last_tick) {
      *flags |= UVMS_FLAG_TICK_NOT_INCREASING;
      out_of_order = 1;
    } else if (tick - 1 > ctrl->last_tick) {
      *flags |= UVMS_FLAG_TICK_GAP;
    }
  }
  if (!out_of_order) {
    ctrl->last_tick = tick;
    ctrl->have_last_tick = 1;
  }
  return out_of_order;
}

/* Timestamp plausibility (UVMS_FLAG_TIME_IMPLAUSIBLE): 1 when a finite time_s of an in-order
   record (tick > k_a) is farther than the tolerance from t_a + (tick − k_a)·tick_s. The tick
   difference is taken in uint64_t (no signed overflow; tick > last_tick ≥ k_a). */
static int time_jumped(const uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *s) {
  if (!ctrl->have_time_anchor || !uvms_isfinite(s->time_s) || s->tick <= ctrl->time_anchor_tick)
    return 0;
  const uint64_t dk = (uint64_t)s->tick - (uint64_t)ctrl->time_anchor_tick;
  const uvms_real_t tick_s = ctrl->cfg->tick_s;
  /* (int32 → real is one instruction on the M4F; uint64 → real a library call.) */
  const uvms_real_t dk_r = (dk <= 0x7FFFFFFFu) ? (uvms_real_t)(int32_t)dk : (uvms_real_t)dk;
  const uvms_real_t expected = ctrl->time_anchor_s + dk_r * tick_s;
  const uvms_real_t tol =
      UVMS_TIME_TOL_TICKS * tick_s + UVMS_TIME_TOL_ABS_S + UVMS_TIME_TOL_REL * uvms_fabs(expected);
  /* NaN/inf expected (a tick count far beyond any run) fails the comparison: a jump. */
  return !(uvms_fabs(s->time_s - expected) <= tol);
}

/* 1. Sensors: sequence, validation and the hold-last-good policy (controller.h,
      docs/FAULTS.md). Sets k->S, k->usable and k->base; fails (SENSOR_HOLD_EXPIRED) when a
      rejected record may not be replaced. */
static uvms_status_t stage_sensors(uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *sensors,
                                   tick_t *k) {
  const size_t nt = ctrl->alloc.geom.num_thrusters;
  const uint32_t all = (nt >= 32u) ? 0xFFFFFFFFu : ((1u << nt) - 1u);
  const uint32_t usable_in = sensors->thruster_usable_mask & all;
  const int out_of_order = sequence_check(ctrl, sensors->tick, &k->flags);
  uvms_status_t st = sensors_check(ctrl, sensors, usable_in, &k->flags);
  if (!out_of_order && time_jumped(ctrl, sensors)) {
    k->flags |= UVMS_FLAG_TIME_IMPLAUSIBLE;
    if (st == UVMS_OK) st = UVMS_ERR_RANGE;
  }
  if (st == UVMS_OK && out_of_order) st = UVMS_ERR_RANGE;
  k->S = sensors;
  if (st != UVMS_OK) {
    if (ctrl->rejected_streak < UINT32_MAX) ctrl->rejected_streak += 1u;
    k->rep.sensor_rejected_ticks = ctrl->rejected_streak;
    if (!ctrl->have_last_good || ctrl->rejected_streak > ctrl->cfg->limits.sensor_hold_max_ticks) {
      k->flags |= UVMS_FLAG_SENSOR_HOLD_EXPIRED;
      return st;
    }
    k->flags |= UVMS_FLAG_SENSOR_HELD;
    k->S = &ctrl->last_good;
  } else {
    ctrl->rejected_streak = 0u;
    uvms_copy_record(&ctrl->last_good, sensors, sizeof *sensors); /* = *sensors (fw_fast.h) */
    ctrl->have_last_good = 1;
    /* The stages read the copy just validated, not the caller's buffer: a buffer changed
       during the tick (a DMA or an interrupt writing the next sample) cannot hand a later
       stage, e.g. the attitude feedback's quaternion, a value the checks did not see. */
    k->S = &ctrl->last_good;
    if (!ctrl->have_time_anchor) {
      ctrl->time_anchor_tick = sensors->tick;
      ctrl->time_anchor_s = sensors->time_s;
      ctrl->have_time_anchor = 1;
    }
  }
  /* A thruster reported unusable is never driven, even by a held tick. */
  k->usable = k->S->thruster_usable_mask & usable_in;
  /* Every field of k->base is written here: the pose and rates of S, and the accelerations 0
     (the model stage evaluates the arm at v̇0 = ω̇0 = 0, SPEC §7). */
  (void)uvms_quat_to_rot(k->S->quaternion_wxyz, k->base.R0); /* norm checked above */
  uvms_v3_copy(k->S->position_m, k->base.position_m);
  uvms_v3_copy(k->S->velocity_m_s, k->base.velocity_m_s);
  uvms_v3_copy(k->S->angular_velocity_rad_s, k->base.omega_rad_s);
  uvms_v3_set(k->base.accel_m_s2, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  uvms_v3_set(k->base.alpha_rad_s2, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  return UVMS_OK;
}

/* 2. Thruster set: H⁺ of the usable thrusters (recomputed only when the set changes,
      allocation.c). Rank < 6 is served by the least-squares H⁺ (flag ALLOC_SINGULAR, the lost
      axes reported); only an H⁺ that could not be computed (UVMS_ERR_SINGULAR) idles the
      thrusters, not the arm (k->alloc_st); any other failure means a corrupt instance. */
static uvms_status_t stage_thruster_set(uvms_ctrl_t *ctrl, tick_t *k) {
  k->alloc_st = uvms_alloc_set_usable(&ctrl->alloc, k->usable);
  k->rep.alloc_rank = (int32_t)ctrl->alloc.rank;
  k->rep.uncontrollable_axes = ctrl->alloc.uncontrollable_axes;
  if (k->alloc_st == UVMS_ERR_SINGULAR || ctrl->alloc.rank < UVMS_ALLOC_WRENCH_DIM)
    k->flags |= UVMS_FLAG_ALLOC_SINGULAR;
  if (k->alloc_st != UVMS_OK && k->alloc_st != UVMS_ERR_SINGULAR) {
    k->flags |= UVMS_FLAG_MODEL_FAULT;
    return k->alloc_st;
  }
  return UVMS_OK;
}

/* Reference capture, first part (first valid tick): attitude, vehicle position, and the start
   of a Cartesian line. A line that cannot start fails the tick (safe output); the capture is
   retried on the next one. */
static uvms_status_t capture_pose(uvms_ctrl_t *ctrl, const uvms_base_state_t *base,
                                  const uvms_real_t q0_wxyz[4], uint32_t *flags) {
  if (ctrl->references_captured) return UVMS_OK;
  for (int k = 0; k < 9; ++k) ctrl->R0d[k] = base->R0[k]; /* = R(q0_wxyz) (stage_sensors) */
  for (int k = 0; k < 4; ++k) ctrl->q0d_wxyz[k] = q0_wxyz[k];
  uvms_v3_copy(base->position_m, ctrl->r0d_m);
  if (ctrl->cfg->traj_mode != UVMS_TRAJ_CARTESIAN_LINE) return UVMS_OK;
  const uvms_cart_traj_params_t params = ctrl->cart.p;
  const uvms_status_t st = uvms_cart_traj_init(&ctrl->cart, &params, &ctrl->model, &ctrl->data,
                                               ctrl->cfg->theta_start_rad, ctrl->r0d_m, ctrl->R0d);
  if (st != UVMS_OK) {
    ctrl->cart.p = params; /* init zeroed the instance; keep the line for the retry */
    *flags |= UVMS_FLAG_TRAJECTORY_FAULT;
  }
  return st;
}

/* Joint reference at time t (SPEC §8). On failure the caller holds the last good reference. */
static uvms_status_t joint_reference(uvms_ctrl_t *ctrl, uvms_real_t t_s, uvms_ctrl_command_t *cmd) {
  const uvms_ctrl_config_t *c = ctrl->cfg;
  const size_t n = ctrl->model.num_joints;
  const uvms_real_t tt = t_s - c->traj_start_s;
  switch (c->traj_mode) {
    case UVMS_TRAJ_JOINT_CYCLOID:
      return uvms_cycloid_eval(n, c->theta_start_rad, c->theta_final_rad, c->traj_duration_s, tt,
                               cmd->joint_ref_rad, cmd->joint_ref_rate_rad_s, cmd->joint_ref_accel_rad_s2);
    case UVMS_TRAJ_CARTESIAN_LINE: {
      if (tt < UVMS_R(0.0)) {
        for (size_t j = 0; j < n && j < UVMS_MAX_JOINTS; ++j)
          cmd->joint_ref_rad[j] = c->theta_start_rad[j];
        return UVMS_OK;
      }
      return uvms_cart_traj_step(&ctrl->cart, &ctrl->model, &ctrl->data, tt, c->tick_s,
                                 cmd->joint_ref_rad, cmd->joint_ref_rate_rad_s, cmd->joint_ref_accel_rad_s2);
    }
    case UVMS_TRAJ_HOLD:
    default:
      for (size_t j = 0; j < n && j < UVMS_MAX_JOINTS; ++j)
        cmd->joint_ref_rad[j] = c->theta_start_rad[j];
      return UVMS_OK;
  }
}

/* 3. Reference: capture (first tick), joint reference and joint servo (SPEC §8). A trajectory
      that fails mid-run holds the last good reference at rest and the tick goes on (flag
      TRAJECTORY_FAULT, controller.h); only a line that cannot start fails the tick. */
static uvms_status_t stage_reference(uvms_ctrl_t *ctrl, tick_t *k, uvms_ctrl_command_t *cmd) {
  uvms_status_t st = capture_pose(ctrl, &k->base, k->S->quaternion_wxyz, &k->flags);
  if (st != UVMS_OK) return st;
  st = joint_reference(ctrl, k->S->time_s, cmd);
  if (st != UVMS_OK) {
    k->flags |= UVMS_FLAG_TRAJECTORY_FAULT;
    for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) {
      cmd->joint_ref_rad[j] = ctrl->q_ref_last_rad[j];
      cmd->joint_ref_rate_rad_s[j] = UVMS_R(0.0);
      cmd->joint_ref_accel_rad_s2[j] = UVMS_R(0.0);
    }
  }
  st = uvms_joint_servo(ctrl->model.num_joints, cmd->joint_ref_rad, cmd->joint_ref_rate_rad_s,
                        cmd->joint_ref_accel_rad_s2, k->S->joint_position_rad, k->S->joint_velocity_rad_s, ctrl->cfg->joint_kq_1_s2,
                        ctrl->cfg->joint_kqd_1_s, cmd->joint_acceleration_rad_s2);
  if (st != UVMS_OK) k->flags |= UVMS_FLAG_TRAJECTORY_FAULT;
  return UVMS_OK;
}

/* 4. Model: arm model and feedforward at the commanded joint accelerations (SPEC §4, §7,
      §7.1), which also give the barycenter [5]; then the second part of the reference capture
      (first tick): the initial barycenter and the position reference r_d. */
static uvms_status_t stage_model(uvms_ctrl_t *ctrl, tick_t *k, const uvms_ctrl_command_t *cmd) {
  const uvms_reference_t ref = ctrl->cfg->switches.position_reference;
  const uvms_status_t st =
      uvms_feedforward(&ctrl->model, &ctrl->data, &ctrl->cfg->fluid, ref, &k->base, k->S->joint_position_rad,
                       k->S->joint_velocity_rad_s, cmd->joint_acceleration_rad_s2, &k->ff);
  if (st != UVMS_OK) {
    k->flags |= UVMS_FLAG_MODEL_FAULT;
    return st;
  }
  k->model_ok = 1;
  if (!ctrl->references_captured) {
    uvms_v3_copy(ctrl->data.barycenter_m, ctrl->barycenter0_m);
    uvms_v3_copy(ref == UVMS_REF_BARYCENTER ? ctrl->data.barycenter_m : k->base.position_m,
                 ctrl->r_d_m);
    ctrl->references_captured = 1;
    k->flags |= UVMS_FLAG_REFERENCE_CAPTURED;
  }
  return UVMS_OK;
}

/* Whether this tick's feedforward belongs to the sequence the lead differentiates: not on a
   held record (its feedforward is the held one's) and without a trajectory fault (its
   reference jumps). Read by the lead and by its commit alike. */
static int feedforward_is_fresh(const tick_t *k) {
  return (k->flags & (UVMS_FLAG_SENSOR_HELD | UVMS_FLAG_TRAJECTORY_FAULT)) == 0u;
}

/* The feedforward wrench led by ctrl->ff_lead_s along its filtered slope (uvms_ff_lead,
   docs/MODEL.md §7.5), in place in the report; the wrench before the lead is kept for the
   next tick (stage_finish). The slope is taken over the ticks of the records the two
   feedforwards were computed from (never their time stamps). No lead on the first tick of a
   sequence, after a failed tick, on a tick run on a held record or with a trajectory fault
   (its feedforward is the held one, or its reference jumps), or across more than
   UVMS_FF_LEAD_MAX_GAP_TICKS ticks. */
static void lead_feedforward(const uvms_ctrl_t *ctrl, tick_t *k) {
  tick_report_t *o = &k->rep;
  uvms_v3_copy(o->force_ff_N, k->ff_unled);
  uvms_v3_copy(o->moment_ff_Nm, k->ff_unled + 3);
  if (!(ctrl->ff_lead_s > UVMS_R(0.0)) || !ctrl->have_ff_prev) return;
  if (!feedforward_is_fresh(k)) return;
  if (!(k->S->tick > ctrl->ff_prev_tick)) return;
  const uint64_t gap = (uint64_t)k->S->tick - (uint64_t)ctrl->ff_prev_tick; /* ≥ 1, no overflow */
  if (gap > (uint64_t)UVMS_FF_LEAD_MAX_GAP_TICKS) return;
  const uvms_real_t dt_s = (uvms_real_t)gap * ctrl->cfg->tick_s;
  uvms_real_t led[6];
  for (size_t i = 0; i < 6; ++i) k->ff_slope[i] = ctrl->ff_slope[i];
  if (uvms_ff_lead(6, k->ff_unled, ctrl->ff_prev, dt_s, ctrl->ff_lead_s, k->ff_slope,
                   ctrl->have_ff_slope, led) != UVMS_OK)
    return;
  k->ff_slope_ok = 1;
  uvms_v3_copy(led, o->force_ff_N);
  uvms_v3_copy(led + 3, o->moment_ff_Nm);
}

/* 5. Feedback [40–46] and the Table X switches: the desired force and moment (inertial),
      and their feedforward and feedback parts (0 where a switch is off). */
static void stage_feedback(const uvms_ctrl_t *ctrl, tick_t *k) {
  const uvms_switches_t *sw = &ctrl->cfg->switches;
  tick_report_t *o = &k->rep;
  const int bary = (sw->position_reference == UVMS_REF_BARYCENTER);
  const uvms_real_t zero3[3] = {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0)};
  uvms_real_t N_fb[3], F_fb[3];
  (void)uvms_attitude_feedback(&ctrl->cfg->gains, ctrl->q0d_wxyz, k->S->quaternion_wxyz,
                               k->base.omega_rad_s, N_fb, o->attitude_error_rad);
  (void)uvms_position_feedback(&ctrl->cfg->gains, ctrl->r_d_m,
                               bary ? ctrl->data.barycenter_m : k->base.position_m, zero3,
                               bary ? ctrl->data.barycenter_v_m_s : k->base.velocity_m_s, F_fb);
  if (sw->position_feedforward)
    uvms_v3_copy(bary ? k->ff.force_barycenter_N : k->ff.force_vehicle_N, o->force_ff_N);
  if (sw->position_feedback) uvms_v3_copy(F_fb, o->force_fb_N);
  if (sw->attitude_control) {
    uvms_v3_copy(k->ff.moment_att_Nm, o->moment_ff_Nm);
    uvms_v3_copy(N_fb, o->moment_fb_Nm);
  }
  lead_feedforward(ctrl, k);
  uvms_v3_add(o->force_ff_N, o->force_fb_N, o->force_des_N);       /* [46] */
  uvms_v3_add(o->moment_ff_Nm, o->moment_fb_Nm, o->moment_des_Nm); /* [41] */
}

/* The wrench the commanded thrusts produce, inertial (reported as force/moment_deliverable). */
static uvms_status_t deliverable_wrench(const uvms_ctrl_t *ctrl, tick_t *k) {
  tick_report_t *o = &k->rep;
  if (ctrl->alloc.rank < UVMS_ALLOC_WRENCH_DIM) {
    /* H·P, then back in inertial coordinates (R0). */
    uvms_real_t w_b[UVMS_ALLOC_WRENCH_DIM];
    const uvms_status_t st = uvms_alloc_wrench_body(&ctrl->alloc, o->thrust_des_N, w_b);
    uvms_m3_mul_v3(k->base.R0, &w_b[0], o->force_deliverable_N);
    uvms_m3_mul_v3(k->base.R0, &w_b[3], o->moment_deliverable_Nm);
    return st;
  }
  /* Full rank: H·H⁺ = I, so H·P = (s_pos·f_b; s_att·n_b) (uvms_alloc_saturate keeps each part's
     direction) and, rotated back, (s_pos·F; s_att·N): no n×6 product per tick. The minimum-power
     thrusts T = P + N·z deliver H·P too (H·N = 0, to rounding). */
  uvms_v3_scale(o->force_des_N, o->thrust_scale_pos, o->force_deliverable_N);
  uvms_v3_scale(o->moment_des_Nm, o->thrust_scale_att, o->moment_deliverable_Nm);
  return UVMS_OK;
}

/* Allocation mode min_power (controller.h): the least-Σ|T|^1.5 thrusts T with P's body wrench
   replace P, warm started from the last good tick's solution (its successor is committed by
   stage_finish); the attitude part stays P_att and the position part becomes T − P_att. If
   the solver cannot run, P stands (flag ALLOC_FALLBACK); if it stopped short of the optimum,
   its last iterate stands (flag ALLOC_NOT_CONVERGED); the tick goes on either way. */
static void allocate_min_power(const uvms_ctrl_t *ctrl, tick_t *k) {
  tick_report_t *o = &k->rep;
  uvms_real_t thrust_N[UVMS_MAX_THRUSTERS];
  uvms_power_info_t info;
  k->power_warm = ctrl->power_warm;
  if (uvms_alloc_min_power_each(&ctrl->alloc, ctrl->thrust_limit_N, ctrl->power_weight,
                                o->thrust_des_N, &k->power_warm, thrust_N, &info) != UVMS_OK) {
    k->flags |= UVMS_FLAG_ALLOC_FALLBACK;
    return;
  }
  if (!info.converged) k->flags |= UVMS_FLAG_ALLOC_NOT_CONVERGED;
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    o->thrust_des_N[j] = thrust_N[j];
    o->thrust_pos_N[j] = thrust_N[j] - o->thrust_att_N[j];
  }
}

/* 6. Allocation [38–39] (least squares at rank < 6) of the desired wrench, the thrust limit
      with attitude priority (allocation.h), in alloc_mode min_power the least-Σ|T|^1.5
      redistribution, the deliverable wrench, and the thrusters' advance speeds. Case I (no
      vehicle control, SPEC §7.2) and a usable set without H⁺ leave the thrusters idle, at the
      safe output's zero voltage: the arm's command still stands. */
static uvms_status_t stage_allocation(uvms_ctrl_t *ctrl, tick_t *k) {
  const uvms_switches_t *sw = &ctrl->cfg->switches;
  tick_report_t *o = &k->rep;
  if (!sw->attitude_control && !sw->position_feedforward && !sw->position_feedback) {
    k->flags |= UVMS_FLAG_THRUSTERS_IDLE;
    return UVMS_OK;
  }
  if (k->alloc_st != UVMS_OK) {
    k->status = k->alloc_st; /* UVMS_ERR_SINGULAR: the vehicle cannot be controlled */
    return UVMS_OK;
  }
  uvms_status_t st = uvms_alloc_step(&ctrl->alloc, k->base.R0, o->force_des_N, o->moment_des_Nm,
                                     o->thrust_des_N, o->thrust_pos_N, o->thrust_att_N);
  if (st == UVMS_OK) {
    o->thrust_scale_pos = UVMS_R(1.0);
    o->thrust_scale_att = UVMS_R(1.0);
  }
  if (st == UVMS_OK && ctrl->thrust_limited) {
    st = uvms_alloc_saturate_each(&ctrl->alloc, ctrl->thrust_limit_N, o->thrust_pos_N,
                                  o->thrust_att_N, o->thrust_des_N, &o->thrust_scale_pos,
                                  &o->thrust_scale_att);
    if (o->thrust_scale_pos < UVMS_R(1.0) || o->thrust_scale_att < UVMS_R(1.0))
      k->flags |= UVMS_FLAG_THRUST_SATURATED;
  }
  if (st == UVMS_OK && ctrl->cfg->alloc_mode == UVMS_ALLOC_MIN_POWER) allocate_min_power(ctrl, k);
  if (st == UVMS_OK) st = deliverable_wrench(ctrl, k);
  if (st == UVMS_OK)
    st = uvms_thruster_advance_speeds(&ctrl->alloc.geom, k->base.R0, k->base.velocity_m_s,
                                      k->base.omega_rad_s, ctrl->cfg->fluid.flow_m_s,
                                      o->advance_speed_m_s);
  if (st != UVMS_OK) {
    k->flags |= UVMS_FLAG_MODEL_FAULT;
    return st;
  }
  k->thrusters_on = 1;
  return UVMS_OK;
}

/* Stage 7's parts (stage_thruster_loops below). Thruster j's loop from its desired speed
   w_des_rad_s and that stage's status speed_st (uvms_motor_speed_fast): its command, or
   V_j = 0 when its loop failed. */
UVMS_FW_INLINE void thruster_loop(const uvms_ctrl_t *ctrl, tick_t *k, uvms_ctrl_command_t *cmd,
                                  size_t j, uvms_status_t speed_st, uvms_real_t w_des_rad_s) {
  tick_report_t *o = &k->rep;
  uvms_motor_cmd_t mc;
  const uvms_status_t ms =
      uvms_motor_drive_fast(&ctrl->motor, j, speed_st, w_des_rad_s, o->advance_speed_m_s[j],
                            k->S->motor_speed_rad_s[j], k->S->motor_current_A[j], &mc);
  if (ms != UVMS_OK) {
    k->flags |= UVMS_FLAG_MOTOR_FAULT; /* mc is zeroed: V_j = 0 */
    thruster_off(j, cmd, o);           /* and no current in the current drive */
    return;
  }
  if (mc.saturated) k->flags |= UVMS_FLAG_VOLTAGE_SATURATED;
  cmd->motor_voltage_V[j] = mc.voltage_V;
  cmd->motor_current_cmd_A[j] = ctrl->motor.current_cmd_A[j]; /* I*: integrated [66] */
  cmd->motor_current_rate_A_s[j] = mc.current_dot_cmd_A_s;    /* İ* within the supply limit */
  o->omega_des_rad_s[j] = mc.omega_des_rad_s;
  o->current_des_A[j] = mc.current_des_A;
}

/* An unusable thruster: no loop, V_j = 0, its results 0 (its thrust is 0 by H⁺'s zero row). */
static void thruster_unusable(size_t j, tick_t *k, uvms_ctrl_command_t *cmd) {
  tick_report_t *o = &k->rep;
  thruster_off(j, cmd, o);
  o->thrust_des_N[j] = UVMS_R(0.0);
  o->thrust_pos_N[j] = UVMS_R(0.0);
  o->thrust_att_N[j] = UVMS_R(0.0);
  o->advance_speed_m_s[j] = UVMS_R(0.0);
}

/* Thruster j's desired speed (uvms_motor_speed_fast) into *w_des_rad_s, and its status. */
UVMS_FW_INLINE uvms_status_t thruster_speed(const uvms_ctrl_t *ctrl, const tick_t *k, size_t j,
                                            uvms_real_t *w_des_rad_s) {
  const tick_report_t *o = &k->rep;
  return uvms_motor_speed_fast(&ctrl->motor, j, o->thrust_des_N[j], o->advance_speed_m_s[j],
                               k->S->motor_speed_rad_s[j], k->S->motor_current_A[j],
                               w_des_rad_s);
}

/* 7. Thruster loops [57–66], [53] (uvms_motor_step, inlined in its two stages,
      uvms_motor_speed_fast and uvms_motor_drive_fast, with thruster j's own parameters): per
      usable thruster the voltage, the integrated current command I* and its rate İ*; unusable
      ones and failed loops get none. */
static void stage_thruster_loops(const uvms_ctrl_t *ctrl, tick_t *k, uvms_ctrl_command_t *cmd) {
  if (!k->thrusters_on) return;
  const size_t nt = ctrl->alloc.geom.num_thrusters;
  const uint32_t usable = k->usable;
#if UVMS_FW_WORK_AHEAD
  /* On a host every usable thruster's desired speed first, then the loops from them
     (fw_fast.h): the speeds' square roots and divisions overlap in a loop of their own. An
     entry the first loop did not write reads as a failed stage (safe output), not as junk. */
  uvms_real_t w_des_rad_s[UVMS_MAX_THRUSTERS];
  uvms_status_t speed_st[UVMS_MAX_THRUSTERS];
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    w_des_rad_s[j] = UVMS_R(0.0);
    speed_st[j] = UVMS_ERR_STATE;
  }
  for (size_t j = 0; j < nt && j < UVMS_MAX_THRUSTERS; ++j)
    if ((usable >> j) & 1u) speed_st[j] = thruster_speed(ctrl, k, j, &w_des_rad_s[j]);
  for (size_t j = 0; j < nt && j < UVMS_MAX_THRUSTERS; ++j) {
    if ((usable >> j) & 1u)
      thruster_loop(ctrl, k, cmd, j, speed_st[j], w_des_rad_s[j]);
    else
      thruster_unusable(j, k, cmd);
  }
#else
  for (size_t j = 0; j < nt && j < UVMS_MAX_THRUSTERS; ++j) {
    if (((usable >> j) & 1u) == 0u) {
      thruster_unusable(j, k, cmd);
      continue;
    }
    uvms_real_t w_des_rad_s;
    const uvms_status_t speed_st = thruster_speed(ctrl, k, j, &w_des_rad_s);
    thruster_loop(ctrl, k, cmd, j, speed_st, w_des_rad_s);
  }
#endif
}

/* 8. Estimate (when the model stage succeeded, whatever came after): the model's quantities
      the tick reports (barycenter, base wrench and acceleration, joint torques, position
      reference), and the EE estimate (SPEC §10): [3] at the reference pose (r0d, R0d), or [4]
      from the initial barycenter. Every point of the FK is r0 + R0·(body-frame point of q), so
      the same arm seen from another vehicle pose is a rigid motion of this one:
        [3]: p̂_EE = r0d + R0d·R0ᵀ·(p_EE − r0);   [4]: p̂_EE = p_cm0 + R0d·R0ᵀ·(p_EE − p_cm).
      This replaces a second forward-kinematics pass (7 sin/cos pairs and 7 matrix products). */
static void stage_estimate(const uvms_ctrl_t *ctrl, tick_t *k) {
  if (!k->model_ok) return;
  const uvms_arm_data_t *d = &ctrl->data;
  tick_report_t *o = &k->rep;
  uvms_v3_copy(d->barycenter_m, o->barycenter_m);
  uvms_v3_copy(d->barycenter_v_m_s, o->barycenter_v_m_s);
  uvms_v3_copy(k->ff.base_force_N, o->base_force_N);
  uvms_v3_copy(k->ff.base_moment_Nm, o->base_moment_Nm);
  uvms_v3_copy(k->ff.base_accel_m_s2, o->base_accel_model_m_s2);
  for (size_t j = 0; j < ctrl->model.num_joints && j < UVMS_MAX_JOINTS; ++j)
    o->joint_torque_model_Nm[j] = d->tau_Nm[j + 1];
  uvms_v3_copy(ctrl->r_d_m, o->position_ref_m);
  const int bary = (ctrl->cfg->switches.position_reference == UVMS_REF_BARYCENTER);
  uvms_real_t rel_b[3], rel_b0[3], rel[3];
  uvms_v3_sub(d->ee_m, bary ? d->barycenter_m : k->base.position_m, rel_b);
  uvms_m3t_mul_v3(k->base.R0, rel_b, rel_b0);
  uvms_m3_mul_v3(ctrl->R0d, rel_b0, rel);
  uvms_v3_add(bary ? ctrl->barycenter0_m : ctrl->r0d_m, rel, o->ee_estimate_m);
  /* A record that passed every check can still be absurd enough for the model's outputs to
     overflow (no bound on position; a disabled speed bound) while the tick succeeds (thrusters
     idle): one sum finds that (NaN and inf propagate); the telemetry then gets the full pass. */
  uvms_real_t sum = UVMS_R(0.0);
  for (int i = 0; i < 3; ++i)
    sum += o->barycenter_m[i] + o->barycenter_v_m_s[i] + o->base_force_N[i] +
           o->base_moment_Nm[i] + o->base_accel_model_m_s2[i] + o->ee_estimate_m[i];
  for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) sum += o->joint_torque_model_Nm[j];
  if (!uvms_isfinite(sum)) k->rep_nonfinite = 1;
}

/* The tick's feedforward before the lead, and the tick of the record it was computed from,
   become what the next tick's lead differentiates against (lead on). A tick run on a held
   record or with a trajectory fault keeps the last ones (lead_feedforward); a failed tick
   clears them (stage_finish). */
static void commit_feedforward(uvms_ctrl_t *ctrl, const tick_t *k) {
  if (!(ctrl->ff_lead_s > UVMS_R(0.0))) return;
  if (!feedforward_is_fresh(k)) return;
  for (size_t i = 0; i < 6; ++i) ctrl->ff_prev[i] = k->ff_unled[i];
  if (k->ff_slope_ok)
    for (size_t i = 0; i < 6; ++i) ctrl->ff_slope[i] = k->ff_slope[i];
  ctrl->ff_prev_tick = k->S->tick;
  ctrl->have_ff_prev = 1;
  ctrl->have_ff_slope = k->ff_slope_ok; /* a tick that did not lead restarts the filter */
}

/* 9. Finish: the tick's joint command stands and its reference becomes the last good one, or
      (any stage failed) the one safe output. */
static uvms_status_t stage_finish(uvms_ctrl_t *ctrl, tick_t *k, uvms_status_t st,
                                  uvms_ctrl_command_t *cmd) {
  if (st != UVMS_OK) {
    k->rep_nonfinite = 1; /* what a failed tick reached may have overflowed on the way */
    if (ctrl != NULL && ctrl->ready) forget_tick_history(ctrl);
    return fail_safe(ctrl, cmd, k, st);
  }
  commit_reference(ctrl, cmd);
  commit_feedforward(ctrl, k);
  ctrl->power_warm = k->power_warm;
  return k->status;
}

/* The real-valued telemetry fields (offset, count): every one of uvms_ctrl_telemetry_t's
   uvms_real_t fields except time_s (made finite by stage_begin). */
#define TLM_REALS(field) {offsetof(uvms_ctrl_telemetry_t, field), \
                          sizeof(((uvms_ctrl_telemetry_t *)0)->field) / sizeof(uvms_real_t)}
static const struct { size_t offset, count; } kTelemetryReals[] = {
    TLM_REALS(force_ff_N),        TLM_REALS(force_fb_N),           TLM_REALS(force_des_N),
    TLM_REALS(moment_ff_Nm),      TLM_REALS(moment_fb_Nm),         TLM_REALS(moment_des_Nm),
    TLM_REALS(thrust_des_N),      TLM_REALS(thrust_pos_N),         TLM_REALS(thrust_att_N),
    TLM_REALS(omega_des_rad_s),   TLM_REALS(current_des_A),        TLM_REALS(advance_speed_m_s),
    TLM_REALS(ee_estimate_m),     TLM_REALS(barycenter_m),         TLM_REALS(barycenter_v_m_s),
    TLM_REALS(position_ref_m),    TLM_REALS(attitude_error_rad),   TLM_REALS(base_force_N),
    TLM_REALS(base_moment_Nm),    TLM_REALS(base_accel_model_m_s2),
    TLM_REALS(joint_torque_model_Nm), TLM_REALS(force_deliverable_N),
    TLM_REALS(moment_deliverable_Nm), TLM_REALS(thrust_scale_pos), TLM_REALS(thrust_scale_att)};
#undef TLM_REALS

/* A failed tick's telemetry holds what its stages reached; a value that overflowed on the way
   (e.g. the desired force of an absurd velocity, which the allocation then refused) reads 0,
   so that telemetry is finite on every tick (only failed ticks pay for the pass). */
static void telemetry_make_finite(uvms_ctrl_telemetry_t *T) {
  for (size_t f = 0; f < sizeof kTelemetryReals / sizeof kTelemetryReals[0]; ++f) {
    uvms_real_t *v = (uvms_real_t *)((char *)T + kTelemetryReals[f].offset);
    for (size_t i = 0; i < kTelemetryReals[f].count; ++i)
      if (!uvms_isfinite(v[i])) v[i] = UVMS_R(0.0);
  }
}

/* 10. Publish: the telemetry record, written once, at the end of the tick, from the tick's
       work and its status (controller.h: every real finite on every tick; a quantity a failed
       tick did not reach reads 0, as does one that overflowed on the way: the full finiteness
       pass runs only when a stage failed or the estimate's sum was not finite). */
static void stage_publish_telemetry(const tick_t *k, uvms_status_t st, uvms_ctrl_telemetry_t *T) {
  T->tick = k->tick;
  T->time_s = k->time_s;
  T->status = (int32_t)st;
  T->flags = k->flags;
  /* force_ff_N .. sensor_rejected_ticks: tick_report_t's layout (checked above). */
  uvms_copy_record((char *)T + offsetof(uvms_ctrl_telemetry_t, force_ff_N), &k->rep,
                   sizeof k->rep);
  if (k->rep_nonfinite) telemetry_make_finite(T);
}

uvms_status_t uvms_ctrl_step(uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *sensors,
                             uvms_ctrl_command_t *cmd, uvms_ctrl_telemetry_t *tlm) {
  tick_t k; /* the tick's work */
  uvms_status_t st = stage_begin(ctrl, sensors, cmd, &k);       /* safe output, arguments */
  if (st == UVMS_OK) st = stage_sensors(ctrl, sensors, &k);      /* S (or held), base state */
  if (st == UVMS_OK) st = stage_thruster_set(ctrl, &k);          /* usable set, H⁺ */
  if (st == UVMS_OK) st = stage_reference(ctrl, &k, cmd);        /* θ_ref, θ̇_ref, θ̈_ref, θ̈_cmd */
  if (st == UVMS_OK) st = stage_model(ctrl, &k, cmd);            /* feedforward, r_d */
  if (st == UVMS_OK) stage_feedback(ctrl, &k);                   /* F_P0, N_P0 */
  if (st == UVMS_OK) st = stage_allocation(ctrl, &k);            /* P, deliverable, v_a */
  if (st == UVMS_OK) stage_thruster_loops(ctrl, &k, cmd);        /* V, I*, İ* */
  stage_estimate(ctrl, &k);                                      /* p̂_EE, model quantities */
  st = stage_finish(ctrl, &k, st, cmd);                          /* commit, or safe output */
  if (tlm != NULL) stage_publish_telemetry(&k, st, tlm);         /* telemetry, once */
  /* [66] integrated over the tick: the next tick's I*_j (0 after a safe output). */
  if (ctrl != NULL && ctrl->ready)
    uvms_motor_end_tick(&ctrl->motor, cmd != NULL ? cmd->motor_current_cmd_A : NULL,
                        cmd != NULL ? cmd->motor_current_rate_A_s : NULL);
  return st;
}
