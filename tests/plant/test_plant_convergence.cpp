// SPDX-License-Identifier: Apache-2.0
// Tolerance independence and determinism of a 60 s paper run (issue 4): label "slow", since
// it integrates three minutes of simulated time (seconds in Release, minutes under ASan).
#include <catch2/catch.hpp>

#include <cmath>

#include "plant_test_util.hpp"
#include "uvms_plant/plant.hpp"

using namespace uvms::plant;

using namespace plant_test;

TEST_CASE("ResultsAreIndependentOfTheToleranceAndRunsAreDeterministic", "[plant]") {
  // 60 s of the paper's arm motion (cycloid θI → Veh.) with open-loop thruster voltages,
  // at the default tolerances and 100× tighter. The limits come from what the harness reports
  // (tools/report.py): EE errors in mm with 2 decimals (10 µm) and energies to 0.1 J of a few
  // hundred J (≥ 2e-4 relative). SPEC §5 asks for independence "well below the reported
  // precision": half the EE resolution, a tenth of the energy resolution.
  // Both drives (SPEC §5): held voltages, or current ramps following a sinusoid.
  const MotorDrive drive = GENERATE(MotorDrive::kCurrent, MotorDrive::kVoltage);
  INFO((drive == MotorDrive::kCurrent ? "current drive" : "voltage drive"));
  auto run = [drive](double scale, Integrator::Stats *stats) {
    PlantParams pp = PaperPlantParams();
    pp.propulsion.drive = drive;
    pp.integrator.rel_tol *= scale;
    pp.integrator.abs_tol *= scale;
    pp.integrator.motor_speed_abs_tol_rad_s *= scale;
    pp.contact.enabled = false;
    pp.env.unsteady.enabled = true;
    Plant plant(pp);
    plant.Reset(Stowed());
    PlantInputs in = Idle(plant);
    for (int k = 0; k < 2000; ++k) {
      const double t = (k + 0.5) * kTick;
      in.joint_accel_rad_s2 = CycloidAccel(t, 60.0);
      for (size_t j = 0; j < 8; ++j) {
        in.motor_voltage_V[j] = 20.0 * std::sin(0.2 * t + double(j));
        // I*(t) = 2 mA·sin(0.2·t + j) at the tick start: the steady current of the voltage
        // drive's 20 V (b·V/(Rm·b + km²)), hence speeds of the same size (≈ 2 rad/s)
        const double t0 = k * kTick;
        in.motor_current_cmd_A[j] = 2e-3 * std::sin(0.2 * t0 + double(j));
        in.motor_current_rate_A_s[j] = 4e-4 * std::cos(0.2 * t0 + double(j));
      }
      REQUIRE(plant.Step(in, kTick).ok());
    }
    if (stats) *stats = plant.integrator_stats();
    return plant.truth();
  };
  Integrator::Stats st;
  const Truth a = run(1.0, &st), b = run(0.01, nullptr), c = run(1.0, nullptr);
  auto rel = [](double x, double y) { return std::abs(x - y) / std::max(std::abs(y), 1e-12); };
  std::printf("tolerance study: |Δr0| %.2e m, |ΔEE| %.2e m, ΔE_thr %.2e rel, ΔE_man %.2e rel; "
              "default: %.1f RHS evaluations per tick\n",
              (a.r0_m - b.r0_m).norm(), (a.ee_m - b.ee_m).norm(),
              rel(a.thruster_energy_J, b.thruster_energy_J),
              rel(a.manipulator_energy_J, b.manipulator_energy_J), double(st.rhs_evals) / 2000.0);
  std::printf("  (%s drive) E_prop %.6e J, ΔE_prop %.2e rel; E_thr %.6e J\n",
              drive == MotorDrive::kCurrent ? "current" : "voltage", a.propulsive_energy_J,
              rel(a.propulsive_energy_J, b.propulsive_energy_J), a.thruster_energy_J);
  CHECK((a.r0_m - b.r0_m).norm() < 5e-6);
  CHECK((a.ee_m - b.ee_m).norm() < 5e-6);
  CHECK(rel(a.thruster_energy_J, b.thruster_energy_J) < 2e-5);
  CHECK(rel(a.manipulator_energy_J, b.manipulator_energy_J) < 2e-5);
  // E_p of these small speeds is below 1 mJ, so CVODE's absolute tolerance dominates its
  // relative error; the report prints E_p to 0.1 mJ: 1e-7 J is a thousandth of that.
  CHECK(std::abs(a.propulsive_energy_J - b.propulsive_energy_J) <
        2e-5 * std::abs(b.propulsive_energy_J) + 1e-7);
  // Same inputs, same result, bit for bit.
  CHECK(a.r0_m == c.r0_m);
  CHECK(a.thruster_energy_J == c.thruster_energy_J);
}

