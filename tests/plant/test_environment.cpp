// SPDX-License-Identifier: Apache-2.0
// Plant environment (SPEC §6): unsteady flow [28] (reproducibility, period mean, bound),
// gravity presets, the variable-coefficient table and trim ballast, against properties of
// the formulas and hand-derived values.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "uvms_plant/environment.hpp"
#include "uvms_plant/params.hpp"

using namespace uvms::plant;

namespace {

constexpr double kPi = 3.14159265358979323846;

UnsteadyFlowParams FlowParams(std::uint64_t seed, int n = 5, double Av = 0.01, double tF = 60.0) {
  UnsteadyFlowParams p;
  p.enabled = true;
  p.amplitude_m_s = Av;
  p.harmonics = n;
  p.seed = seed;
  p.period_s = tF;
  return p;
}

const Vec3 kSteady(0.1, -0.2, 0.05);  // v∞0 for the tests [m/s]

}  // namespace

// ------------------------------------------------------------------------------ unsteady flow

TEST_CASE("UnsteadyFlowSameSeedGivesIdenticalSeries", "[environment][flow]") {
  const UnsteadyFlow a(FlowParams(42), kSteady), b(FlowParams(42), kSteady);
  CHECK(a.psi_sin() == b.psi_sin());
  CHECK(a.psi_cos() == b.psi_cos());
  for (int i = 0; i <= 600; ++i) {
    const double t = 0.1 * i;
    REQUIRE(a.Velocity(t) == b.Velocity(t));  // bit-identical
  }
}

TEST_CASE("UnsteadyFlowDifferentSeedGivesDifferentSeries", "[environment][flow]") {
  const UnsteadyFlow a(FlowParams(42), kSteady), b(FlowParams(43), kSteady);
  CHECK(a.psi_sin() != b.psi_sin());
  CHECK(a.psi_cos() != b.psi_cos());
  double max_diff = 0.0;
  for (int i = 0; i <= 600; ++i) {
    const double t = 0.1 * i;
    max_diff = std::max(max_diff, (a.Velocity(t) - b.Velocity(t)).cwiseAbs().maxCoeff());
  }
  CHECK(max_diff > 1e-4);  // a sizeable fraction of Av = 0.01 m/s
}

TEST_CASE("UnsteadyFlowFollowsDocumentedDrawOrder", "[environment][flow]") {
  // Contract in environment.hpp: mt19937_64(seed); for k = 1..n, for axis x, y, z: Ψs then Ψc,
  // each Ψ = −1 + 2·(word >> 11)·2⁻⁵³.
  const std::uint64_t seed = 7;
  const UnsteadyFlow f(FlowParams(seed, 3), kSteady);
  std::mt19937_64 gen(seed);
  auto next = [&gen]() { return -1.0 + 2.0 * static_cast<double>(gen() >> 11) * 0x1.0p-53; };
  for (int k = 0; k < 3; ++k) {
    for (int axis = 0; axis < 3; ++axis) {
      CHECK(f.psi_sin()(axis, k) == next());
      CHECK(f.psi_cos()(axis, k) == next());
    }
  }
  // Raising n keeps the first harmonics (harmonic-major order).
  const UnsteadyFlow g(FlowParams(seed, 8), kSteady);
  CHECK(g.psi_sin().leftCols(3) == f.psi_sin());
  CHECK(g.psi_cos().leftCols(3) == f.psi_cos());
}

TEST_CASE("UnsteadyFlowPsiWithinUnitInterval", "[environment][flow]") {
  const UnsteadyFlow f(FlowParams(2024, 2000), kSteady);
  for (const auto *m : {&f.psi_sin(), &f.psi_cos()}) {
    CHECK(m->minCoeff() >= -1.0);
    CHECK(m->maxCoeff() <= 1.0);
    // 6000 uniform draws: they cover the interval and are centred (σ of the mean ≈ 0.0075).
    CHECK(m->minCoeff() < -0.99);
    CHECK(m->maxCoeff() > 0.99);
    CHECK(std::abs(m->mean()) < 0.05);
  }
}

TEST_CASE("UnsteadyFlowMatchesFormulaAtQuarterPeriod", "[environment][flow]") {
  // At t = tF/4 the phase of harmonic k is k·π/2: sin = 1, 0, −1, 0, 1 and
  // cos = 0, −1, 0, 1, 0 for k = 1..5, so
  // v = v∞0 + Av·(Ψs1 − Ψc2/2 − Ψs3/3 + Ψc4/4 + Ψs5/5).
  const double Av = 0.5, tF = 40.0;
  const UnsteadyFlow f(FlowParams(11, 5, Av, tF), kSteady);
  const auto &S = f.psi_sin();
  const auto &C = f.psi_cos();
  const Vec3 expected =
      kSteady + Av * (S.col(0) - C.col(1) / 2 - S.col(2) / 3 + C.col(3) / 4 + S.col(4) / 5);
  CHECK((f.Velocity(tF / 4) - expected).cwiseAbs().maxCoeff() < 1e-14);
  // At t = 0 only the cosines remain: v = v∞0 + Av·Σ Ψc,k/k.
  Vec3 at0 = kSteady;
  for (int k = 1; k <= 5; ++k) at0 += Av * C.col(k - 1) / k;
  CHECK((f.Velocity(0.0) - at0).cwiseAbs().maxCoeff() < 1e-15);
}

TEST_CASE("UnsteadyFlowMeanOverOnePeriodIsSteadyFlow", "[environment][flow]") {
  // The rectangle rule with N equally spaced samples over one period integrates sin and cos of
  // harmonics k = 1..N−1 exactly to zero (discrete orthogonality), so with N = 64 > n the
  // sample mean is v∞0 up to rounding. Checked from two start times (periodicity).
  const double Av = 0.3, tF = 60.0;  // a large Av so that a wrong mean would show
  const UnsteadyFlow f(FlowParams(99, 5, Av, tF), kSteady);
  const int N = 64;
  for (double t0 : {0.0, 7.3}) {
    Vec3 sum = Vec3::Zero();
    for (int j = 0; j < N; ++j) sum += f.Velocity(t0 + tF * j / N);
    CHECK((sum / N - kSteady).cwiseAbs().maxCoeff() < 1e-12);
  }
  // Over half a period the mean is not v∞0 in general: the check above can fail.
  Vec3 half = Vec3::Zero();
  for (int j = 0; j < N; ++j) half += f.Velocity(0.5 * tF * j / N);
  CHECK((half / N - kSteady).cwiseAbs().maxCoeff() > 1e-3);
}

TEST_CASE("UnsteadyFlowBoundedByAmplitudeHarmonicSum", "[environment][flow]") {
  // |Ψs·sin φ + Ψc·cos φ| ≤ √(Ψs² + Ψc²) ≤ √2 per harmonic, so per axis
  // |v − v∞0| ≤ Av·√2·Σ_{k=1..n} 1/k.
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const double Av = 0.01;
    const int n = 5;
    const UnsteadyFlow f(FlowParams(seed, n, Av), kSteady);
    double harmonic = 0.0;
    for (int k = 1; k <= n; ++k) harmonic += 1.0 / k;
    const double bound = Av * std::sqrt(2.0) * harmonic;
    double max_dev = 0.0;
    for (int i = 0; i <= 6000; ++i) {
      max_dev = std::max(max_dev, (f.Velocity(0.01 * i) - kSteady).cwiseAbs().maxCoeff());
    }
    CHECK(max_dev <= bound);
    CHECK(max_dev > 0.1 * Av);  // and the flow does vary
  }
}

TEST_CASE("UnsteadyFlowDisabledIsExactlySteady", "[environment][flow]") {
  UnsteadyFlowParams p = FlowParams(5);
  p.enabled = false;
  p.period_s = 0.0;  // ignored when disabled
  const UnsteadyFlow f(p, kSteady);
  CHECK(f.psi_sin().cols() == 0);
  for (double t : {0.0, 1.0, 13.7, 60.0, 1e6}) CHECK(f.Velocity(t) == kSteady);
}

TEST_CASE("UnsteadyFlowRejectsInvalidParameters", "[environment][flow]") {
  UnsteadyFlowParams p = FlowParams(1);
  p.period_s = 0.0;
  CHECK_THROWS_WITH(UnsteadyFlow(p, kSteady), Catch::Contains("period_s"));
  p = FlowParams(1);
  p.harmonics = -1;
  CHECK_THROWS_WITH(UnsteadyFlow(p, kSteady), Catch::Contains("harmonics"));
  p = FlowParams(1);
  p.amplitude_m_s = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH(UnsteadyFlow(p, kSteady), Catch::Contains("amplitude_m_s"));
  CHECK_THROWS_AS(UnsteadyFlow(FlowParams(1), Vec3(0, std::nan(""), 0)), std::invalid_argument);
}

// ------------------------------------------------------------------------------------ gravity

TEST_CASE("GravityPresets", "[environment][gravity]") {
  CHECK(GravityPaper() == Vec3::Zero());
  CHECK(GravityEarth() == Vec3(0, 0, -9.81));
  CHECK(GravityEuropa() == Vec3(0, 0, -1.315));
  CHECK(GravityPreset("paper") == GravityPaper());
  CHECK(GravityPreset("earth") == GravityEarth());
  CHECK(GravityPreset("europa") == GravityEuropa());
  CHECK_THROWS_AS(GravityPreset("mars"), std::invalid_argument);
  CHECK_THROWS_WITH(GravityPreset("mars"), Catch::Contains("mars"));
  CHECK_THROWS_WITH(GravityPreset("Earth"), Catch::Contains("Earth"));
}

// ------------------------------------------------------------------------ coefficient table

TEST_CASE("CoeffInterpolationAtKnotsMidpointsAndClamped", "[environment][coeff]") {
  const std::vector<CoeffTableRow> t = {{1.0, 2.0, 3.0}, {3.0, 4.0, 1.0}, {7.0, 0.0, 1.0}};
  REQUIRE_NOTHROW(ValidateCoeffTable(t));
  for (const CoeffTableRow &r : t) {
    const CoeffFactors f = InterpolateCoeffs(t, r.distance_diameters);
    CHECK(f.drag_factor == r.drag_factor);
    CHECK(f.added_mass_factor == r.added_mass_factor);
  }
  // Midpoints: averages of the neighbours.
  CHECK(InterpolateCoeffs(t, 2.0).drag_factor == Approx(3.0));
  CHECK(InterpolateCoeffs(t, 2.0).added_mass_factor == Approx(2.0));
  CHECK(InterpolateCoeffs(t, 5.0).drag_factor == Approx(2.0));
  CHECK(InterpolateCoeffs(t, 5.0).added_mass_factor == Approx(1.0));
  // A quarter of the way along the first segment.
  CHECK(InterpolateCoeffs(t, 1.5).drag_factor == Approx(2.5));
  // Clamped at both ends.
  CHECK(InterpolateCoeffs(t, 0.0).drag_factor == 2.0);
  CHECK(InterpolateCoeffs(t, -5.0).added_mass_factor == 3.0);
  CHECK(InterpolateCoeffs(t, 100.0).drag_factor == 0.0);
  CHECK(InterpolateCoeffs(t, std::numeric_limits<double>::infinity()).added_mass_factor == 1.0);
  // A one-row table is constant.
  const std::vector<CoeffTableRow> one = {{0.0, 0.7, 0.9}};
  CHECK(InterpolateCoeffs(one, 3.0).drag_factor == 0.7);
  CHECK(InterpolateCoeffs(one, 0.0).added_mass_factor == 0.9);
  CHECK_THROWS_AS(InterpolateCoeffs(t, std::nan("")), std::invalid_argument);
  CHECK_THROWS_AS(InterpolateCoeffs({}, 1.0), std::invalid_argument);
}

TEST_CASE("DefaultCoeffTableHasDocumentedShape", "[environment][coeff]") {
  const std::vector<CoeffTableRow> t = DefaultCoeffTable();
  REQUIRE_NOTHROW(ValidateCoeffTable(t));
  // SPEC §6.4: low drag at rest, overshoot ≈ 1.3 near 5 diameters, 1.0 past about 10;
  // added-mass factor 1.0 at rest, relaxing toward ≈ 0.8.
  double peak = -1.0, peak_at = -1.0, prev_am = InterpolateCoeffs(t, 0.0).added_mass_factor;
  for (int i = 0; i <= 3000; ++i) {
    const double d = 0.01 * i;
    const CoeffFactors f = InterpolateCoeffs(t, d);
    if (f.drag_factor > peak) {
      peak = f.drag_factor;
      peak_at = d;
    }
    REQUIRE(f.drag_factor >= 0.0);
    REQUIRE(f.added_mass_factor <= prev_am);  // monotone relaxation
    prev_am = f.added_mass_factor;
    if (d >= 10.0) REQUIRE(f.drag_factor == 1.0);
  }
  CHECK(InterpolateCoeffs(t, 0.0).drag_factor < 0.7);
  CHECK(peak == Approx(1.3).margin(0.05));
  CHECK(peak_at >= 3.0);
  CHECK(peak_at <= 7.0);
  CHECK(InterpolateCoeffs(t, 0.0).added_mass_factor == 1.0);
  CHECK(t.back().added_mass_factor == Approx(0.8).margin(0.05));
  CHECK(InterpolateCoeffs(t, 1e3).added_mass_factor == t.back().added_mass_factor);
}

TEST_CASE("InvalidCoeffTablesThrowWithMessage", "[environment][coeff]") {
  using Rows = std::vector<CoeffTableRow>;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH(ValidateCoeffTable(Rows{}), Catch::Contains("empty"));
  CHECK_THROWS_WITH(ValidateCoeffTable(Rows{{0, 1, 1}, {5, 1, 1}, {2, 1, 1}}),
                    Catch::Contains("row 2") && Catch::Contains("strictly increasing"));
  CHECK_THROWS_WITH(ValidateCoeffTable(Rows{{0, 1, 1}, {0, 2, 1}}),
                    Catch::Contains("strictly increasing"));
  CHECK_THROWS_WITH(ValidateCoeffTable(Rows{{-1, 1, 1}}), Catch::Contains("negative distance"));
  CHECK_THROWS_WITH(ValidateCoeffTable(Rows{{0, -0.5, 1}}), Catch::Contains("negative factor"));
  CHECK_THROWS_WITH(ValidateCoeffTable(Rows{{0, 1, -1}}), Catch::Contains("negative factor"));
  CHECK_THROWS_WITH(ValidateCoeffTable(Rows{{0, 1, 1}, {nan, 1, 1}}),
                    Catch::Contains("row 1") && Catch::Contains("non-finite"));
  CHECK_THROWS_WITH(ValidateCoeffTable(Rows{{0, inf, 1}}), Catch::Contains("non-finite"));
}

// --------------------------------------------------------------------------------------- trim

namespace {
// SPEC §3.1/§3.2, typed here: link volumes V_i = π·d_L²/4·|l_i| of links 3, 4, 5, 7 (the
// others have |l_i| = 0), |l_3| = √(0.045² + 0.55²), |l_4| = 0.045, |l_5| = 0.3, |l_7| = 0.06.
const double kLinkLengthSum_m = std::sqrt(0.045 * 0.045 + 0.55 * 0.55) + 0.045 + 0.3 + 0.06;
const double kLinkVolume_m3 = kPi * 0.089 * 0.089 / 4.0 * kLinkLengthSum_m;
const double kVolume_m3 = 0.15 + kLinkVolume_m3;  // V0 + Σ V_i
const double kArmMass_kg = 10.77 + 3.87 + 1.80 + 2.40 + 0.12 + 0.42 + 0.07;
}  // namespace

TEST_CASE("TrimBallastPaperParameters", "[environment][trim]") {
  const PlantParams p = PaperPlantParams();
  const double rho = 1025.0;
  // m_ballast = ρ·(V0 + Σ V_i) − (m0 + Σ m_i + m_payload), ≈ 10.4 kg for a 10 kg payload.
  const double expected_kg = rho * kVolume_m3 - (120.0 + kArmMass_kg + 10.0);
  CHECK(TrimBallastKg(p, rho, 10.0) == Approx(expected_kg).epsilon(1e-12));
  CHECK(TrimBallastKg(p, rho, 0.0) == Approx(expected_kg + 10.0).epsilon(1e-12));
  // The density-error model (1000 kg/m³) trims 25·V lighter.
  CHECK(TrimBallastKg(p, 1000.0, 10.0) - TrimBallastKg(p, rho, 10.0) ==
        Approx(-25.0 * kVolume_m3).epsilon(1e-10));
}

TEST_CASE("TrimBallastMakesWeightEqualBuoyancy", "[environment][trim]") {
  const PlantParams p = PaperPlantParams();
  for (const Vec3 &g : {GravityEarth(), GravityEuropa()}) {
    for (double payload : {0.0, 2.0, 10.0}) {
      const double rho = 1025.0;
      const double ballast = TrimBallastKg(p, rho, payload);
      const Vec3 weight_N = (120.0 + kArmMass_kg + payload + ballast) * g;
      const Vec3 buoyancy_N = -rho * kVolume_m3 * g;
      CHECK((weight_N + buoyancy_N).norm() <= 1e-12 * buoyancy_N.norm());
    }
  }
}

TEST_CASE("TrimBallastRejectsBadInput", "[environment][trim]") {
  const PlantParams p = PaperPlantParams();
  CHECK_THROWS_WITH(TrimBallastKg(p, 0.0, 10.0), Catch::Contains("density"));
  CHECK_THROWS_WITH(TrimBallastKg(p, 1025.0, -1.0), Catch::Contains("payload"));
  CHECK_THROWS_AS(TrimBallastKg(p, std::nan(""), 10.0), std::invalid_argument);
}

TEST_CASE("TrimBallastPointMovesDownByTotalOverBallastMassPerMetreOfH", "[environment][trim]") {
  // SPEC §6.3: m_b·b = ρ·Σ V_k·x_k − ρ·V_T·h·e_z − Σ m_k·x_k, so raising h by Δh moves the
  // ballast by −(ρ·V_T/m_b)·Δh·e_z and nothing else; the density, payload and pose parts do
  // not depend on h. ρ·V_T and m_b from SPEC §3 (TrimBallastPaperParameters).
  PlantParams p = PaperPlantParams();
  p.env.density_kg_m3 = 1025.0;
  p.env.trim_payload_kg = 10.0;
  const double M_kg = 1025.0 * kVolume_m3;
  const double mb_kg = M_kg - (120.0 + kArmMass_kg + 10.0);
  p.env.metacentric_height_m = 0.05;
  const Ballast b5 = TrimBallast(p);
  p.env.metacentric_height_m = 0.02;
  const Ballast b2 = TrimBallast(p);
  std::printf("trim ballast (h = 0.05 m, 10 kg payload, stowed): %.4f kg at (%.4f, %.4f, %.4f) m; "
              "h = 0.02 m: (%.4f, %.4f, %.4f) m\n", b5.mass_kg, b5.offset_m.x(), b5.offset_m.y(),
              b5.offset_m.z(), b2.offset_m.x(), b2.offset_m.y(), b2.offset_m.z());
  CHECK(b5.mass_kg == Approx(mb_kg).epsilon(1e-12));
  const Vec3 shift = b5.offset_m - b2.offset_m;
  CHECK(shift.z() == Approx(-M_kg / mb_kg * 0.03).epsilon(1e-12));
  CHECK(std::abs(shift.x()) < 1e-12);
  CHECK(std::abs(shift.y()) < 1e-12);
  CHECK(b5.offset_m.x() < -1.0);  // the arm and payload hang forward: the ballast goes aft
}

TEST_CASE("TrimBallastPointRejectsBadInput", "[environment][trim]") {
  PlantParams p = PaperPlantParams();
  p.env.metacentric_height_m = std::nan("");
  CHECK_THROWS_WITH(TrimBallast(p), Catch::Contains("metacentric"));
  p = PaperPlantParams();
  p.env.trim_pose_rad.pop_back();
  CHECK_THROWS_WITH(TrimBallast(p), Catch::Contains("trim pose"));
  p = PaperPlantParams();  // already neutral: no ballast mass to place
  p.vehicle.mass_kg += TrimBallastKg(p, p.env.density_kg_m3, p.env.trim_payload_kg);
  CHECK_THROWS_WITH(TrimBallast(p), Catch::Contains("neutral"));
}
