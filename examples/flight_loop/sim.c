/* SPDX-License-Identifier: Apache-2.0 */
/* sim.c: see sim.h. */
#include "sim.h"

#include <string.h>

#include "uvms/linalg.h"

/* Residual attitude motion: yaw ψ(t) = A_ψ·sin(w_ψ·t), pitch θ(t) = A_θ·sin(w_θ·t). */
#define SIM_YAW_AMPL_RAD UVMS_R(0.01)
#define SIM_YAW_FREQ_RAD_S UVMS_R(0.2)
#define SIM_PITCH_AMPL_RAD UVMS_R(0.005)
#define SIM_PITCH_FREQ_RAD_S UVMS_R(0.13)

void sim_init(sim_t *sim, const uvms_ctrl_config_t *cfg) {
  memset(sim, 0, sizeof *sim);
  for (int i = 0; i < UVMS_MAX_JOINTS; ++i) sim->q_hold_rad[i] = cfg->theta_start_rad[i];
}

void sim_advance(sim_t *sim, const uvms_real_t force_I_N[3], uvms_real_t dt_s) {
  const uvms_real_t disturbance_N[3] = {SIM_DISTURBANCE_X_N, UVMS_R(0.0), UVMS_R(0.0)};
  for (int i = 0; i < 3; ++i) { /* semi-implicit Euler */
    sim->v_I_m_s[i] += (force_I_N[i] + disturbance_N[i]) / SIM_MASS_KG * dt_s;
    sim->p_I_m[i] += sim->v_I_m_s[i] * dt_s;
  }
}

void sim_set_motors(sim_t *sim, const uvms_real_t omega_rad_s[UVMS_MAX_THRUSTERS],
                    const uvms_real_t current_A[UVMS_MAX_THRUSTERS]) {
  for (int j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    sim->motor_speed_rad_s[j] = omega_rad_s[j];
    sim->motor_current_A[j] = current_A[j];
  }
}

/** x_B = Rᵀ·x_I (R row-major, body → inertial). */
static void to_body(const uvms_real_t R[9], const uvms_real_t x_I[3], uvms_real_t x_B[3]) {
  for (int i = 0; i < 3; ++i) x_B[i] = R[i] * x_I[0] + R[3 + i] * x_I[1] + R[6 + i] * x_I[2];
}

void sim_estimate(const sim_t *sim, int64_t tick, uvms_real_t tick_s, flight_estimate_t *est) {
  memset(est, 0, sizeof *est);
  const uvms_real_t t = (uvms_real_t)tick * tick_s;
  est->tick = tick;
  est->time_s = t;
  /* q = q_z(ψ) ⊗ q_y(θ): yaw about inertial z, then pitch about the yawed y axis. */
  const uvms_real_t yaw = SIM_YAW_AMPL_RAD * uvms_sin(SIM_YAW_FREQ_RAD_S * t);
  const uvms_real_t yaw_rate =
      SIM_YAW_AMPL_RAD * SIM_YAW_FREQ_RAD_S * uvms_cos(SIM_YAW_FREQ_RAD_S * t);
  const uvms_real_t pitch = SIM_PITCH_AMPL_RAD * uvms_sin(SIM_PITCH_FREQ_RAD_S * t);
  const uvms_real_t pitch_rate =
      SIM_PITCH_AMPL_RAD * SIM_PITCH_FREQ_RAD_S * uvms_cos(SIM_PITCH_FREQ_RAD_S * t);
  const uvms_real_t cy = uvms_cos(yaw / 2), sy = uvms_sin(yaw / 2);
  const uvms_real_t cp = uvms_cos(pitch / 2), sp = uvms_sin(pitch / 2);
  est->q_IB_wxyz[0] = cy * cp;
  est->q_IB_wxyz[1] = -sy * sp;
  est->q_IB_wxyz[2] = cy * sp;
  est->q_IB_wxyz[3] = sy * cp;
  uvms_real_t R[9];
  (void)uvms_quat_to_rot(est->q_IB_wxyz, R);
  /* ω_I = ψ̇·e_z + θ̇·R_z(ψ)·e_y; the gyro measures ω_B = Rᵀ·ω_I, the DVL v_B = Rᵀ·v_I. */
  const uvms_real_t w_I[3] = {-pitch_rate * uvms_sin(yaw), pitch_rate * uvms_cos(yaw), yaw_rate};
  to_body(R, w_I, est->w_B_rad_s);
  to_body(R, sim->v_I_m_s, est->v_B_m_s);
  for (int i = 0; i < 3; ++i) est->p_I_m[i] = sim->p_I_m[i];
  for (int i = 0; i < UVMS_MAX_JOINTS; ++i) {
    est->q_rad[i] = sim->q_hold_rad[i];
    est->qd_rad_s[i] = UVMS_R(0.0);
  }
  for (int j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    est->motor_speed_rad_s[j] = sim->motor_speed_rad_s[j];
    est->motor_current_A[j] = sim->motor_current_A[j];
  }
  est->thruster_ok_mask = (1u << UVMS_MAX_THRUSTERS) - 1u;
}
