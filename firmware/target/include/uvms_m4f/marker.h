/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file marker.h
 * @brief Marker functions of the Cortex-M4F images (uvms_add_m4f_image): empty functions whose
 *        addresses bracket the code an instruction-counting QEMU plugin measures.
 *
 * UVMS_M4F_MARKER(name, text) defines `void name(void)`: out of line, never cloned, folded or
 * analysed across (noipa), kept (used), with an asm body that holds `text` so that no two markers
 * can be merged. Each compiles to a single `bx lr`; its address (arm-none-eabi-nm) is what the
 * plugin's begin=, end= and span= arguments name.
 */
#ifndef UVMS_M4F_MARKER_H
#define UVMS_M4F_MARKER_H

#define UVMS_M4F_MARKER(name, text)                                 \
  void name(void);                                                  \
  __attribute__((noinline, noipa, used)) void name(void) {          \
    __asm volatile("/* " text " */" ::: "memory");                  \
  }

#endif /* UVMS_M4F_MARKER_H */
