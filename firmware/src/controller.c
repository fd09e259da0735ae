/* controller.c: the controller tick (SPEC §7–8), configuration and validation. */
#include "uvms/controller.h"

#include <string.h>

#include "uvms/kinematics.h"
#include "uvms/linalg.h"

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
    default: return "unknown";
  }
}

uvms_status_t uvms_switches_case(int case_number, uvms_switches_t *sw) {
  if (sw == NULL) return UVMS_ERR_ARG;
  /* Table X: attitude, reference (1 = barycenter), position feedforward, position feedback. */
  static const signed char table[8][4] = {
      {0, 0, 0, 0}, /* I */    {1, 1, 0, 0}, /* II */  {1, 1, 1, 0}, /* III */
      {1, 0, 1, 1}, /* IV */   {1, 0, 0, 1}, /* V */   {1, 0, 1, 0}, /* VI */
      {1, 1, 1, 1}, /* VII */  {1, 1, 0, 1}, /* VIII */
  };
  memset(sw, 0, sizeof *sw);
  if (case_number < 1 || case_number > 8) return UVMS_ERR_RANGE;
  const signed char *row = table[case_number - 1];
  sw->attitude_control = row[0];
  sw->position_reference = row[1] ? UVMS_REF_BARYCENTER : UVMS_REF_VEHICLE;
  sw->position_feedforward = row[2];
  sw->position_feedback = row[3];
  return UVMS_OK;
}

uvms_status_t uvms_ctrl_config_paper(uvms_ctrl_config_t *cfg, int case_number) {
  if (cfg == NULL) return UVMS_ERR_ARG;
  memset(cfg, 0, sizeof *cfg);
  uvms_arm_params_paper(&cfg->arm);
  cfg->fluid.density_kg_m3 = UVMS_R(1025.0); /* SPEC §3.2; 1000 under "density error" */
  cfg->fluid.angle_of_attack = 1;
  /* flow (0,0,0) and gravity g = 0 for the paper's experiments (SPEC §6.3). */
  uvms_thruster_geometry_paper(&cfg->thrusters);
  uvms_thruster_params_paper(&cfg->thruster);
  uvms_pd_gains_paper(&cfg->gains);
  cfg->joint_kq_1_s2 = UVMS_JOINT_SERVO_KQ_DEFAULT_1_S2;
  cfg->joint_kqd_1_s = UVMS_JOINT_SERVO_KQD_DEFAULT_1_S;
  cfg->tick_s = UVMS_R(0.03);
  cfg->traj_mode = UVMS_TRAJ_JOINT_CYCLOID;
  cfg->traj_start_s = UVMS_R(0.0);
  cfg->traj_duration_s = UVMS_R(60.0);
  uvms_cart_traj_params_default(&cfg->cart);
  /* SPEC §8 table [deg]: θI; θF "Veh." for vehicle reference, "Bary. 10 kg" for barycenter. */
  static const uvms_real_t theta_i_deg[7] = {180, 90, 180, 180, 0, 0, 0};
  static const uvms_real_t veh_deg[7] = {UVMS_R(169.68), UVMS_R(-75.62), UVMS_R(266.00),
                                         UVMS_R(108.77), UVMS_R(193.47), UVMS_R(96.97),
                                         UVMS_R(98.33)};
  static const uvms_real_t bary10_deg[7] = {UVMS_R(176.19), UVMS_R(-77.12), UVMS_R(264.65),
                                            UVMS_R(89.32),  UVMS_R(192.22), UVMS_R(81.35),
                                            UVMS_R(95.12)};
  const uvms_status_t st = uvms_switches_case(case_number, &cfg->switches);
  if (st != UVMS_OK) (void)uvms_switches_case(4, &cfg->switches);
  /* A Cartesian line must refer to the point the case holds (SPEC §8; checked by init). */
  cfg->cart.reference = cfg->switches.position_reference;
  const uvms_real_t *fin =
      cfg->switches.position_reference == UVMS_REF_BARYCENTER ? bary10_deg : veh_deg;
  const uvms_real_t deg = UVMS_PI / UVMS_R(180.0);
  for (int j = 0; j < 7; ++j) {
    cfg->theta_start_rad[j] = theta_i_deg[j] * deg;
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
      UVMS_R(2.0) * cfg->thruster.voltage_limit_V / cfg->thruster.torque_constant_Nm_A;
  lim->max_motor_current_A = UVMS_R(2.0) * cfg->thruster.voltage_limit_V / cfg->thruster.resistance_ohm;
  lim->quat_norm_tol = UVMS_R(0.05);
  lim->sensor_hold_max_ticks = 5u;
  lim->thrust_limit_N = UVMS_R(1.0e6);
  return st;
}

static int finite_n(const uvms_real_t *x, size_t n) {
  for (size_t i = 0; i < n && i < 64u; ++i)
    if (!uvms_isfinite(x[i])) return 0;
  return 1;
}

/* Fault-handling settings: each real finite and ≥ 0 (0 = check off), the quaternion tolerance
   at most 0.5 (beyond it the fixed [0.5, 1.5] check decides), the hold count bounded. */
static uvms_status_t limits_validate(const uvms_ctrl_limits_t *l) {
  const uvms_real_t v[7] = {l->max_vehicle_speed_m_s, l->max_vehicle_rate_rad_s,
                            l->max_joint_rate_rad_s,  l->max_motor_speed_rad_s,
                            l->max_motor_current_A,   l->quat_norm_tol,
                            l->thrust_limit_N};
  if (!finite_n(v, 7)) return UVMS_ERR_NONFINITE;
  for (int k = 0; k < 7; ++k)
    if (v[k] < UVMS_R(0.0)) return UVMS_ERR_RANGE;
  if (l->quat_norm_tol > UVMS_R(0.5)) return UVMS_ERR_RANGE;
  if (l->sensor_hold_max_ticks > UVMS_SENSOR_HOLD_MAX_TICKS_LIMIT) return UVMS_ERR_RANGE;
  return UVMS_OK;
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
  uvms_status_t st = uvms_arm_model_init(&cfg->arm, &ctrl->model);
  if (st != UVMS_OK) return fail_cfg(ctrl, UVMS_CFG_ARM, st);

  const uvms_fluid_t *fl = &cfg->fluid;
  if (!uvms_isfinite(fl->density_kg_m3) || !finite_n(fl->flow_m_s, 3) ||
      !finite_n(fl->gravity_m_s2, 3))
    return fail_cfg(ctrl, UVMS_CFG_FLUID, UVMS_ERR_NONFINITE);
  /* The thruster speed solution [57–63] divides by ρ: the model density must be positive. */
  if (!(fl->density_kg_m3 > UVMS_R(0.0)) || (fl->angle_of_attack != 0 && fl->angle_of_attack != 1))
    return fail_cfg(ctrl, UVMS_CFG_FLUID, UVMS_ERR_RANGE);

  st = uvms_alloc_init(&ctrl->alloc, &cfg->thrusters);
  if (st == UVMS_ERR_SINGULAR) return fail_cfg(ctrl, UVMS_CFG_THRUSTER_RANK, st);
  if (st != UVMS_OK) return fail_cfg(ctrl, UVMS_CFG_THRUSTER_GEOMETRY, st);

  st = uvms_thruster_params_validate(&cfg->thruster);
  if (st != UVMS_OK) return fail_cfg(ctrl, UVMS_CFG_THRUSTER_PARAMS, st);

  const uvms_pd_gains_t *g = &cfg->gains;
  const uvms_real_t gv[4] = {g->kpf_N_m, g->kdf_N_s_m, g->kpn_Nm_rad, g->kdn_Nm_s_rad};
  if (!finite_n(gv, 4)) return fail_cfg(ctrl, UVMS_CFG_GAINS, UVMS_ERR_NONFINITE);
  for (int k = 0; k < 4; ++k)
    if (gv[k] < UVMS_R(0.0)) return fail_cfg(ctrl, UVMS_CFG_GAINS, UVMS_ERR_RANGE);

  const uvms_switches_t *sw = &cfg->switches;
  if ((sw->attitude_control != 0 && sw->attitude_control != 1) ||
      (sw->position_feedforward != 0 && sw->position_feedforward != 1) ||
      (sw->position_feedback != 0 && sw->position_feedback != 1) ||
      (sw->position_reference != UVMS_REF_VEHICLE &&
       sw->position_reference != UVMS_REF_BARYCENTER))
    return fail_cfg(ctrl, UVMS_CFG_SWITCHES, UVMS_ERR_RANGE);

  if (!uvms_isfinite(cfg->joint_kq_1_s2) || !uvms_isfinite(cfg->joint_kqd_1_s))
    return fail_cfg(ctrl, UVMS_CFG_JOINT_SERVO, UVMS_ERR_NONFINITE);
  if (cfg->joint_kq_1_s2 < UVMS_R(0.0) || cfg->joint_kqd_1_s < UVMS_R(0.0))
    return fail_cfg(ctrl, UVMS_CFG_JOINT_SERVO, UVMS_ERR_RANGE);

  if (!uvms_isfinite(cfg->tick_s)) return fail_cfg(ctrl, UVMS_CFG_TICK, UVMS_ERR_NONFINITE);
  if (!(cfg->tick_s > UVMS_R(0.0))) return fail_cfg(ctrl, UVMS_CFG_TICK, UVMS_ERR_RANGE);

  const size_t n = cfg->arm.num_joints;
  if (!finite_n(cfg->theta_start_rad, n) || !finite_n(cfg->theta_final_rad, n) ||
      !uvms_isfinite(cfg->traj_start_s) || !uvms_isfinite(cfg->traj_duration_s))
    return fail_cfg(ctrl, UVMS_CFG_TRAJECTORY, UVMS_ERR_NONFINITE);
  if (cfg->traj_mode == UVMS_TRAJ_JOINT_CYCLOID) {
    if (!(cfg->traj_duration_s > UVMS_R(0.0)))
      return fail_cfg(ctrl, UVMS_CFG_TRAJECTORY, UVMS_ERR_RANGE);
  } else if (cfg->traj_mode == UVMS_TRAJ_CARTESIAN_LINE) {
    /* SPEC §8: the line is referenced to the vehicle or to the barycenter "as the case
       requires", i.e. to the point the position loop holds; anything else would move the EE
       along a line that the vehicle (or the barycenter) is not kept still for. */
    if (cfg->cart.reference != sw->position_reference)
      return fail_cfg(ctrl, UVMS_CFG_TRAJECTORY, UVMS_ERR_RANGE);
    /* Validate the Cartesian parameters now with a trial init at the start pose. */
    const uvms_real_t origin[3] = {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0)};
    uvms_real_t I3[9];
    uvms_m3_identity(I3);
    st = uvms_cart_traj_init(&ctrl->cart, &cfg->cart, &ctrl->model, &ctrl->data,
                             cfg->theta_start_rad, origin, I3);
    if (st != UVMS_OK) return fail_cfg(ctrl, UVMS_CFG_TRAJECTORY, st);
  } else if (cfg->traj_mode != UVMS_TRAJ_HOLD) {
    return fail_cfg(ctrl, UVMS_CFG_TRAJECTORY, UVMS_ERR_RANGE);
  }
  for (size_t j = 0; j < n && j < UVMS_MAX_JOINTS; ++j) {
    const uvms_link_params_t *L = &cfg->arm.link[j];
    (void)L; /* start/final angles outside the sensor limits would trip every tick */
    if (cfg->theta_start_rad[j] < L->joint_min_rad || cfg->theta_start_rad[j] > L->joint_max_rad)
      return fail_cfg(ctrl, UVMS_CFG_TRAJECTORY, UVMS_ERR_RANGE);
  }
  st = limits_validate(&cfg->limits);
  if (st != UVMS_OK) return fail_cfg(ctrl, UVMS_CFG_LIMITS, st);
  if (cfg->drive != UVMS_DRIVE_CURRENT && cfg->drive != UVMS_DRIVE_VOLTAGE)
    return fail_cfg(ctrl, UVMS_CFG_DRIVE, UVMS_ERR_RANGE);

  ctrl->fluid = cfg->fluid;
  ctrl->thruster = cfg->thruster;
  ctrl->drive = cfg->drive;
  ctrl->gains = cfg->gains;
  ctrl->switches = cfg->switches;
  ctrl->joint_kq_1_s2 = cfg->joint_kq_1_s2;
  ctrl->joint_kqd_1_s = cfg->joint_kqd_1_s;
  ctrl->tick_s = cfg->tick_s;
  ctrl->traj_mode = cfg->traj_mode;
  for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) {
    ctrl->theta_start_rad[j] = cfg->theta_start_rad[j];
    ctrl->theta_final_rad[j] = cfg->theta_final_rad[j];
  }
  ctrl->traj_start_s = cfg->traj_start_s;
  ctrl->traj_duration_s = cfg->traj_duration_s;
  /* The line is started at the first tick with the captured pose, from cart.p (not ready
     until then; the capture restores p when uvms_cart_traj_init fails and zeroes it). */
  memset(&ctrl->cart, 0, sizeof ctrl->cart);
  ctrl->cart.p = cfg->cart;
  ctrl->limits = cfg->limits;
  memset(&ctrl->last_good, 0, sizeof ctrl->last_good);
  ctrl->have_last_good = 0;
  ctrl->rejected_streak = 0u;
  for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) ctrl->q_ref_last_rad[j] = cfg->theta_start_rad[j];
  ctrl->config_error = UVMS_CFG_OK;
  ctrl->ready = 1;
  return UVMS_OK;
}

void uvms_ctrl_reset(uvms_ctrl_t *ctrl) {
  if (ctrl == NULL) return;
  /* q_ref_last_rad is kept: it is the reference the arm was last commanded, which is what an
     error before the next good tick must hold (controller.h). */
  ctrl->references_captured = 0;
  ctrl->have_last_tick = 0;
  ctrl->last_tick = 0;
  ctrl->have_last_good = 0; /* a record of the old sequence must not stand in for the new */
  ctrl->rejected_streak = 0u;
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) ctrl->current_cmd_next_A[j] = UVMS_R(0.0);
}

/* Per-thruster outputs of one tick: motor voltage, current command and its rate 0 (no motor
   torque in either drive) and the motor-loop telemetry 0 (no loop ran for thruster j). Used for
   unusable thrusters and on every exit that idles the thrusters. */
static void thruster_off(size_t j, uvms_ctrl_command_t *cmd, uvms_ctrl_telemetry_t *T) {
  cmd->motor_voltage_V[j] = UVMS_R(0.0);
  cmd->motor_current_cmd_A[j] = UVMS_R(0.0);
  cmd->motor_current_rate_A_s[j] = UVMS_R(0.0);
  T->omega_des_rad_s[j] = UVMS_R(0.0);
  T->current_des_A[j] = UVMS_R(0.0);
}

/*
 * The one safe output of uvms_ctrl_step (controller.h), written on entry and by every error
 * exit: every motor voltage 0 (and its loop telemetry 0), θ̈_cmd = 0, θ̇_ref = θ̈_ref = 0 and
 * θ_ref = the last good reference (θI before the first good tick; 0 when ctrl is NULL or not
 * initialised, when no reference is known). T->status = status; returns status.
 */
static uvms_status_t fail_safe(const uvms_ctrl_t *ctrl, uvms_ctrl_command_t *cmd,
                               uvms_ctrl_telemetry_t *T, uvms_status_t status) {
  if (cmd != NULL) {
    memset(cmd, 0, sizeof *cmd);
    if (ctrl != NULL && ctrl->ready)
      for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) cmd->q_ref_rad[j] = ctrl->q_ref_last_rad[j];
    for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) thruster_off(j, cmd, T);
  }
  T->status = status;
  return status;
}

/* The tick's joint command stands (UVMS_OK, or UVMS_ERR_SINGULAR: controller.h): its
   reference becomes the last good one. */
static void commit_reference(uvms_ctrl_t *ctrl, const uvms_ctrl_command_t *cmd) {
  for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) ctrl->q_ref_last_rad[j] = cmd->q_ref_rad[j];
}

/* bound > 0 (the check is on) and value above it. */
static int exceeds(uvms_real_t value, uvms_real_t bound) {
  return bound > UVMS_R(0.0) && value > bound;
}

/*
 * Validation of one record (docs/FAULTS.md): every cause that applies sets its flag; returns
 * UVMS_ERR_NONFINITE if any value is NaN/inf, else UVMS_ERR_RANGE if any other check failed,
 * else UVMS_OK. Motor speed and current are checked for usable thrusters only: an unusable
 * thruster's sensors are not read at all (its loop does not run), so a failed one cannot stop
 * the rest. The plausibility bounds apply to finite values only, so that a non-finite value
 * sets SENSOR_NONFINITE and nothing else (each flag names one cause).
 */
static uvms_status_t sensors_check(const uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *s,
                                   uint32_t usable, uint32_t *flags) {
  const size_t n = ctrl->model.p.num_joints;
  const size_t nt = ctrl->alloc.geom.num_thrusters;
  const uvms_ctrl_limits_t *lim = &ctrl->limits;
  uint32_t f = 0u;
  if (!uvms_isfinite(s->time_s) || !finite_n(s->position_m, 3) ||
      !finite_n(s->quaternion_wxyz, 4) || !finite_n(s->velocity_m_s, 3) ||
      !finite_n(s->omega_rad_s, 3)) {
    f |= UVMS_FLAG_SENSOR_NONFINITE;
  }
  /* Quaternion: |q| ∈ [0.5, 1.5] always (a rotation must be inferable), and within
     quat_norm_tol of 1 when that is set. Compared on |q|² to spare a square root:
     ||q| − 1| ≤ tol ⇔ (1 − tol)² ≤ |q|² ≤ (1 + tol)². */
  const uvms_real_t *q = s->quaternion_wxyz;
  const uvms_real_t n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  const uvms_real_t tol = lim->quat_norm_tol;
  const uvms_real_t lo = (tol > UVMS_R(0.0)) ? (UVMS_R(1.0) - tol) * (UVMS_R(1.0) - tol) : UVMS_R(0.25);
  const uvms_real_t hi = (tol > UVMS_R(0.0)) ? (UVMS_R(1.0) + tol) * (UVMS_R(1.0) + tol) : UVMS_R(2.25);
  if (n2 < lo || n2 > hi) f |= UVMS_FLAG_QUATERNION_INVALID;
  /* Joints: one pass for finiteness, limits and rates (NaN fails no limit comparison). */
  for (size_t j = 0; j < n && j < UVMS_MAX_JOINTS; ++j) {
    const uvms_link_params_t *L = &ctrl->model.p.link[j];
    const uvms_real_t q_rad = s->q_rad[j], qd_rad_s = s->qd_rad_s[j];
    if (!uvms_isfinite(q_rad) || !uvms_isfinite(qd_rad_s)) f |= UVMS_FLAG_SENSOR_NONFINITE;
    if (q_rad < L->joint_min_rad || q_rad > L->joint_max_rad) f |= UVMS_FLAG_JOINT_LIMIT;
    if (uvms_isfinite(qd_rad_s) && exceeds(uvms_fabs(qd_rad_s), lim->max_joint_rate_rad_s))
      f |= UVMS_FLAG_JOINT_RATE_IMPLAUSIBLE;
  }
  /* Usable thrusters: one pass for finiteness and the motor bounds. */
  for (size_t j = 0; j < nt && j < UVMS_MAX_THRUSTERS; ++j) {
    if (((usable >> j) & 1u) == 0u) continue;
    const uvms_real_t w_rad_s = s->motor_speed_rad_s[j], i_A = s->motor_current_A[j];
    if (!uvms_isfinite(w_rad_s) || !uvms_isfinite(i_A)) {
      f |= UVMS_FLAG_SENSOR_NONFINITE;
      continue;
    }
    if (exceeds(uvms_fabs(w_rad_s), lim->max_motor_speed_rad_s))
      f |= UVMS_FLAG_MOTOR_SPEED_IMPLAUSIBLE;
    if (exceeds(uvms_fabs(i_A), lim->max_motor_current_A))
      f |= UVMS_FLAG_MOTOR_CURRENT_IMPLAUSIBLE;
  }
  /* Speeds compared squared (no square root); for finite components an overflowing |v|² is
     +inf > bound²: still caught. */
  const uvms_real_t vmax = lim->max_vehicle_speed_m_s, wmax = lim->max_vehicle_rate_rad_s;
  if (uvms_v3_isfinite(s->velocity_m_s) &&
      exceeds(uvms_v3_dot(s->velocity_m_s, s->velocity_m_s), vmax * vmax))
    f |= UVMS_FLAG_VEHICLE_SPEED_IMPLAUSIBLE;
  if (uvms_v3_isfinite(s->omega_rad_s) &&
      exceeds(uvms_v3_dot(s->omega_rad_s, s->omega_rad_s), wmax * wmax))
    f |= UVMS_FLAG_ANGULAR_RATE_IMPLAUSIBLE;
  *flags |= f;
  if ((f & UVMS_FLAG_SENSOR_NONFINITE) != 0u) return UVMS_ERR_NONFINITE;
  return (f != 0u) ? UVMS_ERR_RANGE : UVMS_OK;
}

/* Joint reference at time t (SPEC §8). On failure the caller holds the last good reference. */
static uvms_status_t joint_reference(uvms_ctrl_t *ctrl, uvms_real_t t_s, uvms_ctrl_command_t *cmd) {
  const size_t n = ctrl->model.p.num_joints;
  const uvms_real_t tt = t_s - ctrl->traj_start_s;
  switch (ctrl->traj_mode) {
    case UVMS_TRAJ_JOINT_CYCLOID:
      return uvms_cycloid_eval(n, ctrl->theta_start_rad, ctrl->theta_final_rad,
                               ctrl->traj_duration_s, tt, cmd->q_ref_rad, cmd->qd_ref_rad_s,
                               cmd->qdd_ref_rad_s2);
    case UVMS_TRAJ_CARTESIAN_LINE: {
      if (tt < UVMS_R(0.0)) {
        for (size_t j = 0; j < n && j < UVMS_MAX_JOINTS; ++j)
          cmd->q_ref_rad[j] = ctrl->theta_start_rad[j];
        return UVMS_OK;
      }
      return uvms_cart_traj_step(&ctrl->cart, &ctrl->model, &ctrl->data, tt, ctrl->tick_s,
                                 cmd->q_ref_rad, cmd->qd_ref_rad_s, cmd->qdd_ref_rad_s2);
    }
    case UVMS_TRAJ_HOLD:
    default:
      for (size_t j = 0; j < n && j < UVMS_MAX_JOINTS; ++j)
        cmd->q_ref_rad[j] = ctrl->theta_start_rad[j];
      return UVMS_OK;
  }
}

/* The tick of uvms_ctrl_step without the current-command bookkeeping (advance_current_cmd). */
static uvms_status_t ctrl_step_core(uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *sensors,
                                    uvms_ctrl_command_t *cmd, uvms_ctrl_telemetry_t *tlm) {
  uvms_ctrl_telemetry_t tlm_local;
  uvms_ctrl_telemetry_t *T = (tlm != NULL) ? tlm : &tlm_local;
  memset(T, 0, sizeof *T);
  if (sensors != NULL) {
    T->tick = sensors->tick;
    T->time_s = sensors->time_s;
  }
  /* Safe output first; every error exit below re-establishes it through fail_safe. */
  (void)fail_safe(ctrl, cmd, T, UVMS_OK);
  if (cmd == NULL || ctrl == NULL || sensors == NULL) return fail_safe(ctrl, cmd, T, UVMS_ERR_ARG);
  if (!ctrl->ready) return fail_safe(ctrl, cmd, T, UVMS_ERR_STATE);
  const size_t n = ctrl->model.p.num_joints;
  const size_t nt = ctrl->alloc.geom.num_thrusters;
  const uint32_t all = (nt >= 32u) ? 0xFFFFFFFFu : ((1u << nt) - 1u);
  const uint32_t usable_in = sensors->thruster_usable_mask & all;

  /* 1. Sequence check. In the gap test tick > last ≥ INT64_MIN, so tick − 1 cannot overflow
        by itself (last + 1 was safe only through the branch before it). An out-of-order
        record is rejected below; any in-order one advances last_tick, also when its values
        are rejected (it was received: the next one is no gap). */
  int out_of_order = 0;
  if (ctrl->have_last_tick) {
    if (sensors->tick <= ctrl->last_tick) {
      T->flags |= UVMS_FLAG_TICK_NOT_INCREASING;
      out_of_order = 1;
    } else if (sensors->tick - 1 > ctrl->last_tick) {
      T->flags |= UVMS_FLAG_TICK_GAP;
    }
  }
  if (!out_of_order) {
    ctrl->last_tick = sensors->tick;
    ctrl->have_last_tick = 1;
  }
  /* 2. Validation and the hold-last-good policy (controller.h, docs/FAULTS.md). */
  uvms_status_t st = sensors_check(ctrl, sensors, usable_in, &T->flags);
  if (st == UVMS_OK && out_of_order) st = UVMS_ERR_RANGE;
  const uvms_ctrl_sensors_t *S = sensors; /* the record this tick runs on */
  if (st != UVMS_OK) {
    if (ctrl->rejected_streak < UINT32_MAX) ctrl->rejected_streak += 1u;
    T->sensor_rejected_ticks = ctrl->rejected_streak;
    if (!ctrl->have_last_good || ctrl->rejected_streak > ctrl->limits.sensor_hold_max_ticks) {
      T->flags |= UVMS_FLAG_SENSOR_HOLD_EXPIRED;
      return fail_safe(ctrl, cmd, T, st);
    }
    T->flags |= UVMS_FLAG_SENSOR_HELD;
    S = &ctrl->last_good;
  } else {
    ctrl->rejected_streak = 0u;
    ctrl->last_good = *sensors;
    ctrl->have_last_good = 1;
  }
  /* A thruster reported unusable is never driven, even by a held tick. */
  const uint32_t usable = S->thruster_usable_mask & usable_in;

  uvms_base_state_t base;
  memset(&base, 0, sizeof base);
  (void)uvms_quat_to_rot(S->quaternion_wxyz, base.R0); /* norm checked above */
  uvms_v3_copy(S->position_m, base.position_m);
  uvms_v3_copy(S->velocity_m_s, base.velocity_m_s);
  uvms_v3_copy(S->omega_rad_s, base.omega_rad_s);

  /* 3. Usable thrusters (H⁺ recomputed only when the set changes, allocation.c). Rank < 6 is
        served by the least-squares H⁺ (flag ALLOC_SINGULAR, the lost axes reported); only an
        H⁺ that could not be computed (UVMS_ERR_SINGULAR) idles the thrusters, not the arm;
        any other failure means a corrupt instance. */
  const uvms_status_t alloc_st = uvms_alloc_set_usable(&ctrl->alloc, usable);
  T->alloc_rank = (int32_t)ctrl->alloc.rank;
  T->uncontrollable_axes = ctrl->alloc.uncontrollable_axes;
  if (alloc_st == UVMS_ERR_SINGULAR || ctrl->alloc.rank < UVMS_ALLOC_WRENCH_DIM) {
    T->flags |= UVMS_FLAG_ALLOC_SINGULAR;
  }
  if (alloc_st != UVMS_OK && alloc_st != UVMS_ERR_SINGULAR) {
    T->flags |= UVMS_FLAG_MODEL_FAULT;
    return fail_safe(ctrl, cmd, T, alloc_st);
  }

  /* 4. References captured on the first valid tick: attitude, vehicle position, and the start
        of a Cartesian line. A line that cannot start fails the tick (hold); the capture is
        retried on the next one. */
  if (!ctrl->references_captured) {
    for (int k = 0; k < 9; ++k) ctrl->R0d[k] = base.R0[k];
    uvms_v3_copy(base.position_m, ctrl->r0d_m);
    if (ctrl->traj_mode == UVMS_TRAJ_CARTESIAN_LINE) {
      const uvms_cart_traj_params_t params = ctrl->cart.p;
      st = uvms_cart_traj_init(&ctrl->cart, &params, &ctrl->model, &ctrl->data,
                               ctrl->theta_start_rad, ctrl->r0d_m, ctrl->R0d);
      if (st != UVMS_OK) {
        ctrl->cart.p = params; /* init zeroed the instance; keep the line for the retry */
        T->flags |= UVMS_FLAG_TRAJECTORY_FAULT;
        return fail_safe(ctrl, cmd, T, st);
      }
    }
  }

  /* 5. Joint reference and servo (SPEC §8). A trajectory that fails mid-run holds the last good
        reference at rest and the tick goes on (flag TRAJECTORY_FAULT, controller.h). */
  st = joint_reference(ctrl, S->time_s, cmd);
  if (st != UVMS_OK) {
    T->flags |= UVMS_FLAG_TRAJECTORY_FAULT;
    for (size_t j = 0; j < UVMS_MAX_JOINTS; ++j) {
      cmd->q_ref_rad[j] = ctrl->q_ref_last_rad[j];
      cmd->qd_ref_rad_s[j] = UVMS_R(0.0);
      cmd->qdd_ref_rad_s2[j] = UVMS_R(0.0);
    }
  }
  st = uvms_joint_servo(n, cmd->q_ref_rad, cmd->qd_ref_rad_s, cmd->qdd_ref_rad_s2,
                        S->q_rad, S->qd_rad_s, ctrl->joint_kq_1_s2,
                        ctrl->joint_kqd_1_s, cmd->joint_accel_cmd_rad_s2);
  if (st != UVMS_OK) T->flags |= UVMS_FLAG_TRAJECTORY_FAULT;

  /* 6. Arm model and feedforward (SPEC §4, §7, §7.1); also the barycenter estimate [5]. */
  const uvms_switches_t *sw = &ctrl->switches;
  uvms_feedforward_t ff;
  st = uvms_feedforward(&ctrl->model, &ctrl->data, &ctrl->fluid, sw->position_reference, &base,
                        S->q_rad, S->qd_rad_s, cmd->joint_accel_cmd_rad_s2, &ff);
  if (st != UVMS_OK) {
    T->flags |= UVMS_FLAG_MODEL_FAULT;
    return fail_safe(ctrl, cmd, T, st);
  }
  uvms_v3_copy(ctrl->data.barycenter_m, T->barycenter_m);
  uvms_v3_copy(ctrl->data.barycenter_v_m_s, T->barycenter_v_m_s);
  uvms_v3_copy(ff.base_force_N, T->base_force_N);
  uvms_v3_copy(ff.base_moment_Nm, T->base_moment_Nm);
  uvms_v3_copy(ff.base_accel_m_s2, T->base_accel_model_m_s2);
  for (size_t j = 0; j < n && j < UVMS_MAX_JOINTS; ++j)
    T->joint_torque_model_Nm[j] = ctrl->data.tau_Nm[j + 1];

  if (!ctrl->references_captured) {
    uvms_v3_copy(T->barycenter_m, ctrl->barycenter0_m);
    if (sw->position_reference == UVMS_REF_BARYCENTER)
      uvms_v3_copy(T->barycenter_m, ctrl->r_d_m);
    else
      uvms_v3_copy(base.position_m, ctrl->r_d_m);
    ctrl->references_captured = 1;
    T->flags |= UVMS_FLAG_REFERENCE_CAPTURED;
  }
  uvms_v3_copy(ctrl->r_d_m, T->position_ref_m);

  /* 7. Feedback [40–46] and the Table X switches. */
  const int bary = (sw->position_reference == UVMS_REF_BARYCENTER);
  const uvms_real_t zero3[3] = {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0)};
  uvms_real_t N_fb[3], F_fb[3];
  (void)uvms_attitude_feedback(&ctrl->gains, ctrl->R0d, base.R0, base.omega_rad_s, N_fb,
                               T->attitude_error_rad);
  (void)uvms_position_feedback(&ctrl->gains, ctrl->r_d_m,
                               bary ? T->barycenter_m : base.position_m, zero3,
                               bary ? T->barycenter_v_m_s : base.velocity_m_s, F_fb);
  if (sw->position_feedforward)
    uvms_v3_copy(bary ? ff.force_barycenter_N : ff.force_vehicle_N, T->force_ff_N);
  if (sw->position_feedback) uvms_v3_copy(F_fb, T->force_fb_N);
  if (sw->attitude_control) {
    uvms_v3_copy(ff.moment_att_Nm, T->moment_ff_Nm);
    uvms_v3_copy(N_fb, T->moment_fb_Nm);
  }
  uvms_v3_add(T->force_ff_N, T->force_fb_N, T->force_des_N);   /* [46] */
  uvms_v3_add(T->moment_ff_Nm, T->moment_fb_Nm, T->moment_des_Nm); /* [41] */

  /* 8. EE estimate (SPEC §10): [3] at the reference pose (r0d, R0d), or [4] from the initial
        barycenter. Every point of the FK above is r0 + R0·(body-frame point of q), so the
        same arm seen from another vehicle pose is a rigid motion of this one:
          [3]: p̂_EE = r0d + R0d·R0ᵀ·(p_EE − r0);   [4]: p̂_EE = p_cm0 + R0d·R0ᵀ·(p_EE − p_cm).
        This replaces a second forward-kinematics pass (7 sin/cos pairs and 7 matrix products). */
  {
    uvms_real_t d[3], b[3], rel[3];
    uvms_v3_sub(ctrl->data.ee_m, bary ? T->barycenter_m : base.position_m, d);
    uvms_m3t_mul_v3(base.R0, d, b);
    uvms_m3_mul_v3(ctrl->R0d, b, rel);
    uvms_v3_add(bary ? ctrl->barycenter0_m : ctrl->r0d_m, rel, T->ee_estimate_m);
  }

  /* 9. Case I: no vehicle control at all → every thruster idle at zero voltage (SPEC §7.2). */
  if (!sw->attitude_control && !sw->position_feedforward && !sw->position_feedback) {
    T->flags |= UVMS_FLAG_THRUSTERS_IDLE;
    commit_reference(ctrl, cmd);
    T->status = UVMS_OK;
    return UVMS_OK;
  }
  /* No H⁺ at all: the vehicle cannot be controlled (voltages stay 0 from the safe output),
     the arm can: its command stands and is committed (controller.h). */
  if (alloc_st != UVMS_OK) {
    commit_reference(ctrl, cmd);
    T->status = alloc_st;
    return alloc_st;
  }

  /* 10. Allocation [38–39] (least squares at rank < 6), the thrust limit with attitude
         priority (allocation.h), the deliverable wrench, and the thruster loops [57–66], [53]. */
  st = uvms_alloc_step(&ctrl->alloc, base.R0, T->force_des_N, T->moment_des_Nm, T->thrust_des_N,
                       T->thrust_pos_N, T->thrust_att_N);
  if (st == UVMS_OK) {
    T->thrust_scale_pos = UVMS_R(1.0);
    T->thrust_scale_att = UVMS_R(1.0);
  }
  if (st == UVMS_OK && ctrl->limits.thrust_limit_N > UVMS_R(0.0)) {
    st = uvms_alloc_saturate(&ctrl->alloc, ctrl->limits.thrust_limit_N, T->thrust_pos_N,
                             T->thrust_att_N, T->thrust_des_N, &T->thrust_scale_pos,
                             &T->thrust_scale_att);
    if (T->thrust_scale_pos < UVMS_R(1.0) || T->thrust_scale_att < UVMS_R(1.0))
      T->flags |= UVMS_FLAG_THRUST_SATURATED;
  }
  if (st == UVMS_OK && ctrl->alloc.rank < UVMS_ALLOC_WRENCH_DIM) {
    /* What the commanded thrusts produce, back in inertial coordinates (H·P, then R0). */
    uvms_real_t w_b[UVMS_ALLOC_WRENCH_DIM];
    st = uvms_alloc_wrench_body(&ctrl->alloc, T->thrust_des_N, w_b);
    uvms_m3_mul_v3(base.R0, &w_b[0], T->force_deliverable_N);
    uvms_m3_mul_v3(base.R0, &w_b[3], T->moment_deliverable_Nm);
  } else if (st == UVMS_OK) {
    /* Full rank: H·H⁺ = I, so H·P = (s_pos·f_b; s_att·n_b) (uvms_alloc_saturate keeps each
       part's direction) and, rotated back, (s_pos·F; s_att·N): no n×6 product per tick. */
    uvms_v3_scale(T->force_des_N, T->thrust_scale_pos, T->force_deliverable_N);
    uvms_v3_scale(T->moment_des_Nm, T->thrust_scale_att, T->moment_deliverable_Nm);
  }
  if (st == UVMS_OK)
    st = uvms_thruster_advance_speeds(&ctrl->alloc.geom, base.R0, base.velocity_m_s,
                                      base.omega_rad_s, ctrl->fluid.flow_m_s,
                                      T->advance_speed_m_s);
  if (st != UVMS_OK) {
    T->flags |= UVMS_FLAG_MODEL_FAULT;
    return fail_safe(ctrl, cmd, T, st);
  }
  for (size_t j = 0; j < nt && j < UVMS_MAX_THRUSTERS; ++j) {
    if (((usable >> j) & 1u) == 0u) {
      /* Unusable: no loop, V_j = 0, its telemetry 0 (its thrust is 0 by H⁺'s zero row). */
      thruster_off(j, cmd, T);
      T->thrust_des_N[j] = UVMS_R(0.0);
      T->thrust_pos_N[j] = UVMS_R(0.0);
      T->thrust_att_N[j] = UVMS_R(0.0);
      T->advance_speed_m_s[j] = UVMS_R(0.0);
      continue;
    }
    uvms_motor_cmd_t mc;
    /* parameters validated once in uvms_ctrl_init */
    const uvms_status_t ms = uvms_motor_control_validated(
        &ctrl->thruster, ctrl->fluid.density_kg_m3, T->thrust_des_N[j], T->advance_speed_m_s[j],
        S->motor_speed_rad_s[j], S->motor_current_A[j], &mc);
    if (ms != UVMS_OK) {
      T->flags |= UVMS_FLAG_MOTOR_FAULT; /* mc is zeroed: V_j = 0 */
      thruster_off(j, cmd, T);           /* and no current in the current drive */
      continue;
    }
    if (mc.saturated) T->flags |= UVMS_FLAG_VOLTAGE_SATURATED;
    cmd->motor_voltage_V[j] = mc.voltage_V;
    /* [66]: the integrated current command and its rate (the current drive's I(t), SPEC §5) */
    cmd->motor_current_cmd_A[j] = ctrl->current_cmd_next_A[j];
    cmd->motor_current_rate_A_s[j] = mc.current_dot_cmd_A_s; /* İ* within the supply limit */
    T->omega_des_rad_s[j] = mc.omega_des_rad_s;
    T->current_des_A[j] = mc.current_des_A;
  }
  commit_reference(ctrl, cmd);
  T->status = UVMS_OK;
  return UVMS_OK;
}

/* [66] integrated: the current each thruster's command reaches at the end of this tick,
   I*_j + İ*_j·tick_s, is the next tick's I*_j. After a safe output (all zero), or with no
   command at all, it is 0: the current drive then held no current. */
static void advance_current_cmd(uvms_ctrl_t *ctrl, const uvms_ctrl_command_t *cmd) {
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    const uvms_real_t next_A =
        (cmd == NULL) ? UVMS_R(0.0)
                      : cmd->motor_current_cmd_A[j] + cmd->motor_current_rate_A_s[j] * ctrl->tick_s;
    ctrl->current_cmd_next_A[j] = uvms_isfinite(next_A) ? next_A : UVMS_R(0.0); /* overflow */
  }
}

uvms_status_t uvms_ctrl_step(uvms_ctrl_t *ctrl, const uvms_ctrl_sensors_t *sensors,
                             uvms_ctrl_command_t *cmd, uvms_ctrl_telemetry_t *tlm) {
  const uvms_status_t st = ctrl_step_core(ctrl, sensors, cmd, tlm);
  if (ctrl != NULL && ctrl->ready) advance_current_cmd(ctrl, cmd);
  return st;
}
