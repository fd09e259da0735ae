// SPDX-License-Identifier: Apache-2.0
// propulsion.hpp: the truth model's thrusters and motors (SPEC §3.4, §5 "Thrusters", "Motors",
// "Energy"), written from SPEC, independently of firmware/.
//
// Sign conventions (SPEC §5), the same ones the controller assumes:
// - thrust T [N] is positive along the thruster's direction u_j;
// - the advance speed v_a [m/s] is the thruster's speed through the fluid along u_j;
// - with CT2 < 0 (the paper), positive thrust needs negative shaft speed ω;
// - the hydrodynamic torque Q [N·m] is a load subtracted from the motor torque:
//   J·ω̇ = km·I − b·ω − Q, whatever its sign.
#pragma once

#include <Eigen/Dense>
#include <utility>
#include <vector>

#include "uvms_plant/params.hpp"

namespace uvms::plant {

/// Check a propulsion parameter set: every field finite; D, Rm, Lm, km, J > 0; b ≥ 0.
/// CT1, CT2, CQ1, CQ2 may have any finite value (the plant has no speed solution to protect).
/// @throws std::invalid_argument naming the first offending field
void ValidatePropulsionParams(const PropulsionParams &p);

/// Propeller thrust, SPEC §5 [47–52] in the non-singular form
///   T = ρ·D⁴/(4π²)·(CT2·ω·|ω| + CT1·(2π·v_a/D)·|ω|),
/// equal to the paper's ρ·D⁴/(4π²)·ω·|ω|·(CT2 + CT1·ζ), ζ = 2π·v_a/(ω·D), for ω ≠ 0.
/// @param p                 propeller parameters (not validated here)
/// @param density_kg_m3     fluid density ρ [kg/m³]
/// @param omega_rad_s       shaft speed ω [rad/s]
/// @param advance_speed_m_s advance speed v_a [m/s] (AdvanceSpeedMS)
/// @return thrust T [N] along u_j
double ThrustN(const PropulsionParams &p, double density_kg_m3, double omega_rad_s,
               double advance_speed_m_s);

/// Hydrodynamic shaft torque, SPEC §5: Q = ρ·D⁵/(4π²)·(CQ2·ω·|ω| + CQ1·(2π·v_a/D)·|ω|).
/// Parameters as ThrustN. @return Q [N·m], the load torque of MotorRhs
double TorqueNm(const PropulsionParams &p, double density_kg_m3, double omega_rad_s,
                double advance_speed_m_s);

/// ThrustN and TorqueNm with their constants folded for one propeller and density (what the
/// plant's right-hand side evaluates): X = ww·ω·|ω| + wv·v_a·|ω|.
struct PropellerCoeffs {
  double thrust_ww{0.0}, thrust_wv{0.0};  ///< ρ·D⁴/(4π²)·CT2 [kg/m], ρ·D⁴/(4π²)·CT1·2π/D [kg/m²·m]
  double torque_ww{0.0}, torque_wv{0.0};  ///< the same with D⁵ and CQ2, CQ1
  double Thrust(double omega_rad_s, double advance_speed_m_s) const {
    const double a = omega_rad_s < 0.0 ? -omega_rad_s : omega_rad_s;
    return thrust_ww * omega_rad_s * a + thrust_wv * advance_speed_m_s * a;
  }
  double Torque(double omega_rad_s, double advance_speed_m_s) const {
    const double a = omega_rad_s < 0.0 ? -omega_rad_s : omega_rad_s;
    return torque_ww * omega_rad_s * a + torque_wv * advance_speed_m_s * a;
  }
};
PropellerCoeffs PropellerCoeffsOf(const PropulsionParams &p, double density_kg_m3);

/// Advance speed of one thruster, SPEC §5 [47–52]:
///   v_a = u·(R0ᵀ·(v0 + ω0 × R0·a − v∞)),
/// the velocity of the thruster point through the water, expressed in the vehicle frame and
/// projected on the thruster direction.
/// @param g      thruster position a (from the vehicle CoM) and unit direction u, vehicle frame
/// @param R0     vehicle attitude (vehicle → inertial)
/// @param v0_I   vehicle CoM velocity, inertial [m/s]
/// @param w0_I   vehicle angular velocity, inertial [rad/s]
/// @param vinf_I fluid velocity v∞ at the vehicle, inertial [m/s]
/// @return v_a [m/s]
double AdvanceSpeedMS(const ThrusterGeometry &g, const Mat3 &R0, const Vec3 &v0_I,
                      const Vec3 &w0_I, const Vec3 &vinf_I);

/// The same from the vehicle's velocity relative to the water v_rel_B = R0ᵀ·(v0 − v∞) and its
/// angular velocity w0_B = R0ᵀ·ω0, both in vehicle axes (computed once for all thrusters).
double AdvanceSpeedBodyMS(const ThrusterGeometry &g, const Vec3 &v_rel_B, const Vec3 &w0_B);

/// Time derivatives of one motor's state.
struct MotorDerivatives {
  double current_dot_A_s{0.0};   ///< İ [A/s]
  double omega_dot_rad_s2{0.0};  ///< ω̇ [rad/s²]
};

/// DC motor, SPEC §5 [53–55]: Lm·İ = V − Rm·I − km·ω;  J·ω̇ = km·I − b·ω − Q.
/// @param p               motor parameters (Lm, J > 0: ValidatePropulsionParams; not checked
///                        here, this runs inside the integrator's right-hand side)
/// @param voltage_V       applied armature voltage V [V]
/// @param current_A       armature current I [A]
/// @param omega_rad_s     shaft speed ω [rad/s]
/// @param load_torque_Nm  propeller torque Q [N·m] (TorqueNm), subtracted from km·I
MotorDerivatives MotorRhs(const PropulsionParams &p, double voltage_V, double current_A,
                          double omega_rad_s, double load_torque_Nm);

/// The same with 1/Lm and 1/J given (precomputed by the plant: no division per evaluation).
MotorDerivatives MotorRhs(const PropulsionParams &p, double inv_inductance_1_H,
                          double inv_rotor_inertia_1_kg_m2, double voltage_V, double current_A,
                          double omega_rad_s, double load_torque_Nm);

/// Integrands of the thruster energies (SPEC §5 "Energy").
struct EnergyRates {
  double thruster_draw_W{0.0};    ///< Σ_j max(V_j·I_j, 0): battery draw, no regeneration [W]
  double thruster_signed_W{0.0};  ///< Σ_j V_j·I_j: signed electrical power [W]
};

/// Thruster power integrands from the voltages and currents of all thrusters.
/// @param voltage_V  V_j [V], one per thruster
/// @param current_A  I_j [A], same size
/// @throws std::invalid_argument if the sizes differ
EnergyRates ThrusterEnergyRates(const Eigen::Ref<const Eigen::VectorXd> &voltage_V,
                                const Eigen::Ref<const Eigen::VectorXd> &current_A);
EnergyRates ThrusterEnergyRates(const std::vector<double> &voltage_V,
                                const std::vector<double> &current_A);

/// Ideal propulsive (actuator-disk) power of all thrusters (SPEC §5 "Energy"):
///   P_p = Σ_j |T_j|^(3/2)/√(2ρ·A_d),  A_d = π·D²/4,
/// the least power any propeller of disk area A_d needs to make thrust T_j at rest in fluid of
/// density ρ (momentum theory). 0 when ρ = 0 (no thrust is possible then).
/// @param p             propeller parameters (D)
/// @param density_kg_m3 fluid density ρ [kg/m³], ≥ 0
/// @param thrust_N      T_j [N], one per thruster
/// @return P_p [W]
double PropulsivePowerW(const PropulsionParams &p, double density_kg_m3,
                        const std::vector<double> &thrust_N);

/// Manipulator power integrand (SPEC §5 "Energy"): Σ_i |τ_i·θ̇_i| [W].
/// @param tau_Nm      joint torques τ_i [N·m]
/// @param qdot_rad_s  joint rates θ̇_i [rad/s], same size
/// @throws std::invalid_argument if the sizes differ
double ManipulatorPowerW(const Eigen::Ref<const Eigen::VectorXd> &tau_Nm,
                         const Eigen::Ref<const Eigen::VectorXd> &qdot_rad_s);
double ManipulatorPowerW(const std::vector<double> &tau_Nm, const std::vector<double> &qdot_rad_s);

/// Closed-form response of the motor with zero propeller load (Q = 0) to a voltage step V
/// applied at t = 0 from rest (I = 0, ω = 0): the solution of the linear system
///   d/dt (I, ω) = A·(I, ω) + (V/Lm, 0),  A = [[−Rm/Lm, −km/Lm], [km/J, −b/J]],
/// as (I, ω) = x∞ + exp(A·t)·(−x∞), with the steady state
///   x∞ = (b·V, km·V)/(Rm·b + km²)
/// and exp(A·t) from Cayley–Hamilton: with s = tr(A)/2 and δ² = s² − det(A) (eigenvalues
/// s ± δ), exp(A·t) = e^{s·t}·(c(t)·I₂ + h(t)·(A − s·I₂)) where c = cosh(δt), h = sinh(δt)/δ for
/// real roots (δ² > 0), c = cos(ω_d·t), h = sin(ω_d·t)/ω_d, ω_d = √(−δ²), for complex roots, and
/// c = 1, h = t for a repeated root. The paper's motor has λ = −1 ± 100i. Used by tests to
/// check numerical integration of MotorRhs.
/// @param p          motor parameters (validated here)
/// @param voltage_V  step height V [V]
/// @param t_s        time since the step [s], ≥ 0
/// @return (I [A], ω [rad/s]) at t_s
/// @throws std::invalid_argument for invalid parameters or t_s < 0 / non-finite inputs
std::pair<double, double> LinearMotorStepResponse(const PropulsionParams &p, double voltage_V,
                                                  double t_s);

}  // namespace uvms::plant
