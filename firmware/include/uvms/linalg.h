/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file linalg.h
 * @brief Small fixed-size linear algebra: 3-vectors, 3x3 rotations, quaternions, and an
 *        SPD solve and a Jacobi eigen-decomposition for the allocation's 6x6 Gram matrix.
 *
 * Conventions: a 3-vector is uvms_real_t[3]; a 3x3 matrix is uvms_real_t[9] in row-major order
 * (M[3*r + c]); a quaternion is (w, x, y, z), scalar first, and represents the rotation that
 * maps body coordinates to inertial coordinates (SPEC §2: R0 maps vehicle to inertial).
 * Output arrays may alias inputs unless a function says otherwise.
 */
#ifndef UVMS_LINALG_H
#define UVMS_LINALG_H

#include "uvms/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest matrix dimension uvms_spd_solve() accepts (the allocation's 6x6 H·Hᵀ). */
#define UVMS_SPD_MAX_N 8

/** @brief out = I (3x3).
 *  @pre out points to 9 writable reals (not checked: no status, no failure). */
void uvms_m3_identity(uvms_real_t out[9]);
/** @brief out = A·Bᵀ; out may alias A or B.
 *  @pre A, B, out point to 9 reals each (not checked). No status: NaN/inf in A or B
 *       propagate into out. */
void uvms_m3_mul_t(const uvms_real_t A[9], const uvms_real_t B[9], uvms_real_t out[9]);

/**
 * @brief Rotation matrix of a quaternion (w, x, y, z). The quaternion is normalised first.
 * @param[in]  q_wxyz quaternion, any non-zero norm
 * @param[out] R      3x3 rotation, row-major; identity on error
 * @pre q_wxyz and R are non-NULL (not checked: there is no UVMS_ERR_ARG return).
 * @retval UVMS_OK            R is the rotation of q/|q|
 * @retval UVMS_ERR_NONFINITE a component is NaN/inf; writes: R = identity
 * @retval UVMS_ERR_RANGE     |q|² ≤ 1e-12 (norm below 1e-6: no rotation can be inferred);
 *                            writes: R = identity
 */
uvms_status_t uvms_quat_to_rot(const uvms_real_t q_wxyz[4], uvms_real_t R[9]);

/**
 * @brief Unit quaternion (w ≥ 0) of a rotation matrix, by Shepperd's method (stable for
 *        every rotation, including near 180°).
 * @pre R is a rotation matrix, R and q_wxyz non-NULL (not checked). No status: a non-finite R
 *      gives a non-finite q; a finite non-orthogonal R gives the normalised quaternion of
 *      Shepperd's formula (no error is reported).
 */
void uvms_rot_to_quat(const uvms_real_t R[9], uvms_real_t q_wxyz[4]);

/**
 * @brief Rotation vector φ·e of a rotation matrix (SPEC §7.2, [42–43]), computed through the
 *        quaternion so that it is well defined at φ = 0 and accurate up to φ = π.
 * @param[in]  R        rotation matrix
 * @param[out] phi_e_rad rotation vector: axis e (unit) times angle φ in [0, π] [rad]
 * @pre as uvms_rot_to_quat (no status; a non-finite R gives a non-finite result).
 */
void uvms_rot_to_rotvec(const uvms_real_t R[9], uvms_real_t phi_e_rad[3]);

/**
 * @brief Rotation vector φ·e of E = R(q_d)·R(q)ᵀ (SPEC §7.2, [42–44]) from the two
 *        quaternions, through e = q_d ⊗ q̄: no rotation matrix, one square root, one atan2
 *        and one division; below φ = 0.0312 rad (the half-angle tangent 2^-6) one division and
 *        the series of atan(t)/t instead. Valid at φ = 0 and up to φ = π, like
 *        uvms_rot_to_rotvec of E; within two ulp of the exact rotation vector of the rounded
 *        e (tests/firmware/test_linalg.cpp).
 * @param[in]  qd_wxyz, q_wxyz desired and measured attitude, (w, x, y, z); the result does
 *                        not depend on their norms (q and −q, or 2·q, give the same) as long
 *                        as the squares of e's components neither overflow nor underflow:
 *                        |q_d|·|q| between 1e-15 and 1e15 in float, 1e-150 and 1e150 in
 *                        double (the controller's sensor check keeps |q| within 0.5–1.5).
 * @param[out] phi_e_rad rotation vector: axis e (unit) times angle φ in [0, π] [rad]
 * @pre no pointer NULL, norms within that range (not checked: beyond it the result is wrong,
 *      0 or off in angle). No status: a non-finite input gives a non-finite result.
 */
void uvms_quat_error_rotvec(const uvms_real_t qd_wxyz[4], const uvms_real_t q_wxyz[4],
                            uvms_real_t phi_e_rad[3]);

/** @brief Rotation about z by angle [rad].
 *  @pre R non-NULL (not checked). No status: a NaN/inf angle gives NaN in the four cos/sin
 *       entries (the z row and column stay exact). */
void uvms_rot_z(uvms_real_t angle_rad, uvms_real_t R[9]);

/**
 * @brief Solve A·X = B for symmetric positive definite A (n×n) by Cholesky, m right-hand sides.
 * @param[in]  n   dimension, 1..UVMS_SPD_MAX_N
 * @param[in]  A   n×n row-major, symmetric positive definite; not modified
 * @param[in]  m   number of right-hand sides (columns of B), ≥ 1
 * @param[in]  B   n×m row-major
 * @param[out] X   n×m row-major solution; zeros on error; may not alias A
 * @param[in]  rel_pivot_tol a pivot below rel_pivot_tol·max(diag A) is treated as zero
 * @pre Only the lower triangle of A is read. B is not checked for NaN/inf (it propagates into
 *      X with UVMS_OK). m ≤ 4·UVMS_SPD_MAX_N.
 * @retval UVMS_OK           X solves A·X = B
 * @retval UVMS_ERR_ARG      X, A or B is NULL, n ∉ 1..UVMS_SPD_MAX_N or m ∉ 1..4·UVMS_SPD_MAX_N;
 *                           writes: X[0..n·m) = 0 when X is non-NULL and n, m are in range,
 *                           nothing otherwise (the size of X is not known)
 * @retval UVMS_ERR_SINGULAR A not (numerically) positive definite: a pivot ≤
 *                           rel_pivot_tol·max(diag A) or ≤ 0, or a NaN/inf on the diagonal or
 *                           in the lower triangle; writes: X[0..n·m) = 0
 */
uvms_status_t uvms_spd_solve(size_t n, const uvms_real_t *A, size_t m, const uvms_real_t *B,
                             uvms_real_t *X, uvms_real_t rel_pivot_tol);

/** Sweep bound of uvms_sym_eig. Cyclic Jacobi converges quadratically once the off-diagonal
 *  part is small; a 6×6 matrix needs 5–8 sweeps in double, fewer in float. */
#define UVMS_SYM_EIG_MAX_SWEEPS 16

/** Unit roundoff-scale epsilon of the real type (FLT_EPSILON / DBL_EPSILON). */
#if UVMS_REAL_IS_FLOAT
#define UVMS_REAL_EPSILON UVMS_R(1.1920929e-7)
#else
#define UVMS_REAL_EPSILON UVMS_R(2.220446049250313e-16)
#endif

/**
 * @brief Eigen-decomposition A = V·diag(λ)·Vᵀ of a symmetric n×n matrix by the cyclic Jacobi
 *        method (Golub & Van Loan, Matrix Computations, §8.5.3): sweeps of plane rotations,
 *        each zeroing one off-diagonal pair, until off(A) ≤ ε·‖A‖_F (ε = UVMS_REAL_EPSILON,
 *        off = Frobenius norm of the off-diagonal part), at most UVMS_SYM_EIG_MAX_SWEEPS sweeps.
 *        No recursion; every loop is bounded by n ≤ UVMS_SPD_MAX_N or the sweep bound.
 * @param[in]  n       dimension, 1..UVMS_SPD_MAX_N
 * @param[in]  A       n×n row-major; read as symmetric (the upper triangle is mirrored); not
 *                     modified
 * @param[out] eigval  [n] eigenvalues, in no particular order; zeros on error
 * @param[out] V       n×n row-major, column k = unit eigenvector of eigval[k] (V orthogonal);
 *                     zeros on error
 * @param[out] sweeps  sweeps performed (may be NULL); 0 on error
 * @retval UVMS_OK            eigval, V hold the decomposition, *sweeps the sweeps done
 * @retval UVMS_ERR_ARG       A, eigval or V is NULL, or n ∉ 1..UVMS_SPD_MAX_N; writes:
 *                            *sweeps = 0, and when n is in range eigval[0..n) = 0 and
 *                            V[0..n²) = 0 (those that are non-NULL)
 * @retval UVMS_ERR_NONFINITE an entry of the upper triangle of A is NaN/inf, or ‖A‖_F²
 *                            overflows; writes: eigval = 0, V = 0, *sweeps = 0
 * @retval UVMS_ERR_SINGULAR  not converged within UVMS_SYM_EIG_MAX_SWEEPS; writes: eigval = 0,
 *                            V = 0, *sweeps = 0. Defensive: no finite input is known to reach
 *                            it (cyclic Jacobi converges quadratically; the bound makes the
 *                            loop provably finite), so no test can construct it.
 */
uvms_status_t uvms_sym_eig(size_t n, const uvms_real_t *A, uvms_real_t *eigval, uvms_real_t *V,
                           uint32_t *sweeps);

/* 3-vector and 3x3-times-vector operations: static inline because they sit on every hot path
   of the tick (a call per 3 flops costs more than the flops). out may alias the inputs.
   Preconditions of all of them: every pointer is non-NULL and points to 3 (vectors) or 9
   (matrices) reals; nothing is checked and there is no status: NaN/inf propagate. */
static inline void uvms_v3_set(uvms_real_t out[3], uvms_real_t x, uvms_real_t y, uvms_real_t z) {
  out[0] = x;
  out[1] = y;
  out[2] = z;
}

static inline void uvms_v3_copy(const uvms_real_t a[3], uvms_real_t out[3]) {
  out[0] = a[0];
  out[1] = a[1];
  out[2] = a[2];
}

static inline void uvms_v3_add(const uvms_real_t a[3], const uvms_real_t b[3], uvms_real_t out[3]) {
  out[0] = a[0] + b[0];
  out[1] = a[1] + b[1];
  out[2] = a[2] + b[2];
}

static inline void uvms_v3_sub(const uvms_real_t a[3], const uvms_real_t b[3], uvms_real_t out[3]) {
  out[0] = a[0] - b[0];
  out[1] = a[1] - b[1];
  out[2] = a[2] - b[2];
}

static inline void uvms_v3_scale(const uvms_real_t a[3], uvms_real_t s, uvms_real_t out[3]) {
  out[0] = s * a[0];
  out[1] = s * a[1];
  out[2] = s * a[2];
}

/** out += s·a */
static inline void uvms_v3_axpy(uvms_real_t s, const uvms_real_t a[3], uvms_real_t out[3]) {
  out[0] += s * a[0];
  out[1] += s * a[1];
  out[2] += s * a[2];
}

static inline uvms_real_t uvms_v3_dot(const uvms_real_t a[3], const uvms_real_t b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/** out = a × b */
static inline void uvms_v3_cross(const uvms_real_t a[3], const uvms_real_t b[3], uvms_real_t out[3]) {
  const uvms_real_t x = a[1] * b[2] - a[2] * b[1];
  const uvms_real_t y = a[2] * b[0] - a[0] * b[2];
  const uvms_real_t z = a[0] * b[1] - a[1] * b[0];
  out[0] = x;
  out[1] = y;
  out[2] = z;
}

static inline uvms_real_t uvms_v3_norm(const uvms_real_t a[3]) { return uvms_sqrt(uvms_v3_dot(a, a)); }

/** 1 if all three components are finite (uvms_all_finite of a 3-vector) */
static inline int uvms_v3_isfinite(const uvms_real_t a[3]) { return uvms_all_finite(a, 3); }

/** out = M·v for the 3×3 matrix M with M(r, c) = A[r·row_stride + c·col_stride]: A·v with
 *  strides (3, 1), Aᵀ·v with (1, 3). The strides are constants at every call, so the compiler
 *  unrolls it to the nine products. out may alias v. */
static inline void uvms_m3_strided_mul_v3(const uvms_real_t A[9], int row_stride, int col_stride,
                                          const uvms_real_t v[3], uvms_real_t out[3]) {
  uvms_real_t t[3];
  for (int r = 0; r < 3; ++r) {
    const uvms_real_t *row = A + r * row_stride;
    t[r] = row[0] * v[0] + row[col_stride] * v[1] + row[2 * col_stride] * v[2];
  }
  out[0] = t[0];
  out[1] = t[1];
  out[2] = t[2];
}

/** out = A·v; out may alias v. */
static inline void uvms_m3_mul_v3(const uvms_real_t A[9], const uvms_real_t v[3], uvms_real_t out[3]) {
  uvms_m3_strided_mul_v3(A, 3, 1, v, out);
}

/** out = Aᵀ·v; out may alias v. */
static inline void uvms_m3t_mul_v3(const uvms_real_t A[9], const uvms_real_t v[3], uvms_real_t out[3]) {
  uvms_m3_strided_mul_v3(A, 1, 3, v, out);
}

/** out = A·B; out may alias A or B. */
static inline void uvms_m3_mul(const uvms_real_t A[9], const uvms_real_t B[9], uvms_real_t out[9]) {
  uvms_real_t t[9];
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      t[3 * r + c] = A[3 * r] * B[c] + A[3 * r + 1] * B[3 + c] + A[3 * r + 2] * B[6 + c];
    }
  }
  for (int i = 0; i < 9; ++i) out[i] = t[i];
}

#ifdef __cplusplus
}
#endif
#endif /* UVMS_LINALG_H */
