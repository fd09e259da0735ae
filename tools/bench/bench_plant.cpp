// bench_plant: wall time of the truth model per 60 s simulated (2000 ticks of 0.03 s) with
// open-loop inputs (the paper's joint cycloid θI → Veh. over 60 s, sinusoidal motor voltages,
// unsteady flow on), and CVODE's work per tick. A benchmark, not a test.
// Usage: bench_plant [REPS]   (prints one Markdown row per method/tolerance)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "uvms_plant/plant.hpp"

using namespace uvms::plant;

int main(int argc, char **argv) {
  const int reps = argc > 1 ? std::atoi(argv[1]) : 3;
  const double d = M_PI / 180.0;
  const double qi[7] = {180 * d, 90 * d, 180 * d, 180 * d, 0, 0, 0};
  const double qf[7] = {169.68 * d, -75.62 * d, 266.00 * d, 108.77 * d, 193.47 * d, 96.97 * d, 98.33 * d};
  struct Variant {
    const char *name;
    IntegratorParams::Method method;
    double rel, abs;
  };
  const Variant variants[] = {
      {"Adams, rel 1e-8 abs 1e-10 (default)", IntegratorParams::Method::kAdams, 1e-8, 1e-10},
      {"Adams, rel 1e-6 abs 1e-8", IntegratorParams::Method::kAdams, 1e-6, 1e-8},
      {"BDF, rel 1e-8 abs 1e-10", IntegratorParams::Method::kBdf, 1e-8, 1e-10},
  };
  std::printf("| integrator | wall s per 60 s simulated (best of %d) | RHS evaluations per tick | steps per tick | final EE x [m] |\n|---|---:|---:|---:|---:|\n", reps);
  for (const Variant &v : variants) {
    double best = 1e9, rhs = 0, steps = 0, ee = 0;
    for (int r = 0; r < reps; ++r) {
      PlantParams pp = PaperPlantParams();
      pp.integrator.method = v.method;
      pp.integrator.rel_tol = v.rel;
      pp.integrator.abs_tol = v.abs;
      pp.env.unsteady.enabled = true;
      Plant plant(pp);
      InitialState s;
      s.q_rad.assign(qi, qi + 7);
      plant.Reset(s);
      PlantInputs in;
      in.motor_voltage_V.assign(8, 0.0);
      in.joint_accel_rad_s2.assign(7, 0.0);
      const auto t0 = std::chrono::steady_clock::now();
      for (int k = 0; k < 2000; ++k) {
        const double t = (k + 0.5) * 0.03;
        for (int j = 0; j < 7; ++j)
          in.joint_accel_rad_s2[size_t(j)] = 2 * M_PI * (qf[j] - qi[j]) / 3600.0 * std::sin(2 * M_PI * t / 60.0);
        for (int j = 0; j < 8; ++j) in.motor_voltage_V[size_t(j)] = 20.0 * std::sin(0.2 * t + j);
        if (!plant.Step(in, 0.03).ok()) return 1;
      }
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      best = std::min(best, wall);
      rhs = double(plant.integrator_stats().rhs_evals) / 2000.0;
      steps = double(plant.integrator_stats().steps) / 2000.0;
      ee = plant.truth().ee_m.x();
    }
    std::printf("| %s | %.3f | %.1f | %.1f | %.9f |\n", v.name, best, rhs, steps, ee);
  }
  return 0;
}
