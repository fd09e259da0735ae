// SPDX-License-Identifier: Apache-2.0
// environment.hpp: the water and gravity the truth model lives in (SPEC §6): unsteady flow
// [28], gravity presets and trim ballast, and the variable hydrodynamic coefficients of the
// model-fidelity experiment. Only the plant sees the unsteady part of the flow.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "uvms_plant/params.hpp"

namespace uvms::plant {

// ---------------------------------------------------------------------------------------------
// Unsteady flow (SPEC §6.1, [28])

/// v∞(t) = v∞0 + Av·Σ_{k=1..n} (Ψs,k/k·sin(2πk·t/tF) + Ψc,k/k·cos(2πk·t/tF)), independently per
/// inertial axis, with Ψ drawn once, at construction, uniformly in [−1, 1).
///
/// Reproducibility: the draws come from std::mt19937_64 seeded with params.seed, whose output
/// sequence the C++ standard fixes. std::uniform_real_distribution is NOT used (its algorithm
/// is implementation-defined, so libstdc++ and libc++ would give different flows); each 64-bit
/// word x is mapped as Ψ = −1 + 2·(x >> 11)·2⁻⁵³, exact in double. Draw order, harmonic-major:
///   for k = 1..n: for axis x, y, z: Ψs,k(axis), then Ψc,k(axis)
/// so the same seed always gives the same flow, and raising n keeps the first harmonics.
/// When params.enabled is false nothing is drawn and Velocity() is exactly v∞0.
class UnsteadyFlow {
 public:
  static constexpr int kMaxHarmonics = 10000;  ///< sanity bound on n

  /// @param params          Av [m/s], n, seed, tF [s], enabled
  /// @param steady_flow_m_s v∞0, inertial [m/s]
  /// @throws std::invalid_argument if v∞0 is not finite or, when enabled, Av is not finite
  ///         and ≥ 0, n is not in [0, kMaxHarmonics], or tF is not finite and > 0
  UnsteadyFlow(const UnsteadyFlowParams &params, const Vec3 &steady_flow_m_s);

  /// Fluid velocity at time t_s [s] since the start of the run, inertial [m/s].
  Vec3 Velocity(double t_s) const;

  const UnsteadyFlowParams &params() const { return params_; }
  const Vec3 &steady_flow_m_s() const { return steady_m_s_; }
  /// Ψs,k per axis: row = axis (x, y, z), column k − 1; 3×0 when disabled.
  const Eigen::Matrix<double, 3, Eigen::Dynamic> &psi_sin() const { return psi_s_; }
  /// Ψc,k per axis, laid out as psi_sin().
  const Eigen::Matrix<double, 3, Eigen::Dynamic> &psi_cos() const { return psi_c_; }

 private:
  UnsteadyFlowParams params_{};
  Vec3 steady_m_s_{Vec3::Zero()};
  Eigen::Matrix<double, 3, Eigen::Dynamic> psi_s_{3, 0};
  Eigen::Matrix<double, 3, Eigen::Dynamic> psi_c_{3, 0};
};

// ---------------------------------------------------------------------------------------------
// Gravity (SPEC §2: g = (0, 0, −g), z up; SPEC §6.3)

Vec3 GravityPaper();   ///< (0, 0, 0): the paper's experiments are reproduced with g = 0
Vec3 GravityEarth();   ///< (0, 0, −9.81) [m/s²]
Vec3 GravityEuropa();  ///< (0, 0, −1.315) [m/s²]

/// Gravity vector by preset name: "paper", "earth" or "europa" (lower case).
/// @throws std::invalid_argument naming the unknown preset and listing the valid ones
Vec3 GravityPreset(const std::string &name);

/// Trim ballast (SPEC §6.3): the mass [kg] to add at the vehicle so that total weight equals
/// total buoyancy with the given payload,
///   m_ballast = ρ·(V0 + Σ_i V_i) − (m0 + Σ_i m_i + m_payload),
/// with the link volumes of SPEC §3.1: V_i = π·d_L,i²/4·|l_i|, |l_i| = √(a_i² + d_i²) (links
/// with |l_i| = 0 have none). The payload and the ballast itself have no volume (SPEC §2).
/// Positive: ballast weight to add; negative: the system is heavy and needs net flotation.
/// Independent of g (weight and buoyancy both scale with it).
/// @throws std::invalid_argument if ρ is not finite and > 0 or the payload is not finite, ≥ 0
double TrimBallastKg(const PlantParams &p, double density_kg_m3, double payload_kg);

/// The trim ballast (SPEC §6.3): a weight-only point (no volume, no inertia).
struct Ballast {
  double mass_kg{0.0};          ///< m_b [kg]; negative: a float (net buoyancy |m_b|·g, no mass)
  Vec3 offset_m{Vec3::Zero()};  ///< its point from the vehicle CoM, vehicle frame [m]
};

/// The trim ballast of SPEC §6.3 for p.env's density, trim payload, metacentric height h and
/// trim pose (the one computation both the plant and the controller's configuration use).
/// Mass: TrimBallastKg, so that total weight equals total buoyancy. Point: the one that puts
/// the center of gravity of all weights (vehicle, links, the trim payload at the payload point,
/// ballast) at h below the center of buoyancy of all displaced volumes (vehicle at cob_m, link
/// i at its mid-point μ_i), the vehicle level and the joints at trim_pose_rad. With every
/// position in the vehicle frame from the CoM (c_i link CoMs, p_p the payload point),
///   b = [ρ·(V0·c_b + Σ_i V_i·μ_i) − ρ·V_T·h·e_z − (Σ_i m_i·c_i + m_trim·p_p)] / m_b,
/// V_T = V0 + Σ_i V_i. Independent of g.
/// @throws std::invalid_argument as TrimBallastKg; if h is not finite, the trim pose does not
///         have one angle per link, or |m_b| ≤ 1e-6·ρ·V_T (an already neutral system: no ballast
///         mass to place)
Ballast TrimBallast(const PlantParams &p);

// ---------------------------------------------------------------------------------------------
// Variable hydrodynamic coefficients (SPEC §6.4, after McLain & Rock 1998)

/// Factors on a link's drag coefficient and added mass at one travelled distance.
struct CoeffFactors {
  double drag_factor{1.0};        ///< multiplies C_D0L [-]
  double added_mass_factor{1.0};  ///< multiplies ρ·V_i·Ma0 [-]
};

/// The default table, an APPROXIMATION of the published trend for a cylinder started from rest
/// (McLain & Rock 1998), NOT measured data: the drag factor starts low (0.5 at rest) while the
/// wake builds, overshoots to 1.3 at 5 diameters travelled and settles to 1.0 from 10 diameters
/// on; the added-mass factor starts at 1.0 and relaxes monotonically to 0.8 at 10 diameters.
/// Knots [d_L]: 0, 2, 5, 7.5, 10; piecewise-linear between them, constant beyond.
std::vector<CoeffTableRow> DefaultCoeffTable();

/// Check a coefficient table: non-empty; every value finite; distances ≥ 0 and strictly
/// increasing; factors ≥ 0.
/// @throws std::invalid_argument naming the offending row and value
void ValidateCoeffTable(const std::vector<CoeffTableRow> &table);

/// Piecewise-linear interpolation of the table at a travelled distance [link diameters],
/// clamped to the first row below the first knot and to the last row beyond the last one.
/// The table must be valid (ValidateCoeffTable once at configuration; only emptiness is
/// re-checked here).
/// @throws std::invalid_argument if the table is empty or the distance is NaN
CoeffFactors InterpolateCoeffs(const std::vector<CoeffTableRow> &table,
                               double distance_diameters);

}  // namespace uvms::plant
