/* SPDX-License-Identifier: Apache-2.0 */
/**
 * @file thruster.h
 * @brief Thruster hydrodynamics (SPEC §5 [47–52]) and the thrust → speed → current → voltage
 *        controller of one thruster (SPEC §7.4 [53], [56–66]).
 *
 * Sign conventions (SPEC §5, §7.4), used identically by the plant:
 * - thrust T [N] is positive along the thruster's direction u_j;
 * - the advance speed v_a [m/s] is the thruster's speed through the fluid along u_j;
 * - the shaft speed ω [rad/s] and the hydrodynamic torque Q [N·m] have the signs given by
 *   the laws below; with CT2 < 0, **positive thrust needs negative shaft speed**;
 * - the motor obeys Lm·İ = V − Rm·I − km·ω and J·ω̇ = km·I − b·ω − Q [53–55], so Q enters as
 *   a load torque subtracted from the motor torque, whatever its sign.
 *
 * The thrust and torque laws are written in their non-singular form (SPEC §5; the advance
 * ratio ζ = 2π·v_a/(ω·D) of the paper is singular at ω = 0):
 *   T = ρ·D⁴/(4π²)·(CT2·ω·|ω| + CT1·(2π·v_a/D)·|ω|)
 *   Q = ρ·D⁵/(4π²)·(CQ2·ω·|ω| + CQ1·(2π·v_a/D)·|ω|)
 * which equal ρ·D⁴/(4π²)·ω·|ω|·(CT2 + CT1·ζ) (resp. D⁵, CQ) for ω ≠ 0.
 */
#ifndef UVMS_THRUSTER_H
#define UVMS_THRUSTER_H

#include "uvms/types.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * The motor power stage (SPEC §5 "Motors"; docs/MODEL.md §5): what the controller's command
 * sets in the motor. Both drives run the same loops [57–66] and [53]; they differ in what the
 * power stage does with the result over a tick.
 */
typedef enum {
  /** The paper's reading and the default: the current follows the controller's integrated
   *  current command, I(t) = I*_k + İ*_k·(t − t_k), over the tick (the supply's response is
   *  negligible, as in the paper; a real ESC closes this loop at kHz rates). The terminal
   *  voltage [53] follows from the current. A speed step settles with KA, KB (≈ 0.3 s). */
  UVMS_DRIVE_CURRENT = 0,
  /** The voltage V of [53] is held over the tick and the motor's own electrical dynamics
   *  Lm·İ = V − Rm·I − km·ω act: with the paper's motor and a 0.03 s tick the speed loop is
   *  about 20× slower (≈ 6 s to 63 %). */
  UVMS_DRIVE_VOLTAGE = 1
} uvms_drive_t;

/** @brief Name of a drive ("current", "voltage"), or "invalid"; never NULL. */
const char *uvms_drive_str(uvms_drive_t drive);

/**
 * @brief Check a drive: one of uvms_drive_t.
 * @param[in] drive the drive
 * Writes nothing (a pure check).
 * @retval UVMS_OK        drive is UVMS_DRIVE_CURRENT or UVMS_DRIVE_VOLTAGE
 * @retval UVMS_ERR_RANGE any other value
 */
uvms_status_t uvms_drive_check(uvms_drive_t drive);

/** Largest number of thrusters the allocation and the motor loops handle (the paper's vehicle
 *  has 8, SPEC §3.4). */
#define UVMS_MAX_THRUSTERS 8

/** One thruster: propeller, DC motor and the two loop gains of the controller. */
typedef struct {
  uvms_real_t diameter_m;            /**< propeller diameter D [m], > 0 */
  uvms_real_t ct1;                   /**< thrust coefficient CT1 (advance term) [1] */
  uvms_real_t ct2;                   /**< thrust coefficient CT2 (static term) [1], < 0 */
  uvms_real_t cq1;                   /**< torque coefficient CQ1 (advance term) [1] */
  uvms_real_t cq2;                   /**< torque coefficient CQ2 (static term) [1] */
  uvms_real_t resistance_ohm;        /**< armature resistance Rm [Ω], > 0 */
  uvms_real_t inductance_H;          /**< armature inductance Lm [H], > 0 */
  uvms_real_t torque_constant_Nm_A;  /**< km [N·m/A] (= back-EMF constant [V·s/rad]), > 0 */
  uvms_real_t viscous_friction_Nm_s; /**< b [N·m·s/rad], ≥ 0 */
  uvms_real_t rotor_inertia_kg_m2;   /**< J [kg·m²], > 0 */
  uvms_real_t speed_gain_1_s;        /**< KA [1/s], speed loop [64], > 0 */
  uvms_real_t current_gain_1_s;      /**< KB [1/s], current loop [66], > 0 */
  uvms_real_t voltage_limit_V;       /**< |V| clamp [V], > 0 */
} uvms_thruster_params_t;

/**
 * @brief The paper's thruster (SPEC §3.4): D = 0.05 m, CT1 = 0.5, CT2 = −0.5, CQ1 = 0.15,
 *        CQ2 = −0.15, Rm = 1 Ω, Lm = 1 H, km = 10 N·m/A, b = 0.01 N·m·s, J = 0.01 kg·m²,
 *        KA = KB = 5 s⁻¹.
 *
 * The paper gives no supply voltage and does not limit it, so the limit is set to be
 * effectively unlimited: voltage_limit_V = 1e5 V. It cannot be smaller: with km = 10 V·s/rad
 * the back-EMF alone is km·|ω|, and a thrust of 5 N at v_a = 0, ρ = 1025 kg/m³ needs
 * |ω| = √(5 N/|c1|) ≈ 248 rad/s, i.e. V ≈ 2.5 kV (a "1000 V" limit would clamp the speed
 * near 100 rad/s, a thrust near 0.8 N). 1e5 V allows |ω| up to ≈ 1e4 rad/s (≈ 8 kN), far
 * beyond any thrust the allocation requests, so the clamp never acts in the paper's runs.
 * Set the real supply limit for hardware.
 * @param[out] p parameters; nothing is written if NULL
 */
void uvms_thruster_params_paper(uvms_thruster_params_t *p);

/**
 * @brief Check a parameter set.
 *
 * CT2 < 0 is required: the desired-speed quadratic [57–63] has c1 = CT2·ρD⁴/(4π²) and
 * c3 = |T| ≥ 0, so its discriminant c2² − 4·c1·c3 = c2² + 4·|c1|·|T| ≥ 0 for every thrust and
 * advance speed only when c1 < 0 (and c1 ≠ 0 is needed to divide by it). CT1, CQ1, CQ2 may
 * have any finite value.
 * @param[in] p parameters
 * Writes nothing (a pure check).
 * @retval UVMS_OK            every field finite and in range
 * @retval UVMS_ERR_ARG       p is NULL
 * @retval UVMS_ERR_NONFINITE a field is NaN or infinite
 * @retval UVMS_ERR_RANGE     a field violates its range: D, Rm, Lm, km, J, KA, KB or the
 *                            voltage limit not > 0, b < 0, or CT2 not < 0
 */
uvms_status_t uvms_thruster_params_validate(const uvms_thruster_params_t *p);

/**
 * @brief Thrust of the propeller, SPEC §5 (non-singular form):
 *        T = ρ·D⁴/(4π²)·(CT2·ω·|ω| + CT1·(2π·v_a/D)·|ω|).
 * @param[in] p                 parameters (not validated here: call
 *                              uvms_thruster_params_validate once at configuration)
 * @param[in] density_kg_m3     fluid density ρ [kg/m³]
 * @param[in] omega_rad_s       shaft speed ω [rad/s]
 * @param[in] advance_speed_m_s advance speed v_a [m/s]
 * @return thrust T [N] along u_j; 0 if p is NULL; NaN propagates from non-finite inputs
 */
uvms_real_t uvms_thruster_thrust_N(const uvms_thruster_params_t *p, uvms_real_t density_kg_m3,
                                   uvms_real_t omega_rad_s, uvms_real_t advance_speed_m_s);

/**
 * @brief Hydrodynamic torque on the shaft, SPEC §5 (non-singular form):
 *        Q = ρ·D⁵/(4π²)·(CQ2·ω·|ω| + CQ1·(2π·v_a/D)·|ω|); it enters the motor as
 *        J·ω̇ = km·I − b·ω − Q [53–55].
 * @param[in] p                 parameters (not validated here)
 * @param[in] density_kg_m3     fluid density ρ [kg/m³]
 * @param[in] omega_rad_s       shaft speed ω [rad/s]
 * @param[in] advance_speed_m_s advance speed v_a [m/s]
 * @return torque Q [N·m]; 0 if p is NULL; NaN propagates from non-finite inputs
 */
uvms_real_t uvms_thruster_torque_Nm(const uvms_thruster_params_t *p, uvms_real_t density_kg_m3,
                                    uvms_real_t omega_rad_s, uvms_real_t advance_speed_m_s);

/**
 * @brief Ramp lag of the thruster chain in the current drive (docs/MODEL.md §7.5):
 *        τ = (KB + b/J)/(KA·KB) [s] (the paper's motor: 0.24 s).
 *
 * With the loops [64]–[66] and the current drive, the shaft obeys (the load torque's slope
 * dQ/dω neglected beside b) ω̈ + (KB + b/J)·ω̇ + KA·KB·ω = KA·KB·ω̂; its transfer function
 * G(s) = KA·KB/(s² + (KB + b/J)·s + KA·KB) has G(0) = 1 and −G'(0) = τ, so a ramp of ω̂ is
 * followed τ behind once the transient has passed. The sampled loop on the plant's motor lags
 * a thrust ramp by 0.2369 s at the paper's 0.03 s tick (plant.drive test).
 * @param[in] p parameters (not validated here)
 * @return τ [s]; 0 if p is NULL or KA, KB or J is not > 0
 */
uvms_real_t uvms_thruster_ramp_lag_s(const uvms_thruster_params_t *p);

/**
 * @brief Shaft speed that produces a thrust, SPEC [57–63].
 *
 * Solves c1·ω² + c2·ω + c3 = 0 with c1 = CT2·ρD⁴/(4π²) < 0, c2 = CT1·v_a·ρD³/(2π), c3 = |T|,
 * taking ω+ = (−c2 + √disc)/(2c1) for T ≥ 0 and ω− = (−c2 − √disc)/(2c1) for T < 0, where
 * disc = c2² − 4c1c3 ≥ c2². Then ω+ ≤ 0 ≤ ω−, and thrust_N(ω) == T (derivation in
 * thruster.c). T = 0 gives ω = 0. Each root is evaluated in the form without cancellation.
 * @param[in]  p                 parameters (validated here)
 * @param[in]  density_kg_m3     fluid density ρ of the controller's model [kg/m³], > 0
 * @param[in]  thrust_N          desired thrust T̂ [N] along u_j
 * @param[in]  advance_speed_m_s advance speed v_a [m/s]
 * @param[out] omega_rad_s       desired shaft speed ω̂ [rad/s]; 0 on error
 * @retval UVMS_OK            *omega_rad_s = ω̂
 * @retval UVMS_ERR_ARG       p or omega_rad_s is NULL; writes: *omega_rad_s = 0 (if non-NULL)
 * @retval UVMS_ERR_NONFINITE a parameter or input is NaN/inf; writes: *omega_rad_s = 0
 * @retval UVMS_ERR_RANGE     invalid parameters (see uvms_thruster_params_validate), density
 *                            not > 0, or the discriminant or the speed overflows the real type
 *                            (huge |T| or |v_a|); writes: *omega_rad_s = 0
 */
uvms_status_t uvms_thruster_desired_speed(const uvms_thruster_params_t *p,
                                          uvms_real_t density_kg_m3, uvms_real_t thrust_N,
                                          uvms_real_t advance_speed_m_s,
                                          uvms_real_t *omega_rad_s);

/** Output of one thruster's controller tick (SPEC §7.4). */
typedef struct {
  uvms_real_t omega_des_rad_s;      /**< ω̂ [rad/s], [57–63] */
  uvms_real_t omega_dot_des_rad_s2; /**< ω̂̇ = KA·(ω̂ − ω) [rad/s²], [64] */
  uvms_real_t current_des_A;        /**< Î = (J·ω̂̇ + b·ω + Q)/km [A], [65] */
  uvms_real_t current_dot_des_A_s;  /**< İ* = KB·(Î − I) [A/s], [66] (before the clamp) */
  uvms_real_t voltage_V;            /**< V [V] to apply, [53], clamped to ±voltage_limit_V */
  uvms_real_t current_dot_cmd_A_s;  /**< the current rate to command [A/s]: İ* when V is not
                                         clamped, else the rate the clamped V gives at the
                                         tick's start through [53], (V − Rm·I − km·ω)/Lm, so
                                         the current drive respects the supply limit as the
                                         voltage drive does (at the start of the tick) */
  int saturated;                    /**< 1 if the voltage was clamped */
} uvms_motor_cmd_t;

/**
 * @brief One tick of the thruster controller, SPEC §7.4:
 *   ω̂ from [57–63];  ω̂̇ = KA·(ω̂ − ω) [64];  Î = (J·ω̂̇ + b·ω + Q(ω, v_a))/km [65];
 *   İ* = KB·(Î − I) [66];  V = Rm·I + Lm·İ* + km·ω [53], clamped to |V| ≤ voltage_limit_V.
 *
 * Without the clamp, applying V to the motor [53–55] gives exactly İ = KB·(Î − I); with it,
 * current_dot_cmd_A_s is the rate the clamped V gives, (V − Rm·I − km·ω)/Lm.
 * @param[in]  p                 parameters (validated here)
 * @param[in]  density_kg_m3     fluid density of the controller's model [kg/m³], > 0
 * @param[in]  thrust_des_N      desired thrust T̂ [N] along u_j (from the allocation)
 * @param[in]  advance_speed_m_s model advance speed v_a [m/s]
 * @param[in]  omega_meas_rad_s  measured shaft speed ω [rad/s]
 * @param[in]  current_meas_A    measured armature current I [A]
 * @param[out] cmd               command; all fields zero (V = 0, saturated = 0) on error
 * @retval UVMS_OK            *cmd holds the tick's command
 * @retval UVMS_ERR_ARG       p or cmd is NULL; writes: *cmd all zero (if non-NULL)
 * @retval UVMS_ERR_NONFINITE a parameter or input is NaN/inf, or a result overflowed; writes:
 *                            *cmd all zero
 * @retval UVMS_ERR_RANGE     invalid parameters, density not > 0, or the desired speed
 *                            overflows (as uvms_thruster_desired_speed); writes: *cmd all zero
 */
uvms_status_t uvms_motor_control(const uvms_thruster_params_t *p, uvms_real_t density_kg_m3,
                                 uvms_real_t thrust_des_N, uvms_real_t advance_speed_m_s,
                                 uvms_real_t omega_meas_rad_s, uvms_real_t current_meas_A,
                                 uvms_motor_cmd_t *cmd);


/**
 * The factors of one thruster's laws that depend only on its parameters and the fluid density
 * (SPEC §5, [57–66]), so that a tick multiplies where it would divide. uvms_motor_init and
 * uvms_motor_init_each compute them per thruster; the per-call functions above compute them
 * on each call, with the same code.
 */
typedef struct {
  uvms_real_t c1_N_s2;   /**< c1 = CT2·ρD⁴/(4π²) [N·s²] of [57–63], < 0 */
  uvms_real_t c2_N_s2_m; /**< c2 per unit advance speed, CT1·ρD³/(2π) [N·s²/m]: c2 = this·v_a */
  uvms_real_t kq_kg_m2;  /**< ρD⁵/(4π²) [kg·m²] of the torque law */
  uvms_real_t two_pi_over_D_1_m; /**< 2π/D [1/m]: the torque law's 2π·v_a/D = this·v_a */
  uvms_real_t inv_km_A_Nm; /**< 1/km [A/(N·m)] of [65] */
} uvms_thruster_coef_t;

/**
 * The motor loops of a vehicle's thrusters (SPEC §7.4 [57–66], [53]) as one caller-owned
 * instance, shaped like the other modules: uvms_motor_init() (one parameter set for every
 * thruster) or uvms_motor_init_each() (a set per thruster: thrusters of different types)
 * validates the parameters once and keeps them; uvms_motor_step() runs one thruster's loops
 * per tick; uvms_motor_end_tick() integrates each thruster's current command [66] over the
 * tick. Read the fields; change them only through the API.
 */
typedef struct {
  /** Thruster j's parameters (j < num_thrusters; beyond, thruster 1's, never NULL), validated
   *  at init and not copied (52 B per set in float): like uvms_arm_model_t's, they must
   *  outlive the instance and must not change while it is in use (the controller's point at
   *  its configuration). After uvms_motor_init every entry points at the one set given. */
  const uvms_thruster_params_t *p[UVMS_MAX_THRUSTERS];
  uvms_thruster_coef_t coef[UVMS_MAX_THRUSTERS]; /**< the factors of thruster j's laws,
                                     computed once at init (of p[j] and the density) */
  size_t num_thrusters;         /**< thrusters with parameters, 1..UVMS_MAX_THRUSTERS */
  uvms_real_t density_kg_m3;    /**< fluid density of the controller's model [kg/m³], > 0 */
  uvms_real_t tick_s;           /**< period over which [66] is integrated [s], > 0 */
  uvms_real_t current_cmd_A[UVMS_MAX_THRUSTERS]; /**< I*_j at the start of the coming tick
                                     [A]: the last tick's I*_j + İ*_j·tick_s (0 after init,
                                     reset, a tick without a command, or an overflow) */
  int ready;                    /**< 1 after a successful init */
} uvms_motor_t;

/**
 * @brief Validate and keep (a pointer to) one parameter set for every thruster
 *        (num_thrusters = UVMS_MAX_THRUSTERS); every integrated current command I*_j = 0.
 * @param[out] motor         instance; zeroed and not ready on error
 * @param[in]  p             parameters (uvms_thruster_params_validate); not copied: they must
 *                           outlive the instance and not change while it is in use
 * @param[in]  density_kg_m3 fluid density of the controller's model [kg/m³], finite and > 0
 * @param[in]  tick_s        controller period [s], finite and > 0
 * @retval UVMS_OK            ready = 1, current_cmd_A = 0
 * @retval UVMS_ERR_ARG       motor or p is NULL; writes: *motor all zero, ready = 0 (if
 *                            motor is non-NULL)
 * @retval UVMS_ERR_NONFINITE a parameter, the density or the tick is NaN/inf; writes: *motor
 *                            all zero
 * @retval UVMS_ERR_RANGE     a parameter out of range (uvms_thruster_params_validate), density
 *                            or tick not > 0; writes: *motor all zero
 */
uvms_status_t uvms_motor_init(uvms_motor_t *motor, const uvms_thruster_params_t *p,
                              uvms_real_t density_kg_m3, uvms_real_t tick_s);

/**
 * @brief Validate and keep (a pointer to) a parameter set per thruster: thruster j <
 *        num_thrusters gets p[j] (the sets of thrusters of different types differ); every
 *        I*_j = 0.
 * @param[out] motor         instance; zeroed and not ready on error
 * @param[in]  p             [UVMS_MAX_THRUSTERS] parameters; entries j < num_thrusters are
 *                           validated and used, the others never read; not copied: they must
 *                           outlive the instance and not change while it is in use
 * @param[in]  num_thrusters n, 1..UVMS_MAX_THRUSTERS
 * @param[in]  density_kg_m3 as uvms_motor_init
 * @param[in]  tick_s        as uvms_motor_init
 * @retval UVMS_OK            ready = 1, current_cmd_A = 0, num_thrusters = n
 * @retval UVMS_ERR_ARG       motor or p is NULL; writes: *motor all zero (if non-NULL)
 * @retval UVMS_ERR_SIZE      num_thrusters 0 or above UVMS_MAX_THRUSTERS; writes: *motor all
 *                            zero
 * @retval UVMS_ERR_NONFINITE a parameter of a set j < n, the density or the tick is NaN/inf;
 *                            writes: *motor all zero
 * @retval UVMS_ERR_RANGE     a parameter of a set j < n out of range, density or tick not > 0;
 *                            writes: *motor all zero
 */
uvms_status_t uvms_motor_init_each(uvms_motor_t *motor,
                                   const uvms_thruster_params_t p[UVMS_MAX_THRUSTERS],
                                   size_t num_thrusters, uvms_real_t density_kg_m3,
                                   uvms_real_t tick_s);

/** @brief Every integrated current command I*_j = 0 (the current drive then holds none).
 *         No status: motor NULL → nothing; readiness is not required. */
void uvms_motor_reset(uvms_motor_t *motor);

/**
 * @brief One tick of thruster j's loops: uvms_motor_control with the instance's parameters
 *        of thruster j (identical results, without re-validating them). The current command
 *        to apply with cmd->current_dot_cmd_A_s over the tick is motor->current_cmd_A[j].
 * @param[in]  motor  a ready instance
 * @param[in]  j      thruster index, < motor->num_thrusters (≤ UVMS_MAX_THRUSTERS)
 * @param[out] cmd    command; all zero (V = 0) on error
 * @retval UVMS_OK            *cmd holds the tick's command
 * @retval UVMS_ERR_ARG       motor or cmd is NULL, or j ≥ num_thrusters; writes: *cmd all
 *                            zero (if non-NULL)
 * @retval UVMS_ERR_STATE     motor not ready; writes: *cmd all zero
 * @retval UVMS_ERR_NONFINITE an input is NaN/inf, or a result overflowed; writes: *cmd all
 *                            zero
 * @retval UVMS_ERR_RANGE     the desired speed overflows (huge |T| or |v_a|); writes: *cmd all
 *                            zero
 */
uvms_status_t uvms_motor_step(const uvms_motor_t *motor, size_t j, uvms_real_t thrust_des_N,
                              uvms_real_t advance_speed_m_s, uvms_real_t omega_meas_rad_s,
                              uvms_real_t current_meas_A, uvms_motor_cmd_t *cmd);

/**
 * @brief End of a tick, [66] integrated: I*_j ← I*_j + İ*_j·tick_s for every j <
 *        UVMS_MAX_THRUSTERS, from the tick's commanded current and rate (a non-finite result
 *        gives 0). NULL arrays (no command this tick) give I*_j = 0.
 * @param[in,out] motor          instance (nothing happens if NULL)
 * @param[in]     current_cmd_A  [UVMS_MAX_THRUSTERS] the tick's I*_j [A], or NULL
 * @param[in]     current_rate_A_s [UVMS_MAX_THRUSTERS] the tick's İ*_j [A/s], or NULL
 */
void uvms_motor_end_tick(uvms_motor_t *motor, const uvms_real_t *current_cmd_A,
                         const uvms_real_t *current_rate_A_s);

#ifdef __cplusplus
}
#endif
#endif /* UVMS_THRUSTER_H */
