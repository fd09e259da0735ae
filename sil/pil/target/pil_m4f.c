/* SPDX-License-Identifier: Apache-2.0 */
/*
 * pil_m4f.c: processor-in-the-loop image for QEMU mps2-an386 (Cortex-M4F, float firmware).
 * The host bridge (sil/pil/pil_bridge_main.c, `uvms-controller-pil`) starts it as
 *
 *   qemu-system-arm -M mps2-an386 ... -semihosting-config enable=on,target=native \
 *     -icount shift=0 -kernel uvms_pil_m4f.elf -append "in=HOST_FIFO out=HOST_FIFO"
 *
 * and exchanges sil/pil/pil_protocol.h frames with it over the two FIFOs (semihosting
 * SYS_OPEN/READ/WRITE): CONFIG -> uvms_ctrl_init -> CONFIG_ACK, SENSORS -> uvms_ctrl_step ->
 * OUTPUT, QUIT -> exit 0. The firmware library is linked unmodified.
 *
 * Instruction counts: every uvms_ctrl_step is bracketed by pil_mark_begin() and
 * pil_mark_end() (one `bx lr` each); bench/qemu_icount_plugin.c, loaded by the bridge
 * with `live=FIFO`, counts the instructions between them exactly and writes each tick's count
 * to the bridge as soon as the end marker runs, i.e. before this image sends its OUTPUT.
 *
 * Everything in static storage: no allocation (semihosting stdio is not used; the startup's
 * initialise_monitor_handles() only sets up newlib's handles). Exit codes: 0 after QUIT, 1 the
 * host closed the link (EOF) or an I/O error, 2 bad command line, 97 a fault (startup_m4f.c).
 */
#include <stdint.h>
#include <string.h>

#include "pil/pil_map.h"
#include "pil/pil_protocol.h"
#include "uvms/controller.h"
#include "uvms_m4f/marker.h"

_Static_assert(UVMS_REAL_IS_FLOAT, "the PIL image runs the float firmware");

/* ---- markers (uvms_m4f/marker.h): begin/end bracket each step ------------------------------ */
UVMS_M4F_MARKER(pil_mark_begin, "uvms pil: step begin")
UVMS_M4F_MARKER(pil_mark_end, "uvms pil: step end")

/* ---- semihosting (ARM semihosting v2 calls through BKPT 0xAB) -------------------------------- */
#define SYS_OPEN 0x01
#define SYS_WRITE 0x05
#define SYS_READ 0x06
#define SYS_GET_CMDLINE 0x15
#define SH_MODE_RB 1 /* "rb" */
#define SH_MODE_WB 5 /* "wb" */

static int semihost(int op, void *block) {
  register int r0 __asm("r0") = op;
  register void *r1 __asm("r1") = block;
  __asm volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

static int sh_open(const char *path, int mode) {
  uint32_t block[3] = {(uint32_t)(uintptr_t)path, (uint32_t)mode, (uint32_t)strlen(path)};
  return semihost(SYS_OPEN, block);
}

/** Bytes actually read (0 = end of file or error). Reads what the FIFO holds, at least 1. */
static uint32_t sh_read(int fd, uint8_t *buf, uint32_t len) {
  uint32_t block[3] = {(uint32_t)fd, (uint32_t)(uintptr_t)buf, len};
  const int not_read = semihost(SYS_READ, block);
  if (not_read < 0 || (uint32_t)not_read > len) return 0u;
  return len - (uint32_t)not_read;
}

/** 0 when all len bytes were written. */
static int sh_write_all(int fd, const uint8_t *buf, uint32_t len) {
  /* A FIFO write either completes or fails (host side blocking write); bounded retries for a
     partial one. */
  for (int attempt = 0; attempt < 64 && len > 0u; ++attempt) {
    uint32_t block[3] = {(uint32_t)fd, (uint32_t)(uintptr_t)buf, len};
    const int not_written = semihost(SYS_WRITE, block);
    if (not_written < 0 || (uint32_t)not_written > len) return -1;
    buf += len - (uint32_t)not_written;
    len = (uint32_t)not_written;
  }
  return len == 0u ? 0 : -1;
}

/** Copies the value of "key=VALUE" (up to a space) from cmd into out; 0 if found. */
static int cmdline_value(const char *cmd, const char *key, char *out, size_t cap) {
  const size_t key_len = strlen(key);
  for (size_t i = 0; cmd[i] != '\0' && i < 1024u; ++i) {
    const int at_token = (i == 0u || cmd[i - 1u] == ' ');
    if (at_token && strncmp(cmd + i, key, key_len) == 0 && cmd[i + key_len] == '=') {
      const char *v = cmd + i + key_len + 1u;
      size_t n = 0;
      while (v[n] != '\0' && v[n] != ' ' && n + 1u < cap) {
        out[n] = v[n];
        ++n;
      }
      out[n] = '\0';
      return n > 0u ? 0 : -1;
    }
  }
  return -1;
}

/* ---- the controller and the link, in static storage ------------------------------------------ */
static uvms_ctrl_t g_ctrl;
static uvms_ctrl_config_t g_cfg;
static uvms_ctrl_sensors_t g_sensors;
static uvms_ctrl_command_t g_cmd;
static uvms_ctrl_telemetry_t g_tlm;
static pil_rx_t g_rx;
static pil_frame_t g_frame;
static pil_output_rec_t g_out_rec;
static uint8_t g_in_chunk[512];
static uint8_t g_reply[PIL_MAX_FRAME]; /* the last answer, kept for retransmissions */
static size_t g_reply_len;
static uint32_t g_reply_seq;
static int g_have_reply;
static char g_cmdline[512];
static char g_in_path[200], g_out_path[200];
static int g_out_fd = -1;

static int send_frame(pil_frame_type_t type, uint32_t seq, const void *payload, size_t len,
                      int keep) {
  static uint8_t scratch[PIL_MAX_FRAME];
  uint8_t *const buf = keep ? g_reply : scratch;
  const size_t n = pil_frame_encode((uint8_t)type, seq, payload, len, buf, PIL_MAX_FRAME);
  if (n == 0u) return -1;
  if (keep) {
    g_reply_len = n;
    g_reply_seq = seq;
    g_have_reply = 1;
  }
  return sh_write_all(g_out_fd, buf, (uint32_t)n);
}

static int send_nak(uint32_t seq) {
  const pil_nak_rec_t nak = {g_rx.header_errors, g_rx.crc_errors, g_rx.bytes_dropped};
  return send_frame(PIL_NAK, seq, &nak, sizeof nak, 0);
}

/** Handles one valid frame; returns 1 to quit, -1 on an I/O error, 0 otherwise. */
static int handle(const pil_frame_t *f) {
  if (g_have_reply && f->seq == g_reply_seq) {
    /* A retransmission of the request already answered: the same answer, no second step. */
    return sh_write_all(g_out_fd, g_reply, (uint32_t)g_reply_len) == 0 ? 0 : -1;
  }
  switch (f->type) {
    case PIL_CONFIG: {
      if (f->len != sizeof(pil_config_rec_t)) return send_nak(f->seq) == 0 ? 0 : -1;
      pil_config_rec_t rec;
      memcpy(&rec, f->payload, sizeof rec);
      pil_config_ack_rec_t ack = {(int32_t)UVMS_ERR_RANGE, 0};
      /* g_ctrl points to g_cfg (uvms_ctrl_init): not ready before g_cfg is rewritten; stays so,
         with no field, if the mapping fails (as sil/link/controller_node.c). */
      memset(&g_ctrl, 0, sizeof g_ctrl);
      if (pil_config_from_rec(&rec, &g_cfg) == 0)
        ack.status = (int32_t)uvms_ctrl_init(&g_ctrl, &g_cfg);
      ack.config_error = (int32_t)g_ctrl.config_error;
      return send_frame(PIL_CONFIG_ACK, f->seq, &ack, sizeof ack, 1) == 0 ? 0 : -1;
    }
    case PIL_SENSORS: {
      if (f->len != sizeof(pil_sensors_rec_t)) return send_nak(f->seq) == 0 ? 0 : -1;
      pil_sensors_rec_t rec;
      memcpy(&rec, f->payload, sizeof rec);
      pil_sensors_from_rec(&rec, &g_sensors);
      memset(&g_cmd, 0, sizeof g_cmd);
      memset(&g_tlm, 0, sizeof g_tlm);
      pil_mark_begin();
      const uvms_status_t st = uvms_ctrl_step(&g_ctrl, &g_sensors, &g_cmd, &g_tlm);
      pil_mark_end();
      pil_output_to_rec(rec.tick, (int32_t)st, &g_cmd, &g_tlm, &g_out_rec);
      return send_frame(PIL_OUTPUT, f->seq, &g_out_rec, sizeof g_out_rec, 1) == 0 ? 0 : -1;
    }
    case PIL_QUIT:
      return 1;
    default: /* a target -> host type: the host never sends it */
      return send_nak(f->seq) == 0 ? 0 : -1;
  }
}

int main(void) {
  uint32_t cmd_block[2] = {(uint32_t)(uintptr_t)g_cmdline, (uint32_t)sizeof g_cmdline};
  if (semihost(SYS_GET_CMDLINE, cmd_block) != 0 ||
      cmdline_value(g_cmdline, "in", g_in_path, sizeof g_in_path) != 0 ||
      cmdline_value(g_cmdline, "out", g_out_path, sizeof g_out_path) != 0) {
    return 2;
  }
  /* Open order fixed (in, then out): the bridge opens its ends in the same order. */
  const int in_fd = sh_open(g_in_path, SH_MODE_RB);
  if (in_fd < 0) return 1;
  g_out_fd = sh_open(g_out_path, SH_MODE_WB);
  if (g_out_fd < 0) return 1;
  pil_rx_init(&g_rx);

  const pil_hello_rec_t hello = {PIL_PROTOCOL_VERSION, (uint32_t)sizeof(pil_config_rec_t),
                                 (uint32_t)sizeof(pil_sensors_rec_t),
                                 (uint32_t)sizeof(pil_output_rec_t), PIL_MAX_PAYLOAD};
  if (send_frame(PIL_HELLO, 0u, &hello, sizeof hello, 0) != 0) return 1;

  /* Runs until QUIT or the host closes the link: the host bounds the run, not this loop. */
  for (;;) {
    const uint32_t n = sh_read(in_fd, g_in_chunk, (uint32_t)sizeof g_in_chunk);
    if (n == 0u) return 1;
    const uint32_t errors_before = pil_rx_errors(&g_rx);
    for (uint32_t i = 0; i < n; ++i) {
      int got = pil_rx_feed(&g_rx, g_in_chunk[i], &g_frame);
      /* pil_rx_next drains frames already buffered; bounded by the buffer's size. */
      for (uint32_t k = 0; got && k < PIL_MAX_FRAME; ++k) {
        const int r = handle(&g_frame);
        if (r != 0) return r > 0 ? 0 : 1;
        got = pil_rx_next(&g_rx, &g_frame);
      }
    }
    if (pil_rx_errors(&g_rx) != errors_before && send_nak(g_have_reply ? g_reply_seq : 0u) != 0)
      return 1;
  }
}
