/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_gen: writes the generated seed corpora of the fuzz targets into OUTDIR:
 *   OUTDIR/fuzz_ctrl_step/   configuration byte + sensor records of a vehicle at rest at θI
 *                            (every case × hold / cycloid / Cartesian line; then a dead
 *                            thruster, rank loss, a NaN, a bad quaternion, ticks out of order)
 *   OUTDIR/fuzz_ctrl_node/   record sequences: paper config then sealed sensors; an encoded
 *                            config as bytes (mutations stay CRC-valid with the seal bit);
 *                            status messages; sensors before any config
 *   OUTDIR/fuzz_lcm_decode/  each type encoded and sealed, once as it is, once with the seal bit
 * Generated at build time rather than committed: encoded messages carry the LCM fingerprint,
 * and sensor records the layout of uvms_ctrl_sensors_t (float or double), so committed bytes
 * would go stale when a type changes. Input formats: the comment at the top of each target.
 *
 *   uvms_fuzz_corpus_gen OUTDIR
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "msg/codec.h"
#include "fuzz_support.h" /* FUZZ_SESSION */

static const char *g_out;
static int g_failed;

static void write_seed(const char *fuzzer, const char *name, const uint8_t *data, size_t n) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", g_out, fuzzer);
  mkdir(path, 0777);
  snprintf(path, sizeof path, "%s/%s/%s", g_out, fuzzer, name);
  FILE *f = fopen(path, "wb");
  if (f == NULL || fwrite(data, 1, n, f) != n) {
    fprintf(stderr, "corpus_gen: cannot write %s\n", path);
    g_failed = 1;
  }
  if (f != NULL) fclose(f);
}

/* The sensors of a vehicle at rest at the origin, joints at θI, every thruster usable. */
static void rest_sensors(const uvms_ctrl_config_t *cfg, int64_t tick, uvms_ctrl_sensors_t *s) {
  memset(s, 0, sizeof *s);
  s->tick = tick;
  s->time_s = (uvms_real_t)tick * cfg->tick_s;
  s->quaternion_wxyz[0] = 1;
  for (int i = 0; i < UVMS_MAX_JOINTS; ++i) s->joint_position_rad[i] = cfg->theta_start_rad[i];
  s->thruster_usable_mask = 0xffu;
}

/* ---- fuzz_ctrl_step ---- */

enum { STEP_RECORDS = 6 };

static void step_seed(const char *name, uint8_t sel, const uvms_ctrl_sensors_t *recs, int n) {
  static uint8_t buf[1 + 16 * sizeof(uvms_ctrl_sensors_t)];
  buf[0] = sel;
  memcpy(buf + 1, recs, (size_t)n * sizeof *recs);
  write_seed("fuzz_ctrl_step", name, buf, 1 + (size_t)n * sizeof *recs);
}

static void gen_ctrl_step(void) {
  static const char *const traj_names[3] = {"hold", "cycloid", "cartesian"};
  uvms_ctrl_config_t cfg;
  uvms_ctrl_sensors_t recs[STEP_RECORDS];
  char name[64];
  for (int c = 1; c <= 8; ++c) {
    uvms_ctrl_config_paper(&cfg, c);
    for (int t = 0; t < 3; ++t) {
      for (int k = 0; k < STEP_RECORDS; ++k) rest_sensors(&cfg, k, &recs[k]);
      snprintf(name, sizeof name, "case%d_%s", c, traj_names[t]);
      step_seed(name, (uint8_t)((c - 1) | (t << 3)), recs, STEP_RECORDS);
    }
  }
  uvms_ctrl_config_paper(&cfg, 4);
  const uint8_t sel4 = 3 | (1 << 3); /* case IV, joint cycloid */
  for (int k = 0; k < STEP_RECORDS; ++k) rest_sensors(&cfg, k, &recs[k]);
  for (int k = 2; k < STEP_RECORDS; ++k) recs[k].thruster_usable_mask = 0x7fu;
  step_seed("dead_thruster", sel4, recs, STEP_RECORDS);
  for (int k = 2; k < STEP_RECORDS; ++k) recs[k].thruster_usable_mask = 0x0fu;
  step_seed("rank_loss", sel4, recs, STEP_RECORDS);
  for (int k = 0; k < STEP_RECORDS; ++k) rest_sensors(&cfg, k, &recs[k]);
  recs[3].joint_position_rad[2] = (uvms_real_t)NAN;
  step_seed("nan_joint", sel4, recs, STEP_RECORDS);
  rest_sensors(&cfg, 3, &recs[3]);
  recs[3].quaternion_wxyz[0] = 2;
  step_seed("bad_quaternion", sel4, recs, STEP_RECORDS);
  rest_sensors(&cfg, 3, &recs[3]);
  recs[3].tick = 1;
  recs[4].tick = 9;
  step_seed("ticks_out_of_order", sel4, recs, STEP_RECORDS);
  for (int k = 0; k < STEP_RECORDS; ++k) {
    rest_sensors(&cfg, k, &recs[k]);
    recs[k].position_m[0] = (uvms_real_t)(0.5 * k);
    recs[k].angular_velocity_rad_s[2] = (uvms_real_t)0.3;
    recs[k].velocity_m_s[1] = (uvms_real_t)-0.2;
    for (int j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
      recs[k].motor_speed_rad_s[j] = (uvms_real_t)(-20.0 * j);
      recs[k].motor_current_A[j] = (uvms_real_t)(0.5 * j);
    }
  }
  step_seed("moving", sel4, recs, STEP_RECORDS);
  step_seed("moving_sequence_reset", (uint8_t)(sel4 | (1 << 5) | (1 << 6)), recs, STEP_RECORDS);
}

/* ---- fuzz_ctrl_node and fuzz_lcm_decode ---- */

static void sensors_msg(const uvms_ctrl_config_t *cfg, int64_t tick, uvms_sensors_t *m) {
  memset(m, 0, sizeof *m);
  m->utime = (int64_t)llround((double)cfg->tick_s * 1e6 * (double)tick);
  m->tick = tick;
  m->session = FUZZ_SESSION;
  m->quaternion_wxyz[0] = 1;
  for (int i = 0; i < 7; ++i) m->joint_position_rad[i] = (double)cfg->theta_start_rad[i];
  m->thruster_usable_mask = 0xff;
}

/* Appends one record [h][len16][bytes] to rec; returns the new length. */
static size_t put_record(uint8_t *rec, size_t at, uint8_t h, const uint8_t *msg, int n) {
  rec[at] = h;
  rec[at + 1] = (uint8_t)(n >> 8);
  rec[at + 2] = (uint8_t)n;
  memcpy(rec + at + 3, msg, (size_t)n);
  return at + 3 + (size_t)n;
}

static void gen_node_and_decode(void) {
  static uint8_t rec[64 * 1024];
  static uint8_t msg[UVMS_MAX_MSG_BYTES];
  static uint8_t sel_msg[UVMS_MAX_MSG_BYTES + 1];
  uvms_ctrl_config_t cfg;
  char name[64];

  for (int c = 1; c <= 8; c += 3) {
    uvms_ctrl_config_paper(&cfg, c);
    /* Paper config by shortcut (channel 3), then sealed sensors of ticks 0..5. */
    size_t at = 0;
    rec[at++] = 3;
    rec[at++] = (uint8_t)(c - 1);
    for (int k = 0; k < 6; ++k) {
      uvms_sensors_t s;
      sensors_msg(&cfg, k, &s);
      const int n = uvms_sensors_t_encode_sealed(&s, msg, (int)sizeof msg);
      at = put_record(rec, at, 0x80 | 1, msg, n);
    }
    snprintf(name, sizeof name, "case%d_shortcut_then_sensors", c);
    write_seed("fuzz_ctrl_node", name, rec, at);

    /* The same with the config as bytes (seal bit: a mutated config stays CRC-valid), a
     * repeated tick, then a FINISHED status. */
    uvms_controller_config_t cm;
    uvms_config_to_msg(&cfg, &cm);
    cm.session = FUZZ_SESSION;
    int n = uvms_controller_config_t_encode_sealed(&cm, msg, (int)sizeof msg);
    at = put_record(rec, 0, 0x80 | 0, msg, n);
    for (int k = 0; k < 4; ++k) {
      uvms_sensors_t s;
      sensors_msg(&cfg, k == 3 ? 2 : k, &s);
      n = uvms_sensors_t_encode_sealed(&s, msg, (int)sizeof msg);
      at = put_record(rec, at, 0x80 | 1, msg, n);
    }
    uvms_run_status_t st;
    memset(&st, 0, sizeof st);
    st.state = UVMS_RUN_STATUS_T_FINISHED;
    st.tick = 4;
    st.session = FUZZ_SESSION;
    n = uvms_run_status_t_encode_sealed(&st, msg, (int)sizeof msg);
    at = put_record(rec, at, 0x80 | 2, msg, n);
    snprintf(name, sizeof name, "case%d_config_bytes_sensors_status", c);
    write_seed("fuzz_ctrl_node", name, rec, at);
  }
  {
    /* Sensors before any config, unsealed junk on each channel. */
    uvms_ctrl_config_paper(&cfg, 4);
    uvms_sensors_t s;
    sensors_msg(&cfg, 0, &s);
    const int n = uvms_sensors_t_encode_sealed(&s, msg, (int)sizeof msg);
    size_t at = put_record(rec, 0, 1, msg, n);
    static const uint8_t junk[] = {0xde, 0xad, 0xbe, 0xef, 0, 1, 2, 3};
    at = put_record(rec, at, 0, junk, (int)sizeof junk);
    at = put_record(rec, at, 2, junk, (int)sizeof junk);
    write_seed("fuzz_ctrl_node", "unconfigured_and_junk", rec, at);
  }

  /* fuzz_lcm_decode: selector (type index, seal bit) + a valid sealed message. */
  uvms_ctrl_config_paper(&cfg, 7);
  int lens[5];
  static uint8_t enc[5][UVMS_MAX_MSG_BYTES];
  {
    uvms_sensors_t s;
    sensors_msg(&cfg, 3, &s);
    lens[0] = uvms_sensors_t_encode_sealed(&s, enc[0], UVMS_MAX_MSG_BYTES);
  }
  {
    uvms_actuators_t a;
    memset(&a, 0, sizeof a);
    a.tick = 3;
    a.session = FUZZ_SESSION;
    for (int j = 0; j < 8; ++j) a.motor_voltage_V[j] = 1.5 * j - 4;
    a.joint_acceleration_rad_s2[2] = 0.01;
    lens[1] = uvms_actuators_t_encode_sealed(&a, enc[1], UVMS_MAX_MSG_BYTES);
  }
  {
    uvms_telemetry_t t;
    memset(&t, 0, sizeof t);
    t.tick = 3;
    t.session = FUZZ_SESSION;
    t.status = -3;
    t.flags = 4;
    lens[2] = uvms_telemetry_t_encode_sealed(&t, enc[2], UVMS_MAX_MSG_BYTES);
  }
  {
    uvms_run_status_t st;
    memset(&st, 0, sizeof st);
    st.state = UVMS_RUN_STATUS_T_FAILED;
    st.session = FUZZ_SESSION;
    st.code = UVMS_RUN_STATUS_T_CONTACT;
    snprintf((char *)st.reason, sizeof st.reason, "link_3|vehicle");
    lens[3] = uvms_run_status_t_encode_sealed(&st, enc[3], UVMS_MAX_MSG_BYTES);
  }
  {
    uvms_controller_config_t cm;
    uvms_config_to_msg(&cfg, &cm);
    cm.session = FUZZ_SESSION;
    lens[4] = uvms_controller_config_t_encode_sealed(&cm, enc[4], UVMS_MAX_MSG_BYTES);
  }
  static const char *const type_names[5] = {"sensors_t", "actuators_t", "telemetry_t",
                                            "run_status_t", "controller_config_t"};
  for (int t = 0; t < 5; ++t) {
    if (lens[t] <= 0) {
      fprintf(stderr, "corpus_gen: %s does not encode\n", type_names[t]);
      g_failed = 1;
      continue;
    }
    memcpy(sel_msg + 1, enc[t], (size_t)lens[t]);
    sel_msg[0] = (uint8_t)t;
    snprintf(name, sizeof name, "%s", type_names[t]);
    write_seed("fuzz_lcm_decode", name, sel_msg, 1 + (size_t)lens[t]);
    sel_msg[0] = (uint8_t)(0x80 | t);
    snprintf(name, sizeof name, "%s_sealbit", type_names[t]);
    write_seed("fuzz_lcm_decode", name, sel_msg, 1 + (size_t)lens[t]);
  }
}

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: uvms_fuzz_corpus_gen OUTDIR\n");
    return 2;
  }
  g_out = argv[1];
  mkdir(g_out, 0777);
  gen_ctrl_step();
  gen_node_and_decode();
  return g_failed;
}
