/* SPDX-License-Identifier: Apache-2.0 */
/*
 * cli_version.h: `--version` for every command-line program (uvms, uvms-plant, uvms-controller,
 * uvms-controller-pil): "<program> <version> (git <commit>)" on stdout, exit 0.
 * The version is the firmware's (uvms/version.h: the project VERSION baked in at build time);
 * the commit is the one provenance records (cmake/git_commit.cmake, refreshed every build).
 */
#ifndef UVMS_SIL_CLI_VERSION_H
#define UVMS_SIL_CLI_VERSION_H

#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

/** 1 if the first argument is "--version" (argv as main's). */
int uvms_cli_wants_version(int argc, char **argv);

/** The version line, "<program> <version> (git <commit>)\n". */
void uvms_cli_print_version(FILE *out, const char *program);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_SIL_CLI_VERSION_H */
