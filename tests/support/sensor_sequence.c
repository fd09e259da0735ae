/* SPDX-License-Identifier: Apache-2.0 */
/* sensor_sequence.c: see sensor_sequence.h. Computed in double, stored in uvms_real_t. */
#include "sensor_sequence.h"

#include <math.h>
#include <string.h>

static const double kPi = 3.14159265358979323846;

void uvms_sensor_sequence(const uvms_ctrl_config_t *cfg, int tick, uvms_ctrl_sensors_t *s) {
  memset(s, 0, sizeof *s);
  const double t = tick * UVMS_SEQ_TICK_S, tf = UVMS_SEQ_DURATION_S;
  s->tick = tick;
  s->time_s = (uvms_real_t)t;
  s->position_m[0] = (uvms_real_t)(-0.03 * (1 - cos(0.05 * t)));
  s->position_m[1] = (uvms_real_t)(0.004 * sin(0.11 * t));
  s->position_m[2] = (uvms_real_t)(0.002 * sin(0.07 * t));
  s->velocity_m_s[0] = (uvms_real_t)(-0.0015 * sin(0.05 * t));
  s->velocity_m_s[1] = (uvms_real_t)(0.00044 * cos(0.11 * t));
  s->velocity_m_s[2] = (uvms_real_t)(0.00014 * cos(0.07 * t));
  /* Yaw then pitch, small angles: q = q_yaw(z) ⊗ q_pitch(y). */
  const double yaw = 0.01 * sin(0.2 * t), pitch = 0.005 * sin(0.13 * t);
  s->quaternion_wxyz[0] = (uvms_real_t)(cos(yaw / 2) * cos(pitch / 2));
  s->quaternion_wxyz[1] = (uvms_real_t)(-sin(yaw / 2) * sin(pitch / 2));
  s->quaternion_wxyz[2] = (uvms_real_t)(cos(yaw / 2) * sin(pitch / 2));
  s->quaternion_wxyz[3] = (uvms_real_t)(sin(yaw / 2) * cos(pitch / 2));
  s->angular_velocity_rad_s[1] = (uvms_real_t)(0.00065 * cos(0.13 * t));
  s->angular_velocity_rad_s[2] = (uvms_real_t)(0.002 * cos(0.2 * t));
  const double tau = t / tf < 1 ? t / tf : 1;
  for (int j = 0; j < 7; ++j) {
    const double d = (double)cfg->theta_final_rad[j] - (double)cfg->theta_start_rad[j];
    const double lag = 0.001 * sin(0.3 * t + j);
    s->joint_position_rad[j] = (uvms_real_t)((double)cfg->theta_start_rad[j] +
                                d * (tau - sin(2 * kPi * tau) / (2 * kPi)) + lag);
    s->joint_velocity_rad_s[j] = (uvms_real_t)(d / tf * (1 - cos(2 * kPi * tau)));
  }
  for (int m = 0; m < 8; ++m) {
    s->motor_speed_rad_s[m] = (uvms_real_t)(40.0 * sin(0.05 * t + m));
    s->motor_current_A[m] = (uvms_real_t)(0.5 * cos(0.05 * t + m));
  }
  s->thruster_usable_mask = 0xFFu;
}
