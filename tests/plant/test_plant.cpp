// The truth model as a whole (SPEC §5) against conservation laws and analytic solutions.
#include <catch2/catch.hpp>

#include <cmath>

#include "plant_test_util.hpp"
#include "uvms_plant/plant.hpp"
#include "uvms_plant/propulsion.hpp"

using namespace uvms::plant;

namespace {
using namespace plant_test;

// Total angular momentum about the inertial origin and linear momentum, from the truth state
// (vehicle + links + payload; rigid masses only, meaningful when ρ = 0).
std::pair<Vec3, Vec3> Momenta(const Plant &p) {
  const Truth &T = p.truth();
  const ArmModel &m = p.model();
  BaseState b;
  b.r0_m = T.r0_m;
  b.R0 = T.attitude.toRotationMatrix();
  b.v0_m_s = T.v0_m_s;
  b.w0_rad_s = T.w0_rad_s;
  ArmKinematics k;
  std::vector<double> zero(size_t(m.n), 0.0);
  ComputeArmKinematics(m, b, T.q_rad.data(), T.qd_rad_s.data(), zero.data(), k);
  const Mat3 I0 = b.R0 * m.vehicle.inertia_kg_m2.asDiagonal() * b.R0.transpose();
  Vec3 L = I0 * b.w0_rad_s + m.vehicle.mass_kg * b.r0_m.cross(b.v0_m_s);
  Vec3 P = m.vehicle.mass_kg * b.v0_m_s;
  for (int i = 1; i <= m.n; ++i) {
    const LinkParams &l = m.link[size_t(i - 1)];
    const Mat3 I = k.R[size_t(i)] * l.inertia_kg_m2.asDiagonal() * k.R[size_t(i)].transpose();
    L += l.mass_kg * k.com_m[size_t(i)].cross(k.v_com_m_s[size_t(i)]) + I * k.w_rad_s[size_t(i)];
    P += l.mass_kg * k.v_com_m_s[size_t(i)];
  }
  L += m.payload_kg * k.payload_m.cross(k.v_payload_m_s);
  P += m.payload_kg * k.v_payload_m_s;
  return {L, P};
}

}  // namespace

TEST_CASE("BarycenterAndAngularMomentumAreConservedWithoutExternalForces", "[plant]") {
  // ρ = 0, g = 0, no thrust: the only forces are internal, so the barycenter stays put and the
  // total angular momentum stays at its initial value (zero: start at rest) while the arm
  // moves from the stowed to the sampling pose in 10 s. Tolerance tied to the integrator's:
  // rel_tol 1e-8 on states of O(1) over 334 ticks.
  PlantParams pp = PaperPlantParams();
  pp.env.density_kg_m3 = 0.0;
  pp.contact.enabled = false;
  Plant plant(pp);
  plant.Reset(Stowed());
  const Vec3 cm0 = plant.truth().barycenter_m;
  PlantInputs in = Idle(plant);
  double max_drift = 0.0, max_L = 0.0, max_move = 0.0;
  for (int k = 0; k < 334; ++k) {
    in.joint_accel_rad_s2 = CycloidAccel((k + 0.5) * kTick, 10.0);
    REQUIRE(plant.Step(in, kTick).ok());
    max_drift = std::max(max_drift, (plant.truth().barycenter_m - cm0).norm());
    max_L = std::max(max_L, Momenta(plant).first.norm());
    max_move = std::max(max_move, (plant.truth().r0_m).norm());
  }
  std::printf("conservation: barycenter drift %.2e m, |L| max %.2e kg m2/s, vehicle moved %.3f m\n",
              max_drift, max_L, max_move);
  CHECK(max_move > 0.01);  // the vehicle really moved (the arm pushed it)
  CHECK(max_drift < 1e-6);
  CHECK(max_L < 1e-5);
}

TEST_CASE("CoastingVehicleFollowsTheQuadraticDragSolution", "[plant]") {
  // Arm without mass or hydrodynamics, no payload: the vehicle alone coasts along x with drag
  // D = −½ρ·C_D0·A0·|v|·v and effective mass m0 + ρV0·Ma0[0][0] (surge added mass):
  //   v(t) = v0 / (1 + k·v0·t),  k = ½ρ·C_D0·A0 / (m0 + 0.1·ρ·V0).
  PlantParams pp = VehicleOnlyParams();
  Plant plant(pp);
  InitialState s = Stowed();
  const double v0 = 0.8;
  s.v0_m_s = Vec3(v0, 0, 0);
  plant.Reset(s);
  const double k = 0.5 * 1025 * 1.2 * 0.5 / (120 + 0.1 * 1025 * 0.15);
  PlantInputs in = Idle(plant);
  double worst = 0.0;
  for (int i = 1; i <= 500; ++i) {
    REQUIRE(plant.Step(in, kTick).ok());
    const double t = i * kTick;
    worst = std::max(worst, std::abs(plant.truth().v0_m_s.x() - v0 / (1 + k * v0 * t)));
    CHECK(std::abs(plant.truth().r0_m.x() - std::log(1 + k * v0 * t) / k) < 1e-6);
  }
  std::printf("quadratic drag coast: max |v - v_exact| = %.2e m/s over 15 s\n", worst);
  CHECK(worst < 1e-6);  // 100·rel_tol·v0 over 500 restarts
  CHECK(plant.truth().v0_m_s.y() == Approx(0).margin(1e-12));
}

TEST_CASE("ConstantForceGivesAccelerationOverMassPlusAddedMass", "[plant]") {
  // No drag (C_D0 = 0), massless arm: a = F/(m0 + ρV0·Ma0[0][0]) along x; x = ½·a·t².
  PlantParams pp = VehicleOnlyParams();
  pp.vehicle.drag_coeff = 0;
  Plant plant(pp);
  plant.Reset(Stowed());
  PlantInputs in = Idle(plant);
  in.disturbance_force_N = Vec3(25.0, 0, 0);
  const double a = 25.0 / (120 + 0.1 * 1025 * 0.15);
  for (int i = 1; i <= 100; ++i) REQUIRE(plant.Step(in, kTick).ok());
  const double t = 100 * kTick;
  CHECK(plant.truth().accel_m_s2.x() == Approx(a).epsilon(1e-12));
  // Global error of 100 restarted integrations at rel_tol 1e-8: below 1e-6 relative.
  CHECK(plant.truth().r0_m.x() == Approx(0.5 * a * t * t).epsilon(1e-6));
  CHECK(plant.truth().v0_m_s.x() == Approx(a * t).epsilon(1e-6));
}

TEST_CASE("MotorVoltageStepMatchesTheLinearMotorWithoutPropellerLoad", "[plant]") {
  // ρ = 0: no thrust and no propeller torque, so each motor is the linear system
  // L·İ = V − R·I − km·ω, J·ω̇ = km·I − b·ω (closed form: LinearMotorStepResponse).
  PlantParams pp = PaperPlantParams();
  pp.propulsion.drive = MotorDrive::kVoltage;  // these inputs are voltages
  pp.env.density_kg_m3 = 0.0;
  pp.contact.enabled = false;
  Plant plant(pp);
  plant.Reset(Stowed());
  PlantInputs in = Idle(plant);
  in.motor_voltage_V = {10, -5, 0, 2, 0, 0, 0, 1};
  double worst = 0.0;
  for (int i = 1; i <= 100; ++i) {
    REQUIRE(plant.Step(in, kTick).ok());
    for (size_t j = 0; j < 8; ++j) {
      const auto [I, w] = LinearMotorStepResponse(pp.propulsion, in.motor_voltage_V[j], i * kTick);
      worst = std::max({worst, std::abs(plant.truth().motor_current_A[j] - I),
                        std::abs(plant.truth().motor_speed_rad_s[j] - w)});
    }
  }
  std::printf("motor step: max error vs closed form %.2e\n", worst);
  // The paper's motor rings at 100 rad/s (λ = −1 ± 100i): 100 restarts at rel_tol 1e-8 of
  // states up to |ω| ≈ 2 rad/s accumulate to ~1e-6; bound 1e-5.
  CHECK(worst < 1e-5);
  // Battery draw: ∫ Σ max(V·I, 0) ≥ signed energy, both positive here.
  CHECK(plant.truth().thruster_energy_J >= plant.truth().thruster_energy_signed_J);
  CHECK(plant.truth().thruster_energy_J > 0);
}

TEST_CASE("TrimmedVehicleNeedsNoVerticalThrustToHoldPosition", "[plant]") {
  // Earth and Europa with trim: with the nominal payload and the arm stowed at rest, weight
  // equals buoyancy, so the thrust force that holds the vehicle still is zero; untrimmed it is
  // the net weight (ρ·V_total − m_total)·g. (A moment remains: weights and buoyancies act at
  // different points, which is the attitude controller's job.)
  for (const double g : {9.81, 1.315}) {
    for (const bool trim : {true, false}) {
      PlantParams pp = PaperPlantParams();
      pp.env.gravity_m_s2 = Vec3(0, 0, -g);
      pp.env.trim = trim;
      pp.env.trim_payload_kg = pp.payload_kg;
      Plant plant(pp);
      plant.Reset(Stowed());
      const Wrench hold = plant.HoldingWrench(Idle(plant));
      // Net weight without trim: ρ(V0 + Σ V_i) − (m0 + Σ m_i + m_p), link volumes from SPEC §3.1.
      const double len = std::hypot(0.045, 0.55) + 0.045 + 0.3 + 0.06;
      const double net_kg = 1025 * (0.15 + M_PI * 0.089 * 0.089 / 4 * len) - (120 + 19.45 + 10);
      INFO("g " << g << " trim " << trim << " holding force " << hold.force_N.transpose());
      if (trim) {
        CHECK(hold.force_N.norm() < 1e-9 * 150 * g);
      } else {
        CHECK(hold.force_N.z() == Approx(-net_kg * g).epsilon(1e-9));
        CHECK(std::abs(net_kg) > 5.0);  // the untrimmed paper vehicle is markedly buoyant
      }
      CHECK(hold.moment_Nm.norm() > 1.0);
    }
  }
}

TEST_CASE("ContactWithTheChimneyStopsTheRunNamingTheBodies", "[plant]") {
  // A chimney (radius 0.15 m) stands where the arm sweeps on its way to the sampling pose.
  PlantParams pp = PaperPlantParams();
  pp.env.density_kg_m3 = 0.0;
  CylinderObstacle chimney;
  chimney.name = "chimney";
  chimney.base_center_m = Vec3(1.45, 0.2, -1.0);  // at the sampling point, top at z = 1 m
  chimney.height_m = 2.0;
  chimney.radius_m = 0.15;
  pp.contact.obstacles.push_back(chimney);
  Plant plant(pp);
  plant.Reset(Stowed());
  INFO("start: " << plant.truth().closest_a << "-" << plant.truth().closest_b);
  REQUIRE(plant.truth().min_clearance_m > 0.0);
  PlantInputs in = Idle(plant);
  StepStatus st;
  int k = 0;
  for (; k < 334 && st.ok(); ++k) {
    in.joint_accel_rad_s2 = CycloidAccel((k + 0.5) * kTick, 10.0);
    st = plant.Step(in, kTick);
  }
  REQUIRE(st.code == StepStatus::Code::kContact);
  CHECK(st.message.find("chimney") != std::string::npos);
  CHECK(st.message.find("link") != std::string::npos);
  CHECK(k < 334);
}

TEST_CASE("IntegratorFailureAndBadInputsAreReportedNotAborted", "[plant]") {
  PlantParams pp = PaperPlantParams();
  pp.propulsion.drive = MotorDrive::kVoltage;  // these inputs are voltages
  pp.integrator.max_steps = 1;
  pp.contact.enabled = false;
  Plant plant(pp);
  plant.Reset(Stowed());
  PlantInputs in = Idle(plant);
  in.motor_voltage_V.assign(8, 300.0);
  const StepStatus st = plant.Step(in, 1.0);
  CHECK(st.code == StepStatus::Code::kIntegratorFailure);
  CHECK(st.message.find("CV_TOO_MUCH_WORK") != std::string::npos);

  PlantInputs bad = Idle(plant);
  bad.motor_voltage_V[3] = std::nan("");
  CHECK(plant.Step(bad, kTick).code == StepStatus::Code::kBadInput);
  bad = Idle(plant);
  bad.joint_accel_rad_s2.pop_back();
  CHECK(plant.Step(bad, kTick).code == StepStatus::Code::kBadInput);
  PlantParams broken = PaperPlantParams();
  broken.vehicle.mass_kg = -1;
  CHECK_THROWS_AS(Plant(broken), std::invalid_argument);
}

TEST_CASE("ThrustFactorScalesTheProducedThrustNotTheMotor", "[plant]") {
  // Fault model "efficiency loss": thrust × factor, shaft torque unchanged, so after one tick
  // the motors of the two plants agree (up to the tiny advance-speed difference the smaller
  // thrust causes) and the produced thrust is the factor times the healthy one.
  PlantParams pp = PaperPlantParams();
  pp.propulsion.drive = MotorDrive::kVoltage;  // these inputs are voltages
  pp.contact.enabled = false;
  Plant healthy(pp), damaged(pp);
  healthy.Reset(Stowed());
  damaged.Reset(Stowed());
  PlantInputs in = Idle(healthy);
  in.motor_voltage_V[4] = -200.0;  // thruster 5 (vertical): negative speed, positive thrust
  in.motor_voltage_V[0] = -150.0;
  PlantInputs hurt = in;
  hurt.thrust_factor.assign(8, 1.0);
  hurt.thrust_factor[4] = 0.25;
  for (int k = 0; k < 5; ++k) {
    REQUIRE(healthy.Step(in, kTick).ok());
    REQUIRE(damaged.Step(hurt, kTick).ok());
  }
  const Truth &h = healthy.truth(), &d = damaged.truth();
  REQUIRE(h.thrust_N[4] > 0.01);
  // Exactly the factor times the thrust law [47–52] at the damaged plant's own state.
  const Eigen::Matrix3d R0 = d.attitude.toRotationMatrix();
  for (int j : {0, 4}) {
    const double va = AdvanceSpeedMS(pp.thrusters[size_t(j)], R0, d.v0_m_s, d.w0_rad_s, d.flow_m_s);
    const double law = ThrustN(pp.propulsion, pp.env.density_kg_m3, d.motor_speed_rad_s[size_t(j)], va);
    CHECK(d.thrust_N[size_t(j)] == Approx((j == 4 ? 0.25 : 1.0) * law).epsilon(1e-12));
  }
  // The motors barely notice (torque unchanged; only the advance speed differs slightly).
  CHECK(d.motor_speed_rad_s[4] == Approx(h.motor_speed_rad_s[4]).epsilon(1e-3));
  CHECK(d.thrust_N[4] == Approx(0.25 * h.thrust_N[4]).epsilon(1e-3));
  CHECK(d.thrust_force_N.z() < 0.3 * h.thrust_force_N.z());

  PlantInputs bad = hurt;
  bad.thrust_factor[2] = 1.5;
  CHECK(damaged.Step(bad, kTick).code == StepStatus::Code::kBadInput);
  bad.thrust_factor.pop_back();
  CHECK(damaged.Step(bad, kTick).code == StepStatus::Code::kBadInput);
}
