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
  m.total_mass_kg = p.vehicle.mass_kg + p.payload_kg;
  for (int i = 0; i < n; ++i) {
    const LinkParams &L = p.links[static_cast<size_t>(i)];
    if (!(L.mass_kg >= 0.0) || !(L.diameter_m >= 0.0) || !(L.drag_coeff >= 0.0) ||
        !(L.inertia_kg_m2.minCoeff() >= 0.0) || !L.com_m.allFinite() ||
        !std::isfinite(L.alpha_rad + L.a_m + L.d_m))
      throw std::invalid_argument("plant: link " + std::to_string(i + 1) + " has invalid parameters");
    // [1] l_i = (a_i, d_i sin α_i, d_i cos α_i), frame i
    const Vec3 l(L.a_m, L.d_m * std::sin(L.alpha_rad), L.d_m * std::cos(L.alpha_rad));
    m.l_m.push_back(l);
    const double len = l.norm();  // SPEC §3.1: cylinder of diameter d_L and length |l_i|
    m.volume_m3.push_back(M_PI * L.diameter_m * L.diameter_m / 4.0 * len);
    m.area_m2.push_back(L.diameter_m * len);
    m.total_mass_kg += L.mass_kg;
  }
  return m;
}

namespace {
// R(i−1 → i) = Rz(θ)·Rx(α), the rotation part of the standard DH transform (SPEC §2).
Mat3 DhRotation(double theta, double alpha) {
  return (Eigen::AngleAxisd(theta, Vec3::UnitZ()) * Eigen::AngleAxisd(alpha, Vec3::UnitX()))
      .toRotationMatrix();
}
}  // namespace

void ComputeArmKinematics(const ArmModel &m, const BaseState &b, const double *q,
                          const double *qd, const double *qdd, ArmKinematics &k) {
  const int n = m.n;
  const size_t N1 = static_cast<size_t>(n) + 1;
  k.R.assign(N1, Mat3::Identity());
  k.p_m.assign(N1, Vec3::Zero());
  k.z.assign(N1, Vec3::Zero());
  k.com_m.assign(N1, Vec3::Zero());
  k.mid_m.assign(N1, Vec3::Zero());
  k.w_rad_s.assign(N1, Vec3::Zero());
  k.alpha0_rad_s2.assign(N1, Vec3::Zero());
  k.v_p_m_s.assign(N1, Vec3::Zero());
  k.v_com_m_s.assign(N1, Vec3::Zero());
  k.a_com0_m_s2.assign(N1, Vec3::Zero());
  k.v_mid_m_s.assign(N1, Vec3::Zero());
  k.a_mid0_m_s2.assign(N1, Vec3::Zero());

  // Positions and orientations [3], SPEC §2.
  k.R[0] = b.R0;
  k.p_m[0] = b.r0_m + b.R0 * m.vehicle.base_offset_m;
  for (int i = 1; i <= n; ++i) {
    const LinkParams &L = m.link[static_cast<size_t>(i - 1)];
    k.z[i] = k.R[i - 1].col(2);  // [10–11]
    k.R[i] = k.R[i - 1] * DhRotation(q[i - 1], L.alpha_rad);
    const Vec3 Rl = k.R[i] * m.l_m[static_cast<size_t>(i - 1)];
    k.p_m[i] = k.p_m[i - 1] + Rl;
    k.com_m[i] = k.p_m[i - 1] + k.R[i] * L.com_m;
    k.mid_m[i] = k.p_m[i - 1] + 0.5 * Rl;  // μ_i = η_i = l_i/2 (SPEC §3.1)
  }
  k.ee_m = k.p_m[n];
  k.payload_m = k.ee_m + k.R[n] * m.payload_offset_m;

  // Angular velocities ω_k = ω0 + Σ_{j≤k} z_j·θ̇_j and accelerations (ω̇0 = 0)
  // ω̇_k = Σ_{j≤k} (θ̇_j·ω_{j−1} × z_j + θ̈_j·z_j)   (ż_j = ω_{j−1} × z_j: z_j is fixed in j−1).
  k.w_rad_s[0] = b.w0_rad_s;
  for (int j = 1; j <= n; ++j) {
    k.w_rad_s[j] = k.w_rad_s[j - 1] + k.z[j] * qd[j - 1];
    k.alpha0_rad_s2[j] = k.alpha0_rad_s2[j - 1] + qd[j - 1] * k.w_rad_s[j - 1].cross(k.z[j]) +
                         qdd[j - 1] * k.z[j];
  }

  // Velocity of a point x fixed to body `body` (0 = vehicle) in joint-axis form:
  //   v = v0 + ω0 × (x − r0) + Σ_{j≤body} θ̇_j·z_j × (x − p_{j−1}*)
  auto vel = [&](const Vec3 &x, int body) {
    Vec3 v = b.v0_m_s + b.w0_rad_s.cross(x - b.r0_m);
    for (int j = 1; j <= body; ++j) v += qd[j - 1] * k.z[j].cross(x - k.p_m[j - 1]);
    return v;
  };
  // Its acceleration with v̇0 = ω̇0 = 0, the time derivative of the sum above term by term:
  //   a = ω0 × (v − v0) + Σ_j [θ̇_j·((ω_{j−1} × z_j) × (x − p_{j−1}) + z_j × (v − v_{p,j−1}))
  //                            + θ̈_j·z_j × (x − p_{j−1})]
  auto acc0 = [&](const Vec3 &x, const Vec3 &v, int body) {
    Vec3 a = b.w0_rad_s.cross(v - b.v0_m_s);
    for (int j = 1; j <= body; ++j) {
      const Vec3 d = x - k.p_m[j - 1];
      a += qd[j - 1] * (k.w_rad_s[j - 1].cross(k.z[j]).cross(d) + k.z[j].cross(v - k.v_p_m_s[j - 1])) +
           qdd[j - 1] * k.z[j].cross(d);
    }
    return a;
  };
  k.v_p_m_s[0] = vel(k.p_m[0], 0);
  for (int i = 1; i <= n; ++i) {
    k.v_p_m_s[i] = vel(k.p_m[i], i);
    k.v_com_m_s[i] = vel(k.com_m[i], i);
    k.a_com0_m_s2[i] = acc0(k.com_m[i], k.v_com_m_s[i], i);
    k.v_mid_m_s[i] = vel(k.mid_m[i], i);
    k.a_mid0_m_s2[i] = acc0(k.mid_m[i], k.v_mid_m_s[i], i);
  }
  k.v_payload_m_s = vel(k.payload_m, n);
  k.a_payload0_m_s2 = acc0(k.payload_m, k.v_payload_m_s, n);

  Vec3 msum = m.vehicle.mass_kg * b.r0_m + m.payload_kg * k.payload_m;
  for (int i = 1; i <= n; ++i) msum += m.link[static_cast<size_t>(i - 1)].mass_kg * k.com_m[i];
  k.barycenter_m = msum / m.total_mass_kg;  // [5]
}

namespace {
// S1(d): (v̇0, ω̇0) → (acceleration of the point r0 + d, ω̇) for rigid attachment.
Mat6 PointAccel(const Vec3 &d) {
  Mat6 S = Mat6::Identity();
  S.block<3, 3>(0, 3) = -Skew(d);
  return S;
}
// S2(d): a wrench about point P + d re-expressed about P (moment += d × F).
Mat6 MoveWrench(const Vec3 &d) {
  Mat6 S = Mat6::Identity();
  S.block<3, 3>(3, 0) = Skew(d);
  return S;
}
Mat6 BlockRot(const Mat3 &R) {
  Mat6 B = Mat6::Zero();
  B.block<3, 3>(0, 0) = R;
  B.block<3, 3>(3, 3) = R;
  return B;
}
}  // namespace

Mat6 RigidInertiaAt(double mass_kg, const Vec3 &d, const Mat3 &R, const Vec3 &I_B) {
  // Point c = r0 + d: a_c = v̇0 − [d]×·ω̇0; F = m·a_c; moment about r0 = I·ω̇0 + d × F.
  const Mat3 S = Skew(d);
  const Mat3 I = R * I_B.asDiagonal() * R.transpose();  // [18]
  Mat6 A;
  A.block<3, 3>(0, 0) = mass_kg * Mat3::Identity();
  A.block<3, 3>(0, 3) = -mass_kg * S;
  A.block<3, 3>(3, 0) = mass_kg * S;
  A.block<3, 3>(3, 3) = I - mass_kg * S * S;
  return A;
}

Mat6 AddedMassInertiaAt(const Mat6 &Ma_scaled, const Vec3 &d, const Mat3 &R) {
  // (a_μ; ω̇) = [[I, −[d]×], [0, I]]·(v̇0; ω̇0); body frame through blkdiag(Rᵀ, Rᵀ); wrench
  // back through blkdiag(R, R) about μ, moved to r0 with [[I, 0], [[d]×, I]] (SPEC §3.3).
  const Mat6 B = BlockRot(R);
  return MoveWrench(d) * B * Ma_scaled * B.transpose() * PointAccel(d);
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

// Required wrench of link i (force; moment about its CoM) for the given accelerations of its
// CoM, its buoyancy center μ_i and its angular acceleration: inertia [16–18], added mass
// (SPEC §3.3, at μ_i in frame i), minus gravity at the CoM, buoyancy [23] and drag at μ_i.
Wrench LinkRequiredWrench(const ArmModel &m, const FluidState &f, const ArmKinematics &k,
                          int i, const Vec3 &a_com, const Vec3 &a_mid, const Vec3 &alpha,
                          const Vec3 &drag) {
  const LinkParams &L = m.link[static_cast<size_t>(i - 1)];
  const Mat3 &R = k.R[i];
  const Vec3 &w = k.w_rad_s[i];
  const Mat3 I = R * L.inertia_kg_m2.asDiagonal() * R.transpose();
  Wrench W;
  W.force_N = L.mass_kg * a_com;
  W.moment_Nm = I * alpha + w.cross(I * w);
  const double vol = m.volume_m3[static_cast<size_t>(i - 1)];
  const Vec3 lever = k.mid_m[i] - k.com_m[i];
  if (vol > 0.0 && f.density_kg_m3 > 0.0) {
    Vec6 acc_b;
    acc_b << R.transpose() * a_mid, R.transpose() * alpha;
    const Vec6 fm_b = f.density_kg_m3 * vol * Factor(f.added_mass_factor, i) * (m.added_mass_coeff * acc_b);
    const Vec3 Fa = R * fm_b.head<3>();
    W.force_N += Fa;
    W.moment_Nm += R * fm_b.tail<3>() + lever.cross(Fa);
  }
  const Vec3 buoy = f.density_kg_m3 * vol * f.gravity_m_s2;  // −(buoyancy force −β·g)
  W.force_N += -L.mass_kg * f.gravity_m_s2 + buoy - drag;
  W.moment_Nm += lever.cross(buoy - drag);
  return W;
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
  loads.body0.assign(np + 1, Wrench{});
  loads.body_inertia.assign(np + 1, Mat6::Zero());
  loads.drag_N.assign(np, Vec3::Zero());
  loads.arm_inertia_r0.setZero();
  loads.arm_wrench0_r0 = Wrench{};
  for (int i = 1; i <= n; ++i) {
    const size_t ii = static_cast<size_t>(i);
    const LinkParams &L = m.link[ii - 1];
    loads.drag_N[ii] = LinkDrag(m, f, k, i);
    loads.body0[ii] = LinkRequiredWrench(m, f, k, i, k.a_com0_m_s2[i], k.a_mid0_m_s2[i],
                                         k.alpha0_rad_s2[i], loads.drag_N[ii]);
    // Acceleration-dependent part: rigid body and added mass of SPEC §3.3 (at μ_i), about r0;
    // the same map about the CoM is that one moved back by (r0 − c).
    const Vec3 dc = k.com_m[i] - b.r0_m;
    Mat6 A_r0 = RigidInertiaAt(L.mass_kg, dc, k.R[i], L.inertia_kg_m2);
    const double vol = m.volume_m3[ii - 1];
    if (vol > 0.0 && f.density_kg_m3 > 0.0)
      A_r0 += AddedMassInertiaAt(
          f.density_kg_m3 * vol * Factor(f.added_mass_factor, i) * m.added_mass_coeff,
          k.mid_m[i] - b.r0_m, k.R[i]);
    const Mat6 A = MoveWrench(-dc) * A_r0;
    loads.body_inertia[ii] = A;
    const Wrench at_r0 = About(loads.body0[ii], k.com_m[i], b.r0_m);
    loads.arm_wrench0_r0.force_N += at_r0.force_N;
    loads.arm_wrench0_r0.moment_Nm += at_r0.moment_Nm;
    loads.arm_inertia_r0 += A_r0;
  }
  loads.body0[np] = PayloadRequiredWrench(m, f, k.a_payload0_m_s2);
  const Vec3 dp = k.payload_m - b.r0_m;
  const Mat6 Ap_r0 = RigidInertiaAt(m.payload_kg, dp, Mat3::Identity(), Vec3::Zero());
  loads.body_inertia[np] = MoveWrench(-dp) * Ap_r0;
  const Wrench pw = About(loads.body0[np], k.payload_m, b.r0_m);
  loads.arm_wrench0_r0.force_N += pw.force_N;
  loads.arm_wrench0_r0.moment_Nm += pw.moment_Nm;
  loads.arm_inertia_r0 += Ap_r0;
}

void ComputeJointWrenches(const ArmModel &m, const BaseState &b, const ArmKinematics &k,
                          const ArmLoads &loads, const Vec6 &x, JointWrenches &out) {
  (void)b;
  // Each body's required wrench at the true vehicle acceleration, W_k = W_k0 + A_k·x, then
  // f_i and n_i as sums over the bodies distal to joint i (no recursion), SPEC [24–25], [29].
  const int n = m.n;
  const size_t np = static_cast<size_t>(n) + 1;
  std::vector<Wrench> W(np + 1);
  std::vector<Vec3> at(np + 1);
  for (size_t kk = 1; kk <= np; ++kk) {
    const Vec6 w = loads.body_inertia[kk] * x;
    W[kk] = Wrench{loads.body0[kk].force_N + w.head<3>(), loads.body0[kk].moment_Nm + w.tail<3>()};
    at[kk] = (kk == np) ? k.payload_m : k.com_m[kk];
  }
  out.tau_Nm.assign(np, 0.0);
  for (int i = 1; i <= n; ++i) {
    Vec3 f = Vec3::Zero(), nm = Vec3::Zero();
    for (size_t kk = static_cast<size_t>(i); kk <= np; ++kk) {
      f += W[kk].force_N;
      nm += W[kk].moment_Nm + (at[kk] - k.p_m[i - 1]).cross(W[kk].force_N);
    }
    if (i == 1) {
      out.f1_N = f;
      out.n1_Nm = nm;
    }
    out.tau_Nm[static_cast<size_t>(i)] = nm.dot(k.z[i]);  // [29]
  }
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
  // Added mass at the CoB, velocity-product part: a_cb = ω0 × (ω0 × d) when v̇0 = ω̇0 = 0.
  const Mat6 Ma = f.density_kg_m3 * V.volume_m3 * m.added_mass_coeff;
  if (V.volume_m3 > 0.0 && f.density_kg_m3 > 0.0) {
    Vec6 acc_b;
    acc_b << b.R0.transpose() * b.w0_rad_s.cross(b.w0_rad_s.cross(d)), Vec3::Zero();
    const Vec6 fm = Ma * acc_b;
    const Vec3 Fa = b.R0 * fm.head<3>();
    w0.force_N += Fa;
    w0.moment_Nm += b.R0 * fm.tail<3>() + d.cross(Fa);
  }
  // Minus the external loads: weight m0·g at the CoM, ballast weight and buoyancy −β0·g at
  // the CoB (SPEC §6.3), drag at the CoM.
  const Vec3 at_cob = (beta0 - f.ballast_kg) * f.gravity_m_s2;
  w0.force_N += -V.mass_kg * f.gravity_m_s2 + at_cob - drag;
  w0.moment_Nm += d.cross(at_cob);
  inertia = RigidInertiaAt(V.mass_kg, Vec3::Zero(), b.R0, V.inertia_kg_m2);  // about the CoM = r0
  if (V.volume_m3 > 0.0 && f.density_kg_m3 > 0.0) inertia += AddedMassInertiaAt(Ma, d, b.R0);
}

Vec6 SolveBaseAcceleration(const Mat6 &M_sys, const Wrench &bias, const Wrench &applied) {
  Vec6 rhs;
  rhs << applied.force_N - bias.force_N, applied.moment_Nm - bias.moment_Nm;
  return M_sys.partialPivLu().solve(rhs);
}

}  // namespace uvms::plant
