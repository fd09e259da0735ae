/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file feedforward.h
 * @brief Model-based feedforward wrenches (SPEC §7, §7.1, Table I of the paper): the attitude
 *        moment N_r, the vehicle-reference force F_r,0 [31] and the barycenter-reference force
 *        F_r,cm [32], from the arm's Newton–Euler model with the controller's fluid model.
 */
#ifndef UVMS_FEEDFORWARD_H
#define UVMS_FEEDFORWARD_H

#include "uvms/arm_model.h"
#include "uvms/thruster.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Feedforward wrenches, all inertial coordinates, moments about the vehicle CoM. */
typedef struct {
  uvms_real_t moment_att_Nm[3];      /**< N_r = n1 + (R0·s0) × f1 + (R0·c_b) × (β0·g)
                                          − (R0·b_b) × (m_b·g) (SPEC §7.1) − M_damping
                                          (docs/MODEL.md §3.2) */
  uvms_real_t force_vehicle_N[3];    /**< F_r,0 = f1 − D0 − (m0 + ballast)·g + β0·g [31];
                                          D0 includes Fossen's damping force */
  uvms_real_t force_barycenter_N[3]; /**< F_r,cm = Σ_k (−D_k − m_k·g + β_k·g) [32] */
  uvms_real_t base_accel_m_s2[3];    /**< vehicle linear acceleration the model assumed (§7) */
  uvms_real_t base_force_N[3];       /**< f1: force of the vehicle on link 1 [24] */
  uvms_real_t base_moment_Nm[3];     /**< n1: moment of the vehicle on link 1 about p_0* [25] */
} uvms_feedforward_t;

/**
 * @brief Run the arm model under SPEC §7's vehicle-acceleration assumption and form the three
 *        feedforward wrenches.
 *
 * The vehicle's angular acceleration is taken as zero (attitude is held). Its linear
 * acceleration is zero under UVMS_REF_VEHICLE; under UVMS_REF_BARYCENTER it is the value that
 * leaves the barycenter unaccelerated by the arm (momentum of the rigid masses conserved):
 * v̇0 = −Σ_k m_k·a_k|_{v̇0=0} / m_T.
 *
 * @param[in]  model     ready model (the controller's parameters)
 * @param[out] data      workspace; holds the full Newton–Euler results afterwards
 * @param[in]  fluid     the controller's fluid model (model density, steady flow, gravity)
 * @param[in]  reference vehicle or barycenter (selects the acceleration assumption)
 * @param[in]  state     sensed vehicle pose and twist; its accelerations are ignored
 * @param[in]  q_rad, qd_rad_s, qdd_rad_s2  sensed joint angles and rates, commanded joint
 *                       accelerations (N each)
 * @param[out] ff        the wrenches; zeros on error
 * @pre Inputs are not checked for NaN/inf (they propagate with UVMS_OK).
 * @retval UVMS_OK        ff holds the wrenches, data the Newton–Euler results
 * @retval UVMS_ERR_ARG   a pointer is NULL, or reference is not a uvms_reference_t; writes:
 *                        *ff all zero (if non-NULL); *data all zero when the pointer missing
 *                        is q_rad, qd_rad_s or qdd_rad_s2 (data otherwise unchanged)
 * @retval UVMS_ERR_STATE model not ready; writes: *ff all zero, *data all zero
 */
uvms_status_t uvms_feedforward(const uvms_arm_model_t *model, uvms_arm_data_t *data,
                               const uvms_fluid_t *fluid, uvms_reference_t reference,
                               const uvms_base_state_t *state, const uvms_real_t *q_rad,
                               const uvms_real_t *qd_rad_s, const uvms_real_t *qdd_rad_s2,
                               uvms_feedforward_t *ff);

/** Largest distance, in ticks, between the records of two feedforwards the lead differentiates
 *  (1: consecutive records; up to 3 lost or held between them): beyond it the tick runs
 *  without lead and the next one leads again. */
#define UVMS_FF_LEAD_MAX_GAP_TICKS 4

/**
 * @brief Check the feedforward-lead setting (uvms_ctrl_config_t.feedforward_lead).
 * @retval UVMS_OK        lead is 0 (off), or 1 with the current drive
 * @retval UVMS_ERR_RANGE lead is not 0 or 1, or it is 1 with a drive other than the current
 *                        drive (the lag it leads, uvms_thruster_ramp_lag_s, is the current
 *                        drive's; the voltage drive is about 20× slower, docs/MODEL.md §5)
 */
uvms_status_t uvms_ff_lead_check(int lead, uvms_drive_t drive);

/**
 * @brief Lead a feedforward by lead_s (docs/MODEL.md §7.5): out = w + lead_s·s, s the slope of
 *        w low-passed over lead_s, for n components: w extrapolated lead_s ahead, which a chain
 *        that lags a ramp by lead_s then delivers on time.
 *
 * The slope of this step, (w − w_prev)/dt_s, updates the filtered slope s (in/out):
 * s += α·((w − w_prev)/dt_s − s) with α = dt_s/(lead_s + dt_s), or s = (w − w_prev)/dt_s when
 * have_slope is 0. A ramp's slope passes unchanged once the filter has settled; sensor noise in
 * w, which the raw difference would multiply by lead_s/dt_s, is averaged over about lead_s.
 * @param[in]     n          number of components
 * @param[in]     w          this step's feedforward
 * @param[in]     w_prev     the feedforward of the step dt_s earlier
 * @param[in]     dt_s       time between the two [s], > 0
 * @param[in]     lead_s     lead and filter time constant [s], ≥ 0
 * @param[in,out] slope      the filtered slope (n components) [unit of w / s]
 * @param[in]     have_slope 0: slope holds nothing yet (it is set to this step's slope)
 * @param[out]    out        the led feedforward (may alias w)
 * @pre w and w_prev are finite (not checked: NaN/inf propagate with UVMS_OK).
 * @retval UVMS_OK        slope updated, out = the led feedforward
 * @retval UVMS_ERR_ARG   a pointer is NULL; writes nothing
 * @retval UVMS_ERR_RANGE lead_s not finite and ≥ 0, or dt_s not finite and > 0 (checked
 *                        before dividing); writes: out = w (no lead), slope unchanged
 */
uvms_status_t uvms_ff_lead(size_t n, const uvms_real_t *w, const uvms_real_t *w_prev,
                           uvms_real_t dt_s, uvms_real_t lead_s, uvms_real_t *slope,
                           int have_slope, uvms_real_t *out);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_FEEDFORWARD_H */
