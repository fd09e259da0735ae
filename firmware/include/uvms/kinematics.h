/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file kinematics.h
 * @brief Forward kinematics of the arm on the vehicle (SPEC §2 [1]–[5], [10–11]), the EE
 *        Jacobian, the barycenter and the virtual-manipulator EE estimate [4].
 */
#ifndef UVMS_KINEMATICS_H
#define UVMS_KINEMATICS_H

#include "uvms/arm_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Positions and orientations of every frame, link CoM, EE, payload and barycenter.
 * @param[in]  model     a ready model
 * @param[out] data      fills R, p_m, z, Rl_m, Rr_m, com_m, R0s0_m, ee_m, payload_m,
 *                       barycenter_m (zeros on error)
 * @param[in]  r0_m      vehicle CoM position, inertial [m] (3)
 * @param[in]  R0        vehicle → inertial rotation, row-major (9)
 * @param[in]  q_rad     joint angles θ_1..θ_N [rad] (N)
 * @pre The inputs are not checked for NaN/inf (they propagate into data with UVMS_OK).
 * @retval UVMS_OK        data holds the kinematics
 * @retval UVMS_ERR_ARG   a pointer is NULL; writes: *data all zero (nothing if data is NULL)
 * @retval UVMS_ERR_STATE model not ready; writes: *data all zero
 */
uvms_status_t uvms_arm_fk(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                          const uvms_real_t r0_m[3], const uvms_real_t R0[9],
                          const uvms_real_t *q_rad);

/**
 * @brief Geometric Jacobian of the EE with the vehicle held fixed, from the last uvms_arm_fk:
 *        column i = (z_i × (p_EE − p_{i−1}*); z_i), inertial coordinates.
 * @param[out] J  row-major 6×N: rows 0–2 linear [m/rad], rows 3–5 angular [rad/rad]
 * @pre J has room for 6·UVMS_MAX_JOINTS reals: on error the whole 6·UVMS_MAX_JOINTS is zeroed
 *      (N is not known then); on success only the 6·N entries are written.
 * @retval UVMS_OK        J filled
 * @retval UVMS_ERR_ARG   J, model or data is NULL; writes: J[0..6·UVMS_MAX_JOINTS) = 0 when J
 *                        is non-NULL
 * @retval UVMS_ERR_STATE model not ready; writes: J[0..6·UVMS_MAX_JOINTS) = 0
 */
uvms_status_t uvms_arm_jacobian(const uvms_arm_model_t *model, const uvms_arm_data_t *data,
                                uvms_real_t *J);

/**
 * @brief Jacobian of the barycenter [5] with respect to the joint angles (vehicle held fixed),
 *        from the last uvms_arm_fk: Σ_i m_i ∂c_i/∂θ + m_payload ∂p_payload/∂θ, over m_T.
 * @param[out] Jcm row-major 3×N [m/rad]
 * @pre Jcm has room for 3·UVMS_MAX_JOINTS reals (zeroed in full on entry).
 * @retval UVMS_OK        Jcm filled (entries past 3·N zero)
 * @retval UVMS_ERR_ARG   Jcm, model or data is NULL; writes: Jcm[0..3·UVMS_MAX_JOINTS) = 0
 *                        when Jcm is non-NULL
 * @retval UVMS_ERR_STATE model not ready; writes: Jcm[0..3·UVMS_MAX_JOINTS) = 0
 */
uvms_status_t uvms_arm_barycenter_jacobian(const uvms_arm_model_t *model,
                                           const uvms_arm_data_t *data, uvms_real_t *Jcm);

/**
 * @brief Virtual-manipulator offset [4]: p_EE − p_cm evaluated at attitude R0 and joint angles
 *        q; it does not depend on the vehicle position. Overwrites the kinematic fields of data.
 * @param[out] ee_rel_m p_EE − p_cm, inertial [m] (zeros on error)
 * @retval UVMS_OK        ee_rel_m = p_EE − p_cm
 * @retval UVMS_ERR_ARG   a pointer is NULL; writes: ee_rel_m = 0 (if non-NULL) and, as
 *                        uvms_arm_fk, *data all zero (if ee_rel_m and data are non-NULL)
 * @retval UVMS_ERR_STATE model not ready; writes: ee_rel_m = 0, *data all zero
 */
uvms_status_t uvms_arm_ee_minus_barycenter(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                                           const uvms_real_t R0[9], const uvms_real_t *q_rad,
                                           uvms_real_t ee_rel_m[3]);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_KINEMATICS_H */
