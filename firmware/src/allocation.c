/* allocation.c: thrust allocation by pseudoinverse, SPEC §7.3 [33–39] (allocation.h).
 * No allocation, no file-scope mutable state; every loop is bounded by UVMS_MAX_THRUSTERS or
 * UVMS_ALLOC_WRENCH_DIM (loops over the n used thrusters also test j < UVMS_MAX_THRUSTERS so
 * that the bound is visible without knowing that init validated n). */
#include "uvms/allocation.h"

#include <string.h>

#include "uvms/linalg.h"

/* The usable set is a bit mask in a uint32_t, and H⁺ is one uvms_spd_solve with n right-hand
 * sides (at most 4·UVMS_SPD_MAX_N). */
_Static_assert(UVMS_MAX_THRUSTERS >= 6 && UVMS_MAX_THRUSTERS <= 31,
               "usable_mask holds one bit per thruster");
_Static_assert(UVMS_MAX_THRUSTERS <= 4 * UVMS_SPD_MAX_N, "uvms_spd_solve right-hand-side limit");
_Static_assert(UVMS_ALLOC_WRENCH_DIM <= UVMS_SPD_MAX_N, "uvms_spd_solve dimension limit");

/* Mask with bits 0..n-1 set; n ≤ UVMS_MAX_THRUSTERS (= 8) < 32, so the shift is defined. */
static uint32_t all_thrusters_mask(size_t n) {
  return (n >= UVMS_MAX_THRUSTERS) ? (uint32_t)((1u << UVMS_MAX_THRUSTERS) - 1u)
                                   : (uint32_t)((1u << (uint32_t)n) - 1u);
}

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

/*
 * H⁺ of the usable columns [38]. With H_u = H with the unusable columns set to zero,
 * G = H_u·H_uᵀ (6×6, symmetric) and H⁺ = H_uᵀ·G⁻¹ = (G⁻¹·H_u)ᵀ: one SPD solve with n
 * right-hand sides. A zero column of H_u gives a zero column of G⁻¹·H_u, so unusable
 * thrusters get an exactly zero row of H⁺; H_u has full row rank iff G is positive definite.
 * On failure H_pinv is all zeros and ready = 0 (the step then refuses to run).
 */
static uvms_status_t alloc_compute_pinv(uvms_alloc_t *alloc) {
  const size_t n = alloc->geom.num_thrusters;
  uvms_real_t Hu[UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS] = {0};
  uvms_real_t G[UVMS_ALLOC_WRENCH_DIM * UVMS_ALLOC_WRENCH_DIM] = {0};
  uvms_real_t X[UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS] = {0};

  alloc->ready = 0;
  alloc->pinv_computations += 1u;
  for (size_t i = 0; i < UVMS_MAX_THRUSTERS * UVMS_ALLOC_WRENCH_DIM; ++i) {
    alloc->H_pinv[i] = UVMS_R(0.0);
  }

  for (size_t r = 0; r < UVMS_ALLOC_WRENCH_DIM; ++r) {
    for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
      Hu[r * n + j] = mask_has(alloc->usable_mask, j) ? alloc->H[r * n + j] : UVMS_R(0.0);
    }
  }
  for (size_t r = 0; r < UVMS_ALLOC_WRENCH_DIM; ++r) {
    for (size_t c = 0; c < UVMS_ALLOC_WRENCH_DIM; ++c) {
      uvms_real_t s = UVMS_R(0.0);
      for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) s += Hu[r * n + j] * Hu[c * n + j];
      G[r * UVMS_ALLOC_WRENCH_DIM + c] = s;
    }
  }
  const uvms_status_t st =
      uvms_spd_solve(UVMS_ALLOC_WRENCH_DIM, G, n, Hu, X, UVMS_ALLOC_REL_PIVOT_TOL);
  if (st != UVMS_OK) {
    /* uvms_spd_solve returns ARG only for sizes/pointers checked here already; any failure
     * of the factorisation means the usable set cannot produce every wrench. */
    alloc->pinv_status = UVMS_ERR_SINGULAR;
    return UVMS_ERR_SINGULAR;
  }
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    const int usable = mask_has(alloc->usable_mask, j);
    for (size_t r = 0; r < UVMS_ALLOC_WRENCH_DIM; ++r) {
      alloc->H_pinv[j * UVMS_ALLOC_WRENCH_DIM + r] = usable ? X[r * n + j] : UVMS_R(0.0);
    }
  }
  alloc->pinv_status = UVMS_OK;
  alloc->ready = 1;
  return UVMS_OK;
}

/* Leave alloc in its defined "refused" state: all zero, not initialised, not ready. */
static uvms_status_t alloc_fail(uvms_alloc_t *alloc, uvms_status_t st) {
  memset(alloc, 0, sizeof(*alloc));
  alloc->pinv_status = st;
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
    if (!uvms_v3_isfinite(src->position_m[j]) || !uvms_v3_isfinite(src->direction[j])) {
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

  /* H [33–37]: column j = (u_j; a_j × u_j), row-major 6 × n. */
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    uvms_real_t axu[3];
    uvms_v3_cross(alloc->geom.position_m[j], alloc->geom.direction[j], axu);
    for (size_t r = 0; r < 3; ++r) {
      alloc->H[r * n + j] = alloc->geom.direction[j][r];
      alloc->H[(r + 3) * n + j] = axu[r];
    }
  }
  for (size_t i = 0; i < UVMS_ALLOC_WRENCH_DIM * UVMS_MAX_THRUSTERS; ++i) {
    if (!uvms_isfinite(alloc->H[i])) return alloc_fail(alloc, UVMS_ERR_NONFINITE);
  }

  /* H⁺ over all thrusters [38]. */
  alloc->usable_mask = all_thrusters_mask(n);
  const uvms_status_t st = alloc_compute_pinv(alloc);
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

uvms_status_t uvms_alloc_step(const uvms_alloc_t *alloc, const uvms_real_t R0[9],
                              const uvms_real_t force_N_I[3], const uvms_real_t moment_Nm_I[3],
                              uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                              uvms_real_t thrust_pos_N[UVMS_MAX_THRUSTERS],
                              uvms_real_t thrust_att_N[UVMS_MAX_THRUSTERS]) {
  /* Safe output first: zero thrust on every thruster. */
  zero_thrusts(thrust_N);
  zero_thrusts(thrust_pos_N);
  zero_thrusts(thrust_att_N);
  if (alloc == NULL || R0 == NULL || force_N_I == NULL || moment_Nm_I == NULL ||
      thrust_N == NULL) {
    return UVMS_ERR_ARG;
  }
  if (!alloc->initialised) return UVMS_ERR_STATE;
  if (!alloc->ready) {
    return (alloc->pinv_status != UVMS_OK) ? alloc->pinv_status : UVMS_ERR_STATE;
  }
  for (size_t i = 0; i < 9; ++i) {
    if (!uvms_isfinite(R0[i])) return UVMS_ERR_NONFINITE;
  }
  if (!uvms_v3_isfinite(force_N_I) || !uvms_v3_isfinite(moment_Nm_I)) {
    return UVMS_ERR_NONFINITE;
  }

  /* [38]: blockdiag(R0ᵀ, R0ᵀ)·(F; N), the wrench in vehicle (body) coordinates. */
  uvms_real_t f_b_N[3], n_b_Nm[3];
  uvms_m3t_mul_v3(R0, force_N_I, f_b_N);
  uvms_m3t_mul_v3(R0, moment_Nm_I, n_b_Nm);

  /* [39] with the §7.3 split: P_pos = H⁺·(f_b; 0), P_att = H⁺·(0; n_b), P = P_pos + P_att. */
  const size_t n = alloc->geom.num_thrusters;
  uvms_real_t p_pos_N[UVMS_MAX_THRUSTERS] = {0};
  uvms_real_t p_att_N[UVMS_MAX_THRUSTERS] = {0};
  uvms_real_t p_N[UVMS_MAX_THRUSTERS] = {0};
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    const uvms_real_t *row = &alloc->H_pinv[j * UVMS_ALLOC_WRENCH_DIM];
    p_pos_N[j] = row[0] * f_b_N[0] + row[1] * f_b_N[1] + row[2] * f_b_N[2];
    p_att_N[j] = row[3] * n_b_Nm[0] + row[4] * n_b_Nm[1] + row[5] * n_b_Nm[2];
    p_N[j] = p_pos_N[j] + p_att_N[j];
    if (!uvms_isfinite(p_N[j]) || !uvms_isfinite(p_pos_N[j]) || !uvms_isfinite(p_att_N[j])) {
      return UVMS_ERR_NONFINITE; /* overflow of huge finite inputs; outputs are still zero */
    }
  }
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) {
    thrust_N[j] = p_N[j];
    if (thrust_pos_N != NULL) thrust_pos_N[j] = p_pos_N[j];
    if (thrust_att_N != NULL) thrust_att_N[j] = p_att_N[j];
  }
  return UVMS_OK;
}

uvms_status_t uvms_alloc_wrench_body(const uvms_alloc_t *alloc,
                                     const uvms_real_t thrust_N[UVMS_MAX_THRUSTERS],
                                     uvms_real_t wrench_body[UVMS_ALLOC_WRENCH_DIM]) {
  if (wrench_body == NULL) return UVMS_ERR_ARG;
  for (size_t r = 0; r < UVMS_ALLOC_WRENCH_DIM; ++r) wrench_body[r] = UVMS_R(0.0);
  if (alloc == NULL || thrust_N == NULL) return UVMS_ERR_ARG;
  if (!alloc->initialised) return UVMS_ERR_STATE;
  const size_t n = alloc->geom.num_thrusters;
  /* [33–37]: (F_b; N_b) = H·P. */
  for (size_t r = 0; r < UVMS_ALLOC_WRENCH_DIM; ++r) {
    uvms_real_t s = UVMS_R(0.0);
    for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) s += alloc->H[r * n + j] * thrust_N[j];
    wrench_body[r] = s;
  }
  return UVMS_OK;
}

uvms_status_t uvms_thruster_advance_speeds(const uvms_thruster_geometry_t *geom,
                                           const uvms_real_t R0[9], const uvms_real_t v0_m_s_I[3],
                                           const uvms_real_t w0_rad_s_I[3],
                                           const uvms_real_t vinf_m_s_I[3],
                                           uvms_real_t advance_m_s[UVMS_MAX_THRUSTERS]) {
  if (advance_m_s == NULL) return UVMS_ERR_ARG;
  zero_thrusts(advance_m_s);
  if (geom == NULL || R0 == NULL || v0_m_s_I == NULL || w0_rad_s_I == NULL ||
      vinf_m_s_I == NULL || geom->num_thrusters == 0) {
    return UVMS_ERR_ARG;
  }
  if (geom->num_thrusters > UVMS_MAX_THRUSTERS) return UVMS_ERR_SIZE;
  for (size_t i = 0; i < 9; ++i) {
    if (!uvms_isfinite(R0[i])) return UVMS_ERR_NONFINITE;
  }
  if (!uvms_v3_isfinite(v0_m_s_I) || !uvms_v3_isfinite(w0_rad_s_I) ||
      !uvms_v3_isfinite(vinf_m_s_I)) {
    return UVMS_ERR_NONFINITE;
  }
  const size_t n = geom->num_thrusters;
  uvms_real_t va_m_s[UVMS_MAX_THRUSTERS] = {0};
  /* [47–52]: v_a,j = u_j · (R0ᵀ·(v0 + ω0 × R0·a_j − v∞)). R0ᵀ distributes over the sum and
     R0ᵀ·(ω0 × R0·a_j) = (R0ᵀω0) × a_j, so with the body-frame relative velocity and angular
     velocity computed once: v_a,j = u_j · (v_b + ω_b × a_j). */
  uvms_real_t rel_I_m_s[3], v_b_m_s[3], w_b_rad_s[3];
  uvms_v3_sub(v0_m_s_I, vinf_m_s_I, rel_I_m_s);
  uvms_m3t_mul_v3(R0, rel_I_m_s, v_b_m_s);
  uvms_m3t_mul_v3(R0, w0_rad_s_I, w_b_rad_s);
  for (size_t j = 0; j < n && j < UVMS_MAX_THRUSTERS; ++j) {
    uvms_real_t w_b_m_s[3];
    uvms_v3_cross(w_b_rad_s, geom->position_m[j], w_b_m_s);
    uvms_v3_add(w_b_m_s, v_b_m_s, w_b_m_s);
    va_m_s[j] = uvms_v3_dot(geom->direction[j], w_b_m_s);
    if (!uvms_isfinite(va_m_s[j])) return UVMS_ERR_NONFINITE;
  }
  for (size_t j = 0; j < UVMS_MAX_THRUSTERS; ++j) advance_m_s[j] = va_m_s[j];
  return UVMS_OK;
}
