/* SPDX-License-Identifier: Apache-2.0 */
/*
 * bench_ctrl_host: host benchmark of one controller tick (uvms_ctrl_step).
 *
 *   bench_ctrl_host time CASE REPS   wall-clock per step: every step of REPS runs of the 60 s
 *                                     sensor sequence (2000 ticks each) is timed on its own
 *                                     (CLOCK_MONOTONIC, timer overhead subtracted); prints
 *                                     median, p90, p99, max [ns] and the per-run mean.
 *   bench_ctrl_host count CASE REPS  no timing: for valgrind --tool=callgrind
 *                                     --toggle-collect=uvms_ctrl_step (instructions per call)
 *
 * The sensor records are precomputed, so only uvms_ctrl_step is measured. This is a
 * benchmark, not a test: nothing here asserts a time.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sensor_sequence.h"
#include "uvms/controller.h"

#define TICKS 2000

static uvms_ctrl_t g_ctrl;
static uvms_ctrl_sensors_t g_sensors[TICKS];

static long long now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (long long)ts.tv_sec * 1000000000LL + ts.tv_nsec;
}

static int cmp_ll(const void *a, const void *b) {
  const long long x = *(const long long *)a, y = *(const long long *)b;
  return (x > y) - (x < y);
}

static const char kUsage[] =
    "usage: bench_ctrl_host time|count CASE REPS\n"
    "  time CASE REPS   wall-clock per uvms_ctrl_step over REPS runs of the 60 s sensor\n"
    "                   sequence of paper case CASE (2000 ticks each): median, p90, p99, max\n"
    "  count CASE REPS  the same steps untimed, for valgrind --tool=callgrind\n"
    "                   --toggle-collect=uvms_ctrl_step (instructions per call)\n";

int main(int argc, char **argv) {
  if (argc == 2 && (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0)) {
    fputs(kUsage, stdout);
    return 0;
  }
  if (argc < 4 || (strcmp(argv[1], "time") != 0 && strcmp(argv[1], "count") != 0)) {
    fputs(kUsage, stderr);
    return 2;
  }
  const int timing = strcmp(argv[1], "time") == 0;
  const int case_number = atoi(argv[2]);
  const int reps = atoi(argv[3]);
  uvms_ctrl_config_t cfg;
  if (uvms_ctrl_config_paper(&cfg, case_number) != UVMS_OK || reps < 1) {
    fprintf(stderr, "bench_ctrl_host: bad case %s or reps %s\n", argv[2], argv[3]);
    return 2;
  }
  for (int k = 0; k < TICKS; ++k) uvms_sensor_sequence(&cfg, k, &g_sensors[k]);

  long long *samples = timing ? malloc(sizeof(long long) * (size_t)TICKS * (size_t)reps) : NULL;
  double *run_mean = timing ? malloc(sizeof(double) * (size_t)reps) : NULL;
  if (timing && (samples == NULL || run_mean == NULL)) return 3;

  /* Timer overhead: median of back-to-back reads. */
  long long overhead = 0;
  if (timing) {
    long long o[1001];
    for (int i = 0; i < 1001; ++i) {
      const long long a = now_ns();
      o[i] = now_ns() - a;
    }
    qsort(o, 1001, sizeof o[0], cmp_ll);
    overhead = o[500];
  }

  uvms_ctrl_command_t cmd;
  uvms_ctrl_telemetry_t tlm;
  int errors = 0;
  size_t n = 0;
  for (int r = 0; r < reps; ++r) {
    if (uvms_ctrl_init(&g_ctrl, &cfg) != UVMS_OK) return 4;
    const long long run_start = timing ? now_ns() : 0;
    for (int k = 0; k < TICKS; ++k) {
      if (timing) {
        const long long a = now_ns();
        errors += uvms_ctrl_step(&g_ctrl, &g_sensors[k], &cmd, &tlm) != UVMS_OK;
        samples[n++] = now_ns() - a - overhead;
      } else {
        errors += uvms_ctrl_step(&g_ctrl, &g_sensors[k], &cmd, &tlm) != UVMS_OK;
      }
    }
    if (timing) run_mean[r] = (double)(now_ns() - run_start) / TICKS;
  }
  if (timing) {
    qsort(samples, n, sizeof samples[0], cmp_ll);
    double best_mean = run_mean[0];
    for (int r = 1; r < reps; ++r)
      if (run_mean[r] < best_mean) best_mean = run_mean[r];
    printf("case %d (%s): %zu steps, per-step ns: median %lld, p90 %lld, p99 %lld, max %lld; "
           "best run mean %.0f ns/step (incl. timer reads); timer overhead %lld ns\n",
           case_number, UVMS_REAL_IS_FLOAT ? "float" : "double", n, samples[n / 2],
           samples[n * 9 / 10], samples[n * 99 / 100], samples[n - 1], best_mean, overhead);
  } else {
    printf("case %d: %d steps run\n", case_number, reps * TICKS);
  }
  free(samples);
  free(run_mean);
  if (errors) fprintf(stderr, "bench_ctrl_host: %d steps returned an error status\n", errors);
  return errors ? 1 : 0;
}
