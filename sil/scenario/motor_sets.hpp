// SPDX-License-Identifier: Apache-2.0
// motor_sets.hpp: the named propeller + motor parameter sets of the scenario key
// `thrusters.motor` (docs/SCENARIOS.md, docs/MODEL.md §5 "Motor parameter sets"). The sets are
// ONE table, in motor_sets.cpp; the key's choices, the scenario rule (sil/scenario/scenario.cpp,
// MotorSetRule) and the tests all read it.
//
// Precedence: a set fills every key of MotorSetKeys() that the scenario does not give; a key
// given explicitly (in the file or by --set) overrides the set's value. Without the key the
// set is "paper": the values of plant::PaperPlantParams() (SPEC §3.4, the paper's Tables
// VII–VIII), read at run time.
#pragma once

#include <array>
#include <string_view>
#include <vector>

#include "scenario/config_schema.hpp"  // Choice
#include "uvms_plant/params.hpp"

namespace uvms::sil {

/// One named set.
struct MotorSet {
  const char *name;    ///< the value of thrusters.motor
  const char *source;  ///< one line: where its values come from (details in docs/MODEL.md §5)
  plant::PropulsionParams (*params)();  ///< its values (the drive member is not part of a set)
};

/// Every named set, "paper" first (the default).
const std::vector<MotorSet> &MotorSets();

/// The set of that name; nullptr when there is none.
const MotorSet *FindMotorSet(std::string_view name);

/// The choices of thrusters.motor: each set's name, its index in MotorSets() as the value.
std::vector<Choice> MotorSetChoices();

/// One scenario key a set fills and the plant::PropulsionParams member behind it (the key's
/// row in sil/msg/config_table.h targets that member and the firmware's field alike).
struct MotorSetKey {
  const char *key;
  double plant::PropulsionParams::*member;
};

/// The ten keys a set fills: D, CT1, CT2, CQ1, CQ2, Rm, Lm, km, b, J (SPEC §3.4).
const std::array<MotorSetKey, 10> &MotorSetKeys();

}  // namespace uvms::sil
