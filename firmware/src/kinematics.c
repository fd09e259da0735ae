/* SPDX-License-Identifier: Apache-2.0 */
/* kinematics.c: forward kinematics, Jacobians, barycenter (SPEC §2, [1]–[5], [10–11]). */
#include "uvms/kinematics.h"

#include <string.h>

#include "uvms/linalg.h"
#include "fw_fast.h"

/* R = Rp·Rz(θ)·Rx(α), column by column (c0, c1, c2: the columns of Rp):
     x = cθ·c0 + sθ·c1,  y = cα·v + sα·c2,  z = −sα·v + cα·c2,  v = −sθ·c0 + cθ·c1,
   the columns of Rz(θ)·Rx(α) = [cθ −sθcα sθsα; sθ cθcα −cθsα; 0 sα cα] applied to Rp (24
   products instead of the 27 of a general 3×3 product). Also sα·y + cα·z = c2. */
static void dh_rotate(const uvms_real_t Rp[9], uvms_real_t ct, uvms_real_t st, uvms_real_t ca,
                      uvms_real_t sa, uvms_real_t R[9]) {
  for (int r = 0; r < 3; ++r) {
    const uvms_real_t c0 = Rp[3 * r], c1 = Rp[3 * r + 1], c2 = Rp[3 * r + 2];
    const uvms_real_t v = ct * c1 - st * c0;
    R[3 * r] = ct * c0 + st * c1;
    R[3 * r + 1] = ca * v + sa * c2;
    R[3 * r + 2] = ca * c2 - sa * v;
  }
}

/* A general link (docs/MODEL.md §2 "General links"), after the DH step wrote R = R_{i−1}·A_i
   into R_i and R·l_DH into R_i·l_i: the fixed placement T(t_i)·Rot(ρ_i) follows, so
   R_i·l_i += R·t_i and R_i = R·Rot(ρ_i). Out of line: the paper's DH links pay one test. */
static void place_link(const uvms_arm_model_t *model, uvms_arm_data_t *data, size_t i) {
  const uvms_link_params_t *L = &model->p->link[i - 1];
  uvms_real_t R[9], t[3];
  for (int k = 0; k < 9; ++k) R[k] = data->R[i][k];
  uvms_m3_mul_v3(R, L->placement_m, t);
  uvms_v3_add(data->Rl_m[i], t, data->Rl_m[i]);
  uvms_m3_mul(R, model->place_rot[i], data->R[i]);
}

uvms_status_t uvms_arm_fk(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                          const uvms_real_t r0_m[3], const uvms_real_t R0[9],
                          const uvms_real_t *q_rad) {
  if (data == NULL) return UVMS_ERR_ARG;
  if (model == NULL || r0_m == NULL || R0 == NULL || q_rad == NULL) {
    memset(data, 0, sizeof *data);
    return UVMS_ERR_ARG;
  }
  if (!model->ready) {
    memset(data, 0, sizeof *data);
    return UVMS_ERR_STATE;
  }
  const size_t n = uvms_arm_joint_count(model);
  const uvms_arm_params_t *p = model->p;

  /* Base frame B: origin r0 + R0·s0, axes of the vehicle (SPEC §2), or turned by the mount's
     rotation (docs/MODEL.md §2 "General links"). */
  if (model->base_rotated)
    uvms_m3_mul(R0, model->base_rot, data->R[0]);
  else
    for (int k = 0; k < 9; ++k) data->R[0][k] = R0[k];
  uvms_m3_mul_v3(R0, p->vehicle.base_offset_m, data->R0s0_m);
  uvms_v3_add(r0_m, data->R0s0_m, data->p_m[0]);

  uvms_real_t msum[3];
  uvms_v3_scale(r0_m, p->vehicle.mass_kg, msum);
  const unsigned placed = model->placed; /* a local: the stores below may alias the model */
#if UVMS_FW_WORK_AHEAD
  uvms_real_t sin_q[UVMS_MAX_JOINTS + 1], cos_q[UVMS_MAX_JOINTS + 1]; /* fw_fast.h */
  for (size_t i = 1; i <= n && i <= UVMS_MAX_JOINTS; ++i)
    uvms_sincos(q_rad[i - 1], &sin_q[i], &cos_q[i]);
#endif
  for (size_t i = 1; i <= n && i <= UVMS_MAX_JOINTS; ++i) {
    const uvms_real_t *Rp = data->R[i - 1];
    /* Joint i turns about z of frame i−1 [10–11]: third column of R_{i−1}. */
    uvms_v3_set(data->z[i], Rp[2], Rp[5], Rp[8]);
#if UVMS_FW_WORK_AHEAD
    const uvms_real_t ct = cos_q[i], st = sin_q[i];
#else
    uvms_real_t ct, st;
    uvms_sincos(q_rad[i - 1], &st, &ct);
#endif
    const uvms_link_params_t *L = &p->link[i - 1];
    uvms_real_t *Rl = data->Rl_m[i];
    const uvms_real_t *Ri = data->R[i];
    /* A_i = Rz(θ_i)·Rx(α_i) (standard DH rotation part); R_i = R_{i−1}·A_i. */
    dh_rotate(Rp, ct, st, model->cos_alpha[i], model->sin_alpha[i], data->R[i]);
    /* [3]: p_i* = p_{i−1}* + R_i·l_i; CoM c_i = p_{i−1}* + R_i·r_i (SPEC §2). With
       l_i = (a_i, d_i·sin α_i, d_i·cos α_i): R_i·l_i = a_i·x_i + d_i·z_{i−1} (dh_rotate). */
    uvms_v3_set(Rl, L->a_m * Ri[0] + L->d_m * Rp[2], L->a_m * Ri[3] + L->d_m * Rp[5],
                L->a_m * Ri[6] + L->d_m * Rp[8]);
    if ((placed >> i) & 1u) place_link(model, data, i);
    uvms_m3_mul_v3(Ri, L->com_m, data->Rr_m[i]);
    uvms_v3_add(data->p_m[i - 1], Rl, data->p_m[i]);
    uvms_v3_add(data->p_m[i - 1], data->Rr_m[i], data->com_m[i]);
    uvms_v3_axpy(L->mass_kg, data->com_m[i], msum);
  }
  uvms_v3_copy(data->p_m[n], data->ee_m);
  uvms_real_t off[3];
  uvms_m3_mul_v3(data->R[n], p->payload_offset_m, off);
  uvms_v3_add(data->ee_m, off, data->payload_m);
  uvms_v3_axpy(p->payload_kg, data->payload_m, msum);
  /* [5]: p_cm = (m0·r0 + Σ m_i·c_i + m_{N+1}·p_payload) / m_T. */
  uvms_v3_scale(msum, model->inv_total_mass_1_kg, data->barycenter_m);
  return UVMS_OK;
}

uvms_status_t uvms_arm_jacobian(const uvms_arm_model_t *model, const uvms_arm_data_t *data,
                                uvms_real_t *J) {
  if (J == NULL) return UVMS_ERR_ARG;
  if (model == NULL || data == NULL || !model->ready) {
    for (size_t k = 0; k < 6 * UVMS_MAX_JOINTS; ++k) J[k] = UVMS_R(0.0);
    return (model != NULL && data != NULL) ? UVMS_ERR_STATE : UVMS_ERR_ARG;
  }
  const size_t n = uvms_arm_joint_count(model);
  for (size_t i = 1; i <= n && i <= UVMS_MAX_JOINTS; ++i) {
    uvms_real_t d[3], c[3];
    uvms_v3_sub(data->ee_m, data->p_m[i - 1], d);
    uvms_v3_cross(data->z[i], d, c);
    for (size_t r = 0; r < 3; ++r) {
      J[r * n + (i - 1)] = c[r];
      J[(r + 3) * n + (i - 1)] = data->z[i][r];
    }
  }
  return UVMS_OK;
}

uvms_status_t uvms_arm_barycenter_jacobian(const uvms_arm_model_t *model,
                                           const uvms_arm_data_t *data, uvms_real_t *Jcm) {
  if (Jcm == NULL) return UVMS_ERR_ARG;
  for (size_t k = 0; k < 3 * UVMS_MAX_JOINTS; ++k) Jcm[k] = UVMS_R(0.0);
  if (model == NULL || data == NULL) return UVMS_ERR_ARG;
  if (!model->ready) return UVMS_ERR_STATE;
  const size_t n = uvms_arm_joint_count(model);
  const uvms_arm_params_t *p = model->p;
  const uvms_real_t inv_mT = model->inv_total_mass_1_kg;
  /* Joint j moves every body distal to it: ∂x/∂θ_j = z_j × (x − p_{j−1}*). */
  for (size_t j = 1; j <= n && j <= UVMS_MAX_JOINTS; ++j) {
    uvms_real_t moment[3] = {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0)}; /* Σ m·(x − p_{j−1}) */
    for (size_t i = j; i <= n && i <= UVMS_MAX_JOINTS; ++i) {
      uvms_real_t d[3];
      uvms_v3_sub(data->com_m[i], data->p_m[j - 1], d);
      uvms_v3_axpy(p->link[i - 1].mass_kg, d, moment);
    }
    uvms_real_t d8[3];
    uvms_v3_sub(data->payload_m, data->p_m[j - 1], d8);
    uvms_v3_axpy(p->payload_kg, d8, moment);
    uvms_real_t c[3];
    uvms_v3_cross(data->z[j], moment, c);
    for (size_t r = 0; r < 3; ++r) Jcm[r * n + (j - 1)] = c[r] * inv_mT;
  }
  return UVMS_OK;
}

uvms_status_t uvms_arm_ee_minus_barycenter(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                                           const uvms_real_t R0[9], const uvms_real_t *q_rad,
                                           uvms_real_t ee_rel_m[3]) {
  if (ee_rel_m == NULL) return UVMS_ERR_ARG;
  uvms_v3_set(ee_rel_m, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  const uvms_real_t origin[3] = {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0)};
  const uvms_status_t st = uvms_arm_fk(model, data, origin, R0, q_rad);
  if (st != UVMS_OK) return st;
  /* [4]: with r0 = 0 the difference is exactly the virtual-manipulator vector. */
  uvms_v3_sub(data->ee_m, data->barycenter_m, ee_rel_m);
  return UVMS_OK;
}
