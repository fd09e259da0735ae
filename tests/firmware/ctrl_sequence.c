/*
 * ctrl_sequence: runs the controller over a fixed, recorded-style sensor sequence and prints
 * its outputs, one line per tick. Built twice (double and float firmware) so that
 * compare_float_double.py can check the float build against the double build.
 *
 * The sensor sequence is a deterministic function of the tick (no randomness): the vehicle
 * drifts and turns slowly, the joints follow the case's cycloid with a small lag, the motors
 * spin and draw current. It exercises every branch of a normal tick.
 * Usage: ctrl_sequence CASE TICKS
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "uvms/controller.h"

static const double kPi = 3.14159265358979323846;

static uvms_ctrl_t g_ctrl; /* static storage, as on the target */

int main(int argc, char **argv) {
  const int case_number = argc > 1 ? atoi(argv[1]) : 7;
  const int ticks = argc > 2 ? atoi(argv[2]) : 2000;
  uvms_ctrl_config_t cfg;
  if (uvms_ctrl_config_paper(&cfg, case_number) != UVMS_OK) return 2;
  if (uvms_ctrl_init(&g_ctrl, &cfg) != UVMS_OK) return 3;
  const double dt = 0.03, tf = 60.0;
  for (int k = 0; k < ticks; ++k) {
    const double t = k * dt;
    uvms_ctrl_sensors_t s;
    memset(&s, 0, sizeof s);
    s.tick = k;
    s.time_s = (uvms_real_t)t;
    s.position_m[0] = (uvms_real_t)(-0.03 * (1 - cos(0.05 * t)));
    s.position_m[1] = (uvms_real_t)(0.004 * sin(0.11 * t));
    s.position_m[2] = (uvms_real_t)(0.002 * sin(0.07 * t));
    s.velocity_m_s[0] = (uvms_real_t)(-0.0015 * sin(0.05 * t));
    s.velocity_m_s[1] = (uvms_real_t)(0.00044 * cos(0.11 * t));
    s.velocity_m_s[2] = (uvms_real_t)(0.00014 * cos(0.07 * t));
    const double yaw = 0.01 * sin(0.2 * t), pitch = 0.005 * sin(0.13 * t);
    s.quaternion_wxyz[0] = (uvms_real_t)(cos(yaw / 2) * cos(pitch / 2));
    s.quaternion_wxyz[2] = (uvms_real_t)(cos(yaw / 2) * sin(pitch / 2));
    s.quaternion_wxyz[3] = (uvms_real_t)(sin(yaw / 2) * cos(pitch / 2));
    s.quaternion_wxyz[1] = (uvms_real_t)(-sin(yaw / 2) * sin(pitch / 2));
    s.omega_rad_s[2] = (uvms_real_t)(0.002 * cos(0.2 * t));
    s.omega_rad_s[1] = (uvms_real_t)(0.00065 * cos(0.13 * t));
    const double tau = t / tf < 1 ? t / tf : 1;
    for (int j = 0; j < 7; ++j) {
      const double d = (double)cfg.theta_final_rad[j] - (double)cfg.theta_start_rad[j];
      const double lag = 0.001 * sin(0.3 * t + j);
      s.q_rad[j] = (uvms_real_t)((double)cfg.theta_start_rad[j] +
                                 d * (tau - sin(2 * kPi * tau) / (2 * kPi)) + lag);
      s.qd_rad_s[j] = (uvms_real_t)(d / tf * (1 - cos(2 * kPi * tau)));
    }
    for (int m = 0; m < 8; ++m) {
      s.motor_speed_rad_s[m] = (uvms_real_t)(40.0 * sin(0.05 * t + m));
      s.motor_current_A[m] = (uvms_real_t)(0.5 * cos(0.05 * t + m));
    }
    s.thruster_usable_mask = 0xFF;
    uvms_ctrl_command_t cmd;
    uvms_ctrl_telemetry_t tlm;
    const uvms_status_t st = uvms_ctrl_step(&g_ctrl, &s, &cmd, &tlm);
    printf("%d %d", k, (int)st);
    for (int m = 0; m < 8; ++m) printf(" %.9e", (double)cmd.motor_voltage_V[m]);
    for (int j = 0; j < 7; ++j) printf(" %.9e", (double)cmd.joint_accel_cmd_rad_s2[j]);
    for (int i = 0; i < 3; ++i) printf(" %.9e", (double)tlm.force_des_N[i]);
    for (int i = 0; i < 3; ++i) printf(" %.9e", (double)tlm.moment_des_Nm[i]);
    for (int i = 0; i < 3; ++i) printf(" %.9e", (double)tlm.ee_estimate_m[i]);
    for (int m = 0; m < 8; ++m) printf(" %.9e", (double)tlm.thrust_des_N[m]);
    printf("\n");
  }
  return 0;
}
