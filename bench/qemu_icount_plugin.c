/* SPDX-License-Identifier: Apache-2.0 */
/*
 * qemu_icount_plugin.c: a QEMU TCG plugin (API v1, QEMU 7.2) that counts executed guest
 * instructions exactly, per interval between two marker addresses.
 *
 *   qemu-system-arm ... -icount shift=0 \
 *     -d plugin -plugin ./libqemu_icount_plugin.so,begin=0xADDR,end=0xADDR[,span=0xADDR]
 *                       [,out=FILE][,syms=FILE]
 *
 * Every translated instruction gets an inline "counter += 1" (no helper call, exact, and
 * cheap). The instruction at `begin` and the one at `end` also get a callback that reads the
 * counter: an interval is counter(end) - counter(begin). QEMU emits an instruction's callback
 * and its inline op in a fixed order, so an interval holds every instruction executed between
 * the two marker instructions plus exactly one of the marker instructions. For markers that
 * are `bx lr` functions bracketing `f(args)`, that is f plus a few instructions of call
 * overhead (argument set-up, the call, the call to the end marker, one marker's `bx lr`).
 *
 * A second, independent total counts whole translation blocks (inline += n_insns on block
 * entry); the two totals agree unless a block is left part-way (an exception mid-block).
 *
 * Arguments (key=value, comma-separated after the .so):
 *   begin=ADDR  end=ADDR   marker addresses (hex 0x.. or decimal). Bit 0 is ignored, so
 *                          Thumb function symbols from `nm` can be passed as they are.
 *   span=ADDR              optional: also report span = count at the last execution of
 *                          ADDR - count at its first (e.g. a marker before and after a loop)
 *   out=FILE               write every interval's count, one per line, in order
 *   live=FILE              write every interval's count as soon as it ends, as 8 bytes
 *                          (uint64, little-endian), with one write(2) each: for a FIFO that a
 *                          host process reads while the guest runs (the PIL bridge,
 *                          sil/pil/pil_host.c; opened at install: its reader must exist)
 *   syms=FILE              per-symbol attribution: instructions executed inside intervals,
 *                          summed per guest symbol (the ELF's symbol table as QEMU loaded it
 *                          with -kernel), written as "count symbol" lines, largest first
 * At exit it prints one line through qemu_plugin_outs, i.e. QEMU's log: enable it with
 * `-d plugin` (stderr, or the file given by -D FILE):
 *   icount: intervals=N unmatched=U open=O median=M mean=A min=L max=H sum=S total=T
 *           tb_total=B span=P   (span=-1 without span= or if ADDR never ran)
 * Single vCPU guests only (the inline counters are not atomic; mps2-an386 has one core).
 */
#define _POSIX_C_SOURCE 200809L /* open, write */
#include <fcntl.h>
#include <inttypes.h>
#include <unistd.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "qemu_plugin_api.h"

QEMU_PLUGIN_EXPORT int qemu_plugin_version = QEMU_PLUGIN_VERSION;

/** Symbols tracked in syms= mode: an open-addressed table sized far above a firmware image's. */
#define SYM_TABLE_SIZE 4096u

typedef struct {
  const char *name; /* owned copy; NULL = empty slot */
  uint64_t count;   /* instructions executed in this symbol, whole run (inline op target) */
  uint64_t inside;  /* of those, inside begin/end intervals */
} sym_entry_t;

static uint64_t g_begin_addr, g_end_addr, g_span_addr;
static int g_have_begin, g_have_end, g_have_span;
static const char *g_out_path, *g_syms_path, *g_live_path;
static int g_live_fd = -1;       /* live= target, or -1 */
static uint64_t g_live_failures; /* live writes that did not complete */

static uint64_t g_insn_total; /* += 1 per executed instruction (inline) */
static uint64_t g_tb_total;   /* += n_insns per executed block (inline) */

static int g_open;              /* a begin was seen and its end not yet */
static uint64_t g_open_at;      /* g_insn_total at that begin */
static uint64_t g_unmatched;    /* begin while open, or end while closed */
static uint64_t *g_intervals;   /* counts, in order */
static size_t g_n_intervals, g_cap_intervals;

static uint64_t g_span_first, g_span_last; /* g_insn_total at ADDR's first, last execution */
static uint64_t g_span_hits;

static sym_entry_t *g_syms; /* NULL unless syms= was given */
static size_t g_n_syms;
static uint64_t g_sym_overflow; /* instructions whose symbol did not fit in the table */

static void outf(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
static void outf(const char *fmt, ...) {
  char buf[512];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  qemu_plugin_outs(buf);
}

/* ---- symbol attribution (syms= mode) ------------------------------------------------------ */

static uint32_t str_hash(const char *s) {
  uint32_t h = 2166136261u; /* FNV-1a */
  for (; *s != '\0'; ++s) h = (h ^ (uint8_t)*s) * 16777619u;
  return h;
}

/** malloc'ed copy of s (strdup is POSIX, not C11). */
static char *copy_str(const char *s) {
  const size_t n = strlen(s) + 1u;
  char *p = malloc(n);
  if (p != NULL) memcpy(p, s, n);
  return p;
}

/** Counter slot of a symbol (created on first sight); NULL when the table is full. */
static sym_entry_t *sym_lookup(const char *name) {
  if (name == NULL || name[0] == '\0') name = "(no symbol)";
  uint32_t i = str_hash(name) & (SYM_TABLE_SIZE - 1u);
  for (uint32_t probe = 0; probe < SYM_TABLE_SIZE; ++probe) {
    sym_entry_t *e = &g_syms[i];
    if (e->name == NULL) {
      if (g_n_syms + 1u >= SYM_TABLE_SIZE) return NULL; /* keep one slot free */
      e->name = copy_str(name);
      if (e->name == NULL) return NULL;
      ++g_n_syms;
      return e;
    }
    if (strcmp(e->name, name) == 0) return e;
    i = (i + 1u) & (SYM_TABLE_SIZE - 1u);
  }
  return NULL;
}

/* On entering an interval subtract every symbol's running count, on leaving add it back:
   `inside` accumulates exactly the instructions executed between the two markers. Symbols
   first translated inside an interval start at 0, so the subtraction they missed is 0. */
static void syms_mark(int entering) {
  for (size_t i = 0; i < SYM_TABLE_SIZE; ++i) {
    if (g_syms[i].name == NULL) continue;
    if (entering) g_syms[i].inside -= g_syms[i].count;
    else g_syms[i].inside += g_syms[i].count;
  }
}

/* ---- marker callbacks ---------------------------------------------------------------------- */

static void on_begin(unsigned int vcpu_index, void *userdata) {
  (void)vcpu_index;
  (void)userdata;
  if (g_open) { /* nested or missing end: restart the interval, remember the anomaly */
    ++g_unmatched;
    if (g_syms != NULL) syms_mark(0);
  }
  g_open = 1;
  g_open_at = g_insn_total;
  if (g_syms != NULL) syms_mark(1);
}

static void on_end(unsigned int vcpu_index, void *userdata) {
  (void)vcpu_index;
  (void)userdata;
  if (!g_open) {
    ++g_unmatched;
    return;
  }
  g_open = 0;
  if (g_syms != NULL) syms_mark(0);
  if (g_n_intervals == g_cap_intervals) {
    const size_t cap = g_cap_intervals ? 2u * g_cap_intervals : 4096u;
    uint64_t *p = realloc(g_intervals, cap * sizeof *p);
    if (p == NULL) {
      ++g_unmatched; /* cannot store: counted as an anomaly rather than silently dropped */
      return;
    }
    g_intervals = p;
    g_cap_intervals = cap;
  }
  g_intervals[g_n_intervals++] = g_insn_total - g_open_at;
  if (g_live_fd >= 0) {
    const uint64_t v = g_insn_total - g_open_at;
    uint8_t b[8];
    for (int k = 0; k < 8; ++k) b[k] = (uint8_t)(v >> (8 * k));
    if (write(g_live_fd, b, sizeof b) != (ssize_t)sizeof b) ++g_live_failures;
  }
}

static void on_span(unsigned int vcpu_index, void *userdata) {
  (void)vcpu_index;
  (void)userdata;
  if (g_span_hits++ == 0) g_span_first = g_insn_total;
  g_span_last = g_insn_total;
}

/* ---- translation ---------------------------------------------------------------------------- */

static void on_tb_trans(qemu_plugin_id_t id, struct qemu_plugin_tb *tb) {
  (void)id;
  const size_t n = qemu_plugin_tb_n_insns(tb);
  qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &g_tb_total, n);
  for (size_t i = 0; i < n; ++i) {
    struct qemu_plugin_insn *insn = qemu_plugin_tb_get_insn(tb, i);
    const uint64_t pc = qemu_plugin_insn_vaddr(insn);
    if (pc == g_begin_addr)
      qemu_plugin_register_vcpu_insn_exec_cb(insn, on_begin, QEMU_PLUGIN_CB_NO_REGS, NULL);
    if (pc == g_end_addr)
      qemu_plugin_register_vcpu_insn_exec_cb(insn, on_end, QEMU_PLUGIN_CB_NO_REGS, NULL);
    if (g_have_span && pc == g_span_addr)
      qemu_plugin_register_vcpu_insn_exec_cb(insn, on_span, QEMU_PLUGIN_CB_NO_REGS, NULL);
    qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64, &g_insn_total, 1);
    if (g_syms != NULL) {
      sym_entry_t *e = sym_lookup(qemu_plugin_insn_symbol(insn));
      qemu_plugin_register_vcpu_insn_exec_inline(insn, QEMU_PLUGIN_INLINE_ADD_U64,
                                                 e != NULL ? &e->count : &g_sym_overflow, 1);
    }
  }
}

/* ---- report --------------------------------------------------------------------------------- */

static int cmp_u64(const void *a, const void *b) {
  const uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

static int cmp_sym_inside_desc(const void *a, const void *b) {
  const sym_entry_t *x = a, *y = b;
  if (x->inside != y->inside) return x->inside < y->inside ? 1 : -1;
  return strcmp(x->name, y->name);
}

static void write_intervals(void) {
  FILE *f = fopen(g_out_path, "w");
  if (f == NULL) {
    outf("icount: cannot write %s\n", g_out_path);
    return;
  }
  for (size_t i = 0; i < g_n_intervals; ++i) fprintf(f, "%" PRIu64 "\n", g_intervals[i]);
  fclose(f);
}

static void write_syms(void) {
  /* Compact the table, then sort by instructions inside intervals. */
  size_t n = 0;
  for (size_t i = 0; i < SYM_TABLE_SIZE; ++i)
    if (g_syms[i].name != NULL) g_syms[n++] = g_syms[i];
  qsort(g_syms, n, sizeof g_syms[0], cmp_sym_inside_desc);
  FILE *f = fopen(g_syms_path, "w");
  if (f == NULL) {
    outf("icount: cannot write %s\n", g_syms_path);
    return;
  }
  uint64_t sum = 0;
  for (size_t i = 0; i < n; ++i) {
    if (g_syms[i].inside == 0) continue;
    fprintf(f, "%" PRIu64 " %s\n", g_syms[i].inside, g_syms[i].name);
    sum += g_syms[i].inside;
  }
  fclose(f);
  outf("icount: syms=%zu inside_sum=%" PRIu64 " overflow=%" PRIu64 "\n", n, sum, g_sym_overflow);
}

static void on_exit_report(qemu_plugin_id_t id, void *userdata) {
  (void)id;
  (void)userdata;
  uint64_t sum = 0, lo = 0, hi = 0;
  double median = 0.0, mean = 0.0;
  if (g_n_intervals > 0) {
    for (size_t i = 0; i < g_n_intervals; ++i) sum += g_intervals[i];
    mean = (double)sum / (double)g_n_intervals;
    if (g_out_path != NULL) write_intervals(); /* in execution order, before sorting */
    qsort(g_intervals, g_n_intervals, sizeof g_intervals[0], cmp_u64);
    lo = g_intervals[0];
    hi = g_intervals[g_n_intervals - 1];
    median = 0.5 * ((double)g_intervals[(g_n_intervals - 1) / 2] +
                    (double)g_intervals[g_n_intervals / 2]);
  } else if (g_out_path != NULL) {
    write_intervals(); /* an empty file: no interval completed */
  }
  if (g_syms != NULL && g_syms_path != NULL) write_syms();
  const long long span = g_span_hits > 0 ? (long long)(g_span_last - g_span_first) : -1;
  outf("icount: intervals=%zu unmatched=%" PRIu64 " open=%d median=%.1f mean=%.3f min=%" PRIu64
       " max=%" PRIu64 " sum=%" PRIu64 " total=%" PRIu64 " tb_total=%" PRIu64 " span=%lld\n",
       g_n_intervals, g_unmatched, g_open, median, mean, lo, hi, sum, g_insn_total, g_tb_total,
       span);
  if (g_live_fd >= 0) {
    if (g_live_failures > 0) outf("icount: live_failures=%" PRIu64 "\n", g_live_failures);
    close(g_live_fd);
    g_live_fd = -1;
  }
  free(g_intervals);
  g_intervals = NULL;
}

/* ---- install -------------------------------------------------------------------------------- */

static int parse_addr(const char *s, uint64_t *out) {
  char *end = NULL;
  const unsigned long long v = strtoull(s, &end, 0);
  if (end == s || *end != '\0') return -1;
  *out = (uint64_t)v & ~(uint64_t)1u; /* Thumb bit of ARM function symbols */
  return 0;
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info,
                                           int argc, char **argv) {
  (void)info;
  for (int i = 0; i < argc; ++i) {
    const char *a = argv[i];
    if (strncmp(a, "begin=", 6) == 0) {
      if (parse_addr(a + 6, &g_begin_addr) != 0) goto bad;
      g_have_begin = 1;
    } else if (strncmp(a, "end=", 4) == 0) {
      if (parse_addr(a + 4, &g_end_addr) != 0) goto bad;
      g_have_end = 1;
    } else if (strncmp(a, "span=", 5) == 0) {
      if (parse_addr(a + 5, &g_span_addr) != 0) goto bad;
      g_have_span = 1;
    } else if (strncmp(a, "out=", 4) == 0 && a[4] != '\0') {
      g_out_path = a + 4;
    } else if (strncmp(a, "live=", 5) == 0 && a[5] != '\0') {
      g_live_path = a + 5;
    } else if (strncmp(a, "syms=", 5) == 0 && a[5] != '\0') {
      g_syms_path = a + 5;
    } else {
      goto bad;
    }
    continue;
  bad:
    fprintf(stderr, "qemu_icount_plugin: bad argument '%s' (begin=ADDR end=ADDR "
                    "[span=ADDR] [out=FILE] [live=FILE] [syms=FILE])\n", a);
    return -1;
  }
  if (!g_have_begin || !g_have_end || g_begin_addr == g_end_addr) {
    fprintf(stderr, "qemu_icount_plugin: need distinct begin=ADDR and end=ADDR\n");
    return -1;
  }
  if (g_have_span && (g_span_addr == g_begin_addr || g_span_addr == g_end_addr)) {
    fprintf(stderr, "qemu_icount_plugin: span=ADDR must differ from begin and end\n");
    return -1;
  }
  if (g_live_path != NULL) {
    g_live_fd = open(g_live_path, O_WRONLY | O_CLOEXEC);
    if (g_live_fd < 0) {
      fprintf(stderr, "qemu_icount_plugin: cannot open live=%s\n", g_live_path);
      return -1;
    }
  }
  if (g_syms_path != NULL) {
    g_syms = calloc(SYM_TABLE_SIZE, sizeof *g_syms);
    if (g_syms == NULL) return -1;
  }
  qemu_plugin_register_vcpu_tb_trans_cb(id, on_tb_trans);
  qemu_plugin_register_atexit_cb(id, on_exit_report, NULL);
  return 0;
}
