// SPDX-License-Identifier: Apache-2.0
// The one place plant and firmware meet (SPEC §5, §7.4): the controller's desired-speed
// solution [57–63] (firmware, C, uvms_real_t) fed into the truth model's thrust law (plant,
// C++, double) must give back the requested thrust. Two independent implementations of the
// same sign conventions and law; a mismatch in either shows up here.
#include <catch2/catch.hpp>

#include <cmath>

#include "uvms/thruster.h"
#include "uvms/types.h"
#include "uvms_plant/params.hpp"
#include "uvms_plant/propulsion.hpp"

using namespace uvms::plant;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr double kRho = 1025.0;  // SPEC §3.2 [kg/m³]
}  // namespace

TEST_CASE("PlantAndFirmwarePaperThrusterParametersAgree", "[propulsion][firmware]") {
  uvms_thruster_params_t fw;
  uvms_thruster_params_paper(&fw);
  const PropulsionParams pl = PaperPlantParams().propulsion;
  // Exact in the double build; the firmware's values rounded to float otherwise.
  auto same = [](double plant, uvms_real_t firmware) {
    return static_cast<uvms_real_t>(plant) == firmware;
  };
  CHECK(same(pl.diameter_m, fw.diameter_m));
  CHECK(same(pl.ct1, fw.ct1));
  CHECK(same(pl.ct2, fw.ct2));
  CHECK(same(pl.cq1, fw.cq1));
  CHECK(same(pl.cq2, fw.cq2));
  CHECK(same(pl.resistance_ohm, fw.resistance_ohm));
  CHECK(same(pl.inductance_H, fw.inductance_H));
  CHECK(same(pl.torque_constant_Nm_A, fw.torque_constant_Nm_A));
  CHECK(same(pl.viscous_friction_Nm_s, fw.viscous_friction_Nm_s));
  CHECK(same(pl.rotor_inertia_kg_m2, fw.rotor_inertia_kg_m2));
}

TEST_CASE("PlantThrustAtFirmwareDesiredSpeedEqualsRequestedThrust", "[propulsion][firmware]") {
  uvms_thruster_params_t fw;
  uvms_thruster_params_paper(&fw);
  const PropulsionParams pl = PaperPlantParams().propulsion;
  const double kT = kRho * std::pow(pl.diameter_m, 4) / (4 * kPi * kPi);  // [kg/m]

  for (double T_mag : {0.01, 1.0, 5.0, 50.0}) {
    for (double sign : {1.0, -1.0}) {
      for (double va : {-1.0, -0.3, 0.0, 0.3, 1.0}) {
        // The firmware sees its real type; the plant is evaluated at exactly those values so
        // that only the two implementations (and the firmware's rounding) are compared.
        const uvms_real_t T_fw = static_cast<uvms_real_t>(sign * T_mag);
        const uvms_real_t va_fw = static_cast<uvms_real_t>(va);
        uvms_real_t w_fw = 0;
        REQUIRE(uvms_thruster_desired_speed(&fw, static_cast<uvms_real_t>(kRho), T_fw, va_fw,
                                            &w_fw) == UVMS_OK);
        const double T_hat = static_cast<double>(T_fw);
        const double w = static_cast<double>(w_fw);
        const double T_plant = ThrustN(pl, kRho, w, static_cast<double>(va_fw));
        const double rel_err = std::abs(T_plant - T_hat) / std::abs(T_hat);
        // Sum of the magnitudes of the law's two terms: with v_a < 0 they nearly cancel for
        // small thrusts (0.01 N at v_a = −1 m/s: terms ≈ 1.3 N each), which amplifies the
        // rounding of ω and of the float parameters by that ratio.
        const double term_scale =
            kT * (std::abs(pl.ct2) * w * w +
                  std::abs(pl.ct1 * 2 * kPi * static_cast<double>(va_fw) / pl.diameter_m) *
                      std::abs(w));
        INFO("T_hat = " << T_hat << " N, v_a = " << va << " m/s, omega = " << w
                        << " rad/s, plant T = " << T_plant << " N, rel. error " << rel_err
                        << ", cancellation ratio " << term_scale / std::abs(T_hat));
        // ω has the sign SPEC §5 requires: positive thrust needs negative speed.
        CHECK(w * T_hat < 0.0);
#if UVMS_REAL_IS_FLOAT
        // Float: ω and D, CT·, ρ rounded to float (relative 2⁻²⁴ ≈ 6e-8 each) and the speed
        // solved in float: a backward error of a few float ulps of the term scale.
        CHECK(std::abs(T_plant - T_hat) <= 1e-6 * term_scale);
#else
        CHECK(rel_err <= 1e-9);
#endif
      }
    }
  }
}
