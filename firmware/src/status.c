/* SPDX-License-Identifier: Apache-2.0 */
/* status.c: names of status codes (types.h). */
#include "uvms/types.h"

const char *uvms_status_str(uvms_status_t status) {
  switch (status) {
    case UVMS_OK: return "UVMS_OK";
    case UVMS_ERR_ARG: return "UVMS_ERR_ARG";
    case UVMS_ERR_NONFINITE: return "UVMS_ERR_NONFINITE";
    case UVMS_ERR_SINGULAR: return "UVMS_ERR_SINGULAR";
    case UVMS_ERR_RANGE: return "UVMS_ERR_RANGE";
    case UVMS_ERR_SIZE: return "UVMS_ERR_SIZE";
    case UVMS_ERR_STATE: return "UVMS_ERR_STATE";
    default: return "UVMS_ERR_UNKNOWN";
  }
}
