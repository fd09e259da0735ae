/* SPDX-License-Identifier: Apache-2.0 */
/* session.c: a run's session identifier (session.h). */
#define _GNU_SOURCE
#include "msg/session.h"

#include <errno.h>
#include <stdio.h>
#include <sys/random.h>

int uvms_session_draw(int64_t *session) {
  *session = UVMS_SESSION_NONE;
  /* A zero draw (probability 2^-64) is drawn again; the bound only keeps the loop bounded. */
  for (int attempt = 0; attempt < 4; ++attempt) {
    uint64_t bits = 0;
    const ssize_t n = getrandom(&bits, sizeof bits, 0);
    if (n != (ssize_t)sizeof bits) {
      if (n >= 0) errno = EIO;
      return -1;
    }
    if (bits != 0) {
      *session = (int64_t)bits;
      return 0;
    }
  }
  errno = EIO;
  return -1;
}

static int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

int uvms_session_parse(const char *text, int64_t *session) {
  *session = UVMS_SESSION_NONE;
  if (text == NULL || text[0] == '\0') return 0;
  uint64_t bits = 0;
  int i = 0;
  for (; text[i] != '\0'; ++i) {
    const int d = hex_digit(text[i]);
    if (d < 0 || i >= 16) return 0;
    bits = (bits << 4) | (uint64_t)d;
  }
  if (bits == 0) return 0;
  *session = (int64_t)bits;
  return 1;
}

void uvms_session_format(int64_t session, char text[UVMS_SESSION_TEXT_BYTES]) {
  (void)snprintf(text, UVMS_SESSION_TEXT_BYTES, "%016llx", (unsigned long long)(uint64_t)session);
}
