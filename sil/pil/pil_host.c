/* SPDX-License-Identifier: Apache-2.0 */
/* pil_host.c: host end of the PIL link (pil_host.h). */
#define _GNU_SOURCE /* mkdtemp, O_CLOEXEC, pipe2 */
#include "pil/pil_host.h"

#include <elf.h>
#include <errno.h>
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

/* ---- mappings ------------------------------------------------------------------------------ */

static void f64_to_f32(float *dst, const double *src, size_t n) {
  for (size_t i = 0; i < n; ++i) dst[i] = (float)src[i];
}

void pil_config_rec_from_msg(const uvms_controller_config_t *m, pil_config_rec_t *r) {
  memset(r, 0, sizeof *r);
#define PIL_FILL_REAL_(name, dims)                                               \
  f64_to_f32((float *)(void *)&r->name, (const double *)(const void *)&m->name, \
             sizeof r->name / sizeof(float));
#define PIL_FILL_INT_(name) r->name = (int32_t)m->name;
#define PIL_FILL_FIELD_(map, shape, fw, lcm, ...) \
  UVMS_CFG_WIRE_##map(PIL_FILL_REAL_, PIL_FILL_INT_, shape, lcm)
  UVMS_CONFIG_TABLE(PIL_FILL_FIELD_)
#undef PIL_FILL_FIELD_
#undef PIL_FILL_REAL_
#undef PIL_FILL_INT_
}

void pil_sensors_rec_from_msg(const uvms_sensors_t *m, pil_sensors_rec_t *r) {
  memset(r, 0, sizeof *r);
  r->tick = m->tick;
  r->time_s = (float)((double)m->utime * 1e-6);
#define PIL_SENSOR_FILL_(name, dims, unit, doc)                                          \
  f64_to_f32((float *)(void *)&r->name, (const double *)(const void *)&m->name,          \
             sizeof r->name / sizeof(float));
  UVMS_SENSOR_FIELDS(PIL_SENSOR_FILL_)
#undef PIL_SENSOR_FILL_
  r->thruster_usable_mask = (uint32_t)m->thruster_usable_mask;
}

static void f32_to_real(uvms_real_t *dst, const float *src, size_t n) {
  for (size_t i = 0; i < n; ++i) dst[i] = (uvms_real_t)src[i];
}

void pil_output_from_rec(const pil_output_rec_t *r, uvms_ctrl_command_t *cmd,
                         uvms_ctrl_telemetry_t *tlm) {
  memset(cmd, 0, sizeof *cmd);
  memset(tlm, 0, sizeof *tlm);
  tlm->tick = r->tick;
  tlm->status = r->status;
  tlm->flags = r->flags;
#define PIL_CMD_(name, dims, unit, doc) \
  f32_to_real((uvms_real_t *)&cmd->name, (const float *)&r->name, sizeof r->name / sizeof(float));
#define PIL_TLM_(name, dims, unit, doc) \
  f32_to_real((uvms_real_t *)&tlm->name, (const float *)&r->name, sizeof r->name / sizeof(float));
#define PIL_INT_(type, name, doc) tlm->name = r->name;
  PIL_COMMAND_FIELDS(PIL_CMD_)
  PIL_TELEMETRY_FIELDS(PIL_TLM_)
  PIL_TELEMETRY_INTS(PIL_INT_)
#undef PIL_CMD_
#undef PIL_TLM_
#undef PIL_INT_
}

/* ---- helpers ------------------------------------------------------------------------------- */

static double now_s(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static void set_err(char *err, size_t cap, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void set_err(char *err, size_t cap, const char *fmt, ...) {
  if (err == NULL || cap == 0) return;
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(err, cap, fmt, ap);
  va_end(ap);
}

/** 1 while QEMU runs; 0 after it exited (reaped; *status gets its exit code or 128+signal). */
static int qemu_alive(pil_link_t *l, int *status) {
  if (l->qemu_pid <= 0) return 0;
  int st = 0;
  const pid_t r = waitpid(l->qemu_pid, &st, WNOHANG);
  if (r == 0) return 1;
  if (status != NULL)
    *status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
  l->qemu_pid = -1;
  return 0;
}

static int write_all(int fd, const uint8_t *p, size_t n) {
  while (n > 0) {
    const ssize_t w = write(fd, p, n);
    if (w < 0) {
      if (errno == EINTR) continue;
      return -1;
    }
    p += w;
    n -= (size_t)w;
  }
  return 0;
}

/* Waits up to timeout_s for a valid frame. 1: *frame filled; 0: timeout; -1: link closed. */
static int recv_frame(pil_link_t *l, double timeout_s) {
  if (pil_rx_next(&l->rx, &l->frame)) return 1; /* already buffered */
  const double deadline = now_s() + timeout_s;
  for (;;) {
    const double left = deadline - now_s();
    if (left <= 0) return 0;
    struct pollfd p = {l->from_fd, POLLIN, 0};
    const int ms = left > 0.1 ? 100 : (int)(left * 1e3) + 1;
    const int pr = poll(&p, 1, ms);
    if (pr < 0 && errno != EINTR) return -1;
    if (pr <= 0) {
      if (!qemu_alive(l, NULL)) return -1;
      continue;
    }
    uint8_t buf[4096];
    const ssize_t n = read(l->from_fd, buf, sizeof buf);
    if (n == 0) return -1; /* every writer closed: QEMU is gone */
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      return -1;
    }
    for (ssize_t i = 0; i < n; ++i) {
      if (pil_rx_feed(&l->rx, buf[i], &l->frame)) {
        /* Keep the rest buffered: append it, the caller takes it with pil_rx_next. */
        for (ssize_t k = i + 1; k < n; ++k) {
          if (l->rx.len < PIL_MAX_FRAME) l->rx.buf[l->rx.len++] = buf[k];
        }
        return 1;
      }
    }
  }
}

/* One request, its answer of type `answer` with the same sequence number. */
static int request(pil_link_t *l, pil_frame_type_t type, const void *payload, size_t len,
                   pil_frame_type_t answer, char *err, size_t cap) {
  static uint8_t frame_buf[PIL_MAX_FRAME];
  const uint32_t seq = ++l->seq;
  const size_t n = pil_frame_encode((uint8_t)type, seq, payload, len, frame_buf, sizeof frame_buf);
  if (n == 0) {
    set_err(err, cap, "PIL: request of %zu bytes does not fit a frame", len);
    return -1;
  }
  for (int attempt = 0; attempt < l->opt.max_attempts; ++attempt) {
    if (attempt > 0) ++l->retransmits;
    if (write_all(l->to_fd, frame_buf, n) != 0) {
      set_err(err, cap, "PIL: writing to the target failed: %s", strerror(errno));
      return -1;
    }
    for (;;) {
      const int r = recv_frame(l, l->opt.reply_timeout_s);
      if (r < 0) {
        int st = 0;
        if (!qemu_alive(l, &st))
          set_err(err, cap, "PIL: QEMU exited (status %d) during request %u", st, seq);
        else
          set_err(err, cap, "PIL: the link to the target closed during request %u", seq);
        return -1;
      }
      if (r == 0) break; /* timeout: send again */
      if (l->frame.type == PIL_NAK) {
        ++l->naks;
        break; /* the target dropped bytes: send again */
      }
      if (l->frame.seq == seq && l->frame.type == (uint8_t)answer) return 0;
      ++l->stale_frames; /* an older answer (after a retransmission) or a wrong type */
    }
  }
  set_err(err, cap, "PIL: no answer to request %u (type %d) after %d attempts", seq, (int)type,
          l->opt.max_attempts);
  return -1;
}

/* ---- ELF symbols ----------------------------------------------------------------------------- */

uint32_t pil_elf_symbol(const char *path, const char *name) {
  FILE *f = fopen(path, "rb");
  if (f == NULL) return 0;
  uint32_t result = 0;
  unsigned char *img = NULL;
  if (fseek(f, 0, SEEK_END) != 0) goto done;
  const long size = ftell(f);
  if (size < (long)sizeof(Elf32_Ehdr) || fseek(f, 0, SEEK_SET) != 0) goto done;
  img = malloc((size_t)size);
  if (img == NULL || fread(img, 1, (size_t)size, f) != (size_t)size) goto done;
  Elf32_Ehdr eh;
  memcpy(&eh, img, sizeof eh);
  if (memcmp(eh.e_ident, ELFMAG, SELFMAG) != 0 || eh.e_ident[EI_CLASS] != ELFCLASS32 ||
      eh.e_shentsize != sizeof(Elf32_Shdr) ||
      (size_t)eh.e_shoff + (size_t)eh.e_shnum * sizeof(Elf32_Shdr) > (size_t)size)
    goto done;
  for (unsigned s = 0; s < eh.e_shnum; ++s) {
    Elf32_Shdr sh, strh;
    memcpy(&sh, img + eh.e_shoff + s * sizeof sh, sizeof sh);
    if (sh.sh_type != SHT_SYMTAB || sh.sh_link >= eh.e_shnum) continue;
    memcpy(&strh, img + eh.e_shoff + sh.sh_link * sizeof strh, sizeof strh);
    if ((size_t)sh.sh_offset + sh.sh_size > (size_t)size ||
        (size_t)strh.sh_offset + strh.sh_size > (size_t)size)
      goto done;
    for (size_t k = 0; k < sh.sh_size / sizeof(Elf32_Sym); ++k) {
      Elf32_Sym sym;
      memcpy(&sym, img + sh.sh_offset + k * sizeof sym, sizeof sym);
      if (sym.st_name >= strh.sh_size || ELF32_ST_TYPE(sym.st_info) != STT_FUNC) continue;
      const char *nm = (const char *)img + strh.sh_offset + sym.st_name;
      if (strnlen(nm, strh.sh_size - sym.st_name) < strh.sh_size - sym.st_name &&
          strcmp(nm, name) == 0) {
        result = sym.st_value & ~1u;
        goto done;
      }
    }
  }
done:
  free(img);
  fclose(f);
  return result;
}

/* ---- start / stop ---------------------------------------------------------------------------- */

void pil_link_options_default(pil_link_options_t *o) {
  memset(o, 0, sizeof *o);
  o->qemu = "qemu-system-arm";
  o->reply_timeout_s = 2.0;
  o->max_attempts = 3;
  o->start_timeout_s = 20.0;
}

static void link_clear(pil_link_t *l) {
  memset(l, 0, sizeof *l);
  l->qemu_pid = -1;
  l->to_fd = l->from_fd = l->icount_fd = -1;
}

/* pil_link_start, stage 1: a private directory with the two link FIFOs (and the plugin's count
   FIFO), read ends opened first (non-blocking opens succeed without a writer), so that QEMU's
   opens for writing (the plugin's at start, the image's "out") never block. */
static int link_make_fifos(pil_link_t *l, const pil_link_options_t *opt, char *err, size_t cap) {
  const char *tmp = getenv("TMPDIR");
  snprintf(l->dir, sizeof l->dir, "%s/uvms-pil-XXXXXX", tmp && *tmp ? tmp : "/tmp");
  if (mkdtemp(l->dir) == NULL) {
    set_err(err, cap, "PIL: mkdtemp %s: %s", l->dir, strerror(errno));
    l->dir[0] = '\0';
    return -1;
  }
  snprintf(l->in_path, sizeof l->in_path, "%s/to_target", l->dir);
  snprintf(l->out_path, sizeof l->out_path, "%s/from_target", l->dir);
  snprintf(l->icount_path, sizeof l->icount_path, "%s/icount", l->dir);
  if (mkfifo(l->in_path, 0600) != 0 || mkfifo(l->out_path, 0600) != 0 ||
      (opt->plugin != NULL && mkfifo(l->icount_path, 0600) != 0)) {
    set_err(err, cap, "PIL: mkfifo in %s: %s", l->dir, strerror(errno));
    return -1;
  }
  l->from_fd = open(l->out_path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (opt->plugin != NULL) l->icount_fd = open(l->icount_path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (l->from_fd < 0 || (opt->plugin != NULL && l->icount_fd < 0)) {
    set_err(err, cap, "PIL: opening the FIFOs: %s", strerror(errno));
    return -1;
  }
  return 0;
}

/* The strings QEMU's command line points to (they must outlive the exec). */
typedef struct {
  char plugin_arg[1024];
  char append[700];
  const char *argv[24];
} qemu_cmdline_t;

/* pil_link_start, stage 2: QEMU's command line: the image on mps2-an386 with -icount shift=0
   (deterministic: virtual time = instruction count), the FIFOs passed on the kernel command
   line, and the counting plugin with the image's marker addresses. */
static int link_qemu_cmdline(const pil_link_t *l, const pil_link_options_t *opt, qemu_cmdline_t *c,
                             char *err, size_t cap) {
  c->plugin_arg[0] = '\0';
  if (opt->plugin != NULL) {
    const uint32_t b = pil_elf_symbol(opt->elf, "pil_mark_begin");
    const uint32_t e = pil_elf_symbol(opt->elf, "pil_mark_end");
    if (b == 0 || e == 0) {
      set_err(err, cap, "PIL: marker symbols pil_mark_begin/pil_mark_end not in %s", opt->elf);
      return -1;
    }
    snprintf(c->plugin_arg, sizeof c->plugin_arg, "%s,begin=0x%x,end=0x%x,live=%s", opt->plugin,
             (unsigned)b, (unsigned)e, l->icount_path);
  }
  snprintf(c->append, sizeof c->append, "in=%s out=%s", l->in_path, l->out_path);
  static const char *const fixed[] = {"-M", "mps2-an386", "-nographic", "-monitor", "none",
                                      "-serial", "none", "-semihosting-config",
                                      "enable=on,target=native", "-icount", "shift=0"};
  int n = 0;
  c->argv[n++] = opt->qemu;
  for (size_t k = 0; k < sizeof fixed / sizeof fixed[0]; ++k) c->argv[n++] = fixed[k];
  if (opt->plugin != NULL) {
    c->argv[n++] = "-plugin";
    c->argv[n++] = c->plugin_arg;
  }
  c->argv[n++] = "-kernel";
  c->argv[n++] = opt->elf;
  c->argv[n++] = "-append";
  c->argv[n++] = c->append;
  c->argv[n] = NULL;
  return 0;
}

/* pil_link_start, stage 3: fork and exec QEMU, which dies with this process. */
static int link_spawn_qemu(pil_link_t *l, const qemu_cmdline_t *c, char *err, size_t cap) {
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    set_err(err, cap, "PIL: fork: %s", strerror(errno));
    return -1;
  }
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);
    dup2(STDERR_FILENO, STDOUT_FILENO); /* the guest's semihosting output: never our stdout */
    execvp(c->argv[0], (char *const *)c->argv);
    fprintf(stderr, "uvms-controller-pil: error: cannot execute %s: %s\n", c->argv[0],
            strerror(errno));
    _exit(127);
  }
  l->qemu_pid = pid;
  return 0;
}

/* pil_link_start, stage 4: the image opens "in" for reading (blocking until we open it for
   writing): open it once the image is there, before the deadline or QEMU's exit. */
static int link_open_to_target(pil_link_t *l, double deadline_s, char *err, size_t cap) {
  while (l->to_fd < 0) {
    l->to_fd = open(l->in_path, O_WRONLY | O_NONBLOCK | O_CLOEXEC);
    if (l->to_fd >= 0) break;
    int st = 0;
    if (errno != ENXIO || !qemu_alive(l, &st) || now_s() > deadline_s) {
      if (l->qemu_pid < 0)
        set_err(err, cap, "PIL: QEMU exited (status %d) before opening the link", st);
      else
        set_err(err, cap, "PIL: the image did not open the link within %.0f s",
                l->opt.start_timeout_s);
      return -1;
    }
    usleep(2000);
  }
  fcntl(l->to_fd, F_SETFL, fcntl(l->to_fd, F_GETFL) & ~O_NONBLOCK);
  return 0;
}

/* pil_link_start, stage 5: the image's HELLO must state this host's protocol and record sizes. */
static int link_check_hello(pil_link_t *l, double deadline_s, char *err, size_t cap) {
  const int r = recv_frame(l, deadline_s - now_s());
  pil_hello_rec_t hello;
  if (r != 1 || l->frame.type != PIL_HELLO || l->frame.len != sizeof hello) {
    set_err(err, cap, "PIL: no HELLO from the image (%s)",
            r == 0 ? "timeout" : r < 0 ? "link closed" : "unexpected frame");
    return -1;
  }
  memcpy(&hello, l->frame.payload, sizeof hello);
  if (hello.version != PIL_PROTOCOL_VERSION || hello.config_rec_bytes != sizeof(pil_config_rec_t) ||
      hello.sensors_rec_bytes != sizeof(pil_sensors_rec_t) ||
      hello.output_rec_bytes != sizeof(pil_output_rec_t) || hello.max_payload != PIL_MAX_PAYLOAD) {
    set_err(err, cap, "PIL: the image's protocol differs (version %u, records %u/%u/%u bytes; "
                      "host: %u, %zu/%zu/%zu): rebuild both",
            hello.version, hello.config_rec_bytes, hello.sensors_rec_bytes,
            hello.output_rec_bytes, PIL_PROTOCOL_VERSION, sizeof(pil_config_rec_t),
            sizeof(pil_sensors_rec_t), sizeof(pil_output_rec_t));
    return -1;
  }
  return 0;
}

int pil_link_start(pil_link_t *l, const pil_link_options_t *opt, char *err, size_t cap) {
  link_clear(l);
  l->opt = *opt;
  pil_rx_init(&l->rx);
  if (opt->elf == NULL || access(opt->elf, R_OK) != 0) {
    set_err(err, cap, "PIL image %s not found: build it with `cmake --preset cortex-m4f && "
                      "cmake --build --preset cortex-m4f` (or pass --elf)",
            opt->elf ? opt->elf : "(none)");
    return -1;
  }
  qemu_cmdline_t cmd;
  if (link_make_fifos(l, opt, err, cap) != 0 || link_qemu_cmdline(l, opt, &cmd, err, cap) != 0 ||
      link_spawn_qemu(l, &cmd, err, cap) != 0) {
    pil_link_stop(l);
    return -1;
  }
  const double deadline_s = now_s() + opt->start_timeout_s;
  if (link_open_to_target(l, deadline_s, err, cap) != 0 ||
      link_check_hello(l, deadline_s, err, cap) != 0) {
    pil_link_stop(l);
    return -1;
  }
  return 0;
}

int pil_link_config(pil_link_t *l, const pil_config_rec_t *rec, pil_config_ack_rec_t *ack,
                    char *err, size_t cap) {
  if (request(l, PIL_CONFIG, rec, sizeof *rec, PIL_CONFIG_ACK, err, cap) != 0) return -1;
  if (l->frame.len != sizeof *ack) {
    set_err(err, cap, "PIL: CONFIG_ACK of %u bytes", (unsigned)l->frame.len);
    return -1;
  }
  memcpy(ack, l->frame.payload, sizeof *ack);
  return 0;
}

/* The count the plugin wrote when the step's end marker ran (before the image answered). */
static int read_icount(pil_link_t *l, int64_t *count) {
  uint8_t b[8];
  size_t got = 0;
  const double deadline = now_s() + l->opt.reply_timeout_s;
  while (got < sizeof b) {
    struct pollfd p = {l->icount_fd, POLLIN, 0};
    const double left = deadline - now_s();
    if (left <= 0 || poll(&p, 1, (int)(left * 1e3) + 1) <= 0) return -1;
    const ssize_t n = read(l->icount_fd, b + got, sizeof b - got);
    if (n == 0) return -1;
    if (n < 0) {
      if (errno == EINTR || errno == EAGAIN) continue;
      return -1;
    }
    got += (size_t)n;
  }
  uint64_t v = 0;
  for (int k = 7; k >= 0; --k) v = (v << 8) | b[k];
  *count = (int64_t)v;
  return 0;
}

int pil_link_step(pil_link_t *l, const pil_sensors_rec_t *rec, pil_output_rec_t *out,
                  int64_t *instructions, char *err, size_t cap) {
  *instructions = 0;
  if (request(l, PIL_SENSORS, rec, sizeof *rec, PIL_OUTPUT, err, cap) != 0) return -1;
  if (l->frame.len != sizeof *out) {
    set_err(err, cap, "PIL: OUTPUT of %u bytes", (unsigned)l->frame.len);
    return -1;
  }
  memcpy(out, l->frame.payload, sizeof *out);
  if (l->icount_fd >= 0 && read_icount(l, instructions) != 0) ++l->icount_missing;
  return 0;
}

int pil_link_stop(pil_link_t *l) {
  int rc = 0;
  if (l->to_fd >= 0 && l->qemu_pid > 0) {
    uint8_t buf[PIL_HEADER_BYTES + PIL_CRC_BYTES];
    const size_t n = pil_frame_encode((uint8_t)PIL_QUIT, ++l->seq, NULL, 0, buf, sizeof buf);
    (void)write_all(l->to_fd, buf, n);
  }
  if (l->to_fd >= 0) close(l->to_fd); /* EOF for the image if QUIT was lost */
  l->to_fd = -1;
  if (l->qemu_pid > 0) {
    int st = -1;
    for (int i = 0; i < 200 && qemu_alive(l, &st); ++i) usleep(10000);
    if (l->qemu_pid > 0) {
      kill(l->qemu_pid, SIGTERM);
      waitpid(l->qemu_pid, NULL, 0);
      l->qemu_pid = -1;
      rc = -1;
    } else {
      rc = st;
    }
  }
  if (l->from_fd >= 0) close(l->from_fd);
  if (l->icount_fd >= 0) close(l->icount_fd);
  l->from_fd = l->icount_fd = -1;
  if (l->dir[0] != '\0') {
    unlink(l->in_path);
    unlink(l->out_path);
    unlink(l->icount_path);
    rmdir(l->dir);
    l->dir[0] = '\0';
  }
  return rc;
}
