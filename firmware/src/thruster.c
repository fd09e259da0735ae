/* SPDX-License-Identifier: Apache-2.0 */
/* thruster.c: thruster hydrodynamics and the per-thruster speed/current/voltage controller,
 * SPEC §5 [47–55] and §7.4 [56–66] (thruster.h). No allocation; the only state is the
 * caller-owned uvms_motor_t (validated parameters, integrated current commands). */
#include "uvms/thruster.h"

#include <string.h>

#include "fw_fast.h"
#include "thruster_tick.h"

const char *uvms_drive_str(uvms_drive_t drive) {
  switch (drive) {
    case UVMS_DRIVE_CURRENT: return "current";
    case UVMS_DRIVE_VOLTAGE: return "voltage";
    default: return "invalid";
  }
}

uvms_status_t uvms_drive_check(uvms_drive_t drive) {
  return (drive == UVMS_DRIVE_CURRENT || drive == UVMS_DRIVE_VOLTAGE) ? UVMS_OK : UVMS_ERR_RANGE;
}

void uvms_thruster_params_paper(uvms_thruster_params_t *p) {
  if (p == NULL) return;
  memset(p, 0, sizeof(*p));
  /* SPEC §3.4 */
  p->diameter_m = UVMS_R(0.05);
  p->ct1 = UVMS_R(0.5);
  p->ct2 = UVMS_R(-0.5);
  p->cq1 = UVMS_R(0.15);
  p->cq2 = UVMS_R(-0.15);
  p->resistance_ohm = UVMS_R(1.0);
  p->inductance_H = UVMS_R(1.0);
  p->torque_constant_Nm_A = UVMS_R(10.0);
  p->viscous_friction_Nm_s = UVMS_R(0.01);
  p->rotor_inertia_kg_m2 = UVMS_R(0.01);
  p->speed_gain_1_s = UVMS_R(5.0);
  p->current_gain_1_s = UVMS_R(5.0);
  /* Not in the paper: effectively unlimited (see thruster.h for why not 1000 V). */
  p->voltage_limit_V = UVMS_R(1.0e5);
}

uvms_real_t uvms_thruster_ramp_lag_s(const uvms_thruster_params_t *p) {
  if (p == NULL) return UVMS_R(0.0);
  const uvms_real_t ka = p->speed_gain_1_s, kb = p->current_gain_1_s, J = p->rotor_inertia_kg_m2;
  if (!(ka > UVMS_R(0.0)) || !(kb > UVMS_R(0.0)) || !(J > UVMS_R(0.0))) return UVMS_R(0.0);
  return (kb + p->viscous_friction_Nm_s / J) / (ka * kb); /* −G'(0), thruster.h */
}

uvms_status_t uvms_thruster_params_validate(const uvms_thruster_params_t *p) {
  if (p == NULL) return UVMS_ERR_ARG;
  const uvms_real_t v[13] = {p->diameter_m,           p->ct1,
                             p->ct2,                  p->cq1,
                             p->cq2,                  p->resistance_ohm,
                             p->inductance_H,         p->torque_constant_Nm_A,
                             p->viscous_friction_Nm_s, p->rotor_inertia_kg_m2,
                             p->speed_gain_1_s,       p->current_gain_1_s,
                             p->voltage_limit_V};
  if (!uvms_all_finite(v, 13)) return UVMS_ERR_NONFINITE;
  if (!(p->diameter_m > UVMS_R(0.0)) || !(p->resistance_ohm > UVMS_R(0.0)) ||
      !(p->inductance_H > UVMS_R(0.0)) || !(p->torque_constant_Nm_A > UVMS_R(0.0)) ||
      !(p->viscous_friction_Nm_s >= UVMS_R(0.0)) || !(p->rotor_inertia_kg_m2 > UVMS_R(0.0)) ||
      !(p->speed_gain_1_s > UVMS_R(0.0)) || !(p->current_gain_1_s > UVMS_R(0.0)) ||
      !(p->voltage_limit_V > UVMS_R(0.0))) {
    return UVMS_ERR_RANGE;
  }
  /* CT2 < 0 keeps the discriminant of [57–63] non-negative (thruster.h). */
  if (!(p->ct2 < UVMS_R(0.0))) return UVMS_ERR_RANGE;
  return UVMS_OK;
}

uvms_real_t uvms_thruster_thrust_N(const uvms_thruster_params_t *p, uvms_real_t density_kg_m3,
                                   uvms_real_t omega_rad_s, uvms_real_t advance_speed_m_s) {
  if (p == NULL) return UVMS_R(0.0);
  const uvms_real_t D_m = p->diameter_m;
  /* SPEC §5: T = ρD⁴/(4π²)·(CT2·ω|ω| + CT1·(2π·v_a/D)·|ω|) [N] */
  const uvms_real_t k_kg_m = density_kg_m3 * D_m * D_m * D_m * D_m / (UVMS_R(4.0) * UVMS_PI * UVMS_PI);
  const uvms_real_t abs_w = uvms_fabs(omega_rad_s);
  return k_kg_m * (p->ct2 * omega_rad_s * abs_w +
                   p->ct1 * (UVMS_R(2.0) * UVMS_PI * advance_speed_m_s / D_m) * abs_w);
}

/* The factors of the thrust [57–63], torque (SPEC §5) and current [65] laws that depend on
   the parameters and the density only (uvms_thruster_coef_t): uvms_motor_init_each keeps them
   per thruster, the per-call functions compute them on each call. */
static uvms_thruster_coef_t thruster_coef(const uvms_thruster_params_t *p,
                                          uvms_real_t density_kg_m3) {
  const uvms_real_t D_m = p->diameter_m;
  uvms_thruster_coef_t k;
  k.c1_N_s2 = p->ct2 * density_kg_m3 * D_m * D_m * D_m * D_m /
              (UVMS_R(4.0) * UVMS_PI * UVMS_PI); /* c1 = CT2·ρD⁴/(4π²) [N·s²] < 0 */
  k.c2_N_s2_m = p->ct1 * density_kg_m3 * D_m * D_m * D_m / (UVMS_R(2.0) * UVMS_PI);
  k.kq_kg_m2 = density_kg_m3 * D_m * D_m * D_m * D_m * D_m / (UVMS_R(4.0) * UVMS_PI * UVMS_PI);
  k.two_pi_over_D_1_m = UVMS_R(2.0) * UVMS_PI / D_m;
  k.inv_km_A_Nm = UVMS_R(1.0) / p->torque_constant_Nm_A;
  return k;
}

uvms_real_t uvms_thruster_torque_Nm(const uvms_thruster_params_t *p, uvms_real_t density_kg_m3,
                                    uvms_real_t omega_rad_s, uvms_real_t advance_speed_m_s) {
  if (p == NULL) return UVMS_R(0.0);
  const uvms_thruster_coef_t k = thruster_coef(p, density_kg_m3);
  return uvms_torque_with_k(p, &k, omega_rad_s, advance_speed_m_s);
}

/*
 * Desired speed [57–63]: why the paper's roots have the right sign.
 *
 * With k = ρD⁴/(4π²) > 0, c1 = CT2·k < 0 and c2 = CT1·v_a·ρD³/(2π) = k·CT1·2π·v_a/D, the
 * thrust law of §5 is T(ω) = c1·ω|ω| + c2·|ω|, i.e.
 *     ω ≥ 0:  T = c1ω² + c2ω;        ω ≤ 0:  T = −(c1ω² + c2ω).
 * The quadratic c1ω² + c2ω + c3 = 0 with c3 = |T| says c1ω² + c2ω = −|T|. Its discriminant is
 * disc = c2² − 4c1c3 = c2² + 4|c1||T| ≥ c2², so s = √disc ≥ |c2| and
 *     ω+ = (−c2 + s)/(2c1):  numerator ≥ 0, denominator < 0  ⇒  ω+ ≤ 0,
 *     ω− = (−c2 − s)/(2c1):  numerator ≤ 0, denominator < 0  ⇒  ω− ≥ 0.
 * T ≥ 0, root ω+ ≤ 0: T(ω+) = −(c1ω+² + c2ω+) = |T| = T.            ✓
 * T < 0, root ω− ≥ 0: T(ω−) = c1ω−² + c2ω− = −|T| = T.              ✓
 * So each root lies on the branch of |ω| that the quadratic assumed, for every sign of v_a;
 * hence positive thrust needs negative shaft speed, negative thrust positive speed.
 *
 * T = 0: the law gives T(0) = 0, so ω = 0 (the least speed, zero power). The quadratic's
 * ω+ would be (−c2 + |c2|)/(2c1), which is 0 for c2 ≥ 0 but |c2|/c1 ≠ 0 for c2 < 0, the other
 * zero of the thrust law; it is skipped. Note that for c2 < 0 (CT1·v_a < 0) the inverse is
 * genuinely discontinuous at T = 0+: on ω ≤ 0 the law is ω·(|c1|ω + |c2|), negative on
 * (−|c2|/|c1|, 0), so any positive thrust needs |ω| > |c2|/|c1|.
 *
 * Cancellation: −c2 + s loses digits when c2 > 0 and s ≈ c2 (small |T|, large c2);
 * −c2 − s loses digits when c2 < 0. The product of the roots is c3/c1, so
 *     ω+ = 2c3/(−c2 − s),   ω− = 2c3/(−c2 + s)
 * (multiply numerator and denominator by the conjugate; c2² − s² = 4c1c3). Use those forms in
 * exactly the cases where the plain form cancels; their denominators are then −(c2 + s) < 0
 * and |c2| + s > 0, never zero.
 *
 * The computation is uvms_desired_speed_finite (thruster_tick.h, inlined into the tick), below with
 * its inputs checked; the thruster loop, uvms_motor_control_core, is there too.
 */
/* [57–63] for parameters already validated: the inputs checked, then
   uvms_desired_speed_finite. */
static uvms_status_t desired_speed_core(const uvms_thruster_params_t *p,
                                        uvms_real_t density_kg_m3, uvms_real_t thrust_N,
                                        uvms_real_t advance_speed_m_s,
                                        uvms_real_t *omega_rad_s) {
  *omega_rad_s = UVMS_R(0.0);
  if (!uvms_isfinite(density_kg_m3) || !uvms_isfinite(thrust_N) ||
      !uvms_isfinite(advance_speed_m_s)) {
    return UVMS_ERR_NONFINITE;
  }
  if (!(density_kg_m3 > UVMS_R(0.0))) return UVMS_ERR_RANGE;
  const uvms_thruster_coef_t k = thruster_coef(p, density_kg_m3);
  return uvms_desired_speed_finite(&k, thrust_N, advance_speed_m_s, omega_rad_s);
}

uvms_status_t uvms_thruster_desired_speed(const uvms_thruster_params_t *p,
                                          uvms_real_t density_kg_m3, uvms_real_t thrust_N,
                                          uvms_real_t advance_speed_m_s,
                                          uvms_real_t *omega_rad_s) {
  if (omega_rad_s == NULL) return UVMS_ERR_ARG;
  *omega_rad_s = UVMS_R(0.0);
  const uvms_status_t st = uvms_thruster_params_validate(p);
  if (st != UVMS_OK) return st;
  return desired_speed_core(p, density_kg_m3, thrust_N, advance_speed_m_s, omega_rad_s);
}

uvms_status_t uvms_motor_control(const uvms_thruster_params_t *p, uvms_real_t density_kg_m3,
                                 uvms_real_t thrust_des_N, uvms_real_t advance_speed_m_s,
                                 uvms_real_t omega_meas_rad_s, uvms_real_t current_meas_A,
                                 uvms_motor_cmd_t *cmd) {
  if (cmd == NULL) return UVMS_ERR_ARG;
  memset(cmd, 0, sizeof(*cmd)); /* safe output: V = 0 */
  const uvms_status_t pst = uvms_thruster_params_validate(p);
  if (pst != UVMS_OK) return pst;
  const uvms_thruster_coef_t k = thruster_coef(p, density_kg_m3);
  return uvms_motor_control_core(p, &k, density_kg_m3, thrust_des_N, advance_speed_m_s,
                                 omega_meas_rad_s, current_meas_A, cmd);
}

/* Validates sets p[0..n) (p[0] only when one_set) and the loop constants, and fills motor. */
static uvms_status_t motor_init(uvms_motor_t *motor, const uvms_thruster_params_t *p, int one_set,
                                size_t num_thrusters, uvms_real_t density_kg_m3, uvms_real_t tick_s) {
  if (motor == NULL) return UVMS_ERR_ARG;
  memset(motor, 0, sizeof(*motor));
  if (p == NULL) return UVMS_ERR_ARG;
  if (num_thrusters < 1u || num_thrusters > UVMS_MAX_THRUSTERS) return UVMS_ERR_SIZE;
  const size_t sets = one_set ? 1u : num_thrusters;
  for (size_t j = 0; j < sets; ++j) {
    const uvms_status_t st = uvms_thruster_params_validate(&p[j]);
    if (st != UVMS_OK) return st;
  }
  if (!uvms_isfinite(density_kg_m3) || !uvms_isfinite(tick_s)) return UVMS_ERR_NONFINITE;
  if (!(density_kg_m3 > UVMS_R(0.0)) || !(tick_s > UVMS_R(0.0))) return UVMS_ERR_RANGE;
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) { /* j ≥ n: thruster 1's (thruster_tick.h) */
    const uvms_thruster_params_t *pj = (one_set || j >= num_thrusters) ? &p[0] : &p[j];
    motor->p[j] = pj;
    motor->coef[j] = thruster_coef(pj, density_kg_m3);
  }
  motor->num_thrusters = num_thrusters;
  motor->density_kg_m3 = density_kg_m3;
  motor->tick_s = tick_s;
  motor->ready = 1;
  return UVMS_OK;
}

uvms_status_t uvms_motor_init(uvms_motor_t *motor, const uvms_thruster_params_t *p,
                              uvms_real_t density_kg_m3, uvms_real_t tick_s) {
  return motor_init(motor, p, 1, UVMS_MAX_THRUSTERS, density_kg_m3, tick_s);
}

uvms_status_t uvms_motor_init_each(uvms_motor_t *motor,
                                   const uvms_thruster_params_t p[UVMS_MAX_THRUSTERS],
                                   size_t num_thrusters, uvms_real_t density_kg_m3,
                                   uvms_real_t tick_s) {
  return motor_init(motor, p, 0, num_thrusters, density_kg_m3, tick_s);
}

void uvms_motor_reset(uvms_motor_t *motor) {
  if (motor == NULL) return;
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) motor->current_cmd_A[j] = UVMS_R(0.0);
}

uvms_status_t uvms_motor_step(const uvms_motor_t *motor, size_t j, uvms_real_t thrust_des_N,
                              uvms_real_t advance_speed_m_s, uvms_real_t omega_meas_rad_s,
                              uvms_real_t current_meas_A, uvms_motor_cmd_t *cmd) {
  if (cmd != NULL && motor != NULL && motor->ready && j >= motor->num_thrusters) {
    memset(cmd, 0, sizeof(*cmd)); /* safe output: V = 0 */
    return UVMS_ERR_ARG;
  }
  return uvms_motor_step_fast(motor, j, thrust_des_N, advance_speed_m_s, omega_meas_rad_s,
                              current_meas_A, cmd);
}

void uvms_motor_end_tick(uvms_motor_t *motor, const uvms_real_t *current_cmd_A,
                         const uvms_real_t *current_rate_A_s) {
  if (motor == NULL) return;
  const int have_cmd = current_cmd_A != NULL && current_rate_A_s != NULL;
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    const uvms_real_t next_A =
        have_cmd ? current_cmd_A[j] + current_rate_A_s[j] * motor->tick_s : UVMS_R(0.0);
    motor->current_cmd_A[j] = uvms_isfinite(next_A) ? next_A : UVMS_R(0.0); /* overflow */
  }
}
