/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file dynamics.h
 * @brief Recursive Newton–Euler inverse dynamics of the arm on a moving vehicle, with drag,
 *        added mass, buoyancy, gravity and payload (SPEC §4, [8]–[29]).
 *
 * The two passes are separate functions so that callers can adjust the base acceleration
 * between them (the barycenter-reference assumption of SPEC §7):
 *   uvms_arm_forward()  kinematics, velocities and accelerations, i = 1…N  [8]–[15]
 *   uvms_arm_backward() body loads and the force/moment recursion, i = N…1 [16]–[29]
 * uvms_arm_rnea() runs both.
 */
#ifndef UVMS_DYNAMICS_H
#define UVMS_DYNAMICS_H

#include "uvms/arm_model.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * @brief Forward pass: runs uvms_arm_fk at the base pose, then velocities and accelerations of
 *        every frame origin and link CoM [8]–[15], the payload, and the barycenter velocity.
 * @param[in]  base   vehicle pose, twist and acceleration (inertial)
 * @param[in]  q_rad, qd_rad_s, qdd_rad_s2  joint positions, rates, accelerations (N each)
 * @param[out] data   kinematic and forward-pass fields (zeros on error)
 * @pre The inputs are not checked for NaN/inf (they propagate with UVMS_OK).
 * @retval UVMS_OK        data holds the kinematic and forward-pass fields
 * @retval UVMS_ERR_ARG   a pointer is NULL; writes: *data all zero (nothing if data is NULL)
 * @retval UVMS_ERR_STATE model not ready; writes: *data all zero
 */
uvms_status_t uvms_arm_forward(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                               const uvms_base_state_t *base, const uvms_real_t *q_rad,
                               const uvms_real_t *qd_rad_s, const uvms_real_t *qdd_rad_s2);

/**
 * @brief Add a uniform linear acceleration to the vehicle and every point of the arm (valid
 *        because the change leaves angular quantities untouched): a ← a + dv0 for the base
 *        point, every frame origin, every CoM and the payload.
 * @param[in] dv0_m_s2 added vehicle linear acceleration, inertial [m/s²]
 * No status: if model, data or dv0_m_s2 is NULL nothing is changed. The model's readiness is
 * not checked (its joint count, clamped to UVMS_MAX_JOINTS, bounds the loop).
 */
void uvms_arm_shift_base_accel(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                               const uvms_real_t dv0_m_s2[3]);

/**
 * @brief Backward pass: inertial reactions [16–17] plus added mass (SPEC §3.3), link drag
 *        [19–22], buoyancy [23], gravity and the payload, then f_i [24], n_i [25], τ_i [29].
 *        Also the vehicle's own drag D0 in data->drag_N[0] (used by SPEC [31–32]).
 * @param[in]  fluid  density, flow, gravity, angle-of-attack switch (the model's view)
 * @param[in,out] data after uvms_arm_forward; fills drag_N, f_N,
 *                n_Nm, tau_Nm. f_N[1], n_Nm[1] are the force and moment (about the base point
 *                p_0*) the vehicle exerts on link 1.
 * @pre data holds a uvms_arm_forward result of the same model (not checkable).
 * @retval UVMS_OK        drag_N, f_N, n_Nm, tau_Nm filled
 * @retval UVMS_ERR_ARG   model, data or fluid is NULL; writes: drag_N, f_N, n_Nm, tau_Nm all
 *                        zero when data is non-NULL (the forward-pass fields are kept)
 * @retval UVMS_ERR_STATE model not ready; writes: drag_N, f_N, n_Nm, tau_Nm all zero
 */
uvms_status_t uvms_arm_backward(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                                const uvms_fluid_t *fluid);

/**
 * @brief uvms_arm_forward then uvms_arm_backward.
 * @retval UVMS_OK        data holds the full Newton–Euler result
 * @retval UVMS_ERR_ARG   a pointer is NULL; writes: *data all zero (nothing if data is NULL)
 * @retval UVMS_ERR_STATE model not ready; writes: *data all zero
 */
uvms_status_t uvms_arm_rnea(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                            const uvms_base_state_t *base, const uvms_fluid_t *fluid,
                            const uvms_real_t *q_rad, const uvms_real_t *qd_rad_s,
                            const uvms_real_t *qdd_rad_s2);

/**
 * @brief Quadratic drag −½ρ·C_D·A·|w|·w of a body whose point moves at w relative to the fluid
 *        [19]; with an axis (unit) and angle_of_attack set, C_D = C_D0·sin²α [21–22].
 * @param[in]  axis unit body axis for the angle of attack, or NULL for C_D = C_D0
 * @param[out] drag_N the drag force, inertial [N]; zero when |w| = 0
 * @pre w_rel_m_s and drag_N non-NULL (not checked); axis unit length when given. No status:
 *      |w| NaN gives zero drag (the speed test fails); other NaN/inf inputs propagate.
 */
void uvms_drag_force(uvms_real_t density_kg_m3, uvms_real_t drag_coeff, uvms_real_t area_m2,
                     const uvms_real_t w_rel_m_s[3], const uvms_real_t *axis,
                     uvms_real_t drag_N[3]);

/**
 * @brief Fossen's diagonal damping of the vehicle body (docs/MODEL.md §3.2): in the vehicle
 *        frame, on ν = (R0ᵀ·w0, R0ᵀ·ω0), the load τ_k = −(D_L,k + D_Q,k·|ν_k|)·ν_k, k = 0..5,
 *        returned inertial: a force at the CoM and a moment about it.
 * @param[in]  vehicle   its linear_damping and quadratic_damping are read
 * @param[in]  R0        vehicle → inertial rotation, row-major
 * @param[in]  w_rel_m_s w0 = v0 − v∞, the CoM's velocity relative to the fluid, inertial [m/s]
 * @param[in]  omega_rad_s ω0, inertial [rad/s] (the flow does not rotate)
 * @param[out] force_N   the damping force, inertial [N]
 * @param[out] moment_Nm the damping moment about the CoM, inertial [N·m]
 * @pre every pointer non-NULL (not checked). No status: NaN inputs propagate.
 */
void uvms_vehicle_damping(const uvms_vehicle_params_t *vehicle, const uvms_real_t R0[9],
                          const uvms_real_t w_rel_m_s[3], const uvms_real_t omega_rad_s[3],
                          uvms_real_t force_N[3], uvms_real_t moment_Nm[3]);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_DYNAMICS_H */
