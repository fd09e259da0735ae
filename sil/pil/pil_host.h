/* SPDX-License-Identifier: Apache-2.0 */
/*
 * pil_host.h: the host end of the processor-in-the-loop link (C, POSIX, LCM types).
 *
 *  - Mappings LCM message -> PIL record (rounding each double to float exactly as sil/msg/codec.c
 *    does in the float build) and PIL output record -> the firmware's command/telemetry types.
 *  - The link: creates three FIFOs in a private temporary directory, starts QEMU mps2-an386
 *    (-icount shift=0) on the PIL image (sil/pil/target/pil_m4f.c), optionally with the
 *    instruction-counting plugin (bench/qemu_icount_plugin.c, live=FIFO), and runs the
 *    lockstep request/answer protocol of pil_protocol.h with retransmission.
 */
#ifndef UVMS_PIL_HOST_H
#define UVMS_PIL_HOST_H

#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>

#include "pil/pil_protocol.h"
#include "uvms/controller.h"
#include "uvms_controller_config_t.h"
#include "uvms_sensors_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- mappings ---- */

/** controller_config_t -> config record: (float) of every real, int8 widened. */
void pil_config_rec_from_msg(const uvms_controller_config_t *msg, pil_config_rec_t *rec);
/** sensors_t -> sensors record: as uvms_sensors_from_msg in the float build
 *  (time_s = (float)(utime · 1e-6), computed in double). */
void pil_sensors_rec_from_msg(const uvms_sensors_t *msg, pil_sensors_rec_t *rec);
/** Output record -> the host's command and telemetry (uvms_real_t; float -> double is exact). */
void pil_output_from_rec(const pil_output_rec_t *rec, uvms_ctrl_command_t *cmd,
                         uvms_ctrl_telemetry_t *tlm);

/* ---- the link ---- */

typedef struct {
  const char *qemu;          /* qemu-system-arm executable (PATH lookup if no '/') */
  const char *elf;           /* the PIL image */
  const char *plugin;        /* libqemu_icount_plugin.so, or NULL: no instruction counts */
  double reply_timeout_s;    /* wait for one answer before retransmitting [s] */
  int max_attempts;          /* sends of one request before giving up */
  double start_timeout_s;    /* wait for QEMU to open the link and say HELLO [s] */
} pil_link_options_t;

typedef struct {
  pid_t qemu_pid;            /* -1 when not running */
  int to_fd, from_fd, icount_fd;
  char dir[256];             /* private directory holding the FIFOs */
  char in_path[300], out_path[300], icount_path[300];
  pil_rx_t rx;
  pil_frame_t frame;
  uint32_t seq;              /* last sequence number sent */
  pil_link_options_t opt;
  /* counters */
  uint32_t retransmits;      /* requests sent again (timeout or NAK) */
  uint32_t naks;             /* NAK frames received */
  uint32_t stale_frames;     /* valid frames that were not the pending answer (desync) */
  uint32_t icount_missing;   /* steps without an instruction count */
} pil_link_t;

/** Sets the defaults (reply 2 s, 3 attempts, start 20 s; qemu-system-arm; no ELF, no plugin). */
void pil_link_options_default(pil_link_options_t *opt);

/**
 * @brief Create the FIFOs, start QEMU on opt->elf and wait for the image's HELLO.
 * @return 0, or -1 with a message in err (the link is then stopped and cleaned up).
 */
int pil_link_start(pil_link_t *link, const pil_link_options_t *opt, char *err, size_t err_cap);

/** CONFIG -> CONFIG_ACK. 0, or -1 if no answer came (err says why). */
int pil_link_config(pil_link_t *link, const pil_config_rec_t *rec, pil_config_ack_rec_t *ack,
                    char *err, size_t err_cap);

/** SENSORS -> OUTPUT, and the step's instruction count (0 without the plugin).
 *  0, or -1 if no answer came (err says why). */
int pil_link_step(pil_link_t *link, const pil_sensors_rec_t *rec, pil_output_rec_t *out,
                  int64_t *instructions, char *err, size_t err_cap);

/** QUIT, wait for QEMU (then SIGTERM), close and remove the FIFOs. Returns QEMU's exit code
 *  (0 after a clean QUIT), or -1 if it had to be killed. Safe on a stopped link. */
int pil_link_stop(pil_link_t *link);

/** Address of a function symbol in an ELF32 file (Thumb bit cleared); 0 if not found. */
uint32_t pil_elf_symbol(const char *elf_path, const char *name);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_PIL_HOST_H */
