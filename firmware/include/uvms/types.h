/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file types.h
 * @brief Real type, status codes and scalar math shared by every firmware module.
 *
 * The controller computes in one real type, uvms_real_t: float on Cortex-M4F (single-precision
 * FPU) and, by default, double on the host. Both variants are built and tested
 * (CMake option UVMS_REAL_FLOAT, baked into the generated uvms/config.h when the library is
 * built). Literals are written UVMS_R(0.5) so that the float build never promotes to double
 * (-Wdouble-promotion is an error in firmware).
 */
#ifndef UVMS_TYPES_H
#define UVMS_TYPES_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The precision the library was built with (generated from firmware/cmake/config.h.in). */
#include "uvms/config.h"

/* A translation unit may still say which precision it expects (-DUVMS_REAL_FLOAT=0 or 1);
 * it must be the library's. */
#if defined(UVMS_REAL_FLOAT) && ((UVMS_REAL_FLOAT + 0) != 0) != UVMS_CONFIG_REAL_FLOAT
#if UVMS_CONFIG_REAL_FLOAT
#error "uvms precision mismatch: the uvms_firmware library was built with float (single precision, uvms/config.h) but this translation unit asks for double (UVMS_REAL_FLOAT=0); remove -DUVMS_REAL_FLOAT or use a double build of the library"
#else
#error "uvms precision mismatch: the uvms_firmware library was built with double (uvms/config.h) but this translation unit asks for float (UVMS_REAL_FLOAT=1); remove -DUVMS_REAL_FLOAT or use a float build of the library"
#endif
#endif

#if UVMS_CONFIG_REAL_FLOAT
typedef float uvms_real_t;
#define UVMS_REAL_IS_FLOAT 1
#else
typedef double uvms_real_t;
#define UVMS_REAL_IS_FLOAT 0
#endif

/* Link-time precision marker: the library defines the marker of its real type (version.c) and
 * every translation unit including this header references the marker of the type it was
 * compiled with. An object compiled against a header of the other precision (a stale or
 * copied config.h) fails to link with "undefined reference to uvms_abi_real_<type>_v1". */
#if UVMS_REAL_IS_FLOAT
extern const int uvms_abi_real_float_v1;
#define UVMS_ABI_MARKER uvms_abi_real_float_v1
#else
extern const int uvms_abi_real_double_v1;
#define UVMS_ABI_MARKER uvms_abi_real_double_v1
#endif
/* Two references, neither in the library's own objects (UVMS_FIRMWARE_BUILD):
 * - a pointer in every translation unit, kept by the compiler (used); a linker that collects
 *   unused sections (-Wl,--gc-sections) may drop it, and with it the reference;
 * - a read of the marker in uvms_ctrl_init (uvms/controller.h wraps every call in a consumer),
 *   which stays wherever the controller is initialised, with or without --gc-sections. */
#if !defined(UVMS_FIRMWARE_BUILD)
#if defined(__GNUC__)
__attribute__((used)) static const int *const uvms_abi_marker_ref = &UVMS_ABI_MARKER;
#endif
/** @brief Reads this header's precision marker (a link-time check; see above). */
static inline void uvms_abi_check(void) { (void)*(const volatile int *)&UVMS_ABI_MARKER; }
#endif

/** A literal in the controller's real type. */
#define UVMS_R(x) ((uvms_real_t)(x))
/** pi in the controller's real type. */
#define UVMS_PI UVMS_R(3.14159265358979323846)

/**
 * Status returned by every firmware function that can fail. UVMS_OK is zero, errors are
 * negative. On any error the function has written a defined safe output (documented per
 * function, usually zeros) before returning.
 */
typedef enum {
  UVMS_OK = 0,
  UVMS_ERR_ARG = -1,        /**< null pointer or invalid argument */
  UVMS_ERR_NONFINITE = -2,  /**< NaN or infinity in an input or configuration value */
  UVMS_ERR_SINGULAR = -3,   /**< matrix singular or rank deficient */
  UVMS_ERR_RANGE = -4,      /**< value outside its physical or configured range */
  UVMS_ERR_SIZE = -5,       /**< count exceeds a compile-time maximum */
  UVMS_ERR_STATE = -6       /**< object used before a successful init */
} uvms_status_t;

/** Which point the position loop, the EE estimate and Cartesian trajectories refer to
 *  (SPEC §7.2, §8, §10): the vehicle CoM, or the system barycenter ("virtual manipulator"). */
typedef enum { UVMS_REF_VEHICLE = 0, UVMS_REF_BARYCENTER = 1 } uvms_reference_t;

/** @brief Name of a status code ("UVMS_OK", "UVMS_ERR_ARG", ...); never NULL.
 *  No preconditions. A value that is not a uvms_status_t enumerator gives "UVMS_ERR_UNKNOWN". */
const char *uvms_status_str(uvms_status_t status);

/* Scalar math in the real type: sqrtf etc. in the float build, sqrt etc. in double. No status:
   each returns what its libm function returns (NaN for NaN input, sqrt of a negative is NaN). */
#if UVMS_REAL_IS_FLOAT
#define UVMS_LIBM(fn) fn##f /* the libm function's float variant: sqrtf, sinf, ... */
#else
#define UVMS_LIBM(fn) fn
#endif
static inline uvms_real_t uvms_sqrt(uvms_real_t x) { return UVMS_LIBM(sqrt)(x); }
static inline uvms_real_t uvms_sin(uvms_real_t x) { return UVMS_LIBM(sin)(x); }
static inline uvms_real_t uvms_cos(uvms_real_t x) { return UVMS_LIBM(cos)(x); }
static inline uvms_real_t uvms_atan2(uvms_real_t y, uvms_real_t x) { return UVMS_LIBM(atan2)(y, x); }
static inline uvms_real_t uvms_fabs(uvms_real_t x) { return UVMS_LIBM(fabs)(x); }
/** @brief 1 if x is neither NaN nor infinite. */
static inline int uvms_isfinite(uvms_real_t x) { return isfinite(x) ? 1 : 0; }

/** @brief 1 if each of x[0..n) is finite (1 for n = 0). The firmware's one "all finite" test:
 *         every module checks arrays (vectors, joint sets, parameter lists) with it.
 *  @pre x points to n reals (not checked; x may be NULL only for n = 0). */
static inline int uvms_all_finite(const uvms_real_t *x, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (!uvms_isfinite(x[i])) return 0;
  return 1;
}

#ifdef __cplusplus
}
#endif
#endif /* UVMS_TYPES_H */
