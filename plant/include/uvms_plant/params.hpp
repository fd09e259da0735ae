// SPDX-License-Identifier: Apache-2.0
// params.hpp: every parameter of the truth model (SPEC §3, §5, §6), with the paper's values
// as defaults. The plant never reads the firmware's structures: this is its own description.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace uvms::plant {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Vec6 = Eigen::Matrix<double, 6, 1>;

/// One arm link: standard DH, inertia, hydrodynamic cylinder (SPEC §2, §3.1).
struct LinkParams {
  double alpha_rad{0.0};        ///< DH twist α_i [rad]
  double a_m{0.0};              ///< DH length a_i [m]
  double d_m{0.0};              ///< DH offset d_i [m]
  /// General placement (docs/MODEL.md §2 "General links"): frame i = frame i−1 ·
  /// Rz(θ_i)·Tz(d)·Tx(a)·Rx(α)·T(t_i)·Rot(ρ_i); both zero: a standard DH link.
  Vec3 placement_m{Vec3::Zero()};          ///< t_i, in the frame after Rx(α_i) [m]
  Vec3 placement_rotvec_rad{Vec3::Zero()};  ///< ρ_i, rotation vector (axis × angle) [rad]
  double mass_kg{0.0};          ///< m_i [kg]
  Vec3 com_m{Vec3::Zero()};     ///< r_i: proximal joint → CoM, frame i [m]
  Vec3 inertia_kg_m2{Vec3::Zero()};  ///< diagonal of I_Bi about the CoM, frame-i axes [kg·m²]
  /// Off-diagonal entries (I_xy, I_xz, I_yz) of I_Bi as they stand in the tensor, frame-i axes
  /// [kg·m²]; zero: principal axes (the paper's links).
  Vec3 inertia_products_kg_m2{Vec3::Zero()};
  double diameter_m{0.089};     ///< hydrodynamic cylinder diameter d_L [m]
  double drag_coeff{1.0};       ///< C_D0L [-]
  /// The link's own added mass (docs/MODEL.md §3.3): diagonal on (a; ω̇) of its center of
  /// buoyancy μ_i, frame-i axes, kg ×3 then kg·m² ×3; all zero (the paper's links): ρ·V_i·Ma0.
  double added_mass_kg[6]{};
};

/// True when link L has its own diagonal added mass (LinkParams::added_mass_kg).
inline bool HasOwnAddedMass(const LinkParams &L) {
  for (double x : L.added_mass_kg)
    if (x != 0.0) return true;
  return false;
}

/// Rot(ρ) of a rotation vector (identity for ρ = 0).
inline Mat3 RotationOf(const Vec3 &rotvec_rad) {
  const double phi = rotvec_rad.norm();
  return phi > 0.0 ? Mat3(Eigen::AngleAxisd(phi, rotvec_rad / phi)) : Mat3(Mat3::Identity());
}

/// True if the link has a general placement (not a pure standard-DH link).
inline bool IsPlaced(const LinkParams &L) {
  return !L.placement_m.isZero(0.0) || !L.placement_rotvec_rad.isZero(0.0);
}

/// l_i: origin i−1 → origin i in frame i ([1]; Rot(ρ_i)ᵀ·(l_DH + t_i) for a placed link).
inline Vec3 LinkVector(const LinkParams &L) {
  const Vec3 l(L.a_m, L.d_m * std::sin(L.alpha_rad), L.d_m * std::cos(L.alpha_rad));
  return IsPlaced(L) ? Vec3(RotationOf(L.placement_rotvec_rad).transpose() * (l + L.placement_m)) : l;
}

/// |l_i|, the link cylinder's length (SPEC §3.1): √(a² + d²) for a DH link.
inline double LinkLength(const LinkParams &L) {
  return IsPlaced(L) ? LinkVector(L).norm() : std::hypot(L.a_m, L.d_m);
}

/// I_Bi of a link: the full tensor from its diagonal and off-diagonal entries.
inline Mat3 InertiaTensor(const LinkParams &L) {
  const Vec3 &d = L.inertia_kg_m2, &o = L.inertia_products_kg_m2;
  Mat3 I;
  I << d[0], o[0], o[1],  //
      o[0], d[1], o[2],   //
      o[1], o[2], d[2];
  return I;
}

/// The vehicle body (SPEC §3.2).
struct VehicleParams {
  double mass_kg{120.0};                  ///< m0 [kg]
  double volume_m3{0.15};                 ///< V0 [m³]
  double frontal_area_m2{0.5};            ///< A0 [m²]
  double drag_coeff{1.2};                 ///< C_D0 [-]
  /// Fossen's diagonal damping on the body velocity relative to the fluid, ν = (u, v, w, p, q,
  /// r) (docs/MODEL.md §3.2): linear [N·s/m ×3, N·m·s/rad ×3] and quadratic [N·s²/m² ×3,
  /// N·m·s²/rad² ×3]. Zero (the paper's vehicle): only the isotropic drag of C_D0, A0 acts.
  double linear_damping[6]{};
  double quadratic_damping[6]{};
  /// The vehicle's own 6×6 added mass, absolute [kg, kg·m, kg·m²] on (v̇; ω̇) at the center of
  /// buoyancy, vehicle frame (docs/MODEL.md §3.3), as identification papers give it. Absent
  /// (the paper's vehicle): ρ·V0·Ma0, the links' coefficients scaled by the vehicle's volume.
  std::optional<Mat6> added_mass_kg;
  Vec3 inertia_kg_m2{20.0, 20.0, 20.0};   ///< diagonal about the CoM, vehicle axes [kg·m²]
  Vec3 cob_m{Vec3::Zero()};               ///< center of buoyancy from the CoM, vehicle frame [m]
  Vec3 base_offset_m{0.914, 0.0, 0.152};  ///< s0: CoM → arm base point, vehicle frame [m]
  Vec3 base_rotvec_rad{Vec3::Zero()};      ///< arm base axes from the vehicle's (rotation vector) [rad]
  /// Hull box for the contact monitor (not in the paper): 1 m × 1 m in plan, 0.6 m tall, its
  /// top 0.1 m above the CoM so that it sits under the stowed arm (whose lowest point, link 3
  /// near the base, is at z = 0.1075 m in the vehicle frame).
  Vec3 hull_size_m{1.0, 1.0, 0.6};         ///< hull box edge lengths [m]
  Vec3 hull_center_m{0.0, 0.0, -0.2};      ///< hull box center from the CoM, vehicle frame [m]
};

/// Thruster j: position a_j and direction u_j in the vehicle frame (SPEC §3.4).

/// Propeller and motor of every thruster (SPEC §3.4, §5 [47]–[55]).
/// The motors' power stage (SPEC §5 "Motors", docs/MODEL.md §5).
enum class MotorDrive {
  /// The paper's reading, the default: over a tick the armature current is the controller's
  /// integrated command, I(t) = I*_k + İ*_k·(t − t_k); the terminal voltage
  /// V = Rm·I + Lm·İ + km·ω [53] follows and enters the energy integrals.
  kCurrent,
  /// The controller's voltage is held over the tick; Lm·İ = V − Rm·I − km·ω is integrated.
  kVoltage,
};

struct PropulsionParams {
  MotorDrive drive{MotorDrive::kCurrent};  ///< power stage of every motor
  double diameter_m{0.05};        ///< D [m]
  double ct1{0.5}, ct2{-0.5};     ///< thrust coefficients [-]
  double cq1{0.15}, cq2{-0.15};   ///< torque coefficients [-]
  double resistance_ohm{1.0};     ///< Rm [Ω]
  double inductance_H{1.0};       ///< Lm [H]
  double torque_constant_Nm_A{10.0};  ///< km [N·m/A] = back-EMF constant [V·s/rad]
  double viscous_friction_Nm_s{0.01}; ///< b [N·m·s/rad]
  double rotor_inertia_kg_m2{0.01};   ///< J [kg·m²]
};

/// One thruster (SPEC §3.4): where it is, where it pushes, and its propeller and motor when
/// they differ from PlantParams::propulsion (a thruster of another type).
struct ThrusterGeometry {
  Vec3 position_m{Vec3::Zero()};  ///< a_j from the vehicle CoM, vehicle frame [m]
  Vec3 direction{Vec3::UnitX()};  ///< u_j, vehicle frame (normalised by the plant)
  /// This thruster's propeller and motor; none: PlantParams::propulsion's. Its `drive` is not
  /// read: every motor has PlantParams::propulsion.drive's power stage.
  std::optional<PropulsionParams> propulsion;
};

/// Unsteady flow [28] (SPEC §6.1): per axis, Av·Σ_k (Ψs,k/k·sin(2πkt/tF) + Ψc,k/k·cos(2πkt/tF)).
struct UnsteadyFlowParams {
  bool enabled{false};
  double amplitude_m_s{0.01};     ///< Av [m/s]
  int harmonics{5};               ///< n
  uint64_t seed{1};               ///< seed of the Ψ draws (uniform in [−1, 1])
  double period_s{60.0};          ///< tF, the run duration [s]
};

/// One row of the variable-coefficient table (SPEC §6.4): factors at a travelled distance.
struct CoeffTableRow {
  double distance_diameters{0.0};  ///< distance travelled by the aerodynamic center [d_L]
  double drag_factor{1.0};         ///< multiplies C_D0L [-]
  double added_mass_factor{1.0};   ///< multiplies the link's added mass [-]
};

/// Environment of the truth model (SPEC §6).
struct EnvironmentParams {
  double density_kg_m3{1025.0};            ///< actual ρ [kg/m³]
  Vec3 steady_flow_m_s{Vec3::Zero()};      ///< v∞0, inertial [m/s]
  UnsteadyFlowParams unsteady{};
  Vec3 gravity_m_s2{Vec3::Zero()};         ///< g vector (paper experiments: 0; SPEC §6.3)
  bool angle_of_attack{true};              ///< C_D = C_D0L·sin²α [21] (false: C_D0L)
  bool variable_coefficients{false};       ///< SPEC §6.4
  std::vector<CoeffTableRow> coeff_table;  ///< empty: the default approximation
  bool trim{false};                        ///< add trim ballast (SPEC §6.3)
  double trim_payload_kg{10.0};            ///< nominal payload the trim is computed for [kg]
  /// h: the trimmed system's center of gravity lies this far below its center of buoyancy, in
  /// the trim pose with the vehicle level (SPEC §6.3) [m]. 0.05 m (choice C19): a few cm, as
  /// on small underwater vehicles; the restoring moment M·g·h·sin φ gives ≈ 78 N·m/rad at Earth
  /// and ≈ 10.5 N·m/rad on Europa, of the order of the attitude stiffness K_PN = 10 N·m/rad
  /// (SPEC §3.5). Each centimetre lowers the ballast by M/m_ballast ≈ 15 cm.
  double metacentric_height_m{0.05};
  /// Joint angles the trim is computed at, N of them [rad]; PaperPlantParams() sets the
  /// stowed pose θI of SPEC §8. Empty is accepted only while trim is off.
  std::vector<double> trim_pose_rad;
  /// Displacement of the plant's ballast from its trim point, vehicle frame [m]: a trim error
  /// (plant only; the controller's model keeps the trim point). 0: trimmed as computed.
  Vec3 ballast_error_m{Vec3::Zero()};
};

/// CVODE settings (SPEC §5).
struct IntegratorParams {
  enum class Method { kAdams, kBdf };
  Method method{Method::kAdams};
  double rel_tol{1e-8};
  /// [state units] 1e-9, not 1e-10: the states that hover near zero in
  /// station keeping (attitude vector part, velocities) made the absolute term bind and cost
  /// 21 rhs evaluations per closed-loop tick; 1e-9 takes 14 with the results unchanged far
  /// below the reported precision (plant.convergence; docs/BENCHMARKS.md, tolerance study).
  double abs_tol{1e-9};
  long max_steps{5000};          ///< per tick (CVodeSetMaxNumSteps)
  /// Safety factor of CVODE's nonlinear convergence test (CVodeSetNonlinConvCoef; CVODE's
  /// default 0.1), > 0: the corrector stops once its estimated remaining error is below this
  /// fraction of the local error tolerance. 0.2 lets most Adams/fixed-point steps converge
  /// after one iteration (plant benchmark: 15.2 → 13.0 rhs evaluations per tick) with the
  /// accuracy unchanged: the integrator's analytic tests (decay 4.5e-8 → 4.8e-8, oscillator
  /// 1.4e-6 → 1.1e-6) and the plant's tolerance study (docs/BENCHMARKS.md). 0.5 saved more
  /// (10.8) but multiplied the oscillator's error by 6.
  double nonlin_conv_coef{0.2};
  /// Integrate the motors [53–55] in integrating-factor (Lawson) variables: within a tick
  /// CVODE carries z_j with (I_j, ω_j) = x∞_j + e^{A·τ}·z_j, so the linear motor mode
  /// (λ = −1 ± 100i for the paper's motor) is propagated exactly and only the propeller-load
  /// change drives z_j; the thruster energies are split the same way (plant.cpp). An exact
  /// change of variables, not an approximation; false integrates (I, ω) directly. Ignored
  /// (direct form) when e^{−A·dt} would amplify by more than e⁴ (very fast real modes).
  bool motor_integrating_factor{true};
  /// First step of each tick's restart as a fraction of the step CVODE's error control chose
  /// at the end of the previous tick (Integrator::SetInitStep / NextStep), in [0, 1]; 0 leaves
  /// the first step to CVODE's own estimate (two extra rhs evaluations per tick). The restart
  /// begins at order 1, and CVODE may grow its first step 10⁴-fold, so a small fraction costs
  /// no steps while keeping the order-1 error far below the tolerance: 0.001–0.02 take the
  /// same work on the benchmark, and at 0.002 the coasting test's global error is CVODE's
  /// own (5.5e-7 vs 5.4e-7 m; 1.3e-6 m at 0.02). See docs/BENCHMARKS.md.
  double restart_step_fraction{0.002};
  /// [rad/s] Absolute tolerance of the motor speeds ω_j, in place of abs_tol (whose 1e-9 is
  /// meant for metres and radians): a thruster idling near ω = 0 in station keeping made
  /// 1e-9 rad/s bind, and the speeds set most of CVODE's steps. 2e-6 rad/s moves the paper's
  /// propeller thrust by less than 4e-8 N at 100 rad/s; closed-loop case VII takes 8.0 (stagnant)
  /// and 8.4 (unsteady) rhs evaluations per tick instead of 10.7, with the EE errors within
  /// 1e-7 m and the energies within 2e-6 relative of a rel 1e-12 / abs 1e-14 reference. The
  /// per-tick split of the propulsive energy into position and attitude parts (an attribution of
  /// small differences) is the most sensitive figure: 0.6 % off the reference in case V stagnant
  /// (0.03 % at 1e-9, 1.6 % at 1e-5) (docs/BENCHMARKS.md, tolerance study).
  double motor_speed_abs_tol_rad_s{2e-6};
  /// Largest step growth CVODE allows in the first steps after a restart
  /// (CVodeSetEtaMaxEarlyStep; CVODE's default 10), > 1. Every tick restarts at order 1 with a
  /// small first step (restart_step_fraction); a 10-fold growth at the switch to order 2 failed
  /// CVODE's error test about once per tick, and each failure cost a repeated step. 4 grows
  /// the steps as fast without the failures: 13.8 → 10.7 rhs evaluations per closed-loop tick
  /// (case VII), accuracy unchanged (the error test is the same).
  double early_step_growth_max{4.0};
};

/// A vertical-cylinder obstacle of the scene (e.g. the vent chimney), for the contact monitor.
struct CylinderObstacle {
  std::string name{"chimney"};
  Vec3 base_center_m{Vec3::Zero()};  ///< center of the bottom disc, inertial [m]
  double height_m{1.0};
  double radius_m{0.5};
};

/// Contact monitoring (SPEC §5): links as capsules, hull as a box, scene obstacles.
struct ContactParams {
  bool enabled{true};
  double clearance_m{0.0};           ///< a distance below this ends the run [m]
  /// Link–link checks. Off by default: with the hydrodynamic cylinders of SPEC §3.1
  /// (0.089 m diameter) the paper's stowed pose θI already overlaps itself (link 3 with the
  /// wrist links 6–7, −0.02 m): the real WAM's links are slimmer where they fold. The arm is
  /// then checked against the hull and the scene only.
  bool self_collision{false};
  std::vector<CylinderObstacle> obstacles;
};

/// Everything the plant needs. PaperPlantParams() gives SPEC §3's values.
struct PlantParams {
  std::vector<LinkParams> links;            ///< 1..7 links
  VehicleParams vehicle{};
  double payload_kg{10.0};                  ///< point payload at the EE [kg]
  Vec3 payload_offset_m{Vec3::Zero()};      ///< EE → payload, frame N [m]
  Mat6 added_mass_coeff{Mat6::Zero()};      ///< Ma0 (SPEC §3.3), unscaled
  std::vector<ThrusterGeometry> thrusters;  ///< 8 in the paper
  PropulsionParams propulsion{};
  EnvironmentParams env{};
  IntegratorParams integrator{};
  ContactParams contact{};
};

/// Thruster j's propeller and motor: its own, else p.propulsion (ThrusterGeometry::propulsion).
inline const PropulsionParams &PropulsionOf(const PlantParams &p, std::size_t j) {
  return (j < p.thrusters.size() && p.thrusters[j].propulsion) ? *p.thrusters[j].propulsion : p.propulsion;
}

/// True when some thruster has its own propeller and motor.
inline bool HasThrusterTypes(const PlantParams &p) {
  for (const ThrusterGeometry &t : p.thrusters)
    if (t.propulsion) return true;
  return false;
}

/// SPEC §3's parameters: Barrett WAM links, 120 kg vehicle, 10 kg payload, Ma0, 8 thrusters.
PlantParams PaperPlantParams();

}  // namespace uvms::plant
