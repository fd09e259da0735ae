/* SPDX-License-Identifier: Apache-2.0 */
/* feedforward.c: feedforward wrenches (SPEC §7, §7.1, [30]–[32]). */
#include "uvms/feedforward.h"

#include <string.h>

#include "uvms/dynamics.h"
#include "uvms/linalg.h"
#include "fw_fast.h"

/* The moment about the vehicle CoM that cancels the vehicle's own hydrostatic loads (SPEC
   §7.1, §6.3): buoyancy −β0·g at the center of buoyancy c_b and the ballast weight m_b·g at its
   point b_b, so moment = (R0·c_b) × (β0·g) − (R0·b_b) × (m_b·g). Drag D0 acts at the CoM (SPEC
   §3.2 geometry) and has no moment. */
static void vehicle_hydrostatic_moment(const uvms_vehicle_params_t *v, const uvms_real_t R0[9],
                                       const uvms_real_t g[3], uvms_real_t beta0_kg,
                                       uvms_real_t moment_Nm[3]) {
  uvms_real_t r[3], f[3], t[3];
  uvms_m3_mul_v3(R0, v->cob_m, r);
  uvms_v3_scale(g, beta0_kg, f);
  uvms_v3_cross(r, f, moment_Nm);
  uvms_m3_mul_v3(R0, v->ballast_offset_m, r);
  uvms_v3_scale(g, v->ballast_kg, f);
  uvms_v3_cross(r, f, t);
  uvms_v3_sub(moment_Nm, t, moment_Nm);
}

uvms_status_t uvms_feedforward(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                               const uvms_fluid_t *fluid, uvms_reference_t reference,
                               const uvms_base_state_t *state, const uvms_real_t *q_rad,
                               const uvms_real_t *qd_rad_s, const uvms_real_t *qdd_rad_s2,
                               uvms_feedforward_t *ff) {
  if (ff == NULL) return UVMS_ERR_ARG;
  uvms_clear_record(ff, sizeof *ff);
  if (model == NULL || data == NULL || fluid == NULL || state == NULL) return UVMS_ERR_ARG;
  if (reference != UVMS_REF_VEHICLE && reference != UVMS_REF_BARYCENTER) return UVMS_ERR_ARG;

  /* SPEC §7: ω̇0 = 0; v̇0 = 0 for now (the barycenter case adds its value below). */
  uvms_base_state_t base;
  uvms_copy_record(&base, state, sizeof base); /* = *state (no byte-wise memcpy on the target) */
  uvms_v3_set(base.accel_m_s2, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  uvms_v3_set(base.alpha_rad_s2, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  uvms_status_t st = uvms_arm_forward(model, data, &base, q_rad, qd_rad_s, qdd_rad_s2);
  if (st != UVMS_OK) return st;

  const uvms_arm_params_t *p = model->p;
  const size_t n = uvms_arm_joint_count(model);
  if (reference == UVMS_REF_BARYCENTER) {
    /* Rigid-mass momentum conserved: m_T·v̇0 + Σ_k m_k·a_k|_{v̇0=0} = 0 (vehicle term is 0). */
    uvms_real_t msum[3];
    uvms_v3_scale(data->payload_a_m_s2, p->payload_kg, msum);
    for (size_t i = 1; i <= n && i <= UVMS_MAX_JOINTS; ++i)
      uvms_v3_axpy(p->link[i - 1].mass_kg, data->ac_m_s2[i], msum);
    uvms_v3_scale(msum, -model->inv_total_mass_1_kg, ff->base_accel_m_s2);
    uvms_arm_shift_base_accel(model, data, ff->base_accel_m_s2);
  }
  st = uvms_arm_backward(model, data, fluid);
  if (st != UVMS_OK) {
    uvms_clear_record(ff, sizeof *ff);
    return st;
  }

  const uvms_real_t *g = fluid->gravity_m_s2;
  const uvms_real_t *f1 = data->f_N[1], *n1 = data->n_Nm[1];
  /* D0: the vehicle's drag [31], plus Fossen's damping force when it has any (docs/MODEL.md
     §3.2); the damping moment joins the attitude feedforward below. */
  uvms_real_t D0[3], damping_moment_Nm[3] = {UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0)};
  uvms_v3_copy(data->drag_N[0], D0);
  if (model->vehicle_damping) {
    uvms_real_t w0[3], Fd[3];
    uvms_v3_sub(data->vc_m_s[0], fluid->flow_m_s, w0);
    uvms_vehicle_damping(&model->p->vehicle, base.R0, w0, base.omega_rad_s, Fd,
                         damping_moment_Nm);
    uvms_v3_add(D0, Fd, D0);
  }
  uvms_v3_copy(f1, ff->base_force_N);
  uvms_v3_copy(n1, ff->base_moment_Nm);
  const uvms_real_t beta0 = fluid->density_kg_m3 * p->vehicle.volume_m3; /* [23] */
  const uvms_real_t m0w = p->vehicle.mass_kg + p->vehicle.ballast_kg;     /* weight mass */

  /* Attitude: N_r = n1 + (R0·s0) × f1 (the physical content of the garbled [30]), plus the
     moment cancelling the vehicle's own hydrostatic loads about its CoM (SPEC §7.1). */
  uvms_real_t t[3];
  uvms_v3_cross(data->R0s0_m, f1, t);
  uvms_v3_add(n1, t, ff->moment_att_Nm);
  vehicle_hydrostatic_moment(&p->vehicle, base.R0, g, beta0, t);
  uvms_v3_add(ff->moment_att_Nm, t, ff->moment_att_Nm);
  if (model->vehicle_damping) uvms_v3_sub(ff->moment_att_Nm, damping_moment_Nm, ff->moment_att_Nm);

  /* [31] F_r,0 = f1 − D0 − m0·g + β0·g (m0 including trim ballast, SPEC §6.3). */
  for (int k = 0; k < 3; ++k) ff->force_vehicle_N[k] = f1[k] - D0[k] + (beta0 - m0w) * g[k];

  /* [32] F_r,cm = Σ_{k=0..N+1} (−D_k − m_k·g + β_k·g): external forces only. */
  uvms_real_t mass = m0w + p->payload_kg, buoy = beta0;
  uvms_real_t drag[3];
  uvms_v3_copy(D0, drag);
  for (size_t i = 1; i <= n && i <= UVMS_MAX_JOINTS; ++i) {
    mass += p->link[i - 1].mass_kg;
    buoy += fluid->density_kg_m3 * model->volume_m3[i];
    uvms_v3_add(drag, data->drag_N[i], drag);
  }
  for (int k = 0; k < 3; ++k) ff->force_barycenter_N[k] = -drag[k] + (buoy - mass) * g[k];
  return UVMS_OK;
}

uvms_status_t uvms_ff_lead_check(int lead, uvms_drive_t drive) {
  if (lead == 0) return UVMS_OK;
  return (lead == 1 && drive == UVMS_DRIVE_CURRENT) ? UVMS_OK : UVMS_ERR_RANGE;
}

uvms_status_t uvms_ff_lead(size_t n, const uvms_real_t *w, const uvms_real_t *w_prev,
                           uvms_real_t dt_s, uvms_real_t lead_s, uvms_real_t *slope,
                           int have_slope, uvms_real_t *out) {
  if (w == NULL || w_prev == NULL || slope == NULL || out == NULL) return UVMS_ERR_ARG;
  const int ok = uvms_isfinite(lead_s) && lead_s >= UVMS_R(0.0) && uvms_isfinite(dt_s) &&
                 dt_s > UVMS_R(0.0);
  const uvms_real_t alpha = ok ? dt_s / (lead_s + dt_s) : UVMS_R(0.0);
  for (size_t i = 0; i < n; ++i) {
    if (ok) {
      const uvms_real_t raw = (w[i] - w_prev[i]) / dt_s;
      slope[i] = have_slope ? slope[i] + alpha * (raw - slope[i]) : raw; /* no old value read */
    }
    out[i] = ok ? w[i] + lead_s * slope[i] : w[i];
  }
  return ok ? UVMS_OK : UVMS_ERR_RANGE;
}
