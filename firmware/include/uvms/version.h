/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file version.h
 * @brief The library's version: numeric macros (UVMS_VERSION_MAJOR, _MINOR, _PATCH and
 *        UVMS_VERSION_STRING, from the generated uvms/config.h) and uvms_version().
 *
 * The one source is the top-level CMakeLists.txt's project(VERSION); the string is baked in
 * when the library is built (no git, no file access at run time).
 */
#ifndef UVMS_VERSION_H
#define UVMS_VERSION_H

#include "uvms/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/** @brief The version of the linked library, "MAJOR.MINOR.PATCH"; never NULL (a static string;
 *         no preconditions, no failure). */
const char *uvms_version(void);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_VERSION_H */
