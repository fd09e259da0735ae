// SPDX-License-Identifier: Apache-2.0
// multibody.cpp: see multibody.hpp. SPEC equation numbers in brackets.
#include "uvms_plant/multibody.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace uvms::plant {

Mat3 Skew(const Vec3 &v) {
  Mat3 S;
  S << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return S;
}

ArmModel ArmModel::FromParams(const PlantParams &p) {
  const int n = static_cast<int>(p.links.size());
  if (n < 1 || n > 7) throw std::invalid_argument("plant: number of links must be 1..7, got " + std::to_string(n));
  ArmModel m;
  m.n = n;
  m.link = p.links;
  m.vehicle = p.vehicle;
  m.payload_kg = p.payload_kg;
  m.payload_offset_m = p.payload_offset_m;
  m.added_mass_coeff = p.added_mass_coeff;
  if (!(p.vehicle.mass_kg > 0.0) || !std::isfinite(p.vehicle.mass_kg))
    throw std::invalid_argument("plant: vehicle.mass_kg must be positive and finite");
  if (!(p.payload_kg >= 0.0)) throw std::invalid_argument("plant: payload_kg must be >= 0");
  if (!p.added_mass_coeff.allFinite()) throw std::invalid_argument("plant: added_mass_coeff not finite");
  if (p.vehicle.added_mass_kg && !p.vehicle.added_mass_kg->allFinite())
    throw std::invalid_argument("plant: vehicle.added_mass_kg not finite");
  for (int k = 0; k < 6; ++k)
    if (!(std::isfinite(p.vehicle.linear_damping[k]) && p.vehicle.linear_damping[k] >= 0.0) ||
        !(std::isfinite(p.vehicle.quadratic_damping[k]) && p.vehicle.quadratic_damping[k] >= 0.0))
      throw std::invalid_argument("plant: vehicle damping coefficients must be finite and >= 0");
  m.total_mass_kg = p.vehicle.mass_kg + p.payload_kg;
  if (!p.vehicle.base_rotvec_rad.allFinite())
    throw std::invalid_argument("plant: vehicle.base_rotvec_rad not finite");
  m.base_rotated = !p.vehicle.base_rotvec_rad.isZero(0.0);
  m.base_rot = RotationOf(p.vehicle.base_rotvec_rad);
  for (int i = 0; i < n; ++i) {
    const LinkParams &L = p.links[static_cast<size_t>(i)];
    if (!(L.mass_kg >= 0.0) || !(L.diameter_m >= 0.0) || !(L.drag_coeff >= 0.0) ||
        !(L.inertia_kg_m2.minCoeff() >= 0.0) || !L.com_m.allFinite() ||
        !L.inertia_products_kg_m2.allFinite() || !std::isfinite(L.alpha_rad + L.a_m + L.d_m) ||
        Eigen::SelfAdjointEigenSolver<Mat3>(InertiaTensor(L)).eigenvalues().minCoeff() <
            -1e-9 * L.inertia_kg_m2.sum())
      throw std::invalid_argument("plant: link " + std::to_string(i + 1) + " has invalid parameters");
    // [1] l_i = (a_i, d_i sin α_i, d_i cos α_i), frame i; Rot(ρ_i)ᵀ·(that + t_i) if placed.
    if (!L.placement_m.allFinite() || !L.placement_rotvec_rad.allFinite())
      throw std::invalid_argument("plant: link " + std::to_string(i + 1) + " has a non-finite placement");
    for (double x : L.added_mass_kg)
      if (!(std::isfinite(x) && x >= 0.0))
        throw std::invalid_argument("plant: link " + std::to_string(i + 1) + " added_mass_kg must be finite and >= 0");
    const Vec3 l = LinkVector(L);
    m.l_m.push_back(l);
    m.cos_alpha.push_back(std::cos(L.alpha_rad));
    m.sin_alpha.push_back(std::sin(L.alpha_rad));
    m.placed.push_back(IsPlaced(L));
    m.place_rot.push_back(RotationOf(L.placement_rotvec_rad));
    const double len = l.norm();  // SPEC §3.1: cylinder of diameter d_L and length |l_i|
    m.volume_m3.push_back(M_PI * L.diameter_m * L.diameter_m / 4.0 * len);
    m.area_m2.push_back(L.diameter_m * len);
    m.total_mass_kg += L.mass_kg;
  }
  return m;
}

void ComputeArmKinematics(const ArmModel &m, const BaseState &b, const double *q,
                          const double *qd, const double *qdd, ArmKinematics &k) {
  const int n = m.n;
  const size_t N1 = static_cast<size_t>(n) + 1;
  if (k.R.size() != N1) {  // sized by the model: allocated on the first call only
    k.R.assign(N1, Mat3::Identity());
    for (std::vector<Vec3> *v : {&k.p_m, &k.z, &k.com_m, &k.mid_m, &k.w_rad_s, &k.alpha0_rad_s2,
                                 &k.v_p_m_s, &k.v_com_m_s, &k.a_com0_m_s2, &k.v_mid_m_s,
                                 &k.a_mid0_m_s2})
      v->assign(N1, Vec3::Zero());
  }
  // Index 0 of the per-link arrays is not a link: keep it zero whatever the caller left there.
  k.z[0] = k.com_m[0] = k.mid_m[0] = k.alpha0_rad_s2[0] = Vec3::Zero();
  k.v_com_m_s[0] = k.a_com0_m_s2[0] = k.v_mid_m_s[0] = k.a_mid0_m_s2[0] = Vec3::Zero();

  // Positions and orientations [3], SPEC §2; R(i−1 → i) = Rz(θ_i)·Rx(α_i) written out, with
  // cos α_i, sin α_i from the model.
  k.R[0] = m.base_rotated ? Mat3(b.R0 * m.base_rot) : b.R0;  // the arm base's axes
  k.p_m[0] = b.r0_m + b.R0 * m.vehicle.base_offset_m;
  for (int i = 1; i <= n; ++i) {
    const size_t i1 = static_cast<size_t>(i - 1);
    const LinkParams &L = m.link[i1];
    const double c = std::cos(q[i - 1]), s = std::sin(q[i - 1]);
    const double ca = m.cos_alpha[i1], sa = m.sin_alpha[i1];
    Mat3 Rdh;
    Rdh << c, -s * ca, s * sa,  //
        s, c * ca, -c * sa,     //
        0.0, sa, ca;
    k.z[i] = k.R[i - 1].col(2);  // [10–11]
    k.R[i] = m.placed[i1] ? Mat3(k.R[i - 1] * Rdh * m.place_rot[i1]) : Mat3(k.R[i - 1] * Rdh);
    const Vec3 Rl = k.R[i] * m.l_m[i1];
    k.p_m[i] = k.p_m[i - 1] + Rl;
    k.com_m[i] = k.p_m[i - 1] + k.R[i] * L.com_m;
    k.mid_m[i] = k.p_m[i - 1] + 0.5 * Rl;  // μ_i = η_i = l_i/2 (SPEC §3.1)
  }
  k.ee_m = k.p_m[n];
  k.payload_m = k.ee_m + k.R[n] * m.payload_offset_m;

  // Velocity of a point x fixed to body i (0 = vehicle) in joint-axis form, and its
  // acceleration with v̇0 = ω̇0 = 0 (the time derivative of the sum term by term):
  //   v = v0 + ω0 × (x − r0) + Σ_{j≤i} θ̇_j·z_j × (x − p_{j−1}*)
  //   a = ω0 × (v − v0) + Σ_{j≤i} [θ̇_j·((ω_{j−1} × z_j) × (x − p_{j−1}) + z_j × (v − v_{p,j−1}))
  //                               + θ̈_j·z_j × (x − p_{j−1})]
  // (ż_j = ω_{j−1} × z_j: z_j is fixed in frame j−1). The same sums with the point-independent
  // parts collected once per joint instead of once per point (O(N) instead of O(N²)): with
  // s_j = θ̇_j·z_j, u_j = θ̇_j·ω_{j−1} × z_j + θ̈_j·z_j, d_j = p_{j−1} − r0 and the running sums
  //   ω_i = ω0 + Σ s_j,  ω̇_i = Σ u_j,  Cs_i = Σ s_j × d_j,  Cu_i = Σ u_j × d_j,
  //   Cv_i = Σ s_j × v_{p,j−1},
  // they read  v = v0 + ω_i × (x − r0) − Cs_i,  a = ω_i × v − ω0 × v0 + ω̇_i × (x − r0) − Cu_i − Cv_i.
  const Vec3 &r0 = b.r0_m, &v0 = b.v0_m_s;
  const Vec3 w0xv0 = b.w0_rad_s.cross(v0);
  k.w_rad_s[0] = b.w0_rad_s;
  k.v_p_m_s[0] = v0 + b.w0_rad_s.cross(k.p_m[0] - r0);
  Vec3 Cs = Vec3::Zero(), Cu = Vec3::Zero(), Cv = Vec3::Zero();
  for (int i = 1; i <= n; ++i) {
    const Vec3 s_j = qd[i - 1] * k.z[i];
    const Vec3 u_j = qd[i - 1] * k.w_rad_s[i - 1].cross(k.z[i]) + qdd[i - 1] * k.z[i];
    k.w_rad_s[i] = k.w_rad_s[i - 1] + s_j;             // [8]
    k.alpha0_rad_s2[i] = k.alpha0_rad_s2[i - 1] + u_j;  // [9] with ω̇0 = 0
    const Vec3 d_j = k.p_m[i - 1] - r0;
    Cs += s_j.cross(d_j);
    Cu += u_j.cross(d_j);
    Cv += s_j.cross(k.v_p_m_s[i - 1]);
    const Vec3 &w = k.w_rad_s[i], &al = k.alpha0_rad_s2[i];
    const Vec3 Cuv = Cu + Cv + w0xv0;
    k.v_p_m_s[i] = v0 + w.cross(k.p_m[i] - r0) - Cs;
    const Vec3 dc = k.com_m[i] - r0, dm = k.mid_m[i] - r0;
    k.v_com_m_s[i] = v0 + w.cross(dc) - Cs;
    k.a_com0_m_s2[i] = w.cross(k.v_com_m_s[i]) + al.cross(dc) - Cuv;
    k.v_mid_m_s[i] = v0 + w.cross(dm) - Cs;
    k.a_mid0_m_s2[i] = w.cross(k.v_mid_m_s[i]) + al.cross(dm) - Cuv;
  }
  {
    const Vec3 dp = k.payload_m - r0;
    k.v_payload_m_s = v0 + k.w_rad_s[n].cross(dp) - Cs;
    k.a_payload0_m_s2 = k.w_rad_s[n].cross(k.v_payload_m_s) + k.alpha0_rad_s2[n].cross(dp) - (Cu + Cv + w0xv0);
  }

  Vec3 msum = m.vehicle.mass_kg * b.r0_m + m.payload_kg * k.payload_m;
  for (int i = 1; i <= n; ++i) msum += m.link[static_cast<size_t>(i - 1)].mass_kg * k.com_m[i];
  k.barycenter_m = msum / m.total_mass_kg;  // [5]
}

namespace {
// The rigid-body inertia of RigidInertiaAt with the inertial rotational inertia I given.
Mat6 RigidInertiaWith(double mass_kg, const Vec3 &d, const Mat3 &I) {
  // Point c = r0 + d: a_c = v̇0 − [d]×·ω̇0; F = m·a_c; moment about r0 = I·ω̇0 + d × F.
  const Mat3 S = Skew(d);
  Mat6 A;
  A.block<3, 3>(0, 0) = mass_kg * Mat3::Identity();
  A.block<3, 3>(0, 3) = -mass_kg * S;
  A.block<3, 3>(3, 0) = mass_kg * S;
  A.block<3, 3>(3, 3) = I - mass_kg * S * S;
  return A;
}
}  // namespace

Mat6 RigidInertiaAt(double mass_kg, const Vec3 &d, const Mat3 &R, const Vec3 &I_B) {
  return RigidInertiaWith(mass_kg, d, R * I_B.asDiagonal() * R.transpose());  // [18]
}

Mat6 AddedMassInertiaAt(const Mat6 &Ma_scaled, const Vec3 &d, const Mat3 &R) {
  // (a_μ; ω̇) = [[I, −[d]×], [0, I]]·(v̇0; ω̇0); body frame through blkdiag(Rᵀ, Rᵀ); wrench
  // back through blkdiag(R, R) about μ, moved to r0 with [[I, 0], [[d]×, I]] (SPEC §3.3).
  // The same product written block-wise (3×3 products only): with Mw = blkdiag(R, R)·Ma·
  // blkdiag(Rᵀ, Rᵀ) = [[A, B], [C, D]] and S = [d]×,
  //   [[I, 0], [S, I]]·Mw·[[I, −S], [0, I]] = [[A, B − A·S], [S·A + C, S·(B − A·S) + D − C·S]].
  const Mat3 S = Skew(d);
  const Mat3 A = R * Ma_scaled.block<3, 3>(0, 0) * R.transpose();
  const Mat3 B = R * Ma_scaled.block<3, 3>(0, 3) * R.transpose();
  const Mat3 C = R * Ma_scaled.block<3, 3>(3, 0) * R.transpose();
  const Mat3 D = R * Ma_scaled.block<3, 3>(3, 3) * R.transpose();
  const Mat3 B1 = B - A * S;
  Mat6 M;
  M.block<3, 3>(0, 0) = A;
  M.block<3, 3>(0, 3) = B1;
  M.block<3, 3>(3, 0) = S * A + C;
  M.block<3, 3>(3, 3) = S * B1 + D - C * S;
  return M;
}

namespace {
double Factor(const std::vector<double> &f, int i) {
  return f.empty() ? 1.0 : f[static_cast<size_t>(i - 1)];
}

// Drag [19–22] at the aerodynamic center of link i, relative velocity w = v_η − v∞.
Vec3 LinkDrag(const ArmModel &m, const FluidState &f, const ArmKinematics &k, int i) {
  const double area = m.area_m2[static_cast<size_t>(i - 1)];
  if (!(area > 0.0) || !(f.density_kg_m3 > 0.0)) return Vec3::Zero();
  const Vec3 w = k.v_mid_m_s[i] - f.flow_m_s;
  const double speed = w.norm();
  if (!(speed > 0.0)) return Vec3::Zero();
  double cd = m.link[static_cast<size_t>(i - 1)].drag_coeff * Factor(f.drag_factor, i);
  if (f.angle_of_attack) {
    const Vec3 axis = (k.p_m[i] - k.p_m[i - 1]).normalized();  // ẑ_L along R_i·l_i
    const double c = axis.dot(w) / speed;                      // [22] cos α
    cd *= 1.0 - c * c;                                          // [21] sin²α
  }
  return -0.5 * f.density_kg_m3 * cd * area * speed * w;  // [19]
}

// blkdiag(R, R)·(scale·Ma0)·blkdiag(Rᵀ, Rᵀ) = [[A, B], [C, D]]: the added mass of SPEC §3.3
// in inertial coordinates, about the body's center of buoyancy.
struct RotatedAddedMass {
  Mat3 A, B, C, D;
};
/// A link's own added mass as a 6×6 matrix (the diagonal LinkParams::added_mass_kg).
Mat6 OwnAddedMass(const LinkParams &L) {
  return Eigen::Map<const Eigen::Matrix<double, 6, 1>>(L.added_mass_kg).asDiagonal();
}

RotatedAddedMass RotateAddedMass(const Mat6 &Ma0, double scale, const Mat3 &R) {
  const Mat3 Rs = scale * R;
  return RotatedAddedMass{Rs * Ma0.block<3, 3>(0, 0) * R.transpose(), Rs * Ma0.block<3, 3>(0, 3) * R.transpose(),
                          Rs * Ma0.block<3, 3>(3, 0) * R.transpose(), Rs * Ma0.block<3, 3>(3, 3) * R.transpose()};
}

// AddedMassInertiaAt for already rotated blocks (see AddedMassInertiaAt for the derivation).
Mat6 AddedMassInertiaWith(const RotatedAddedMass &Mw, const Vec3 &d) {
  const Mat3 S = Skew(d);
  const Mat3 B1 = Mw.B - Mw.A * S;
  Mat6 M;
  M.block<3, 3>(0, 0) = Mw.A;
  M.block<3, 3>(0, 3) = B1;
  M.block<3, 3>(3, 0) = S * Mw.A + Mw.C;
  M.block<3, 3>(3, 3) = S * B1 + Mw.D - Mw.C * S;
  return M;
}

Wrench PayloadRequiredWrench(const ArmModel &m, const FluidState &f, const Vec3 &a) {
  Wrench W;
  W.force_N = m.payload_kg * (a - f.gravity_m_s2);  // point mass, no volume, no drag
  return W;
}

Wrench About(const Wrench &w, const Vec3 &from_point, const Vec3 &to_point) {
  return Wrench{w.force_N, w.moment_Nm + (from_point - to_point).cross(w.force_N)};
}
}  // namespace

void ComputeArmLoads(const ArmModel &m, const BaseState &b, const FluidState &f,
                     const ArmKinematics &k, ArmLoads &loads) {
  const int n = m.n;
  const size_t np = static_cast<size_t>(n) + 1;
  if (loads.body0_r0.size() != np + 1) {  // sized by the model: allocated on the first call only
    loads.body0_r0.assign(np + 1, Wrench{});
    loads.body_inertia_r0.assign(np + 1, Mat6::Zero());
    loads.drag_N.assign(np, Vec3::Zero());
  }
  loads.arm_inertia_r0.setZero();
  loads.arm_wrench0_r0 = Wrench{};
  for (int i = 1; i <= n; ++i) {
    const size_t ii = static_cast<size_t>(i);
    const LinkParams &L = m.link[ii - 1];
    const Mat3 &R = k.R[i];
    const Vec3 &w = k.w_rad_s[i], &alpha = k.alpha0_rad_s2[i];
    const Vec3 drag = LinkDrag(m, f, k, i);
    loads.drag_N[ii] = drag;
    // Required wrench of link i at zero vehicle acceleration (force; moment about its CoM):
    // inertia [16–18], added mass (SPEC §3.3, at μ_i, frame i), minus gravity at the CoM,
    // buoyancy [23] and drag at μ_i. R·I_B·Rᵀ and the rotated added mass serve both this
    // wrench and the link's 6×6 map of the vehicle acceleration below.
    // [18]; a link on principal axes takes the diagonal product (the paper's, bit for bit).
    const Mat3 I = L.inertia_products_kg_m2.isZero(0.0)
                       ? Mat3(R * L.inertia_kg_m2.asDiagonal() * R.transpose())
                       : Mat3(R * InertiaTensor(L) * R.transpose());
    Wrench W;
    W.force_N = L.mass_kg * k.a_com0_m_s2[i];                         // [16]
    W.moment_Nm = I * alpha + w.cross(I * w);                          // [17]
    const double vol = m.volume_m3[ii - 1];
    const Vec3 lever = k.mid_m[i] - k.com_m[i];
    const Vec3 dc = k.com_m[i] - b.r0_m;
    Mat6 A_r0 = RigidInertiaWith(L.mass_kg, dc, I);
    if (vol > 0.0 && f.density_kg_m3 > 0.0) {
      // The link's own diagonal when it has one, else ρ·V_i·Ma0 (docs/MODEL.md §3.3).
      const RotatedAddedMass Mw =
          HasOwnAddedMass(L)
              ? RotateAddedMass(OwnAddedMass(L), Factor(f.added_mass_factor, i), R)
              : RotateAddedMass(m.added_mass_coeff, f.density_kg_m3 * vol * Factor(f.added_mass_factor, i), R);
      const Vec3 &a_mid = k.a_mid0_m_s2[i];
      const Vec3 Fa = Mw.A * a_mid + Mw.B * alpha;
      W.force_N += Fa;
      W.moment_Nm += Mw.C * a_mid + Mw.D * alpha + lever.cross(Fa);
      A_r0 += AddedMassInertiaWith(Mw, k.mid_m[i] - b.r0_m);
    }
    const Vec3 buoy = f.density_kg_m3 * vol * f.gravity_m_s2;  // −(buoyancy force −β·g)
    W.force_N += -L.mass_kg * f.gravity_m_s2 + buoy - drag;
    W.moment_Nm += lever.cross(buoy - drag);
    const Wrench at_r0 = About(W, k.com_m[i], b.r0_m);
    loads.body0_r0[ii] = at_r0;
    loads.body_inertia_r0[ii] = A_r0;
    loads.arm_wrench0_r0.force_N += at_r0.force_N;
    loads.arm_wrench0_r0.moment_Nm += at_r0.moment_Nm;
    loads.arm_inertia_r0 += A_r0;
  }
  const Vec3 dp = k.payload_m - b.r0_m;
  const Wrench pw = About(PayloadRequiredWrench(m, f, k.a_payload0_m_s2), k.payload_m, b.r0_m);
  const Mat6 Ap_r0 = RigidInertiaWith(m.payload_kg, dp, Mat3::Zero());
  loads.body0_r0[np] = pw;
  loads.body_inertia_r0[np] = Ap_r0;
  loads.arm_wrench0_r0.force_N += pw.force_N;
  loads.arm_wrench0_r0.moment_Nm += pw.moment_Nm;
  loads.arm_inertia_r0 += Ap_r0;
}

void ComputeJointWrenches(const ArmModel &m, const BaseState &b, const ArmKinematics &k,
                          const ArmLoads &loads, const Vec6 &x, JointWrenches &out) {
  // Each body's required wrench about r0 at the true vehicle acceleration,
  // W_k = W_k0 + A_k·x; f_i and n_i are the sums over the bodies distal to joint i, SPEC
  // [24–25], [29], accumulated from the payload inwards (no recursion over links: suffix sums
  // about r0, moved to p_{i−1}* by n_i = Σ M_k − (p_{i−1}* − r0) × Σ F_k).
  const int n = m.n;
  const size_t np = static_cast<size_t>(n) + 1;
  if (out.tau_Nm.size() != np) out.tau_Nm.assign(np, 0.0);
  Vec3 f = Vec3::Zero(), m_r0 = Vec3::Zero();
  for (size_t kk = np; kk >= 1; --kk) {
    const Vec6 w = loads.body_inertia_r0[kk] * x;
    f += loads.body0_r0[kk].force_N + w.head<3>();
    m_r0 += loads.body0_r0[kk].moment_Nm + w.tail<3>();
    if (kk == np) continue;  // the payload has no joint of its own
    const int i = static_cast<int>(kk);
    const Vec3 nm = m_r0 - (k.p_m[i - 1] - b.r0_m).cross(f);
    if (i == 1) {
      out.f1_N = f;
      out.n1_Nm = nm;
    }
    out.tau_Nm[kk] = nm.dot(k.z[i]);  // [29]
  }
}

bool HasDamping(const VehicleParams &V) {
  for (int k = 0; k < 6; ++k)
    if (V.linear_damping[k] != 0.0 || V.quadratic_damping[k] != 0.0) return true;
  return false;
}

Wrench FossenDamping(const VehicleParams &V, const Mat3 &R0, const Vec3 &w_rel_m_s,
                     const Vec3 &omega_rad_s) {
  // ν = (R0ᵀ·w0, R0ᵀ·ω0); τ_k = −(D_L,k + D_Q,k·|ν_k|)·ν_k in the vehicle frame.
  Vec6 nu;
  nu << R0.transpose() * w_rel_m_s, R0.transpose() * omega_rad_s;
  Vec6 tau;
  for (int k = 0; k < 6; ++k)
    tau[k] = -(V.linear_damping[k] + V.quadratic_damping[k] * std::abs(nu[k])) * nu[k];
  return Wrench{R0 * tau.head<3>(), R0 * tau.tail<3>()};
}

void ComputeVehicleLoads(const ArmModel &m, const BaseState &b, const FluidState &f,
                         Wrench &w0, Mat6 &inertia, Vec3 &drag) {
  const VehicleParams &V = m.vehicle;
  const Mat3 I = b.R0 * V.inertia_kg_m2.asDiagonal() * b.R0.transpose();
  const Vec3 d = b.R0 * V.cob_m;  // CoM → center of buoyancy, inertial
  // Drag D0 = −½ρ·C_D0·A0·|w0|·w0, w0 = v0 − v∞, at the CoM (SPEC [31]).
  const Vec3 wrel = b.v0_m_s - f.flow_m_s;
  drag = -0.5 * f.density_kg_m3 * V.drag_coeff * V.frontal_area_m2 * wrel.norm() * wrel;
  const double beta0 = f.density_kg_m3 * V.volume_m3;
  w0 = Wrench{};
  w0.moment_Nm = b.w0_rad_s.cross(I * b.w0_rad_s);
  if (HasDamping(V)) {  // Fossen's damping (docs/MODEL.md §3.2): a force in D0, a moment
    const Wrench d = FossenDamping(V, b.R0, wrel, b.w0_rad_s);
    drag += d.force_N;
    w0.moment_Nm -= d.moment_Nm;
  }
  // Added mass at the CoB, velocity-product part: a_cb = ω0 × (ω0 × d) when v̇0 = ω̇0 = 0.
  // The vehicle's own added mass when given (docs/MODEL.md §3.3), else ρ·V0·Ma0.
  const Mat6 Ma = V.added_mass_kg ? *V.added_mass_kg : f.density_kg_m3 * V.volume_m3 * m.added_mass_coeff;
  const bool has_added_mass = V.added_mass_kg || (V.volume_m3 > 0.0 && f.density_kg_m3 > 0.0);
  if (has_added_mass) {
    Vec6 acc_b;
    acc_b << b.R0.transpose() * b.w0_rad_s.cross(b.w0_rad_s.cross(d)), Vec3::Zero();
    const Vec6 fm = Ma * acc_b;
    const Vec3 Fa = b.R0 * fm.head<3>();
    w0.force_N += Fa;
    w0.moment_Nm += b.R0 * fm.tail<3>() + d.cross(Fa);
  }
  // Minus the external loads: weight m0·g at the CoM, buoyancy −β0·g at the CoB, the ballast
  // weight m_b·g at its own point (SPEC §5, §6.3), drag at the CoM.
  const Vec3 buoyancy_neg = beta0 * f.gravity_m_s2;
  const Vec3 ballast_weight = f.ballast_kg * f.gravity_m_s2;
  const Vec3 d_ballast = b.R0 * f.ballast_offset_m;  // CoM → ballast point, inertial
  w0.force_N += -V.mass_kg * f.gravity_m_s2 + buoyancy_neg - ballast_weight - drag;
  w0.moment_Nm += d.cross(buoyancy_neg) - d_ballast.cross(ballast_weight);
  inertia = RigidInertiaAt(V.mass_kg, Vec3::Zero(), b.R0, V.inertia_kg_m2);  // about the CoM = r0
  if (has_added_mass) inertia += AddedMassInertiaAt(Ma, d, b.R0);
}

Vec6 SolveBaseAcceleration(const Mat6 &M_sys, const Wrench &bias, const Wrench &applied) {
  Vec6 rhs;
  rhs << applied.force_N - bias.force_N, applied.moment_Nm - bias.moment_Nm;
  return M_sys.partialPivLu().solve(rhs);
}

}  // namespace uvms::plant
