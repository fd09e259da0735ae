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

namespace {
// S += the rigid-body inertia of a body of mass m with rotational inertia I (about its CoM)
// whose CoM is at c = P + d from the reference point P, in the axes of d and I:
// a_c = a_P − [d]×·ω̇; F = m·a_c; moment about P = I·ω̇ + d × F, i.e.
// [[m·1, −m·[d]×], [m·[d]×, I − m·[d]×²]] (SPEC [16–18]).
void AddRigidInertia(Mat6 &S, double mass_kg, const Vec3 &d, const Mat3 &I) {
  const Vec3 h = mass_kg * d;  // first moment about the reference point
  const double hd = h.dot(d);
  for (int k = 0; k < 3; ++k) S(k, k) += mass_kg;
  // −[h]× above the diagonal blocks, +[h]× = (−[h]×)ᵀ below:
  // [h]× = [[0, −h_z, h_y], [h_z, 0, −h_x], [−h_y, h_x, 0]].
  S(0, 4) += h.z(), S(0, 5) -= h.y(), S(1, 3) -= h.z(), S(1, 5) += h.x(), S(2, 3) += h.y(), S(2, 4) -= h.x();
  S(4, 0) += h.z(), S(5, 0) -= h.y(), S(3, 1) -= h.z(), S(5, 1) += h.x(), S(3, 2) += h.y(), S(4, 2) -= h.x();
  for (int c = 0; c < 3; ++c)  // I − m·[d]×² = I + m·(|d|²·1 − d·dᵀ)
    for (int r = 0; r < 3; ++r) S(3 + r, 3 + c) += I(r, c) + (r == c ? hd : 0.0) - h(r) * d(c);
}

Mat6 RigidInertiaWith(double mass_kg, const Vec3 &d, const Mat3 &I) {
  Mat6 A = Mat6::Zero();
  AddRigidInertia(A, mass_kg, d, I);
  return A;
}

// A body's 6×6 inertia M = [[A, B], [C, D]] (force and moment about a point P from the
// acceleration of P and ω̇) given in body axes, expressed in inertial axes:
// blkdiag(R, R)·M·blkdiag(Rᵀ, Rᵀ), block by block. A symmetric M (C = Bᵀ) skips C's product.
Mat6 RotateBlocks(const Mat6 &M, const Mat3 &R, bool symmetric) {
  Mat6 out;
  out.block<3, 3>(0, 0) = R * M.block<3, 3>(0, 0) * R.transpose();
  out.block<3, 3>(0, 3) = R * M.block<3, 3>(0, 3) * R.transpose();
  out.block<3, 3>(3, 3) = R * M.block<3, 3>(3, 3) * R.transpose();
  if (symmetric) {
    out.block<3, 3>(3, 0) = out.block<3, 3>(0, 3).transpose();
  } else {
    out.block<3, 3>(3, 0) = R * M.block<3, 3>(3, 0) * R.transpose();
  }
  return out;
}

// [d]×·X (column j: d × X_j) and X·[d]× (row i: X_i × d, since x·[d]× = (x × d)ᵀ for a row x).
Mat3 SkewTimes(const Vec3 &d, const Mat3 &X) {
  Mat3 out;
  for (int c = 0; c < 3; ++c) out.col(c) = d.cross(X.col(c));
  return out;
}
Mat3 TimesSkew(const Mat3 &X, const Vec3 &d) {
  Mat3 out;
  for (int r = 0; r < 3; ++r) out.row(r) = Vec3(X.row(r).transpose()).cross(d).transpose();
  return out;
}

// The same inertia about the point Q with d = P − Q:
// (a_P; ω̇) = [[I, −[d]×], [0, I]]·(a_Q; ω̇) and the moment about Q = moment about P + d × F
// (SPEC §3.3), block-wise with S = [d]×:
//   [[I, 0], [S, I]]·M·[[I, −S], [0, I]] = [[A, B − A·S], [S·A + C, S·(B − A·S) + D − C·S]].
// For a symmetric M the lower-left block is (B − A·S)ᵀ. Products with S as cross products.
// (Added to S in place.)
void AddShifted(Mat6 &S, const Mat3 &A, const Mat3 &B, const Mat3 &C, const Mat3 &D,
                const Vec3 &d, bool symmetric) {
  const Mat3 B1 = B - TimesSkew(A, d);
  S.block<3, 3>(0, 0) += A;
  S.block<3, 3>(0, 3) += B1;
  if (symmetric) {
    S.block<3, 3>(3, 0) += B1.transpose();
  } else {
    S.block<3, 3>(3, 0) += SkewTimes(d, A) + C;
  }
  S.block<3, 3>(3, 3) += SkewTimes(d, B1) + D - TimesSkew(C, d);
}
Mat6 ShiftTo(const Mat6 &M, const Vec3 &d, bool symmetric) {
  Mat6 out = Mat6::Zero();
  AddShifted(out, M.block<3, 3>(0, 0), M.block<3, 3>(0, 3), M.block<3, 3>(3, 0), M.block<3, 3>(3, 3),
             d, symmetric);
  return out;
}

bool IsSymmetric(const Mat6 &M) { return (M.array() == M.transpose().array()).all(); }

// Body-frame constants of ComputeArmLoads and ComputeVehicleLoads.
void PrecomputeInertias(ArmModel &m) {
  m.symmetric = IsSymmetric(m.added_mass_coeff) &&
                (!m.vehicle.added_mass_kg || IsSymmetric(*m.vehicle.added_mass_kg));
  for (int i = 0; i < m.n; ++i) {
    const LinkParams &L = m.link[static_cast<size_t>(i)];
    const bool own = HasOwnAddedMass(L);
    m.inertia_com.push_back(InertiaTensor(L));
    m.inertia_diagonal.push_back(L.inertia_products_kg_m2.isZero(0.0) ? 1 : 0);
    m.own_added.push_back(own ? 1 : 0);
    m.added_unit.push_back(ArmModel::AddedMassBlocks::Of(
        own ? Mat6(Eigen::Map<const Vec6>(L.added_mass_kg).asDiagonal()) : m.added_mass_coeff));
  }
  const VehicleParams &V = m.vehicle;
  m.vehicle_rigid = RigidInertiaWith(V.mass_kg, Vec3::Zero(), Mat3(V.inertia_kg_m2.asDiagonal()));
  const Mat6 Ma = V.added_mass_kg ? *V.added_mass_kg : m.added_mass_coeff;
  m.vehicle_added_cob_unit = Ma;
  m.vehicle_added_unit = ShiftTo(Ma, V.cob_m, IsSymmetric(Ma));  // from the CoB to the CoM
  m.vehicle_damped = HasDamping(V);
}
}  // namespace

ArmModel::RotatableBlock ArmModel::RotatableBlock::Of(const Mat3 &X) {
  RotatableBlock b;
  b.X = X;
  if (X(0, 0) == X(1, 1) && X(1, 1) == X(2, 2)) b.scalar = X(0, 0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const double v = r == c ? X(r, c) - b.scalar : X(r, c);
      if (v == 0.0) continue;
      if (b.terms == kMaxTerms) {
        b.terms = -1;
        return b;
      }
      b.j[b.terms] = r;
      b.k[b.terms] = c;
      b.value[b.terms] = v;
      ++b.terms;
    }
  return b;
}

Mat3 ArmModel::RotatableBlock::Rotated(const Mat3 &R) const {
  if (terms < 0) return R * X * R.transpose();
  Mat3 out = scalar * Mat3::Identity();
  for (int t = 0; t < terms; ++t) out.noalias() += value[t] * R.col(j[t]) * R.col(k[t]).transpose();
  return out;
}

ArmModel::AddedMassBlocks ArmModel::AddedMassBlocks::Of(const Mat6 &M) {
  AddedMassBlocks b;
  b.symmetric = IsSymmetric(M);
  b.A = RotatableBlock::Of(M.block<3, 3>(0, 0));
  b.B = RotatableBlock::Of(M.block<3, 3>(0, 3));
  b.C = RotatableBlock::Of(M.block<3, 3>(3, 0));
  b.D = RotatableBlock::Of(M.block<3, 3>(3, 3));
  return b;
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
    m.l_unit.push_back(len > 0.0 ? Vec3(l / len) : Vec3::Zero());
    m.area_m2.push_back(L.diameter_m * len);
    m.total_mass_kg += L.mass_kg;
  }
  PrecomputeInertias(m);
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
    // R_{i−1}·Rz(θ)·Rx(α) by columns: with u = −s·r0 + c·r1 (r_k the columns of R_{i−1}),
    // (c·r0 + s·r1, ca·u + sa·r2, ca·r2 − sa·u).
    const Mat3 &Rp = k.R[i - 1];
    const Vec3 u = c * Rp.col(1) - s * Rp.col(0);
    Mat3 Ri;
    Ri.col(0) = c * Rp.col(0) + s * Rp.col(1);
    Ri.col(1) = ca * u + sa * Rp.col(2);
    Ri.col(2) = ca * Rp.col(2) - sa * u;
    k.z[i] = Rp.col(2);  // [10–11]
    k.R[i] = m.placed[i1] ? Mat3(Ri * m.place_rot[i1]) : Ri;
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


Mat6 RigidInertiaAt(double mass_kg, const Vec3 &d, const Mat3 &R, const Vec3 &I_B) {
  return RigidInertiaWith(mass_kg, d, R * I_B.asDiagonal() * R.transpose());  // [18]
}

Mat6 AddedMassInertiaAt(const Mat6 &Ma_scaled, const Vec3 &d, const Mat3 &R) {
  // Body axes → inertial, then from μ to r0 (SPEC §3.3).
  return ShiftTo(RotateBlocks(Ma_scaled, R, false), d, false);
}

namespace {
double Factor(const std::vector<double> &f, int i) {
  return f.empty() ? 1.0 : f[static_cast<size_t>(i - 1)];
}

// Drag [19–22] at the aerodynamic center of link i, relative velocity w = v_η − v∞ of
// magnitude speed.
Vec3 LinkDrag(const ArmModel &m, const FluidState &f, const ArmKinematics &k, int i, const Vec3 &w,
              double speed) {
  const double area = m.area_m2[static_cast<size_t>(i - 1)];
  if (!(area > 0.0) || !(f.density_kg_m3 > 0.0)) return Vec3::Zero();
  if (!(speed > 0.0)) return Vec3::Zero();
  double cd = m.link[static_cast<size_t>(i - 1)].drag_coeff * Factor(f.drag_factor, i);
  if (f.angle_of_attack) {
    const double along = (k.R[i] * m.l_unit[static_cast<size_t>(i - 1)]).dot(w);  // ẑ_L along R_i·l_i
    cd *= 1.0 - along * along / (speed * speed);  // [21] sin²α, [22] cos α = ẑ_L·w/|w|
  }
  return -0.5 * f.density_kg_m3 * cd * area * speed * w;  // [19]
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
  if (loads.distal0_r0.size() != np + 1) {  // sized by the model: allocated on the first call only
    loads.distal0_r0.assign(np + 1, Wrench{});
    loads.distal_inertia_r0.assign(np + 1, Mat6::Zero());
    loads.drag_N.assign(np, Vec3::Zero());
    loads.speed_m_s.assign(np, 0.0);
  }
  // Sums over the bodies distal to each joint, from the payload inwards.
  Mat6 S = Mat6::Zero();
  if (m.payload_kg != 0.0) AddRigidInertia(S, m.payload_kg, k.payload_m - b.r0_m, Mat3::Zero());
  Wrench W = About(PayloadRequiredWrench(m, f, k.a_payload0_m_s2), k.payload_m, b.r0_m);
  loads.distal0_r0[np] = W;
  loads.distal_inertia_r0[np] = S;
  for (int i = n; i >= 1; --i) {
    const size_t ii = static_cast<size_t>(i);
    const LinkParams &L = m.link[ii - 1];
    const Mat3 &R = k.R[i];
    const Vec3 &w = k.w_rad_s[i], &alpha = k.alpha0_rad_s2[i];
    const Vec3 w_rel = k.v_mid_m_s[i] - f.flow_m_s;
    const double speed = w_rel.norm();
    loads.speed_m_s[ii] = speed;
    const Vec3 drag = LinkDrag(m, f, k, i, w_rel, speed);
    loads.drag_N[ii] = drag;
    const Vec3 dc = k.com_m[i] - b.r0_m, dm = k.mid_m[i] - b.r0_m;
    // Link i's required wrench about r0 at zero vehicle acceleration, and its 6×6 map of the
    // vehicle acceleration, added to the sums. Rigid body: inertia [16–18] at the CoM;
    // R·I_B·Rᵀ (a link on principal axes takes the diagonal product, the paper's bit for bit).
    const Mat3 I = m.inertia_diagonal[ii - 1] != 0 ? Mat3(R * L.inertia_kg_m2.asDiagonal() * R.transpose())
                                                   : Mat3(R * m.inertia_com[ii - 1] * R.transpose());
    const Vec3 F = L.mass_kg * k.a_com0_m_s2[i];                         // [16]
    W.force_N += F;
    W.moment_Nm += I * alpha + w.cross(I * w) + dc.cross(F);             // [17], about r0
    AddRigidInertia(S, L.mass_kg, dc, I);
    // Added mass (SPEC §3.3) at μ_i in frame i: the link's own diagonal, else ρ·V_i·Ma0
    // (docs/MODEL.md §3.3); rotated to inertial axes block by block, then moved to r0.
    const double vol = m.volume_m3[ii - 1];
    if (vol > 0.0 && f.density_kg_m3 > 0.0) {
      const ArmModel::AddedMassBlocks &Ma = m.added_unit[ii - 1];
      const double scale = (m.own_added[ii - 1] != 0 ? 1.0 : f.density_kg_m3 * vol) * Factor(f.added_mass_factor, i);
      const Mat3 A = scale * Ma.A.Rotated(R), B = scale * Ma.B.Rotated(R), D = scale * Ma.D.Rotated(R);
      const Mat3 C = Ma.symmetric ? Mat3(B.transpose()) : Mat3(scale * Ma.C.Rotated(R));
      const Vec3 &a_mid = k.a_mid0_m_s2[i];
      const Vec3 Fa = A * a_mid + B * alpha;
      W.force_N += Fa;
      W.moment_Nm += C * a_mid + D * alpha + dm.cross(Fa);
      AddShifted(S, A, B, C, D, dm, Ma.symmetric);
    }
    // Minus gravity at the CoM, buoyancy [23] and drag at μ_i.
    const Vec3 weight = L.mass_kg * f.gravity_m_s2;
    const Vec3 buoy_drag = f.density_kg_m3 * vol * f.gravity_m_s2 - drag;  // −(buoyancy −β·g) − D
    W.force_N += buoy_drag - weight;
    W.moment_Nm += dm.cross(buoy_drag) - dc.cross(weight);
    loads.distal0_r0[ii] = W;
    loads.distal_inertia_r0[ii] = S;
  }
  loads.arm_inertia_r0 = S;
  loads.arm_wrench0_r0 = W;
}

void ComputeJointWrenches(const ArmModel &m, const BaseState &b, const ArmKinematics &k,
                          const ArmLoads &loads, const Vec6 &x, JointWrenches &out) {
  // f_i and n_i, SPEC [24–25], [29]: the required wrenches of the bodies distal to joint i at
  // the true vehicle acceleration, Σ_{k ≥ i} (W_k0 + A_k·x) (ArmLoads keeps the sums, about r0),
  // moved to p_{i−1}* by n_i = Σ M_k − (p_{i−1}* − r0) × Σ F_k.
  const int n = m.n;
  const size_t np = static_cast<size_t>(n) + 1;
  if (out.tau_Nm.size() != np) out.tau_Nm.assign(np, 0.0);
  for (int i = 1; i <= n; ++i) {
    const size_t ii = static_cast<size_t>(i);
    const Vec6 w = loads.distal_inertia_r0[ii] * x;
    const Vec3 f = loads.distal0_r0[ii].force_N + w.head<3>();
    const Vec3 nm = loads.distal0_r0[ii].moment_Nm + w.tail<3>() - (k.p_m[i - 1] - b.r0_m).cross(f);
    if (i == 1) {
      out.f1_N = f;
      out.n1_Nm = nm;
    }
    out.tau_Nm[ii] = nm.dot(k.z[i]);  // [29]
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
  const Vec3 d = b.R0 * V.cob_m;  // CoM → center of buoyancy, inertial
  // Drag D0 = −½ρ·C_D0·A0·|w0|·w0, w0 = v0 − v∞, at the CoM (SPEC [31]).
  const Vec3 wrel = b.v0_m_s - f.flow_m_s;
  drag = -0.5 * f.density_kg_m3 * V.drag_coeff * V.frontal_area_m2 * wrel.norm() * wrel;
  const double beta0 = f.density_kg_m3 * V.volume_m3;
  w0 = Wrench{};
  // In vehicle axes: the gyroscopic moment ω0 × I·ω0 and, with added mass at the CoB, its
  // velocity-product part (acceleration of the CoB ω0 × (ω0 × d) when v̇0 = ω̇0 = 0); the
  // vehicle's own added mass when given (docs/MODEL.md §3.3), else ρ·V0·Ma0.
  const Vec3 w_body = b.R0.transpose() * b.w0_rad_s;
  Vec3 force_body = Vec3::Zero();
  Vec3 moment_body = w_body.cross(V.inertia_kg_m2.cwiseProduct(w_body));
  const bool has_added_mass = V.added_mass_kg || (V.volume_m3 > 0.0 && f.density_kg_m3 > 0.0);
  const double added_scale = V.added_mass_kg ? 1.0 : f.density_kg_m3 * V.volume_m3;
  if (has_added_mass) {
    const Vec3 a_cob = w_body.cross(w_body.cross(V.cob_m));
    const Vec6 fm = added_scale * (m.vehicle_added_cob_unit.leftCols<3>() * a_cob);
    force_body = fm.head<3>();
    moment_body += fm.tail<3>() + V.cob_m.cross(force_body);
  }
  w0.force_N = b.R0 * force_body;
  w0.moment_Nm = b.R0 * moment_body;
  if (m.vehicle_damped) {  // Fossen's damping (docs/MODEL.md §3.2): a force in D0, a moment
    const Wrench fd = FossenDamping(V, b.R0, wrel, b.w0_rad_s);
    drag += fd.force_N;
    w0.moment_Nm -= fd.moment_Nm;
  }
  // Minus the external loads: weight m0·g at the CoM, buoyancy −β0·g at the CoB, the ballast
  // weight m_b·g at its own point (SPEC §5, §6.3), drag at the CoM.
  const Vec3 buoyancy_neg = beta0 * f.gravity_m_s2;
  const Vec3 ballast_weight = f.ballast_kg * f.gravity_m_s2;
  const Vec3 d_ballast = b.R0 * f.ballast_offset_m;  // CoM → ballast point, inertial
  w0.force_N += -V.mass_kg * f.gravity_m_s2 + buoyancy_neg - ballast_weight - drag;
  w0.moment_Nm += d.cross(buoyancy_neg) - d_ballast.cross(ballast_weight);
  // Rigid plus added mass about the CoM = r0 in vehicle axes (ArmModel), then inertial.
  Mat6 M_body = m.vehicle_rigid;
  if (has_added_mass) M_body += added_scale * m.vehicle_added_unit;
  inertia = RotateBlocks(M_body, b.R0, m.symmetric);
}

namespace {
// x = M⁻¹·b for a symmetric positive definite 6×6 M (lower triangle read) by Cholesky, M = L·Lᵀ;
// false (x untouched) if a pivot is not positive and finite. Written out for the fixed size:
// about a third of Eigen's LLT's instructions for 6×6.
bool CholeskySolve6(const Mat6 &M, const Vec6 &b, Vec6 &x) {
  double L[6][6] = {}, inv_diag[6];
  for (int j = 0; j < 6; ++j) {
    double d = M(j, j);
    for (int k = 0; k < j; ++k) d -= L[j][k] * L[j][k];
    if (!(d > 0.0) || !std::isfinite(d)) return false;
    L[j][j] = std::sqrt(d);
    inv_diag[j] = 1.0 / L[j][j];
    for (int i = j + 1; i < 6; ++i) {
      double v = M(i, j);
      for (int k = 0; k < j; ++k) v -= L[i][k] * L[j][k];
      L[i][j] = v * inv_diag[j];
    }
  }
  double y[6];
  for (int i = 0; i < 6; ++i) {  // L·y = b
    double v = b[i];
    for (int k = 0; k < i; ++k) v -= L[i][k] * y[k];
    y[i] = v * inv_diag[i];
  }
  for (int i = 5; i >= 0; --i) {  // Lᵀ·x = y
    double v = y[i];
    for (int k = i + 1; k < 6; ++k) v -= L[k][i] * x[k];
    x[i] = v * inv_diag[i];
  }
  return true;
}
}  // namespace

Vec6 SolveBaseAcceleration(const Mat6 &M_sys, const Wrench &bias, const Wrench &applied,
                           bool symmetric) {
  Vec6 rhs;
  rhs << applied.force_N - bias.force_N, applied.moment_Nm - bias.moment_Nm;
  Vec6 x;
  if (symmetric && CholeskySolve6(M_sys, rhs, x)) return x;  // rigid + added mass: SPD
  return M_sys.partialPivLu().solve(rhs);
}

}  // namespace uvms::plant
