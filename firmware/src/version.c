/* SPDX-License-Identifier: Apache-2.0 */
/* version.c: the library's version string and its precision marker (uvms/types.h). */
#include "uvms/version.h"

#include "uvms/types.h"

const char *uvms_version(void) { return UVMS_VERSION_STRING; }

/* The ABI marker of this library's real type: every translation unit that includes
 * uvms/types.h references the marker of the precision it was compiled for, so an object built
 * against a header of the other precision fails to link, naming the precision. */
#if UVMS_REAL_IS_FLOAT
const int uvms_abi_real_float_v1 = 1;
#else
const int uvms_abi_real_double_v1 = 1;
#endif
