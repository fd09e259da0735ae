/* SPDX-License-Identifier: Apache-2.0 */
/* fw_fast.h: internal helpers of the firmware's per-tick path (not part of the public API).
 *
 *   uvms_clear_record()  zeroing of a record: memset on a 64-bit host; on the target word
 *                        stores (newlib-nano's memset is byte-wise), STM on Thumb-2
 *   uvms_copy_record()   copy of a record: memcpy on a 64-bit host, LDM/STM on Thumb-2
 *   uvms_nonfinite_probe(), uvms_all_finite_fast()  finiteness without a branch per value
 *   uvms_sincos()        sin and cos of one angle with one argument reduction
 *   UVMS_FW_INLINE       a static function inlined into every caller
 *   UVMS_FW_WORK_AHEAD   independent long-latency work ahead of the chained work (hosts)
 *   uvms_motor_speed_fast(), uvms_motor_drive_fast()  the loop of one thruster, in two stages,
 *                        inlined into the tick, with the constants uvms_motor_init computed
 *                        once (thruster_tick.h)
 */
#ifndef UVMS_FW_FAST_H
#define UVMS_FW_FAST_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "uvms/types.h"

/* GCC at -O2+ turns zeroing and copy loops of a few floats into memset/memcpy calls, which
   newlib-nano runs byte by byte (≈ 4 instructions per byte on the Cortex-M4F); every file of
   the per-tick path includes this header first, so those loops stay word stores. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("no-tree-loop-distribute-patterns")
#endif
/* A static function of the per-tick path that is to be inlined into each caller even when the
   compiler's size heuristics would keep one copy (the call and its argument moves cost more
   than the copy). */
#if defined(__GNUC__)
#define UVMS_FW_INLINE static inline __attribute__((always_inline))
#else
#define UVMS_FW_INLINE static inline
#endif

/* UVMS_FW_WORK_AHEAD: 1 where the core executes out of order (a 64-bit host), 0 on the
   in-order Cortex-M4F. Where it is 1, three loops of the tick take their independent,
   long-latency work into a loop of its own ahead of the chained work that uses it; the same
   values either way (tests/firmware/test_work_ahead_order.cpp compares the two orders bit for
   bit):
     - the forward kinematics: every joint's sine and cosine, before the links' chained
       rotations (kinematics.c);
     - the Newton–Euler inward pass: every link's own loads (each with the square root and the
       division of its drag), before the recursion that sums them from the tip (dynamics.c);
     - the thruster loops: every thruster's desired speed (a square root and a division),
       before the speed and current loops that wait on it (controller.c, thruster_tick.h).
   On the host the polynomials, roots and divisions then overlap one another, which between
   the chained steps they did not (docs/BENCHMARKS.md, "The tick at 0.10.0" and "The tick below
   0.8 of an RNEA"); on the in-order target the split only adds the stores and loads of the
   values carried between the loops (+72, +190 and +200 instructions per tick, case VII).
   "The same values" needs the host's strict evaluation (no -ffp-contract=fast, which the
   target's toolchain sets): with fused multiply-adds, values stored between the loops could
   be fused differently from the one-loop order's. */
#ifndef UVMS_FW_WORK_AHEAD
#if UINTPTR_MAX > 0xFFFFFFFFu
#define UVMS_FW_WORK_AHEAD 1
#else
#define UVMS_FW_WORK_AHEAD 0
#endif
#endif

/* Fused multiply-add on the Cortex-M4F comes from -ffp-contract=fast in its toolchain file
   (cmake/arm-none-eabi-cortex-m4f.cmake), for every file built for the target. */

#if !defined(__GNUC__) || (UINTPTR_MAX > 0xFFFFFFFFu && !defined(UVMS_WORD_RECORD_LOOPS))
/* A 64-bit host (the SIL controller, the tests, the benchmarks), or a compiler without the
   extensions below: the C library's memset and memcpy. GCC writes a small record as a few
   16-byte moves, and on an x86-64 host calls the library for a larger one, where it would
   otherwise expand a microcoded `rep stos`/`rep movs` (-mstringop-strategy=libcall, from
   firmware/CMakeLists.txt: docs/BENCHMARKS.md, "The tick below 0.8 of an RNEA").
   Against the word loops below, the `rep` forms had been faster on an AMD EPYC (the tick
   1,014-1,019 ns instead of 1,058-1,079; docs/BENCHMARKS.md, "The tick at 0.9.0"). Same result
   as the loops; UVMS_WORD_RECORD_LOOPS selects them on such a host too (tests/firmware builds
   test_fw_fast.cpp both ways). */
static inline void uvms_clear_record(void *p, size_t bytes) { memset(p, 0, bytes); }
static inline void uvms_copy_record(void *dst, const void *src, size_t bytes) {
  memcpy(dst, src, bytes);
}
#else
/* A word that may alias any object (GCC/clang), so clearing a record of floats through it is
   defined. (GCC keeps the loops below as stores: loop-distribute-patterns is off, above.) */
typedef uint32_t __attribute__((may_alias)) uvms_alias_word_t;

/* Same effect as memset(p, 0, bytes) (all-zero bits are 0.0 and integer 0 in every field);
   p must be 4-byte aligned (every record cleared with it holds only 4- and 8-byte fields).
   On Thumb-2 (the Cortex-M4F) a record of 64 bytes or more is cleared 16 bytes per STMIA of
   four zero registers: one instruction where the word loop needs four stores and its share of
   the loop (GCC emits no STM/STRD for a zeroing loop by itself). */
static inline void uvms_clear_record(void *p, size_t bytes) {
  uvms_alias_word_t *w = (uvms_alias_word_t *)p;
  size_t nw = bytes / sizeof(uint32_t);
#if defined(__thumb2__)
  if (nw >= 16u) { /* below 64 bytes the word stores cost less than saving four registers */
    register uint32_t z0 __asm__("r4") = 0u;
    register uint32_t z1 __asm__("r5") = 0u;
    register uint32_t z2 __asm__("r6") = 0u;
    register uint32_t z3 __asm__("r8") = 0u; /* not r7: the Thumb frame pointer */
    for (; nw >= 16u; nw -= 16u) /* 64 bytes per iteration: the loop's own cost shared */
      __asm__ volatile("stmia %0!, {%1, %2, %3, %4}\n\t"
                       "stmia %0!, {%1, %2, %3, %4}\n\t"
                       "stmia %0!, {%1, %2, %3, %4}\n\t"
                       "stmia %0!, {%1, %2, %3, %4}"
                       : "+r"(w)
                       : "r"(z0), "r"(z1), "r"(z2), "r"(z3)
                       : "memory");
    for (; nw >= 4u; nw -= 4u)
      __asm__ volatile("stmia %0!, {%1, %2, %3, %4}"
                       : "+r"(w)
                       : "r"(z0), "r"(z1), "r"(z2), "r"(z3)
                       : "memory");
  }
#else
  for (; nw >= 4u; nw -= 4u, w += 4) {
    w[0] = 0u;
    w[1] = 0u;
    w[2] = 0u;
    w[3] = 0u;
  }
#endif
  for (; nw > 0u; --nw, ++w) *w = 0u;
  unsigned char *tail = (unsigned char *)p + (bytes & ~(size_t)(sizeof(uint32_t) - 1u));
  for (size_t b = 0; b < (bytes & (sizeof(uint32_t) - 1u)); ++b) tail[b] = 0u;
}

/* Same effect as memcpy(dst, src, bytes) for non-overlapping 4-byte aligned records. On
   Thumb-2, 16 bytes per LDMIA/STMIA pair (two instructions instead of eight). */
static inline void uvms_copy_record(void *dst, const void *src, size_t bytes) {
  uvms_alias_word_t *d = (uvms_alias_word_t *)dst;
  const uvms_alias_word_t *s = (const uvms_alias_word_t *)src;
  size_t nw = bytes / sizeof(uint32_t);
#if defined(__thumb2__)
  for (; nw >= 8u; nw -= 8u) /* 32 bytes per iteration */
    __asm__ volatile("ldmia %1!, {r4, r5, r6, r8}\n\tstmia %0!, {r4, r5, r6, r8}\n\t"
                     "ldmia %1!, {r4, r5, r6, r8}\n\tstmia %0!, {r4, r5, r6, r8}"
                     : "+r"(d), "+r"(s)
                     :
                     : "r4", "r5", "r6", "r8", "memory");
  for (; nw >= 4u; nw -= 4u)
    __asm__ volatile("ldmia %1!, {r4, r5, r6, r8}\n\tstmia %0!, {r4, r5, r6, r8}"
                     : "+r"(d), "+r"(s)
                     :
                     : "r4", "r5", "r6", "r8", "memory");
#else
  for (; nw >= 4u; nw -= 4u, d += 4, s += 4) {
    d[0] = s[0];
    d[1] = s[1];
    d[2] = s[2];
    d[3] = s[3];
  }
#endif
  for (; nw > 0u; --nw) *d++ = *s++;
  for (size_t b = (bytes / sizeof(uint32_t)) * sizeof(uint32_t); b < bytes; ++b)
    ((unsigned char *)dst)[b] = ((const unsigned char *)src)[b];
}
#endif

/* Σ 0·x_k + acc: 0·x is ±0 for a finite x and NaN for ±inf or NaN (IEEE 754; the compiler may
   not fold it without -ffinite-math-only), so with acc = 0 the sum is 0 exactly when every x_k
   is finite: one multiply-add per value instead of a compare and a branch each. */
static inline uvms_real_t uvms_nonfinite_probe(const uvms_real_t *x, size_t n, uvms_real_t acc) {
  for (size_t i = 0; i < n; ++i) acc += UVMS_R(0.0) * x[i];
  return acc;
}

/* uvms_all_finite and uvms_v3_isfinite (types.h, linalg.h) without a branch per value. */
static inline int uvms_all_finite_fast(const uvms_real_t *x, size_t n) {
  return uvms_nonfinite_probe(x, n, UVMS_R(0.0)) == UVMS_R(0.0);
}
static inline int uvms_v3_isfinite_fast(const uvms_real_t a[3]) {
  return uvms_all_finite_fast(a, 3);
}

/* sin and cos of x = j·π/2 + r from sr = sin r and cr = cos r, by the quadrant j mod 4:
   (sin, cos) = (s, c), (c, −s), (−s, −c), (−c, s). Shared by both uvms_sincos below. */
static inline void uvms_sincos_quadrant(int32_t j, uvms_real_t sr, uvms_real_t cr,
                                        uvms_real_t *s, uvms_real_t *c) {
  switch ((uint32_t)j & 3u) {
    case 0u: *s = sr; *c = cr; break;
    case 1u: *s = cr; *c = -sr; break;
    case 2u: *s = -sr; *c = -cr; break;
    default: *s = -cr; *c = sr; break;
  }
}

#if UVMS_REAL_IS_FLOAT
/* sin x and cos x in float with one reduction x = j·π/2 + r, |r| ≤ π/4 (Cody–Waite, π/2 split
   in three floats as in fdlibm's __ieee754_rem_pio2f: j·P1 and j·P2 are exact for |j| < 2^7),
   then fdlibm's float kernels __kernel_sinf/__kernel_cosf on r and the quadrant j mod 4
   (uvms_sincos_quadrant). |x| > 64 (never a joint angle or 2πτ),
   NaN and inf go to libm. Error below 1.5 ulp (no tail word for the reduced angle: its
   rounding adds to the kernels' one ulp; tests/firmware/test_fw_fast.cpp measures it). */
static inline void uvms_sincos(uvms_real_t x, uvms_real_t *s, uvms_real_t *c) {
  if (!(fabsf(x) <= 64.0f)) {
    *s = sinf(x);
    *c = cosf(x);
    return;
  }
  const float P1 = 1.5707855225e+00f;  /* 0x3fc90f80: first 17 bits of π/2 */
  const float P2 = 1.0804273188e-05f;  /* 0x37354400: next 14 bits */
  const float P3 = 6.0770943833e-11f;  /* 0x2e85a300: next bits */
  const float P3T = 6.1232342629e-17f; /* π/2 − P1 − P2 − P3 */
  const float two_over_pi = 6.3661974669e-01f;
  const int32_t j = (int32_t)(x * two_over_pi + (x >= 0.0f ? 0.5f : -0.5f));
  const float fj = (float)j;
  const float r = (((x - fj * P1) - fj * P2) - fj * P3) - fj * P3T;
  const float z = r * r;
  /* __kernel_sinf: sin r = r + r·z·(S1 + z·(S2 + … + z·S6)) */
  const float ps = 8.3333337680e-03f +
                   z * (-1.9841270114e-04f +
                        z * (2.7557314297e-06f + z * (-2.5050759689e-08f + z * 1.5896910177e-10f)));
  const float sr = r + (r * z) * (-1.6666667163e-01f + z * ps);
  /* __kernel_cosf: cos r = w + (((1 − w) − z/2) + z²·(C1 + z·(C2 + … + z·C6))), w = 1 − z/2 */
  const float pc =
      4.1666667908e-02f +
      z * (-1.3888889225e-03f +
           z * (2.4801587642e-05f +
                z * (-2.7557314297e-07f + z * (2.0875723372e-09f + z * -1.1359647598e-11f))));
  const float hz = 0.5f * z, w = 1.0f - hz;
  const float cr = w + (((1.0f - w) - hz) + (z * z) * pc);
  uvms_sincos_quadrant(j, sr, cr, s, c);
}
#else
/* sin x and cos x in double, the same way: x = j·π/2 + (r + y), r + y the reduced angle as a
   head and a tail, from π/2 split in three doubles as in fdlibm's __ieee754_rem_pio2 (its
   second reduction step: P1, P2 of 33 bits each, so that j·P1 and j·P2 are exact for
   |j| < 2^20, and P2T the rest), then fdlibm's kernels __kernel_sin(r, y) and
   __kernel_cos(r, y) (k_sin.c, k_cos.c: minimax polynomials of degree 13 and 14 on
   |r| ≤ π/4, with the tail's first-order term), and the quadrant as above. |x| > 64, NaN and
   inf go to libm. Error below one ulp (tests/firmware/test_fw_fast.cpp measures it against
   long double); one reduction for both, and inlined: libm's sin and cos were two calls and
   two reductions per joint. */
static inline void uvms_sincos(uvms_real_t x, uvms_real_t *s, uvms_real_t *c) {
  if (!(fabs(x) <= 64.0)) {
    *s = sin(x);
    *c = cos(x);
    return;
  }
  const double P1 = 1.57079632673412561417e+00;  /* 0x3FF921FB 54400000 */
  const double P2 = 6.07710050630396597660e-11;  /* 0x3DD0B461 1A600000 */
  const double P2T = 2.02226624879595063154e-21; /* 0x3BA3198A 2E037073 */
  const double two_over_pi = 6.36619772367581343076e-01; /* 0x3FE45F30 6DC9C883 */
  const int32_t j = (int32_t)(x * two_over_pi + (x >= 0.0 ? 0.5 : -0.5));
  const double fj = (double)j;
  /* x − j·P1 exactly, then fdlibm's second step: (head, tail) = x − j·(P1 + P2 + P2T). */
  const double t = x - fj * P1;
  const double w2 = fj * P2;
  const double h = t - w2;
  const double w = fj * P2T - ((t - h) - w2);
  const double r = h - w;
  const double y = (h - r) - w;
  const double z = r * r, zz = z * z, v = z * r;
  /* __kernel_sin: sin(r + y) = r − ((z·(y/2 − v·ps) − y) − v·S1), ps = S2 + z·S3 + … */
  const double ps = 8.33333333332248946124e-03 +
                    z * (-1.98412698298579493134e-04 + z * 2.75573137070700676789e-06) +
                    z * zz * (-2.50507602534068634195e-08 + z * 1.58969099521155010221e-10);
  const double sr = r - ((z * (0.5 * y - v * ps) - y) - v * -1.66666666666666324348e-01);
  /* __kernel_cos: cos(r + y) = u + (((1 − u) − z/2) + (z·q − r·y)), u = 1 − z/2,
     q = z·(C1 + z·(C2 + z·C3)) + z⁴·(C4 + z·(C5 + z·C6)) */
  const double q = z * (4.16666666666666019037e-02 +
                        z * (-1.38888888888741095749e-03 + z * 2.48015872894767294178e-05)) +
                   zz * zz * (-2.75573143513906633035e-07 +
                              z * (2.08757232129817482790e-09 + z * -1.13596475577881948265e-11));
  const double hz = 0.5 * z, u = 1.0 - hz;
  const double cr = u + (((1.0 - u) - hz) + (z * q - r * y));
  uvms_sincos_quadrant(j, sr, cr, s, c);
}
#endif

#endif /* UVMS_FW_FAST_H */
