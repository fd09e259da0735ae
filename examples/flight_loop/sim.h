/* SPDX-License-Identifier: Apache-2.0 */
/*
 * sim.h: a small simulated stand-in for the estimator (not a truth model: the project's plant
 * in plant/ is that). The vehicle is a point mass that feels the force the controller's
 * command delivers (telemetry force_deliverable_N) plus a steady current's drag; its attitude
 * follows a closed-form small yaw/pitch oscillation; the arm holds its start pose; the motors
 * track the controller's desired speeds and currents within a tick.
 */
#ifndef FLIGHT_LOOP_SIM_H
#define FLIGHT_LOOP_SIM_H

#include "estimator.h"

/** Effective mass of vehicle, arm, payload and added mass along each axis [kg] (a round
 *  stand-in value: 120 kg vehicle, ≈ 27 kg arm, 10 kg payload, added mass). */
#define SIM_MASS_KG UVMS_R(200.0)
/** Steady current's drag on the vehicle, inertial +x [N]. */
#define SIM_DISTURBANCE_X_N UVMS_R(1.0)

typedef struct {
  uvms_real_t p_I_m[3];      /**< CoM position, inertial [m] */
  uvms_real_t v_I_m_s[3];    /**< CoM velocity, inertial [m/s] */
  uvms_real_t q_hold_rad[UVMS_MAX_JOINTS];               /**< the arm's pose [rad] */
  uvms_real_t motor_speed_rad_s[UVMS_MAX_THRUSTERS];     /**< what the ESCs report [rad/s] */
  uvms_real_t motor_current_A[UVMS_MAX_THRUSTERS];       /**< [A] */
} sim_t;

/** At rest at the origin, the arm at cfg's start pose θI, motors stopped. */
void sim_init(sim_t *sim, const uvms_ctrl_config_t *cfg);

/** Integrate dt_s [s] with force_I_N [N] (inertial) held, plus the disturbance. */
void sim_advance(sim_t *sim, const uvms_real_t force_I_N[3], uvms_real_t dt_s);

/** The motors reach the controller's desired speeds ω̂ and currents Î within a tick. */
void sim_set_motors(sim_t *sim, const uvms_real_t omega_rad_s[UVMS_MAX_THRUSTERS],
                    const uvms_real_t current_A[UVMS_MAX_THRUSTERS]);

/** The estimate of tick k at time k·tick_s, as an estimator would hand it over. */
void sim_estimate(const sim_t *sim, int64_t tick, uvms_real_t tick_s, flight_estimate_t *est);

#endif /* FLIGHT_LOOP_SIM_H */
