// SPDX-License-Identifier: Apache-2.0
// Plant thrusters, motors and energy integrands (SPEC §5), checked against the paper's
// advance-ratio form of the thrust law, hand-derived advance speeds, an RK4 integration of the
// motor equations against their closed-form solution, and hand-computed power sums.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "uvms_plant/params.hpp"
#include "uvms_plant/propulsion.hpp"

using namespace uvms::plant;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRho = 1025.0;  // SPEC §3.2 [kg/m³]
// SPEC §3.4, typed here from SPEC so that the defaults of PropulsionParams are checked too.
constexpr double kD = 0.05, kCT1 = 0.5, kCT2 = -0.5, kCQ1 = 0.15, kCQ2 = -0.15;

Mat3 Rz(double yaw_rad) {
  return Eigen::AngleAxisd(yaw_rad, Vec3::UnitZ()).toRotationMatrix();
}

// Test-local classic RK4 of the motor [53–55] with zero propeller load.
struct MotorState {
  double I_A{0.0};
  double w_rad_s{0.0};
};
MotorState Rk4Step(const PropulsionParams &p, double V, const MotorState &x, double h) {
  auto f = [&](const MotorState &s) { return MotorRhs(p, V, s.I_A, s.w_rad_s, 0.0); };
  const MotorDerivatives k1 = f(x);
  const MotorDerivatives k2 =
      f({x.I_A + 0.5 * h * k1.current_dot_A_s, x.w_rad_s + 0.5 * h * k1.omega_dot_rad_s2});
  const MotorDerivatives k3 =
      f({x.I_A + 0.5 * h * k2.current_dot_A_s, x.w_rad_s + 0.5 * h * k2.omega_dot_rad_s2});
  const MotorDerivatives k4 = f({x.I_A + h * k3.current_dot_A_s, x.w_rad_s + h * k3.omega_dot_rad_s2});
  return {x.I_A + h / 6.0 *
                      (k1.current_dot_A_s + 2 * k2.current_dot_A_s + 2 * k3.current_dot_A_s +
                       k4.current_dot_A_s),
          x.w_rad_s + h / 6.0 *
                          (k1.omega_dot_rad_s2 + 2 * k2.omega_dot_rad_s2 +
                           2 * k3.omega_dot_rad_s2 + k4.omega_dot_rad_s2)};
}

// δ² = ((Rm/Lm − b/J)/2)² − km²/(Lm·J): sign decides real (> 0) or complex (< 0) eigenvalues
// of the motor's 2×2 system matrix (tr² /4 − det, written without cancellation).
double Delta2(const PropulsionParams &p) {
  const double hd = 0.5 * (p.resistance_ohm / p.inductance_H -
                           p.viscous_friction_Nm_s / p.rotor_inertia_kg_m2);
  return hd * hd -
         p.torque_constant_Nm_A * p.torque_constant_Nm_A / (p.inductance_H * p.rotor_inertia_kg_m2);
}

}  // namespace

TEST_CASE("PropulsionDefaultsAreSpecValues", "[propulsion]") {
  const PropulsionParams p = PaperPlantParams().propulsion;
  CHECK(p.diameter_m == kD);
  CHECK(p.ct1 == kCT1);
  CHECK(p.ct2 == kCT2);
  CHECK(p.cq1 == kCQ1);
  CHECK(p.cq2 == kCQ2);
  CHECK(p.resistance_ohm == 1.0);
  CHECK(p.inductance_H == 1.0);
  CHECK(p.torque_constant_Nm_A == 10.0);
  CHECK(p.viscous_friction_Nm_s == 0.01);
  CHECK(p.rotor_inertia_kg_m2 == 0.01);
  CHECK_NOTHROW(ValidatePropulsionParams(p));
}

TEST_CASE("ThrustAndTorqueEqualAdvanceRatioFormAwayFromZeroSpeed", "[propulsion]") {
  const PropulsionParams p;
  const double kT = kRho * std::pow(kD, 4) / (4 * kPi * kPi);  // [kg/m]
  const double kQ = kRho * std::pow(kD, 5) / (4 * kPi * kPi);  // [kg]
  for (double w : {-400.0, -125.0, -3.0, -0.01, 0.01, 2.5, 125.0, 400.0}) {
    for (double va : {-1.0, -0.3, 0.0, 0.3, 1.0}) {
      const double zeta = 2 * kPi * va / (w * kD);  // advance ratio [47–52]
      const double T_paper = kT * w * std::abs(w) * (kCT2 + kCT1 * zeta);
      const double Q_paper = kQ * w * std::abs(w) * (kCQ2 + kCQ1 * zeta);
      // Scale of the two terms (they can cancel: ζ = 1 gives T = 0).
      const double T_scale = kT * w * w * (std::abs(kCT2) + std::abs(kCT1 * zeta));
      const double Q_scale = kQ * w * w * (std::abs(kCQ2) + std::abs(kCQ1 * zeta));
      INFO("omega = " << w << " rad/s, v_a = " << va << " m/s");
      CHECK(std::abs(ThrustN(p, kRho, w, va) - T_paper) <= 1e-13 * T_scale);
      CHECK(std::abs(TorqueNm(p, kRho, w, va) - Q_paper) <= 1e-13 * Q_scale);
    }
  }
}

TEST_CASE("ZeroSpeedGivesZeroThrustAndTorque", "[propulsion]") {
  const PropulsionParams p;
  for (double va : {-1.0, 0.0, 0.7}) {
    CHECK(ThrustN(p, kRho, 0.0, va) == 0.0);
    CHECK(TorqueNm(p, kRho, 0.0, va) == 0.0);
  }
}

TEST_CASE("PositiveThrustAtNegativeSpeedInStillWater", "[propulsion]") {
  const PropulsionParams p;
  // v_a = 0: T = ρD⁴/(4π²)·CT2·ω·|ω|, CT2 < 0, so ω = −100 rad/s gives
  // T = ρD⁴/(4π²)·0.5·10⁴ > 0 and the law is odd in ω.
  const double T_expected = kRho * std::pow(kD, 4) / (4 * kPi * kPi) * 0.5 * 1e4;
  CHECK(ThrustN(p, kRho, -100.0, 0.0) > 0.0);
  CHECK(ThrustN(p, kRho, -100.0, 0.0) == Approx(T_expected).epsilon(1e-14));
  CHECK(ThrustN(p, kRho, 100.0, 0.0) == Approx(-T_expected).epsilon(1e-14));
  // The torque follows CQ2 < 0 the same way: Q > 0 at ω < 0.
  CHECK(TorqueNm(p, kRho, -100.0, 0.0) > 0.0);
  // Thrust scales with density.
  CHECK(ThrustN(p, 1000.0, -100.0, 0.0) == Approx(T_expected * 1000.0 / kRho).epsilon(1e-14));
}

TEST_CASE("AdvanceSpeedPureSurge", "[propulsion]") {
  const PlantParams pp = PaperPlantParams();
  const ThrusterGeometry &t1 = pp.thrusters[0];  // u = x
  const ThrusterGeometry &t5 = pp.thrusters[4];  // u = z
  const ThrusterGeometry &t7 = pp.thrusters[6];  // u = y
  const Vec3 zero = Vec3::Zero();
  // Level vehicle surging at 2 m/s: the x thrusters see v_a = 2 m/s, the others 0.
  CHECK(AdvanceSpeedMS(t1, Mat3::Identity(), Vec3(2, 0, 0), zero, zero) == Approx(2.0));
  CHECK(AdvanceSpeedMS(t5, Mat3::Identity(), Vec3(2, 0, 0), zero, zero) == Approx(0.0).margin(1e-15));
  // Yawed by +90°: vehicle x points along inertial y, so an inertial velocity (0, 2, 0) is a
  // surge of 2 m/s and (−2, 0, 0) is a sway of +2 m/s (body y = inertial −x).
  const Mat3 R = Rz(kPi / 2);
  CHECK(AdvanceSpeedMS(t1, R, Vec3(0, 2, 0), zero, zero) == Approx(2.0));
  CHECK(AdvanceSpeedMS(t7, R, Vec3(0, 2, 0), zero, zero) == Approx(0.0).margin(1e-15));
  CHECK(AdvanceSpeedMS(t7, R, Vec3(-2, 0, 0), zero, zero) == Approx(2.0));
}

TEST_CASE("AdvanceSpeedPureYawOfOffsetThrusters", "[propulsion]") {
  const PlantParams pp = PaperPlantParams();
  const Vec3 zero = Vec3::Zero();
  const double r = 0.4;  // yaw rate [rad/s]
  const Vec3 w(0, 0, r);
  // ω × a with ω = (0, 0, r): (−r·a_y, r·a_x, 0).
  // Thruster 1, a = (−0.5, 0.5, 0.5), u = x: v_a = −r·a_y = −0.5·r.
  CHECK(AdvanceSpeedMS(pp.thrusters[0], Mat3::Identity(), zero, w, zero) == Approx(-0.5 * r));
  // Thruster 2, a = (−0.5, −0.5, 0.5), u = x: v_a = +0.5·r.
  CHECK(AdvanceSpeedMS(pp.thrusters[1], Mat3::Identity(), zero, w, zero) == Approx(0.5 * r));
  // Thruster 7, a = (0.1, 0, 0.5), u = y: v_a = r·a_x = 0.1·r.
  CHECK(AdvanceSpeedMS(pp.thrusters[6], Mat3::Identity(), zero, w, zero) == Approx(0.1 * r));
  // Thruster 5, u = z: a yaw moves it horizontally only.
  CHECK(AdvanceSpeedMS(pp.thrusters[4], Mat3::Identity(), zero, w, zero) ==
        Approx(0.0).margin(1e-15));
  // The same yaw rate with the vehicle yawed by any angle: yaw about the vertical commutes with
  // the attitude, so the body-frame result is unchanged.
  CHECK(AdvanceSpeedMS(pp.thrusters[0], Rz(1.1), zero, w, zero) == Approx(-0.5 * r));
  CHECK(AdvanceSpeedMS(pp.thrusters[6], Rz(-2.0), zero, w, zero) == Approx(0.1 * r));
}

TEST_CASE("AdvanceSpeedInAFlow", "[propulsion]") {
  const PlantParams pp = PaperPlantParams();
  const Vec3 zero = Vec3::Zero();
  const Vec3 flow(0.3, 0, 0);  // inertial [m/s]
  // A vehicle at rest in a current along +x moves at −0.3 m/s through the water.
  CHECK(AdvanceSpeedMS(pp.thrusters[0], Mat3::Identity(), zero, zero, flow) == Approx(-0.3));
  // Yawed by +90°: relative velocity (−0.3, 0, 0) inertial = +0.3 along body y.
  CHECK(AdvanceSpeedMS(pp.thrusters[6], Rz(kPi / 2), zero, zero, flow) == Approx(0.3));
  CHECK(AdvanceSpeedMS(pp.thrusters[0], Rz(kPi / 2), zero, zero, flow) ==
        Approx(0.0).margin(1e-15));
  // Moving with the current: no advance speed.
  CHECK(AdvanceSpeedMS(pp.thrusters[0], Mat3::Identity(), flow, zero, flow) == 0.0);
}

TEST_CASE("MotorRhsIsTheSpecEquations", "[propulsion][motor]") {
  const PropulsionParams p;  // Rm = 1, Lm = 1, km = 10, b = 0.01, J = 0.01
  // Lm·İ = V − Rm·I − km·ω = 12 − 2 − 10·0.5 = 5;  J·ω̇ = km·I − b·ω − Q = 20 − 0.005 − 0.3.
  const MotorDerivatives d = MotorRhs(p, 12.0, 2.0, 0.5, 0.3);
  CHECK(d.current_dot_A_s == Approx(5.0));
  CHECK(d.omega_dot_rad_s2 == Approx((20.0 - 0.005 - 0.3) / 0.01));
}

TEST_CASE("MotorStepResponseMatchesRk4", "[propulsion][motor]") {
  PropulsionParams paper;  // λ = −1 ± 100i: complex pair
  PropulsionParams real_roots;  // Rm/Lm = 100, b/J = 1, km²/(Lm·J) = 100: δ² = 49.5² − 100 > 0
  real_roots.inductance_H = 0.01;
  real_roots.torque_constant_Nm_A = 0.1;
  PropulsionParams near_repeated;  // δ² = 49.5² − km²/(Lm·J) ≈ 0 for km = 0.495
  near_repeated.inductance_H = 0.01;
  near_repeated.torque_constant_Nm_A = 0.495;
  REQUIRE(Delta2(paper) < 0.0);
  REQUIRE(Delta2(real_roots) > 0.0);
  REQUIRE(std::abs(Delta2(near_repeated)) < 1e-9);

  const double V = 10.0;  // step [V]
  const double h = 1e-4;  // RK4 step [s]
  const std::vector<double> times = {0.001, 0.01, 0.05, 0.2, 1.0, 3.0};
  for (const PropulsionParams &p : {paper, real_roots, near_repeated}) {
    INFO("km = " << p.torque_constant_Nm_A << ", Lm = " << p.inductance_H);
    // The tolerance is relative to the largest |I| and |ω| reached so far on the RK4 path.
    double I_scale = 0.0, w_scale = 0.0;
    MotorState x;
    double t = 0.0;
    long step = 0;
    for (double t_check : times) {
      const long n_to = std::lround(t_check / h);
      for (; step < n_to; ++step) {
        x = Rk4Step(p, V, x, h);
        I_scale = std::max(I_scale, std::abs(x.I_A));
        w_scale = std::max(w_scale, std::abs(x.w_rad_s));
      }
      t = step * h;
      const auto [I_ref, w_ref] = LinearMotorStepResponse(p, V, t);
      INFO("t = " << t << " s: RK4 (" << x.I_A << ", " << x.w_rad_s << "), closed form ("
                  << I_ref << ", " << w_ref << ")");
      // RK4 global error ~ t·|λ|⁵·h⁴/120 ≤ 3·100⁵·1e-16/120 ≈ 3e-8 of the scale here.
      CHECK(std::abs(x.I_A - I_ref) <= 1e-7 * I_scale);
      CHECK(std::abs(x.w_rad_s - w_ref) <= 1e-7 * w_scale);
    }
  }
}

TEST_CASE("MotorStepResponseReachesAnalyticSteadyState", "[propulsion][motor]") {
  const PropulsionParams p;
  const double V = 10.0;
  // Steady state of [53–55] with Q = 0: 0 = V − Rm·I − km·ω, 0 = km·I − b·ω
  // ⇒ I∞ = b·V/(Rm·b + km²), ω∞ = km·V/(Rm·b + km²).
  const double den = p.resistance_ohm * p.viscous_friction_Nm_s +
                     p.torque_constant_Nm_A * p.torque_constant_Nm_A;
  const double I_inf = p.viscous_friction_Nm_s * V / den;
  const double w_inf = p.torque_constant_Nm_A * V / den;
  // The transient decays as e^{−t} (Re λ = −1 for the paper's motor); after 25 s it is
  // e^{−25} ≈ 1.4e-11 of its initial size.
  MotorState x;
  const double h = 1e-4;
  for (long k = 0; k < 250000; ++k) x = Rk4Step(p, V, x, h);
  CHECK(x.I_A == Approx(I_inf).epsilon(1e-8));
  CHECK(x.w_rad_s == Approx(w_inf).epsilon(1e-8));
  const auto [I_cf, w_cf] = LinearMotorStepResponse(p, V, 25.0);
  CHECK(I_cf == Approx(I_inf).epsilon(1e-8));
  CHECK(w_cf == Approx(w_inf).epsilon(1e-8));
  // From rest at t = 0.
  const auto [I0, w0] = LinearMotorStepResponse(p, V, 0.0);
  CHECK(std::abs(I0) < 1e-15);
  CHECK(std::abs(w0) < 1e-15);
}

TEST_CASE("MotorStepResponseRejectsBadInput", "[propulsion][motor]") {
  PropulsionParams p;
  CHECK_THROWS_AS(LinearMotorStepResponse(p, 10.0, -1.0), std::invalid_argument);
  CHECK_THROWS_AS(LinearMotorStepResponse(p, std::nan(""), 1.0), std::invalid_argument);
  p.inductance_H = 0.0;
  CHECK_THROWS_WITH(LinearMotorStepResponse(p, 10.0, 1.0), Catch::Contains("inductance_H"));
  PropulsionParams q;
  q.viscous_friction_Nm_s = -0.1;
  CHECK_THROWS_WITH(ValidatePropulsionParams(q), Catch::Contains("viscous_friction_Nm_s"));
}

TEST_CASE("EnergyRatesDoNotCreditRegeneration", "[propulsion][energy]") {
  // V·I per thruster: 20, −5, −12, 0 W.
  const std::vector<double> V = {10.0, -5.0, 3.0, 0.0};
  const std::vector<double> I = {2.0, 1.0, -4.0, 7.0};
  const EnergyRates r = ThrusterEnergyRates(V, I);
  CHECK(r.thruster_draw_W == 20.0);
  CHECK(r.thruster_signed_W == 3.0);
  // Eigen overload agrees.
  const Eigen::VectorXd Ve = Eigen::Map<const Eigen::VectorXd>(V.data(), 4);
  const Eigen::VectorXd Ie = Eigen::Map<const Eigen::VectorXd>(I.data(), 4);
  const EnergyRates re = ThrusterEnergyRates(Ve, Ie);
  CHECK(re.thruster_draw_W == r.thruster_draw_W);
  CHECK(re.thruster_signed_W == r.thruster_signed_W);
  // All thrusters regenerating: nothing drawn, negative signed power.
  const EnergyRates g = ThrusterEnergyRates(std::vector<double>{5, -5}, std::vector<double>{-1, 2});
  CHECK(g.thruster_draw_W == 0.0);
  CHECK(g.thruster_signed_W == -15.0);
  CHECK_THROWS_AS(ThrusterEnergyRates(std::vector<double>{1, 2}, std::vector<double>{1}),
                  std::invalid_argument);
}

TEST_CASE("EnergyDrawNeverNegativeAndBoundsSignedPower", "[propulsion][energy]") {
  std::mt19937_64 gen(20140301);
  std::uniform_real_distribution<double> u(-100.0, 100.0);
  for (int trial = 0; trial < 1000; ++trial) {
    std::vector<double> V(8), I(8);
    double regen_W = 0.0;  // Σ max(−V·I, 0)
    for (int j = 0; j < 8; ++j) {
      V[j] = u(gen);
      I[j] = u(gen) / 10.0;
      regen_W += std::max(-V[j] * I[j], 0.0);
    }
    const EnergyRates r = ThrusterEnergyRates(V, I);
    REQUIRE(r.thruster_draw_W >= 0.0);
    REQUIRE(r.thruster_draw_W >= r.thruster_signed_W);
    // draw − signed = what regeneration would have returned.
    REQUIRE(r.thruster_draw_W - r.thruster_signed_W == Approx(regen_W).margin(1e-9));
  }
}

TEST_CASE("ManipulatorPowerSumsAbsoluteJointPowers", "[propulsion][energy]") {
  // |1·(−1)| + |(−2)·(−1)| + |3·2| = 1 + 2 + 6.
  CHECK(ManipulatorPowerW(std::vector<double>{1, -2, 3}, std::vector<double>{-1, -1, 2}) == 9.0);
  Eigen::VectorXd tau(2), qd(2);
  tau << -4.0, 0.5;
  qd << 0.25, -2.0;
  CHECK(ManipulatorPowerW(tau, qd) == 2.0);
  CHECK_THROWS_AS(ManipulatorPowerW(std::vector<double>{1}, std::vector<double>{1, 2}),
                  std::invalid_argument);
}
