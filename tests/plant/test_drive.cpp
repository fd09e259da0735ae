// SPDX-License-Identifier: Apache-2.0
// The two motor drives of SPEC §5 "Motors" (docs/MODEL.md §5), checked against closed forms and
// independent integrations:
// - current drive: the plant's current is I*_k + İ*_k·(t − t_k) exactly, and ω, the electrical
//   energy ∫max(V·I, 0) dt and ∫V·I dt match an RK4 + Simpson integration written here;
// - the propulsive (actuator-disk) energy matches momentum theory and a trapezoid quadrature;
// - a shaft-speed step with the firmware's loops (SPEC §7.4) settles with the KA/KB time
//   constants in the current drive (closed form below) and about 20× slower in the voltage
//   drive (an independent discrete-time simulation of the linear motor);
// - a thrust ramp through the firmware's loops and the plant's motor lags by the closed form
//   τ = (KB + b/J)/(KA·KB) of uvms_thruster_ramp_lag_s, and the feedforward lead
//   (uvms_ff_lead) by L cuts that lag to τ − L (docs/MODEL.md §7.5).
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "plant_test_util.hpp"
#include "uvms/feedforward.h"
#include "uvms/thruster.h"
#include "uvms_plant/propulsion.hpp"

using namespace plant_test;

namespace {

// A plant whose thrusters turn but push nothing (thrust factor 0): the vehicle and the arm stay
// at rest, so each motor sees v_a = 0 and the load Q(ω) of SPEC §5 alone.
struct StillVehicle {
  Plant plant;
  explicit StillVehicle(MotorDrive drive) : plant(Params(drive)) { plant.Reset(Stowed()); }
  static PlantParams Params(MotorDrive drive) {
    PlantParams pp = PaperPlantParams();
    pp.propulsion.drive = drive;
    pp.contact.enabled = false;
    return pp;
  }
  PlantInputs Inputs() const {
    PlantInputs in = Idle(plant);
    in.thrust_factor.assign(in.motor_voltage_V.size(), 0.0);
    return in;
  }
};

// SPEC §5 at v_a = 0, written out here: Q = ρD⁵/(4π²)·CQ2·ω|ω| [N·m].
double LoadTorqueNm(const PropulsionParams &p, double rho, double w) {
  return rho * std::pow(p.diameter_m, 5) / (4 * M_PI * M_PI) * p.cq2 * w * std::abs(w);
}

struct Reference {
  double omega_rad_s{0}, draw_J{0}, signed_J{0};
};

// One motor over one tick of the current drive: RK4 on J·ω̇ = km·I(t) − b·ω − Q(ω) with
// I(t) = I0 + İ·τ, and Simpson's rule on P(τ) = V·I, V = Rm·I + Lm·İ + km·ω [53].
Reference CurrentDriveTick(const PropulsionParams &p, double rho, double w0, double I0,
                           double Idot, double dt, int steps /* even */) {
  const double h = dt / steps;
  auto I = [&](double tau) { return I0 + Idot * tau; };
  auto f = [&](double tau, double w) {
    return (p.torque_constant_Nm_A * I(tau) - p.viscous_friction_Nm_s * w - LoadTorqueNm(p, rho, w)) /
           p.rotor_inertia_kg_m2;
  };
  auto power = [&](double tau, double w) {
    const double V = p.resistance_ohm * I(tau) + p.inductance_H * Idot + p.torque_constant_Nm_A * w;
    return V * I(tau);
  };
  std::vector<double> w(size_t(steps + 1));
  w[0] = w0;
  for (int i = 0; i < steps; ++i) {
    const double t = i * h, y = w[size_t(i)];
    const double k1 = f(t, y), k2 = f(t + h / 2, y + h / 2 * k1), k3 = f(t + h / 2, y + h / 2 * k2),
                 k4 = f(t + h, y + h * k3);
    w[size_t(i + 1)] = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  Reference r;
  r.omega_rad_s = w.back();
  for (int i = 0; i < steps; i += 2) {
    const double a = power(i * h, w[size_t(i)]), m = power((i + 1) * h, w[size_t(i + 1)]),
                 b = power((i + 2) * h, w[size_t(i + 2)]);
    r.signed_J += h / 3 * (a + 4 * m + b);
    r.draw_J += h / 3 * (std::max(a, 0.0) + 4 * std::max(m, 0.0) + std::max(b, 0.0));
  }
  return r;
}

}  // namespace

TEST_CASE("CurrentDriveFollowsTheCommandedRampAndItsEnergyMatchesAQuadratureOfVI", "[plant][drive]") {
  StillVehicle sv(MotorDrive::kCurrent);
  const PropulsionParams &p = sv.plant.params().propulsion;
  const double rho = sv.plant.params().env.density_kg_m3;
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> cur(-3.0, 3.0), rate(-40.0, 40.0);
  std::vector<double> w(8, 0.0);
  double draw_J = 0, signed_J = 0;
  for (int k = 0; k < 12; ++k) {
    PlantInputs in = sv.Inputs();
    for (size_t j = 0; j < 8; ++j) {
      in.motor_current_cmd_A[j] = cur(rng);  // the power stage sets I(t_k) = I*_k, jump or not
      in.motor_current_rate_A_s[j] = rate(rng);
    }
    REQUIRE(sv.plant.Step(in, kTick).ok());
    const Truth &T = sv.plant.truth();
    for (size_t j = 0; j < 8; ++j) {
      INFO("tick " << k << ", motor " << j + 1);
      // exactly the commanded ramp at the tick's end (the same double operations)
      CHECK(T.motor_current_A[j] == in.motor_current_cmd_A[j] + in.motor_current_rate_A_s[j] * kTick);
      const Reference r = CurrentDriveTick(p, rho, w[j], in.motor_current_cmd_A[j],
                                           in.motor_current_rate_A_s[j], kTick, 2000);
      // CVODE's rel_tol is 1e-8 per step; 1e-6 leaves room for any valid step sequence (the
      // energy states share the error norm) while a wrong current law moves ω by percents.
      CHECK(T.motor_speed_rad_s[j] == Approx(r.omega_rad_s).epsilon(1e-6).margin(1e-9));
      w[j] = T.motor_speed_rad_s[j];
      draw_J += r.draw_J;
      signed_J += r.signed_J;
      // [53] at the tick's end
      CHECK(T.motor_voltage_V[j] == Approx(p.resistance_ohm * T.motor_current_A[j] +
                                           p.inductance_H * in.motor_current_rate_A_s[j] +
                                           p.torque_constant_Nm_A * T.motor_speed_rad_s[j]));
    }
  }
  const Truth &T = sv.plant.truth();
  CHECK(signed_J < draw_J);  // some power was regenerative: the max(·, 0) mattered
  CHECK(T.thruster_energy_J == Approx(draw_J).epsilon(2e-6));
  CHECK(T.thruster_energy_signed_J == Approx(signed_J).epsilon(2e-6).margin(1e-6));
  CHECK(T.v0_m_s.norm() < 1e-12);  // nothing pushed the vehicle: v_a stayed 0
}

TEST_CASE("PropulsivePowerIsThrustTimesInducedVelocity", "[plant][drive]") {
  // Momentum theory: a disk of area A_d making thrust T at rest accelerates the water by the
  // induced velocity v_i = √(T/(2ρA_d)); the ideal power is T·v_i = T^(3/2)/√(2ρA_d).
  const PropulsionParams p;
  const double rho = 1025.0, A = M_PI * p.diameter_m * p.diameter_m / 4;
  const std::vector<double> thrust_N = {1.0, -2.5, 0.0, 4.0};
  double expect_W = 0;
  for (double T : thrust_N) expect_W += std::abs(T) * std::sqrt(std::abs(T) / (2 * rho * A));
  CHECK(PropulsivePowerW(p, rho, thrust_N) == Approx(expect_W).epsilon(1e-14));
  CHECK(PropulsivePowerW(p, 1025.0, {1.0}) == Approx(0.498430).epsilon(1e-5));  // 1/√(2·1025·A_d)
  CHECK(PropulsivePowerW(p, 0.0, thrust_N) == 0.0);  // no fluid: no thrust is possible
}

TEST_CASE("PropulsiveEnergyIsTheTimeIntegralOfTheProducedThrustsPower", "[plant][drive]") {
  // Thrusting plant, constant current commands; the plant's E_p against a trapezoid sum of
  // |T|^(3/2)/√(2ρA_d) over its own produced thrusts at 1 ms steps (second-order accurate).
  PlantParams pp = StillVehicle::Params(MotorDrive::kCurrent);
  Plant plant(pp);
  plant.Reset(Stowed());
  PlantInputs in = Idle(plant);
  in.motor_current_cmd_A = {0.3, -0.2, 0.1, 0.0, 0.25, -0.25, 0.05, -0.1};
  const double rho = pp.env.density_kg_m3, A = M_PI * std::pow(pp.propulsion.diameter_m, 2) / 4;
  auto power = [&](const std::vector<double> &T) {
    double s = 0;
    for (double t : T) s += std::pow(std::abs(t), 1.5) / std::sqrt(2 * rho * A);
    return s;
  };
  const double dt = 1e-3;
  double prev = power(plant.truth().thrust_N), E = 0;
  for (int k = 0; k < 2000; ++k) {
    REQUIRE(plant.Step(in, dt).ok());
    const double now = power(plant.truth().thrust_N);
    E += 0.5 * dt * (prev + now);
    prev = now;
  }
  REQUIRE(E > 1e-3);
  CHECK(plant.truth().propulsive_energy_J == Approx(E).epsilon(1e-5));
}

namespace {

// The firmware's thruster loops (SPEC §7.4) on the plant's motor 1: one tick with the desired
// thrust T̂, its motor command computed from the measured ω and I, the plant stepped with it
// through its drive and the controller's integrated current command I_cmd advanced.
struct Motor1Loop {
  StillVehicle sv;
  uvms_thruster_params_t fw{};
  double rho, I_cmd{0};
  explicit Motor1Loop(MotorDrive drive) : sv(drive), rho(sv.plant.params().env.density_kg_m3) {
    uvms_thruster_params_paper(&fw);
  }
  double omega_rad_s() const { return sv.plant.truth().motor_speed_rad_s[0]; }
  uvms_motor_cmd_t Command(uvms_real_t thrust_N) const {
    const Truth &T = sv.plant.truth();
    uvms_motor_cmd_t mc;
    REQUIRE(uvms_motor_control(&fw, uvms_real_t(rho), thrust_N, 0, uvms_real_t(T.motor_speed_rad_s[0]),
                               uvms_real_t(T.motor_current_A[0]), &mc) == UVMS_OK);
    return mc;
  }
  void Step(const uvms_motor_cmd_t &mc) {
    PlantInputs in = sv.Inputs();
    in.motor_voltage_V[0] = mc.voltage_V;
    in.motor_current_cmd_A[0] = I_cmd;
    in.motor_current_rate_A_s[0] = mc.current_dot_des_A_s;
    REQUIRE(sv.plant.Step(in, kTick).ok());
    I_cmd += mc.current_dot_des_A_s * kTick;
  }
};

// A step of T̂ through Motor1Loop; returns the time [s] at which ω first reaches 63 % of the
// desired speed ω̂.
double SpeedStepRiseTime(MotorDrive drive, double thrust_N, double horizon_s) {
  Motor1Loop loop(drive);
  for (int k = 0; k * kTick < horizon_s; ++k) {
    const uvms_motor_cmd_t mc = loop.Command(uvms_real_t(thrust_N));
    if (std::abs(loop.omega_rad_s()) >= 0.632 * std::abs(double(mc.omega_des_rad_s))) return k * kTick;
    loop.Step(mc);
  }
  return INFINITY;
}

// The voltage drive's loop as a linear discrete-time system, independently of the plant: per
// tick the controller sets V = Rm·I + Lm·KB·(Î − I) + km·ω with Î = (J·KA·(ω̂ − ω) + b·ω)/km
// (Q neglected: |Q| < 1e-4·b·|ω| at this speed), and the motor Lm·İ = V − Rm·I − km·ω,
// J·ω̇ = km·I − b·ω runs open loop over the tick (RK4, 300 steps).
double LinearVoltageDriveRiseTime(double w_des, double horizon_s) {
  const double Rm = 1, Lm = 1, km = 10, b = 0.01, J = 0.01, KA = 5, KB = 5;
  double I = 0, w = 0;
  for (int k = 0; k * kTick < horizon_s; ++k) {
    if (std::abs(w) >= 0.632 * std::abs(w_des)) return k * kTick;
    const double I_des = (J * KA * (w_des - w) + b * w) / km;
    const double V = Rm * I + Lm * KB * (I_des - I) + km * w;
    const int n = 300;
    const double h = kTick / n;
    auto dI = [&](double i, double ww) { return (V - Rm * i - km * ww) / Lm; };
    auto dw = [&](double i, double ww) { return (km * i - b * ww) / J; };
    for (int s = 0; s < n; ++s) {
      const double a1 = dI(I, w), b1 = dw(I, w);
      const double a2 = dI(I + h / 2 * a1, w + h / 2 * b1), b2 = dw(I + h / 2 * a1, w + h / 2 * b1);
      const double a3 = dI(I + h / 2 * a2, w + h / 2 * b2), b3 = dw(I + h / 2 * a2, w + h / 2 * b2);
      const double a4 = dI(I + h * a3, w + h * b3), b4 = dw(I + h * a3, w + h * b3);
      I += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
      w += h / 6 * (b1 + 2 * b2 + 2 * b3 + b4);
    }
  }
  return INFINITY;
}

}  // namespace

TEST_CASE("ASpeedStepSettlesWithKaKbInTheCurrentDriveAndTwentyTimesSlowerInTheVoltageDrive",
          "[plant][drive]") {
  // A small thrust (1e-4 N → |ω̂| ≈ 1.1 rad/s) keeps the propeller torque negligible (Q ≈ 0),
  // so the current drive's loop is linear: J·ω̇ = km·I − b·ω and the current loop
  // km·İ = KB·(J·KA·(ω̂ − ω) + b·ω − km·I) = KB·(J·KA·(ω̂ − ω) − J·ω̇) give
  //   J·ω̈ = km·İ − b·ω̇  ⇒  ω̈ + (KB + b/J)·ω̇ + KA·KB·ω = KA·KB·ω̂:
  // ω_n = √(KA·KB) = 5 rad/s, ζ = (KB + b/J)/(2·ω_n) = 6/10 = 0.6. Its unit step response
  // 1 − e^(−3t)·(cos(4t) + 0.75·sin(4t)) crosses 1 − 1/e at t = 0.3275 s. The controller
  // samples every 0.03 s, so the first tick at or past it is 0.33 s (one tick of margin for
  // the discrete loop).
  const double t_current = SpeedStepRiseTime(MotorDrive::kCurrent, 1e-4, 3.0);
  INFO("current drive: 63 % at " << t_current << " s");
  CHECK(t_current == Approx(0.33).margin(0.031));
  // The voltage drive: the same loops, the held voltage and the motor's own −1 ± 100i rad/s
  // mode (SPEC §5): against the independent linear simulation, to one tick.
  const double w_des = std::sqrt(1e-4 / (0.5 * 1025 * std::pow(0.05, 4) / (4 * M_PI * M_PI)));
  const double t_linear = LinearVoltageDriveRiseTime(-w_des, 30.0);
  const double t_voltage = SpeedStepRiseTime(MotorDrive::kVoltage, 1e-4, 30.0);
  INFO("voltage drive: 63 % at " << t_voltage << " s (linear model " << t_linear << " s)");
  CHECK(std::abs(t_voltage - t_linear) <= kTick + 1e-9);
  CHECK(t_voltage > 3.0);
  CHECK(t_voltage < 10.0);
  CHECK(t_voltage / t_current > 10.0);
}

namespace {

// A thrust ramp T̂(t) = T0 + rate·t requested of motor 1 through the firmware's loops (SPEC
// §7.4) in the current drive, T̂ led by lead_s with uvms_ff_lead as the controller leads its
// feedforward; returns the produced thrust's lag behind T̂ at the end [s]: (T̂ − T)/rate.
double ThrustRampLagS(double lead_s, double T0_N, double rate_N_s, double horizon_s) {
  Motor1Loop loop(MotorDrive::kCurrent);
  uvms_real_t prev = 0, slope = 0;
  const int ticks = int(std::lround(horizon_s / kTick));
  for (int k = 0; k < ticks; ++k) {
    const uvms_real_t T_hat = uvms_real_t(T0_N + rate_N_s * k * kTick);
    uvms_real_t led = T_hat;
    if (k > 0)
      REQUIRE(uvms_ff_lead(1, &T_hat, &prev, uvms_real_t(kTick), uvms_real_t(lead_s), &slope, k > 1,
                           &led) == UVMS_OK);
    prev = T_hat;
    loop.Step(loop.Command(led));
  }
  const double T_end = ThrustN(loop.sv.plant.params().propulsion, loop.rho, loop.omega_rad_s(), 0.0);
  return (T0_N + rate_N_s * ticks * kTick - T_end) / rate_N_s;
}

}  // namespace

TEST_CASE("AThrustRampLagsByTheChainsClosedFormAndTheLeadCutsThatLagByItsOwnLength",
          "[plant][drive][lead]") {
  // The closed form of thruster.h for the paper's motor: (KB + b/J)/(KA·KB) = (5 + 1)/25.
  uvms_thruster_params_t fw;
  uvms_thruster_params_paper(&fw);
  const double tau = double(uvms_thruster_ramp_lag_s(&fw));
  CHECK(tau == Approx(0.24).epsilon(1e-6));
  // A slow ramp (2 → 6 N over 8 s: ω̂ ≈ 157 → 272 rad/s) after the loop's transient
  // (e^(−3t): 1e-10 at 8 s). What the closed form neglects: dQ/dω (≤ 7 % of b here, +0.003 s)
  // and the curvature of ω̂ = √(T/|c1|) (T is not linear in ω): 3 % of τ covers both.
  const double lag0 = ThrustRampLagS(0.0, 2.0, 0.5, 8.0);
  INFO("lag without lead " << lag0 << " s, closed form " << tau << " s");
  CHECK(lag0 == Approx(tau).epsilon(0.03));
  // Led by L, the chain sees T̂ L ahead: the lag is τ − L (the predicted factor (τ − L)/τ).
  for (double frac : {0.5, 1.0}) {
    const double lagL = ThrustRampLagS(frac * tau, 2.0, 0.5, 8.0);
    INFO("lead " << frac << "·τ: lag " << lagL << " s, predicted " << (1 - frac) * lag0 << " s");
    CHECK(std::abs(lagL - (1 - frac) * lag0) <= 0.03 * tau);
  }
}
