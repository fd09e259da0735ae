// SPDX-License-Identifier: Apache-2.0
// propulsion.cpp: thrusters, motors and energy integrands of the truth model (SPEC §5).
#include "uvms_plant/propulsion.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace uvms::plant {
namespace {

constexpr double kPi = 3.14159265358979323846;

void RequireFinite(double v, const char *name) {
  if (!std::isfinite(v)) {
    std::ostringstream os;
    os << "PropulsionParams: " << name << " must be finite (got " << v << ")";
    throw std::invalid_argument(os.str());
  }
}

void RequirePositive(double v, const char *name) {
  RequireFinite(v, name);
  if (!(v > 0.0)) {
    std::ostringstream os;
    os << "PropulsionParams: " << name << " must be > 0 (got " << v << ")";
    throw std::invalid_argument(os.str());
  }
}

void RequireSameSize(Eigen::Index a, Eigen::Index b, const char *what) {
  if (a != b) {
    std::ostringstream os;
    os << what << ": size mismatch (" << a << " vs " << b << ")";
    throw std::invalid_argument(os.str());
  }
}

}  // namespace

void ValidatePropulsionParams(const PropulsionParams &p) {
  RequirePositive(p.diameter_m, "diameter_m");
  RequireFinite(p.ct1, "ct1");
  RequireFinite(p.ct2, "ct2");
  RequireFinite(p.cq1, "cq1");
  RequireFinite(p.cq2, "cq2");
  RequirePositive(p.resistance_ohm, "resistance_ohm");
  RequirePositive(p.inductance_H, "inductance_H");
  RequirePositive(p.torque_constant_Nm_A, "torque_constant_Nm_A");
  RequireFinite(p.viscous_friction_Nm_s, "viscous_friction_Nm_s");
  if (p.viscous_friction_Nm_s < 0.0) {
    std::ostringstream os;
    os << "PropulsionParams: viscous_friction_Nm_s must be >= 0 (got " << p.viscous_friction_Nm_s
       << ")";
    throw std::invalid_argument(os.str());
  }
  RequirePositive(p.rotor_inertia_kg_m2, "rotor_inertia_kg_m2");
}

PropellerCoeffs PropellerCoeffsOf(const PropulsionParams &p, double density_kg_m3) {
  // SPEC §5's laws ρ·D^n/(4π²)·(c2·ω·|ω| + c1·(2π·v_a/D)·|ω|), n = 4 (thrust) or 5 (torque).
  const double D = p.diameter_m;
  const double thrust_scale = density_kg_m3 * D * D * D * D / (4.0 * kPi * kPi);  // [kg/m]
  const double torque_scale = thrust_scale * D;                                   // [kg]
  PropellerCoeffs c;
  c.thrust_ww = thrust_scale * p.ct2;
  c.thrust_wv = thrust_scale * p.ct1 * (2.0 * kPi / D);
  c.torque_ww = torque_scale * p.cq2;
  c.torque_wv = torque_scale * p.cq1 * (2.0 * kPi / D);
  return c;
}

double ThrustN(const PropulsionParams &p, double density_kg_m3, double omega_rad_s,
               double advance_speed_m_s) {
  return PropellerCoeffsOf(p, density_kg_m3).Thrust(omega_rad_s, advance_speed_m_s);
}

double TorqueNm(const PropulsionParams &p, double density_kg_m3, double omega_rad_s,
                double advance_speed_m_s) {
  return PropellerCoeffsOf(p, density_kg_m3).Torque(omega_rad_s, advance_speed_m_s);
}

double AdvanceSpeedMS(const ThrusterGeometry &g, const Mat3 &R0, const Vec3 &v0_I,
                      const Vec3 &w0_I, const Vec3 &vinf_I) {
  return AdvanceSpeedBodyMS(g, R0.transpose() * (v0_I - vinf_I), R0.transpose() * w0_I);
}

double AdvanceSpeedBodyMS(const ThrusterGeometry &g, const Vec3 &v_rel_B, const Vec3 &w0_B) {
  // [47–52]: velocity of the thruster point relative to the water in vehicle axes, along u.
  return g.direction.dot(v_rel_B + w0_B.cross(g.position_m));
}

MotorDerivatives MotorRhs(const PropulsionParams &p, double voltage_V, double current_A,
                          double omega_rad_s, double load_torque_Nm) {
  return MotorRhs(p, 1.0 / p.inductance_H, 1.0 / p.rotor_inertia_kg_m2, voltage_V, current_A,
                  omega_rad_s, load_torque_Nm);
}

MotorDerivatives MotorRhs(const PropulsionParams &p, double inv_inductance_1_H,
                          double inv_rotor_inertia_1_kg_m2, double voltage_V, double current_A,
                          double omega_rad_s, double load_torque_Nm) {
  MotorDerivatives d;
  // [53] Lm·İ = V − Rm·I − km·ω
  d.current_dot_A_s = (voltage_V - p.resistance_ohm * current_A - p.torque_constant_Nm_A * omega_rad_s) *
                      inv_inductance_1_H;
  // [54–55] J·ω̇ = km·I − b·ω − Q
  d.omega_dot_rad_s2 = (p.torque_constant_Nm_A * current_A - p.viscous_friction_Nm_s * omega_rad_s -
                        load_torque_Nm) *
                       inv_rotor_inertia_1_kg_m2;
  return d;
}

EnergyRates ThrusterEnergyRates(const Eigen::Ref<const Eigen::VectorXd> &voltage_V,
                                const Eigen::Ref<const Eigen::VectorXd> &current_A) {
  RequireSameSize(voltage_V.size(), current_A.size(), "ThrusterEnergyRates");
  EnergyRates r;
  for (Eigen::Index j = 0; j < voltage_V.size(); ++j) {
    const double P_W = voltage_V[j] * current_A[j];
    r.thruster_signed_W += P_W;
    r.thruster_draw_W += std::max(P_W, 0.0);  // regeneration is not credited
  }
  return r;
}

EnergyRates ThrusterEnergyRates(const std::vector<double> &voltage_V,
                                const std::vector<double> &current_A) {
  RequireSameSize(static_cast<Eigen::Index>(voltage_V.size()),
                  static_cast<Eigen::Index>(current_A.size()), "ThrusterEnergyRates");
  return ThrusterEnergyRates(
      Eigen::Map<const Eigen::VectorXd>(voltage_V.data(), static_cast<Eigen::Index>(voltage_V.size())),
      Eigen::Map<const Eigen::VectorXd>(current_A.data(), static_cast<Eigen::Index>(current_A.size())));
}

double PropulsivePowerW(const PropulsionParams &p, double density_kg_m3,
                        const std::vector<double> &thrust_N) {
  const double disk_area_m2 = kPi * p.diameter_m * p.diameter_m / 4.0;  // A_d
  const double denom = std::sqrt(2.0 * density_kg_m3 * disk_area_m2);   // [√(kg/m)]
  if (!(denom > 0.0)) return 0.0;
  double sum = 0.0;
  for (double T : thrust_N) sum += std::abs(T) * std::sqrt(std::abs(T));  // |T|^(3/2)
  return sum / denom;
}

double ManipulatorPowerW(const Eigen::Ref<const Eigen::VectorXd> &tau_Nm,
                         const Eigen::Ref<const Eigen::VectorXd> &qdot_rad_s) {
  RequireSameSize(tau_Nm.size(), qdot_rad_s.size(), "ManipulatorPowerW");
  double P_W = 0.0;
  for (Eigen::Index i = 0; i < tau_Nm.size(); ++i) P_W += std::abs(tau_Nm[i] * qdot_rad_s[i]);
  return P_W;
}

double ManipulatorPowerW(const std::vector<double> &tau_Nm, const std::vector<double> &qdot_rad_s) {
  RequireSameSize(static_cast<Eigen::Index>(tau_Nm.size()),
                  static_cast<Eigen::Index>(qdot_rad_s.size()), "ManipulatorPowerW");
  return ManipulatorPowerW(
      Eigen::Map<const Eigen::VectorXd>(tau_Nm.data(), static_cast<Eigen::Index>(tau_Nm.size())),
      Eigen::Map<const Eigen::VectorXd>(qdot_rad_s.data(),
                                        static_cast<Eigen::Index>(qdot_rad_s.size())));
}

std::pair<double, double> LinearMotorStepResponse(const PropulsionParams &p, double voltage_V,
                                                  double t_s) {
  ValidatePropulsionParams(p);
  if (!std::isfinite(voltage_V) || !std::isfinite(t_s) || t_s < 0.0) {
    std::ostringstream os;
    os << "LinearMotorStepResponse: need finite V and finite t >= 0 (got V = " << voltage_V
       << ", t = " << t_s << ")";
    throw std::invalid_argument(os.str());
  }
  const double Rm = p.resistance_ohm, Lm = p.inductance_H, km = p.torque_constant_Nm_A;
  const double b = p.viscous_friction_Nm_s, J = p.rotor_inertia_kg_m2;

  // x = (I, ω): ẋ = A·x + (V/Lm, 0) with A = [[a11, a12], [a21, a22]] ([53–55], Q = 0).
  const double a11 = -Rm / Lm, a12 = -km / Lm, a21 = km / J, a22 = -b / J;
  // Steady state: A·x∞ = −(V/Lm, 0), det(A) = (Rm·b + km²)/(Lm·J) > 0.
  const double den = Rm * b + km * km;  // [Ω·N·m·s + (N·m/A)²]
  const double I_inf_A = b * voltage_V / den;
  const double w_inf_rad_s = km * voltage_V / den;
  // Error e = x − x∞ starts at −x∞ and obeys ė = A·e.
  const double e0_I = -I_inf_A, e0_w = -w_inf_rad_s;

  // Eigenvalues s ± δ: s = tr(A)/2, δ² = s² − det(A) = ((a11 − a22)/2)² + a12·a21 (the form
  // without the cancellation of s² − det). N = A − s·I₂ has N² = δ²·I₂.
  const double s = 0.5 * (a11 + a22);
  const double half_diff = 0.5 * (a11 - a22);
  const double delta2 = half_diff * half_diff + a12 * a21;
  const double n11 = half_diff, n12 = a12, n21 = a21, n22 = -half_diff;

  // exp(A·t) = ec·I₂ + eh·N with ec = e^{st}·c(t), eh = e^{st}·h(t) (see the header).
  double ec = 0.0, eh = 0.0;
  if (delta2 > 0.0) {  // two real roots λ1,2 = s ± δ (both < 0 since det > 0, tr < 0)
    const double delta = std::sqrt(delta2);
    const double e1 = std::exp((s + delta) * t_s), e2 = std::exp((s - delta) * t_s);
    ec = 0.5 * (e1 + e2);
    // sinh(δt)/δ: direct for small δt (no cancellation); from the exponentials otherwise
    // (no overflow of sinh, and e2/e1 ≤ e⁻² so no cancellation either).
    const double x = delta * t_s;
    eh = (x < 1.0) ? std::exp(s * t_s) * (x == 0.0 ? t_s : std::sinh(x) / delta)
                   : (e1 - e2) / (2.0 * delta);
  } else if (delta2 < 0.0) {  // complex pair s ± i·ω_d
    const double wd = std::sqrt(-delta2);
    const double es = std::exp(s * t_s);
    ec = es * std::cos(wd * t_s);
    eh = es * std::sin(wd * t_s) / wd;
  } else {  // repeated root s: exp(A·t) = e^{st}·(I₂ + t·N)
    const double es = std::exp(s * t_s);
    ec = es;
    eh = es * t_s;
  }
  const double I_A = I_inf_A + ec * e0_I + eh * (n11 * e0_I + n12 * e0_w);
  const double w_rad_s = w_inf_rad_s + ec * e0_w + eh * (n21 * e0_I + n22 * e0_w);
  return {I_A, w_rad_s};
}

}  // namespace uvms::plant
