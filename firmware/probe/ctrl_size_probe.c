/* SPDX-License-Identifier: Apache-2.0 */
/* ctrl_size_probe.c: one controller instance in static storage; the build reads its symbol
   size with nm and prints it (RAM of one controller, in this build's real type). */
#include "uvms/controller.h"

uvms_ctrl_t uvms_ctrl_size_probe_instance;
