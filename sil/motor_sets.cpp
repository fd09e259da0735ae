// SPDX-License-Identifier: Apache-2.0
// motor_sets.cpp: THE table of named propeller + motor parameter sets (motor_sets.hpp). Each
// set's values and their source are documented in docs/MODEL.md §5 "Motor parameter sets".
#include "motor_sets.hpp"

namespace uvms::sil {
namespace {

using plant::PropulsionParams;

/// SPEC §3.4 (the paper's Tables VII–VIII): the plant's own paper values, never copied.
PropulsionParams PaperSet() { return plant::PaperPlantParams().propulsion; }

}  // namespace

const std::vector<MotorSet> &MotorSets() {
  static const std::vector<MotorSet> sets = {
      {"paper", "SPEC §3.4, the paper's Tables VII–VIII (plant::PaperPlantParams())", PaperSet},
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
