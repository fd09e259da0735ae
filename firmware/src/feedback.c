/* SPDX-License-Identifier: Apache-2.0 */
/* feedback.c: vehicle PD feedback (SPEC §7.2, [40]–[46]), its gains and the Table X switches. */
#include "uvms/feedback.h"

#include <string.h>

#include "uvms/linalg.h"
#include "fw_fast.h"

void uvms_pd_gains_paper(uvms_pd_gains_t *gains) {
  if (gains == NULL) return;
  gains->kpf_N_m = UVMS_R(10.0);
  gains->kdf_N_s_m = UVMS_R(100.0);
  gains->kpn_Nm_rad = UVMS_R(10.0);
  gains->kdn_Nm_s_rad = UVMS_R(100.0);
}

uvms_status_t uvms_pd_gains_check(const uvms_pd_gains_t *gains) {
  if (gains == NULL) return UVMS_ERR_ARG;
  const uvms_real_t g[4] = {gains->kpf_N_m, gains->kdf_N_s_m, gains->kpn_Nm_rad,
                            gains->kdn_Nm_s_rad};
  if (!uvms_all_finite(g, 4)) return UVMS_ERR_NONFINITE;
  for (int k = 0; k < 4; ++k)
    if (g[k] < UVMS_R(0.0)) return UVMS_ERR_RANGE;
  return UVMS_OK;
}

uvms_status_t uvms_switches_case(int case_number, uvms_switches_t *sw) {
  if (sw == NULL) return UVMS_ERR_ARG;
  /* Table X: attitude, reference (1 = barycenter), position feedforward, position feedback. */
  static const signed char table[8][4] = {
      {0, 0, 0, 0}, /* I */    {1, 1, 0, 0}, /* II */  {1, 1, 1, 0}, /* III */
      {1, 0, 1, 1}, /* IV */   {1, 0, 0, 1}, /* V */   {1, 0, 1, 0}, /* VI */
      {1, 1, 1, 1}, /* VII */  {1, 1, 0, 1}, /* VIII */
  };
  memset(sw, 0, sizeof *sw);
  if (case_number < 1 || case_number > 8) return UVMS_ERR_RANGE;
  const signed char *row = table[case_number - 1];
  sw->attitude_control = row[0];
  sw->position_reference = row[1] ? UVMS_REF_BARYCENTER : UVMS_REF_VEHICLE;
  sw->position_feedforward = row[2];
  sw->position_feedback = row[3];
  return UVMS_OK;
}

uvms_status_t uvms_switches_check(const uvms_switches_t *sw) {
  if (sw == NULL) return UVMS_ERR_ARG;
  if ((sw->attitude_control != 0 && sw->attitude_control != 1) ||
      (sw->position_feedforward != 0 && sw->position_feedforward != 1) ||
      (sw->position_feedback != 0 && sw->position_feedback != 1) ||
      (sw->position_reference != UVMS_REF_VEHICLE &&
       sw->position_reference != UVMS_REF_BARYCENTER))
    return UVMS_ERR_RANGE;
  return UVMS_OK;
}

uvms_status_t uvms_attitude_feedback(const uvms_pd_gains_t *gains, const uvms_real_t q0d_wxyz[4],
                                     const uvms_real_t q0_wxyz[4],
                                     const uvms_real_t omega0_rad_s[3], uvms_real_t moment_Nm[3],
                                     uvms_real_t *phi_e_rad) {
  if (moment_Nm == NULL) return UVMS_ERR_ARG;
  uvms_v3_set(moment_Nm, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  if (phi_e_rad != NULL) uvms_v3_set(phi_e_rad, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  if (gains == NULL || q0d_wxyz == NULL || q0_wxyz == NULL || omega0_rad_s == NULL)
    return UVMS_ERR_ARG;
  /* [44] E = R0d·R0ᵀ, the rotation taking the current attitude to the desired one (inertial),
     and [42–43] its rotation vector, both from the quaternions (linalg.h): valid at φ = 0 and
     near π. */
  uvms_real_t phi_e[3];
  uvms_quat_error_rotvec(q0d_wxyz, q0_wxyz, phi_e);
  /* [40] N_fb = K_PN·φ·e − K_DN·ω0 */
  for (int k = 0; k < 3; ++k)
    moment_Nm[k] = gains->kpn_Nm_rad * phi_e[k] - gains->kdn_Nm_s_rad * omega0_rad_s[k];
  if (phi_e_rad != NULL) uvms_v3_copy(phi_e, phi_e_rad);
  return UVMS_OK;
}

uvms_status_t uvms_position_feedback(const uvms_pd_gains_t *gains, const uvms_real_t r_d_m[3],
                                     const uvms_real_t r_m[3], const uvms_real_t v_d_m_s[3],
                                     const uvms_real_t v_m_s[3], uvms_real_t force_N[3]) {
  if (force_N == NULL) return UVMS_ERR_ARG;
  uvms_v3_set(force_N, UVMS_R(0.0), UVMS_R(0.0), UVMS_R(0.0));
  if (gains == NULL || r_d_m == NULL || r_m == NULL || v_d_m_s == NULL || v_m_s == NULL)
    return UVMS_ERR_ARG;
  /* [45] F_fb = K_PF·(r_d − r) + K_DF·(v_d − v) */
  for (int k = 0; k < 3; ++k)
    force_N[k] = gains->kpf_N_m * (r_d_m[k] - r_m[k]) + gains->kdf_N_s_m * (v_d_m_s[k] - v_m_s[k]);
  return UVMS_OK;
}
