/* SPDX-License-Identifier: Apache-2.0 */
/*
 * fuzz_support.h: what every fuzz target in tests/fuzz shares.
 *
 * A target is one LLVMFuzzerTestOneInput(data, size). It is linked two ways:
 *  - with libFuzzer (-fsanitize=fuzzer, preset host-fuzz): the fuzzer itself;
 *  - with replay_main.c (any preset): a plain program that feeds it every file of the
 *    directories it is given once (the committed regressions and the seed corpus).
 * A property the target checks is a FUZZ_REQUIRE: on violation it prints what and where, then
 * abort()s, which libFuzzer reports as a crash and saves the input as an artifact.
 */
#ifndef UVMS_FUZZ_SUPPORT_H
#define UVMS_FUZZ_SUPPORT_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#ifdef __cplusplus
extern "C" {
#endif

/** The session (sil/msg/session.h) of the generated seeds' messages and of fuzz_ctrl_node's
 *  shortcut configuration, so that seeded sequences reach the controller. */
#define FUZZ_SESSION ((int64_t)0x00f0220000000001LL)

/** The libFuzzer entry point every target defines. Returns 0 (libFuzzer's convention). */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#ifdef __cplusplus
}
#endif

/* FUZZ_REQUIRE(condition, "printf format", args...): abort with a message when false. */
#define FUZZ_REQUIRE(cond, ...)                                                  \
  do {                                                                           \
    if (!(cond)) {                                                               \
      fprintf(stderr, "fuzz property violated at %s:%d: %s: ", __FILE__, __LINE__, \
              #cond);                                                            \
      fprintf(stderr, __VA_ARGS__);                                              \
      fputc('\n', stderr);                                                       \
      abort();                                                                   \
    }                                                                            \
  } while (0)

#endif /* UVMS_FUZZ_SUPPORT_H */
