/* SPDX-License-Identifier: Apache-2.0 */
/*
 * app.c: the flight loop, shared by every board (board.h). What a flight computer around the
 * uvms_firmware library does each tick:
 *
 *   timer interrupt (33.3 Hz) ─► wake from WFI ─► estimate ─► pack_sensors() ─► uvms_ctrl_step()
 *     ─► handle the status and flags (apply the command, or the safe output it wrote)
 *     ─► actuators ─► telemetry record over the UART ─► sleep
 *
 * The run: APP_TICKS ticks of the paper's case IV (vehicle reference, attitude control, position
 * feedforward and feedback; the arm holding its start pose) against the simulated estimator of
 * sim.c, with estimator faults injected at known ticks (APP_FAULT_*), and optionally a stall
 * that overruns the tick (option "stall_at=K") or a configuration upset (option
 * "config_upset_at=K"). At the end a summary, then the run's checks:
 * the exit code is the number of failed checks (0: the result documented in examples/README.md).
 *
 * Everything lives in static storage; nothing allocates.
 */
#include <math.h>
#include <string.h>

#include "board.h"
#include "estimator.h"
#include "sim.h"
#include "uvms/controller.h"
#include "uvms/linalg.h"
#include "uvms/version.h"

/* ---- the run ------------------------------------------------------------------------------ */
#define APP_TICK_S UVMS_R(0.03)        /* controller period [s] (SPEC §3.5): 33.3 Hz */
#define APP_TICK_US 30000u             /* the same period [µs], for the timer */
#define APP_TICKS 200                  /* ticks run [ticks] (6 s) */
#define APP_PAPER_CASE 4               /* Table X case IV */
#define APP_TLM_EVERY 10               /* a telemetry record every N ticks (and on events) */
#define APP_CONFIG_CHECK_EVERY 33      /* the configuration checked every N ticks (~1 s) */

/* Injected estimator faults (what a flight computer sees when its estimator glitches):
 * - APP_FAULT_QUAT_TICK: one attitude quaternion of norm 1.2 (a bad normalisation). Rejected
 *   (QUATERNION_INVALID); one rejection is within the hold budget: the tick runs on the last
 *   good record, status UVMS_OK, flag SENSOR_HELD.
 * - APP_FAULT_NAN_FIRST .. + APP_FAULT_NAN_TICKS − 1: the DVL drops out and the velocity is NaN
 *   for 7 ticks. Each is rejected (SENSOR_NONFINITE); the first sensor_hold_max_ticks (5 in
 *   the paper configuration) are held (UVMS_OK, SENSOR_HELD), the rest get the safe output:
 *   status UVMS_ERR_NONFINITE, flag SENSOR_HOLD_EXPIRED, every motor command zero. */
#define APP_FAULT_QUAT_TICK 60
#define APP_FAULT_QUAT_NORM UVMS_R(1.2)
#define APP_FAULT_NAN_FIRST 120
#define APP_FAULT_NAN_TICKS 7
/* Injected overrun (option stall_at=K): after tick K's step the loop busy-waits 2.5 tick
 * periods (a stand-in for a blocking flash write). Ticks K+1 and K+2 arrive while it runs
 * (2 overruns); the loop wakes for K+2, so tick K+1 is never stepped (1 missed tick) and the
 * controller reports TICK_GAP on tick K+2. */
#define APP_STALL_HALF_PERIODS 5u
/* Injected configuration upset (option config_upset_at=K): after tick K's step the lowest
 * mantissa bit of the configuration's position damping K_DF flips in RAM (a stand-in for a
 * memory upset). The controller does not notice; the next configuration check does
 * (check_config): the configuration is rebuilt and the controller initialised again, and it
 * captures its station anew on the next tick. */

/* Flags that say a sensor record was rejected (controller.h). */
#define APP_REJECT_FLAGS                                                                      \
  (UVMS_FLAG_SENSOR_NONFINITE | UVMS_FLAG_QUATERNION_INVALID | UVMS_FLAG_JOINT_LIMIT |          \
   UVMS_FLAG_VEHICLE_SPEED_IMPLAUSIBLE | UVMS_FLAG_ANGULAR_RATE_IMPLAUSIBLE |                   \
   UVMS_FLAG_JOINT_RATE_IMPLAUSIBLE | UVMS_FLAG_MOTOR_SPEED_IMPLAUSIBLE |                       \
   UVMS_FLAG_MOTOR_CURRENT_IMPLAUSIBLE | UVMS_FLAG_TICK_NOT_INCREASING |                        \
   UVMS_FLAG_TIME_IMPLAUSIBLE)
/* Flags checked against the expected outcome of each tick. */
#define APP_CHECKED_FLAGS                                                                     \
  (APP_REJECT_FLAGS | UVMS_FLAG_SENSOR_HELD | UVMS_FLAG_SENSOR_HOLD_EXPIRED | UVMS_FLAG_TICK_GAP | \
   UVMS_FLAG_MODEL_FAULT | UVMS_FLAG_TRAJECTORY_FAULT | UVMS_FLAG_INSTANCE_INVALID)

/* ---- state, all static -------------------------------------------------------------------- */
static uvms_ctrl_t g_ctrl;
static uvms_ctrl_config_t g_cfg; /* g_ctrl points to it (uvms_ctrl_init): never written while
                                    g_ctrl is in use */
static uvms_ctrl_sensors_t g_sensors;
static uvms_ctrl_command_t g_cmd;
static uvms_ctrl_telemetry_t g_tlm;
static flight_estimate_t g_est;
static sim_t g_sim;

/* Shared with the timer interrupt. */
static volatile uint32_t g_tick_flag;   /* set by the interrupt, cleared by the loop */
static volatile uint32_t g_tick_count;  /* timer interrupts since start [ticks] */
static volatile uint32_t g_busy;        /* 1 while a tick's work runs */
static volatile uint32_t g_overruns;    /* interrupts that came while g_busy */

/* What the actuator drivers were last given (the current drive: I*_j, İ*_j; joints θ̈_cmd). */
typedef struct {
  uvms_real_t current_cmd_A[UVMS_MAX_THRUSTERS];
  uvms_real_t current_rate_A_s[UVMS_MAX_THRUSTERS];
  uvms_real_t joint_accel_rad_s2[UVMS_MAX_JOINTS];
  uvms_real_t force_I_N[3]; /* the force those thrusts deliver (stand-in plant input) [N] */
} actuators_t;
static actuators_t g_act;

typedef struct {
  uint32_t steps, missed, ok, nonfinite, range, singular, state, other;
  uint32_t held, safe_output, tick_gap, reinit, check_failed;
  uint32_t config_checks, config_changed;
  uint32_t step_cycles_max, work_cycles_max;
  uint64_t step_cycles_sum;
  uvms_real_t pos_err_max_m, pos_err_final_m;
} stats_t;
static stats_t g_stats;

/* ---- the timer interrupt ------------------------------------------------------------------ */
void app_timer_isr(void) {
  g_tick_count = g_tick_count + 1u;
  if (g_busy) g_overruns = g_overruns + 1u; /* the previous tick's work is still running */
  g_tick_flag = 1u;
}

/* ---- telemetry text, without stdio (no printf, no heap) ----------------------------------- */
typedef struct {
  char buf[200];
  size_t n;
} line_t;

static void put_str(line_t *l, const char *s) {
  while (*s != '\0' && l->n + 1u < sizeof l->buf) l->buf[l->n++] = *s++;
}
static void put_u32(line_t *l, uint32_t v) {
  char tmp[10];
  int n = 0;
  do {
    tmp[n++] = (char)('0' + v % 10u);
    v /= 10u;
  } while (v != 0u && n < 10);
  while (n > 0 && l->n + 1u < sizeof l->buf) l->buf[l->n++] = tmp[--n];
}
static void put_i32(line_t *l, int32_t v) {
  if (v < 0) {
    put_str(l, "-");
    put_u32(l, (uint32_t)(-(v + 1)) + 1u);
  } else {
    put_u32(l, (uint32_t)v);
  }
}
static void put_hex(line_t *l, uint32_t v) {
  static const char digits[] = "0123456789abcdef";
  put_str(l, "0x");
  for (int s = 28; s >= 0; s -= 4)
    if (l->n + 1u < sizeof l->buf) l->buf[l->n++] = digits[(v >> s) & 0xFu];
}
/** x·scale rounded to an integer, clamped to ±2e9 (telemetry units: mm, mrad, mN...). */
static int32_t scaled(uvms_real_t x, uvms_real_t scale) {
  uvms_real_t y = x * scale;
  if (!(y == y)) return 0;
  if (y > UVMS_R(2.0e9)) y = UVMS_R(2.0e9);
  if (y < UVMS_R(-2.0e9)) y = UVMS_R(-2.0e9);
  return (int32_t)(y >= 0 ? y + UVMS_R(0.5) : y - UVMS_R(0.5));
}
static void send(line_t *l) {
  put_str(l, "\n");
  board_uart_write(l->buf, l->n);
  l->n = 0u;
}

/* One "name value" pair of a summary line. */
typedef struct {
  const char *name;
  uint32_t value;
} field_t;

#define ARRAY_LEN(a) (sizeof(a) / sizeof((a)[0]))

/* Append "head name value name value ..." (n pairs). */
static void put_fields(line_t *l, const char *head, const field_t *f, size_t n) {
  put_str(l, head);
  for (size_t i = 0; i < n; ++i) {
    put_str(l, " ");
    put_str(l, f[i].name);
    put_str(l, " ");
    put_u32(l, f[i].value);
  }
}

/* Send "head name value ..." as one line. */
static void send_fields(line_t *l, const char *head, const field_t *f, size_t n) {
  put_fields(l, head, f, n);
  send(l);
}

/* ---- sensor packing ----------------------------------------------------------------------- */
/**
 * Fill the controller's sensor record from the estimator's output (estimator.h). What
 * uvms_ctrl_step expects (uvms/controller.h, uvms_ctrl_sensors_t; docs/MODEL.md §2):
 *
 *  tick, time_s      strictly increasing sequence number k, and the time since the start [s]
 *                    consistent with it: time_s ≈ t_a + (k − k_a)·tick_s (t_a, k_a: the first
 *                    accepted record) within half a tick (plus a few units of rounding of the
 *                    real type, so a float time stays acceptable on runs of years). A
 *                    repeated tick is rejected; a skipped one is reported (TICK_GAP) and the
 *                    record used. The clock is the estimator's own (sim.c: k·tick_s).
 *  position_m        r0: vehicle CoM, INERTIAL frame, z up [m]. The station to hold is the
 *                    position (and attitude) of the first accepted tick.
 *  quaternion_wxyz   R0 as a Hamilton unit quaternion, SCALAR FIRST, rotating vehicle (body)
 *                    vectors into the inertial frame. Not renormalised here on purpose: the
 *                    controller rejects ||q| − 1| > limits.quat_norm_tol (0.05), which catches
 *                    an estimator fault that renormalising would hide.
 *  velocity_m_s      v0: CoM velocity in the INERTIAL frame [m/s] (a DVL gives body-frame
 *                    velocity: rotate it, v_I = R0·v_B).
 *  omega_rad_s       ω0: angular velocity in the INERTIAL frame [rad/s] (a gyro gives body
 *                    rates: rotate them, ω_I = R0·ω_B).
 *  q_rad, qd_rad_s   joint angles θ_i [rad] (DH convention of the arm model, inside
 *                    joint_min/max_rad) and rates θ̇_i [rad/s], joints 1..7 in order.
 *  motor_speed_rad_s, motor_current_A
 *                    each thruster motor's signed shaft speed ω_j [rad/s] and winding current
 *                    I_j [A], thrusters in the order of the configured geometry; read only for
 *                    usable thrusters.
 *  thruster_usable_mask
 *                    bit j = thruster j usable. Clearing a bit re-allocates over the others.
 *
 * Nothing is validated or filtered here: the controller validates every field and says what
 * it rejected (flags), which is what the application must act on.
 */
static void pack_sensors(const flight_estimate_t *est, uvms_ctrl_sensors_t *s) {
  memset(s, 0, sizeof *s);
  s->tick = est->tick;
  s->time_s = est->time_s;
  uvms_real_t R0[9];
  (void)uvms_quat_to_rot(est->q_IB_wxyz, R0); /* normalises; identity if q is not finite */
  for (int i = 0; i < 3; ++i) {
    s->position_m[i] = est->p_I_m[i];
    /* body → inertial: x_I = R0·x_B (R0 row-major) */
    s->velocity_m_s[i] = R0[3 * i] * est->v_B_m_s[0] + R0[3 * i + 1] * est->v_B_m_s[1] +
                         R0[3 * i + 2] * est->v_B_m_s[2];
    s->angular_velocity_rad_s[i] = R0[3 * i] * est->w_B_rad_s[0] + R0[3 * i + 1] * est->w_B_rad_s[1] +
                        R0[3 * i + 2] * est->w_B_rad_s[2];
  }
  for (int i = 0; i < 4; ++i) s->quaternion_wxyz[i] = est->q_IB_wxyz[i];
  for (int i = 0; i < UVMS_MAX_JOINTS; ++i) {
    s->joint_position_rad[i] = est->q_rad[i];
    s->joint_velocity_rad_s[i] = est->qd_rad_s[i];
  }
  for (int j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    s->motor_speed_rad_s[j] = est->motor_speed_rad_s[j];
    s->motor_current_A[j] = est->motor_current_A[j];
  }
  s->thruster_usable_mask = est->thruster_ok_mask;
}

/** The estimator faults of the run (see APP_FAULT_*), applied to tick k's estimate. */
static void inject_faults(int64_t k, flight_estimate_t *est) {
  if (k == APP_FAULT_QUAT_TICK)
    for (int i = 0; i < 4; ++i) est->q_IB_wxyz[i] *= APP_FAULT_QUAT_NORM;
  if (k >= APP_FAULT_NAN_FIRST && k < APP_FAULT_NAN_FIRST + APP_FAULT_NAN_TICKS)
    for (int i = 0; i < 3; ++i) est->v_B_m_s[i] = (uvms_real_t)NAN;
}

/* ---- status, flags, safe output ----------------------------------------------------------- */
/** 1 if the command is the controller's safe output: no motor current, voltage or current
 *  rate, no joint acceleration (controller.h, uvms_ctrl_step). */
static int is_safe_output(const uvms_ctrl_command_t *cmd) {
  for (int j = 0; j < UVMS_MAX_THRUSTERS; ++j)
    if (cmd->motor_voltage_V[j] != 0 || cmd->motor_current_cmd_A[j] != 0 ||
        cmd->motor_current_rate_A_s[j] != 0)
      return 0;
  for (int i = 0; i < UVMS_MAX_JOINTS; ++i)
    if (cmd->joint_acceleration_rad_s2[i] != 0) return 0;
  return 1;
}

/** Hand the command to the drivers: the motors' current commands and the joints'
 *  accelerations. stand_in_force_I_N is what the simulated vehicle feels from it. */
static void apply_actuators(const uvms_ctrl_command_t *cmd, const uvms_real_t force_I_N[3]) {
  for (int j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    g_act.current_cmd_A[j] = cmd->motor_current_cmd_A[j];
    g_act.current_rate_A_s[j] = cmd->motor_current_rate_A_s[j];
  }
  for (int i = 0; i < UVMS_MAX_JOINTS; ++i)
    g_act.joint_accel_rad_s2[i] = cmd->joint_acceleration_rad_s2[i];
  for (int i = 0; i < 3; ++i) g_act.force_I_N[i] = force_I_N[i];
}

/**
 * What the application does with each status of uvms_ctrl_step (controller.h, docs/FAULTS.md).
 * On every error return the library has already written its safe output into cmd (zero motor
 * voltage, current command and current rate; zero joint acceleration; θ_ref held), so the
 * command is always applied: the app never invents its own "safe" values, except for
 * UVMS_ERR_ARG, where cmd may not have been written.
 */
static void handle_status(uvms_status_t status) {
  static const uvms_real_t no_force_N[3] = {0, 0, 0};
  switch (status) {
    case UVMS_OK:
      /* Normal, or degraded but controlled: the flags say how (SENSOR_HELD: an estimate was
         rejected and the last good one used; THRUST_SATURATED, VOLTAGE_SATURATED,
         ALLOC_SINGULAR: the wrench was cut; TICK_GAP: ticks were lost upstream). */
      ++g_stats.ok;
      apply_actuators(&g_cmd, g_tlm.force_deliverable_N);
      break;
    case UVMS_ERR_NONFINITE: /* a NaN/inf estimate, beyond the hold budget */
    case UVMS_ERR_RANGE:     /* an implausible estimate, beyond the hold budget */
      /* Safe output: thrusters unpowered until the estimator recovers; the next accepted
         record resumes control about the same station (no reset: the reference is kept). A
         real vehicle would also tell the estimator and, after a long outage, the mission
         manager. */
      if (status == UVMS_ERR_NONFINITE) ++g_stats.nonfinite; else ++g_stats.range;
      apply_actuators(&g_cmd, no_force_N);
      break;
    case UVMS_ERR_SINGULAR: /* no allocation at all: zero voltages, the joint command stands */
      ++g_stats.singular;
      apply_actuators(&g_cmd, no_force_N);
      break;
    case UVMS_ERR_STATE:
      /* The instance is not initialised or its own counts are corrupt (INSTANCE_INVALID, e.g.
         a memory upset): apply the safe output and initialise again from the configuration. */
      ++g_stats.state;
      apply_actuators(&g_cmd, no_force_N);
      if (uvms_ctrl_init(&g_ctrl, &g_cfg) == UVMS_OK) ++g_stats.reinit;
      break;
    case UVMS_ERR_ARG: /* a programming error (NULL): cmd may be unwritten; zero it here */
      ++g_stats.other;
      memset(&g_cmd, 0, sizeof g_cmd);
      apply_actuators(&g_cmd, no_force_N);
      break;
    default: /* a module failed (MODEL_FAULT, TRAJECTORY_FAULT): the safe output was written */
      ++g_stats.other;
      apply_actuators(&g_cmd, no_force_N);
      break;
  }
  if (status != UVMS_OK && status != UVMS_ERR_SINGULAR) {
    if (is_safe_output(&g_cmd)) ++g_stats.safe_output;
    else ++g_stats.check_failed; /* the library's contract says this cannot happen */
  }
  if (g_tlm.flags & UVMS_FLAG_SENSOR_HELD) ++g_stats.held;
  if (g_tlm.flags & UVMS_FLAG_TICK_GAP) ++g_stats.tick_gap;
}

/* ---- the expected outcome of each tick (from the fault schedule and docs/FAULTS.md) -------- */
typedef struct {
  uvms_status_t status;
  uint32_t flags; /* expected value of flags & APP_CHECKED_FLAGS */
} expected_t;

static expected_t expected(int64_t k, int gap) {
  expected_t e = {UVMS_OK, gap ? UVMS_FLAG_TICK_GAP : 0u};
  uint32_t reject = 0u;
  int64_t streak = 0; /* consecutive rejected records up to k */
  if (k == APP_FAULT_QUAT_TICK) {
    reject = UVMS_FLAG_QUATERNION_INVALID;
    streak = 1;
  } else if (k >= APP_FAULT_NAN_FIRST && k < APP_FAULT_NAN_FIRST + APP_FAULT_NAN_TICKS) {
    reject = UVMS_FLAG_SENSOR_NONFINITE;
    streak = k - APP_FAULT_NAN_FIRST + 1;
  }
  if (reject != 0u) {
    if (streak <= (int64_t)g_cfg.limits.sensor_hold_max_ticks) {
      e.flags |= reject | UVMS_FLAG_SENSOR_HELD;
    } else {
      e.flags |= reject | UVMS_FLAG_SENSOR_HOLD_EXPIRED;
      e.status = (reject & UVMS_FLAG_SENSOR_NONFINITE) ? UVMS_ERR_NONFINITE : UVMS_ERR_RANGE;
    }
  }
  return e;
}

/* ---- one tick ----------------------------------------------------------------------------- */
static void telemetry_record(int64_t k, uvms_status_t status, uint32_t step_cycles) {
  /* T,<tick>,<status>,<flags>,<position error x,y,z [mm]>,<attitude error |φ| [µrad]>,
     <|force delivered| [mN]>,<I*_0 [mA]>,<step [µs]> */
  line_t l = {{0}, 0u};
  uvms_real_t err_rad2 = 0;
  for (int i = 0; i < 3; ++i) err_rad2 += g_tlm.attitude_error_rad[i] * g_tlm.attitude_error_rad[i];
  uvms_real_t f_N2 = 0;
  for (int i = 0; i < 3; ++i) f_N2 += g_act.force_I_N[i] * g_act.force_I_N[i];
  put_str(&l, "T,");
  put_i32(&l, (int32_t)k);
  put_str(&l, ",");
  put_str(&l, uvms_status_str(status));
  put_str(&l, ",");
  put_hex(&l, g_tlm.flags);
  for (int i = 0; i < 3; ++i) {
    put_str(&l, ",");
    put_i32(&l, scaled(g_sensors.position_m[i] - g_tlm.position_ref_m[i], UVMS_R(1e3)));
  }
  put_str(&l, ",");
  put_i32(&l, scaled(uvms_sqrt(err_rad2), UVMS_R(1e6)));
  put_str(&l, ",");
  put_i32(&l, scaled(uvms_sqrt(f_N2), UVMS_R(1e3)));
  put_str(&l, ",");
  put_i32(&l, scaled(g_act.current_cmd_A[0], UVMS_R(1e3)));
  put_str(&l, ",");
  put_u32(&l, step_cycles / (board_core_clock_hz() / 1000000u));
  send(&l);
}

/* The configuration: the paper's case IV with the arm holding its start pose. Its one source;
 * a flight build would keep it as const data in flash. Returns 0 when built. */
static int load_config(uvms_ctrl_config_t *cfg) {
  if (uvms_ctrl_config_paper(cfg, APP_PAPER_CASE) != UVMS_OK) return -1;
  cfg->traj_mode = UVMS_TRAJ_HOLD;
  cfg->tick_s = APP_TICK_S;
  return 0;
}

/* The controller reads g_cfg on every step and does not check it (uvms_ctrl_init,
 * "Configuration lifetime"); the application does, about once a second
 * (uvms_ctrl_config_verify: the CRC-32 taken at init). A changed configuration (a memory
 * upset, a stray write) is rebuilt from its source and the controller initialised again; the
 * instance is cleared first, so that it never runs on a configuration being rewritten. */
static void check_config(void) {
  ++g_stats.config_checks;
  if (uvms_ctrl_config_verify(&g_ctrl) == UVMS_OK) return;
  ++g_stats.config_changed;
  memset(&g_ctrl, 0, sizeof g_ctrl);
  if (load_config(&g_cfg) == 0 && uvms_ctrl_init(&g_ctrl, &g_cfg) == UVMS_OK) ++g_stats.reinit;
}

static void run_tick(int64_t k, int64_t k_prev) {
  /* The simulated vehicle moves under the command held since the last step. */
  if (k_prev >= 0) sim_advance(&g_sim, g_act.force_I_N, (uvms_real_t)(k - k_prev) * APP_TICK_S);
  sim_estimate(&g_sim, k, APP_TICK_S, &g_est);
  inject_faults(k, &g_est);
  pack_sensors(&g_est, &g_sensors);

  const uint64_t t0 = board_now_cycles();
  const uvms_status_t status = uvms_ctrl_step(&g_ctrl, &g_sensors, &g_cmd, &g_tlm);
  const uint32_t step_cycles = (uint32_t)(board_now_cycles() - t0);

  handle_status(status);
  sim_set_motors(&g_sim, g_tlm.omega_des_rad_s, g_tlm.current_des_A);

  ++g_stats.steps;
  g_stats.step_cycles_sum += step_cycles;
  if (step_cycles > g_stats.step_cycles_max) g_stats.step_cycles_max = step_cycles;
  uvms_real_t e2 = 0;
  for (int i = 0; i < 3; ++i) {
    const uvms_real_t d = g_sim.p_I_m[i] - g_tlm.position_ref_m[i];
    e2 += d * d;
  }
  g_stats.pos_err_final_m = uvms_sqrt(e2);
  if (g_stats.pos_err_final_m > g_stats.pos_err_max_m)
    g_stats.pos_err_max_m = g_stats.pos_err_final_m;

  const expected_t want = expected(k, k_prev >= 0 && k > k_prev + 1);
  const int as_expected = status == want.status && (g_tlm.flags & APP_CHECKED_FLAGS) == want.flags;
  if (!as_expected) ++g_stats.check_failed;
  const uint32_t events = APP_CHECKED_FLAGS | UVMS_FLAG_THRUST_SATURATED |
                          UVMS_FLAG_VOLTAGE_SATURATED | UVMS_FLAG_ALLOC_SINGULAR;
  if (k % APP_TLM_EVERY == 0 || status != UVMS_OK || (g_tlm.flags & events) != 0u || !as_expected)
    telemetry_record(k, status, step_cycles);
  if (!as_expected) {
    line_t l = {{0}, 0u};
    put_str(&l, "CHECK FAILED: tick ");
    put_i32(&l, (int32_t)k);
    put_str(&l, " expected ");
    put_str(&l, uvms_status_str(want.status));
    put_str(&l, " flags ");
    put_hex(&l, want.flags);
    send(&l);
  }
}

/** The value of "key=N" in the options string, or -1. */
static int64_t option(const char *opts, const char *key) {
  const size_t key_len = strlen(key);
  for (const char *p = opts; *p != '\0'; ++p) {
    if ((p == opts || p[-1] == ' ') && strncmp(p, key, key_len) == 0 && p[key_len] == '=') {
      int64_t v = 0;
      const char *d = p + key_len + 1;
      if (*d < '0' || *d > '9') return -1;
      for (int n = 0; *d >= '0' && *d <= '9' && n < 9; ++d, ++n) v = v * 10 + (*d - '0');
      return v;
    }
  }
  return -1;
}

static void upset_config(void) {
  unsigned char *b = (unsigned char *)&g_cfg.gains.kdf_N_s_m;
  b[0] ^= 1u; /* little-endian (Cortex-M, x86-64): the lowest mantissa bit */
}

static void summary_and_checks(int64_t stall_at, int64_t upset_at, uint32_t period_cycles) {
  /* What the run must show (the documented outcome, examples/README.md). */
  const uint32_t want_overruns = stall_at >= 0 ? 2u : 0u;
  const uint32_t want_missed = stall_at >= 0 ? 1u : 0u;
  uint32_t want_ok = 0, want_nonfinite = 0, want_held = 0, want_config_checks = 0;
  uint32_t want_config_changed = 0;
  for (int64_t k = 0; k < APP_TICKS; ++k) {
    if (stall_at >= 0 && k == stall_at + 1) continue; /* never stepped */
    if (k % APP_CONFIG_CHECK_EVERY == 0) {
      ++want_config_checks;
      if (upset_at >= 0 && k > upset_at) want_config_changed = 1u; /* the first check after */
    }
    const expected_t e = expected(k, 0);
    if (e.status == UVMS_OK) ++want_ok;
    if (e.status == UVMS_ERR_NONFINITE) ++want_nonfinite;
    if (e.flags & UVMS_FLAG_SENSOR_HELD) ++want_held;
  }
  /* Static deflection of the position PD under the steady disturbance: the loop (K_PF, K_DF,
     SIM_MASS_KG) is overdamped, so from rest the error approaches F/K_PF without overshoot. */
  const uvms_real_t bound_m = SIM_DISTURBANCE_X_N / g_cfg.gains.kpf_N_m;
  const uint32_t cycles_per_us = board_core_clock_hz() / 1000000u;
  const uint32_t overruns = g_overruns;

  line_t l = {{0}, 0u};
  const field_t counts[] = {{"ticks", (uint32_t)APP_TICKS}, {"steps", g_stats.steps},
                            {"missed", g_stats.missed}, {"overruns", overruns}};
  send_fields(&l, "summary:", counts, ARRAY_LEN(counts));
  const field_t statuses[] = {{"ok", g_stats.ok},         {"nonfinite", g_stats.nonfinite},
                              {"range", g_stats.range},   {"singular", g_stats.singular},
                              {"state", g_stats.state},   {"other", g_stats.other},
                              {"| held", g_stats.held},   {"safe_output", g_stats.safe_output},
                              {"tick_gap", g_stats.tick_gap}};
  send_fields(&l, "summary: status", statuses, ARRAY_LEN(statuses));
  const uint32_t mean_cycles =
      g_stats.steps ? (uint32_t)(g_stats.step_cycles_sum / g_stats.steps) : 0u;
  const field_t timing_us[] = {{"max", g_stats.step_cycles_max / cycles_per_us},
                               {"mean", mean_cycles / cycles_per_us},
                               {"work_us max", g_stats.work_cycles_max / cycles_per_us},
                               {"budget_us", period_cycles / cycles_per_us}};
  send_fields(&l, "summary: step_us", timing_us, ARRAY_LEN(timing_us));
  const field_t config[] = {{"checks", g_stats.config_checks},
                            {"changed", g_stats.config_changed},
                            {"reinit", g_stats.reinit}};
  send_fields(&l, "summary: config", config, ARRAY_LEN(config));
  put_str(&l, "summary: position error mm final ");
  put_i32(&l, scaled(g_stats.pos_err_final_m, UVMS_R(1e3)));
  put_str(&l, " max ");
  put_i32(&l, scaled(g_stats.pos_err_max_m, UVMS_R(1e3)));
  put_str(&l, " bound ");
  put_i32(&l, scaled(bound_m, UVMS_R(1e3)));
  send(&l);

  int failed = (int)g_stats.check_failed;
  failed += g_stats.steps != (uint32_t)APP_TICKS - want_missed;
  failed += g_stats.missed != want_missed;
  failed += overruns != want_overruns;
  failed += g_stats.ok != want_ok;
  failed += g_stats.nonfinite != want_nonfinite;
  failed += g_stats.held != want_held;
  failed += g_stats.safe_output != want_nonfinite;
  failed += g_stats.tick_gap != want_missed;
  failed += g_stats.range + g_stats.singular + g_stats.state + g_stats.other != 0u;
  failed += !(g_stats.pos_err_max_m <= bound_m);
  failed += g_stats.config_checks != want_config_checks;
  failed += g_stats.config_changed != want_config_changed;
  failed += g_stats.reinit != want_config_changed; /* no other re-initialisation */
  const field_t expected_counts[] = {{"steps", (uint32_t)APP_TICKS - want_missed},
                                     {"overruns", want_overruns}, {"ok", want_ok},
                                     {"nonfinite", want_nonfinite}, {"held", want_held}};
  put_fields(&l, "summary: expected", expected_counts, ARRAY_LEN(expected_counts));
  put_str(&l, " -> ");
  put_str(&l, failed == 0 ? "PASS" : "FAIL");
  put_str(&l, " (");
  put_u32(&l, (uint32_t)failed);
  put_str(&l, " failed checks)");
  send(&l);
  g_stats.check_failed = (uint32_t)failed;
}

int app_main(void) {
  static char opts[128];
  board_init();
  board_cmdline(opts, sizeof opts);
  const int64_t stall_at = option(opts, "stall_at");
  const int64_t upset_at = option(opts, "config_upset_at");

  if (load_config(&g_cfg) != 0) return 100;
  const uvms_status_t init = uvms_ctrl_init(&g_ctrl, &g_cfg);
  line_t l = {{0}, 0u};
  put_str(&l, "flight_loop: uvms ");
  put_str(&l, uvms_version());
  put_str(&l, UVMS_REAL_IS_FLOAT ? " float" : " double");
  put_str(&l, ", init ");
  put_str(&l, uvms_status_str(init));
  put_str(&l, " (");
  put_str(&l, uvms_cfg_field_str(g_ctrl.config_error));
  put_str(&l, "), case IV hold, ");
  put_u32(&l, (uint32_t)APP_TICKS);
  put_str(&l, " ticks");
  if (stall_at >= 0) {
    put_str(&l, ", stall after tick ");
    put_u32(&l, (uint32_t)stall_at);
  }
  if (upset_at >= 0) {
    put_str(&l, ", configuration upset after tick ");
    put_u32(&l, (uint32_t)upset_at);
  }
  send(&l);
  if (init != UVMS_OK) return 101; /* a configuration error is found on the bench, not in flight */
  sim_init(&g_sim, &g_cfg);

  /* The tick: SysTick reload = core clock × period − 1 (25 MHz × 0.03 s − 1 = 749 999). */
  const uint32_t period_cycles = board_core_clock_hz() / 1000000u * APP_TICK_US;
  put_str(&l, "flight_loop: core clock ");
  put_u32(&l, board_core_clock_hz());
  put_str(&l, " Hz, tick ");
  put_u32(&l, APP_TICK_US);
  put_str(&l, " us, timer reload ");
  put_u32(&l, period_cycles - 1u);
  send(&l);
  put_str(&l, "T,tick,status,flags,ex_mm,ey_mm,ez_mm,att_err_urad,force_mN,Icmd0_mA,step_us");
  send(&l);
  if (board_timer_start(period_cycles) != 0) return 102;

  int64_t k_prev = -1;
  for (;;) {
    board_sleep_until_set(&g_tick_flag);
    g_tick_flag = 0u;                         /* clear first, then read the count: a tick */
    const int64_t k = (int64_t)g_tick_count - 1; /* arriving in between is seen next time */
    if (k == k_prev) continue;                /* already stepped (woken by that tick) */
    if (k >= APP_TICKS) break;
    g_busy = 1u;
    const uint64_t t0 = board_now_cycles();
    if (k_prev >= 0) g_stats.missed += (uint32_t)(k - k_prev - 1);
    run_tick(k, k_prev);
    if (k % APP_CONFIG_CHECK_EVERY == 0) check_config();
    k_prev = k;
    if (k == stall_at) board_busy_wait_cycles(period_cycles / 2u * APP_STALL_HALF_PERIODS);
    if (k == upset_at) upset_config();
    const uint32_t work_cycles = (uint32_t)(board_now_cycles() - t0);
    if (work_cycles > g_stats.work_cycles_max) g_stats.work_cycles_max = work_cycles;
    g_busy = 0u;
  }
  summary_and_checks(stall_at, upset_at, period_cycles);
  return g_stats.check_failed > 255u ? 255 : (int)g_stats.check_failed;
}
