/* SPDX-License-Identifier: Apache-2.0 */
/* dynamics.c: recursive Newton–Euler with hydrodynamics on a moving base (SPEC §4). */
#include "uvms/dynamics.h"

#include <string.h>

#include "uvms/kinematics.h"
#include "uvms/linalg.h"
#include "fw_fast.h"

/* a = a_prev + α × r + ω × (ω × r): acceleration of a point rigidly attached at offset r.
   Inlined into its callers (the forward pass's base point and payload): as a call it cost its
   operands' trip through memory. */
UVMS_FW_INLINE void rigid_accel(const uvms_real_t a_prev[3], const uvms_real_t alpha[3],
                                const uvms_real_t omega[3], const uvms_real_t r[3],
                                uvms_real_t out[3]) {
  uvms_real_t t[3], u[3];
  uvms_v3_cross(alpha, r, t);
  uvms_v3_cross(omega, r, u);
  uvms_v3_cross(omega, u, u);
  out[0] = a_prev[0] + t[0] + u[0];
  out[1] = a_prev[1] + t[1] + u[1];
  out[2] = a_prev[2] + t[2] + u[2];
}

/* K = [ω̇]× + [ω]×[ω]× = [ω̇]× + ω·ωᵀ − |ω|²·I: a rigid body's point acceleration relative to
   another of its points, α × r + ω × (ω × r) = K·r, as one 3×3 matrix (row-major), so that a
   link's several points cost one 3×3 product each instead of three cross products. */
static void rigid_accel_matrix(const uvms_real_t alpha[3], const uvms_real_t omega[3],
                               uvms_real_t K[9]) {
  const uvms_real_t xx = omega[0] * omega[0], yy = omega[1] * omega[1], zz = omega[2] * omega[2];
  const uvms_real_t xy = omega[0] * omega[1], xz = omega[0] * omega[2], yz = omega[1] * omega[2];
  K[0] = -(yy + zz);
  K[1] = xy - alpha[2];
  K[2] = xz + alpha[1];
  K[3] = xy + alpha[2];
  K[4] = -(xx + zz);
  K[5] = yz - alpha[0];
  K[6] = xz - alpha[1];
  K[7] = yz + alpha[0];
  K[8] = -(xx + yy);
}

/* a = a_prev + K·r (rigid_accel_matrix) */
static void rigid_accel_k(const uvms_real_t a_prev[3], const uvms_real_t K[9],
                          const uvms_real_t r[3], uvms_real_t out[3]) {
  uvms_real_t t[3];
  uvms_m3_mul_v3(K, r, t);
  uvms_v3_add(a_prev, t, out);
}

/* v = v_prev + ω × r */
static void rigid_vel(const uvms_real_t v_prev[3], const uvms_real_t omega[3],
                      const uvms_real_t r[3], uvms_real_t out[3]) {
  uvms_real_t t[3];
  uvms_v3_cross(omega, r, t);
  uvms_v3_add(v_prev, t, out);
}

uvms_status_t uvms_arm_forward(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                               const uvms_base_state_t *base, const uvms_real_t *q_rad,
                               const uvms_real_t *qd_rad_s, const uvms_real_t *qdd_rad_s2) {
  if (data == NULL) return UVMS_ERR_ARG;
  if (base == NULL || qd_rad_s == NULL || qdd_rad_s2 == NULL) {
    memset(data, 0, sizeof *data);
    return UVMS_ERR_ARG;
  }
  const uvms_status_t st = uvms_arm_fk(model, data, base->position_m, base->R0, q_rad);
  if (st != UVMS_OK) return st;
  const size_t n = uvms_arm_joint_count(model);
  const uvms_arm_params_t *p = model->p;

  /* Base point: v_B = v0 + ω0 × R0·s0; v̇_B = v̇0 + ω̇0 × R0·s0 + ω0 × (ω0 × R0·s0) (SPEC §4). */
  uvms_v3_copy(base->omega_rad_s, data->omega_rad_s[0]);
  uvms_v3_copy(base->alpha_rad_s2, data->alpha_rad_s2[0]);
  rigid_vel(base->velocity_m_s, base->omega_rad_s, data->R0s0_m, data->v_m_s[0]);
  rigid_accel(base->accel_m_s2, base->alpha_rad_s2, base->omega_rad_s, data->R0s0_m,
              data->a_m_s2[0]);
  uvms_v3_copy(base->velocity_m_s, data->vc_m_s[0]);
  uvms_v3_copy(base->accel_m_s2, data->ac_m_s2[0]);

  uvms_real_t msum_v[3];
  uvms_v3_scale(base->velocity_m_s, p->vehicle.mass_kg, msum_v);
  for (size_t i = 1; i <= n && i <= UVMS_MAX_JOINTS; ++i) {
    const uvms_real_t *z = data->z[i];
    const uvms_real_t qd = qd_rad_s[i - 1], qdd = qdd_rad_s2[i - 1];
    uvms_real_t zqd[3], t[3];
    uvms_v3_scale(z, qd, zqd);
    /* [8] ω_i = ω_{i−1} + z_i·θ̇_i */
    uvms_v3_add(data->omega_rad_s[i - 1], zqd, data->omega_rad_s[i]);
    /* [9] ω̇_i = ω̇_{i−1} + z_i·θ̈_i + ω_{i−1} × z_i·θ̇_i */
    uvms_v3_cross(data->omega_rad_s[i - 1], zqd, t);
    uvms_v3_add(data->alpha_rad_s2[i - 1], t, data->alpha_rad_s2[i]);
    uvms_v3_axpy(qdd, z, data->alpha_rad_s2[i]);
    const uvms_real_t *w = data->omega_rad_s[i], *al = data->alpha_rad_s2[i];
    /* [12–13] distal point p_i* */
    uvms_real_t K[9];
    rigid_accel_matrix(al, w, K);
    rigid_vel(data->v_m_s[i - 1], w, data->Rl_m[i], data->v_m_s[i]);
    rigid_accel_k(data->a_m_s2[i - 1], K, data->Rl_m[i], data->a_m_s2[i]);
    /* [14–15] CoM, from the distal point along −R_i·s_i (= R_i·r_i − R_i·l_i) */
    uvms_real_t mRs[3];
    uvms_v3_sub(data->Rr_m[i], data->Rl_m[i], mRs);
    rigid_vel(data->v_m_s[i], w, mRs, data->vc_m_s[i]);
    rigid_accel_k(data->a_m_s2[i], K, mRs, data->ac_m_s2[i]);
    uvms_v3_axpy(p->link[i - 1].mass_kg, data->vc_m_s[i], msum_v);
  }
  /* Payload, rigidly at offset R_N·r_{N+1} from the EE. */
  uvms_real_t off[3];
  uvms_v3_sub(data->payload_m, data->ee_m, off);
  rigid_vel(data->v_m_s[n], data->omega_rad_s[n], off, data->payload_v_m_s);
  rigid_accel(data->a_m_s2[n], data->alpha_rad_s2[n], data->omega_rad_s[n], off,
              data->payload_a_m_s2);
  uvms_v3_axpy(p->payload_kg, data->payload_v_m_s, msum_v);
  /* d/dt of [5] */
  uvms_v3_scale(msum_v, model->inv_total_mass_1_kg, data->barycenter_v_m_s);
  return UVMS_OK;
}

void uvms_arm_shift_base_accel(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                               const uvms_real_t dv0_m_s2[3]) {
  if (model == NULL || data == NULL || dv0_m_s2 == NULL) return;
  const size_t n = uvms_arm_joint_count(model);
  /* dv0 in locals: it may alias the workspace as far as the compiler knows, which would
     reload it after every store. */
  const uvms_real_t dv[3] = {dv0_m_s2[0], dv0_m_s2[1], dv0_m_s2[2]};
  for (size_t i = 0; i <= n && i <= UVMS_MAX_JOINTS; ++i) {
    uvms_v3_add(data->a_m_s2[i], dv, data->a_m_s2[i]);
    uvms_v3_add(data->ac_m_s2[i], dv, data->ac_m_s2[i]);
  }
  uvms_v3_add(data->payload_a_m_s2, dv, data->payload_a_m_s2);
}

void uvms_drag_force(uvms_real_t density_kg_m3, uvms_real_t drag_coeff, uvms_real_t area_m2,
                     const uvms_real_t w_rel_m_s[3], const uvms_real_t *axis,
                     uvms_real_t drag_N[3]) {
  const uvms_real_t speed2 = uvms_v3_dot(w_rel_m_s, w_rel_m_s);
  const uvms_real_t speed = uvms_sqrt(speed2);
  if (!(speed > UVMS_R(0.0))) {
    uvms_v3_set(drag_N, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
    return;
  }
  uvms_real_t cd = drag_coeff;
  if (axis != NULL) {
    /* [22] cos α = (ẑ_L·w)/|w|; [21] C_D = C_D0·sin²α = C_D0·(1 − cos²α), with
       cos²α = (ẑ_L·w)²/|w|²: the division does not wait for the square root. */
    const uvms_real_t d = uvms_v3_dot(axis, w_rel_m_s);
    cd = drag_coeff * (UVMS_R(1.0) - d * d / speed2);
  }
  /* [19] D = −½·ρ·C_D·A·|w|·w */
  uvms_v3_scale(w_rel_m_s, -UVMS_R(0.5) * density_kg_m3 * cd * area_m2 * speed, drag_N);
}

/* τ = −(D_L + D_Q·|ν|)·ν on three body axes, from the vehicle's coefficients at `first`. */
static void fossen_axes(const uvms_vehicle_params_t *v, int first, const uvms_real_t nu[3],
                        uvms_real_t tau[3]) {
  for (int k = 0; k < 3; ++k)
    tau[k] = -(v->linear_damping[first + k] +
               v->quadratic_damping[first + k] * uvms_fabs(nu[k])) * nu[k];
}

void uvms_vehicle_damping(const uvms_vehicle_params_t *vehicle, const uvms_real_t R0[9],
                          const uvms_real_t w_rel_m_s[3], const uvms_real_t omega_rad_s[3],
                          uvms_real_t force_N[3], uvms_real_t moment_Nm[3]) {
  uvms_real_t nu[3], tau[3];
  uvms_m3t_mul_v3(R0, w_rel_m_s, nu); /* (u, v, w) */
  fossen_axes(vehicle, 0, nu, tau);
  uvms_m3_mul_v3(R0, tau, force_N);
  uvms_m3t_mul_v3(R0, omega_rad_s, nu); /* (p, q, r) */
  fossen_axes(vehicle, 3, nu, tau);
  uvms_m3_mul_v3(R0, tau, moment_Nm);
}

/* I_Bi·v for the full tensor [Ixx Ixy Ixz; Ixy Iyy Iyz; Ixz Iyz Izz]. */
static void full_inertia_mul(const uvms_link_params_t *L, const uvms_real_t v[3],
                             uvms_real_t out[3]) {
  const uvms_real_t *d = L->inertia_kg_m2, *o = L->inertia_products_kg_m2;
  uvms_v3_set(out, d[0] * v[0] + o[0] * v[1] + o[1] * v[2],
              o[0] * v[0] + d[1] * v[1] + o[2] * v[2],
              o[1] * v[0] + o[2] * v[1] + d[2] * v[2]);
}

/* [16] F_ci = m_i·v̇_ci;  [17] N_ci = I_i·ω̇_i + ω_i × I_i·ω_i with I_i = R_i·I_Bi·R_iᵀ [18].
   Since R·(a × b) = R·a × R·b, N_ci = R_i·N_b with the link-frame moment
   N_b = I_Bi·ω̇_b + ω_b × I_Bi·ω_b, ω_b = R_iᵀ·ω_i, ω̇_b = R_iᵀ·ω̇_i (link_body_rates): no
   inertial-frame 3×3 products. I_Bi diagonal (principal axes, `full` 0) takes 6 products,
   the full tensor 18. N_b is rotated back by the caller, after the fluid loads have added
   their link-frame moment to it. */
static void link_inertial_loads(const uvms_link_params_t *L, const uvms_arm_data_t *data,
                                size_t i, int full, const uvms_real_t wb[3],
                                const uvms_real_t alb[3], uvms_real_t Fc[3], uvms_real_t Nb[3]) {
  uvms_v3_scale(data->ac_m_s2[i], L->mass_kg, Fc);
  uvms_real_t Iw[3], t[3];
  if (full) {
    uvms_real_t Ia[3];
    full_inertia_mul(L, wb, Iw);
    full_inertia_mul(L, alb, Ia);
    uvms_v3_cross(wb, Iw, t);
    uvms_v3_add(Ia, t, Nb);
    return;
  }
  const uvms_real_t *Id = L->inertia_kg_m2;
  uvms_v3_set(Iw, Id[0] * wb[0], Id[1] * wb[1], Id[2] * wb[2]);
  uvms_v3_cross(wb, Iw, t);
  uvms_v3_set(Nb, Id[0] * alb[0] + t[0], Id[1] * alb[1] + t[1], Id[2] * alb[2] + t[2]);
}

/* SPEC §3.3: fm = k·Ma0·acc (k = ρ·V_i), row by row, each row summed over the columns in
   order from 0. */
static void added_mass_dense(const uvms_real_t Ma0[36], const uvms_real_t acc[6], uvms_real_t k,
                             uvms_real_t fm[6]) {
  for (int r = 0; r < 6; ++r) {
    uvms_real_t s = UVMS_R(0.0);
    for (int c = 0; c < 6; ++c) s += Ma0[6 * r + c] * acc[c];
    fm[r] = k * s;
  }
}

/* The 24 entries that are zero in SPEC §3.3's Ma0 (uvms_added_mass_paper), which has 12
   non-zeros: row 0 couples column 0; row 1 columns 1, 2; row 2 columns 1, 2, 4; row 3
   columns 3, 5; row 4 columns 2, 4; row 5 columns 3, 5. Returns 1 when Ma0 is zero at all 24
   (Σ|entry| = 0: no square to underflow; NaN or an overflow gives a non-zero sum). */
static int added_mass_paper_pattern(const uvms_real_t M[36]) {
  /* Written out (constant offsets, no index table): this runs on every pass. */
  const uvms_real_t sum =
      uvms_fabs(M[1]) + uvms_fabs(M[2]) + uvms_fabs(M[3]) + uvms_fabs(M[4]) + uvms_fabs(M[5]) +
      uvms_fabs(M[6]) + uvms_fabs(M[9]) + uvms_fabs(M[10]) + uvms_fabs(M[11]) +
      uvms_fabs(M[12]) + uvms_fabs(M[15]) + uvms_fabs(M[17]) + uvms_fabs(M[18]) +
      uvms_fabs(M[19]) + uvms_fabs(M[20]) + uvms_fabs(M[22]) + uvms_fabs(M[24]) +
      uvms_fabs(M[25]) + uvms_fabs(M[27]) + uvms_fabs(M[29]) + uvms_fabs(M[30]) +
      uvms_fabs(M[31]) + uvms_fabs(M[32]) + uvms_fabs(M[34]);
  return sum == UVMS_R(0.0);
}

/* added_mass_dense for a Ma0 with SPEC §3.3's zero pattern (added_mass_paper_pattern): the
   same sums without their zero terms. Bit for bit the same result for finite acc: each row
   sum starts at +0 and, in round-to-nearest, a sum that starts at +0 is never −0, so adding a
   term 0·a = ±0 to it changes nothing (with a fused multiply-add too: s + 0·a exactly). */
static void added_mass_sparse(const uvms_real_t M[36], const uvms_real_t acc[6], uvms_real_t k,
                              uvms_real_t fm[6]) {
  const uvms_real_t z = UVMS_R(0.0);
  fm[0] = k * (z + M[0] * acc[0]);
  fm[1] = k * (z + M[7] * acc[1] + M[8] * acc[2]);
  fm[2] = k * (z + M[13] * acc[1] + M[14] * acc[2] + M[16] * acc[4]);
  fm[3] = k * (z + M[21] * acc[3] + M[23] * acc[5]);
  fm[4] = k * (z + M[26] * acc[2] + M[28] * acc[4]);
  fm[5] = k * (z + M[33] * acc[3] + M[35] * acc[5]);
}

/* The added-mass product a link's fluid loads use: ρ·V_i·Ma0 in the paper's sparsity
   pattern or dense, or the link's own diagonal. */
enum { MA_DENSE = 0, MA_SPARSE = 1, MA_OWN = 2 };

/* A link's own diagonal added mass (docs/MODEL.md §3.3): fm = diag(D)·acc. */
static void added_mass_diagonal(const uvms_real_t D[6], const uvms_real_t acc[6],
                                uvms_real_t fm[6]) {
  for (int r = 0; r < 6; ++r) fm[r] = D[r] * acc[r];
}

/* The link's midpoint μ_i = η_i = l_i/2 (SPEC §3.1: a cylinder along l_i), the center of buoyancy
   and the aerodynamic center, as R_i·μ_i = R_i·l_i/2 from the forward kinematics' R_i·l_i.
   Since a point's velocity and acceleration on a rigid link are affine in its offset
   (v_{i−1} + ω_i × r, a_{i−1} + K_i·r), the midpoint's are the means of the two ends':
   v_μ = (v_{i−1}* + v_i*)/2 and a_μ = (a_{i−1}* + a_i*)/2 (mean3), with no product by ω_i,
   ω̇_i. Equal to R_i·μ_i and its rigid_vel/rigid_accel to rounding. */
static void mid_point(const uvms_arm_data_t *data, size_t i, uvms_real_t Rmid[3]) {
  uvms_v3_scale(data->Rl_m[i], UVMS_R(0.5), Rmid);
}
static void mean3(const uvms_real_t a[3], const uvms_real_t b[3], uvms_real_t out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = UVMS_R(0.5) * (a[k] + b[k]);
}

/* Link i's fluid loads (a link with volume in a fluid): added mass (SPEC §3.3) added to F_ci and
   to the link-frame moment N_b (link_inertial_loads), and the drag D_i [19–22] into
   data->drag_N[i]. Rmid = R_i·μ_i = R_i·η_i [m]; alb = R_iᵀ·ω̇_i. The moment of the added-mass
   force about the CoM, (μ_i − r_i) × F (inertial), goes to Nshift. */
static void link_fluid_loads(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                             const uvms_fluid_t *fluid, size_t i, const uvms_real_t Rmid[3],
                             const uvms_real_t alb[3], int ma_form, uvms_real_t Fc[3],
                             uvms_real_t Nb[3], uvms_real_t Nshift[3]) {
  const uvms_link_params_t *L = &model->p->link[i - 1];
  const uvms_real_t *R = data->R[i];
  const uvms_real_t rho = fluid->density_kg_m3;
  /* Added mass: ρ·V_i·Ma0 (or the link's own diagonal) on (a_b; ω̇_b) at the center of
     buoyancy μ_i, in frame i; its reaction adds like inertia to F_ci, and its moment is
     shifted from μ_i to the CoM: M_CoM = M_μ + (μ_i − r_i) × F. */
  uvms_real_t a_mu[3], acc_b[6], fm_b[6];
  mean3(data->a_m_s2[i - 1], data->a_m_s2[i], a_mu); /* μ_i = l_i/2 (mid_point) */
  uvms_m3t_mul_v3(R, a_mu, &acc_b[0]);
  uvms_v3_copy(alb, &acc_b[3]);
  const uvms_real_t k = rho * model->volume_m3[i];
  if (ma_form == MA_SPARSE)
    added_mass_sparse(model->p->added_mass_coeff, acc_b, k, fm_b);
  else if (ma_form == MA_DENSE)
    added_mass_dense(model->p->added_mass_coeff, acc_b, k, fm_b);
  else /* MA_OWN: the link's own diagonal (docs/MODEL.md §3.3) */
    added_mass_diagonal(L->added_mass_kg, acc_b, fm_b);
  uvms_real_t Fa[3], lever[3];
  uvms_m3_mul_v3(R, &fm_b[0], Fa);
  uvms_v3_add(Nb, &fm_b[3], Nb); /* M_μ in frame i, rotated with N_b */
  uvms_v3_sub(Rmid, data->Rr_m[i], lever);
  uvms_v3_cross(lever, Fa, Nshift);
  uvms_v3_add(Fc, Fa, Fc);

  /* [19–22] drag at the aerodynamic center η_i (SPEC §4 uses η_i, not the distal point). */
  uvms_real_t v_eta[3], w_rel[3], axis[3];
  mean3(data->v_m_s[i - 1], data->v_m_s[i], v_eta); /* η_i = l_i/2 (mid_point) */
  uvms_v3_sub(v_eta, fluid->flow_m_s, w_rel);
  uvms_v3_scale(data->Rl_m[i], model->inv_length_1_m[i], axis);
  uvms_drag_force(rho, L->drag_coeff, model->area_m2[i], w_rel,
                  fluid->angle_of_attack ? axis : NULL, data->drag_N[i]);
}

/* [24], [25] and [29] for link i, from link i+1's f, n and link i's loads F_ci, N_ci, D_i.
   f_i and n_i are summed in locals and stored once (the workspace rows may alias as far as
   the compiler knows, which would store and reload them after every term). */
static void link_wrench(const uvms_link_params_t *L, uvms_arm_data_t *data, size_t i,
                        const uvms_real_t g[3], uvms_real_t beta, const uvms_real_t Fc[3],
                        const uvms_real_t Nc[3]) {
  uvms_real_t Rmid[3]; /* R_i·μ_i = R_i·η_i [m] */
  mid_point(data, i, Rmid);
  const uvms_real_t *D = data->drag_N[i];
  const uvms_real_t *f1 = data->f_N[i + 1], *n1 = data->n_Nm[i + 1];
  const uvms_real_t m = L->mass_kg;
  /* [24] f_i = f_{i+1} + F_ci − m_i·g + β_i·g − D_i */
  uvms_real_t f[3], nm[3];
  for (int k = 0; k < 3; ++k) f[k] = f1[k] + Fc[k] + (beta - m) * g[k] - D[k];

  /* [25] n_i = n_{i+1} + N_ci + R_i·l_i × f_{i+1} + R_i·r_i × F_ci + R_i·r_i × (−m_i·g)
                + R_i·μ_i × (β_i·g) + R_i·η_i × (−D_i), about p_{i−1}* */
  uvms_real_t Fr[3], Fmid[3], t[3];
  for (int k = 0; k < 3; ++k) {
    Fr[k] = Fc[k] - m * g[k];
    Fmid[k] = beta * g[k] - D[k];
  }
  uvms_v3_add(n1, Nc, nm);
  uvms_v3_cross(data->Rl_m[i], f1, t);
  uvms_v3_add(nm, t, nm);
  uvms_v3_cross(data->Rr_m[i], Fr, t);
  uvms_v3_add(nm, t, nm);
  uvms_v3_cross(Rmid, Fmid, t);
  uvms_v3_add(nm, t, nm);
  uvms_v3_copy(f, data->f_N[i]);
  uvms_v3_copy(nm, data->n_Nm[i]);

  /* [29] τ_i = n_i·z_i */
  data->tau_Nm[i] = uvms_v3_dot(nm, data->z[i]);
}

/* Link i's own loads for the recursion (link_wrench): F_ci and N_ci, the inertial ones
   [16–18] and, in a fluid, the added mass (SPEC §3.3) with its moment shifted to the CoM; the
   drag D_i [19–22] into data->drag_N[i] (0 without a fluid or a cylinder). ma_shared: the
   added-mass product of the links without their own (uvms_arm_backward). */
UVMS_FW_INLINE void link_loads(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                               const uvms_fluid_t *fluid, size_t i, int ma_shared,
                               uvms_real_t Fc[3], uvms_real_t Nc[3]) {
  const uvms_link_params_t *L = &model->p->link[i - 1];
  const uvms_real_t *R = data->R[i];
  uvms_real_t Rmid[3]; /* R_i·μ_i = R_i·η_i [m] */
  mid_point(data, i, Rmid);
  uvms_real_t wb[3], alb[3], Nb[3], Nshift[3] = {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0)};
  uvms_m3t_mul_v3(R, data->omega_rad_s[i], wb);   /* ω_b = R_iᵀ·ω_i */
  uvms_m3t_mul_v3(R, data->alpha_rad_s2[i], alb); /* ω̇_b = R_iᵀ·ω̇_i */
  link_inertial_loads(L, data, i, (int)((model->full_inertia >> i) & 1u), wb, alb, Fc, Nb);
  if (model->volume_m3[i] > UVMS_R(0.0) && fluid->density_kg_m3 > UVMS_R(0.0)) {
    const unsigned own = model->own_added_mass;
    link_fluid_loads(model, data, fluid, i, Rmid, alb,
                     (own != 0u && ((own >> i) & 1u)) ? MA_OWN : ma_shared, Fc, Nb, Nshift);
  } else {
    uvms_v3_set(data->drag_N[i], UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  }
  uvms_m3_mul_v3(R, Nb, Nc); /* N_ci = R_i·N_b (+ the added-mass shift, inertial) */
  uvms_v3_add(Nc, Nshift, Nc);
}

/* The backward pass's outputs all zero (its error exits; the forward-pass fields are kept). */
static uvms_status_t backward_fail(uvms_arm_data_t *data, uvms_status_t st) {
  if (data != NULL) {
    memset(data->drag_N, 0, sizeof data->drag_N);
    memset(data->f_N, 0, sizeof data->f_N);
    memset(data->n_Nm, 0, sizeof data->n_Nm);
    memset(data->tau_Nm, 0, sizeof data->tau_Nm);
  }
  return st;
}

uvms_status_t uvms_arm_backward(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                                const uvms_fluid_t *fluid) {
  if (model == NULL || data == NULL || fluid == NULL) return backward_fail(data, UVMS_ERR_ARG);
  if (!model->ready) return backward_fail(data, UVMS_ERR_STATE);
  const size_t n = uvms_arm_joint_count(model);
  const uvms_arm_params_t *p = model->p;
  const uvms_real_t rho = fluid->density_kg_m3;
  const uvms_real_t *g = fluid->gravity_m_s2;

  /* Vehicle drag D0 (SPEC [31]): w0 = v0 − v∞, no angle-of-attack factor. */
  uvms_real_t w0[3];
  uvms_v3_sub(data->vc_m_s[0], fluid->flow_m_s, w0);
  uvms_drag_force(rho, p->vehicle.drag_coeff, p->vehicle.frontal_area_m2, w0, NULL,
                  data->drag_N[0]);

  /* Payload reaction f_{N+1} = m_{N+1}·(v̇_payload − g), acting at the payload point, so its
     moment about p_N* is (p_payload − p_N*) × f_{N+1}; a point payload has no n of its own. */
  uvms_real_t gneg[3];
  uvms_v3_sub(data->payload_a_m_s2, g, gneg);
  uvms_v3_scale(gneg, p->payload_kg, data->f_N[n + 1]);
  uvms_real_t off[3];
  uvms_v3_sub(data->payload_m, data->ee_m, off);
  uvms_v3_cross(off, data->f_N[n + 1], data->n_Nm[n + 1]);

  /* Which added-mass product the fluid loads use (once per pass, not per link). */
  const int ma_shared = ((rho > UVMS_R(0.0)) && added_mass_paper_pattern(p->added_mass_coeff))
                            ? MA_SPARSE
                            : MA_DENSE;
  /* UVMS_FW_WORK_AHEAD (fw_fast.h): on a host every link's own loads first (they depend only
     on the forward pass; each has its drag's square root and division), then the recursion
     that sums them from the tip; on the target both in one loop. The same values. */
#if UVMS_FW_WORK_AHEAD
  uvms_real_t Fc[UVMS_LINK_SLOTS][3], Nc[UVMS_LINK_SLOTS][3];
  for (size_t i = n; i >= 1 && i <= UVMS_MAX_JOINTS; --i)
    link_loads(model, data, fluid, i, ma_shared, Fc[i], Nc[i]);
  for (size_t i = n; i >= 1 && i <= UVMS_MAX_JOINTS; --i)
    link_wrench(&p->link[i - 1], data, i, g, rho * model->volume_m3[i], Fc[i], Nc[i]);
#else
  for (size_t i = n; i >= 1 && i <= UVMS_MAX_JOINTS; --i) {
    uvms_real_t Fc[3], Nc[3];
    link_loads(model, data, fluid, i, ma_shared, Fc, Nc);
    link_wrench(&p->link[i - 1], data, i, g, rho * model->volume_m3[i], Fc, Nc);
  }
#endif
  return UVMS_OK;
}

uvms_status_t uvms_arm_rnea(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                            const uvms_base_state_t *base, const uvms_fluid_t *fluid,
                            const uvms_real_t *q_rad, const uvms_real_t *qd_rad_s,
                            const uvms_real_t *qdd_rad_s2) {
  if (fluid == NULL) { /* dynamics.h: *data all zero on every UVMS_ERR_ARG */
    if (data != NULL) memset(data, 0, sizeof *data);
    return UVMS_ERR_ARG;
  }
  const uvms_status_t st = uvms_arm_forward(model, data, base, q_rad, qd_rad_s, qdd_rad_s2);
  if (st != UVMS_OK) return st;
  return uvms_arm_backward(model, data, fluid);
}
