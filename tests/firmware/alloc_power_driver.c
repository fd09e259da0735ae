/* SPDX-License-Identifier: Apache-2.0 */
/*
 * alloc_power_driver.c: the firmware's allocation on the paper's thruster layout, one case per
 * stdin line, for test_alloc_power_scipy.py (an independent check with scipy.optimize).
 *
 * Usage: alloc_power_driver [warm] [vectored] [weighted]
 *   without "warm" every case starts cold (z = 0); with it each case is warm started from the
 *   previous case's solution (as the controller does from tick to tick).
 *   "vectored": a second layout instead of the paper's: four horizontal thrusters at 45° in
 *   the corners (surge, sway and yaw from all four) and four vertical ones (heave, roll and
 *   pitch), so each of the two null directions couples four thrusters (the paper's layout
 *   couples the surge quad and the heave and sway pairs). Positions [m] and directions in
 *   vectored_layout() below; test_alloc_power_scipy.py types the same numbers in.
 *   "weighted": the cost Σ w_j·|T_j|^1.5 with the weights of kWeight below (thrusters of
 *   different propellers, alloc_power.h), through uvms_alloc_min_power_each with every limit
 *   equal to limit_N; test_alloc_power_scipy.py types the same weights in.
 * Input line:  mask limit_N fx_N fy_N fz_N mx_Nm my_Nm mz_Nm
 *   mask     usable thrusters (bit j = thruster j, 0..255)
 *   limit_N  thrust limit T_max [N]; ≤ 0: none
 *   f, m     the wrench, vehicle frame (R0 = identity) [N], [N·m]
 * Output line: status iterations converged null_dim P_0..P_7 T_0..T_7
 *   status      uvms_alloc_min_power's (0 = UVMS_OK)
 *   iterations  its iterations; converged 1/0; null_dim d
 *   P           pseudoinverse thrusts after the thrust limit [N] (uvms_alloc_step, _saturate)
 *   T           least-Σ|T|^1.5 thrusts with P's wrench [N]
 * Reals are printed with 17 significant digits (exact for float and double). Exits 0 at the
 * end of input, 2 on a malformed line or a failed pseudoinverse step.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "uvms/alloc_power.h"

/* The "weighted" cost's weights: they differ inside each null direction of both layouts. */
static const double kWeight[8] = {1.0, 1.4, 1.0, 0.7, 0.6578947368421053, 0.6578947368421053,
                                  1.2, 1.2};

/* One case; returns 0, or 2 if the pseudoinverse path itself failed. */
static int run_case(uvms_alloc_t *al, uvms_power_warm_t *warm, int weighted, unsigned mask,
                    double limit_N, const double w[6]) {
  const uvms_real_t R0[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  uvms_real_t F[3], N[3], P[8], Ppos[8], Patt[8], T[8];
  for (int i = 0; i < 3; ++i) {
    F[i] = (uvms_real_t)w[i];
    N[i] = (uvms_real_t)w[i + 3];
  }
  if (uvms_alloc_set_usable(al, (uint32_t)mask) != UVMS_OK) return 2;
  if (uvms_alloc_step(al, R0, F, N, P, Ppos, Patt) != UVMS_OK) return 2;
  uvms_real_t limit = (uvms_real_t)INFINITY;
  if (limit_N > 0) {
    limit = (uvms_real_t)limit_N;
    uvms_real_t sp = 0, sa = 0;
    if (uvms_alloc_saturate(al, limit, Ppos, Patt, P, &sp, &sa) != UVMS_OK) return 2;
  }
  uvms_power_info_t info;
  uvms_real_t limits[8], weight[8];
  for (int j = 0; j < 8; ++j) {
    limits[j] = limit;
    weight[j] = (uvms_real_t)kWeight[j];
  }
  const uvms_status_t st =
      weighted ? uvms_alloc_min_power_each(al, limits, weight, P, warm, T, &info)
               : uvms_alloc_min_power(al, limit, P, warm, T, &info);
  printf("%d %u %d %u", (int)st, (unsigned)info.iterations, info.converged,
         (unsigned)info.null_dim);
  for (int j = 0; j < 8; ++j) printf(" %.17g", (double)P[j]);
  for (int j = 0; j < 8; ++j) printf(" %.17g", (double)T[j]);
  printf("\n");
  return 0;
}

/* The "vectored" layout (see the usage above). */
static void vectored_layout(uvms_thruster_geometry_t *g) {
  static const double kPos_m[8][3] = {{0.16, 0.11, 0.0},   {0.16, -0.11, 0.0},
                                      {-0.16, 0.11, 0.0},  {-0.16, -0.11, 0.0},
                                      {0.12, 0.22, 0.05},  {0.12, -0.22, 0.05},
                                      {-0.12, 0.22, 0.05}, {-0.12, -0.22, 0.05}};
  static const double kDir[8][3] = {{1, -1, 0}, {1, 1, 0}, {1, 1, 0}, {1, -1, 0},
                                    {0, 0, 1},  {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  memset(g, 0, sizeof *g);
  g->num_thrusters = 8;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 3; ++i) {
      g->position_m[j][i] = (uvms_real_t)kPos_m[j][i];
      g->direction[j][i] = (uvms_real_t)kDir[j][i]; /* normalised by uvms_alloc_init */
    }
}

int main(int argc, char **argv) {
  int warm_start = 0, vectored = 0, weighted = 0;
  for (int a = 1; a < argc; ++a) {
    if (strcmp(argv[a], "--help") == 0 || strcmp(argv[a], "-h") == 0) {
      puts("usage: alloc_power_driver [warm] [vectored] [weighted]   (cases on stdin; see the "
           "source)");
      return 0;
    }
    if (strcmp(argv[a], "warm") == 0) warm_start = 1;
    else if (strcmp(argv[a], "vectored") == 0) vectored = 1;
    else if (strcmp(argv[a], "weighted") == 0) weighted = 1;
    else return 2;
  }
  uvms_thruster_geometry_t g;
  if (vectored) vectored_layout(&g);
  else uvms_thruster_geometry_paper(&g);
  static uvms_alloc_t al;
  if (uvms_alloc_init(&al, &g) != UVMS_OK) return 2;
  uvms_power_warm_t warm;
  memset(&warm, 0, sizeof warm);
  unsigned mask = 0;
  double limit_N = 0, w[6];
  for (;;) {
    const int got = scanf("%u %lf %lf %lf %lf %lf %lf %lf", &mask, &limit_N, &w[0], &w[1], &w[2],
                          &w[3], &w[4], &w[5]);
    if (got == EOF) return 0;
    if (got != 8 || mask > 255u) return 2;
    if (run_case(&al, warm_start ? &warm : NULL, weighted, mask, limit_N, w) != 0) return 2;
  }
}
