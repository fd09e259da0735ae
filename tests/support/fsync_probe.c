/* SPDX-License-Identifier: Apache-2.0 */
/* fsync_probe.c: an LD_PRELOAD library for the tests that records which files a program makes
   durable. Each call of fsync, fdatasync or syncfs appends one line, "<call> <path>\n" (the
   path of the descriptor, from /proc/self/fd), to the file named by UVMS_FSYNC_PROBE_LOG, then
   calls the C library's function. Without that variable it records nothing. Every process
   that inherits the variable and the preload (forked runs, exec'd nodes) appends to the same
   file; a line is one write with O_APPEND, so lines do not interleave.
   Failures, injected: with UVMS_FSYNC_PROBE_FAIL_SYNCFS=1 every syncfs fails with EIO, and
   with UVMS_FSYNC_PROBE_FAIL_FSYNC=TEXT every fsync of a path containing TEXT fails with EIO,
   without calling the C library (the line is still recorded). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Appends "<call> <path of fd>\n" to the probe's log (errors are ignored: the probe's own
   failures never fail the program it watches); returns 1 if the call is to fail (the
   UVMS_FSYNC_PROBE_FAIL_* variables). */
static int record(const char *call, int fd) {
  char link[64], path[4096], line[4200];
  snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
  const ssize_t n = readlink(link, path, sizeof path - 1);
  path[n < 0 ? 0 : n] = '\0';
  const char *fail_syncfs = getenv("UVMS_FSYNC_PROBE_FAIL_SYNCFS");
  const char *fail_fsync = getenv("UVMS_FSYNC_PROBE_FAIL_FSYNC");
  const int fail = (strcmp(call, "syncfs") == 0 && fail_syncfs != NULL && fail_syncfs[0] == '1') ||
                   (strcmp(call, "fsync") == 0 && fail_fsync != NULL && fail_fsync[0] != '\0' &&
                    strstr(path, fail_fsync) != NULL);
  const char *log = getenv("UVMS_FSYNC_PROBE_LOG");
  if (log == NULL || log[0] == '\0') return fail;
  const int len = snprintf(line, sizeof line, "%s %s\n", call, n < 0 ? "?" : path);
  const int out = open(log, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0644);
  if (out < 0) return fail;
  if (len > 0 && write(out, line, (size_t)len < sizeof line ? (size_t)len : sizeof line - 1) < 0) {
  }
  close(out);
  return fail;
}

/* The injected failure: -1 with errno EIO. */
static int failed(void) {
  errno = EIO;
  return -1;
}

typedef int (*fd_call_t)(int);

/* The C library's own function `name` (the next definition after this library's). */
static int call_next(const char *name, int fd) {
  void *sym = dlsym(RTLD_NEXT, name);
  fd_call_t next = NULL;
  memcpy(&next, &sym, sizeof next); /* ISO C has no cast from an object to a function pointer */
  return next != NULL ? next(fd) : -1;
}

int fsync(int fd) { return record("fsync", fd) ? failed() : call_next("fsync", fd); }

int fdatasync(int fd) { return record("fdatasync", fd) ? failed() : call_next("fdatasync", fd); }

int syncfs(int fd) { return record("syncfs", fd) ? failed() : call_next("syncfs", fd); }
