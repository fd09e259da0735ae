/* SPDX-License-Identifier: Apache-2.0 */
/*
 * paper_step.c: one controller tick of the paper's case IV through the installed library
 * (tests/consumer/CMakeLists.txt). Prints the version, the precision and the step's status;
 * exit 0 only if init and step return UVMS_OK and the library's version is its headers'.
 */
#include <stdio.h>
#include <string.h>

#include "uvms/controller.h"
#include "uvms/version.h"

#ifdef UVMS_CONSUMER_EXPECT_FLOAT
_Static_assert(UVMS_REAL_IS_FLOAT == UVMS_CONSUMER_EXPECT_FLOAT,
               "the installed headers give the precision the library was built with");
#endif

static uvms_ctrl_t g_ctrl; /* one instance, static storage as on the flight computer */

/* The first sensor record: at rest at the origin, joints at the start pose, all thrusters. */
static void start_sensors(const uvms_ctrl_config_t *cfg, uvms_ctrl_sensors_t *s) {
  memset(s, 0, sizeof *s);
  s->quaternion_wxyz[0] = UVMS_R(1.0);
  for (int j = 0; j < UVMS_MAX_JOINTS; ++j) s->joint_position_rad[j] = cfg->theta_start_rad[j];
  s->thruster_usable_mask = 0xFFu;
}

int main(void) {
  static uvms_ctrl_config_t cfg;
  static uvms_ctrl_sensors_t sensors;
  static uvms_ctrl_command_t cmd;
  static uvms_ctrl_telemetry_t tlm;
  uvms_status_t status = uvms_ctrl_config_paper(&cfg, 4);
  if (status == UVMS_OK) status = uvms_ctrl_init(&g_ctrl, &cfg);
  if (status == UVMS_OK) {
    start_sensors(&cfg, &sensors);
    status = uvms_ctrl_step(&g_ctrl, &sensors, &cmd, &tlm);
  }
  const int version_ok = strcmp(uvms_version(), UVMS_VERSION_STRING) == 0;
  printf("uvms consumer: library %s (headers %s), precision %s, step status %s\n", uvms_version(),
         UVMS_VERSION_STRING, UVMS_REAL_IS_FLOAT ? "float" : "double", uvms_status_str(status));
  return (status == UVMS_OK && version_ok) ? 0 : 1;
}
