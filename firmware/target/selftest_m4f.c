/* SPDX-License-Identifier: Apache-2.0 */
/*
 * selftest_m4f.c: a minimal Cortex-M4F image linking the firmware library (float build).
 * Runs algebraic identities of the firmware's math on the target's FPU and libm and returns
 * the number of failed checks as the exit code (0 = pass), so ctest can run it in QEMU.
 * Each check compares two independent computations, not a number copied from a run.
 */
#include <stdio.h>

#include "uvms/linalg.h"

static int g_checks = 0;
static int g_failed = 0;

static void check(int ok, const char *what) {
  ++g_checks;
  if (!ok) {
    ++g_failed;
    printf("FAIL: %s\n", what);
  }
}

static float absf(float x) { return x < 0.0f ? -x : x; }

int main(void) {
  /* 1. A quaternion's rotation matrix is orthonormal and converts back to the quaternion. */
  const uvms_real_t q[4] = {0.5f, 0.5f, -0.5f, 0.5f}; /* 120 deg about (1,-1,1)/sqrt(3) */
  uvms_real_t R[9], RRt[9], q2[4];
  check(uvms_quat_to_rot(q, R) == UVMS_OK, "quat_to_rot status");
  uvms_m3_mul_t(R, R, RRt);
  float err = 0.0f;
  for (int i = 0; i < 9; ++i) err += absf(RRt[i] - ((i % 4 == 0) ? 1.0f : 0.0f));
  check(err < 1e-5f, "R*R^T == I");
  uvms_rot_to_quat(R, q2);
  err = 0.0f;
  for (int i = 0; i < 4; ++i) err += absf(q2[i] - q[i]);
  check(err < 1e-5f, "rot_to_quat(quat_to_rot(q)) == q");

  /* 2. Rotation vector of Rz(phi) is (0, 0, phi) for phi = 2.0 rad (uses atan2f, sqrtf). */
  uvms_real_t Rz[9], rv[3];
  uvms_rot_z(2.0f, Rz);
  uvms_rot_to_rotvec(Rz, rv);
  check(absf(rv[0]) + absf(rv[1]) + absf(rv[2] - 2.0f) < 1e-5f, "rotvec(Rz(2)) == (0,0,2)");

  /* 3. SPD solve: A·x == b residual for a diagonally dominant 6x6. */
  uvms_real_t A[36], b[6], x[6];
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) A[6 * i + j] = (i == j) ? 10.0f : 1.0f / (float)(1 + i + j);
    b[i] = (float)(i + 1);
  }
  check(uvms_spd_solve(6, A, 1, b, x, 1e-6f) == UVMS_OK, "spd_solve status");
  err = 0.0f;
  for (int i = 0; i < 6; ++i) {
    float r = -b[i];
    for (int j = 0; j < 6; ++j) r += A[6 * i + j] * x[j];
    err += absf(r);
  }
  check(err < 1e-4f, "A*x == b");

  printf("uvms cortex-m4f selftest: %d checks, %d failed\n", g_checks, g_failed);
  return g_failed;
}
