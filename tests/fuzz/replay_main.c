/* SPDX-License-Identifier: Apache-2.0 */
/*
 * replay_main.c: runs a fuzz target without libFuzzer. Every argument is a file or a directory
 * (not recursive); each regular file is read whole and passed to LLVMFuzzerTestOneInput once,
 * in name order within a directory. A property violation aborts (the test then fails with the
 * file's name on stderr). Prints how many inputs ran; a missing argument path is an error.
 *
 *   fuzz_<target>_replay tests/fuzz/regressions/<target> <seed dir>...
 */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "fuzz_support.h"

static int run_file(const char *path) {
  FILE *f = fopen(path, "rb");
  if (f == NULL) {
    fprintf(stderr, "replay: cannot open %s\n", path);
    return -1;
  }
  size_t cap = 4096, n = 0;
  uint8_t *buf = malloc(cap);
  size_t got;
  while (buf != NULL && (got = fread(buf + n, 1, cap - n, f)) > 0) {
    n += got;
    if (n == cap) {
      uint8_t *bigger = realloc(buf, cap * 2);
      if (bigger == NULL) break;
      buf = bigger;
      cap *= 2;
    }
  }
  const int failed = buf == NULL || ferror(f);
  fclose(f);
  if (failed) {
    free(buf);
    fprintf(stderr, "replay: cannot read %s\n", path);
    return -1;
  }
  /* Exactly n bytes, as libFuzzer passes them (so AddressSanitizer sees over-reads). */
  uint8_t *exact = malloc(n > 0 ? n : 1);
  if (exact == NULL) {
    free(buf);
    return -1;
  }
  memcpy(exact, buf, n);
  free(buf);
  fprintf(stderr, "replay: %s (%zu bytes)\n", path, n);
  LLVMFuzzerTestOneInput(exact, n);
  free(exact);
  return 0;
}

static int cmp_names(const void *a, const void *b) {
  return strcmp(*(char *const *)a, *(char *const *)b);
}

static int run_dir(const char *dir, long *count) {
  DIR *d = opendir(dir);
  if (d == NULL) return -1;
  char **names = NULL;
  size_t n = 0, cap = 0;
  struct dirent *e;
  while ((e = readdir(d)) != NULL) {
    if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
    if (n == cap) {
      cap = cap ? cap * 2 : 64;
      char **more = realloc(names, cap * sizeof *names);
      if (more == NULL) break;
      names = more;
    }
    names[n++] = strdup(e->d_name);
  }
  closedir(d);
  if (n > 0) qsort(names, n, sizeof *names, cmp_names);
  int status = 0;
  for (size_t i = 0; i < n; ++i) {
    const size_t len = strlen(dir) + strlen(names[i]) + 2;
    char *path = malloc(len);
    struct stat st;
    if (path != NULL) {
      snprintf(path, len, "%s/%s", dir, names[i]);
      if (stat(path, &st) == 0 && S_ISREG(st.st_mode)) {
        if (run_file(path) != 0) status = -1;
        else ++*count;
      }
    }
    free(path);
    free(names[i]);
  }
  free(names);
  return status;
}

int main(int argc, char **argv) {
  long count = 0;
  int status = 0;
  for (int i = 1; i < argc; ++i) {
    struct stat st;
    if (stat(argv[i], &st) != 0) {
      fprintf(stderr, "replay: %s does not exist\n", argv[i]);
      status = 1;
    } else if (S_ISDIR(st.st_mode)) {
      if (run_dir(argv[i], &count) != 0) status = 1;
    } else if (run_file(argv[i]) == 0) {
      ++count;
    } else {
      status = 1;
    }
  }
  printf("replay: %ld inputs ran, every property held\n", count);
  return status;
}
