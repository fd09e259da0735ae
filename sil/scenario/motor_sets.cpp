// SPDX-License-Identifier: Apache-2.0
// motor_sets.cpp: THE table of named propeller + motor parameter sets (motor_sets.hpp). Each
// set's values and their source are documented in docs/MODEL.md §5 "Motor parameter sets".
#include "scenario/motor_sets.hpp"

namespace uvms::sil {
namespace {

using plant::PropulsionParams;

/// SPEC §3.4 (the paper's Tables VII–VIII): the plant's own paper values, never copied.
PropulsionParams PaperSet() { return plant::PaperPlantParams().propulsion; }

/// Blue Robotics T200 at a 16 V bus (docs/MODEL.md §5 "The T200 set"): fitted by
/// tools/thruster_fit.py to Blue Robotics' published bollard data, "T200 Public Performance Data
/// 10-20V September 2019" (https://cad.bluerobotics.com/T200-Public-Performance-Data-10-20V-
/// September-2019.xlsx, sheet "16 V"), transcribed with its citation in
/// tests/tools/data/t200_16V_bollard.csv (186 points, 308–3533 rpm, −39.9 to +51.5 N, up to
/// 389 W). D: the published 76 mm. CT2 from thrust vs RPM (ρ = 1000 kg/m³); b, CQ2, Rm/km² from
/// supply power vs RPM; km from the bus voltage at full throttle. CT1, CQ1: not identifiable
/// from bollard data, 0. J, Lm: stated estimates, not measured. Positive thrust needs negative
/// ω (CT2 < 0, as the paper's); CQ2 > 0: the water loads the shaft (Q·ω > 0), unlike the
/// paper's (C12). Checked against the data by tests/tools/test_thruster_fit.py.
PropulsionParams T200Set() {
  PropulsionParams p;
  p.diameter_m = 0.076;              // published propeller diameter, 76 mm
  p.ct1 = 0.0;                       // not identifiable from bollard data
  p.ct2 = -0.3734;                   // thrust vs RPM
  p.cq1 = 0.0;                       // not identifiable from bollard data
  p.cq2 = 0.05849;                   // power vs RPM
  p.resistance_ohm = 0.3350;         // power vs RPM (Rm/km²) and km; ESC and cable included
  p.inductance_H = 5.0e-5;           // estimate: Lm/Rm = 0.15 ms, far below the 0.03 s tick
  p.torque_constant_Nm_A = 0.02166;  // 16 V at full throttle (duty 1); ≈ 441 rpm/V
  p.viscous_friction_Nm_s = 2.893e-5;  // power vs RPM
  p.rotor_inertia_kg_m2 = 2.0e-5;    // estimate: rotor bell, magnets, propeller, entrained water
  return p;
}

}  // namespace

const std::vector<MotorSet> &MotorSets() {
  static const std::vector<MotorSet> sets = {
      {"paper", "SPEC §3.4, the paper's Tables VII–VIII (plant::PaperPlantParams())", PaperSet},
      {"t200", "Blue Robotics T200 at 16 V, fitted to its published bollard data (tools/thruster_fit.py)",
       T200Set},
  };
  return sets;
}

const MotorSet *FindMotorSet(std::string_view name) {
  for (const MotorSet &set : MotorSets())
    if (name == set.name) return &set;
  return nullptr;
}

std::vector<Choice> MotorSetChoices() {
  std::vector<Choice> choices;
  const std::vector<MotorSet> &sets = MotorSets();
  for (std::size_t i = 0; i < sets.size(); ++i) choices.push_back({sets[i].name, static_cast<long>(i)});
  return choices;
}

const std::array<MotorSetKey, 10> &MotorSetKeys() {
  static const std::array<MotorSetKey, 10> keys = {{
      {"thrusters.propeller_diameter_m", &PropulsionParams::diameter_m},
      {"thrusters.ct1", &PropulsionParams::ct1},
      {"thrusters.ct2", &PropulsionParams::ct2},
      {"thrusters.cq1", &PropulsionParams::cq1},
      {"thrusters.cq2", &PropulsionParams::cq2},
      {"thrusters.resistance_ohm", &PropulsionParams::resistance_ohm},
      {"thrusters.inductance_H", &PropulsionParams::inductance_H},
      {"thrusters.torque_constant_Nm_A", &PropulsionParams::torque_constant_Nm_A},
      {"thrusters.viscous_friction_Nm_s", &PropulsionParams::viscous_friction_Nm_s},
      {"thrusters.rotor_inertia_kg_m2", &PropulsionParams::rotor_inertia_kg_m2},
  }};
  return keys;
}

}  // namespace uvms::sil
