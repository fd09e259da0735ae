/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file feedback.h
 * @brief PD feedback of the vehicle (SPEC §7.2, [40]–[46]): attitude on a robust rotation
 *        vector, position of the vehicle CoM or of the barycenter; the gains and the Table X
 *        switches that select the terms of the desired wrench, and their checks.
 */
#ifndef UVMS_FEEDBACK_H
#define UVMS_FEEDBACK_H

#include "uvms/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/** PD gains (SPEC §3.5: KPF = 10 N/m, KDF = 100 N·s/m, KPN = 10 N·m/rad, KDN = 100 N·m·s/rad). */
typedef struct {
  uvms_real_t kpf_N_m;      /**< position stiffness K_PF [N/m] */
  uvms_real_t kdf_N_s_m;    /**< position damping K_DF [N·s/m] */
  uvms_real_t kpn_Nm_rad;   /**< attitude stiffness K_PN [N·m/rad] */
  uvms_real_t kdn_Nm_s_rad; /**< attitude damping K_DN [N·m·s/rad] */
} uvms_pd_gains_t;

/** @brief SPEC §3.5's gains. No status: gains NULL → nothing is written. */
void uvms_pd_gains_paper(uvms_pd_gains_t *gains);

/**
 * @brief Check a gain set: every gain finite and ≥ 0 (0 turns a term off).
 * @param[in] gains the gains
 * Writes nothing (a pure check).
 * @retval UVMS_OK            every gain finite and ≥ 0
 * @retval UVMS_ERR_ARG       gains is NULL
 * @retval UVMS_ERR_NONFINITE a gain is NaN or infinite
 * @retval UVMS_ERR_RANGE     a gain is negative
 */
uvms_status_t uvms_pd_gains_check(const uvms_pd_gains_t *gains);

/** Table X of the paper (SPEC §7.2, §9): which terms make up the desired wrench. */
typedef struct {
  int attitude_control;                /**< 1: attitude PD + attitude feedforward */
  uvms_reference_t position_reference; /**< vehicle CoM or barycenter */
  int position_feedforward;            /**< 1: F_r,0 [31] or F_r,cm [32] */
  int position_feedback;               /**< 1: position PD [45] */
} uvms_switches_t;

/**
 * @brief Table X switches of case 1..8 (I..VIII).
 * @retval UVMS_OK        *sw = the case's switches
 * @retval UVMS_ERR_ARG   sw is NULL; writes: nothing
 * @retval UVMS_ERR_RANGE case outside 1..8; writes: *sw all zero (every switch off, vehicle
 *                        reference: case I)
 */
uvms_status_t uvms_switches_case(int case_number, uvms_switches_t *sw);

/**
 * @brief Check a switch set: each switch 0 or 1, the reference one of uvms_reference_t.
 * @param[in] sw the switches
 * Writes nothing (a pure check).
 * @retval UVMS_OK        every switch valid
 * @retval UVMS_ERR_ARG   sw is NULL
 * @retval UVMS_ERR_RANGE a switch other than 0/1, or an unknown reference
 */
uvms_status_t uvms_switches_check(const uvms_switches_t *sw);

/**
 * @brief Attitude PD [40], [44]: E = R0d·R0ᵀ, φ·e = rotation vector of E (valid at φ = 0 and
 *        near π), N_fb = K_PN·φ·e − K_DN·ω0. E and φ·e come from the attitudes' quaternions
 *        (uvms_quat_error_rotvec), with no rotation matrix.
 * @param[in]  q0d_wxyz, q0_wxyz desired and measured vehicle → inertial attitude as
 *                        quaternions (w, x, y, z), of either sign and any norm in the range
 *                        uvms_quat_error_rotvec states (R0 = R(q0), R0d = R(q0d):
 *                        uvms_quat_to_rot)
 * @param[in]  omega0_rad_s measured angular velocity, inertial [rad/s]
 * @param[out] moment_Nm N_fb, inertial [N·m]; zeros on error
 * @param[out] phi_e_rad the attitude error rotation vector [rad] (may be NULL)
 *
 * The outputs must not alias the inputs (nor each other): they are zeroed (the safe output)
 * before the inputs are read.
 * @pre q0d_wxyz, q0_wxyz within that range of norms; inputs are not checked for NaN/inf
 *      (they propagate with UVMS_OK).
 * @retval UVMS_OK      moment_Nm = N_fb, phi_e_rad = φ·e
 * @retval UVMS_ERR_ARG gains, q0d_wxyz, q0_wxyz, omega0_rad_s or moment_Nm is NULL; writes:
 *                      moment_Nm = 0 and phi_e_rad = 0 (those that are non-NULL)
 */
uvms_status_t uvms_attitude_feedback(const uvms_pd_gains_t *gains, const uvms_real_t q0d_wxyz[4],
                                     const uvms_real_t q0_wxyz[4],
                                     const uvms_real_t omega0_rad_s[3], uvms_real_t moment_Nm[3],
                                     uvms_real_t *phi_e_rad);

/**
 * @brief Position PD [45]: F_fb = K_PF·(r_d − r) + K_DF·(v_d − v), for the vehicle CoM or the
 *        barycenter (the caller passes the point it regulates).
 * @param[in]  r_d_m, r_m   desired and measured position, inertial [m]
 * @param[in]  v_d_m_s, v_m_s desired and measured velocity, inertial [m/s]
 * @param[out] force_N F_fb, inertial [N]; zeros on error. Must not alias an input: it is
 *                     zeroed (the safe output) before the inputs are read.
 * @pre Inputs are not checked for NaN/inf (they propagate with UVMS_OK).
 * @retval UVMS_OK      force_N = F_fb
 * @retval UVMS_ERR_ARG a pointer is NULL; writes: force_N = 0 (if non-NULL)
 */
uvms_status_t uvms_position_feedback(const uvms_pd_gains_t *gains, const uvms_real_t r_d_m[3],
                                     const uvms_real_t r_m[3], const uvms_real_t v_d_m_s[3],
                                     const uvms_real_t v_m_s[3], uvms_real_t force_N[3]);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_FEEDBACK_H */
