/* SPDX-License-Identifier: Apache-2.0 */
/* linalg.c: fixed-size linear algebra (linalg.h). No allocation, bounded loops. */
#include "uvms/linalg.h"
#include "fw_fast.h"

void uvms_m3_identity(uvms_real_t out[9]) {
  for (int i = 0; i < 9; ++i) out[i] = UVMS_R(0.0);
  out[0] = out[4] = out[8] = UVMS_R(1.0);
}

void uvms_m3_mul_t(const uvms_real_t A[9], const uvms_real_t B[9], uvms_real_t out[9]) {
  uvms_real_t t[9];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      t[3 * r + c] =
          A[3 * r] * B[3 * c] + A[3 * r + 1] * B[3 * c + 1] + A[3 * r + 2] * B[3 * c + 2];
    }
  }
  for (int i = 0; i < 9; ++i) out[i] = t[i];
}

uvms_status_t uvms_quat_to_rot(const uvms_real_t q_wxyz[4], uvms_real_t R[9]) {
  uvms_m3_identity(R);
  if (!uvms_all_finite(q_wxyz, 4)) return UVMS_ERR_NONFINITE;
  const uvms_real_t n2 = q_wxyz[0] * q_wxyz[0] + q_wxyz[1] * q_wxyz[1] +
                         q_wxyz[2] * q_wxyz[2] + q_wxyz[3] * q_wxyz[3];
  if (!(n2 > UVMS_R(1e-12))) return UVMS_ERR_RANGE;
  const uvms_real_t s = UVMS_R(2.0) / n2;
  const uvms_real_t w = q_wxyz[0], x = q_wxyz[1], y = q_wxyz[2], z = q_wxyz[3];
  R[0] = UVMS_R(1.0) - s * (y * y + z * z);
  R[1] = s * (x * y - w * z);
  R[2] = s * (x * z + w * y);
  R[3] = s * (x * y + w * z);
  R[4] = UVMS_R(1.0) - s * (x * x + z * z);
  R[5] = s * (y * z - w * x);
  R[6] = s * (x * z - w * y);
  R[7] = s * (y * z + w * x);
  R[8] = UVMS_R(1.0) - s * (x * x + y * y);
  return UVMS_OK;
}

void uvms_rot_to_quat(const uvms_real_t R[9], uvms_real_t q_wxyz[4]) {
  /* Shepperd: pick the largest of 4w², 4x², 4y², 4z² to divide by (one division, its
     reciprocal multiplied). */
  const uvms_real_t tr = R[0] + R[4] + R[8];
  uvms_real_t w, x, y, z;
  if (tr >= R[0] && tr >= R[4] && tr >= R[8]) {
    const uvms_real_t s = uvms_sqrt(UVMS_R(1.0) + tr) * UVMS_R(2.0); /* s = 4w */
    const uvms_real_t inv = UVMS_R(1.0) / s;
    w = UVMS_R(0.25) * s;
    x = (R[7] - R[5]) * inv;
    y = (R[2] - R[6]) * inv;
    z = (R[3] - R[1]) * inv;
  } else if (R[0] >= R[4] && R[0] >= R[8]) {
    const uvms_real_t s = uvms_sqrt(UVMS_R(1.0) + R[0] - R[4] - R[8]) * UVMS_R(2.0); /* 4x */
    const uvms_real_t inv = UVMS_R(1.0) / s;
    w = (R[7] - R[5]) * inv;
    x = UVMS_R(0.25) * s;
    y = (R[1] + R[3]) * inv;
    z = (R[2] + R[6]) * inv;
  } else if (R[4] >= R[8]) {
    const uvms_real_t s = uvms_sqrt(UVMS_R(1.0) + R[4] - R[0] - R[8]) * UVMS_R(2.0); /* 4y */
    const uvms_real_t inv = UVMS_R(1.0) / s;
    w = (R[2] - R[6]) * inv;
    x = (R[1] + R[3]) * inv;
    y = UVMS_R(0.25) * s;
    z = (R[5] + R[7]) * inv;
  } else {
    const uvms_real_t s = uvms_sqrt(UVMS_R(1.0) + R[8] - R[0] - R[4]) * UVMS_R(2.0); /* 4z */
    const uvms_real_t inv = UVMS_R(1.0) / s;
    w = (R[3] - R[1]) * inv;
    x = (R[2] + R[6]) * inv;
    y = (R[5] + R[7]) * inv;
    z = UVMS_R(0.25) * s;
  }
  /* Normalised (R orthonormal only to rounding), sign chosen so that w ≥ 0. */
  const uvms_real_t n = uvms_sqrt(w * w + x * x + y * y + z * z);
  const uvms_real_t k = ((w < UVMS_R(0.0)) ? UVMS_R(-1.0) : UVMS_R(1.0)) / n;
  q_wxyz[0] = k * w;
  q_wxyz[1] = k * x;
  q_wxyz[2] = k * y;
  q_wxyz[3] = k * z;
}

/* t² below which rotvec_of_quat takes φ/|v| from the series of atan(t)/t: t = |v|/|w| ≤ 2^-6,
   an angle φ = 2·atan(t) below 0.0312 rad (1.79°), the range of a vehicle holding its
   attitude. */
#define ROTVEC_SERIES_T2 (UVMS_R(1.0) / UVMS_R(4096.0))

/* atan(t)/t = 1 − t²/3 + t⁴/5 − t⁶/7 + t⁸/9 − … for t² ≤ ROTVEC_SERIES_T2 = 2^-12: the first
   term left out, t¹⁰/11, is below 2^-63 of the sum, under half an ulp of double. */
static uvms_real_t atan_over_t(uvms_real_t t2) {
  return UVMS_R(1.0) +
         t2 * (UVMS_R(-1.0) / UVMS_R(3.0) +
               t2 * (UVMS_R(1.0) / UVMS_R(5.0) +
                     t2 * (UVMS_R(-1.0) / UVMS_R(7.0) + t2 * (UVMS_R(1.0) / UVMS_R(9.0)))));
}

/* φ·e of the rotation of the quaternion (w, x, y, z), of any norm (within the range linalg.h
   states for uvms_quat_error_rotvec) and either sign: |v| = |q|·sin(φ/2) and |w| = |q|·cos(φ/2)
   for the representative with w ≥ 0, so φ = 2·atan2(|v|, |w|) in [0, π] and φ·e = ±(φ/|v|)·v,
   the sign of w (either at w = 0, φ = π). |v| = 0 only at φ = 0, where φ·e = 0; below that
   φ/|v| → 2/|w| without cancellation (atan2 of a small ratio is the ratio). For a small angle
   (t = |v|/|w| ≤ 2^-6), φ/|v| = (2/|w|)·atan(t)/t from its series (atan_over_t): one division,
   no square root and no atan2 (both routes within two ulp of long double on either side of
   the switch: tests/firmware/test_linalg.cpp). */
static void rotvec_of_quat(uvms_real_t w, uvms_real_t x, uvms_real_t y, uvms_real_t z,
                           uvms_real_t phi_e_rad[3]) {
  const uvms_real_t s2 = x * x + y * y + z * z, w2 = w * w;
  uvms_real_t k;
  /* The series for t² < 2^-12, which also gives φ·e = (2/|w|)·v where the squares of v
     underflowed (s2 = 0), and +0 or −0 (the sign of w) at φ = 0; w = 0, an overflowed s2
     and NaN take the general route. t² is formed as (s2/|w|)/|w|, which stays finite for every
     finite w. */
  if (s2 < ROTVEC_SERIES_T2 * w2) {
    const uvms_real_t inv_aw = UVMS_R(1.0) / uvms_fabs(w);
    const uvms_real_t phi_over_s = UVMS_R(2.0) * inv_aw * atan_over_t((s2 * inv_aw) * inv_aw);
    k = (w < UVMS_R(0.0)) ? -phi_over_s : phi_over_s;
  } else {
    const uvms_real_t s = uvms_sqrt(s2);
    const uvms_real_t phi = UVMS_R(2.0) * uvms_atan2(s, uvms_fabs(w));
    k = (s > UVMS_R(0.0)) ? ((w < UVMS_R(0.0)) ? -phi : phi) / s : UVMS_R(0.0);
  }
  phi_e_rad[0] = k * x;
  phi_e_rad[1] = k * y;
  phi_e_rad[2] = k * z;
}

void uvms_rot_to_rotvec(const uvms_real_t R[9], uvms_real_t phi_e_rad[3]) {
  uvms_real_t q[4];
  uvms_rot_to_quat(R, q); /* unit, w = cos(φ/2) ≥ 0 */
  rotvec_of_quat(q[0], q[1], q[2], q[3], phi_e_rad);
}

void uvms_quat_error_rotvec(const uvms_real_t qd_wxyz[4], const uvms_real_t q_wxyz[4],
                            uvms_real_t phi_e_rad[3]) {
  /* e = q_d ⊗ q̄, q̄ = (w, −v) the conjugate: the rotation of e/|e| is R(q_d)·R(q)ᵀ = E, and
     the norm |e| = |q_d|·|q| is a scale neither the angle nor the axis below depends on. With
     v_d, v the vector parts: e_w = w_d·w + v_d·v, e_v = w·v_d − w_d·v − v_d × v. */
  const uvms_real_t wd = qd_wxyz[0], xd = qd_wxyz[1], yd = qd_wxyz[2], zd = qd_wxyz[3];
  const uvms_real_t w = q_wxyz[0], x = q_wxyz[1], y = q_wxyz[2], z = q_wxyz[3];
  const uvms_real_t ew = wd * w + xd * x + yd * y + zd * z;
  const uvms_real_t ex = w * xd - wd * x - (yd * z - zd * y);
  const uvms_real_t ey = w * yd - wd * y - (zd * x - xd * z);
  const uvms_real_t ez = w * zd - wd * z - (xd * y - yd * x);
  rotvec_of_quat(ew, ex, ey, ez, phi_e_rad);
}

void uvms_rot_z(uvms_real_t angle_rad, uvms_real_t R[9]) {
  const uvms_real_t c = uvms_cos(angle_rad), s = uvms_sin(angle_rad);
  uvms_m3_identity(R);
  R[0] = c;
  R[1] = -s;
  R[3] = s;
  R[4] = c;
}

uvms_status_t uvms_spd_solve(size_t n, const uvms_real_t *A, size_t m, const uvms_real_t *B,
                             uvms_real_t *X, uvms_real_t rel_pivot_tol) {
  if (X == NULL) return UVMS_ERR_ARG;
  if (n >= 1 && n <= UVMS_SPD_MAX_N && m >= 1 && m <= UVMS_SPD_MAX_N * 4) {
    for (size_t i = 0; i < n * m; ++i) X[i] = UVMS_R(0.0);
  }
  if (A == NULL || B == NULL || n < 1 || n > UVMS_SPD_MAX_N || m < 1 ||
      m > UVMS_SPD_MAX_N * 4) {
    return UVMS_ERR_ARG;
  }
  uvms_real_t L[UVMS_SPD_MAX_N * UVMS_SPD_MAX_N] = {0};
  uvms_real_t dmax = UVMS_R(0.0);
  for (size_t i = 0; i < n; ++i) {
    if (!uvms_isfinite(A[i * n + i])) return UVMS_ERR_SINGULAR;
    if (A[i * n + i] > dmax) dmax = A[i * n + i];
  }
  const uvms_real_t tol = rel_pivot_tol * dmax;
  /* Cholesky A = L·Lᵀ, lower triangular L. */
  for (size_t j = 0; j < n; ++j) {
    uvms_real_t d = A[j * n + j];
    for (size_t k = 0; k < j; ++k) d -= L[j * n + k] * L[j * n + k];
    if (!(d > tol) || !(d > UVMS_R(0.0))) return UVMS_ERR_SINGULAR;
    const uvms_real_t ljj = uvms_sqrt(d);
    L[j * n + j] = ljj;
    for (size_t i = j + 1; i < n; ++i) {
      uvms_real_t s = A[i * n + j];
      for (size_t k = 0; k < j; ++k) s -= L[i * n + k] * L[j * n + k];
      L[i * n + j] = s / ljj;
    }
  }
  /* For each column: forward solve L·y = b, then back solve Lᵀ·x = y. */
  for (size_t c = 0; c < m; ++c) {
    uvms_real_t y[UVMS_SPD_MAX_N];
    for (size_t i = 0; i < n; ++i) {
      uvms_real_t s = B[i * m + c];
      for (size_t k = 0; k < i; ++k) s -= L[i * n + k] * y[k];
      y[i] = s / L[i * n + i];
    }
    for (size_t ii = n; ii-- > 0;) {
      uvms_real_t s = y[ii];
      for (size_t k = ii + 1; k < n; ++k) s -= L[k * n + ii] * X[k * m + c];
      X[ii * m + c] = s / L[ii * n + ii];
    }
  }
  return UVMS_OK;
}

/* Frobenius norm of the strictly off-diagonal part of the n×n matrix W, squared. */
static uvms_real_t off_diag_sq(size_t n, const uvms_real_t *W) {
  uvms_real_t s = UVMS_R(0.0);
  for (size_t p = 0; p < n && p < UVMS_SPD_MAX_N; ++p) {
    for (size_t q = 0; q < n && q < UVMS_SPD_MAX_N; ++q) {
      if (p != q) s += W[p * n + q] * W[p * n + q];
    }
  }
  return s;
}

uvms_status_t uvms_sym_eig(size_t n, const uvms_real_t *A, uvms_real_t *eigval, uvms_real_t *V,
                           uint32_t *sweeps) {
  if (sweeps != NULL) *sweeps = 0u;
  const int n_ok = (n >= 1 && n <= UVMS_SPD_MAX_N);
  if (n_ok && eigval != NULL) {
    for (size_t i = 0; i < n; ++i) eigval[i] = UVMS_R(0.0);
  }
  if (n_ok && V != NULL) {
    for (size_t i = 0; i < n * n; ++i) V[i] = UVMS_R(0.0);
  }
  if (!n_ok || A == NULL || eigval == NULL || V == NULL) return UVMS_ERR_ARG;

  /* Working copy W (symmetrised from the upper triangle) and V = I. */
  uvms_real_t W[UVMS_SPD_MAX_N * UVMS_SPD_MAX_N] = {0};
  uvms_real_t Vw[UVMS_SPD_MAX_N * UVMS_SPD_MAX_N] = {0};
  uvms_real_t fro_sq = UVMS_R(0.0);
  for (size_t p = 0; p < n; ++p) {
    for (size_t q = 0; q < n; ++q) {
      const uvms_real_t a = (q >= p) ? A[p * n + q] : A[q * n + p];
      if (!uvms_isfinite(a)) return UVMS_ERR_NONFINITE;
      W[p * n + q] = a;
      fro_sq += a * a;
    }
    Vw[p * n + p] = UVMS_R(1.0);
  }
  if (!uvms_isfinite(fro_sq)) return UVMS_ERR_NONFINITE;
  /* Stop when off(W) ≤ ε·‖A‖_F (rotations preserve ‖W‖_F). */
  const uvms_real_t tol_sq = UVMS_REAL_EPSILON * UVMS_REAL_EPSILON * fro_sq;

  uint32_t done = 0u;
  int converged = (off_diag_sq(n, W) <= tol_sq);
  for (uint32_t sweep = 0u; sweep < UVMS_SYM_EIG_MAX_SWEEPS && !converged; ++sweep) {
    for (size_t p = 0; p + 1 < n; ++p) {
      for (size_t q = p + 1; q < n; ++q) {
        const uvms_real_t apq = W[p * n + q];
        if (apq == UVMS_R(0.0)) continue;
        /* Rotation J(p, q, θ) with t = tan θ the smaller root of t² + 2τt − 1 = 0,
           τ = (a_qq − a_pp)/(2·a_pq), so that (JᵀWJ)_pq = 0 (GvL Algorithm 8.5.1). For huge
           |τ| (τ² would overflow) t ≈ 1/(2τ). */
        const uvms_real_t tau = (W[q * n + q] - W[p * n + p]) / (UVMS_R(2.0) * apq);
        const uvms_real_t abs_tau = uvms_fabs(tau);
        uvms_real_t t = (abs_tau > UVMS_R(1e15))
                            ? UVMS_R(0.5) / abs_tau
                            : UVMS_R(1.0) / (abs_tau + uvms_sqrt(UVMS_R(1.0) + tau * tau));
        if (tau < UVMS_R(0.0)) t = -t;
        const uvms_real_t c = UVMS_R(1.0) / uvms_sqrt(UVMS_R(1.0) + t * t);
        const uvms_real_t s = t * c;
        /* W ← W·J (columns p, q), then W ← Jᵀ·W (rows p, q); V ← V·J. */
        for (size_t k = 0; k < n; ++k) {
          const uvms_real_t wkp = W[k * n + p], wkq = W[k * n + q];
          W[k * n + p] = c * wkp - s * wkq;
          W[k * n + q] = s * wkp + c * wkq;
          const uvms_real_t vkp = Vw[k * n + p], vkq = Vw[k * n + q];
          Vw[k * n + p] = c * vkp - s * vkq;
          Vw[k * n + q] = s * vkp + c * vkq;
        }
        for (size_t k = 0; k < n; ++k) {
          const uvms_real_t wpk = W[p * n + k], wqk = W[q * n + k];
          W[p * n + k] = c * wpk - s * wqk;
          W[q * n + k] = s * wpk + c * wqk;
        }
        W[p * n + q] = UVMS_R(0.0); /* zero in exact arithmetic: set it so */
        W[q * n + p] = UVMS_R(0.0);
      }
    }
    done = sweep + 1u;
    converged = (off_diag_sq(n, W) <= tol_sq);
  }
  if (!converged) return UVMS_ERR_SINGULAR; /* outputs stay zero */
  for (size_t i = 0; i < n; ++i) eigval[i] = W[i * n + i];
  for (size_t i = 0; i < n * n; ++i) V[i] = Vw[i];
  if (sweeps != NULL) *sweeps = done;
  return UVMS_OK;
}
