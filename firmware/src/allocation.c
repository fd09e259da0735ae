/* SPDX-License-Identifier: Apache-2.0 */
/* allocation.c: thrust allocation by pseudoinverse, SPEC §7.3 [33–39] (allocation.h).
 * No allocation, no file-scope mutable state; every loop is bounded by UVMS_MAX_THRUSTERS or
 * UVMS_ALLOC_WRENCH_DIM (loops over the n used thrusters also test j < UVMS_MAX_THRUSTERS so
 * that the bound is visible without knowing that init validated n). */
#include "uvms/allocation.h"

#include <string.h>

#include "uvms/linalg.h"
#include "fw_fast.h"

/* The usable set is a bit mask in a uint32_t; the 6×6 Gram matrix goes through uvms_sym_eig;
 * rank and the axis mask fit a uint8_t. */
_Static_assert(UVMS_MAX_THRUSTERS >= 6 && UVMS_MAX_THRUSTERS <= 31,
               "usable_mask holds one bit per thruster");
_Static_assert(UVMS_ALLOC_WRENCH_DIM <= UVMS_SPD_MAX_N, "uvms_sym_eig dimension limit");
_Static_assert(UVMS_ALLOC_WRENCH_DIM <= 8, "uncontrollable_axes holds one bit per axis");
_Static_assert(UVMS_SYM_EIG_MAX_SWEEPS <= 255, "eig_sweeps is a uint8_t");

/* Mask with bits 0..n-1 set; n ≤ UVMS_MAX_THRUSTERS (= 8) < 32, so the shift is defined. */
static uint32_t all_thrusters_mask(size_t n) {
  return (n >= UVMS_MAX_THRUSTERS) ? (uint32_t)((1u << UVMS_MAX_THRUSTERS) - 1u)
                                   : (uint32_t)((1u << (uint32_t)n) - 1u);
}

/* A thruster count clamped to UVMS_MAX_THRUSTERS: what every loop and index over the
   thrusters uses, so that a corrupted count in RAM cannot index past H, H⁺ or the thrusts
   (init validates it; uvms_ctrl_step also rejects a corrupted instance before use). */
static size_t thruster_count(size_t n) { return (n < UVMS_MAX_THRUSTERS) ? n : UVMS_MAX_THRUSTERS; }

static int mask_has(uint32_t mask, size_t j) { return ((mask >> (uint32_t)j) & 1u) != 0u; }

static void zero_thrusts(uvms_real_t *out) {
  if (out == NULL) return;
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) out[j] = UVMS_R(0.0);
}

void uvms_thruster_geometry_paper(uvms_thruster_geometry_t *geom) {
  /* SPEC §3.4: a_j [m] from the vehicle CoM and u_j, both in the vehicle frame. Four surge
   * thrusters at the stern corners, two heave and two sway thrusters slightly forward. */
  static const uvms_real_t kPosition_m[8][3] = {
      {UVMS_R(-0.5), UVMS_R(0.5), UVMS_R(0.5)},  {UVMS_R(-0.5), UVMS_R(-0.5), UVMS_R(0.5)},
      {UVMS_R(-0.5), UVMS_R(0.5), UVMS_R(-0.5)}, {UVMS_R(-0.5), UVMS_R(-0.5), UVMS_R(-0.5)},
      {UVMS_R(0.1), UVMS_R(0.5), UVMS_R(0.0)},   {UVMS_R(0.1), UVMS_R(-0.5), UVMS_R(0.0)},
      {UVMS_R(0.1), UVMS_R(0.0), UVMS_R(0.5)},   {UVMS_R(0.1), UVMS_R(0.0), UVMS_R(-0.5)}};
  static const uvms_real_t kDirection[8][3] = {
      {UVMS_R(1.0), UVMS_R(0.0), UVMS_R(0.0)}, {UVMS_R(1.0), UVMS_R(0.0), UVMS_R(0.0)},
      {UVMS_R(1.0), UVMS_R(0.0), UVMS_R(0.0)}, {UVMS_R(1.0), UVMS_R(0.0), UVMS_R(0.0)},
      {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(1.0)}, {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(1.0)},
      {UVMS_R(0.0), UVMS_R(1.0), UVMS_R(0.0)}, {UVMS_R(0.0), UVMS_R(1.0), UVMS_R(0.0)}};
  if (geom == NULL) return;
  memset(geom, 0, sizeof(*geom));
  geom->num_thrusters = 8;
  for (size_t j = 0; j < 8 && j < UVMS_MAX_THRUSTERS; ++j) {
    uvms_v3_copy(kPosition_m[j], geom->position_m[j]);
    uvms_v3_copy(kDirection[j], geom->direction[j]);
  }
}

/* H [33–37] from the (validated, normalised) geometry: row-major 6 × n, column j =
 * (u_j; a_j × u_j), or zero when j is not in mask. Entries past 6·n stay zero. */
static void build_H(const uvms_thruster_geometry_t *geom, uint32_t mask,
                    uvms_real_t H[UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS]) {
  const size_t n = thruster_count(geom->num_thrusters);
  for (size_t i = 0; i < UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS; ++i) H[i] = UVMS_R(0.0);
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    if (!mask_has(mask, j)) continue;
    uvms_real_t axu[3];
    uvms_v3_cross(geom->position_m[j], geom->direction[j], axu);
    for (size_t r = 0; r < 3; ++r) {
      H[r * n + j] = geom->direction[j][r];
      H[(r + 3) * n + j] = axu[r];
    }
  }
}

/*
 * H⁺ of the usable columns, rank-revealing (allocation.h): H_u = H with the unusable columns
 * zero, G = H_u·H_uᵀ = V·Λ·Vᵀ (Jacobi), M = V·Λ⁺·Vᵀ with the eigenvalues above
 * UVMS_ALLOC_REL_EIG_TOL·λ_max inverted and the others dropped, H⁺ = H_uᵀ·M. At full rank
 * M = G⁻¹ and this is [38]. A zero column of H_u gives an exactly zero row of H⁺. The dropped
 * eigenvectors span the lost wrench directions; axis i is lost when Σ_{k dropped} V_ik²
 * (squared distance of e_i from the range of H_u) exceeds UVMS_ALLOC_AXIS_RESIDUAL_TOL.
 * On failure H_pinv is all zeros, rank 0, every axis lost and ready = 0.
 */
static uvms_status_t alloc_compute_pinv(uvms_alloc_t *alloc) {
  enum { W = UVMS_ALLOC_WRENCH_DIM };
  const size_t n = thruster_count(alloc->geom.num_thrusters);
  uvms_real_t Hu[W * UVMS_MAX_THRUSTERS];
  uvms_real_t G[W * W] = {0};
  uvms_real_t lambda[W] = {0};
  uvms_real_t V[W * W] = {0};
  uvms_real_t M[W * W] = {0};

  alloc->ready = 0;
  alloc->rank = 0u;
  alloc->uncontrollable_axes = (uint8_t)UVMS_AXIS_ALL;
  alloc->eig_sweeps = 0u;
  alloc->pinv_computations += 1u;
  for (size_t i = 0; i < UVMS_MAX_THRUSTERS * W; ++i) alloc->H_pinv[i] = UVMS_R(0.0);

  build_H(&alloc->geom, alloc->usable_mask, Hu);
  for (size_t r = 0; r < W; ++r) {
    for (size_t c = r; c < W; ++c) {
      uvms_real_t s = UVMS_R(0.0);
      for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) s += Hu[r * n + j] * Hu[c * n + j];
      G[r * W + c] = s;
      G[c * W + r] = s;
    }
  }
  uint32_t sweeps = 0u;
  if (uvms_sym_eig(W, G, lambda, V, &sweeps) != UVMS_OK) {
    /* Finite geometry never gets here (the sweep bound is generous); if it did, no thrust
       can be trusted: not ready, every axis lost. */
    alloc->pinv_status = UVMS_ERR_SINGULAR;
    return UVMS_ERR_SINGULAR;
  }
  uvms_real_t lambda_max = UVMS_R(0.0);
  for (size_t k = 0; k < W; ++k) {
    if (lambda[k] > lambda_max) lambda_max = lambda[k];
  }
  /* λ > 0 too: with no usable thruster G = 0, λ_max = 0 and nothing is kept (rank 0). */
  const uvms_real_t threshold = UVMS_ALLOC_REL_EIG_TOL * lambda_max;
  uvms_real_t lost_sq[W] = {0}; /* Σ_{k dropped} V_ik² per axis i */
  unsigned rank = 0u;
  for (size_t k = 0; k < W; ++k) {
    const int keep = (lambda[k] > threshold) && (lambda[k] > UVMS_R(0.0));
    if (keep) {
      ++rank;
      const uvms_real_t inv = UVMS_R(1.0) / lambda[k];
      for (size_t r = 0; r < W; ++r) {
        for (size_t c = 0; c < W; ++c) M[r * W + c] += V[r * W + k] * inv * V[c * W + k];
      }
    } else {
      for (size_t i = 0; i < W; ++i) lost_sq[i] += V[i * W + k] * V[i * W + k];
    }
  }
  unsigned axes = 0u;
  for (size_t i = 0; i < W; ++i) {
    if (lost_sq[i] > UVMS_ALLOC_AXIS_RESIDUAL_TOL) axes |= 1u << i;
  }
  /* H⁺ = H_uᵀ·M: H_pinv[j·6 + r] = Σ_c H_u[c][j]·M[c][r]. */
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    if (!mask_has(alloc->usable_mask, j)) continue; /* exact zero row */
    for (size_t r = 0; r < W; ++r) {
      uvms_real_t s = UVMS_R(0.0);
      for (size_t c = 0; c < W; ++c) s += Hu[c * n + j] * M[c * W + r];
      if (!uvms_isfinite(s)) {
        for (size_t i = 0; i < UVMS_MAX_THRUSTERS * W; ++i) alloc->H_pinv[i] = UVMS_R(0.0);
        alloc->pinv_status = UVMS_ERR_SINGULAR;
        return UVMS_ERR_SINGULAR;
      }
      alloc->H_pinv[j * W + r] = s;
    }
  }
  alloc->rank = (uint8_t)rank;
  alloc->uncontrollable_axes = (uint8_t)axes;
  alloc->eig_sweeps = (uint8_t)sweeps;
  alloc->pinv_status = UVMS_OK;
  alloc->ready = 1;
  return UVMS_OK;
}

/* Leave alloc in its defined "refused" state: all zero, not initialised, not ready. */
static uvms_status_t alloc_fail(uvms_alloc_t *alloc, uvms_status_t st) {
  memset(alloc, 0, sizeof(*alloc));
  alloc->pinv_status = st;
  alloc->uncontrollable_axes = (uint8_t)UVMS_AXIS_ALL;
  return st;
}

uvms_status_t uvms_alloc_init(uvms_alloc_t *alloc, const uvms_thruster_geometry_t *geom) {
  if (alloc == NULL) return UVMS_ERR_ARG;
  if (geom == NULL) return alloc_fail(alloc, UVMS_ERR_ARG);
  /* Work from a copy: geom may be &alloc->geom (re-initialisation), which is cleared next. */
  const uvms_thruster_geometry_t copy = *geom;
  const uvms_thruster_geometry_t *const src = &copy;
  memset(alloc, 0, sizeof(*alloc));
  if (src->num_thrusters == 0) return alloc_fail(alloc, UVMS_ERR_ARG);
  if (src->num_thrusters > UVMS_MAX_THRUSTERS) return alloc_fail(alloc, UVMS_ERR_SIZE);
  const size_t n = src->num_thrusters;

  /* Validate everything before keeping anything. */
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    if (!uvms_v3_isfinite_fast(src->position_m[j]) || !uvms_v3_isfinite_fast(src->direction[j])) {
      return alloc_fail(alloc, UVMS_ERR_NONFINITE);
    }
    /* A finite vector can still overflow the norm (components ~1e20 in float). */
    const uvms_real_t norm = uvms_v3_norm(src->direction[j]);
    if (!uvms_isfinite(norm)) return alloc_fail(alloc, UVMS_ERR_NONFINITE);
    if (!(norm >= UVMS_ALLOC_MIN_DIRECTION_NORM)) return alloc_fail(alloc, UVMS_ERR_RANGE);
  }

  /* Keep a copy with unit directions; slots ≥ n stay zero. */
  alloc->geom.num_thrusters = n;
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    uvms_v3_copy(src->position_m[j], alloc->geom.position_m[j]);
    uvms_v3_scale(src->direction[j], UVMS_R(1.0) / uvms_v3_norm(src->direction[j]),
                  alloc->geom.direction[j]);
  }

  /* H [33–37] must be finite (a × u of huge finite positions can overflow). */
  {
    uvms_real_t H[UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS];
    build_H(&alloc->geom, all_thrusters_mask(n), H);
    if (!uvms_all_finite_fast(H, UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS))
      return alloc_fail(alloc, UVMS_ERR_NONFINITE);
  }

  /* H⁺ over all thrusters [38]; the full set must span every wrench. */
  alloc->usable_mask = all_thrusters_mask(n);
  uvms_status_t st = alloc_compute_pinv(alloc);
  if (st == UVMS_OK && alloc->rank < UVMS_ALLOC_WRENCH_DIM) st = UVMS_ERR_SINGULAR;
  if (st != UVMS_OK) return alloc_fail(alloc, st);
  alloc->initialised = 1;
  return UVMS_OK;
}

uvms_status_t uvms_alloc_set_usable(uvms_alloc_t *alloc, uint32_t usable_mask) {
  if (alloc == NULL) return UVMS_ERR_ARG;
  if (!alloc->initialised) return UVMS_ERR_STATE;
  const uint32_t mask = usable_mask & all_thrusters_mask(alloc->geom.num_thrusters);
  /* Expensive work only when its input changes (PX4's _mix_update_needed). */
  if (mask == alloc->usable_mask && alloc->pinv_computations > 0u) return alloc->pinv_status;
  alloc->usable_mask = mask;
  return alloc_compute_pinv(alloc);
}

/* The safe output of uvms_alloc_step (zero thrust on every thruster), written by every error
   exit; a successful one writes all three outputs itself. */
static uvms_status_t alloc_step_fail(uvms_real_t *thrust_N, uvms_real_t *thrust_pos_N,
                                     uvms_real_t *thrust_att_N, uvms_status_t st) {
  zero_thrusts(thrust_N);
  zero_thrusts(thrust_pos_N);
  zero_thrusts(thrust_att_N);
  return st;
}

uvms_status_t uvms_alloc_step(const uvms_alloc_t *alloc, const uvms_real_t R0[9],
                              const uvms_real_t force_N_I[3], const uvms_real_t moment_Nm_I[3],
                              uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                              uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS],
                              uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS]) {
  if (alloc == NULL || R0 == NULL || force_N_I == NULL || moment_Nm_I == NULL ||
      thrust_N == NULL) {
    return alloc_step_fail(thrust_N, thrust_pos_N, thrust_att_N, UVMS_ERR_ARG);
  }
  if (!alloc->initialised)
    return alloc_step_fail(thrust_N, thrust_pos_N, thrust_att_N, UVMS_ERR_STATE);
  if (!alloc->ready) {
    return alloc_step_fail(thrust_N, thrust_pos_N, thrust_att_N,
                           (alloc->pinv_status != UVMS_OK) ? alloc->pinv_status
                                                           : UVMS_ERR_STATE);
  }
  /* A usable set of rank < 6 is ready too: P below is its least-squares thrust. */
  if (!uvms_all_finite_fast(R0, 9) || !uvms_v3_isfinite_fast(force_N_I) ||
      !uvms_v3_isfinite_fast(moment_Nm_I)) {
    return alloc_step_fail(thrust_N, thrust_pos_N, thrust_att_N, UVMS_ERR_NONFINITE);
  }

  /* [38]: blockdiag(R0ᵀ, R0ᵀ)·(F; N), the wrench in vehicle (body) coordinates. */
  uvms_real_t f_b_N[3], n_b_Nm[3];
  uvms_m3t_mul_v3(R0, force_N_I, f_b_N);
  uvms_m3t_mul_v3(R0, moment_Nm_I, n_b_Nm);

  /* [39] with the §7.3 split: P_pos = H⁺·(f_b; 0), P_att = H⁺·(0; n_b), P = P_pos + P_att. */
  const size_t n = thruster_count(alloc->geom.num_thrusters);
  uvms_real_t p_pos_N[UVMS_MAX_THRUSTERS], p_att_N[UVMS_MAX_THRUSTERS], p_N[UVMS_MAX_THRUSTERS];
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) /* word stores, not a byte-wise memset */
    p_pos_N[j] = p_att_N[j] = p_N[j] = UVMS_R(0.0);
  uvms_real_t probe = UVMS_R(0.0); /* Σ 0·x: 0 exactly when every part is finite (fw_fast.h) */
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    const uvms_real_t *row = &alloc->H_pinv[j * UVMS_ALLOC_WRENCH_DIM];
    p_pos_N[j] = row[0] * f_b_N[0] + row[1] * f_b_N[1] + row[2] * f_b_N[2];
    p_att_N[j] = row[3] * n_b_Nm[0] + row[4] * n_b_Nm[1] + row[5] * n_b_Nm[2];
    p_N[j] = p_pos_N[j] + p_att_N[j];
    probe += UVMS_R(0.0) * p_N[j] + UVMS_R(0.0) * p_pos_N[j] + UVMS_R(0.0) * p_att_N[j];
  }
  if (probe != UVMS_R(0.0)) /* overflow of huge finite inputs */
    return alloc_step_fail(thrust_N, thrust_pos_N, thrust_att_N, UVMS_ERR_NONFINITE);
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    thrust_N[j] = p_N[j];
    if (thrust_pos_N != NULL) thrust_pos_N[j] = p_pos_N[j];
    if (thrust_att_N != NULL) thrust_att_N[j] = p_att_N[j];
  }
  return UVMS_OK;
}

uvms_status_t uvms_alloc_saturate(const uvms_alloc_t *alloc, uvms_real_t thrust_limit_N,
                                  uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS],
                                  uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS],
                                  uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                  uvms_real_t *scale_pos, uvms_real_t *scale_att) {
  uvms_real_t limits_N[UVMS_MAX_THRUSTERS];
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) limits_N[j] = thrust_limit_N;
  return uvms_alloc_saturate_each(alloc, limits_N, thrust_pos_N, thrust_att_N, thrust_N,
                                  scale_pos, scale_att);
}

/* Step 1 of uvms_alloc_saturate_each: the largest uniform s_att ≤ 1 with |s_att·a_j| ≤ T_j. */
static uvms_real_t attitude_scale(size_t n, const uvms_real_t *T_N, const uvms_real_t *att_N) {
  uvms_real_t s_att = UVMS_R(1.0);
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    const uvms_real_t a_N = uvms_fabs(att_N[j]);
    if (a_N > T_N[j] && T_N[j] / a_N < s_att) s_att = T_N[j] / a_N;
  }
  return s_att;
}

/* Step 2: the largest s_pos ∈ [0, 1] with |a_j + s_pos·p_j| ≤ T_j for all j; |a_j| ≤ T_j here,
   so the room T_j − a_j·sign(p_j) is ≥ 0 and so is each bound. */
static uvms_real_t position_scale(size_t n, const uvms_real_t *T_N, const uvms_real_t *pos_N,
                                  const uvms_real_t *att_N) {
  uvms_real_t s_pos = UVMS_R(1.0);
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    const uvms_real_t p_N = pos_N[j], a_N = att_N[j];
    if (p_N == UVMS_R(0.0)) continue;
    const uvms_real_t room_N = (p_N > UVMS_R(0.0)) ? (T_N[j] - a_N) : (T_N[j] + a_N);
    if (room_N < s_pos * uvms_fabs(p_N)) s_pos = room_N / uvms_fabs(p_N);
  }
  return (s_pos < UVMS_R(0.0)) ? UVMS_R(0.0) : s_pos; /* rounding only */
}

uvms_status_t uvms_alloc_saturate_each(const uvms_alloc_t *alloc,
                                       const uvms_real_t thrust_limit_N[UVMS_MAX_THRUSTERS],
                                       uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS],
                                       uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS],
                                       uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                       uvms_real_t *scale_pos, uvms_real_t *scale_att) {
  if (scale_pos != NULL) *scale_pos = UVMS_R(0.0);
  if (scale_att != NULL) *scale_att = UVMS_R(0.0);
  zero_thrusts(thrust_N);
  if (alloc == NULL || thrust_limit_N == NULL || thrust_pos_N == NULL || thrust_att_N == NULL ||
      thrust_N == NULL || scale_pos == NULL || scale_att == NULL) {
    zero_thrusts(thrust_pos_N);
    zero_thrusts(thrust_att_N);
    return UVMS_ERR_ARG;
  }
  uvms_status_t st = alloc->initialised ? UVMS_OK : UVMS_ERR_STATE;
  const size_t n = thruster_count(alloc->geom.num_thrusters);
  const uvms_real_t *T_N = thrust_limit_N;
  /* Fast path (every tick of an unsaturated run): P = P_pos + P_att, done if every |P_j| ≤ T_j
     with T_j > 0. A finite sum implies finite parts (inf + finite = inf, inf − inf = NaN), and
     NaN fails the comparisons, so anything else takes the full path below, which validates. */
  if (st == UVMS_OK) {
    int fits = 1;
    for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
      const uvms_real_t p_N = thrust_pos_N[j] + thrust_att_N[j];
      thrust_N[j] = p_N;
      if (!(uvms_fabs(p_N) <= T_N[j]) || !(T_N[j] > UVMS_R(0.0))) fits = 0;
    }
    if (fits) {
      *scale_pos = UVMS_R(1.0);
      *scale_att = UVMS_R(1.0);
      return UVMS_OK;
    }
  }
  for (size_t j = 0; st == UVMS_OK && j < n && j < UVMS_MAX_THRUSTERS; ++j)
    if (!(T_N[j] > UVMS_R(0.0))) st = UVMS_ERR_RANGE;
  for (size_t j = 0; st == UVMS_OK && j < n && j < UVMS_MAX_THRUSTERS; ++j)
    if (!uvms_isfinite(thrust_pos_N[j]) || !uvms_isfinite(thrust_att_N[j])) st = UVMS_ERR_NONFINITE;
  if (st != UVMS_OK) {
    zero_thrusts(thrust_N);
    zero_thrusts(thrust_pos_N);
    zero_thrusts(thrust_att_N);
    return st;
  }
  /* 1. An attitude part that alone exceeds a limit is scaled uniformly, no position part;
     2. otherwise the position part is scaled into the room the attitude part leaves. */
  const uvms_real_t s_att = attitude_scale(n, T_N, thrust_att_N);
  const uvms_real_t s_pos =
      (s_att < UVMS_R(1.0)) ? UVMS_R(0.0) : position_scale(n, T_N, thrust_pos_N, thrust_att_N);
  /* 3. Scale the parts; P = sum, clamped to ±T_j against rounding. */
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    thrust_pos_N[j] *= s_pos;
    thrust_att_N[j] *= s_att;
    uvms_real_t p_N = thrust_pos_N[j] + thrust_att_N[j];
    if (p_N > T_N[j]) p_N = T_N[j];
    if (p_N < -T_N[j]) p_N = -T_N[j];
    thrust_N[j] = p_N;
  }
  *scale_pos = s_pos;
  *scale_att = s_att;
  return UVMS_OK;
}

const char *uvms_alloc_mode_str(uvms_alloc_mode_t mode) {
  switch (mode) {
    case UVMS_ALLOC_PSEUDOINVERSE: return "pseudoinverse";
    case UVMS_ALLOC_MIN_POWER: return "min_power";
    default: return "invalid";
  }
}

uvms_status_t uvms_alloc_mode_check(uvms_alloc_mode_t mode) {
  return (mode == UVMS_ALLOC_PSEUDOINVERSE || mode == UVMS_ALLOC_MIN_POWER) ? UVMS_OK
                                                                            : UVMS_ERR_RANGE;
}

uvms_status_t uvms_alloc_thrust_limit_check(uvms_real_t thrust_limit_N) {
  if (!uvms_isfinite(thrust_limit_N)) return UVMS_ERR_NONFINITE;
  return (thrust_limit_N < UVMS_R(0.0)) ? UVMS_ERR_RANGE : UVMS_OK;
}

uvms_status_t uvms_alloc_config_matrix(const uvms_alloc_t *alloc,
                                       uvms_real_t H[UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS]) {
  if (H == NULL) return UVMS_ERR_ARG;
  for (size_t i = 0; i < UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS; ++i) H[i] = UVMS_R(0.0);
  if (alloc == NULL) return UVMS_ERR_ARG;
  if (!alloc->initialised) return UVMS_ERR_STATE;
  build_H(&alloc->geom, all_thrusters_mask(alloc->geom.num_thrusters), H);
  return UVMS_OK;
}

uvms_status_t uvms_alloc_wrench_body(const uvms_alloc_t *alloc,
                                     const uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                     uvms_real_t wrench_body[UVMS_ALLOC_WRENCH_DIM]) {
  if (wrench_body == NULL) return UVMS_ERR_ARG;
  for (size_t r = 0; r < UVMS_ALLOC_WRENCH_DIM; ++r) wrench_body[r] = UVMS_R(0.0);
  if (alloc == NULL || thrust_N == NULL) return UVMS_ERR_ARG;
  if (!alloc->initialised) return UVMS_ERR_STATE;
  const size_t n = thruster_count(alloc->geom.num_thrusters);
  /* [33–37]: (F_b; N_b) = H·P = Σ_j (u_j; a_j × u_j)·P_j = (Σ u_j·P_j; Σ a_j × (u_j·P_j)). */
  uvms_real_t f_N[3] = {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0)};
  uvms_real_t m_Nm[3] = {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0)};
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    uvms_real_t fj_N[3], mj_Nm[3];
    uvms_v3_scale(alloc->geom.direction[j], thrust_N[j], fj_N);
    uvms_v3_cross(alloc->geom.position_m[j], fj_N, mj_Nm);
    uvms_v3_add(f_N, fj_N, f_N);
    uvms_v3_add(m_Nm, mj_Nm, m_Nm);
  }
  for (size_t r = 0; r < 3; ++r) {
    wrench_body[r] = f_N[r];
    wrench_body[r + 3] = m_Nm[r];
  }
  return UVMS_OK;
}

uvms_status_t uvms_thruster_advance_speeds(const uvms_thruster_geometry_t *geom,
                                           const uvms_real_t R0[9], const uvms_real_t v0_m_s_I[3],
                                           const uvms_real_t w0_rad_s_I[3],
                                           const uvms_real_t vinf_m_s_I[3],
                                           uvms_real_t advance_m_s[UVMS_MAX_THRUSTERS]) {
  if (advance_m_s == NULL) return UVMS_ERR_ARG;
  /* Every error exit below writes the safe output, zero; a success writes all of it. */
  if (geom == NULL || R0 == NULL || v0_m_s_I == NULL || w0_rad_s_I == NULL ||
      vinf_m_s_I == NULL || geom->num_thrusters == 0) {
    zero_thrusts(advance_m_s);
    return UVMS_ERR_ARG;
  }
  if (geom->num_thrusters > UVMS_MAX_THRUSTERS) {
    zero_thrusts(advance_m_s);
    return UVMS_ERR_SIZE;
  }
  if (!uvms_all_finite_fast(R0, 9) || !uvms_v3_isfinite_fast(v0_m_s_I) ||
      !uvms_v3_isfinite_fast(w0_rad_s_I) || !uvms_v3_isfinite_fast(vinf_m_s_I)) {
    zero_thrusts(advance_m_s);
    return UVMS_ERR_NONFINITE;
  }
  const size_t n = thruster_count(geom->num_thrusters);
  uvms_real_t va_m_s[UVMS_MAX_THRUSTERS] = {0};
  /* [47–52]: v_a,j = u_j · (R0ᵀ·(v0 + ω0 × R0·a_j − v∞)). R0ᵀ distributes over the sum and
     R0ᵀ·(ω0 × R0·a_j) = (R0ᵀω0) × a_j, so with the body-frame relative velocity and angular
     velocity computed once: v_a,j = u_j · (v_b + ω_b × a_j). */
  uvms_real_t rel_I_m_s[3], v_b_m_s[3], w_b_rad_s[3];
  uvms_v3_sub(v0_m_s_I, vinf_m_s_I, rel_I_m_s);
  uvms_m3t_mul_v3(R0, rel_I_m_s, v_b_m_s);
  uvms_m3t_mul_v3(R0, w0_rad_s_I, w_b_rad_s);
  uvms_real_t probe = UVMS_R(0.0); /* Σ 0·v_a: 0 exactly when all are finite (fw_fast.h) */
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    uvms_real_t w_b_m_s[3];
    uvms_v3_cross(w_b_rad_s, geom->position_m[j], w_b_m_s);
    uvms_v3_add(w_b_m_s, v_b_m_s, w_b_m_s);
    va_m_s[j] = uvms_v3_dot(geom->direction[j], w_b_m_s);
    probe += UVMS_R(0.0) * va_m_s[j];
  }
  if (probe != UVMS_R(0.0)) {
    zero_thrusts(advance_m_s);
    return UVMS_ERR_NONFINITE;
  }
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) advance_m_s[j] = va_m_s[j];
  return UVMS_OK;
}
