// SPDX-License-Identifier: Apache-2.0
// environment.cpp: unsteady flow [28], gravity, trim and variable coefficients (SPEC §6).
#include "uvms_plant/environment.hpp"

#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <stdexcept>

#include "uvms_plant/multibody.hpp"

namespace uvms::plant {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Ψ uniform in [−1, 1) from one mt19937_64 word: the top 53 bits as a fraction in [0, 1),
// scaled and shifted exactly (see UnsteadyFlow in the header for why not
// std::uniform_real_distribution).
double DrawPsi(std::mt19937_64 &gen) {
  const std::uint64_t x = gen();
  const double u = static_cast<double>(x >> 11) * 0x1.0p-53;  // [0, 1)
  return -1.0 + 2.0 * u;
}

[[noreturn]] void ThrowFlow(const std::string &what) {
  throw std::invalid_argument("UnsteadyFlow: " + what);
}

}  // namespace

UnsteadyFlow::UnsteadyFlow(const UnsteadyFlowParams &params, const Vec3 &steady_flow_m_s)
    : params_(params), steady_m_s_(steady_flow_m_s) {
  if (!steady_m_s_.allFinite()) ThrowFlow("steady flow v_inf0 must be finite");
  if (!params_.enabled) return;
  if (!std::isfinite(params_.amplitude_m_s) || params_.amplitude_m_s < 0.0) {
    std::ostringstream os;
    os << "amplitude_m_s must be finite and >= 0 (got " << params_.amplitude_m_s << ")";
    ThrowFlow(os.str());
  }
  if (params_.harmonics < 0 || params_.harmonics > kMaxHarmonics) {
    std::ostringstream os;
    os << "harmonics must be in [0, " << kMaxHarmonics << "] (got " << params_.harmonics << ")";
    ThrowFlow(os.str());
  }
  if (!std::isfinite(params_.period_s) || !(params_.period_s > 0.0)) {
    std::ostringstream os;
    os << "period_s must be finite and > 0 (got " << params_.period_s << ")";
    ThrowFlow(os.str());
  }
  const int n = params_.harmonics;
  psi_s_.resize(3, n);
  psi_c_.resize(3, n);
  std::mt19937_64 gen(params_.seed);
  // Documented draw order: harmonic-major, then axis, then sin before cos.
  for (int k = 0; k < n; ++k) {
    for (int axis = 0; axis < 3; ++axis) {
      psi_s_(axis, k) = DrawPsi(gen);
      psi_c_(axis, k) = DrawPsi(gen);
    }
  }
}

Vec3 UnsteadyFlow::Velocity(double t_s) const {
  Vec3 v = steady_m_s_;
  if (!params_.enabled) return v;
  const double phase = 2.0 * kPi * t_s / params_.period_s;  // 2π·t/tF [rad]
  // sin(k·φ), cos(k·φ) by the angle-addition recurrence from one sin/cos (each step rotates by
  // φ; the phase's rounding grows by about an ulp per harmonic, as k·φ's did).
  const double s1 = std::sin(phase), c1 = std::cos(phase);
  double sk = s1, ck = c1;
  for (int k = 1; k <= params_.harmonics; ++k) {
    v += params_.amplitude_m_s * (psi_s_.col(k - 1) * (sk / k) + psi_c_.col(k - 1) * (ck / k));  // [28]
    const double s_next = sk * c1 + ck * s1;
    ck = ck * c1 - sk * s1;
    sk = s_next;
  }
  return v;
}

Vec3 GravityPaper() { return Vec3::Zero(); }
Vec3 GravityEarth() { return Vec3(0.0, 0.0, -9.81); }
Vec3 GravityEuropa() { return Vec3(0.0, 0.0, -1.315); }

Vec3 GravityPreset(const std::string &name) {
  if (name == "paper") return GravityPaper();
  if (name == "earth") return GravityEarth();
  if (name == "europa") return GravityEuropa();
  throw std::invalid_argument("unknown gravity preset '" + name +
                              "' (expected \"paper\", \"earth\" or \"europa\")");
}

double TrimBallastKg(const PlantParams &p, double density_kg_m3, double payload_kg) {
  if (!std::isfinite(density_kg_m3) || !(density_kg_m3 > 0.0)) {
    std::ostringstream os;
    os << "TrimBallastKg: density must be finite and > 0 (got " << density_kg_m3 << ")";
    throw std::invalid_argument(os.str());
  }
  if (!std::isfinite(payload_kg) || payload_kg < 0.0) {
    std::ostringstream os;
    os << "TrimBallastKg: payload must be finite and >= 0 (got " << payload_kg << ")";
    throw std::invalid_argument(os.str());
  }
  double volume_m3 = p.vehicle.volume_m3;
  double mass_kg = p.vehicle.mass_kg + payload_kg;
  for (const LinkParams &l : p.links) {
    const double len_m = LinkLength(l);  // |l_i| (SPEC §2, [1])
    volume_m3 += kPi * l.diameter_m * l.diameter_m / 4.0 * len_m;  // SPEC §3.1
    mass_kg += l.mass_kg;
  }
  return density_kg_m3 * volume_m3 - mass_kg;  // SPEC §6.3
}

namespace {
/// First moments of the weights and of the displaced volumes (SPEC §6.3) at the trim: vehicle
/// level at the origin, joints at the trim pose, the trim payload at the payload point.
struct TrimMoments {
  Vec3 weight_kg_m{Vec3::Zero()};    ///< Σ_k m_k·x_k without the ballast (vehicle CoM at 0)
  Vec3 buoyancy_kg_m{Vec3::Zero()};  ///< ρ·Σ_k V_k·x_k, x_k the centers of buoyancy
  double buoyancy_kg{0.0};           ///< ρ·V_T
};

TrimMoments MomentsAtTrim(const PlantParams &p) {
  const EnvironmentParams &e = p.env;
  if (e.trim_pose_rad.size() != p.links.size()) {
    std::ostringstream os;
    os << "TrimBallast: the trim pose needs " << p.links.size() << " joint angles (got "
       << e.trim_pose_rad.size() << ")";
    throw std::invalid_argument(os.str());
  }
  PlantParams nominal = p;
  nominal.payload_kg = e.trim_payload_kg;
  const ArmModel m = ArmModel::FromParams(nominal);
  const std::vector<double> still(p.links.size(), 0.0);
  ArmKinematics kin;
  ComputeArmKinematics(m, BaseState{}, e.trim_pose_rad.data(), still.data(), still.data(), kin);
  const double rho = e.density_kg_m3;
  TrimMoments t;
  t.weight_kg_m = e.trim_payload_kg * kin.payload_m;
  t.buoyancy_kg_m = rho * p.vehicle.volume_m3 * p.vehicle.cob_m;
  double volume_m3 = p.vehicle.volume_m3;
  for (int i = 1; i <= m.n; ++i) {
    const double vol = m.volume_m3[size_t(i - 1)];
    t.weight_kg_m += m.link[size_t(i - 1)].mass_kg * kin.com_m[size_t(i)];
    t.buoyancy_kg_m += rho * vol * kin.mid_m[size_t(i)];
    volume_m3 += vol;
  }
  t.buoyancy_kg = rho * volume_m3;
  return t;
}
}  // namespace

Ballast TrimBallast(const PlantParams &p) {
  const EnvironmentParams &e = p.env;
  Ballast b;
  b.mass_kg = TrimBallastKg(p, e.density_kg_m3, e.trim_payload_kg);
  if (!std::isfinite(e.metacentric_height_m)) {
    std::ostringstream os;
    os << "TrimBallast: metacentric height must be finite (got " << e.metacentric_height_m << ")";
    throw std::invalid_argument(os.str());
  }
  const TrimMoments t = MomentsAtTrim(p);
  if (!(std::abs(b.mass_kg) > 1e-6 * t.buoyancy_kg)) {
    std::ostringstream os;
    os << "TrimBallast: the untrimmed system is already neutral (ballast " << b.mass_kg
       << " kg): no ballast mass to place the center of gravity with";
    throw std::invalid_argument(os.str());
  }
  // SPEC §6.3: M·G = Σ m_k·x_k + m_b·b with M = ρ·V_T (trimmed) and G = B − h·e_z, where
  // M·B = ρ·Σ V_k·x_k: m_b·b = ρ·Σ V_k·x_k − ρ·V_T·h·e_z − Σ m_k·x_k.
  const Vec3 lowered = t.buoyancy_kg_m - t.buoyancy_kg * e.metacentric_height_m * Vec3::UnitZ();
  b.offset_m = (lowered - t.weight_kg_m) / b.mass_kg;
  return b;
}

std::vector<CoeffTableRow> DefaultCoeffTable() {
  // APPROXIMATION of the trend reported by McLain & Rock (1998) for a cylinder accelerated
  // from rest; the numbers are chosen to match SPEC §6.4's description, not taken from data.
  //        distance [d_L], drag factor, added-mass factor
  return {
      {0.0, 0.5, 1.0},    // at rest: wake not yet formed, low drag; full added mass
      {2.0, 0.9, 0.92},
      {5.0, 1.3, 0.85},   // drag overshoot
      {7.5, 1.1, 0.82},
      {10.0, 1.0, 0.8},   // settled; constant beyond
  };
}

void ValidateCoeffTable(const std::vector<CoeffTableRow> &table) {
  if (table.empty()) throw std::invalid_argument("coefficient table: empty (need >= 1 row)");
  for (std::size_t i = 0; i < table.size(); ++i) {
    const CoeffTableRow &r = table[i];
    std::ostringstream os;
    os << "coefficient table row " << i << " (distance " << r.distance_diameters << ", drag "
       << r.drag_factor << ", added mass " << r.added_mass_factor << "): ";
    if (!std::isfinite(r.distance_diameters) || !std::isfinite(r.drag_factor) ||
        !std::isfinite(r.added_mass_factor)) {
      throw std::invalid_argument(os.str() + "non-finite value");
    }
    if (r.distance_diameters < 0.0) {
      throw std::invalid_argument(os.str() + "negative distance");
    }
    if (r.drag_factor < 0.0 || r.added_mass_factor < 0.0) {
      throw std::invalid_argument(os.str() + "negative factor");
    }
    if (i > 0 && !(r.distance_diameters > table[i - 1].distance_diameters)) {
      throw std::invalid_argument(os.str() + "distances not strictly increasing");
    }
  }
}

CoeffFactors InterpolateCoeffs(const std::vector<CoeffTableRow> &table,
                               double distance_diameters) {
  if (table.empty()) throw std::invalid_argument("InterpolateCoeffs: empty coefficient table");
  if (std::isnan(distance_diameters)) {
    throw std::invalid_argument("InterpolateCoeffs: distance is NaN");
  }
  const CoeffTableRow &first = table.front();
  const CoeffTableRow &last = table.back();
  if (distance_diameters <= first.distance_diameters) {
    return {first.drag_factor, first.added_mass_factor};
  }
  if (distance_diameters >= last.distance_diameters) {
    return {last.drag_factor, last.added_mass_factor};
  }
  // first < d < last: find the segment [table[i−1], table[i]] containing d.
  std::size_t i = 1;
  while (table[i].distance_diameters < distance_diameters) ++i;
  const CoeffTableRow &a = table[i - 1];
  const CoeffTableRow &b = table[i];
  if (b.distance_diameters == distance_diameters) return {b.drag_factor, b.added_mass_factor};
  const double w = (distance_diameters - a.distance_diameters) /
                   (b.distance_diameters - a.distance_diameters);  // in (0, 1)
  return {a.drag_factor + w * (b.drag_factor - a.drag_factor),
          a.added_mass_factor + w * (b.added_mass_factor - a.added_mass_factor)};
}

}  // namespace uvms::plant
