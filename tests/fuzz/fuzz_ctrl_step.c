/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_ctrl_step: the controller's step (firmware/include/uvms/controller.h) fed arbitrary
 * sensor records, through the public API only.
 *
 * Input layout:
 *   byte 0   configuration: case = 1 + (b & 7) (Table X I..VIII, uvms_ctrl_config_paper);
 *            trajectory = (b >> 3) & 3: 0 hold θI, 1 and 3 the paper's joint cycloid,
 *            2 the Cartesian line (its paper defaults);
 *            bit 5: sequence mode: the harness overwrites tick = k and time_s = k·tick_s, so
 *            inputs need not discover increasing ticks to reach the steady path;
 *            bit 6: uvms_ctrl_reset after the first step (re-capture of the references).
 *   then     up to FUZZ_MAX_STEPS records of sizeof(uvms_ctrl_sensors_t) bytes, copied into
 *            the struct as they are (any bit pattern: NaN, inf, denormals, huge values, any
 *            usable mask); a short last record is zero-padded.
 *
 * Properties of every step (the header's contract):
 *   - the status is UVMS_OK or one of the negative uvms_status_t codes, and telemetry carries it
 *     and the sensors' tick;
 *   - every command output is finite; |V_j| ≤ thruster j's voltage_limit_V, V_j = 0 past the
 *     layout;
 *   - an unusable thruster (bit j of thruster_usable_mask clear) gets V_j = 0;
 *   - UVMS_ERR_SINGULAR: every V_j = 0;
 *   - any other error: the safe output (V = 0, θ̈_cmd = 0, θ̇_ref = θ̈_ref = 0);
 *   - every real of the telemetry record is finite, whatever the status.
 */
#include <math.h>
#include <string.h>

#include "fuzz_support.h"
#include "uvms/controller.h"

enum { FUZZ_MAX_STEPS = 16 };

static int finite_all(const uvms_real_t *v, size_t n) {
  for (size_t i = 0; i < n; ++i) {
    if (!isfinite(v[i])) return 0;
  }
  return 1;
}

static void check_step(const uvms_ctrl_config_t *cfg, const uvms_ctrl_sensors_t *s,
                       uvms_status_t st, const uvms_ctrl_command_t *cmd,
                       const uvms_ctrl_telemetry_t *tlm) {
  const size_t n = cfg->thrusters.num_thrusters;
  FUZZ_REQUIRE(st <= UVMS_OK && st >= UVMS_ERR_STATE, "status %d", (int)st);
  FUZZ_REQUIRE(tlm->status == (int32_t)st, "telemetry status %d, step returned %d",
               (int)tlm->status, (int)st);
  FUZZ_REQUIRE(tlm->tick == s->tick, "telemetry tick %lld, sensors tick %lld",
               (long long)tlm->tick, (long long)s->tick);
  FUZZ_REQUIRE(finite_all(cmd->motor_voltage_V, UVMS_MAX_THRUSTERS), "status %d", (int)st);
  FUZZ_REQUIRE(finite_all(cmd->motor_current_cmd_A, UVMS_MAX_THRUSTERS), "status %d", (int)st);
  FUZZ_REQUIRE(finite_all(cmd->motor_current_rate_A_s, UVMS_MAX_THRUSTERS), "status %d", (int)st);
  FUZZ_REQUIRE(finite_all(cmd->joint_acceleration_rad_s2, UVMS_MAX_JOINTS), "status %d", (int)st);
  FUZZ_REQUIRE(finite_all(cmd->joint_ref_rad, UVMS_MAX_JOINTS), "status %d", (int)st);
  FUZZ_REQUIRE(finite_all(cmd->joint_ref_rate_rad_s, UVMS_MAX_JOINTS), "status %d", (int)st);
  FUZZ_REQUIRE(finite_all(cmd->joint_ref_accel_rad_s2, UVMS_MAX_JOINTS), "status %d", (int)st);
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    /* Each thruster within its own supply (its motor set, firmware 0.8.0). */
    const double vmax = j < n ? (double)cfg->thruster[j].voltage_limit_V : 0.0;
    const double v = (double)cmd->motor_voltage_V[j];
    FUZZ_REQUIRE(fabs(v) <= vmax, "V[%zu] = %g V, limit %g V (status %d)", j, v, vmax, (int)st);
    const double i_cmd = (double)cmd->motor_current_cmd_A[j];
    const double i_rate = (double)cmd->motor_current_rate_A_s[j];
    if (j < n && (s->thruster_usable_mask & (1u << j)) == 0u) {
      FUZZ_REQUIRE(v == 0.0, "unusable thruster %zu commanded %g V (status %d)", j, v, (int)st);
      FUZZ_REQUIRE(i_cmd == 0.0 && i_rate == 0.0, "unusable thruster %zu commanded %g A, %g A/s",
                   j, i_cmd, i_rate);
    }
    if (st != UVMS_OK) {
      FUZZ_REQUIRE(v == 0.0, "V[%zu] = %g V with status %d", j, v, (int)st);
      FUZZ_REQUIRE(i_cmd == 0.0 && i_rate == 0.0, "I*[%zu] = %g A, %g A/s with status %d", j,
                   i_cmd, i_rate, (int)st);
    }
  }
  /* Telemetry is finite on every tick (issue 15, item 7): every real of the record. */
  const struct { const uvms_real_t *v; size_t n; const char *name; } reals[] = {
      {&tlm->time_s, 1, "time_s"},
      {tlm->force_ff_N, 3, "force_ff_N"}, {tlm->force_fb_N, 3, "force_fb_N"},
      {tlm->force_des_N, 3, "force_des_N"}, {tlm->moment_ff_Nm, 3, "moment_ff_Nm"},
      {tlm->moment_fb_Nm, 3, "moment_fb_Nm"}, {tlm->moment_des_Nm, 3, "moment_des_Nm"},
      {tlm->thrust_des_N, UVMS_MAX_THRUSTERS, "thrust_des_N"},
      {tlm->thrust_pos_N, UVMS_MAX_THRUSTERS, "thrust_pos_N"},
      {tlm->thrust_att_N, UVMS_MAX_THRUSTERS, "thrust_att_N"},
      {tlm->omega_des_rad_s, UVMS_MAX_THRUSTERS, "omega_des_rad_s"},
      {tlm->current_des_A, UVMS_MAX_THRUSTERS, "current_des_A"},
      {tlm->advance_speed_m_s, UVMS_MAX_THRUSTERS, "advance_speed_m_s"},
      {tlm->ee_estimate_m, 3, "ee_estimate_m"}, {tlm->barycenter_m, 3, "barycenter_m"},
      {tlm->barycenter_v_m_s, 3, "barycenter_v_m_s"}, {tlm->position_ref_m, 3, "position_ref_m"},
      {tlm->attitude_error_rad, 3, "attitude_error_rad"}, {tlm->base_force_N, 3, "base_force_N"},
      {tlm->base_moment_Nm, 3, "base_moment_Nm"},
      {tlm->base_accel_model_m_s2, 3, "base_accel_model_m_s2"},
      {tlm->joint_torque_model_Nm, UVMS_MAX_JOINTS, "joint_torque_model_Nm"},
      {tlm->force_deliverable_N, 3, "force_deliverable_N"},
      {tlm->moment_deliverable_Nm, 3, "moment_deliverable_Nm"},
      {&tlm->thrust_scale_pos, 1, "thrust_scale_pos"},
      {&tlm->thrust_scale_att, 1, "thrust_scale_att"},
  };
  for (size_t f = 0; f < sizeof reals / sizeof reals[0]; ++f)
    FUZZ_REQUIRE(finite_all(reals[f].v, reals[f].n), "telemetry %s not finite (status %d)",
                 reals[f].name, (int)st);
  if (st != UVMS_OK && st != UVMS_ERR_SINGULAR) {
    for (size_t i = 0; i < UVMS_MAX_JOINTS; ++i) {
      FUZZ_REQUIRE(cmd->joint_acceleration_rad_s2[i] == 0 && cmd->joint_ref_rate_rad_s[i] == 0 &&
                       cmd->joint_ref_accel_rad_s2[i] == 0,
                   "joint %zu not at the safe output with status %d", i, (int)st);
    }
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  if (size < 1) return 0;
  const uint8_t sel = data[0];
  const int case_number = 1 + (sel & 7);
  const int traj = (sel >> 3) & 3;
  const int sequence_mode = (sel >> 5) & 1;
  const int reset_after_first = (sel >> 6) & 1;

  static uvms_ctrl_config_t cfg; /* static: uvms_ctrl_t is large; one input at a time */
  static uvms_ctrl_t ctrl;
  const uvms_status_t pst = uvms_ctrl_config_paper(&cfg, case_number);
  FUZZ_REQUIRE(pst == UVMS_OK, "uvms_ctrl_config_paper(%d) = %d", case_number, (int)pst);
  if (traj == 0) cfg.traj_mode = UVMS_TRAJ_HOLD;
  if (traj == 2) cfg.traj_mode = UVMS_TRAJ_CARTESIAN_LINE;
  const uvms_status_t ist = uvms_ctrl_init(&ctrl, &cfg);
  FUZZ_REQUIRE(ist == UVMS_OK, "paper case %d, trajectory %d rejected: %d (part %s)",
               case_number, traj, (int)ist, uvms_cfg_field_str(ctrl.config_error));

  const uint8_t *p = data + 1;
  size_t left = size - 1;
  for (int k = 0; k < FUZZ_MAX_STEPS && left > 0; ++k) {
    uvms_ctrl_sensors_t s;
    memset(&s, 0, sizeof s);
    const size_t take = left < sizeof s ? left : sizeof s;
    memcpy(&s, p, take);
    p += take;
    left -= take;
    if (sequence_mode) {
      s.tick = k;
      s.time_s = (uvms_real_t)k * cfg.tick_s;
    }
    uvms_ctrl_command_t cmd;
    uvms_ctrl_telemetry_t tlm;
    memset(&cmd, 0xFF, sizeof cmd); /* all NaN: an output the step leaves unwritten fails */
    memset(&tlm, 0xFF, sizeof tlm);
    const uvms_status_t st = uvms_ctrl_step(&ctrl, &s, &cmd, &tlm);
    check_step(&cfg, &s, st, &cmd, &tlm);
    if (k == 0 && reset_after_first) uvms_ctrl_reset(&ctrl);
  }
  return 0;
}
