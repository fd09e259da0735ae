/* SPDX-License-Identifier: Apache-2.0 */
/* trajectory.c: joint cycloid, joint servo, cosine line and Cartesian resolved-rate IK
 * (SPEC §8, [69–71], [78], [3]–[5]; trajectory.h).
 * No allocation, no recursion, no file-scope mutable state; every loop is bounded by
 * UVMS_MAX_JOINTS or 3 (loops over the n used joints also test i < UVMS_MAX_JOINTS so that
 * the bound is visible without knowing that n was validated). */
#include "uvms/trajectory.h"

#include <string.h>

#include "uvms/kinematics.h"
#include "uvms/linalg.h"
#include "fw_fast.h"

/*
 * A pivot of the Cholesky factorisation of J·Jᵀ + λ²I below this fraction of its largest
 * diagonal entry counts as singular. The smallest eigenvalue is ≥ λ² (1e-4 m² at the default
 * λ) against a largest diagonal of at most ≈ 2 m² (|J row|² of a 1.8 m reach), a relative
 * pivot ≳ 5e-5; the Cholesky's own rounding is ≈ 3·eps relative (2e-7 in float). The
 * threshold sits between the two.
 */
#if UVMS_REAL_IS_FLOAT
#define CART_REL_PIVOT_TOL UVMS_R(1e-6)
#else
#define CART_REL_PIVOT_TOL UVMS_R(1e-12)
#endif

#define TWO_PI (UVMS_R(2.0) * UVMS_PI)
#define INV_TWO_PI (UVMS_R(0.5) / UVMS_PI)

/* SPEC §8's joint-angle table [deg] (docs/MODEL.md §8), the only copy: θI, "Veh.", and the
   barycenter columns for 0, 1, 2, 5 and 10 kg of payload. One documented correction (docs/MODEL.md
   C26): the 10 kg column's joint 1 is printed 176.19°, which misses the column's EE target by
   35 mm; 173.19° (a transposed digit) meets it within 0.3 mm and follows the column's trend.
   The printed value stays available as UVMS_JOINT_TABLE_BARY_10KG_J1_PRINTED_DEG. */
static const uvms_real_t kJointTableDeg[UVMS_JOINT_TABLE_COLUMNS][UVMS_JOINT_TABLE_JOINTS] = {
    {UVMS_R(180.0), UVMS_R(90.0), UVMS_R(180.0), UVMS_R(180.0), UVMS_R(0.0), UVMS_R(0.0),
     UVMS_R(0.0)},
    {UVMS_R(169.68), UVMS_R(-75.62), UVMS_R(266.00), UVMS_R(108.77), UVMS_R(193.47),
     UVMS_R(96.97), UVMS_R(98.33)},
    {UVMS_R(170.06), UVMS_R(-76.01), UVMS_R(265.62), UVMS_R(102.87), UVMS_R(192.96),
     UVMS_R(91.56), UVMS_R(97.24)},
    {UVMS_R(170.32), UVMS_R(-76.12), UVMS_R(265.53), UVMS_R(101.58), UVMS_R(192.86),
     UVMS_R(90.56), UVMS_R(97.02)},
    {UVMS_R(170.59), UVMS_R(-76.24), UVMS_R(265.45), UVMS_R(100.28), UVMS_R(192.76),
     UVMS_R(89.56), UVMS_R(96.80)},
    {UVMS_R(171.48), UVMS_R(-76.58), UVMS_R(265.17), UVMS_R(96.30), UVMS_R(192.51),
     UVMS_R(86.53), UVMS_R(96.14)},
    {UVMS_R(173.19), UVMS_R(-77.12), UVMS_R(264.65), UVMS_R(89.32), UVMS_R(192.22),
     UVMS_R(81.35), UVMS_R(95.12)},
};

const uvms_real_t *uvms_joint_table_deg(uvms_joint_table_column_t column) {
  /* One unsigned comparison also rejects negative values, whatever the enum's type. */
  if ((unsigned)column >= (unsigned)UVMS_JOINT_TABLE_COLUMNS) return NULL;
  return kJointTableDeg[column];
}

uvms_real_t uvms_joint_table_payload_kg(uvms_joint_table_column_t column) {
  switch (column) {
    case UVMS_JOINT_TABLE_BARY_0KG: return UVMS_R(0.0);
    case UVMS_JOINT_TABLE_BARY_1KG: return UVMS_R(1.0);
    case UVMS_JOINT_TABLE_BARY_2KG: return UVMS_R(2.0);
    case UVMS_JOINT_TABLE_BARY_5KG: return UVMS_R(5.0);
    case UVMS_JOINT_TABLE_BARY_10KG: return UVMS_R(10.0);
    default: return UVMS_R(-1.0);
  }
}

static size_t clamp_count(size_t n) { return (n < UVMS_MAX_JOINTS) ? n : UVMS_MAX_JOINTS; }

static void zero_n(uvms_real_t *out, size_t n) {
  if (out == NULL) return;
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) out[i] = UVMS_R(0.0);
}

/* "Hold the start": out[i] = start[i] where finite, else 0 (start may be NULL). */
static void hold_start(uvms_real_t *out, const uvms_real_t *start, size_t n, size_t n_max) {
  if (out == NULL) return;
  for (size_t i = 0; i < n && i < n_max; ++i) {
    out[i] = (start != NULL && uvms_isfinite(start[i])) ? start[i] : UVMS_R(0.0);
  }
}

/* τ = clamp(t/tF, 0, 1) (SPEC §8), given the ratio t/tF. */
static uvms_real_t clamp_tau(uvms_real_t tau) {
  if (!(tau > UVMS_R(0.0))) return UVMS_R(0.0);
  if (tau > UVMS_R(1.0)) return UVMS_R(1.0);
  return tau;
}

/* ---------------------------------------------------------------------------------------- */
/* Joint cycloid, SPEC §8 (the corrected [69–71]).                                           */

/* The safe output of uvms_cycloid_eval (hold the start, at rest), written by every error exit;
   a successful one writes all three outputs itself, so nothing is written twice. */
static uvms_status_t cycloid_fail(size_t n, const uvms_real_t *theta_start_rad, uvms_real_t *q_rad,
                                  uvms_real_t *qd_rad_s, uvms_real_t *qdd_rad_s2,
                                  uvms_status_t st) {
  const size_t nw = clamp_count(n);
  hold_start(q_rad, theta_start_rad, nw, UVMS_MAX_JOINTS);
  zero_n(qd_rad_s, nw);
  zero_n(qdd_rad_s2, nw);
  return st;
}

uvms_status_t uvms_cycloid_eval(size_t n, const uvms_real_t *theta_start_rad,
                                const uvms_real_t *theta_final_rad, uvms_real_t duration_s,
                                uvms_real_t t_s, uvms_real_t *q_rad, uvms_real_t *qd_rad_s,
                                uvms_real_t *qdd_rad_s2) {
  if (q_rad == NULL || qd_rad_s == NULL || qdd_rad_s2 == NULL || theta_start_rad == NULL ||
      theta_final_rad == NULL) {
    return cycloid_fail(n, theta_start_rad, q_rad, qd_rad_s, qdd_rad_s2, UVMS_ERR_ARG);
  }
  if (n < 1 || n > UVMS_MAX_JOINTS)
    return cycloid_fail(n, theta_start_rad, q_rad, qd_rad_s, qdd_rad_s2, UVMS_ERR_SIZE);
  if (!uvms_isfinite(duration_s) || !uvms_isfinite(t_s))
    return cycloid_fail(n, theta_start_rad, q_rad, qd_rad_s, qdd_rad_s2, UVMS_ERR_NONFINITE);

  /* Outside the open interval, and a duration out of range: the angles checked first (their
     status comes before the range's), then exact end values, zero rate and acceleration. */
  if (!(duration_s > UVMS_R(0.0)) || t_s <= UVMS_R(0.0) || t_s >= duration_s) {
    if (!uvms_all_finite_fast(theta_start_rad, n) || !uvms_all_finite_fast(theta_final_rad, n))
      return cycloid_fail(n, theta_start_rad, q_rad, qd_rad_s, qdd_rad_s2, UVMS_ERR_NONFINITE);
    if (!(duration_s > UVMS_R(0.0)))
      return cycloid_fail(n, theta_start_rad, q_rad, qd_rad_s, qdd_rad_s2, UVMS_ERR_RANGE);
    const uvms_real_t *end = (t_s <= UVMS_R(0.0)) ? theta_start_rad : theta_final_rad;
    for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) {
      q_rad[i] = end[i];
      qd_rad_s[i] = UVMS_R(0.0);
      qdd_rad_s2[i] = UVMS_R(0.0);
    }
    return UVMS_OK;
  }
  /* One division (1/tF), multiplied where the formulas divide. */
  const uvms_real_t inv_T_1_s = UVMS_R(1.0) / duration_s;
  const uvms_real_t tau = clamp_tau(t_s * inv_T_1_s);
  uvms_real_t s2, c2; /* sin(2πτ), cos(2πτ) */
  uvms_sincos(TWO_PI * tau, &s2, &c2);
  const uvms_real_t shape = tau - s2 * INV_TWO_PI;                  /* θ:  τ − sin(2πτ)/(2π) */
  const uvms_real_t rate = (UVMS_R(1.0) - c2) * inv_T_1_s;           /* θ̇ per unit Δ */
  const uvms_real_t accel = TWO_PI * s2 * inv_T_1_s * inv_T_1_s;     /* θ̈ per unit Δ */
  /* One pass: the profile and Σ 0·x (fw_fast.h: 0 exactly when every x is finite) over the
     angles and over the results; the outputs alias no input (trajectory.h), so the hold
     written over them on an error is the same as without the pass. */
  uvms_real_t pr_in = UVMS_R(0.0), pr_out = UVMS_R(0.0);
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) {
    const uvms_real_t start = theta_start_rad[i], fin = theta_final_rad[i];
    const uvms_real_t delta = fin - start;
    const uvms_real_t q = start + delta * shape, qd = delta * rate, qdd = delta * accel;
    pr_in += UVMS_R(0.0) * start + UVMS_R(0.0) * fin;
    pr_out += UVMS_R(0.0) * q + UVMS_R(0.0) * qd + UVMS_R(0.0) * qdd;
    q_rad[i] = q;
    qd_rad_s[i] = qd;
    qdd_rad_s2[i] = qdd;
  }
  if (pr_in != UVMS_R(0.0))
    return cycloid_fail(n, theta_start_rad, q_rad, qd_rad_s, qdd_rad_s2, UVMS_ERR_NONFINITE);
  if (pr_out != UVMS_R(0.0)) {
    /* Only a vanishing tF (or a huge Δ) can overflow: restore the hold. */
    return cycloid_fail(n, theta_start_rad, q_rad, qd_rad_s, qdd_rad_s2, UVMS_ERR_RANGE);
  }
  return UVMS_OK;
}

/* ---------------------------------------------------------------------------------------- */
/* Joint servo, SPEC §8.                                                                     */

uvms_status_t uvms_joint_servo_gains_check(uvms_real_t kq_1_s2, uvms_real_t kqd_1_s) {
  if (!uvms_isfinite(kq_1_s2) || !uvms_isfinite(kqd_1_s)) return UVMS_ERR_NONFINITE;
  if (kq_1_s2 < UVMS_R(0.0) || kqd_1_s < UVMS_R(0.0)) return UVMS_ERR_RANGE;
  return UVMS_OK;
}

uvms_status_t uvms_joint_servo(size_t n, const uvms_real_t *q_ref_rad,
                               const uvms_real_t *qd_ref_rad_s, const uvms_real_t *qdd_ref_rad_s2,
                               const uvms_real_t *q_rad, const uvms_real_t *qd_rad_s,
                               uvms_real_t kq_1_s2, uvms_real_t kqd_1_s,
                               uvms_real_t *qdd_cmd_rad_s2) {
  /* Every exit writes qdd_cmd_rad_s2[0..n): zero on the first four (no safe command but zero
     without references and gains), feed-forward or the servo law after them. */
  if (qdd_cmd_rad_s2 == NULL || q_ref_rad == NULL || qd_ref_rad_s == NULL ||
      qdd_ref_rad_s2 == NULL || q_rad == NULL || qd_rad_s == NULL) {
    zero_n(qdd_cmd_rad_s2, clamp_count(n));
    return UVMS_ERR_ARG;
  }
  if (n < 1 || n > UVMS_MAX_JOINTS) {
    zero_n(qdd_cmd_rad_s2, clamp_count(n));
    return UVMS_ERR_SIZE;
  }
  /* One pass: the servo law and, for the checks below, Σ 0·x (fw_fast.h: 0 exactly when every
     x is finite) over the references, the measurements and the result. The checks then decide
     in the order of the contract (trajectory.h); the outputs alias no input, so writing the
     law's result first and overwriting it on an error gives the same outputs. */
  uvms_real_t pr_ref = UVMS_R(0.0), pr_meas = UVMS_R(0.0), pr_out = UVMS_R(0.0);
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) {
    const uvms_real_t qr = q_ref_rad[i], qdr = qd_ref_rad_s[i], qddr = qdd_ref_rad_s2[i];
    const uvms_real_t q = q_rad[i], qd = qd_rad_s[i];
    pr_ref += UVMS_R(0.0) * qr + UVMS_R(0.0) * qdr + UVMS_R(0.0) * qddr;
    pr_meas += UVMS_R(0.0) * q + UVMS_R(0.0) * qd;
    /* SPEC §8: θ̈_cmd = θ̈_ref + Kq·(θ_ref − θ) + Kqd·(θ̇_ref − θ̇) */
    const uvms_real_t cmd = qddr + kq_1_s2 * (qr - q) + kqd_1_s * (qdr - qd);
    pr_out += UVMS_R(0.0) * cmd;
    qdd_cmd_rad_s2[i] = cmd;
  }
  if (pr_ref != UVMS_R(0.0) || !uvms_isfinite(kq_1_s2) || !uvms_isfinite(kqd_1_s)) {
    zero_n(qdd_cmd_rad_s2, n);
    return UVMS_ERR_NONFINITE;
  }
  if (kq_1_s2 < UVMS_R(0.0) || kqd_1_s < UVMS_R(0.0)) {
    zero_n(qdd_cmd_rad_s2, n);
    return UVMS_ERR_RANGE;
  }
  /* Measurement: a corrupt one gets feed-forward only (documented in the header). Finite
     inputs can still overflow (absurd gains): feed-forward only too. */
  if (pr_meas != UVMS_R(0.0) || pr_out != UVMS_R(0.0)) {
    for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) qdd_cmd_rad_s2[i] = qdd_ref_rad_s2[i];
    return (pr_meas != UVMS_R(0.0)) ? UVMS_ERR_NONFINITE : UVMS_ERR_RANGE;
  }
  return UVMS_OK;
}

/* ---------------------------------------------------------------------------------------- */
/* Cosine line profile [78].                                                                 */

uvms_status_t uvms_cosine_line_eval(const uvms_real_t r_start_m[3], const uvms_real_t direction[3],
                                    uvms_real_t distance_m, uvms_real_t duration_s,
                                    uvms_real_t t_s, uvms_real_t r_m[3], uvms_real_t v_m_s[3],
                                    uvms_real_t a_m_s2[3]) {
  hold_start(r_m, r_start_m, 3, 3);
  zero_n(v_m_s, 3);
  zero_n(a_m_s2, 3);
  if (r_start_m == NULL || direction == NULL || r_m == NULL || v_m_s == NULL ||
      a_m_s2 == NULL) {
    return UVMS_ERR_ARG;
  }
  if (!uvms_v3_isfinite_fast(r_start_m) || !uvms_v3_isfinite_fast(direction) ||
      !uvms_isfinite(distance_m) || !uvms_isfinite(duration_s) || !uvms_isfinite(t_s)) {
    return UVMS_ERR_NONFINITE;
  }
  if (!(duration_s > UVMS_R(0.0))) return UVMS_ERR_RANGE;
  const uvms_real_t dir_norm = uvms_v3_norm(direction);
  if (!(dir_norm >= UVMS_TRAJ_MIN_DIRECTION_NORM)) return UVMS_ERR_RANGE;
  uvms_real_t u[3];
  uvms_v3_scale(direction, UVMS_R(1.0) / dir_norm, u);

  uvms_real_t s_m = UVMS_R(0.0), sd_m_s = UVMS_R(0.0), sdd_m_s2 = UVMS_R(0.0);
  if (t_s >= duration_s) {
    s_m = distance_m; /* exact end point r_start + rΔ·u, at rest (no rounding of cos π) */
  } else if (t_s > UVMS_R(0.0)) {
    const uvms_real_t arg = UVMS_PI * clamp_tau(t_s / duration_s);
    const uvms_real_t half = UVMS_R(0.5) * distance_m;
    s_m = half * (UVMS_R(1.0) - uvms_cos(arg));
    sd_m_s = half * UVMS_PI / duration_s * uvms_sin(arg);
    sdd_m_s2 = half * UVMS_PI * UVMS_PI / (duration_s * duration_s) * uvms_cos(arg);
  }
  /* t ≤ 0: s = ṡ = s̈ = 0 (hold the start). */
  if (!uvms_isfinite(s_m) || !uvms_isfinite(sd_m_s) || !uvms_isfinite(sdd_m_s2)) {
    return UVMS_ERR_RANGE; /* outputs still hold the start */
  }
  uvms_real_t r[3];
  for (size_t k = 0; k < 3; ++k) r[k] = r_start_m[k] + s_m * u[k];
  if (!uvms_v3_isfinite_fast(r)) return UVMS_ERR_RANGE; /* a huge rΔ: outputs still hold */
  for (size_t k = 0; k < 3; ++k) {
    r_m[k] = r[k];
    v_m_s[k] = sd_m_s * u[k];
    a_m_s2[k] = sdd_m_s2 * u[k];
  }
  return UVMS_OK;
}

/* ---------------------------------------------------------------------------------------- */
/* Cartesian line by resolved-rate DLS inverse kinematics, SPEC §8.                          */

void uvms_cart_traj_params_default(uvms_cart_traj_params_t *params) {
  if (params == NULL) return;
  memset(params, 0, sizeof(*params));
  /* The reasons for each value are given in trajectory.h. */
  params->distance_m = UVMS_R(0.3);
  uvms_v3_set(params->direction, UVMS_R(1.0), UVMS_R(0.0), UVMS_R(0.0));
  params->duration_s = UVMS_R(60.0);
  params->reference = UVMS_REF_VEHICLE;
  params->damping_m = UVMS_R(0.01);
  params->position_gain_1_s = UVMS_R(5.0);
  params->nullspace_gain_1_s = UVMS_R(1.0);
  params->max_joint_rate_rad_s = UVMS_R(1.0);
}

/*
 * The task: EE estimate r̂(q) and its 3×n Jacobian Jt (row-major, stride n), from one FK at
 * the reference vehicle pose (r0d, R0d).
 *  vehicle:    r̂ = p_EE [3],                            Jt = J_EE,linear
 *  barycenter: r̂ = barycenter0 + (p_EE − p_cm)(R0d, q) [4], Jt = J_EE,linear − J_cm
 * (p_EE − p_cm does not depend on the vehicle position, so evaluating it at r0d is exact.)
 */
static uvms_status_t cart_task(const uvms_cart_traj_t *traj, const uvms_arm_model_t *model,
                               uvms_arm_data_t *work, const uvms_real_t *q_rad,
                               uvms_real_t r_est_m[3], uvms_real_t Jt[3 * UVMS_MAX_JOINTS]) {
  uvms_real_t J[6 * UVMS_MAX_JOINTS];
  uvms_real_t Jcm[3 * UVMS_MAX_JOINTS];
  const size_t n = clamp_count(traj->n);
  uvms_status_t st = uvms_arm_fk(model, work, traj->r0d_m, traj->R0d, q_rad);
  if (st != UVMS_OK) return st;
  st = uvms_arm_jacobian(model, work, J);
  if (st != UVMS_OK) return st;
  /* Linear rows 0..2 of the 6×n Jacobian are its first 3·n entries (row-major, stride n). */
  for (size_t k = 0; k < 3 * n && k < 3 * UVMS_MAX_JOINTS; ++k) Jt[k] = J[k];
  if (traj->p.reference == UVMS_REF_BARYCENTER) {
    st = uvms_arm_barycenter_jacobian(model, work, Jcm);
    if (st != UVMS_OK) return st;
    for (size_t k = 0; k < 3 * n && k < 3 * UVMS_MAX_JOINTS; ++k) Jt[k] -= Jcm[k];
    uvms_real_t rel[3];
    uvms_v3_sub(work->ee_m, work->barycenter_m, rel);
    uvms_v3_add(traj->barycenter0_m, rel, r_est_m);
  } else {
    uvms_v3_copy(work->ee_m, r_est_m);
  }
  return UVMS_OK;
}

/* Parameter validation shared by init (returns the status init documents). */
static uvms_status_t cart_params_check(const uvms_cart_traj_params_t *p) {
  if (!uvms_isfinite(p->distance_m) || !uvms_v3_isfinite_fast(p->direction) ||
      !uvms_isfinite(p->duration_s) || !uvms_isfinite(p->damping_m) ||
      !uvms_isfinite(p->position_gain_1_s) || !uvms_isfinite(p->nullspace_gain_1_s) ||
      !uvms_isfinite(p->max_joint_rate_rad_s)) {
    return UVMS_ERR_NONFINITE;
  }
  if (!(p->duration_s > UVMS_R(0.0)) || !(p->damping_m > UVMS_R(0.0)) ||
      p->position_gain_1_s < UVMS_R(0.0) || p->nullspace_gain_1_s < UVMS_R(0.0) ||
      !(p->max_joint_rate_rad_s > UVMS_R(0.0)) ||
      !(uvms_v3_norm(p->direction) >= UVMS_TRAJ_MIN_DIRECTION_NORM) ||
      (p->reference != UVMS_REF_VEHICLE && p->reference != UVMS_REF_BARYCENTER)) {
    return UVMS_ERR_RANGE;
  }
  return UVMS_OK;
}

uvms_status_t uvms_cart_traj_init(uvms_cart_traj_t *traj, const uvms_cart_traj_params_t *params,
                                  const uvms_arm_model_t *model, uvms_arm_data_t *work,
                                  const uvms_real_t *q_start_rad, const uvms_real_t r0d_m[3],
                                  const uvms_real_t R0d[9]) {
  if (traj == NULL) return UVMS_ERR_ARG;
  if (params == NULL || model == NULL || work == NULL || q_start_rad == NULL || r0d_m == NULL ||
      R0d == NULL) {
    memset(traj, 0, sizeof(*traj));
    return UVMS_ERR_ARG;
  }
  if (!model->ready) {
    memset(traj, 0, sizeof(*traj));
    return UVMS_ERR_STATE;
  }
  const size_t n = uvms_arm_joint_count(model);
  /* Copy the inputs before touching traj: callers may re-initialise from traj's own fields
   * (e.g. params = &traj->p, q_start_rad = traj->q_start_rad). */
  const uvms_cart_traj_params_t prm = *params;
  uvms_real_t q0[UVMS_MAX_JOINTS] = {0}, r0d[3], R0[9];
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) q0[i] = q_start_rad[i];
  uvms_v3_copy(r0d_m, r0d);
  for (size_t k = 0; k < 9; ++k) R0[k] = R0d[k];
  memset(traj, 0, sizeof(*traj));

  uvms_status_t st = cart_params_check(&prm);
  if (st != UVMS_OK) return st;
  if (!uvms_all_finite_fast(q0, n) || !uvms_v3_isfinite_fast(r0d) || !uvms_all_finite_fast(R0, 9)) {
    return UVMS_ERR_NONFINITE;
  }

  traj->p = prm;
  uvms_v3_scale(prm.direction, UVMS_R(1.0) / uvms_v3_norm(prm.direction), traj->p.direction);
  traj->n = n;
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) {
    traj->q_start_rad[i] = q0[i];
    traj->q_ref_rad[i] = q0[i];
  }
  uvms_v3_copy(r0d, traj->r0d_m);
  for (size_t k = 0; k < 9; ++k) traj->R0d[k] = R0[k];

  /* barycenter0 [5] at (r0d, R0d, q_start), then the line's start r̂(q_start). */
  st = uvms_arm_fk(model, work, r0d, R0, q0);
  if (st != UVMS_OK) {
    memset(traj, 0, sizeof(*traj));
    return st;
  }
  uvms_v3_copy(work->barycenter_m, traj->barycenter0_m);
  uvms_real_t Jt[3 * UVMS_MAX_JOINTS];
  st = cart_task(traj, model, work, q0, traj->r_start_m, Jt);
  if (st != UVMS_OK) {
    memset(traj, 0, sizeof(*traj));
    return st;
  }
  uvms_v3_copy(traj->r_start_m, traj->r_est_m);
  uvms_v3_copy(traj->r_start_m, traj->r_des_m);
  traj->ready = 1;
  return UVMS_OK;
}

/* Rate law without argument checks (callers validated traj, model, work, q). */
static uvms_status_t cart_rate(const uvms_cart_traj_t *traj, const uvms_arm_model_t *model,
                               uvms_arm_data_t *work, uvms_real_t t_s, const uvms_real_t *q_rad,
                               uvms_real_t qd_rad_s[UVMS_MAX_JOINTS], uvms_real_t r_est_m[3],
                               uvms_real_t r_des_m[3]) {
  const size_t n = clamp_count(traj->n);
  const uvms_cart_traj_params_t *p = &traj->p;
  uvms_real_t Jt[3 * UVMS_MAX_JOINTS] = {0};
  zero_n(qd_rad_s, UVMS_MAX_JOINTS);

  /* Desired line point and velocity [78]. */
  uvms_real_t v_d[3], a_d[3];
  uvms_status_t st = uvms_cosine_line_eval(traj->r_start_m, p->direction, p->distance_m,
                                           p->duration_s, t_s, r_des_m, v_d, a_d);
  if (st != UVMS_OK) return st;
  st = cart_task(traj, model, work, q_rad, r_est_m, Jt);
  if (st != UVMS_OK) return st;

  /* v = ṙ_d + K·(r_d − r̂): the closed-loop task velocity (CLIK). */
  uvms_real_t v[3], e[3];
  uvms_v3_sub(r_des_m, r_est_m, e);
  uvms_v3_copy(v_d, v);
  uvms_v3_axpy(p->position_gain_1_s, e, v);

  /* z = k0·(q_start − q): the secondary task, projected by (I − J⁺J) below. */
  uvms_real_t z[UVMS_MAX_JOINTS] = {0};
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) {
    z[i] = p->nullspace_gain_1_s * (traj->q_start_rad[i] - q_rad[i]);
  }
  /* w = v − J·z; A = J·Jᵀ + λ²I. */
  uvms_real_t w[3], A[9];
  for (size_t r = 0; r < 3; ++r) {
    uvms_real_t jz = UVMS_R(0.0);
    for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) jz += Jt[r * n + i] * z[i];
    w[r] = v[r] - jz;
    for (size_t c = 0; c < 3; ++c) {
      uvms_real_t s = UVMS_R(0.0);
      for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) s += Jt[r * n + i] * Jt[c * n + i];
      A[3 * r + c] = s;
    }
    A[3 * r + r] += p->damping_m * p->damping_m;
  }
  /* q̇ = J⁺·v + (I − J⁺J)·z = z + Jᵀ·A⁻¹·(v − J·z), J⁺ = Jᵀ·A⁻¹ (DLS). */
  uvms_real_t y[3];
  st = uvms_spd_solve(3, A, 1, w, y, CART_REL_PIVOT_TOL);
  if (st != UVMS_OK) return st;
  uvms_real_t peak_rad_s = UVMS_R(0.0);
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) {
    qd_rad_s[i] = z[i] + Jt[i] * y[0] + Jt[n + i] * y[1] + Jt[2 * n + i] * y[2];
    const uvms_real_t mag = uvms_fabs(qd_rad_s[i]);
    if (mag > peak_rad_s) peak_rad_s = mag;
  }
  if (!uvms_all_finite_fast(qd_rad_s, n) || !uvms_isfinite(peak_rad_s)) {
    zero_n(qd_rad_s, UVMS_MAX_JOINTS);
    return UVMS_ERR_NONFINITE;
  }
  /* Rate limit: uniform scaling keeps the joint-space direction, hence (to first order) the
   * direction of the EE velocity; the K loop recovers the lag once the limit releases. */
  if (peak_rad_s > p->max_joint_rate_rad_s) {
    const uvms_real_t scale = p->max_joint_rate_rad_s / peak_rad_s;
    for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) qd_rad_s[i] *= scale;
  }
  return UVMS_OK;
}

/* Common precondition of rate and step: traj ready and matching a ready model. */
static uvms_status_t cart_ready(const uvms_cart_traj_t *traj, const uvms_arm_model_t *model) {
  if (!traj->ready || !model->ready) return UVMS_ERR_STATE;
  if (model->num_joints != traj->n || traj->n < 1 || traj->n > UVMS_MAX_JOINTS) {
    return UVMS_ERR_ARG;
  }
  return UVMS_OK;
}

uvms_status_t uvms_cart_traj_rate(const uvms_cart_traj_t *traj, const uvms_arm_model_t *model,
                                  uvms_arm_data_t *work, uvms_real_t t_s,
                                  const uvms_real_t *q_rad, uvms_real_t *qd_rad_s,
                                  uvms_real_t r_est_m[3]) {
  zero_n(qd_rad_s, UVMS_MAX_JOINTS);
  zero_n(r_est_m, 3);
  if (traj == NULL || model == NULL || work == NULL || q_rad == NULL || qd_rad_s == NULL) {
    return UVMS_ERR_ARG;
  }
  uvms_status_t st = cart_ready(traj, model);
  if (st != UVMS_OK) return st;
  if (!uvms_isfinite(t_s) || !uvms_all_finite_fast(q_rad, traj->n)) return UVMS_ERR_NONFINITE;
  uvms_real_t r_est[3], r_des[3];
  st = cart_rate(traj, model, work, t_s, q_rad, qd_rad_s, r_est, r_des);
  if (st != UVMS_OK) return st;
  if (r_est_m != NULL) uvms_v3_copy(r_est, r_est_m);
  return UVMS_OK;
}

uvms_status_t uvms_cart_traj_step(uvms_cart_traj_t *traj, const uvms_arm_model_t *model,
                                  uvms_arm_data_t *work, uvms_real_t t_s, uvms_real_t dt_s,
                                  uvms_real_t *q_ref_rad, uvms_real_t *qd_ref_rad_s,
                                  uvms_real_t *qdd_ref_rad_s2) {
  zero_n(q_ref_rad, UVMS_MAX_JOINTS);
  zero_n(qd_ref_rad_s, UVMS_MAX_JOINTS);
  zero_n(qdd_ref_rad_s2, UVMS_MAX_JOINTS);
  if (traj == NULL || model == NULL || work == NULL || q_ref_rad == NULL ||
      qd_ref_rad_s == NULL || qdd_ref_rad_s2 == NULL) {
    return UVMS_ERR_ARG;
  }
  uvms_status_t st = cart_ready(traj, model);
  if (st != UVMS_OK) return st;
  const size_t n = clamp_count(traj->n);
  /* From here on the safe output is the hold: the stored reference, zero rate/accel. */
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) q_ref_rad[i] = traj->q_ref_rad[i];
  if (!uvms_isfinite(t_s) || !uvms_isfinite(dt_s)) return UVMS_ERR_NONFINITE;
  const uvms_real_t kmax = (traj->p.position_gain_1_s > traj->p.nullspace_gain_1_s)
                               ? traj->p.position_gain_1_s
                               : traj->p.nullspace_gain_1_s;
  if (!(dt_s > UVMS_R(0.0)) || kmax * dt_s > UVMS_CART_TRAJ_MAX_GAIN_DT) return UVMS_ERR_RANGE;

  /* Heun (explicit trapezoid): f1 = f(t, q); q_pred = q + dt·f1; f2 = f(t + dt, q_pred). */
  uvms_real_t f1[UVMS_MAX_JOINTS], f2[UVMS_MAX_JOINTS], q_pred[UVMS_MAX_JOINTS] = {0};
  uvms_real_t r_est[3], r_des[3], r_est2[3], r_des2[3];
  st = cart_rate(traj, model, work, t_s, traj->q_ref_rad, f1, r_est, r_des);
  if (st != UVMS_OK) return st;
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) {
    q_pred[i] = traj->q_ref_rad[i] + dt_s * f1[i];
  }
  st = cart_rate(traj, model, work, t_s + dt_s, q_pred, f2, r_est2, r_des2);
  if (st != UVMS_OK) return st;

  uvms_real_t q_next[UVMS_MAX_JOINTS] = {0}, qdd[UVMS_MAX_JOINTS] = {0};
  const uvms_real_t half_dt = UVMS_R(0.5) * dt_s;
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) {
    qdd[i] = (f2[i] - f1[i]) / dt_s;
    q_next[i] = traj->q_ref_rad[i] + half_dt * (f1[i] + f2[i]);
  }
  if (!uvms_all_finite_fast(qdd, n) || !uvms_all_finite_fast(q_next, n)) return UVMS_ERR_NONFINITE;

  /* Emit the triple at t_s, then commit the state at t_s + dt_s. */
  for (size_t i = 0; i < n && i < UVMS_MAX_JOINTS; ++i) {
    qd_ref_rad_s[i] = f1[i];
    qdd_ref_rad_s2[i] = qdd[i];
    traj->qd_ref_rad_s[i] = f1[i];
    traj->qdd_ref_rad_s2[i] = qdd[i];
    traj->q_ref_rad[i] = q_next[i];
  }
  uvms_v3_copy(r_est, traj->r_est_m);
  uvms_v3_copy(r_des, traj->r_des_m);
  traj->t_state_s = t_s + dt_s;
  return UVMS_OK;
}
