// SPDX-License-Identifier: Apache-2.0
// plant.cpp: the truth model (SPEC §5). The state vector's layout is StateLayout (plant.hpp):
// r0, quaternion, v0, ω0, motor speeds, 4 energies, link travel, motor currents, θ, θ̇.
// CVODE integrates its first StateLayout::Integrated() slots; the rest follow the held inputs
// in closed form within a tick (ClosedFormStates): θ, θ̇ under the held joint acceleration,
// and in the current drive (SPEC §5) the motor currents I*_j + İ*_j·(t − t_k) (set exactly at
// the tick's start and end).
// Voltage drive: inside a tick CVODE integrates the motor and thruster-energy slots in
// integrating-factor variables (IntegratorParams::motor_integrating_factor; see MotorTick):
//   motor speed / current slots:  z_j = e^{−A·τ}·((I_j, ω_j) − x∞_j)   [A], [rad/s]
//   thruster draw / signed slots: W = E − (the part of E due to the frozen-load motion) [J]
// with τ = t − t_k the time since the tick began. Step converts to and from physical values.
#include "uvms_plant/plant.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "uvms_plant/propulsion.hpp"

namespace uvms::plant {

namespace {
using Mat2 = Eigen::Matrix2d;
using Vec2 = Eigen::Vector2d;  // motor state (I [A], ω [rad/s])

// The motor's linear part, SPEC §5 [53–55] with the propeller torque Q held:
//   d/dt (I, ω) = A·(I, ω) + (V/Lm, −Q/J),  A = [[−Rm/Lm, −km/Lm], [km/J, −b/J]],
// and e^{A·τ} by Cayley–Hamilton (as LinearMotorStepResponse): with s = tr(A)/2 and
// δ² = ((a11 − a22)/2)² + a12·a21, N = A − s·I₂ has N² = δ²·I₂ and
//   e^{A·τ} = e^{s·τ}·(c(τ)·I₂ + h(τ)·N),
// c = cos(ω_d·τ), h = sin(ω_d·τ)/ω_d (ω_d = √(−δ²), complex modes: the paper's −1 ± 100i);
// c = cosh(δ·τ), h = sinh(δ·τ)/δ (real modes); c = 1, h = τ (repeated mode).
struct MotorModes {
  Mat2 A{Mat2::Zero()}, N{Mat2::Zero()}, A_inv{Mat2::Zero()};
  double s_1_s{0.0};      // s = tr(A)/2 [1/s]
  double delta2_1_s2{0.0};  // δ² [1/s²]
  double root_1_s{0.0};   // √|δ²| [1/s]

  explicit MotorModes(const PropulsionParams &p) {
    const double Lm = p.inductance_H, J = p.rotor_inertia_kg_m2, km = p.torque_constant_Nm_A;
    A << -p.resistance_ohm / Lm, -km / Lm, km / J, -p.viscous_friction_Nm_s / J;
    s_1_s = 0.5 * (A(0, 0) + A(1, 1));
    const double half_diff = 0.5 * (A(0, 0) - A(1, 1));
    delta2_1_s2 = half_diff * half_diff + A(0, 1) * A(1, 0);
    root_1_s = std::sqrt(std::abs(delta2_1_s2));
    N = A - s_1_s * Mat2::Identity();
    A_inv = A.inverse();  // det A = (Rm·b + km²)/(Lm·J) > 0 (ValidatePropulsionParams)
  }
  // e^{A·τ} = ec·I₂ + eh·N (τ may be negative).
  void Coeffs(double tau_s, double &ec, double &eh) const {
    const double es = std::exp(s_1_s * tau_s);
    if (delta2_1_s2 < 0.0) {
      ec = es * std::cos(root_1_s * tau_s);
      eh = es * std::sin(root_1_s * tau_s) / root_1_s;
    } else if (delta2_1_s2 > 0.0) {
      ec = es * std::cosh(root_1_s * tau_s);
      eh = es * std::sinh(root_1_s * tau_s) / root_1_s;
    } else {
      ec = es;
      eh = es * tau_s;
    }
  }
  Mat2 Exp(double tau_s) const {
    double ec = 0.0, eh = 0.0;
    Coeffs(tau_s, ec, eh);
    return ec * Mat2::Identity() + eh * N;
  }
  // Φ(τ) = ∫₀^τ e^{A·σ} dσ = A⁻¹·(e^{A·τ} − I₂).
  Mat2 Phi(double tau_s) const { return A_inv * (Exp(tau_s) - Mat2::Identity()); }
  // The integrating factor is used for a tick of dt only while e^{−A·dt} stays moderate
  // (≤ e⁴: it inverts a decaying propagator) and PositiveDrawJ's breakpoint list holds the
  // extrema of a tick (ω_d·dt/π < 60).
  bool Usable(double dt_s) const {
    const double growth_1_s = -s_1_s + (delta2_1_s2 > 0.0 ? root_1_s : 0.0);
    const double half_periods = delta2_1_s2 < 0.0 ? root_1_s * dt_s / M_PI : 0.0;
    return growth_1_s * dt_s <= 4.0 && half_periods < 60.0;
  }
};

// ∫₀^T max(g(τ), 0) dτ for the battery draw of one motor under the frozen-load motion
//   g(τ) = V·Ī(τ),  Ī(τ) = x∞_I + [e^{A·τ}·z0]_I,
// exactly: g is monotone between the zeros of g'(τ) = V·[e^{A·τ}·A·z0]_I (closed form), a
// sign change on such a piece is one root (safeguarded Newton), and g has the antiderivative
// G(τ) = V·(x∞_I·τ + [Φ(τ)·z0]_I). Returns [J].
double PositiveDrawJ(const MotorModes &m, double V, const Vec2 &x_inf, const Vec2 &z0,
                     double T_s) {
  if (V == 0.0 || !(T_s > 0.0)) return 0.0;
  const Vec2 Nz0 = m.N * z0, Az0 = m.A * z0, NAz0 = m.N * Az0;
  auto g = [&](double tau) {
    double ec = 0.0, eh = 0.0;
    m.Coeffs(tau, ec, eh);
    return V * (x_inf[0] + ec * z0[0] + eh * Nz0[0]);
  };
  auto dg = [&](double tau) {
    double ec = 0.0, eh = 0.0;
    m.Coeffs(tau, ec, eh);
    return V * (ec * Az0[0] + eh * NAz0[0]);
  };
  auto G = [&](double tau) { return V * (x_inf[0] * tau + (m.Phi(tau) * z0)[0]); };

  // Breakpoints: 0, the zeros of g' in (0, T), T. g' ∝ p·c(τ) + q·h(τ).
  const double p = Az0[0], q = NAz0[0];
  double bp[64];
  int nb = 0;
  bp[nb++] = 0.0;
  if (m.delta2_1_s2 < 0.0) {
    const double wd = m.root_1_s, r = q / wd;  // p·cos(ω_d·τ) + r·sin(ω_d·τ) = 0
    if (p != 0.0 || r != 0.0) {
      double th = std::atan2(-p, r);  // (cos θ, sin θ) ∝ (r, −p)
      if (th <= 0.0) th += M_PI;
      for (; th / wd < T_s && nb < 62; th += M_PI) bp[nb++] = th / wd;
    }
  } else if (m.delta2_1_s2 > 0.0) {  // p·cosh(δτ) + (q/δ)·sinh(δτ) = 0
    if (q != 0.0) {
      const double x = -p * m.root_1_s / q;
      if (std::abs(x) < 1.0) {
        const double tau = std::atanh(x) / m.root_1_s;
        if (tau > 0.0 && tau < T_s) bp[nb++] = tau;
      }
    }
  } else if (q != 0.0) {  // p + q·τ = 0
    const double tau = -p / q;
    if (tau > 0.0 && tau < T_s) bp[nb++] = tau;
  }
  bp[nb++] = T_s;  // MotorModes::Usable keeps the extrema of a tick below 60
  double total = 0.0;
  double a = bp[0], ga = g(a);
  for (int i = 1; i < nb; ++i) {
    const double b = bp[i], gb = g(b);
    if (ga >= 0.0 && gb >= 0.0) {
      total += G(b) - G(a);
    } else if ((ga > 0.0) != (gb > 0.0) && !(ga <= 0.0 && gb <= 0.0)) {
      // One root in (a, b): safeguarded Newton on the bracket.
      double lo = a, hi = b, glo = ga, x = 0.5 * (a + b);
      for (int it = 0; it < 100 && hi - lo > 4e-16 * T_s; ++it) {
        const double gx = g(x);
        if (gx == 0.0) break;
        if ((gx > 0.0) == (glo > 0.0)) {
          lo = x;
          glo = gx;
        } else {
          hi = x;
        }
        const double d = dg(x);
        double xn = (d != 0.0) ? x - gx / d : 0.5 * (lo + hi);
        if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
        if (std::abs(xn - x) <= 1e-16 * T_s) {
          x = xn;
          break;
        }
        x = xn;
      }
      total += (ga > 0.0) ? G(x) - G(a) : G(b) - G(x);
    }
    a = b;
    ga = gb;
  }
  return total;
}

ContactMonitor MakeMonitor(const PlantParams &p) {
  // Links meet their neighbours at joints, and links joined by short links touch by
  // construction (the WAM's elbow: links 3 and 5 are folded side by side 0.045 m apart, less
  // than their 0.089 m diameter). A pair of links is ignored when the links strictly between
  // them are together shorter than the two radii; so are the links that meet the hull at the
  // arm mount (the first links up to the first one with length).
  std::vector<std::pair<std::string, std::string>> ignore;
  const int n = static_cast<int>(p.links.size());
  auto len = [&](int i) { return LinkLength(p.links[size_t(i - 1)]); };
  auto radius = [&](int i) { return 0.5 * p.links[size_t(i - 1)].diameter_m; };
  for (int i = 1; i <= n; ++i) {
    double between = 0.0;
    for (int j = i + 1; j <= n; ++j) {
      if (between <= radius(i) + radius(j))
        ignore.emplace_back("link" + std::to_string(i), "link" + std::to_string(j));
      between += len(j);
    }
  }
  for (int j = 1; j <= n; ++j) {
    ignore.emplace_back("hull", "link" + std::to_string(j));
    if (len(j) > 0.0) break;
  }
  return ContactMonitor(p.contact.clearance_m, ignore);
}
}  // namespace

struct Plant::Eval {
  BaseState base;
  FluidState fluid;
  ArmKinematics kin;
  ArmLoads loads;
  Wrench vehicle_w0;
  Mat6 vehicle_M{Mat6::Zero()};
  Vec3 vehicle_drag{Vec3::Zero()};
  Wrench thrust;
  std::vector<double> thrust_N, torque_Nm;
  Vec6 accel{Vec6::Zero()};
  Wrench bias;  ///< thrust wrench (about r0) that would leave the vehicle unaccelerated
  JointWrenches joints;
};

// Integrating-factor constants of one tick (SPEC §5 [53–55], IntegratorParams::
// motor_integrating_factor). With the propeller torque frozen at its tick-start value Q0_j,
// motor j is linear: ẋ = A·x + f_j, f_j = (V_j/Lm, −Q0_j/J), steady state x∞_j = −A⁻¹·f_j.
// The exact change of variables x_j(τ) = x∞_j + e^{A·τ}·z_j(τ) gives
//   ż_j = e^{−A·τ}·(0, −(Q_j(t) − Q0_j)/J),
// which is zero for a constant load: the 100 rad/s ringing no longer limits CVODE's steps.
// The energies (SPEC §5 "Energy") split the same way around the frozen-load current
// Ī_j(τ) = x∞_I,j + [e^{A·τ}·z_j(0)]_I, whose integrals are closed form:
//   E_signed(τ) = W_s(τ) + Σ_j V_j·(x∞_I,j·τ + [Φ(τ)·z_j(0)]_I),  Ẇ_s = Σ_j V_j·(I_j − Ī_j)
//   E_draw(τ)   = W_d(τ) + Σ_j ∫₀^τ max(V_j·Ī_j, 0),  Ẇ_d = Σ_j max(V_j·I_j, 0) − max(V_j·Ī_j, 0)
// and CVODE integrates W_s, W_d (their integrands are as small as the load change).
// Thrusters of different types (ThrusterGeometry::propulsion) have their own modes: one
// MotorModes per distinct motor, mode_of[j] thruster j's; e^{A·τ} is evaluated once per
// distinct motor per call.
struct Plant::MotorTick {
  static constexpr std::size_t kMaxModes = 16;  // the plant's thruster maximum
  explicit MotorTick(const PlantParams &p) {
    std::vector<const PropulsionParams *> motors;
    for (std::size_t j = 0; j < p.thrusters.size(); ++j) {
      const PropulsionParams &pj = PropulsionOf(p, j);
      std::size_t m = 0;
      while (m < motors.size() && !SameMotor(*motors[m], pj)) ++m;
      if (m == motors.size()) {
        motors.push_back(&pj);
        modes.emplace_back(pj);
      }
      mode_of.push_back(m);
      inv_J.push_back(1.0 / pj.rotor_inertia_kg_m2);
      inv_L.push_back(1.0 / pj.inductance_H);
      inductance_H.push_back(pj.inductance_H);
    }
  }
  static bool SameMotor(const PropulsionParams &a, const PropulsionParams &b) {
    return a.resistance_ohm == b.resistance_ohm && a.inductance_H == b.inductance_H &&
           a.torque_constant_Nm_A == b.torque_constant_Nm_A &&
           a.viscous_friction_Nm_s == b.viscous_friction_Nm_s &&
           a.rotor_inertia_kg_m2 == b.rotor_inertia_kg_m2;
  }
  bool Usable(double dt_s) const {
    for (const MotorModes &m : modes)
      if (!m.Usable(dt_s)) return false;
    return true;
  }
  std::vector<MotorModes> modes;
  std::vector<std::size_t> mode_of;  // thruster j's entry of modes
  std::vector<double> inv_J;         // 1/J_j [1/(kg·m²)]
  std::vector<double> inv_L;         // 1/Lm_j [1/H]
  std::vector<double> inductance_H;  // Lm_j [H]
  bool active{false};  // this tick integrates in the variables above
  double t0_s{0.0};   // t_k, start of the tick [s]
  std::vector<Vec2> x_inf, z0;
  std::vector<double> q0_Nm;  // Q0_j [N·m]
};

Wrench Plant::HoldingWrench(const PlantInputs &in) const {
  Eval e;
  Evaluate(t_, y_.data(), in, e);
  return e.bias;
}

Plant::Plant(PlantParams params)
    : params_(std::move(params)),
      model_(ArmModel::FromParams(params_)),
      flow_(params_.env.unsteady, params_.env.steady_flow_m_s),
      contact_(MakeMonitor(params_)) {
  ValidatePropulsionParams(params_.propulsion);
  for (const ThrusterGeometry &t : params_.thrusters)
    if (t.propulsion) ValidatePropulsionParams(*t.propulsion);
  if (params_.thrusters.empty() || params_.thrusters.size() > 16)
    throw std::invalid_argument("plant: need 1..16 thrusters, got " + std::to_string(params_.thrusters.size()));
  for (const auto &t : params_.thrusters)
    if (!t.position_m.allFinite() || !t.direction.allFinite() || t.direction.norm() < 1e-9)
      throw std::invalid_argument("plant: thruster geometry must be finite with a non-zero direction");
  const EnvironmentParams &e = params_.env;
  if (!(e.density_kg_m3 >= 0.0) || !std::isfinite(e.density_kg_m3))
    throw std::invalid_argument("plant: env.density_kg_m3 must be finite and >= 0");
  if (!e.gravity_m_s2.allFinite()) throw std::invalid_argument("plant: env.gravity_m_s2 must be finite");
  if (e.variable_coefficients) {
    if (params_.env.coeff_table.empty()) params_.env.coeff_table = DefaultCoeffTable();
    ValidateCoeffTable(params_.env.coeff_table);
  }
  if (!e.ballast_error_m.allFinite())
    throw std::invalid_argument("plant: env.ballast_error_m must be finite");
  if (e.trim) {  // SPEC §6.3, with the configured trim error
    ballast_ = TrimBallast(params_);
    ballast_.offset_m += e.ballast_error_m;
  }
  const double abs_w = params_.integrator.motor_speed_abs_tol_rad_s;
  if (!(std::isfinite(abs_w) && abs_w > 0.0))
    throw std::invalid_argument("plant: integrator.motor_speed_abs_tol_rad_s must be finite and > 0");
  const double h0_frac = params_.integrator.restart_step_fraction;
  if (!(std::isfinite(h0_frac) && h0_frac >= 0.0 && h0_frac <= 1.0))
    throw std::invalid_argument("plant: integrator.restart_step_fraction must be in [0, 1]");
  n_ = model_.n;
  nt_ = static_cast<int>(params_.thrusters.size());
  lay_ = StateLayout::Make(size_t(n_), size_t(nt_));
  for (auto &t : params_.thrusters) t.direction.normalize();
  thruster_types_ = HasThrusterTypes(params_);
  for (size_t j = 0; j < params_.thrusters.size(); ++j)
    propeller_.push_back(PropellerCoeffsOf(PropulsionOf(params_, j), params_.env.density_kg_m3));
  n_int_ = lay_.Integrated(params_.propulsion.drive == MotorDrive::kCurrent);
  integ_ = std::make_unique<Integrator>(n_int_, params_.integrator, [this](double t, const double *w, double *wd) {
    return IntegratorRhs(t, w, wd);
  });
  y_.assign(lay_.size, 0.0);
  w_.assign(n_int_, 0.0);
  y_rhs_.assign(lay_.size, 0.0);
  yd_rhs_.assign(lay_.size, 0.0);
  load_torque_Nm_.assign(size_t(nt_), 0.0);
  scratch_ = std::make_unique<Eval>();
  motor_ = std::make_unique<MotorTick>(params_);
  // Error weights 1/(rel_tol·scale_i + abs_tol) with scale_i = |y_i| for every state, except
  // that in integrating-factor variables a motor state's scale is the physical one,
  // |x∞_j| + |z_j| per component (≥ |x_j(τ)| up to the e^{A·τ} mixing), not |z_j| alone:
  // the same relative accuracy the direct form asks of I_j and ω_j.
  // The motor speeds take their own absolute tolerance (IntegratorParams::
  // motor_speed_abs_tol_rad_s).
  // CVODE's error test is a root mean square over the n_int_ integrated states; the
  // closed-form states have no integration error, and the test is kept that of the whole
  // state vector (their zero errors counted): every weight × √(n_int_/size).
  const double full_norm = std::sqrt(double(n_int_) / double(lay_.size));
  integ_->SetErrorWeights([this, full_norm](const double *w, double *ewt) {
    const double rel = params_.integrator.rel_tol / full_norm, abs = params_.integrator.abs_tol / full_norm;
    const double abs_w = params_.integrator.motor_speed_abs_tol_rad_s / full_norm;
    for (size_t i = 0; i < n_int_; ++i) ewt[i] = 1.0 / (rel * std::abs(w[i]) + abs);
    const MotorTick &mt = *motor_;
    const size_t kw = lay_.motor_speed_rad_s, ki = lay_.motor_current_A;
    if (mt.active) {
      for (size_t j = 0; j < size_t(nt_); ++j) {
        ewt[ki + j] = 1.0 / (rel * (std::abs(mt.x_inf[j][0]) + std::abs(w[ki + j])) + abs);
        ewt[kw + j] = 1.0 / (rel * (std::abs(mt.x_inf[j][1]) + std::abs(w[kw + j])) + abs_w);
      }
    } else {
      for (size_t j = 0; j < size_t(nt_); ++j) ewt[kw + j] = 1.0 / (rel * std::abs(w[kw + j]) + abs_w);
    }
    return 0;
  });
  motor_->x_inf.assign(size_t(nt_), Vec2::Zero());
  motor_->z0.assign(size_t(nt_), Vec2::Zero());
  motor_->q0_Nm.assign(size_t(nt_), 0.0);
}

void Plant::ClosedFormStates(double tau_s, const double *y_k, double *y) const {
  const std::vector<double> &qdd = held_.joint_accel_rad_s2;
  for (size_t j = 0; j < size_t(n_); ++j) {
    const double q0 = y_k[lay_.q_rad + j], qd0 = y_k[lay_.qd_rad_s + j];
    y[lay_.q_rad + j] = q0 + qd0 * tau_s + 0.5 * qdd[j] * tau_s * tau_s;
    y[lay_.qd_rad_s + j] = qd0 + qdd[j] * tau_s;
  }
  if (params_.propulsion.drive == MotorDrive::kCurrent)  // SPEC §5: I_j = I*_j + İ*_j·τ
    for (size_t j = 0; j < size_t(nt_); ++j)
      y[lay_.motor_current_A + j] = held_.motor_current_cmd_A[j] + held_.motor_current_rate_A_s[j] * tau_s;
}

void Plant::ToPhysical(double t, const double *w, double *y) const {
  std::copy(w, w + n_int_, y);
  ClosedFormStates(t - t_, y, y);  // y still holds the tick's start beyond n_int_
  const MotorTick &mt = *motor_;
  if (!mt.active) return;
  const size_t kw = lay_.motor_speed_rad_s, ki = lay_.motor_current_A;
  const double tau = t - mt.t0_s;
  std::array<Mat2, MotorTick::kMaxModes> E, Phi;
  for (size_t m = 0; m < mt.modes.size() && m < MotorTick::kMaxModes; ++m) {
    E[m] = mt.modes[m].Exp(tau);
    Phi[m] = mt.modes[m].Phi(tau);
  }
  double signed_J = 0.0, draw_J = 0.0;
  for (size_t j = 0; j < size_t(nt_); ++j) {
    const size_t m = mt.mode_of[j];
    const Vec2 x = mt.x_inf[j] + E[m] * Vec2(w[ki + j], w[kw + j]);
    y[ki + j] = x[0];
    y[kw + j] = x[1];
    const double V = held_.motor_voltage_V[j];
    signed_J += V * (mt.x_inf[j][0] * tau + (Phi[m] * mt.z0[j])[0]);
    draw_J += PositiveDrawJ(mt.modes[m], V, mt.x_inf[j], mt.z0[j], tau);
  }
  y[lay_.energy_draw_J] = w[lay_.energy_draw_J] + draw_J;
  y[lay_.energy_signed_J] = w[lay_.energy_signed_J] + signed_J;
}

int Plant::IntegratorRhs(double t, const double *w, double *wd) {
  const MotorTick &mt = *motor_;
  // The physical state: CVODE's states, then the closed-form ones at t (y_ holds the tick's
  // start until Step ends).
  std::copy(w, w + n_int_, y_rhs_.data());
  ClosedFormStates(t - t_, y_.data(), y_rhs_.data());
  if (!mt.active) {
    Derivatives(t, y_rhs_.data(), held_, yd_rhs_.data());
    std::copy(yd_rhs_.data(), yd_rhs_.data() + n_int_, wd);
  } else {
    // Physical motor states (energies are not read by the physics), then ż_j, Ẇ_d, Ẇ_s.
    const size_t kw = lay_.motor_speed_rad_s, ki = lay_.motor_current_A, nt = size_t(nt_);
    const double tau = t - mt.t0_s;
    std::array<Mat2, MotorTick::kMaxModes> E, E_inv;
    for (size_t m = 0; m < mt.modes.size() && m < MotorTick::kMaxModes; ++m) {
      E[m] = mt.modes[m].Exp(tau);
      E_inv[m] = mt.modes[m].Exp(-tau);
    }
    for (size_t j = 0; j < nt; ++j) {
      const Vec2 x = mt.x_inf[j] + E[mt.mode_of[j]] * Vec2(w[ki + j], w[kw + j]);
      y_rhs_[ki + j] = x[0];
      y_rhs_[kw + j] = x[1];
    }
    Derivatives(t, y_rhs_.data(), held_, yd_rhs_.data());
    std::copy(yd_rhs_.data(), yd_rhs_.data() + n_int_, wd);
    const Eval &e = *scratch_;
    double d_draw_W = 0.0, d_signed_W = 0.0;
    for (size_t j = 0; j < nt; ++j) {
      const size_t m = mt.mode_of[j];
      const Vec2 dz = E_inv[m] * Vec2(0.0, -(e.torque_Nm[j] - mt.q0_Nm[j]) * mt.inv_J[j]);
      wd[ki + j] = dz[0];
      wd[kw + j] = dz[1];
      const double V = held_.motor_voltage_V[j];
      const double dI = (E[m] * (Vec2(w[ki + j], w[kw + j]) - mt.z0[j]))[0];
      const double I_bar = mt.x_inf[j][0] + (E[m] * mt.z0[j])[0];
      d_signed_W += V * dI;
      d_draw_W += std::max(V * (I_bar + dI), 0.0) - std::max(V * I_bar, 0.0);
    }
    wd[lay_.energy_draw_J] = d_draw_W;
    wd[lay_.energy_signed_J] = d_signed_W;
  }
  for (size_t i = 0; i < n_int_; ++i)
    if (!std::isfinite(wd[i])) return -1;  // fatal: never integrate NaN
  return 0;
}

// One motor at an instant (SPEC §5 "Motors"): derivatives of its state slots, and the current
// and terminal voltage whose product is its electrical power.
struct Plant::MotorState {
  double omega_dot_rad_s2{0.0};
  double current_dot_A_s{0.0};
  double current_A{0.0};
  double voltage_V{0.0};
};

double Plant::PropulsivePower(const std::vector<double> &thrust_N) const {
  const double rho = params_.env.density_kg_m3;
  if (!thruster_types_) return PropulsivePowerW(params_.propulsion, rho, thrust_N);
  double P_W = 0.0;
  for (size_t j = 0; j < thrust_N.size(); ++j)
    P_W += PropulsivePowerW(PropulsionOf(params_, j), rho, {thrust_N[j]});
  return P_W;
}

Plant::MotorState Plant::MotorTerms(double t, const double *y, const PlantInputs &in, size_t j,
                                    double torque_Nm) const {
  const PropulsionParams &p = PropulsionOf(params_, j);
  const double w_rad_s = y[lay_.motor_speed_rad_s + j];
  MotorState m;
  if (params_.propulsion.drive == MotorDrive::kCurrent) {
    // The power stage's current over the tick begun at t_; V from [53]; J·ω̇ = km·I − b·ω − Q.
    m.current_A = in.motor_current_cmd_A[j] + in.motor_current_rate_A_s[j] * (t - t_);
    m.current_dot_A_s = in.motor_current_rate_A_s[j];
    m.voltage_V = p.resistance_ohm * m.current_A + p.inductance_H * m.current_dot_A_s +
                  p.torque_constant_Nm_A * w_rad_s;
    m.omega_dot_rad_s2 =
        MotorRhs(p, motor_->inv_L[j], motor_->inv_J[j], m.voltage_V, m.current_A, w_rad_s, torque_Nm).omega_dot_rad_s2;
    return m;
  }
  m.current_A = y[lay_.motor_current_A + j];
  m.voltage_V = in.motor_voltage_V[j];
  const MotorDerivatives d =
      MotorRhs(p, motor_->inv_L[j], motor_->inv_J[j], m.voltage_V, m.current_A, w_rad_s, torque_Nm);
  m.omega_dot_rad_s2 = d.omega_dot_rad_s2;
  m.current_dot_A_s = d.current_dot_A_s;
  return m;
}

Plant::~Plant() = default;

Integrator::Stats Plant::integrator_stats() const { return integ_->GetStats(); }

void Plant::Reset(const InitialState &init) {
  if (static_cast<int>(init.q_rad.size()) != n_)
    throw std::invalid_argument("plant: initial q_rad needs " + std::to_string(n_) + " joint angles");
  if (!init.qd_rad_s.empty() && static_cast<int>(init.qd_rad_s.size()) != n_)
    throw std::invalid_argument("plant: initial qd_rad_s needs " + std::to_string(n_) + " rates (or none)");
  if (!init.r0_m.allFinite() || !init.v0_m_s.allFinite() || !init.w0_rad_s.allFinite() ||
      !init.attitude.coeffs().allFinite() || init.attitude.norm() < 1e-9)
    throw std::invalid_argument("plant: initial vehicle state must be finite with a non-zero quaternion");
  std::fill(y_.begin(), y_.end(), 0.0);
  const Eigen::Quaterniond q = init.attitude.normalized();
  for (int k = 0; k < 3; ++k) {
    y_[lay_.r0_m + size_t(k)] = init.r0_m[k];
    y_[lay_.v0_m_s + size_t(k)] = init.v0_m_s[k];
    y_[lay_.w0_rad_s + size_t(k)] = init.w0_rad_s[k];
  }
  y_[lay_.attitude] = q.w();
  y_[lay_.attitude + 1] = q.x();
  y_[lay_.attitude + 2] = q.y();
  y_[lay_.attitude + 3] = q.z();
  for (size_t j = 0; j < size_t(n_); ++j) {
    y_[lay_.q_rad + j] = init.q_rad[j];
    y_[lay_.qd_rad_s + j] = init.qd_rad_s.empty() ? 0.0 : init.qd_rad_s[j];
  }
  t_ = 0.0;
  next_step_s_ = 0.0;
  held_ = PlantInputs{};
  held_.motor_voltage_V.assign(size_t(nt_), 0.0);
  held_.motor_current_cmd_A.assign(size_t(nt_), 0.0);
  held_.motor_current_rate_A_s.assign(size_t(nt_), 0.0);
  held_.joint_accel_rad_s2.assign(size_t(n_), 0.0);
  FillTruth(held_);
}

void Plant::Evaluate(double t, const double *y, const PlantInputs &in, Eval &e) const {
  const int n = n_, nt = nt_;
  const double *q = y + lay_.q_rad, *qd = y + lay_.qd_rad_s;
  const double *wm = y + lay_.motor_speed_rad_s;
  const double *travel = y + lay_.travel_m;
  const double *qa = y + lay_.attitude;
  Eigen::Quaterniond quat(qa[0], qa[1], qa[2], qa[3]);
  quat.normalize();  // the integrator lets |q| drift slightly between ticks
  e.base.r0_m = Eigen::Map<const Vec3>(y + lay_.r0_m);
  e.base.R0 = quat.toRotationMatrix();
  e.base.v0_m_s = Eigen::Map<const Vec3>(y + lay_.v0_m_s);
  e.base.w0_rad_s = Eigen::Map<const Vec3>(y + lay_.w0_rad_s);

  const EnvironmentParams &env = params_.env;
  e.fluid.density_kg_m3 = env.density_kg_m3;
  e.fluid.flow_m_s = flow_.Velocity(t);  // SPEC §6.1: only the plant sees the unsteady part
  e.fluid.gravity_m_s2 = env.gravity_m_s2;
  e.fluid.angle_of_attack = env.angle_of_attack;
  e.fluid.ballast_kg = ballast_.mass_kg;
  e.fluid.ballast_offset_m = ballast_.offset_m;
  e.fluid.drag_factor.clear();
  e.fluid.added_mass_factor.clear();
  if (env.variable_coefficients) {  // SPEC §6.4: factors by distance travelled, in diameters
    for (int i = 0; i < n; ++i) {
      const double dl = model_.link[size_t(i)].diameter_m;
      const CoeffFactors c = InterpolateCoeffs(env.coeff_table, dl > 0.0 ? travel[i] / dl : 0.0);
      e.fluid.drag_factor.push_back(c.drag_factor);
      e.fluid.added_mass_factor.push_back(c.added_mass_factor);
    }
  }

  const double *qdd = in.joint_accel_rad_s2.data();
  ComputeArmKinematics(model_, e.base, q, qd, qdd, e.kin);
  ComputeArmLoads(model_, e.base, e.fluid, e.kin, e.loads);
  ComputeVehicleLoads(model_, e.base, e.fluid, e.vehicle_w0, e.vehicle_M, e.vehicle_drag);

  // Thrusters [47–52]: thrust along u_j at a_j from the motor speed and advance speed.
  // Summed in vehicle axes, then turned to inertial once.
  e.thrust_N.assign(size_t(nt), 0.0);
  e.torque_Nm.assign(size_t(nt), 0.0);
  const Vec3 v_rel_B = e.base.R0.transpose() * (e.base.v0_m_s - e.fluid.flow_m_s);
  const Vec3 w0_B = e.base.R0.transpose() * e.base.w0_rad_s;
  Vec3 force_B = Vec3::Zero(), moment_B = Vec3::Zero();
  for (int j = 0; j < nt; ++j) {
    const ThrusterGeometry &g = params_.thrusters[size_t(j)];
    const double va = AdvanceSpeedBodyMS(g, v_rel_B, w0_B);
    const double factor = in.thrust_factor.empty() ? 1.0 : in.thrust_factor[size_t(j)];
    const PropellerCoeffs &c = propeller_[size_t(j)];
    e.thrust_N[size_t(j)] = factor * c.Thrust(wm[j], va);
    e.torque_Nm[size_t(j)] = c.Torque(wm[j], va);
    const Vec3 F = g.direction * e.thrust_N[size_t(j)];
    force_B += F;
    moment_B += g.position_m.cross(F);
  }
  e.thrust = Wrench{e.base.R0 * force_B, e.base.R0 * moment_B};

  // SPEC §5: M_sys·(v̇0, ω̇0) = thrust + disturbance − bias, solved in every evaluation.
  const Mat6 M = e.loads.arm_inertia_r0 + e.vehicle_M;
  Wrench bias{e.loads.arm_wrench0_r0.force_N + e.vehicle_w0.force_N,
              e.loads.arm_wrench0_r0.moment_Nm + e.vehicle_w0.moment_Nm};
  Wrench applied{e.thrust.force_N + in.disturbance_force_N, e.thrust.moment_Nm + in.disturbance_moment_Nm};
  e.bias = bias;
  e.accel = SolveBaseAcceleration(M, bias, applied, model_.symmetric);
  ComputeJointWrenches(model_, e.base, e.kin, e.loads, e.accel, e.joints);
}

void Plant::Derivatives(double t, const double *y, const PlantInputs &in, double *yd) const {
  Eval &e = *scratch_;  // reused: no allocation per right-hand-side evaluation
  Evaluate(t, y, in, e);
  const StateLayout &L = lay_;
  const size_t n = size_t(n_), nt = size_t(nt_);
  for (size_t k = 0; k < 3; ++k) {
    yd[L.r0_m + k] = y[L.v0_m_s + k];
    yd[L.v0_m_s + k] = e.accel[long(k)];
    yd[L.w0_rad_s + k] = e.accel[long(3 + k)];
  }
  // q̇ = ½·(0, ω)⊗q for an inertial angular velocity ω and q mapping vehicle → inertial.
  const double *qa = y + L.attitude, *om = y + L.w0_rad_s;
  const double w = qa[0], x = qa[1], yy = qa[2], z = qa[3];
  const double ox = om[0], oy = om[1], oz = om[2];
  double *qad = yd + L.attitude;
  qad[0] = 0.5 * (-ox * x - oy * yy - oz * z);
  qad[1] = 0.5 * (ox * w + oy * z - oz * yy);
  qad[2] = 0.5 * (oy * w + oz * x - ox * z);
  qad[3] = 0.5 * (oz * w + ox * yy - oy * x);
  for (size_t j = 0; j < n; ++j) {
    yd[L.q_rad + j] = y[L.qd_rad_s + j];
    yd[L.qd_rad_s + j] = in.joint_accel_rad_s2[j];
  }
  double draw = 0.0, signed_p = 0.0;
  for (size_t j = 0; j < nt; ++j) {
    const MotorState m = MotorTerms(t, y, in, j, e.torque_Nm[j]);
    yd[L.motor_speed_rad_s + j] = m.omega_dot_rad_s2;
    yd[L.motor_current_A + j] = m.current_dot_A_s;
    const double P_W = m.voltage_V * m.current_A;
    draw += std::max(P_W, 0.0);  // battery draw, no regeneration credited (SPEC §5)
    signed_p += P_W;
  }
  double manip = 0.0;
  for (size_t i = 1; i <= n; ++i) manip += std::abs(e.joints.tau_Nm[i] * y[L.qd_rad_s + i - 1]);
  yd[L.energy_draw_J] = draw;
  yd[L.energy_signed_J] = signed_p;
  yd[L.energy_manip_J] = manip;
  yd[L.energy_prop_J] = PropulsivePower(e.thrust_N);
  for (size_t i = 1; i <= n; ++i)  // distance through the water of each aerodynamic center
    yd[L.travel_m + i - 1] = e.loads.speed_m_s[i];
}

std::string Plant::CheckInputs(const PlantInputs &in, double dt_s) const {
  const bool current = params_.propulsion.drive == MotorDrive::kCurrent;
  const size_t nt = size_t(nt_);
  auto finite = [](const std::vector<double> &v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
  };
  if (in.joint_accel_rad_s2.size() != size_t(n_))
    return "plant: inputs need " + std::to_string(n_) + " joint accelerations";
  if (current && (in.motor_current_cmd_A.size() != nt || in.motor_current_rate_A_s.size() != nt))
    return "plant: the current drive needs " + std::to_string(nt) + " current commands and rates";
  if (!current && in.motor_voltage_V.size() != nt)
    return "plant: the voltage drive needs " + std::to_string(nt) + " voltages";
  if (!in.thrust_factor.empty()) {
    bool ok = in.thrust_factor.size() == nt;
    for (double f : in.thrust_factor) ok = ok && std::isfinite(f) && f >= 0.0 && f <= 1.0;
    if (!ok) return "plant: thrust_factor needs " + std::to_string(nt) + " values in [0, 1]";
  }
  const bool ok = std::isfinite(dt_s) && dt_s > 0.0 && in.disturbance_force_N.allFinite() &&
                  in.disturbance_moment_Nm.allFinite() && finite(in.joint_accel_rad_s2) &&
                  finite(in.motor_voltage_V) && finite(in.motor_current_cmd_A) &&
                  finite(in.motor_current_rate_A_s);
  return ok ? std::string() : "plant: non-finite input or tick length";
}

StepStatus Plant::Step(const PlantInputs &in, double dt_s) {
  StepStatus st;
  st.message = CheckInputs(in, dt_s);
  if (!st.message.empty()) {
    st.code = StepStatus::Code::kBadInput;
    return st;
  }
  held_ = in;
  const bool current_drive = params_.propulsion.drive == MotorDrive::kCurrent;
  const size_t kc = lay_.motor_current_A;  // first motor current slot
  if (current_drive)  // SPEC §5: the power stage sets I_j(t_k) = I*_j
    std::copy(in.motor_current_cmd_A.begin(), in.motor_current_cmd_A.end(), y_.begin() + long(kc));
  // Normalise the quaternion at the tick boundary; CVODE restarts cleanly (inputs jumped).
  Eigen::Map<Eigen::Vector4d> qv(y_.data() + lay_.attitude);
  qv.normalize();
  // Integrating-factor variables of this tick (MotorTick): z_j(0) = x_j − x∞_j, W(0) = E(0).
  // Only the voltage drive has the stiff electromechanical mode it removes.
  MotorTick &mt = *motor_;
  mt.active = !current_drive && params_.integrator.motor_integrating_factor && mt.Usable(dt_s);
  w_.assign(y_.begin(), y_.begin() + long(n_int_));
  if (mt.active) {
    const size_t kw = lay_.motor_speed_rad_s, ki = lay_.motor_current_A;
    mt.t0_s = t_;
    for (size_t j = 0; j < size_t(nt_); ++j) {
      mt.q0_Nm[j] = load_torque_Nm_[j];
      mt.x_inf[j] = -(mt.modes[mt.mode_of[j]].A_inv *
                      Vec2(in.motor_voltage_V[j] / mt.inductance_H[j], -mt.q0_Nm[j] * mt.inv_J[j]));
      mt.z0[j] = Vec2(y_[ki + j], y_[kw + j]) - mt.x_inf[j];
      w_[ki + j] = mt.z0[j][0];
      w_[kw + j] = mt.z0[j][1];
    }
  }
  // First step after the restart: a small fraction of the step CVODE's error control chose
  // at the end of the previous tick (IntegratorParams::restart_step_fraction), instead of
  // CVODE's estimate, which costs two extra rhs evaluations per tick. None (0: CVODE's
  // estimate) after Reset or a failure.
  const double h0_s = std::min(params_.integrator.restart_step_fraction * next_step_s_, dt_s);
  integ_->SetInitStep(std::isfinite(h0_s) && h0_s > 0.0 ? h0_s : 0.0);
  integ_->Reset(t_, w_.data());
  const Integrator::Result r = integ_->AdvanceTo(t_ + dt_s, w_.data());
  next_step_s_ = r.ok ? integ_->NextStep() : 0.0;
  ToPhysical(r.t_reached, w_.data(), y_.data());
  mt.active = false;  // Derivatives / HoldingWrench callers see the physical state only
  if (!r.ok) {
    st.code = StepStatus::Code::kIntegratorFailure;
    st.message = "plant: CVODE failed at t = " + std::to_string(r.t_reached) + " s: " + r.flag_name + " " + r.message;
    return st;
  }
  if (current_drive)  // exactly I*_j + İ*_j·Δt at the tick's end (SPEC §5)
    for (size_t j = 0; j < size_t(nt_); ++j)
      y_[kc + j] = in.motor_current_cmd_A[j] + in.motor_current_rate_A_s[j] * dt_s;
  t_ += dt_s;
  FillTruth(in);
  if (truth_.contact_breach) {
    st.code = StepStatus::Code::kContact;
    st.message = "plant: contact: " + truth_.closest_a + " and " + truth_.closest_b + " at distance " +
                 std::to_string(truth_.min_clearance_m) + " m (clearance " +
                 std::to_string(params_.contact.clearance_m) + " m)";
  }
  return st;
}

void Plant::FillTruth(const PlantInputs &in) {
  Eval &e = *scratch_;  // the integration is over: the rhs workspace is free
  Evaluate(t_, y_.data(), in, e);
  const int n = n_, nt = nt_;
  Truth &T = truth_;
  T.time_s = t_;
  T.r0_m = e.base.r0_m;
  const double *qa = y_.data() + lay_.attitude;
  T.attitude = Eigen::Quaterniond(qa[0], qa[1], qa[2], qa[3]).normalized();
  T.v0_m_s = e.base.v0_m_s;
  T.w0_rad_s = e.base.w0_rad_s;
  T.accel_m_s2 = e.accel.head<3>();
  T.alpha_rad_s2 = e.accel.tail<3>();
  auto slots = [this](std::vector<double> &out, size_t first, int count) {  // reuses out's storage
    out.assign(y_.begin() + long(first), y_.begin() + long(first) + count);
  };
  slots(T.q_rad, lay_.q_rad, n);
  slots(T.qd_rad_s, lay_.qd_rad_s, n);
  slots(T.motor_speed_rad_s, lay_.motor_speed_rad_s, nt);
  slots(T.motor_current_A, lay_.motor_current_A, nt);
  T.motor_voltage_V.assign(size_t(nt), 0.0);
  for (int j = 0; j < nt; ++j) {
    const PropulsionParams &p = PropulsionOf(params_, size_t(j));
    T.motor_voltage_V[size_t(j)] =
        params_.propulsion.drive == MotorDrive::kVoltage
            ? in.motor_voltage_V[size_t(j)]
            : p.resistance_ohm * T.motor_current_A[size_t(j)] +
                  p.inductance_H * in.motor_current_rate_A_s[size_t(j)] +
                  p.torque_constant_Nm_A * T.motor_speed_rad_s[size_t(j)];  // [53]
  }
  T.thrust_N = e.thrust_N;
  load_torque_Nm_ = e.torque_Nm;  // Q0_j of the next tick's integrating factor
  T.thrust_force_N = e.thrust.force_N;
  T.thrust_moment_Nm = e.thrust.moment_Nm;
  T.ee_m = e.kin.ee_m;
  T.barycenter_m = e.kin.barycenter_m;
  Vec3 mv = model_.vehicle.mass_kg * e.base.v0_m_s + model_.payload_kg * e.kin.v_payload_m_s;
  for (int i = 1; i <= n; ++i) mv += model_.link[size_t(i - 1)].mass_kg * e.kin.v_com_m_s[size_t(i)];
  T.barycenter_v_m_s = mv / model_.total_mass_kg;
  T.flow_m_s = e.fluid.flow_m_s;
  T.joint_torque_Nm.assign(e.joints.tau_Nm.begin() + 1, e.joints.tau_Nm.end());
  T.thruster_energy_J = y_[lay_.energy_draw_J];
  T.thruster_energy_signed_J = y_[lay_.energy_signed_J];
  T.manipulator_energy_J = y_[lay_.energy_manip_J];
  T.propulsive_energy_J = y_[lay_.energy_prop_J];
  if (params_.contact.enabled) {
    // The body list (names, groups, scene obstacles) is built once; each tick moves the hull
    // and the link capsules.
    std::vector<Body> &bodies = contact_bodies_;
    if (bodies.empty()) {
      bodies.push_back(Body{"hull", Box{}, -1});
      for (int i = 1; i <= n; ++i)
        bodies.push_back(Body{"link" + std::to_string(i), Capsule{}, params_.contact.self_collision ? -1 : 1});
      for (const CylinderObstacle &o : params_.contact.obstacles) {
        Cylinder cyl;
        cyl.base_center_m = o.base_center_m;
        cyl.axis = Vec3::UnitZ();
        cyl.height_m = o.height_m;
        cyl.radius_m = o.radius_m;
        bodies.push_back(Body{o.name, cyl, 0});  // scene bodies share a group
      }
      contact_pairs_ = contact_.CheckedPairs(bodies);
    }
    Box hull;
    hull.center_m = e.base.r0_m + e.base.R0 * model_.vehicle.hull_center_m;
    hull.R = e.base.R0;
    hull.half_extent_m = 0.5 * model_.vehicle.hull_size_m;
    bodies[0].shape = hull;
    for (int i = 1; i <= n; ++i) {
      Capsule c;
      c.a = e.kin.p_m[size_t(i - 1)];
      c.b = e.kin.p_m[size_t(i)];
      c.radius_m = 0.5 * model_.link[size_t(i - 1)].diameter_m;
      bodies[size_t(i)].shape = c;
    }
    const ContactMonitor::Report rep = contact_.Check(bodies, contact_pairs_);
    T.min_clearance_m = rep.min_distance_m;
    T.closest_a = rep.body_a;
    T.closest_b = rep.body_b;
    T.contact_breach = rep.breach;
  } else {
    T.contact_breach = false;
    T.min_clearance_m = std::numeric_limits<double>::infinity();
  }
}

}  // namespace uvms::plant
