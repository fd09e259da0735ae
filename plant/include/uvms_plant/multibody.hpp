// SPDX-License-Identifier: Apache-2.0
// multibody.hpp: the truth model's rigid-body mechanics (SPEC §2, §4, §5), written
// independently of the firmware: point velocities and accelerations from the joint-axis
// (Jacobian) form instead of the paper's link-to-link recursion, every body's required wrench
// computed on its own and then summed (the joint wrenches are sums over the distal bodies),
// and the vehicle acceleration from the composite 6×6 system inertia of SPEC §5.
#pragma once

#include <vector>

#include "uvms_plant/params.hpp"

namespace uvms::plant {

/// Immutable model derived from PlantParams (SPEC §2, §3.1).
struct ArmModel {
  int n{0};                          ///< number of links N
  std::vector<LinkParams> link;      ///< link[i-1] is link i
  std::vector<Vec3> l_m;             ///< l_i = (a, d·sin α, d·cos α), frame i [m] ([1]); index i-1
  std::vector<double> cos_alpha, sin_alpha;  ///< cos α_i, sin α_i of the DH twist; index i-1
  std::vector<bool> placed;          ///< link i has a general placement (t_i, ρ_i); index i-1
  std::vector<Mat3> place_rot;       ///< Rot(ρ_i) of a placed link (else identity); index i-1
  bool base_rotated{false};          ///< the arm base frame is turned from the vehicle axes
  Mat3 base_rot{Mat3::Identity()};   ///< Rot(ρ_B): vehicle axes → arm base axes
  std::vector<double> volume_m3;     ///< V_i = π·d_L²/4·|l_i| [m³]
  std::vector<double> area_m2;       ///< A_i = d_L·|l_i| [m²]
  std::vector<Vec3> l_unit;          ///< l_i/|l_i| (zero for a link of no length); index i-1
  VehicleParams vehicle;
  double payload_kg{0.0};
  Vec3 payload_offset_m{Vec3::Zero()};
  Mat6 added_mass_coeff{Mat6::Zero()};  ///< Ma0, unscaled (SPEC §3.3)
  double total_mass_kg{0.0};         ///< m0 + Σ m_i + payload [kg]
  /// A 3×3 block X of an added-mass matrix, kept for R·X·Rᵀ = x·I + Σ X_jk·r_j·r_kᵀ (r_j the
  /// columns of R; R·Rᵀ = I): the equal part x of its diagonal and the other non-zero entries.
  /// A block with more than kMaxTerms such entries is rotated by two 3×3 products instead.
  struct RotatableBlock {
    static constexpr int kMaxTerms = 4;
    Mat3 X{Mat3::Zero()};
    double scalar{0.0};
    int terms{0};  ///< -1: dense
    int j[kMaxTerms]{}, k[kMaxTerms]{};
    double value[kMaxTerms]{};
    static RotatableBlock Of(const Mat3 &X);
    Mat3 Rotated(const Mat3 &R) const;  ///< R·X·Rᵀ
  };
  /// An added-mass matrix by blocks [[A, B], [C, D]]; symmetric: C = Bᵀ (not rotated).
  struct AddedMassBlocks {
    RotatableBlock A, B, C, D;
    bool symmetric{true};
    static AddedMassBlocks Of(const Mat6 &M);
  };
  // Per-link constants of the loads (index i-1):
  std::vector<AddedMassBlocks> added_unit;  ///< the link's own diagonal, else Ma0 (unscaled)
  std::vector<char> own_added;       ///< added_unit is the link's own (scale 1, not ρ·V_i)
  std::vector<Mat3> inertia_com;     ///< I_Bi about the CoM, frame i [kg·m²]
  std::vector<char> inertia_diagonal;  ///< I_Bi has no products of inertia
  /// Ma0 and the vehicle's added mass are symmetric (as an ideal fluid's are): M_sys is
  /// symmetric positive definite and solved by Cholesky (otherwise LU).
  bool symmetric{true};
  Mat6 vehicle_rigid{Mat6::Zero()};       ///< vehicle rigid inertia about its CoM, vehicle axes
  Mat6 vehicle_added_unit{Mat6::Zero()};  ///< its added mass (own, or Ma0) moved from the CoB
                                          ///< to the CoM, vehicle axes, unscaled
  Mat6 vehicle_added_cob_unit{Mat6::Zero()};  ///< the same about the CoB (own, or Ma0)
  bool vehicle_damped{false};             ///< HasDamping(vehicle)

  static ArmModel FromParams(const PlantParams &p);  ///< throws std::invalid_argument
};

/// Vehicle state: CoM position, attitude (vehicle → inertial), CoM velocity and angular
/// velocity, all inertial.
struct BaseState {
  Vec3 r0_m{Vec3::Zero()};
  Mat3 R0{Mat3::Identity()};
  Vec3 v0_m_s{Vec3::Zero()};
  Vec3 w0_rad_s{Vec3::Zero()};
};

/// The water and gravity as the truth model sees them at one instant.
struct FluidState {
  double density_kg_m3{1025.0};
  Vec3 flow_m_s{Vec3::Zero()};        ///< v∞(t), inertial
  Vec3 gravity_m_s2{Vec3::Zero()};
  bool angle_of_attack{true};
  double ballast_kg{0.0};             ///< trim ballast, weight only (SPEC §6.3) [kg]
  Vec3 ballast_offset_m{Vec3::Zero()};  ///< its point from the vehicle CoM, vehicle frame [m]
  std::vector<double> drag_factor;    ///< per link, SPEC §6.4 (empty: 1)
  std::vector<double> added_mass_factor;  ///< per link, SPEC §6.4 (empty: 1)
};

/// Positions, orientations, velocities and velocity-product accelerations of the arm. The
/// accelerations are those with zero vehicle acceleration (suffix _0); the true ones add
/// v̇0 + ω̇0 × (x − r0) for a point x and ω̇0 for an angular acceleration.
struct ArmKinematics {
  std::vector<Mat3> R;        ///< R_i, i = 0..N (R_0 = R0)
  std::vector<Vec3> p_m;      ///< p_i*, i = 0..N (p_0* = base point)
  std::vector<Vec3> z;        ///< z_i = R_{i−1}·e_z, i = 1..N (index i; z[0] unused)
  std::vector<Vec3> com_m;    ///< c_i, i = 1..N (index i)
  std::vector<Vec3> mid_m;    ///< μ_i = η_i = p_{i−1}* + R_i·l_i/2, i = 1..N
  std::vector<Vec3> w_rad_s;  ///< ω_i, i = 0..N
  std::vector<Vec3> alpha0_rad_s2;  ///< ω̇_i with ω̇0 = 0
  std::vector<Vec3> v_p_m_s;  ///< velocity of p_i*, i = 0..N
  std::vector<Vec3> v_com_m_s, a_com0_m_s2;  ///< CoM velocity, acceleration (v̇0 = ω̇0 = 0)
  std::vector<Vec3> v_mid_m_s, a_mid0_m_s2;  ///< same at μ_i
  Vec3 ee_m{Vec3::Zero()}, payload_m{Vec3::Zero()};
  Vec3 v_payload_m_s{Vec3::Zero()}, a_payload0_m_s2{Vec3::Zero()};
  Vec3 barycenter_m{Vec3::Zero()};
};

/// Fill kin for the vehicle state, joint angles, rates and accelerations (SPEC §2, [3],
/// [8]–[15] in joint-axis form).
void ComputeArmKinematics(const ArmModel &m, const BaseState &b, const double *q_rad,
                          const double *qd_rad_s, const double *qdd_rad_s2, ArmKinematics &kin);

/// A wrench: force [N] and moment [N·m] about a stated point, inertial coordinates.
struct Wrench {
  Vec3 force_N{Vec3::Zero()};
  Vec3 moment_Nm{Vec3::Zero()};
};

/// Every body's required wrench (the wrench the rest of the system must apply to it, beyond
/// gravity, buoyancy and drag, for its motion) as an affine function of the vehicle
/// acceleration x = (v̇0, ω̇0): W_k(x) = W_k0 + A_k·x, about the vehicle CoM r0; kept summed
/// over the bodies distal to each joint (what the joint wrenches [24–25] need).
struct ArmLoads {
  std::vector<Wrench> distal0_r0;  ///< Σ_{k ≥ i} W_k0 over links i..N and the payload
                                   ///< (index i = 1..N; index N+1: the payload alone)
  std::vector<Mat6> distal_inertia_r0;  ///< Σ_{k ≥ i} A_k, same indices
  std::vector<Vec3> drag_N;    ///< D_i (index i); [0] = vehicle drag D0
  std::vector<double> speed_m_s;  ///< |v_μ,i − v∞|, link i's center through the water (index i)
  Mat6 arm_inertia_r0{Mat6::Zero()};  ///< Σ_k A_k for links + payload, about r0
  Wrench arm_wrench0_r0;       ///< Σ_k W_k0 for links + payload, about r0
};

/// Loads of links and payload (SPEC §4: inertia [16–18], added mass §3.3, drag [19–22],
/// buoyancy [23], gravity, payload) for the kinematics kin.
void ComputeArmLoads(const ArmModel &m, const BaseState &b, const FluidState &f,
                     const ArmKinematics &kin, ArmLoads &loads);

/// Joint-level results for a given vehicle acceleration: f1 and n1 (about p_0*), τ_i [29].
struct JointWrenches {
  Vec3 f1_N{Vec3::Zero()};
  Vec3 n1_Nm{Vec3::Zero()};
  std::vector<double> tau_Nm;  ///< index i = 1..N
};
void ComputeJointWrenches(const ArmModel &m, const BaseState &b, const ArmKinematics &kin,
                          const ArmLoads &loads, const Vec6 &base_accel, JointWrenches &out);

/// True if any of the vehicle's Fossen damping coefficients is non-zero.
bool HasDamping(const VehicleParams &V);

/// Fossen's diagonal damping of the vehicle (docs/MODEL.md §3.2): on ν = (R0ᵀ·w, R0ᵀ·ω),
/// τ_k = −(D_L,k + D_Q,k·|ν_k|)·ν_k; returned inertial, force at the CoM, moment about it.
Wrench FossenDamping(const VehicleParams &V, const Mat3 &R0, const Vec3 &w_rel_m_s,
                     const Vec3 &omega_rad_s);

/// The vehicle's own loads: required wrench at zero acceleration (gyroscopic term, added-mass
/// velocity-product term) minus drag (with Fossen's damping: its force is in drag_N), weight,
/// ballast and buoyancy, about r0, and its 6×6 inertia (rigid + added mass) about r0.
void ComputeVehicleLoads(const ArmModel &m, const BaseState &b, const FluidState &f,
                         Wrench &w0_r0, Mat6 &inertia_r0, Vec3 &drag_N);

/// SPEC §5: solve M_sys·(v̇0, ω̇0) = applied − b for the vehicle acceleration, given the
/// external wrench applied to the vehicle about r0 (thrust). Returns (v̇0, ω̇0), inertial.
/// symmetric: M_sys is symmetric positive definite (ArmModel::symmetric), solved by Cholesky;
/// otherwise, or if Cholesky fails, by LU with partial pivoting.
Vec6 SolveBaseAcceleration(const Mat6 &M_sys, const Wrench &bias_r0, const Wrench &applied_r0,
                           bool symmetric = false);

/// The 6×6 matrix that maps (v̇0, ω̇0) to a body's required wrench about r0, for a body with
/// mass m at c and a diagonal rotational inertia I_B in frame R (rigid part).
Mat6 RigidInertiaAt(double mass_kg, const Vec3 &c_minus_r0, const Mat3 &R, const Vec3 &I_B);

/// Same for added mass ρ·V·k·Ma0 acting in frame R about the point μ (SPEC §3.3).
Mat6 AddedMassInertiaAt(const Mat6 &Ma_scaled, const Vec3 &mu_minus_r0, const Mat3 &R);

/// Skew-symmetric matrix [v]× with [v]×·u = v × u.
Mat3 Skew(const Vec3 &v);

}  // namespace uvms::plant
