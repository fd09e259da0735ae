// SPDX-License-Identifier: Apache-2.0
// The firmware's per-tick helpers (firmware/src/fw_fast.h, internal) against independent
// references: uvms_sincos against the C library's sin and cos evaluated in a wider type (long
// double for the double build, double for the float one), the record clear and copy against
// memset and memcpy, the finiteness probe against std::isfinite. Built twice (tests/firmware):
// as the host's firmware is (the record helpers are memset and memcpy there) and with
// UVMS_WORD_RECORD_LOOPS, the target's word loops, which the host's firmware does not use.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "fw_fast.h"

namespace {

using Real = uvms_real_t;
// The reference in a wider type than the controller's real.
using Wide = std::conditional_t<UVMS_REAL_IS_FLOAT, double, long double>;
static_assert(std::numeric_limits<Wide>::digits > std::numeric_limits<Real>::digits + 8,
              "the reference must resolve fractions of the real type's ulp");

// |got − exact| in units of the real type's ulp at the exact value: the spacing of the reals
// around it (below a power of two when the exact value lies below it, e.g. cos x just under
// 1), at least the smallest normal's, so that results near 0 are measured absolutely.
double UlpError(Real got, Wide exact) {
  const Real rounded = static_cast<Real>(exact);
  const Real mag = std::fabs(rounded);
  Real ulp = std::fabs(static_cast<Wide>(exact)) < static_cast<Wide>(mag)
                 ? mag - std::nextafter(mag, Real(0))
                 : std::nextafter(mag, std::numeric_limits<Real>::infinity()) - mag;
  ulp = std::max(ulp, std::numeric_limits<Real>::min());
  return static_cast<double>(std::fabs(static_cast<Wide>(got) - exact) / static_cast<Wide>(ulp));
}

struct SinCosError {
  double sin_ulp = 0.0, cos_ulp = 0.0;
  void Add(Real x) {
    Real s = 0, c = 0;
    uvms_sincos(x, &s, &c);
    const Wide xw = static_cast<Wide>(x);
    sin_ulp = std::max(sin_ulp, UlpError(s, std::sin(xw)));
    cos_ulp = std::max(cos_ulp, UlpError(c, std::cos(xw)));
  }
};

}  // namespace

TEST_CASE("SinCosWithinItsBoundOverTheReducedRange", "[fw_fast]") {
  // Every angle the tick passes (joint angles, 2πτ) lies in |x| ≤ 64, the reduced path. The
  // bound (fw_fast.h): in double, fdlibm's kernels with the reduced angle's tail word, below one
  // ulp; in float, the kernels without a tail: the reduced angle's rounding (half an ulp of r)
  // on top of the kernels' one ulp.
  const double bound_ulp = UVMS_REAL_IS_FLOAT ? 1.5 : 1.0;
  SinCosError e;
  const int n = 400001;
  for (int k = 0; k < n; ++k) e.Add(static_cast<Real>(-64.0 + 128.0 * k / (n - 1)));
  // Near the multiples of π/2, where the reduction cancels most digits.
  for (int j = -40; j <= 40; ++j) {
    const Real x0 = static_cast<Real>(j * 1.5707963267948966);
    Real x = x0;
    for (int step = 0; step < 64; ++step) x = std::nextafter(x, Real(100));
    for (int step = 0; step < 128; ++step) {
      e.Add(x);
      x = std::nextafter(x, Real(-100));
    }
  }
  // Small angles, and zero.
  for (Real x = Real(1e-30); x < Real(1); x *= Real(3)) {
    e.Add(x);
    e.Add(-x);
  }
  WARN("uvms_sincos max error over the sample: sin " << e.sin_ulp << " ulp, cos " << e.cos_ulp
                                                      << " ulp (bound " << bound_ulp << ")");
  CHECK(e.sin_ulp <= bound_ulp);
  CHECK(e.cos_ulp <= bound_ulp);
  Real s = 1, c = 0;
  uvms_sincos(Real(-0.0), &s, &c);
  CHECK(s == Real(0));
  CHECK(c == Real(1));
}

TEST_CASE("SinCosOutsideTheRangeIsTheLibrarys", "[fw_fast]") {
  for (Real x : {Real(64.5), Real(-100.25), Real(1e6), Real(-3e7)}) {
    Real s = 0, c = 0;
    uvms_sincos(x, &s, &c);
    CHECK(s == std::sin(x));
    CHECK(c == std::cos(x));
  }
  for (Real x : {std::numeric_limits<Real>::quiet_NaN(), std::numeric_limits<Real>::infinity(),
                 -std::numeric_limits<Real>::infinity()}) {
    Real s = 0, c = 0;
    uvms_sincos(x, &s, &c);
    CHECK(std::isnan(s));
    CHECK(std::isnan(c));
  }
}

TEST_CASE("RecordClearAndCopyAreMemsetAndMemcpy", "[fw_fast]") {
  // Every length 0..120 bytes at offsets 0 and 4 of a 16-byte aligned buffer: the word loops'
  // 16-byte, word and byte tails (with UVMS_WORD_RECORD_LOOPS); the bytes around the record
  // stay untouched.
  alignas(16) unsigned char src[128], dst[128], want[128];
  for (size_t i = 0; i < sizeof src; ++i) src[i] = static_cast<unsigned char>(37 * i + 11);
  for (size_t off : {size_t{0}, size_t{4}}) {
    for (size_t len = 0; len + off + 8 <= sizeof dst; ++len) {
      std::memset(dst, 0xA5, sizeof dst);
      std::memcpy(want, dst, sizeof want);
      std::memcpy(want + off, src, len);
      uvms_copy_record(dst + off, src, len);
      CHECK(std::memcmp(dst, want, sizeof dst) == 0);
      std::memset(want + off, 0, len);
      uvms_clear_record(dst + off, len);
      CHECK(std::memcmp(dst, want, sizeof dst) == 0);
    }
  }
}

TEST_CASE("NonfiniteProbeIsZeroExactlyWhenAllFinite", "[fw_fast]") {
  std::vector<Real> v = {Real(1), Real(-2.5), std::numeric_limits<Real>::max(),
                         -std::numeric_limits<Real>::max(), std::numeric_limits<Real>::denorm_min(),
                         Real(-0.0)};
  CHECK(uvms_nonfinite_probe(v.data(), v.size(), Real(0)) == Real(0));
  CHECK(uvms_all_finite_fast(v.data(), v.size()));
  for (Real bad : {std::numeric_limits<Real>::quiet_NaN(), std::numeric_limits<Real>::infinity(),
                   -std::numeric_limits<Real>::infinity()}) {
    for (size_t at = 0; at < v.size(); ++at) {
      std::vector<Real> w = v;
      w[at] = bad;
      CHECK_FALSE(uvms_all_finite_fast(w.data(), w.size()));
    }
  }
}
