/* SPDX-License-Identifier: Apache-2.0 */
/* cli_version.c: `--version` of the command-line programs (cli_version.h). */
#include "msg/cli_version.h"

#include <string.h>

#include "uvms/config.h"      /* UVMS_VERSION_STRING (generated with the firmware library) */
#include "uvms_git_commit.h"  /* generated at build time: UVMS_GIT_COMMIT */

int uvms_cli_wants_version(int argc, char **argv) {
  return argc >= 2 && strcmp(argv[1], "--version") == 0;
}

void uvms_cli_print_version(FILE *out, const char *program) {
  fprintf(out, "%s %s (git %s)\n", program, UVMS_VERSION_STRING, UVMS_GIT_COMMIT);
}
