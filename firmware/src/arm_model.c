/* SPDX-License-Identifier: Apache-2.0 */
/* arm_model.c: parameters, validation and derived geometry of the model (SPEC §2–3), and the
   check of the model's fluid. */
#include "uvms/arm_model.h"

#include <string.h>

#include "uvms/linalg.h"

void uvms_added_mass_paper(uvms_real_t Ma0[36]) {
  /* SPEC §3.3 [26–27], unscaled; multiplied by ρ·V of each body. */
  static const uvms_real_t k[36] = {
      UVMS_R(0.1), UVMS_R(0.0),   UVMS_R(0.0),    UVMS_R(0.0),   UVMS_R(0.0),    UVMS_R(0.0),
      UVMS_R(0.0), UVMS_R(0.1),   UVMS_R(-0.01),  UVMS_R(0.0),   UVMS_R(0.0),    UVMS_R(0.0),
      UVMS_R(0.0), UVMS_R(-0.01), UVMS_R(0.1),    UVMS_R(0.0),   UVMS_R(-0.001), UVMS_R(0.0),
      UVMS_R(0.0), UVMS_R(0.0),   UVMS_R(0.0),    UVMS_R(0.01),  UVMS_R(0.0),    UVMS_R(0.001),
      UVMS_R(0.0), UVMS_R(0.0),   UVMS_R(-0.001), UVMS_R(0.0),   UVMS_R(0.01),   UVMS_R(0.0),
      UVMS_R(0.0), UVMS_R(0.0),   UVMS_R(0.0),    UVMS_R(0.001), UVMS_R(0.0),    UVMS_R(0.01)};
  for (int i = 0; i < 36; ++i) Ma0[i] = k[i];
}

void uvms_arm_params_paper(uvms_arm_params_t *params) {
  if (params == NULL) return;
  memset(params, 0, sizeof *params);
  /* SPEC §3.1 table: m_i [kg], α_i [rad], a_i [m], d_i [m], r_i [mm → m], I_Bi diag [kg·m²]. */
  static const struct {
    double m, alpha, a, d, r[3], I[3];
  } wam[7] = {
      {10.77, -1.0, 0.0, 0.0, {-4.4, 121.9, -0.7}, {0.1349, 0.1133, 0.0905}},
      {3.87, 1.0, 0.0, 0.0, {-2.4, 31.1, 15.4}, {0.0214, 0.0138, 0.0156}},
      {1.80, -1.0, 0.045, 0.550, {6.7, -342.5, 0.0}, {0.0591, 0.0032, 0.0593}},
      {2.40, 1.0, -0.045, 0.0, {-40.0, -0.2, 132.7}, {0.0149, 0.0148, 0.0029}},
      {0.12, -1.0, 0.0, 0.300, {0.1, -294.9, 4.4}, {0.0001, 0.0001, 0.0001}},
      {0.42, 1.0, 0.0, 0.0, {-0.1, -17.0, 24.7}, {0.0006, 0.0002, 0.0004}},
      {0.07, 0.0, 0.0, 0.060, {-0.1, 0.2, 56.8}, {0.0000, 0.0000, 0.0001}},
  };
  params->num_joints = 7;
  for (int i = 0; i < 7; ++i) {
    uvms_link_params_t *L = &params->link[i];
    L->alpha_rad = (uvms_real_t)wam[i].alpha * (UVMS_PI / UVMS_R(2.0)); /* ±π/2 or 0 */
    L->a_m = (uvms_real_t)wam[i].a;
    L->d_m = (uvms_real_t)wam[i].d;
    L->mass_kg = (uvms_real_t)wam[i].m;
    for (int k = 0; k < 3; ++k) {
      L->com_m[k] = (uvms_real_t)wam[i].r[k] * UVMS_R(1e-3); /* mm → m */
      L->inertia_kg_m2[k] = (uvms_real_t)wam[i].I[k];
    }
    L->diameter_m = UVMS_R(0.089); /* d_L */
    L->drag_coeff = UVMS_R(1.0);   /* C_D0L */
    /* Joint limits are not in the paper: ±2π admits every pose of SPEC §8's table
       (up to 266°) and rejects only implausible sensor values. */
    L->joint_min_rad = UVMS_R(-2.0) * UVMS_PI;
    L->joint_max_rad = UVMS_R(2.0) * UVMS_PI;
  }
  uvms_vehicle_params_t *v = &params->vehicle;
  v->mass_kg = UVMS_R(120.0);
  v->volume_m3 = UVMS_R(0.15);
  v->frontal_area_m2 = UVMS_R(0.5);
  v->drag_coeff = UVMS_R(1.2);
  uvms_v3_set(v->inertia_kg_m2, UVMS_R(20.0), UVMS_R(20.0), UVMS_R(20.0));
  uvms_v3_set(v->cob_m, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  uvms_v3_set(v->base_offset_m, UVMS_R(0.914), UVMS_R(0.0), UVMS_R(0.152));
  v->ballast_kg = UVMS_R(0.0);
  uvms_v3_set(v->ballast_offset_m, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  params->payload_kg = UVMS_R(10.0);
  uvms_v3_set(params->payload_offset_m, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  uvms_added_mass_paper(params->added_mass_coeff);
}

/* A link's inertia tensor [Ixx Ixy Ixz; Ixy Iyy Iyz; Ixz Iyz Izz] is positive semidefinite:
   its principal minors are ≥ 0 (Sylvester), to a rounding tolerance of 1e-6 of the trace's
   scale. The diagonal's sign is checked by the caller. */
static int inertia_psd(const uvms_link_params_t *L) {
  const uvms_real_t *d = L->inertia_kg_m2, *o = L->inertia_products_kg_m2;
  const uvms_real_t scale = d[0] + d[1] + d[2];
  const uvms_real_t tol2 = UVMS_R(1e-6) * scale * scale, tol3 = tol2 * scale;
  const uvms_real_t mxy = d[0] * d[1] - o[0] * o[0];
  const uvms_real_t mxz = d[0] * d[2] - o[1] * o[1];
  const uvms_real_t myz = d[1] * d[2] - o[2] * o[2];
  const uvms_real_t det = d[0] * myz - o[0] * (o[0] * d[2] - o[2] * o[1]) +
                          o[1] * (o[0] * o[2] - d[1] * o[1]);
  return mxy >= -tol2 && mxz >= -tol2 && myz >= -tol2 && det >= -tol3;
}

/* R = Rot(ρ) of a rotation vector ρ = e·φ (Rodrigues, through the unit quaternion
   (cos φ/2, sin φ/2·e)); ρ = 0 gives the identity. */
static void rotvec_to_rot(const uvms_real_t rho[3], uvms_real_t R[9]) {
  const uvms_real_t phi = uvms_v3_norm(rho);
  if (!(phi > UVMS_R(0.0))) {
    uvms_m3_identity(R);
    return;
  }
  const uvms_real_t k = uvms_sin(UVMS_R(0.5) * phi) / phi;
  const uvms_real_t q[4] = {uvms_cos(UVMS_R(0.5) * phi), k * rho[0], k * rho[1], k * rho[2]};
  (void)uvms_quat_to_rot(q, R); /* finite and unit by construction */
}

static int nonzero3(const uvms_real_t v[3]) {
  return v[0] != UVMS_R(0.0) || v[1] != UVMS_R(0.0) || v[2] != UVMS_R(0.0);
}

static uvms_status_t check_params(const uvms_arm_params_t *p) {
  if (p->num_joints < 1 || p->num_joints > UVMS_MAX_JOINTS) return UVMS_ERR_SIZE;
  for (size_t i = 0; i < p->num_joints; ++i) {
    const uvms_link_params_t *L = &p->link[i];
    const uvms_real_t scalars[8] = {L->alpha_rad,  L->a_m,        L->d_m,
                                    L->mass_kg,    L->diameter_m, L->drag_coeff,
                                    L->joint_min_rad, L->joint_max_rad};
    if (!uvms_all_finite(scalars, 8) || !uvms_all_finite(L->com_m, 3) ||
        !uvms_all_finite(L->inertia_kg_m2, 3) || !uvms_all_finite(L->inertia_products_kg_m2, 3) ||
        !uvms_all_finite(L->placement_m, 3) || !uvms_all_finite(L->placement_rotvec_rad, 3) ||
        !uvms_all_finite(L->added_mass_kg, 6))
      return UVMS_ERR_NONFINITE;
    for (int k = 0; k < 6; ++k)
      if (L->added_mass_kg[k] < UVMS_R(0.0)) return UVMS_ERR_RANGE;
    if (L->mass_kg < UVMS_R(0.0) || L->diameter_m < UVMS_R(0.0) ||
        L->drag_coeff < UVMS_R(0.0) || L->inertia_kg_m2[0] < UVMS_R(0.0) ||
        L->inertia_kg_m2[1] < UVMS_R(0.0) || L->inertia_kg_m2[2] < UVMS_R(0.0) ||
        !(L->joint_min_rad < L->joint_max_rad) || !inertia_psd(L))
      return UVMS_ERR_RANGE;
  }
  const uvms_vehicle_params_t *v = &p->vehicle;
  const uvms_real_t vs[5] = {v->mass_kg, v->volume_m3, v->frontal_area_m2, v->drag_coeff,
                             v->ballast_kg};
  if (!uvms_all_finite(vs, 5) || !uvms_all_finite(v->inertia_kg_m2, 3) ||
      !uvms_all_finite(v->cob_m, 3) || !uvms_all_finite(v->base_offset_m, 3) ||
      !uvms_all_finite(v->base_rotvec_rad, 3) ||
      !uvms_all_finite(v->ballast_offset_m, 3) || !uvms_isfinite(p->payload_kg) ||
      !uvms_all_finite(p->payload_offset_m, 3) || !uvms_all_finite(p->added_mass_coeff, 36) ||
      !uvms_all_finite(v->linear_damping, 6) || !uvms_all_finite(v->quadratic_damping, 6))
    return UVMS_ERR_NONFINITE;
  for (int k = 0; k < 6; ++k)
    if (v->linear_damping[k] < UVMS_R(0.0) || v->quadratic_damping[k] < UVMS_R(0.0))
      return UVMS_ERR_RANGE;
  if (!(v->mass_kg > UVMS_R(0.0)) || v->volume_m3 < UVMS_R(0.0) ||
      v->frontal_area_m2 < UVMS_R(0.0) || v->drag_coeff < UVMS_R(0.0) ||
      !(v->inertia_kg_m2[0] > UVMS_R(0.0)) || !(v->inertia_kg_m2[1] > UVMS_R(0.0)) ||
      !(v->inertia_kg_m2[2] > UVMS_R(0.0)) || p->payload_kg < UVMS_R(0.0))
    return UVMS_ERR_RANGE;
  return UVMS_OK;
}

uvms_status_t uvms_fluid_check(const uvms_fluid_t *fluid) {
  if (fluid == NULL) return UVMS_ERR_ARG;
  if (!uvms_isfinite(fluid->density_kg_m3) || !uvms_all_finite(fluid->flow_m_s, 3) ||
      !uvms_all_finite(fluid->gravity_m_s2, 3))
    return UVMS_ERR_NONFINITE;
  if (!(fluid->density_kg_m3 > UVMS_R(0.0)) ||
      (fluid->angle_of_attack != 0 && fluid->angle_of_attack != 1))
    return UVMS_ERR_RANGE;
  return UVMS_OK;
}

uvms_status_t uvms_arm_model_init(const uvms_arm_params_t *params, uvms_arm_model_t *model) {
  if (model == NULL) return UVMS_ERR_ARG;
  memset(model, 0, sizeof *model);
  if (params == NULL) return UVMS_ERR_ARG;
  const uvms_status_t st = check_params(params);
  if (st != UVMS_OK) return st;

  model->p = params;
  model->num_joints = params->num_joints;
  uvms_real_t mT = params->vehicle.mass_kg + params->payload_kg;
  for (size_t i = 1; i <= params->num_joints; ++i) {
    const uvms_link_params_t *L = &params->link[i - 1];
    /* [1]: l_i = (a_i, d_i sin α_i, d_i cos α_i), frame i; s_i = l_i − r_i. */
    uvms_v3_set(model->l_m[i], L->a_m, L->d_m * uvms_sin(L->alpha_rad),
                L->d_m * uvms_cos(L->alpha_rad));
    if (nonzero3(L->placement_m) || nonzero3(L->placement_rotvec_rad)) {
      /* Origin i from origin i−1 in frame i: Rot(ρ_i)ᵀ·(l_DH + t_i). */
      uvms_real_t t[3];
      model->placed |= 1u << i;
      rotvec_to_rot(L->placement_rotvec_rad, model->place_rot[i]);
      uvms_v3_add(model->l_m[i], L->placement_m, t);
      uvms_m3t_mul_v3(model->place_rot[i], t, model->l_m[i]);
    }
    uvms_v3_sub(model->l_m[i], L->com_m, model->s_m[i]);
    const uvms_real_t len = uvms_v3_norm(model->l_m[i]);
    model->length_m[i] = len;
    model->inv_length_1_m[i] = (len > UVMS_R(0.0)) ? UVMS_R(1.0) / len : UVMS_R(0.0);
    /* SPEC §3.1: cylinder of diameter d_L along l_i; links with |l_i| = 0 have no hydro. */
    model->volume_m3[i] = UVMS_PI * L->diameter_m * L->diameter_m / UVMS_R(4.0) * len;
    model->area_m2[i] = L->diameter_m * len;
    model->cos_alpha[i] = uvms_cos(L->alpha_rad);
    model->sin_alpha[i] = uvms_sin(L->alpha_rad);
    if (nonzero3(L->inertia_products_kg_m2)) model->full_inertia |= 1u << i;
    if (nonzero3(&L->added_mass_kg[0]) || nonzero3(&L->added_mass_kg[3]))
      model->own_added_mass |= 1u << i;
    mT += L->mass_kg;
  }
  model->total_mass_kg = mT;
  model->inv_total_mass_1_kg = UVMS_R(1.0) / mT;
  uvms_m3_identity(model->base_rot);
  if (nonzero3(params->vehicle.base_rotvec_rad)) {
    model->base_rotated = 1;
    rotvec_to_rot(params->vehicle.base_rotvec_rad, model->base_rot);
  }
  for (int k = 0; k < 6; ++k)
    if (params->vehicle.linear_damping[k] > UVMS_R(0.0) ||
        params->vehicle.quadratic_damping[k] > UVMS_R(0.0))
      model->vehicle_damping = 1;
  model->ready = 1;
  return UVMS_OK;
}
