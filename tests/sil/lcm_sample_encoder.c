/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lcm_sample_encoder: encodes one uvms_sensors_t and one uvms_actuators_t with the generated
 * C code and writes them to stdout as [uint32 big-endian length][bytes] records. Every double
 * element k of the f-th array field (declaration order, from 1) holds f*100 + k + 0.25, so the
 * decoder can check each value by the same rule. Used by test_lcmtypes_python.py.
 */
#include <stdint.h>
#include <stdio.h>

#include "uvms_actuators_t.h"
#include "uvms_sensors_t.h"

static double rule(int field, int k) { return field * 100.0 + k + 0.25; }

static int write_record(const void *buf, int len) {
  const unsigned char hdr[4] = {(unsigned char)(len >> 24), (unsigned char)(len >> 16),
                                (unsigned char)(len >> 8), (unsigned char)len};
  return fwrite(hdr, 1, 4, stdout) == 4 && fwrite(buf, 1, (size_t)len, stdout) == (size_t)len;
}

int main(void) {
  uvms_sensors_t s = {0};
  s.utime = 1234567;
  s.tick = 42;
  s.session = (int64_t)0xfedcba9876543210ULL; /* top bit set: the sign must survive */
  for (int k = 0; k < 3; ++k) s.position_m[k] = rule(1, k);
  for (int k = 0; k < 4; ++k) s.quaternion_wxyz[k] = rule(2, k);
  for (int k = 0; k < 3; ++k) s.velocity_m_s[k] = rule(3, k);
  for (int k = 0; k < 3; ++k) s.angular_velocity_rad_s[k] = rule(4, k);
  for (int k = 0; k < 7; ++k) s.joint_position_rad[k] = rule(5, k);
  for (int k = 0; k < 7; ++k) s.joint_velocity_rad_s[k] = rule(6, k);
  for (int k = 0; k < 8; ++k) s.motor_speed_rad_s[k] = rule(7, k);
  for (int k = 0; k < 8; ++k) s.motor_current_A[k] = rule(8, k);

  uvms_actuators_t a = {0};
  a.utime = 1234567;
  a.tick = 42;
  a.session = 0x0123456789abcdefLL;
  for (int k = 0; k < 8; ++k) a.motor_voltage_V[k] = rule(1, k);
  for (int k = 0; k < 7; ++k) a.joint_acceleration_rad_s2[k] = rule(2, k);
  for (int k = 0; k < 8; ++k) a.motor_current_cmd_A[k] = rule(3, k);
  for (int k = 0; k < 8; ++k) a.motor_current_rate_A_s[k] = rule(4, k);
  a.status = -3;

  unsigned char buf[2048];
  int n = uvms_sensors_t_encode(buf, 0, (int)sizeof buf, &s);
  if (n < 0 || !write_record(buf, n)) return 1;
  n = uvms_actuators_t_encode(buf, 0, (int)sizeof buf, &a);
  if (n < 0 || !write_record(buf, n)) return 1;
  return 0;
}
