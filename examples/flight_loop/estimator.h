/* SPDX-License-Identifier: Apache-2.0 */
/*
 * estimator.h: what the vehicle's state estimator and the drive electronics hand to the flight
 * loop each tick, in the units and frames such sources naturally give (a DVL and a gyro
 * measure in the body frame). pack_sensors() in app.c converts this into the controller's
 * uvms_ctrl_sensors_t; sim.c is a simulated stand-in that produces it.
 *
 * Frames (docs/MODEL.md §2): inertial frame I right-handed with z UP (not NED: an NED
 * estimator must convert, e.g. (x, y, z)_I = (y, x, −z)_NED for positions and velocities);
 * body frame B = the vehicle frame 0, origin at the vehicle's centre of mass.
 */
#ifndef FLIGHT_LOOP_ESTIMATOR_H
#define FLIGHT_LOOP_ESTIMATOR_H

#include <stdint.h>

#include "uvms/controller.h"

typedef struct {
  int64_t tick;                                 /**< sequence number k of the tick [ticks] */
  uvms_real_t time_s;                           /**< time of the estimate since the run's
                                                     start [s]; k·0.03 s (the controller
                                                     rejects a time that drifts from its
                                                     tick by more than half a tick) */
  uvms_real_t p_I_m[3];                         /**< vehicle CoM position, inertial [m] */
  uvms_real_t q_IB_wxyz[4];                     /**< attitude: Hamilton quaternion, scalar
                                                     first, rotating body vectors into the
                                                     inertial frame (x_I = R(q)·x_B); unit */
  uvms_real_t v_B_m_s[3];                       /**< CoM velocity, body frame [m/s] (DVL) */
  uvms_real_t w_B_rad_s[3];                     /**< angular rate, body frame [rad/s] (gyro) */
  uvms_real_t q_rad[UVMS_MAX_JOINTS];           /**< joint angles θ_i, DH convention of the
                                                     arm model, within its joint limits [rad] */
  uvms_real_t qd_rad_s[UVMS_MAX_JOINTS];        /**< joint rates θ̇_i [rad/s] */
  uvms_real_t motor_speed_rad_s[UVMS_MAX_THRUSTERS]; /**< signed shaft speed ω_j [rad/s]
                                                     (uvms/thruster.h: positive thrust needs
                                                     negative ω with the paper's propeller) */
  uvms_real_t motor_current_A[UVMS_MAX_THRUSTERS];   /**< signed winding current I_j [A] */
  uint32_t thruster_ok_mask;                    /**< bit j: thruster j healthy (drive fault
                                                     monitor) */
} flight_estimate_t;

#endif /* FLIGHT_LOOP_ESTIMATOR_H */
