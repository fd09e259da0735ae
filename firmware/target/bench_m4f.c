/* SPDX-License-Identifier: Apache-2.0 */
/*
 * bench_m4f.c: Cortex-M4F benchmark image (QEMU mps2-an386, float firmware). Runs the
 * controller of one paper case over the 60 s deterministic sensor sequence (2000 ticks of
 * 0.03 s) with one controller instance in static storage, and brackets every uvms_ctrl_step
 * call between two marker functions. bench/qemu_icount_plugin.c counts the guest
 * instructions between the markers; bench/m4f_bench.sh drives both.
 *
 * The sensor sequence is tests/firmware/ctrl_sequence.c's (same formulas, same order),
 * evaluated in float with sinf/cosf: no soft-float double in the loop. Its values differ from
 * the double-computed sequence by float rounding only; the controller takes the same branches.
 * Sensor generation happens outside the markers and is not measured.
 *
 * Parameters: compile-time UVMS_BENCH_CASE (0 = cases IV then VII; default 0) and
 * UVMS_BENCH_TICKS (default 2000), overridable at run time through the semihosting command
 * line (qemu ... -append "case=7 ticks=2000 measure=1"):
 *   case=N     paper case 1..8, or 0 for IV then VII
 *   ticks=N    ticks per case, 0..UVMS_BENCH_MAX_TICKS
 *   measure=0  generate the sensors of every tick but call neither the markers nor the
 *              controller (the baseline of the cross-check: the plugin's instruction count
 *              over the tick loop, between the two uvms_bench_mark_span calls, with and
 *              without the controller)
 * Prints one summary line per case (semihosting) and exits 0 if every step returned UVMS_OK,
 * 1 if one did not, 2 on a bad parameter or a failed init. This is a benchmark, not a test.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "uvms/controller.h"
#include "uvms_m4f/marker.h"

_Static_assert(UVMS_REAL_IS_FLOAT, "the Cortex-M4F benchmark measures the float firmware");

#ifndef UVMS_BENCH_CASE
#define UVMS_BENCH_CASE 0
#endif
#ifndef UVMS_BENCH_TICKS
#define UVMS_BENCH_TICKS 2000
#endif
#define UVMS_BENCH_MAX_TICKS 1000000

/* Stack high-water measurement: this many bytes below main's frame are painted before the
   tick loop and scanned after it. The linker script keeps >= 16 KiB for heap + stack. */
#define STACK_PAINT_BYTES (12u * 1024u)
#define STACK_PAINT_WORD 0xC5AC5AC5u

/* The markers (uvms_m4f/marker.h): begin/end bracket each step, span runs right before and
   right after the tick loop. */
UVMS_M4F_MARKER(uvms_bench_mark_begin, "uvms bench: begin")
UVMS_M4F_MARKER(uvms_bench_mark_end, "uvms bench: end")
UVMS_M4F_MARKER(uvms_bench_mark_span, "uvms bench: tick loop")

/* One controller instance, and the step's I/O, in static storage as on a real target. The
   markers are opaque calls, so every store to these objects is complete before the begin
   marker runs and no load of them moves before the end marker. */
static uvms_ctrl_t uvms_bench_ctrl;
static uvms_ctrl_sensors_t g_sensors;
static uvms_ctrl_command_t g_cmd;
static uvms_ctrl_telemetry_t g_tlm;

/** ctrl_sequence.c's sensor record of tick k, in float. */
static void sensor_sequence_f32(const uvms_ctrl_config_t *cfg, int k, uvms_ctrl_sensors_t *s) {
  const float dt = 0.03f, tf = 60.0f, two_pi = 6.283185307f;
  const float t = (float)k * dt;
  memset(s, 0, sizeof *s);
  s->tick = k;
  s->time_s = t;
  s->position_m[0] = -0.03f * (1.0f - cosf(0.05f * t));
  s->position_m[1] = 0.004f * sinf(0.11f * t);
  s->position_m[2] = 0.002f * sinf(0.07f * t);
  s->velocity_m_s[0] = -0.0015f * sinf(0.05f * t);
  s->velocity_m_s[1] = 0.00044f * cosf(0.11f * t);
  s->velocity_m_s[2] = 0.00014f * cosf(0.07f * t);
  const float yaw = 0.01f * sinf(0.2f * t), pitch = 0.005f * sinf(0.13f * t);
  s->quaternion_wxyz[0] = cosf(yaw / 2.0f) * cosf(pitch / 2.0f);
  s->quaternion_wxyz[2] = cosf(yaw / 2.0f) * sinf(pitch / 2.0f);
  s->quaternion_wxyz[3] = sinf(yaw / 2.0f) * cosf(pitch / 2.0f);
  s->quaternion_wxyz[1] = -sinf(yaw / 2.0f) * sinf(pitch / 2.0f);
  s->angular_velocity_rad_s[2] = 0.002f * cosf(0.2f * t);
  s->angular_velocity_rad_s[1] = 0.00065f * cosf(0.13f * t);
  const float tau = t / tf < 1.0f ? t / tf : 1.0f;
  for (int j = 0; j < 7; ++j) {
    const float d = cfg->theta_final_rad[j] - cfg->theta_start_rad[j];
    const float lag = 0.001f * sinf(0.3f * t + (float)j);
    s->joint_position_rad[j] = cfg->theta_start_rad[j] + d * (tau - sinf(two_pi * tau) / two_pi) + lag;
    s->joint_velocity_rad_s[j] = d / tf * (1.0f - cosf(two_pi * tau));
  }
  for (int m = 0; m < 8; ++m) {
    s->motor_speed_rad_s[m] = 40.0f * sinf(0.05f * t + (float)m);
    s->motor_current_A[m] = 0.5f * cosf(0.05f * t + (float)m);
  }
  s->thruster_usable_mask = 0xFFu;
}

/** Semihosting SYS_GET_CMDLINE (0x15): the command line QEMU builds from -kernel/-append. */
static int semihost_cmdline(char *buf, int len) {
  struct {
    char *buf;
    int len;
  } block = {buf, len};
  register int r0 __asm("r0") = 0x15;
  register void *r1 __asm("r1") = &block;
  __asm volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0 == 0 ? block.len : -1;
}

/** Value of "key=N" among the space-separated tokens of cmd, or fallback if absent. */
static long cmdline_value(const char *cmd, const char *key, long fallback) {
  const size_t key_len = strlen(key);
  for (const char *p = cmd; *p != '\0';) {
    while (*p == ' ') ++p;
    if (strncmp(p, key, key_len) == 0 && p[key_len] == '=') {
      long v = 0;
      int digits = 0;
      for (const char *q = p + key_len + 1; *q >= '0' && *q <= '9' && digits < 9; ++q, ++digits)
        v = 10 * v + (*q - '0');
      return digits > 0 ? v : -1;
    }
    while (*p != '\0' && *p != ' ') ++p;
  }
  return fallback;
}

static uint32_t read_sp(void) {
  uint32_t sp;
  __asm volatile("mov %0, sp" : "=r"(sp));
  return sp;
}

/** Runs one case; returns 0 (all steps OK), 1 (a step failed) or 2 (config/init failed). */
static int run_case(int case_number, long ticks, int measure) {
  /* The configuration the instance points to (uvms_ctrl_init): static storage, so that it is
     counted in the image's RAM, as the instance is. */
  static uvms_ctrl_config_t cfg;
  if (uvms_ctrl_config_paper(&cfg, case_number) != UVMS_OK) return 2;
  if (uvms_ctrl_init(&uvms_bench_ctrl, &cfg) != UVMS_OK) {
    printf("bench_m4f: case %d: init failed (%s)\n", case_number,
           uvms_cfg_field_str(uvms_bench_ctrl.config_error));
    return 2;
  }

  /* Paint the stack below this frame (no interrupts run in this image). */
  const uint32_t sp0 = read_sp() & ~3u;
  volatile uint32_t *const paint_lo = (volatile uint32_t *)(sp0 - 64u - STACK_PAINT_BYTES);
  volatile uint32_t *const paint_hi = (volatile uint32_t *)(sp0 - 64u);
  for (volatile uint32_t *w = paint_lo; w < paint_hi; ++w) *w = STACK_PAINT_WORD;

  long not_ok = 0, measured = 0;
  uint32_t flags_or = 0u, saturated_ticks = 0u;
  uvms_bench_mark_span();
  for (long k = 0; k < ticks; ++k) {
    sensor_sequence_f32(&cfg, (int)k, &g_sensors);
    if (measure) {
      uvms_bench_mark_begin();
      const uvms_status_t st = uvms_ctrl_step(&uvms_bench_ctrl, &g_sensors, &g_cmd, &g_tlm);
      uvms_bench_mark_end();
      ++measured;
      if (st != UVMS_OK) ++not_ok;
      flags_or |= g_tlm.flags;
      if (g_tlm.flags & UVMS_FLAG_VOLTAGE_SATURATED) ++saturated_ticks;
    }
  }
  uvms_bench_mark_span();

  const volatile uint32_t *w = paint_lo;
  while (w < paint_hi && *w == STACK_PAINT_WORD) ++w;
  const unsigned long stack_peak = (unsigned long)(sp0 - (uint32_t)(uintptr_t)w);

  printf("bench_m4f: case %d: ticks=%ld measured_steps=%ld not_ok=%ld flags_or=0x%03lx "
         "saturated_ticks=%lu stack_peak_below_caller=%lu%s sizeof_ctrl=%lu\n",
         case_number, ticks, measured, not_ok, (unsigned long)flags_or,
         (unsigned long)saturated_ticks, stack_peak,
         w == paint_lo ? "(paint_exhausted)" : "", (unsigned long)sizeof uvms_bench_ctrl);
  return not_ok ? 1 : 0;
}

int main(void) {
  char cmd[256] = "";
  if (semihost_cmdline(cmd, (int)sizeof cmd) < 0) cmd[0] = '\0';
  const long case_arg = cmdline_value(cmd, "case", UVMS_BENCH_CASE);
  const long ticks = cmdline_value(cmd, "ticks", UVMS_BENCH_TICKS);
  const long measure = cmdline_value(cmd, "measure", 1);
  if (case_arg < 0 || case_arg > 8 || ticks < 0 || ticks > UVMS_BENCH_MAX_TICKS ||
      (measure != 0 && measure != 1)) {
    printf("bench_m4f: bad parameters '%s' (case=0..8 ticks=0..%d measure=0|1)\n", cmd,
           UVMS_BENCH_MAX_TICKS);
    return 2;
  }
  printf("bench_m4f: %s, %ld ticks of 0.03 s per case, %s\n",
         case_arg == 0 ? "cases 4 and 7 in sequence" : "one case",
         ticks, measure ? "uvms_ctrl_step bracketed by markers" : "sensors only (measure=0)");
  int rc = 0;
  if (case_arg == 0) {
    const int r4 = run_case(4, ticks, (int)measure);
    const int r7 = run_case(7, ticks, (int)measure);
    rc = r4 > r7 ? r4 : r7;
  } else {
    rc = run_case((int)case_arg, ticks, (int)measure);
  }
  return rc;
}
