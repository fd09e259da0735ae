/* SPDX-License-Identifier: Apache-2.0 */
/*
 * qemu_plugin_api.h: the subset of QEMU's TCG plugin API (version 1, as shipped by QEMU 7.2
 * in include/qemu/qemu-plugin.h) that qemu_icount_plugin.c uses. Debian installs QEMU without
 * that header, so the declarations the plugin needs are restated here, with the same names,
 * types and enum values, which is what the ABI depends on (QEMU resolves these functions in
 * its own executable when it dlopen()s the plugin).
 *
 * Version check: QEMU 7.2 accepts plugins whose exported `qemu_plugin_version` lies in
 * [QEMU_PLUGIN_MIN_VERSION, QEMU_PLUGIN_VERSION] = [0, 1]. API version 2 (register access)
 * arrived with QEMU 8.x; nothing below needs it.
 */
#ifndef UVMS_QEMU_PLUGIN_API_H
#define UVMS_QEMU_PLUGIN_API_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define QEMU_PLUGIN_EXPORT __attribute__((visibility("default")))

/** API level this plugin is written against (QEMU 7.2: current 1, minimum 0). */
#define QEMU_PLUGIN_VERSION 1

/** Opaque plugin id handed to qemu_plugin_install(). */
typedef uint64_t qemu_plugin_id_t;

/** Every plugin exports the API level it was built for; QEMU reads it before installing. */
extern QEMU_PLUGIN_EXPORT int qemu_plugin_version;

/** What QEMU tells the plugin at install time (valid only during qemu_plugin_install). */
typedef struct qemu_info_t {
  const char *target_name; /**< guest architecture, e.g. "arm" */
  struct {
    int min; /**< oldest API level this QEMU supports */
    int cur; /**< newest API level this QEMU supports */
  } version;
  bool system_emulation; /**< true for qemu-system-*, false for linux-user */
  union {
    struct {
      int smp_vcpus;
      int max_vcpus;
    } system;
  };
} qemu_info_t;

/** Opaque handles, valid only inside the translation callback that received them. */
struct qemu_plugin_tb;
struct qemu_plugin_insn;

/** Whether a callback reads or writes guest registers (API v1: informational). */
enum qemu_plugin_cb_flags {
  QEMU_PLUGIN_CB_NO_REGS,
  QEMU_PLUGIN_CB_R_REGS,
  QEMU_PLUGIN_CB_RW_REGS,
};

/** Inline operations QEMU emits into translated code (API v1 has only one). */
enum qemu_plugin_op {
  QEMU_PLUGIN_INLINE_ADD_U64, /**< *(uint64_t *)ptr += imm, not atomic */
};

typedef void (*qemu_plugin_udata_cb_t)(qemu_plugin_id_t id, void *userdata);
typedef void (*qemu_plugin_vcpu_udata_cb_t)(unsigned int vcpu_index, void *userdata);
typedef void (*qemu_plugin_vcpu_tb_trans_cb_t)(qemu_plugin_id_t id, struct qemu_plugin_tb *tb);

/** Entry point QEMU calls once after loading; return 0 on success. argv lives as long as QEMU. */
QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t *info,
                                           int argc, char **argv);

void qemu_plugin_register_vcpu_tb_trans_cb(qemu_plugin_id_t id, qemu_plugin_vcpu_tb_trans_cb_t cb);
void qemu_plugin_register_vcpu_tb_exec_inline(struct qemu_plugin_tb *tb, enum qemu_plugin_op op,
                                              void *ptr, uint64_t imm);
void qemu_plugin_register_vcpu_insn_exec_cb(struct qemu_plugin_insn *insn,
                                            qemu_plugin_vcpu_udata_cb_t cb,
                                            enum qemu_plugin_cb_flags flags, void *userdata);
void qemu_plugin_register_vcpu_insn_exec_inline(struct qemu_plugin_insn *insn,
                                                enum qemu_plugin_op op, void *ptr, uint64_t imm);
size_t qemu_plugin_tb_n_insns(const struct qemu_plugin_tb *tb);
struct qemu_plugin_insn *qemu_plugin_tb_get_insn(const struct qemu_plugin_tb *tb, size_t idx);
uint64_t qemu_plugin_insn_vaddr(const struct qemu_plugin_insn *insn);
/** Best-effort symbol of an instruction from the guest ELF's symbol table; NULL if none. */
const char *qemu_plugin_insn_symbol(const struct qemu_plugin_insn *insn);
void qemu_plugin_register_atexit_cb(qemu_plugin_id_t id, qemu_plugin_udata_cb_t cb,
                                    void *userdata);
/** Writes through QEMU's log: shown only with -d plugin (stderr, or -D FILE). */
void qemu_plugin_outs(const char *string);

#endif /* UVMS_QEMU_PLUGIN_API_H */
