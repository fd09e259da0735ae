// SPDX-License-Identifier: Apache-2.0
// The schema printed from the table of configuration fields (sil/scenario/config_schema.hpp):
//  - `uvms scenario schema` is JSON of the documented shape;
//  - it lists exactly the keys the scenario reader accepts (found by asking the reader: an
//    unknown key in every table, whose error lists that table's known keys);
//  - its defaults are what the reader gives a scenario that sets nothing;
//  - docs/SCENARIOS.md's key tables are the generator's (regenerate: uvms scenario schema
//    --markdown --update docs/SCENARIOS.md).
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "scenario/config_schema.hpp"
#include "scenario/scenario.hpp"
#include "cli/scenario_cmd.hpp"
#include "uvms_plant/environment.hpp"

#ifndef UVMS_SOURCE_DIR
#error "UVMS_SOURCE_DIR (the repository) must be defined by the build"
#endif

using uvms::sil::ConfigRow;
using uvms::sil::ConfigTable;
using uvms::sil::Json;

namespace {

const char kBase[] = "[control]\ncase = \"IV\"\n[environment]\nvariable_coefficients = true\n";

std::set<std::string> SchemaKeys() {
  std::set<std::string> keys;
  const Json schema = uvms::sil::SchemaJson();
  for (const Json &k : schema["keys"]) keys.insert(k["key"].get<std::string>());
  return keys;
}

bool AnyKeyStartsWith(const std::set<std::string> &keys, const std::string &prefix) {
  for (const std::string &k : keys)
    if (k.rfind(prefix, 0) == 0) return true;
  return false;
}

/// The reader's known keys of one table, from the error an unknown key there gets.
std::vector<std::string> KnownKeysOf(const std::string &table) {
  std::string set;
  if (table.size() > 2 && table.compare(table.size() - 2, 2, "[]") == 0) {
    // One element of the array of tables, its required fields given.
    const std::string array = table.substr(0, table.size() - 2);
    std::string element = "zzz_probe = 1";
    for (const ConfigRow *row : uvms::sil::ElementRows(array))
      if (row->IsRequired())
        element += ", " + row->Leaf() +
                   (row->type == uvms::sil::KeyType::kVec3     ? " = [1, 1, 1]"
                    : row->type == uvms::sil::KeyType::kString ? " = \"probe\""
                                                               : " = 1");
    set = array + "=[{" + element + "}]";
  } else {
    set = (table.empty() ? "" : table + ".") + "zzz_probe=1";
  }
  std::string err;
  try {
    (void)uvms::sil::ParseScenario(kBase, "probe.toml", {set});
  } catch (const uvms::sil::ScenarioError &e) {
    err = e.what();
  }
  INFO("probe " << set << ": " << err);
  const std::string marker = "unknown key (expected one of: ";
  const auto at = err.find(marker);
  REQUIRE(at != std::string::npos);
  std::vector<std::string> names;
  std::istringstream list(err.substr(at + marker.size(), err.rfind(')') - at - marker.size()));
  for (std::string name; std::getline(list, name, ',');) names.push_back(name.substr(name[0] == ' '));
  return names;
}

/// Every key the reader accepts: its tables walked from the root ("a.b", "a.c[].d").
std::set<std::string> ReaderKeys(const std::set<std::string> &schema) {
  std::set<std::string> keys;
  std::function<void(const std::string &)> walk = [&](const std::string &table) {
    for (const std::string &name : KnownKeysOf(table)) {
      const std::string key = table.empty() ? name : table + "." + name;
      if (AnyKeyStartsWith(schema, key + "[].")) {
        keys.insert(key);
        walk(key + "[]");
      } else if (AnyKeyStartsWith(schema, key + ".")) {
        walk(key);
      } else {
        keys.insert(key);
      }
    }
  };
  walk("");
  return keys;
}

std::string ReadFile(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST_CASE("SchemaIsJsonOfTheDocumentedShape", "[config_schema]") {
  const Json schema = Json::parse(uvms::sil::SchemaJson().dump());
  CHECK(schema["schema_version"] == 1);
  REQUIRE(schema["keys"].is_array());
  const std::set<std::string> types = {"real", "int", "bool", "string", "enum", "vec3", "array"};
  std::set<std::string> seen;
  for (const Json &k : schema["keys"]) {
    INFO(k.dump());
    CHECK(seen.insert(k["key"].get<std::string>()).second);
    CHECK(types.count(k["type"].get<std::string>()) == 1);
    for (const char *field : {"unit", "range", "doc"}) CHECK(k[field].is_string());
    for (const char *field : {"firmware", "lcm", "plant", "harness"})
      CHECK((k[field].is_null() || k[field].is_string()));
    CHECK(k.contains("default"));
  }
  // Spot checks of a few rows against the libraries they come from.
  const auto key = [&](const std::string &name) {
    for (const Json &k : schema["keys"])
      if (k["key"] == name) return k;
    FAIL("no key " << name);
    return Json();
  };
  CHECK(key("thrusters.kb_1_s")["firmware"] == "thruster[].current_gain_1_s");
  CHECK(key("thrusters.kb_1_s")["lcm"] == "current_gain_1_s");
  CHECK(key("payload.mass_kg")["plant"] == "payload_kg");
  CHECK(key("payload.mass_kg")["firmware"] == "arm.payload_kg");
  CHECK(key("thrusters.drive")["default"] == "current");
  CHECK(key("integrator.rel_tol")["default"] == uvms::plant::IntegratorParams{}.rel_tol);
  uvms_ctrl_config_t paper;
  REQUIRE(uvms_ctrl_config_paper(&paper, 4) == UVMS_OK);
  CHECK(key("limits.sensor_hold_max_ticks")["default"] == paper.limits.sensor_hold_max_ticks);
  const Json table = key("environment.coeff_table")["default"];
  const auto rows = uvms::plant::DefaultCoeffTable();
  REQUIRE(table.size() == rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    CHECK(table[i]["distance_diameters"] == rows[i].distance_diameters);
    CHECK(table[i]["drag_factor"] == rows[i].drag_factor);
    CHECK(table[i]["added_mass_factor"] == rows[i].added_mass_factor);
  }
}

TEST_CASE("SchemaListsExactlyTheKeysTheReaderAccepts", "[config_schema]") {
  const std::set<std::string> schema = SchemaKeys();
  const std::set<std::string> reader = ReaderKeys(schema);
  for (const std::string &k : reader) CHECK_THAT(k, Catch::Predicate<std::string>([&](const std::string &x) { return schema.count(x) == 1; }, "is in the schema"));
  for (const std::string &k : schema) CHECK_THAT(k, Catch::Predicate<std::string>([&](const std::string &x) { return reader.count(x) == 1; }, "is accepted by the reader"));
  CHECK(reader.size() == schema.size());
}

TEST_CASE("DefaultsAreWhatTheReaderGivesAScenarioThatSetsNothing", "[config_schema]") {
  const uvms::sil::Scenario s = uvms::sil::ParseScenario(kBase, "x.toml");
  for (const ConfigRow &row : ConfigTable()) {
    if (!row.HasKey() || row.dflt.kind != uvms::sil::DefaultSpec::Kind::kPaper) continue;
    if (row.key == std::string("environment.variable_coefficients")) continue;  // set in kBase
    const auto get = row.cpp_get != nullptr ? row.cpp_get : row.fw_get;
    if (get == nullptr) continue;  // element fields: their struct's own defaults
    INFO(row.key);
    Json got = get(s);
    if (row.type == uvms::sil::KeyType::kBool && got.is_number()) got = got.get<double>() != 0.0;
    if (row.type == uvms::sil::KeyType::kEnum) got = uvms::sil::ChoiceName(row, got.get<long>());
    CHECK(got == uvms::sil::DefaultJson(row));
  }
}

TEST_CASE("AKeyThatSetsBothSidesStartsThemFromTheSameValue", "[config_schema]") {
  // The reader gives the firmware the plant's (or the harness's) value of such a key also when
  // the key is absent: that must be the controller's own paper value, or a scenario that sets
  // nothing would change the controller.
  const uvms::sil::Scenario paper = uvms::sil::PaperScenario(4);
  for (const ConfigRow &row : ConfigTable()) {
    if (!row.HasKey() || row.by_rule || row.cpp_get == nullptr || row.fw_put == nullptr) continue;
    INFO(row.key);
    uvms::sil::Scenario s = paper;
    row.fw_put(s, row.cpp_get(paper));
    CHECK(row.fw_get(s) == row.fw_get(paper));
  }
}

TEST_CASE("EveryRealKeyTheTableWalkAppliesReachesItsTargets", "[config_schema]") {
  // A value in range (the multiple of 1/8 beyond its bound by 1/8 at least: exact in float and
  // its own shortest decimal, which is how a float build reports a firmware field) set with
  // --set arrives in the plant's or the harness's field and in the firmware's, for every such
  // row of the table (the motor and propeller keys included: thrusters.ct2 < 0 gets −0.125,
  // propeller_diameter_m ≥ 0.01 gets 0.25).
  for (const ConfigRow &row : ConfigTable()) {
    if (!row.HasKey() || row.by_rule || row.type != uvms::sil::KeyType::kReal) continue;
    INFO(row.key);
    const bool below = row.range.kind == uvms::sil::RangeRule::Kind::kBelow;
    const double x = below ? (std::floor(row.range.lo * 8.0) - 1.0) / 8.0
                           : (std::ceil(row.range.lo * 8.0) + 1.0) / 8.0;
    std::ostringstream set;
    set.precision(17);  // x to the last digit
    set << row.key << "=" << x;
    uvms::sil::Scenario s;
    REQUIRE_NOTHROW(s = uvms::sil::ParseScenario(kBase, "x.toml", {set.str()}));
    if (row.cpp_get != nullptr) CHECK(row.cpp_get(s) == x);
    if (row.fw_get != nullptr) CHECK(row.fw_get(s) == x);
  }
}

TEST_CASE("EveryArmLinkKeyReachesThatLinkOfBothModels", "[config_schema]") {
  // Each [[arm.link]] field set on link 3 of a three-link arm (a value exact in float, valid for
  // the field) arrives in the controller's arm.link[2] and, for the fields the plant has, in the
  // plant's links[2]; link 2 keeps the baseline's. Every LINK row of the table has such a key.
  const std::map<std::string, std::string> baseline = {
      {"alpha_rad", "0.0"}, {"a_m", "0.25"}, {"d_m", "0.0"}, {"mass_kg", "1.0"}, {"diameter_m", "0.0"},
      {"inertia_kg_m2", "[2.0, 2.0, 2.0]"}};  // room for the off-diagonal entries below
  int link_rows = 0;
  for (const ConfigRow *row : uvms::sil::ElementRows("arm.link")) {
    INFO(row->key);
    REQUIRE(row->fw_link_put != nullptr);
    REQUIRE(row->fw_link_get != nullptr);
    ++link_rows;
    const bool vec = row->type == uvms::sil::KeyType::kVec3;
    const bool six = row->type == uvms::sil::KeyType::kArray;  // added_mass_kg: 6 numbers
    const std::string leaf = row->Leaf();
    const Json want = vec   ? Json::array({0.25, 0.25, 0.375})
                      : six ? Json::array({0.25, 0.25, 0.375, 0.125, 0.125, 0.5})
                            : Json(leaf == "joint_min_rad" ? -0.375 : 0.375);
    std::string text = kBase;
    for (int i = 0; i < 3; ++i) {
      std::map<std::string, std::string> fields = baseline;
      if (i == 2) {
        fields[leaf] = vec   ? "[0.25, 0.25, 0.375]"
                       : six ? "[0.25, 0.25, 0.375, 0.125, 0.125, 0.5]"
                             : (leaf == "joint_min_rad" ? "-0.375" : "0.375");
        if (six) fields["diameter_m"] = "0.0625";  // a link's own added mass needs a cylinder
      }
      text += "[[arm.link]]\n";
      for (const auto &[k, v] : fields) text += k + " = " + v + "\n";
    }
    text += "[trajectory]\ntheta_start_deg = [0, 0, 0]\ntheta_final_deg = [0, 0, 0]\n";
    uvms::sil::Scenario s;
    REQUIRE_NOTHROW(s = uvms::sil::ParseScenario(text, "x.toml"));
    CHECK(row->fw_link_get(s, 2) == want);
    CHECK(row->fw_link_get(s, 1) != want);
    if (row->plant[0] != '\0') {  // the plant's part of the link
      uvms::sil::ArmLink plant_link;
      static_cast<uvms::plant::LinkParams &>(plant_link) = s.plant.links[2];
      CHECK(row->elem_get(&plant_link) == want);
    }
  }
  // Every firmware field of uvms_link_params_t has a key (fourteen LINK rows).
  CHECK(link_rows == 14);
}

TEST_CASE("EveryKeyTheTableWalkAppliesHasATarget", "[config_schema]") {
  for (const ConfigRow &row : ConfigTable()) {
    if (!row.HasKey() || row.by_rule) continue;
    INFO(row.key);
    CHECK((row.cpp_put != nullptr || row.fw_put != nullptr));
  }
}

TEST_CASE("DocKeyTablesAreGeneratedFromTheTable", "[config_schema]") {
  const std::string path = std::string(UVMS_SOURCE_DIR) + "/docs/SCENARIOS.md";
  const std::string doc = ReadFile(path);
  REQUIRE_FALSE(doc.empty());
  std::string generated;
  REQUIRE_NOTHROW(generated = uvms::sil::UpdateGeneratedBlocks(doc));
  if (generated != doc)
    FAIL("docs/SCENARIOS.md's key tables differ from sil/msg/config_table.h; regenerate them with\n"
         "  build/host/sil/uvms scenario schema --markdown --update docs/SCENARIOS.md");
  CHECK(uvms::sil::SchemaMarkdown().find("| `kb_1_s` | 1/s | 5 | > 0 |") != std::string::npos);
}

TEST_CASE("SchemaCli", "[config_schema]") {
  std::ostringstream out, err;
  CHECK(uvms::sil::RunScenarioCli({"schema"}, out, err) == 0);
  CHECK(Json::parse(out.str())["schema_version"] == 1);
  std::ostringstream md, err2;
  CHECK(uvms::sil::RunScenarioCli({"schema", "--markdown"}, md, err2) == 0);
  CHECK(md.str() == uvms::sil::SchemaMarkdown());
  std::ostringstream help, err3;
  CHECK(uvms::sil::RunScenarioCli({"schema", "--help"}, help, err3) == 0);
  CHECK(help.str().rfind("usage: uvms scenario check FILE", 0) == 0);
  std::ostringstream out4, err4;
  CHECK(uvms::sil::RunScenarioCli({"schema", "--bogus"}, out4, err4) == 2);
  CHECK(uvms::sil::RunScenarioCli({"schema", "--update", "x.md"}, out4, err4) == 2);
}
