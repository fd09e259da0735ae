/* SPDX-License-Identifier: Apache-2.0 */
/*
 * lcm_roundtrip.c: what the lockstep link costs with nothing to compute. Two processes on a
 * private LCM udpm link play the two ends of a SIL tick: the "plant" publishes a sensors-sized
 * message (384 B) and waits for an actuators-sized answer (292 B); the "controller" answers
 * each one with that and a telemetry-sized message (1092 B), as sil/link/controller_node.h
 * publishes; the plant takes the telemetry too before the next round. Both ends wait as the
 * SIL nodes do (sil/link/lcm_wait.h: busy-poll for spin_us, then block). The message sizes are
 * those of a case VII log.
 *
 * Two layouts, measured one after the other:
 *  - shared: both directions on one URL (`uvms run --url`). Every datagram also reaches its
 *    sender's own receive socket, so each process's LCM receive thread wakes for what it sent;
 *  - split: each direction on a port of its own (`uvms run`'s private link): each process
 *    listens on one URL and publishes on the other through an LCM instance it never subscribes
 *    on, which LCM gives no receive socket.
 *
 * Prints the wall time per round (median and quartiles) after a warm-up: the floor under the
 * "link cost per tick" of bench/sil_bench.sh, which runs this after its SIL runs.
 *
 * Usage: bench_lcm_roundtrip [ROUNDS [SPIN_US]]   (defaults 2000 rounds, 2000 us)
 */
#define _POSIX_C_SOURCE 200809L
#include <lcm/lcm.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "link/lcm_wait.h"

enum { kSensorsBytes = 384, kActuatorsBytes = 292, kTelemetryBytes = 1092, kWarmup = 200 };
enum { kMaxRounds = 1000000, kTimeoutMs = 2000 };

static const char kUsage[] =
    "usage: bench_lcm_roundtrip [ROUNDS [SPIN_US]]\n"
    "  The lockstep link's cost with nothing to compute: two processes on a private LCM udpm\n"
    "  link exchange a sensors-sized message (384 B) for an actuators-sized (292 B) and a\n"
    "  telemetry-sized (1092 B) one, waiting as the SIL nodes do (busy-poll SPIN_US, then\n"
    "  block); both directions on one URL (shared, as `uvms run --url`), then each on a port of\n"
    "  its own (split, as `uvms run`'s private link). Prints the wall time per round of each:\n"
    "  median and quartiles, after 200 warm-up rounds.\n"
    "  ROUNDS: 1..1000000 (default 2000); SPIN_US: as link.spin_us (default 2000).\n";

static long long now_ns(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (long long)ts.tv_sec * 1000000000LL + (long long)ts.tv_nsec;
}

/* ---- the controller's end: answer every sensors message ---- */

struct Echo {
  lcm_t *lcm;
  unsigned char actuators[kActuatorsBytes], telemetry[kTelemetryBytes];
  int stop;
};

static void on_sensors(const lcm_recv_buf_t *rbuf, const char *channel, void *user) {
  (void)channel;
  struct Echo *e = user;
  if (rbuf->data_size == 1) { /* the plant's end-of-run byte */
    e->stop = 1;
    return;
  }
  if (rbuf->data_size >= sizeof(int)) /* the round's number goes back with both answers */
    memcpy(e->actuators, rbuf->data, sizeof(int));
  memcpy(e->telemetry, e->actuators, sizeof(int));
  lcm_publish(e->lcm, "RT_ACTUATORS", e->actuators, sizeof e->actuators);
  lcm_publish(e->lcm, "RT_TELEMETRY", e->telemetry, sizeof e->telemetry);
}

/* Listens on rx_url, answers on tx_url (the same URL: one instance). */
static int run_echo(const char *rx_url, const char *tx_url, int spin_us) {
  struct Echo e;
  memset(&e, 0, sizeof e);
  lcm_t *rx = lcm_create(rx_url);
  if (rx == NULL) return 1;
  e.lcm = strcmp(rx_url, tx_url) == 0 ? rx : lcm_create(tx_url);
  if (e.lcm == NULL) {
    lcm_destroy(rx);
    return 1;
  }
  lcm_subscribe(rx, "RT_SENSORS", on_sensors, &e);
  /* Bounded: the plant ends with a stop byte, or goes silent (then the wait times out). */
  while (!e.stop && uvms_lcm_wait(rx, kTimeoutMs, spin_us) > 0) {
  }
  if (e.lcm != rx) lcm_destroy(e.lcm);
  lcm_destroy(rx);
  return 0;
}

/* ---- the plant's end: send, await the answer, take the telemetry ---- */

/* The number of the last round answered, per channel (-1: none yet). An answer to a re-sent
   start-up probe that comes late carries an old number, so it cannot pass for a round's. */
struct Plant {
  int actuators, telemetry;
};

static void on_answer(const lcm_recv_buf_t *rbuf, const char *channel, void *user) {
  struct Plant *p = user;
  int round = -1;
  if (rbuf->data_size >= sizeof round) memcpy(&round, rbuf->data, sizeof round);
  if (strcmp(channel, "RT_ACTUATORS") == 0) p->actuators = round;
  else p->telemetry = round;
}

static int cmp_ll(const void *a, const void *b) {
  const long long x = *(const long long *)a, y = *(const long long *)b;
  return (x > y) - (x < y);
}

/* Waits until *last is round; 0 when it is, -1 on a timeout or an error. */
static int await_round(lcm_t *lcm, const int *last, int round, int spin_us) {
  while (*last != round)
    if (uvms_lcm_wait(lcm, kTimeoutMs, spin_us) <= 0) return -1;
  return 0;
}

/* Listens on rx_url, publishes on tx_url (the same URL: one instance). */
/* Returns 0, or -1 with *failed_round the round that got no answer (0: the start-up probe). */
static int run_plant(const char *rx_url, const char *tx_url, int rounds, int spin_us,
                     long long *round_ns, int *failed_round) {
  *failed_round = 0;
  lcm_t *lcm = lcm_create(rx_url);
  if (lcm == NULL) return -1;
  lcm_t *out = strcmp(rx_url, tx_url) == 0 ? lcm : lcm_create(tx_url);
  if (out == NULL) {
    lcm_destroy(lcm);
    return -1;
  }
  struct Plant p = {-1, -1};
  lcm_subscribe(lcm, "RT_ACTUATORS", on_answer, &p);
  lcm_subscribe(lcm, "RT_TELEMETRY", on_answer, &p);
  unsigned char sensors[kSensorsBytes];
  memset(sensors, 0, sizeof sensors);
  /* The controller may not be listening yet: the first message (round 0) is re-sent until
     answered; the rounds then count from 1. */
  /* An answer, not just any message handled: LCM's own self-test message can come first. */
  for (int i = 0; i < 100 && p.actuators != 0; ++i) {
    lcm_publish(out, "RT_SENSORS", sensors, sizeof sensors);
    const long long until = now_ns() + 50000000LL;  /* 50 ms per probe */
    while (p.actuators != 0 && now_ns() < until)
      if (uvms_lcm_wait(lcm, 50, spin_us) < 0) break;
  }
  int st = p.actuators == 0 ? 0 : -1;
  if (st == 0) st = await_round(lcm, &p.telemetry, 0, spin_us);
  for (int i = 0; st == 0 && i < kWarmup + rounds; ++i) {
    const int round = i + 1;
    *failed_round = round;
    memcpy(sensors, &round, sizeof round);
    const long long t0 = now_ns();
    lcm_publish(out, "RT_SENSORS", sensors, sizeof sensors);
    st = await_round(lcm, &p.actuators, round, spin_us);
    const long long t1 = now_ns();
    if (st == 0) st = await_round(lcm, &p.telemetry, round, spin_us);
    if (i >= kWarmup) round_ns[i - kWarmup] = t1 - t0;
  }
  const unsigned char stop = 0;
  lcm_publish(out, "RT_SENSORS", &stop, 1);
  if (out != lcm) lcm_destroy(out);
  lcm_destroy(lcm);
  return st;
}

/* A udpm URL on a group derived from this process and port. */
static void private_url(char *url, size_t size, unsigned port) {
  const unsigned pid = (unsigned)getpid();
  snprintf(url, size, "udpm://239.255.%u.%u:%u?ttl=0", (pid >> 8) & 0xFFu,
           (pid & 0xFFu) ? (pid & 0xFFu) : 1u, port);
}

/* One layout: the plant listens on a and publishes on b (a == b: shared). Prints its line;
   returns 0, or 1 when the controller's end did not answer. */
static int measure(const char *layout, const char *a, const char *b, int rounds, int spin_us,
                   long long *round_ns) {
  const pid_t child = fork();
  if (child < 0) {
    perror("bench_lcm_roundtrip: fork");
    return 1;
  }
  if (child == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    _exit(run_echo(b, a, spin_us));
  }
  int failed_round = 0;
  const int st = run_plant(a, b, rounds, spin_us, round_ns, &failed_round);
  int status = 0;
  waitpid(child, &status, 0);
  if (st != 0) {
    fprintf(stderr,
            "bench_lcm_roundtrip: %s: no answer to round %d of %d (0: the start-up probe) within "
            "%d ms on %s; the controller's end exited with status %d\n",
            layout, failed_round, kWarmup + rounds, kTimeoutMs, b,
            WIFEXITED(status) ? WEXITSTATUS(status) : -1);
    return 1;
  }
  qsort(round_ns, (size_t)rounds, sizeof *round_ns, cmp_ll);
  printf("LCM udpm round trip, %s (%d B -> %d B + %d B, spin %d us), %d rounds: median %.1f us "
         "(quartiles %.1f-%.1f us)\n",
         layout, kSensorsBytes, kActuatorsBytes, kTelemetryBytes, spin_us, rounds,
         round_ns[rounds / 2] / 1e3, round_ns[rounds / 4] / 1e3, round_ns[3 * rounds / 4] / 1e3);
  fflush(stdout);
  return 0;
}

int main(int argc, char **argv) {
  if (argc > 1 && (strcmp(argv[1], "-h") == 0 || strcmp(argv[1], "--help") == 0)) {
    fputs(kUsage, stdout);
    return 0;
  }
  const int rounds = argc > 1 ? atoi(argv[1]) : 2000;
  int spin_us = 2000;
  if (argc > 3 || rounds < 1 || rounds > kMaxRounds ||
      (argc > 2 && !uvms_parse_spin_us(argv[2], &spin_us))) {
    fputs(kUsage, stderr);
    return 2;
  }
  char a[64], b[64];
  const unsigned port = 20000u + (unsigned)getpid() % 40000u;
  private_url(a, sizeof a, port);
  private_url(b, sizeof b, port + 1u);
  long long *round_ns = calloc((size_t)rounds, sizeof *round_ns);
  if (round_ns == NULL) return 1;
  int rc = measure("shared: one URL both ways", a, a, rounds, spin_us, round_ns);
  if (rc == 0) rc = measure("split: a port per direction", a, b, rounds, spin_us, round_ns);
  free(round_ns);
  return rc;
}
