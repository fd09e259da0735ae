// SPDX-License-Identifier: Apache-2.0
// config_schema.hpp: the table of configuration fields (sil/msg/config_table.h) as a runtime table
// for C++: what each row says (key, firmware path, LCM field, plant or harness path, type, unit,
// range rule, default, doc) and what the scenario reader does with it (read a value into its
// targets), plus the machine-readable schema (`uvms scenario schema`, JSON) and the key tables
// of docs/SCENARIOS.md (`uvms scenario schema --markdown`), both printed from the rows.
//
// Defaults are never copied into the table: a PAPER default is read, at run time, from the
// configurations the reader starts from (PaperScenario: uvms_ctrl_config_paper(),
// plant::PaperPlantParams(), the plant's and the harness's default-constructed structs).
#pragma once

#include <nlohmann/json.hpp>

#include <string>
#include <string_view>
#include <vector>

#include "scenario/scenario.hpp"

namespace uvms::sil {

using Json = nlohmann::ordered_json;

/// The TOML value of a key (schema "type").
enum class KeyType { kReal, kInt, kBool, kString, kEnum, kVec3, kArray };

/// "real", "int", "bool", "string", "enum", "vec3", "array".
const char *KeyTypeName(KeyType type);

/// One value of an enum key: its name in the scenario and its value in the targets.
struct Choice {
  const char *name;
  long value;
};

/// What the reader checks on a given value (after its type). See sil/msg/config_table.h.
struct RangeRule {
  enum class Kind {
    kAny,          ///< any value of the type (numbers finite)
    kAtLeast,      ///< >= lo
    kAbove,        ///< > lo
    kBelow,        ///< < lo
    kIntIn,        ///< integer in lo..hi
    kIntAtLeast,   ///< integer >= lo
    kProbability,  ///< [0, 1]
    kFraction,     ///< [0, 1)
    kNonEmpty,     ///< non-empty string
    kNonZero,      ///< vector of norm >= lo
    kReals,        ///< exactly lo finite numbers
    kRealsAtLeast, ///< exactly lo finite numbers, each >= hi
    kOneOf,        ///< one of choices (error "expected one of: a, b")
    kEither,       ///< one of choices (error "expected \"a\" or \"b\"")
    kTables,       ///< an array of tables (the elements' rows follow)
    kSpecial,      ///< checked by a cross-key rule; `text` says what
  };
  Kind kind{Kind::kAny};
  double lo{0.0};
  double hi{0.0};
  std::vector<Choice> choices;
  const char *text{""};
};

/// Where a key's default comes from.
struct DefaultSpec {
  enum class Kind {
    kPaper,  ///< the row's target in PaperScenario() (or the element type's default)
    kValue,  ///< value(): the reader's own default, given in the table (or computed)
    kNote,   ///< none single: note says what it is
  };
  Kind kind{Kind::kPaper};
  Json (*value)(){nullptr};
  const char *note{nullptr};  ///< kNote; for kValue, how the doc shows it (null: the value)
};

/// One row of sil/msg/config_table.h.
struct ConfigRow {
  const char *key;       ///< scenario key, "" for a firmware field without one
  const char *firmware;  ///< uvms_ctrl_config_t member path, "" when none
  const char *lcm;       ///< controller_config_t field, "" when none
  Json (*fw_get)(const Scenario &);         ///< the firmware field (null: none, or a per-link field)
  void (*fw_put)(Scenario &, const Json &);
  /// A LINK row's field of the controller's arm.link[i], a THR row's of thruster[i] (null for
  /// the other map kinds); i below UVMS_MAX_JOINTS (LINK), UVMS_MAX_THRUSTERS (THR), else
  /// nothing is written (get: null).
  void (*fw_link_put)(Scenario &, std::size_t i, const Json &);
  Json (*fw_link_get)(const Scenario &, std::size_t i);
  const char *plant;    ///< plant::PlantParams path, "" when none
  const char *harness;  ///< Scenario path, "" when none
  bool by_rule;         ///< applied by a cross-key rule (or an array's rule), not the table walk
  Json (*cpp_get)(const Scenario &);        ///< the plant/harness target (null: none)
  void (*cpp_put)(Scenario &, const Json &);  ///< (null: none, or a rule applies the key)
  Json (*elem_get)(const void *element);    ///< a field of an array element (ELEM_* rows)
  Json (*elem_default)();
  void (*elem_put)(void *element, const Json &);
  KeyType type;
  const char *unit;
  RangeRule range;
  DefaultSpec dflt;
  const char *doc;

  bool HasKey() const { return key[0] != '\0'; }
  /// "environment.unsteady_flow" for "environment.unsteady_flow.enabled"; "contact.obstacle[]"
  /// for "contact.obstacle[].name"; "" for a key at the root.
  std::string Section() const;
  std::string Leaf() const;  ///< "enabled", "name"
  bool IsElement() const;    ///< a field of an array of tables
  bool IsRequired() const;   ///< an element field without a default (NOTE("required"))
};

/// Every row, in the table's order.
const std::vector<ConfigRow> &ConfigTable();

/// The row of a scenario key. std::logic_error when there is none (a programming error).
const ConfigRow &ConfigRowOf(std::string_view key);

/// The rows of the elements of the array of tables `key` ("contact.obstacle").
std::vector<const ConfigRow *> ElementRows(std::string_view key);

/// The configurations every scenario starts from: the controller from
/// uvms_ctrl_config_paper(case_number) (case IV's when 0), the plant from PaperPlantParams(),
/// the harness from Scenario{}.
Scenario PaperScenario(int case_number);

/// The name of an enum key's value ("" when none).
std::string ChoiceName(const ConfigRow &row, long value);

/// A retired choice of an enum key (sil/msg/config_table.h, UVMS_RETIRED_CHOICES): never
/// reused, refused with the replacement named.
struct RetiredChoice {
  const char *key;          ///< scenario key, "thrusters.allocation"
  const char *name;         ///< the retired name, "min_abs_thrust"
  long value;               ///< its retired enum value
  const char *replacement;  ///< the choice to use instead
  const char *why;          ///< why it was retired
};

/// The retired choice of `key` with this name, or with this value; nullptr when none.
const RetiredChoice *RetiredChoiceNamed(std::string_view key, std::string_view name);
const RetiredChoice *RetiredChoiceValued(std::string_view key, long value);

/// "\"min_abs_thrust\" (value 1) is retired: <why>; use \"min_power\"".
std::string RetiredText(const RetiredChoice &r);

/// The range rule as text ("≥ 0", "integer 0..100", "\"a\" | \"b\"", ...).
std::string RangeText(const ConfigRow &row);

/// A key's default as JSON (enums by name; null when it has no single value).
Json DefaultJson(const ConfigRow &row);

/// `uvms scenario schema`: {"schema_version": 1, "keys": [{"key", "type", "unit", "default",
/// "range", "firmware", "lcm", "plant", "harness", "doc"}, ...]}, every scenario key.
Json SchemaJson();

/// The sections that have generated key tables, in the table's order ("run", ...,
/// "contact.obstacle[]", ...).
std::vector<std::string> SchemaSections();

/// One section's generated block for docs/SCENARIOS.md: the BEGIN marker, the key table and
/// the END marker.
std::string SchemaMarkdownBlock(const std::string &section);

/// `uvms scenario schema --markdown`: every section's block.
std::string SchemaMarkdown();

/// `doc` with every generated block replaced by the generator's (`--markdown --update`).
/// std::runtime_error when a section's block is missing, repeated or unknown, or a BEGIN
/// marker has no END.
std::string UpdateGeneratedBlocks(const std::string &doc);

}  // namespace uvms::sil
