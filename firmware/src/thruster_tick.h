/* SPDX-License-Identifier: Apache-2.0 */
/* thruster_tick.h: the thruster module's per-tick core (internal, not part of the public API).
 *
 *   uvms_motor_step_fast() and the functions under it  one thruster's loop, given the thrust
 *                        and torque laws' factors that depend on the parameters and the
 *                        density only (uvms_motor_t keeps them per thruster), and its two
 *                        stages uvms_motor_speed_fast() and uvms_motor_drive_fast(), which the
 *                        tick calls itself (controller.c, UVMS_FW_WORK_AHEAD)
 *
 * The code of thruster.c's per-tick path, static inline so that the controller's tick
 * (controller.c) inlines it: a call per thruster with eight arguments cost more than its
 * checks. thruster.c's public uvms_motor_step and uvms_motor_control call the same code.
 */
#ifndef UVMS_THRUSTER_TICK_H
#define UVMS_THRUSTER_TICK_H

#include "uvms/thruster.h"
#include "fw_fast.h"


/* The thruster loop of one thruster (thruster.c's uvms_motor_step and uvms_motor_control use
   these too), static inline here so that the controller's tick inlines it: a call per
   thruster with eight arguments cost more than its checks. */

/* SPEC §5: Q = ρD⁵/(4π²)·(CQ2·ω|ω| + CQ1·(2π·v_a/D)·|ω|) [N·m], with k->kq_kg_m2 = ρD⁵/(4π²)
   and k->two_pi_over_D_1_m = 2π/D (uvms_thruster_coef_t). */
UVMS_FW_INLINE uvms_real_t uvms_torque_with_k(const uvms_thruster_params_t *p,
                                              const uvms_thruster_coef_t *k,
                                              uvms_real_t omega_rad_s,
                                              uvms_real_t advance_speed_m_s) {
  const uvms_real_t abs_w = uvms_fabs(omega_rad_s);
  return k->kq_kg_m2 * (p->cq2 * omega_rad_s * abs_w +
                        p->cq1 * (k->two_pi_over_D_1_m * advance_speed_m_s) * abs_w);
}

/* [57–63] for parameters already validated (uvms_thruster_params_validate) and finite
   inputs with density_kg_m3 > 0 (thruster.c's desired_speed_core checks them,
   uvms_motor_control_core has); c1 = k->c1_N_s2 = CT2·ρD⁴/(4π²) [N·s²], c2 = CT1·ρD³/(2π)·v_a
   [N·s] (uvms_thruster_coef_t). Why these roots, and their forms free of cancellation:
   thruster.c, above desired_speed_core. One division: the root's. */
UVMS_FW_INLINE uvms_status_t uvms_desired_speed_finite(const uvms_thruster_coef_t *k,
                                                       uvms_real_t thrust_N,
                                                       uvms_real_t advance_speed_m_s,
                                                       uvms_real_t *omega_rad_s) {
  *omega_rad_s = UVMS_R(0.0);
  if (thrust_N == UVMS_R(0.0)) return UVMS_OK; /* T(0) = 0: ω = 0 (thruster.c) */

  const uvms_real_t c1 = k->c1_N_s2;
  const uvms_real_t c2 = k->c2_N_s2_m * advance_speed_m_s;          /* [N·s] */
  const uvms_real_t c3 = uvms_fabs(thrust_N);                        /* [N] */
  const uvms_real_t disc = c2 * c2 - UVMS_R(4.0) * c1 * c3;          /* [N²·s²] ≥ c2² */
  if (!uvms_isfinite(disc)) return UVMS_ERR_RANGE;
  const uvms_real_t s = uvms_sqrt(disc);

  uvms_real_t w;
  if (thrust_N > UVMS_R(0.0)) {
    /* root ω+ ≤ 0 [57–63] */
    w = (c2 > UVMS_R(0.0)) ? UVMS_R(2.0) * c3 / (-c2 - s) : (-c2 + s) / (UVMS_R(2.0) * c1);
  } else {
    /* root ω− ≥ 0 [57–63] */
    w = (c2 < UVMS_R(0.0)) ? UVMS_R(2.0) * c3 / (-c2 + s) : (-c2 - s) / (UVMS_R(2.0) * c1);
  }
  if (!uvms_isfinite(w)) return UVMS_ERR_RANGE;
  *omega_rad_s = w;
  return UVMS_OK;
}

/* SPEC §7.4 for parameters already validated, in two stages: uvms_motor_speed_stage (the
   inputs checked and the desired shaft speed [57–63]) and uvms_motor_drive_stage (the speed
   and current loops from it [64–66], [53]); uvms_motor_control_core runs both. On a 64-bit host
   (UVMS_FW_WORK_AHEAD, fw_fast.h) the controller's tick runs the first stage of every thruster
   before the second of any (controller.c): each speed is a square root and a division that the
   second stage's chain of products waits on, and in a loop of their own the eight overlap. */
UVMS_FW_INLINE uvms_status_t uvms_motor_speed_stage(const uvms_thruster_coef_t *k,
                                                    uvms_real_t density_kg_m3,
                                                    uvms_real_t thrust_des_N,
                                                    uvms_real_t advance_speed_m_s,
                                                    uvms_real_t omega_meas_rad_s,
                                                    uvms_real_t current_meas_A,
                                                    uvms_real_t *w_des_rad_s) {
  *w_des_rad_s = UVMS_R(0.0);
  /* Σ 0·x over the inputs (uvms_nonfinite_probe), summed pairwise from registers */
  const uvms_real_t z = UVMS_R(0.0);
  const uvms_real_t in_probe = (z * density_kg_m3 + z * thrust_des_N) +
                               (z * advance_speed_m_s + z * omega_meas_rad_s) +
                               z * current_meas_A;
  if (in_probe != UVMS_R(0.0)) return UVMS_ERR_NONFINITE;
  if (!(density_kg_m3 > UVMS_R(0.0))) return UVMS_ERR_RANGE;
  /* [57–63] desired shaft speed (inputs finite and ρ > 0: checked above) */
  return uvms_desired_speed_finite(k, thrust_des_N, advance_speed_m_s, w_des_rad_s);
}

/* The second stage, from a desired speed uvms_motor_speed_stage gave with UVMS_OK for the same
   inputs. Writes every field of cmd when it returns UVMS_OK and none otherwise (the callers
   then write the safe output). */
UVMS_FW_INLINE uvms_status_t uvms_motor_drive_stage(const uvms_thruster_params_t *p,
                                                    const uvms_thruster_coef_t *k,
                                                    uvms_real_t w_des_rad_s,
                                                    uvms_real_t advance_speed_m_s,
                                                    uvms_real_t omega_meas_rad_s,
                                                    uvms_real_t current_meas_A,
                                                    uvms_motor_cmd_t *cmd) {
  const uvms_real_t z = UVMS_R(0.0);
  const uvms_real_t w_rad_s = omega_meas_rad_s;
  const uvms_real_t I_A = current_meas_A;
  /* [64] speed loop: ω̂̇ = KA·(ω̂ − ω) [rad/s²] */
  const uvms_real_t wdot_des_rad_s2 = p->speed_gain_1_s * (w_des_rad_s - w_rad_s);
  /* [65] current that gives ω̂̇ through J·ω̇ = km·I − b·ω − Q [53–55] */
  const uvms_real_t Q_Nm = uvms_torque_with_k(p, k, w_rad_s, advance_speed_m_s);
  const uvms_real_t I_des_A = (p->rotor_inertia_kg_m2 * wdot_des_rad_s2 +
                               p->viscous_friction_Nm_s * w_rad_s + Q_Nm) *
                              k->inv_km_A_Nm;
  /* [66] current loop: İ* = KB·(Î − I) [A/s] */
  const uvms_real_t Idot_des_A_s = p->current_gain_1_s * (I_des_A - I_A);
  /* [53] voltage that gives İ* through Lm·İ = V − Rm·I − km·ω [53–55] */
  const uvms_real_t V_V = p->resistance_ohm * I_A + p->inductance_H * Idot_des_A_s +
                          p->torque_constant_Nm_A * w_rad_s;

  const uvms_real_t out_probe =
      (z * wdot_des_rad_s2 + z * I_des_A) + (z * Idot_des_A_s + z * V_V); /* the same, outputs */
  if (out_probe != UVMS_R(0.0))
    return UVMS_ERR_NONFINITE; /* overflow of huge finite inputs; cmd is still all zero */
  cmd->omega_des_rad_s = w_des_rad_s;
  cmd->omega_dot_des_rad_s2 = wdot_des_rad_s2;
  cmd->current_des_A = I_des_A;
  cmd->current_dot_des_A_s = Idot_des_A_s;
  /* Supply clamp: |V| ≤ voltage_limit_V. The current drive's rate is the one the clamped
     voltage gives through [53] at the tick's start: the same limit in both drives. */
  if (V_V > p->voltage_limit_V) {
    cmd->voltage_V = p->voltage_limit_V;
    cmd->saturated = 1;
  } else if (V_V < -p->voltage_limit_V) {
    cmd->voltage_V = -p->voltage_limit_V;
    cmd->saturated = 1;
  } else {
    cmd->voltage_V = V_V;
    cmd->saturated = 0;
  }
  cmd->current_dot_cmd_A_s = cmd->saturated ? (cmd->voltage_V - p->resistance_ohm * I_A -
                                                p->torque_constant_Nm_A * w_rad_s) /
                                                   p->inductance_H
                                             : Idot_des_A_s;
  return UVMS_OK;
}

/* Both stages (SPEC §7.4) for parameters already validated. Writes every field of cmd when it
   returns UVMS_OK and none otherwise (the callers then write the safe output). */
UVMS_FW_INLINE uvms_status_t uvms_motor_control_core(const uvms_thruster_params_t *p,
                                                     const uvms_thruster_coef_t *k,
                                                     uvms_real_t density_kg_m3,
                                                     uvms_real_t thrust_des_N,
                                                     uvms_real_t advance_speed_m_s,
                                                     uvms_real_t omega_meas_rad_s,
                                                     uvms_real_t current_meas_A,
                                                     uvms_motor_cmd_t *cmd) {
  uvms_real_t w_des_rad_s;
  const uvms_status_t st = uvms_motor_speed_stage(k, density_kg_m3, thrust_des_N,
                                                  advance_speed_m_s, omega_meas_rad_s,
                                                  current_meas_A, &w_des_rad_s);
  if (st != UVMS_OK) return st;
  return uvms_motor_drive_stage(p, k, w_des_rad_s, advance_speed_m_s, omega_meas_rad_s,
                                current_meas_A, cmd);
}

/* uvms_motor_step (thruster.h) for an index the caller has bounded by the instance's count,
   inlined, in its two stages: uvms_motor_speed_fast, then uvms_motor_drive_fast with the speed
   and status it gave. Same results, statuses and safe output as uvms_motor_step. j is checked
   against the array bound on every call; an entry at or beyond num_thrusters holds thruster 1's
   set (never NULL), so a caller's corrupted count cannot make it read outside the instance. */
UVMS_FW_INLINE uvms_status_t uvms_motor_speed_fast(const uvms_motor_t *motor, size_t j,
                                                   uvms_real_t thrust_des_N,
                                                   uvms_real_t advance_speed_m_s,
                                                   uvms_real_t omega_meas_rad_s,
                                                   uvms_real_t current_meas_A,
                                                   uvms_real_t *w_des_rad_s) {
  *w_des_rad_s = UVMS_R(0.0);
  if (motor == NULL) return UVMS_ERR_ARG;
  if (!motor->ready) return UVMS_ERR_STATE;
  if (j >= UVMS_MAX_THRUSTERS) return UVMS_ERR_ARG;
  return uvms_motor_speed_stage(&motor->coef[j], motor->density_kg_m3, thrust_des_N,
                                advance_speed_m_s, omega_meas_rad_s, current_meas_A,
                                w_des_rad_s);
}

/* The second stage: speed_st is uvms_motor_speed_fast's status for the same motor, j and
   inputs, w_des_rad_s its speed. Writes every field of cmd: the loop's command, or the safe
   output V = 0 (all zero) on every failure, the first stage's included. */
UVMS_FW_INLINE uvms_status_t uvms_motor_drive_fast(const uvms_motor_t *motor, size_t j,
                                                   uvms_status_t speed_st,
                                                   uvms_real_t w_des_rad_s,
                                                   uvms_real_t advance_speed_m_s,
                                                   uvms_real_t omega_meas_rad_s,
                                                   uvms_real_t current_meas_A,
                                                   uvms_motor_cmd_t *cmd) {
  if (cmd == NULL) return UVMS_ERR_ARG;
  uvms_status_t st = speed_st;
  if (st == UVMS_OK && motor != NULL && j < UVMS_MAX_THRUSTERS)
    st = uvms_motor_drive_stage(motor->p[j], &motor->coef[j], w_des_rad_s, advance_speed_m_s,
                                omega_meas_rad_s, current_meas_A, cmd);
  else if (st == UVMS_OK)
    st = UVMS_ERR_ARG;
  /* Safe output V = 0 on every failure (uvms_motor_drive_stage writes cmd, every field of it,
     only when it succeeds). */
  if (st != UVMS_OK) uvms_clear_record(cmd, sizeof(*cmd));
  return st;
}

/* Both stages for one thruster (thruster.c's uvms_motor_step). */
UVMS_FW_INLINE uvms_status_t uvms_motor_step_fast(const uvms_motor_t *motor, size_t j,
                                                  uvms_real_t thrust_des_N,
                                                  uvms_real_t advance_speed_m_s,
                                                  uvms_real_t omega_meas_rad_s,
                                                  uvms_real_t current_meas_A,
                                                  uvms_motor_cmd_t *cmd) {
  if (cmd == NULL) return UVMS_ERR_ARG;
  uvms_real_t w_des_rad_s;
  const uvms_status_t speed_st =
      uvms_motor_speed_fast(motor, j, thrust_des_N, advance_speed_m_s, omega_meas_rad_s,
                            current_meas_A, &w_des_rad_s);
  return uvms_motor_drive_fast(motor, j, speed_st, w_des_rad_s, advance_speed_m_s,
                               omega_meas_rad_s, current_meas_A, cmd);
}

#endif /* UVMS_THRUSTER_TICK_H */
