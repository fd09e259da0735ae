/* SPDX-License-Identifier: Apache-2.0 */
/*
 * ctrl_sequence: runs the controller over the deterministic sensor sequence of
 * tests/support/sensor_sequence.h and prints its outputs, one line per tick. Built twice
 * (double and float firmware) so that compare_float_double.py can check the float build
 * against the double build. Usage: ctrl_sequence CASE TICKS
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sensor_sequence.h"
#include "uvms/controller.h"

static uvms_ctrl_t g_ctrl; /* static storage, as on the target */

int main(int argc, char **argv) {
  const int case_number = argc > 1 ? atoi(argv[1]) : 7;
  const int ticks = argc > 2 ? atoi(argv[2]) : 2000;
  uvms_ctrl_config_t cfg;
  if (uvms_ctrl_config_paper(&cfg, case_number) != UVMS_OK) return 2;
  if (uvms_ctrl_init(&g_ctrl, &cfg) != UVMS_OK) return 3;
  for (int k = 0; k < ticks; ++k) {
    uvms_ctrl_sensors_t s;
    uvms_sensor_sequence(&cfg, k, &s);
    uvms_ctrl_command_t cmd;
    uvms_ctrl_telemetry_t tlm;
    const uvms_status_t st = uvms_ctrl_step(&g_ctrl, &s, &cmd, &tlm);
    printf("%d %d", k, (int)st);
    for (int m = 0; m < 8; ++m) printf(" %.9e", (double)cmd.motor_voltage_V[m]);
    for (int j = 0; j < 7; ++j) printf(" %.9e", (double)cmd.joint_acceleration_rad_s2[j]);
    for (int i = 0; i < 3; ++i) printf(" %.9e", (double)tlm.force_des_N[i]);
    for (int i = 0; i < 3; ++i) printf(" %.9e", (double)tlm.moment_des_Nm[i]);
    for (int i = 0; i < 3; ++i) printf(" %.9e", (double)tlm.ee_estimate_m[i]);
    for (int m = 0; m < 8; ++m) printf(" %.9e", (double)tlm.thrust_des_N[m]);
    for (int m = 0; m < 8; ++m) printf(" %.9e", (double)cmd.motor_current_cmd_A[m]);
    for (int m = 0; m < 8; ++m) printf(" %.9e", (double)cmd.motor_current_rate_A_s[m]);
    printf("\n");
  }
  return 0;
}
