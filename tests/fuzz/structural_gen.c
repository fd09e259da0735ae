/* SPDX-License-Identifier: Apache-2.0 */
/*
 * structural_gen: writes the structural regression inputs of the fuzz targets (issue 15,
 * item 8): the shapes a length-limited fuzzer (-max_len of a few kB) cannot reach, built at
 * build time instead of committed as blobs.
 *
 *   structural_gen <out dir>
 *
 * writes <out>/<target>/<name> for fuzz_scenario, fuzz_ctrl_step, fuzz_ctrl_node and
 * fuzz_lcm_decode (all replayed: the scenario reader's input bounds refuse the deepest ones
 * before toml++ sees them).
 *
 * Every file is a pure function of its name: the same bytes on every build.
 * Raw sensor records (fuzz_ctrl_step) use this build's uvms_real_t, like corpus_gen.c.
 */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "uvms/controller.h"

/* ---- a growable byte buffer ---------------------------------------------------------- */
typedef struct {
  char *p;
  size_t n, cap;
} buf_t;

static void put(buf_t *b, const void *data, size_t n) {
  if (b->n + n > b->cap) {
    size_t cap = b->cap ? b->cap : 4096;
    while (cap < b->n + n) cap *= 2;
    char *q = realloc(b->p, cap);
    if (q == NULL) {
      fprintf(stderr, "structural_gen: out of memory\n");
      exit(1);
    }
    b->p = q;
    b->cap = cap;
  }
  memcpy(b->p + b->n, data, n);
  b->n += n;
}
static void puts_(buf_t *b, const char *s) { put(b, s, strlen(s)); }
static void rep(buf_t *b, const char *s, size_t times) {
  for (size_t i = 0; i < times; ++i) puts_(b, s);
}
static void putbyte(buf_t *b, unsigned v) {
  const unsigned char c = (unsigned char)v;
  put(b, &c, 1);
}

static const char *g_out;
static int g_count;

static void mkdir_p(const char *dir) {
  if (mkdir(dir, 0777) != 0 && errno != EEXIST) {
    fprintf(stderr, "structural_gen: cannot create %s: %s\n", dir, strerror(errno));
    exit(1);
  }
}

/* Writes b to <out>/<target>/<name> and empties b. */
static void emit(const char *target, const char *name, buf_t *b) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", g_out, target);
  mkdir_p(path);
  snprintf(path, sizeof path, "%s/%s/%s", g_out, target, name);
  FILE *f = fopen(path, "wb");
  if (f == NULL || (b->n > 0 && fwrite(b->p, 1, b->n, f) != b->n) || fclose(f) != 0) {
    fprintf(stderr, "structural_gen: cannot write %s\n", path);
    exit(1);
  }
  b->n = 0;
  ++g_count;
}

/* ---- fuzz_scenario: TOML text (NUL-separated --set strings after the first NUL) ------------ */

/* A minimal valid scenario to which a structural part is appended. */
static const char kBase[] = "[control]\ncase = \"IV\"\n[run]\nduration_s = 1.0\n";

/* Every scenario input is replayed: the deep nesting and 50,000-part keys, which crashed
   toml++ by recursion before the reader bounded nesting and dotted-key depth ahead of parsing
   (sil/scenario/toml_bounds.hpp), are refused with a clear error now. */
static void emit_scenario(const char *name, buf_t *b) { emit("fuzz_scenario", name, b); }

static void scenario_inputs(buf_t *b) {
  /* Nesting: arrays, inline tables and both mixed, shallow enough to pass and deep. */
  static const size_t depths[] = {100, 1000, 100000};
  char name[128];
  for (size_t d = 0; d < sizeof depths / sizeof depths[0]; ++d) {
    puts_(b, kBase);
    puts_(b, "x = ");
    rep(b, "[", depths[d]);
    rep(b, "]", depths[d]);
    puts_(b, "\n");
    snprintf(name, sizeof name, "deep_array_nesting_%zu", depths[d]);
    emit_scenario(name, b);
    puts_(b, kBase);
    puts_(b, "x = ");
    rep(b, "{a = ", depths[d]);
    puts_(b, "1");
    rep(b, "}", depths[d]);
    puts_(b, "\n");
    snprintf(name, sizeof name, "deep_inline_table_nesting_%zu", depths[d]);
    emit_scenario(name, b);
  }
  puts_(b, kBase);
  puts_(b, "x = ");
  rep(b, "[{a = ", 50000);
  puts_(b, "1");
  rep(b, "}]", 50000);
  puts_(b, "\n");
  emit_scenario("mixed_array_table_nesting_50000", b);

  /* Dotted keys: many parts (the 100 KB, 50,000-part key), in a key and a header;
     and one very long single part. */
  static const size_t parts[] = {100, 5000, 50000};
  for (size_t k = 0; k < sizeof parts / sizeof parts[0]; ++k) {
    puts_(b, kBase);
    rep(b, "a.", parts[k] - 1);
    puts_(b, "a = 1\n");
    snprintf(name, sizeof name, "dotted_key_%zu_parts", parts[k]);
    emit_scenario(name, b);
    puts_(b, kBase);
    puts_(b, "[");
    rep(b, "a.", parts[k] - 1);
    puts_(b, "a]\nx = 1\n");
    snprintf(name, sizeof name, "table_header_%zu_parts", parts[k]);
    emit_scenario(name, b);
  }
  puts_(b, kBase);
  rep(b, "k", 1000000);
  puts_(b, " = 1\n");
  emit_scenario("single_key_1000000_chars", b);
  puts_(b, kBase);
  puts_(b, "[run]\nname = \"");
  rep(b, "n", 1000000);
  puts_(b, "\"\n");
  emit_scenario("run_name_1000000_chars", b);

  /* Huge arrays and counts. */
  puts_(b, kBase);
  puts_(b, "x = [");
  rep(b, "0,", 200000);
  puts_(b, "0]\n");
  emit_scenario("array_200000_elements", b);
  puts_(b, "[control]\ncase = \"IV\"\n[run]\nduration_s = 1.0\n");
  rep(b, "[[faults.thruster]]\nthruster = 1\nmode = \"off\"\nstart_s = 0.5\n", 20000);
  emit_scenario("faults_thruster_20000_tables", b);
  puts_(b, kBase);
  rep(b, "[[faults.thruster]]\n", 100000);
  emit_scenario("faults_thruster_100000_empty_tables", b);
  puts_(b, kBase);
  puts_(b, "[[faults.thruster]]\nthruster = 9223372036854775807\nmode = \"off\"\n");
  puts_(b, "[[faults.thruster]]\nthruster = -9223372036854775808\nmode = \"off\"\n");
  emit_scenario("faults_thruster_index_int64_extremes", b);
  puts_(b, kBase);
  rep(b, "[[x]]\n", 100000);
  emit_scenario("array_of_tables_100000", b);

  /* Extreme numbers in real keys. */
  static const char *const reals[] = {
      "5e-324", "4.9e-324", "1e-320", "2.2250738585072014e-308", "1.7976931685134157e308",
      "1e308", "-1e308", "1e400", "-0.0", "nan", "+inf", "-inf", "0x7fffffffffffffff",
      "9223372036854775807", "-9223372036854775808", "99999999999999999999999",
  };
  static const char *const keys[] = {"run.tick_s", "run.duration_s", "trajectory.duration_s",
                                     "vehicle.payload_kg", "limits.thrust_limit_N"};
  for (size_t k = 0; k < sizeof keys / sizeof keys[0]; ++k) {
    for (size_t r = 0; r < sizeof reals / sizeof reals[0]; ++r) {
      puts_(b, "[control]\ncase = \"IV\"\n");
      const char *dot = strchr(keys[k], '.');
      puts_(b, "[");
      put(b, keys[k], (size_t)(dot - keys[k]));
      puts_(b, "]\n");
      puts_(b, dot + 1);
      puts_(b, " = ");
      puts_(b, reals[r]);
      puts_(b, "\n");
      snprintf(name, sizeof name, "extreme_%s_%zu", keys[k], r);
      for (char *c = name; *c; ++c)
        if (*c == '.') *c = '_';
      emit_scenario(name, b);
    }
  }
  puts_(b, kBase);
  puts_(b, "[trajectory]\nduration_s = 1.");
  rep(b, "0", 100000);
  puts_(b, "1\n");
  emit_scenario("real_with_100000_digits", b);

  /* Many --set overrides after the NUL. */
  puts_(b, kBase);
  putbyte(b, 0);
  for (int i = 0; i < 20000; ++i) {
    puts_(b, "run.tick_s=0.03");
    putbyte(b, 0);
  }
  emit_scenario("set_20000_overrides", b);
  puts_(b, kBase);
  putbyte(b, 0);
  rep(b, "a.", 49999);
  puts_(b, "a=1");
  emit_scenario("set_dotted_key_50000_parts", b);
}

/* ---- fuzz_ctrl_step: byte 0 then raw uvms_ctrl_sensors_t records ------------------------- */

static void ctrl_step_inputs(buf_t *b) {
  const uvms_real_t extremes[] = {
      (uvms_real_t)NAN,      (uvms_real_t)INFINITY,  -(uvms_real_t)INFINITY,
      (uvms_real_t)(sizeof(uvms_real_t) == 4 ? FLT_MAX : DBL_MAX),
      -(uvms_real_t)(sizeof(uvms_real_t) == 4 ? FLT_MAX : DBL_MAX),
      (uvms_real_t)(sizeof(uvms_real_t) == 4 ? FLT_TRUE_MIN : DBL_TRUE_MIN),
      (uvms_real_t)(sizeof(uvms_real_t) == 4 ? FLT_MIN : DBL_MIN), (uvms_real_t)-0.0,
      (uvms_real_t)1e30,
  };
  const size_t nx = sizeof extremes / sizeof extremes[0];
  const int64_t ticks[] = {INT64_MAX, INT64_MIN, 0, -1, INT64_MAX - 1, 1};
  char name[128];
  /* Every configuration byte (case × trajectory × sequence/reset bits) with records whose
     every real is one extreme value, ticks at the integer range's ends, masks all/none. */
  for (unsigned cfgb = 0; cfgb < 128; cfgb += 5) {
    for (size_t x = 0; x < nx; ++x) {
      putbyte(b, cfgb);
      for (int r = 0; r < 16; ++r) {
        uvms_ctrl_sensors_t s;
        memset(&s, 0, sizeof s);
        s.tick = ticks[(size_t)r % (sizeof ticks / sizeof ticks[0])];
        s.time_s = (r & 1) ? extremes[x] : (uvms_real_t)(0.03 * r);
        s.quaternion_wxyz[0] = (r & 2) ? extremes[x] : (uvms_real_t)1;
        for (int i = 0; i < 3; ++i) {
          s.position_m[i] = extremes[x];
          s.velocity_m_s[i] = (r & 4) ? extremes[x] : (uvms_real_t)0;
          s.angular_velocity_rad_s[i] = (r & 8) ? extremes[x] : (uvms_real_t)0;
        }
        for (int j = 0; j < UVMS_MAX_JOINTS; ++j) {
          s.joint_position_rad[j] = (r & 1) ? extremes[x] : (uvms_real_t)0;
          s.joint_velocity_rad_s[j] = extremes[x];
        }
        for (int j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
          s.motor_speed_rad_s[j] = extremes[x];
          s.motor_current_A[j] = (r & 2) ? extremes[x] : (uvms_real_t)0;
        }
        s.thruster_usable_mask = (r & 1) ? 0xFFFFFFFFu : (uint32_t)(0xFFu >> (r & 7));
        put(b, &s, sizeof s);
      }
      snprintf(name, sizeof name, "extreme_records_cfg%u_value%zu", cfgb, x);
      emit("fuzz_ctrl_step", name, b);
    }
  }
  /* Time jumps and tick gaps in record mode (bit 5 clear): a plausible run whose clock jumps
     forward and back and whose ticks skip, so the TIME_IMPLAUSIBLE and hold paths run. */
  for (unsigned c = 0; c < 8; ++c) {
    putbyte(b, c);
    for (int r = 0; r < 16; ++r) {
      uvms_ctrl_sensors_t s;
      memset(&s, 0, sizeof s);
      s.tick = r + ((r > 8) ? 1000 : 0);
      s.time_s = (uvms_real_t)(0.03 * s.tick + ((r % 3 == 1) ? 5.0 : (r % 3 == 2) ? -5.0 : 0));
      s.quaternion_wxyz[0] = 1;
      s.thruster_usable_mask = 0xFF;
      put(b, &s, sizeof s);
    }
    snprintf(name, sizeof name, "time_jumps_case%u", c + 1);
    emit("fuzz_ctrl_step", name, b);
  }
}

/* ---- fuzz_ctrl_node: (channel, length, bytes) records ----------------------------------- */

static void ctrl_node_inputs(buf_t *b) {
  /* A valid configuration, then the most records of the longest length, sealed or not. */
  for (unsigned fill = 0; fill < 4; ++fill) {
    static const unsigned char fills[] = {0x00, 0xFF, 0x7F, 0x80};
    putbyte(b, 3);
    putbyte(b, 3);
    for (int r = 0; r < 64; ++r) {
      putbyte(b, (r & 1) ? 0x81u : 0x01u); /* sensors, sealed on odd records */
      putbyte(b, 0xFF);
      putbyte(b, 0xFF);
      for (int i = 0; i < 0xFFFF / 64; ++i) putbyte(b, fills[fill]);
    }
    char name[64];
    snprintf(name, sizeof name, "long_sensors_records_fill%02x", fills[fill]);
    emit("fuzz_ctrl_node", name, b);
  }
  /* Many configurations and status messages. */
  for (int r = 0; r < 5000; ++r) {
    putbyte(b, 3);
    putbyte(b, (unsigned)r);
    putbyte(b, 0x82);
    putbyte(b, 0);
    putbyte(b, 16);
    rep(b, "\xff", 16);
  }
  emit("fuzz_ctrl_node", "configs_and_status_5000", b);
}

/* ---- fuzz_lcm_decode: type byte, message ------------------------------------------------ */

static void lcm_decode_inputs(buf_t *b) {
  /* Every type, sealed and not, the fingerprint followed by bytes that read as the largest,
     the most negative and other extreme counts and lengths. */
  static const unsigned char fills[] = {0x7F, 0xFF, 0x80, 0x00};
  for (unsigned t = 0; t < 5; ++t) {
    for (unsigned seal = 0; seal < 2; ++seal) {
      for (size_t f = 0; f < sizeof fills; ++f) {
        putbyte(b, t | (seal << 7));
        for (int i = 0; i < 65536; ++i) putbyte(b, fills[f]);
        char name[64];
        snprintf(name, sizeof name, "type%u_seal%u_fill%02x_64k", t, seal, fills[f]);
        emit("fuzz_lcm_decode", name, b);
      }
    }
  }
}

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: structural_gen <out dir>\n");
    return 2;
  }
  g_out = argv[1];
  mkdir_p(g_out);
  buf_t b = {0};
  scenario_inputs(&b);
  ctrl_step_inputs(&b);
  ctrl_node_inputs(&b);
  lcm_decode_inputs(&b);
  free(b.p);
  printf("structural_gen: %d inputs in %s\n", g_count, g_out);
  return 0;
}
