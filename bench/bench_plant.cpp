// SPDX-License-Identifier: Apache-2.0
// bench_plant: wall time of the truth model per 60 s simulated (2000 ticks of 0.03 s) with
// open-loop inputs (the paper's joint cycloid θI → Veh. over 60 s, unsteady flow on; the motors
// get sinusoidal voltages in the voltage drive, or the current ramps of the same speeds in the
// current drive, SPEC §5), and CVODE's work per tick. A benchmark, not a test.
// Usage: bench_plant [REPS] [ROWS]   (prints one Markdown row per method/tolerance; ROWS
// limits the run to the first ROWS variants, e.g. 1 for the default only, for profiling)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "uvms/trajectory.h"
#include "uvms_plant/plant.hpp"

using namespace uvms::plant;

int main(int argc, char **argv) {
  const int reps = argc > 1 ? std::atoi(argv[1]) : 3;
  const int max_rows = argc > 2 ? std::atoi(argv[2]) : 1000;
  const double d = M_PI / 180.0;
  // SPEC §8: θI → "Veh." (the firmware's table, written once there)
  double qi[7], qf[7];
  for (int j = 0; j < 7; ++j) {
    qi[j] = double(uvms_joint_table_deg(UVMS_JOINT_TABLE_START)[j]) * d;
    qf[j] = double(uvms_joint_table_deg(UVMS_JOINT_TABLE_VEHICLE)[j]) * d;
  }
  struct Variant {
    const char *name;
    IntegratorParams::Method method;
    double rel, abs;
    bool motor_integrating_factor;
    double restart_step_fraction;  // 0: CVODE's own first step after each restart
    double nonlin_conv_coef;
    MotorDrive drive = MotorDrive::kVoltage;  // the rows below study the voltage drive's IF
  };
  using M = IntegratorParams::Method;
  const Variant variants[] = {
      {"current drive (default): Adams, rel 1e-8 abs 1e-9, h0 0.002, nlscoef 0.2", M::kAdams, 1e-8, 1e-9, true, 0.002, 0.2, MotorDrive::kCurrent},
      {"voltage drive: Adams, rel 1e-8 abs 1e-9, IF, h0 0.002, nlscoef 0.2 (default)", M::kAdams, 1e-8, 1e-9, true, 0.002, 0.2},
      {"Adams, rel 1e-8 abs 1e-10, IF, h0 0.002, nlscoef 0.2 (issue-4 default)", M::kAdams, 1e-8, 1e-10, true, 0.002, 0.2},
      {"Adams, rel 1e-8 abs 1e-10, IF, h0 0.002, nlscoef 0.1", M::kAdams, 1e-8, 1e-10, true, 0.002, 0.1},
      {"Adams, rel 1e-8 abs 1e-10, IF, CVODE's h0, nlscoef 0.1", M::kAdams, 1e-8, 1e-10, true, 0.0, 0.1},
      {"Adams, rel 1e-8 abs 1e-8, IF, h0 0.002, nlscoef 0.2", M::kAdams, 1e-8, 1e-8, true, 0.002, 0.2},
      {"Adams, rel 1e-7 abs 1e-9, IF, h0 0.002, nlscoef 0.2", M::kAdams, 1e-7, 1e-9, true, 0.002, 0.2},
      {"Adams, rel 1e-6 abs 1e-8, IF, h0 0.002, nlscoef 0.2", M::kAdams, 1e-6, 1e-8, true, 0.002, 0.2},
      {"Adams, rel 1e-10 abs 1e-12, IF, h0 0.002, nlscoef 0.2", M::kAdams, 1e-10, 1e-12, true, 0.002, 0.2},
      {"Adams, rel 1e-8 abs 1e-10, direct motor states, CVODE's h0, nlscoef 0.1", M::kAdams, 1e-8, 1e-10, false, 0.0, 0.1},
      {"BDF, rel 1e-8 abs 1e-10, direct motor states, CVODE's h0, nlscoef 0.1", M::kBdf, 1e-8, 1e-10, false, 0.0, 0.1},
  };
  std::printf("IF: motor integrating factor; h0: first step after each restart as a fraction of the "
              "previous tick's next step\n\n");
  std::printf("| integrator | wall s per 60 s simulated (best of %d) | RHS evaluations per tick | steps per tick | error-test failures per tick | final EE x [m] | thruster energy [J] |\n|---|---:|---:|---:|---:|---:|---:|\n", reps);
  Integrator::Stats last_stats;
  int row = 0;
  for (const Variant &v : variants) {
    if (row++ >= max_rows) break;
    double best = 1e9, rhs = 0, steps = 0, ee = 0, e_thr = 0;
    for (int r = 0; r < reps; ++r) {
      PlantParams pp = PaperPlantParams();
      pp.propulsion.drive = v.drive;
      pp.integrator.method = v.method;
      pp.integrator.rel_tol = v.rel;
      pp.integrator.abs_tol = v.abs;
      pp.integrator.motor_integrating_factor = v.motor_integrating_factor;
      pp.integrator.restart_step_fraction = v.restart_step_fraction;
      pp.integrator.nonlin_conv_coef = v.nonlin_conv_coef;
      pp.env.unsteady.enabled = true;
      Plant plant(pp);
      InitialState s;
      s.q_rad.assign(qi, qi + 7);
      plant.Reset(s);
      PlantInputs in;
      in.motor_voltage_V.assign(8, 0.0);
      in.motor_current_cmd_A.assign(8, 0.0);
      in.motor_current_rate_A_s.assign(8, 0.0);
      in.joint_accel_rad_s2.assign(7, 0.0);
      const auto t0 = std::chrono::steady_clock::now();
      for (int k = 0; k < 2000; ++k) {
        const double t = (k + 0.5) * 0.03;
        for (int j = 0; j < 7; ++j)
          in.joint_accel_rad_s2[size_t(j)] = 2 * M_PI * (qf[j] - qi[j]) / 3600.0 * std::sin(2 * M_PI * t / 60.0);
        for (int j = 0; j < 8; ++j) {
          in.motor_voltage_V[size_t(j)] = 20.0 * std::sin(0.2 * t + j);
          // 2 mA: the voltage drive's steady current at 20 V, b·V/(Rm·b + km²)
          in.motor_current_cmd_A[size_t(j)] = 2e-3 * std::sin(0.2 * k * 0.03 + j);
          in.motor_current_rate_A_s[size_t(j)] = 4e-4 * std::cos(0.2 * k * 0.03 + j);
        }
        if (!plant.Step(in, 0.03).ok()) return 1;
      }
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      best = std::min(best, wall);
      rhs = double(plant.integrator_stats().rhs_evals) / 2000.0;
      steps = double(plant.integrator_stats().steps) / 2000.0;
      ee = plant.truth().ee_m.x();
      e_thr = plant.truth().thruster_energy_J;
      last_stats = plant.integrator_stats();
    }
    std::printf("| %s | %.3f | %.1f | %.1f | %.2f | %.9f | %.9f |\n", v.name, best, rhs, steps,
                double(last_stats.err_test_fails) / 2000.0, ee, e_thr);
  }
  return 0;
}
