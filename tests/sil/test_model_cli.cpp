// SPDX-License-Identifier: Apache-2.0
// `uvms model` (sil/cli/model_cmd.cpp) through its own functions:
//  - parsing: a valid input reaches the firmware unchanged; every missing, unknown, mistyped,
//    mis-sized or non-finite field is reported by name; config overrides and their errors;
//  - physics: the results are the firmware's own (bit for bit, same real type), and two
//    physical identities that do not use the CLI: a still arm in vacuum without gravity loads
//    nothing, a still arm under gravity hangs its weight (SPEC §3.1 masses) on the vehicle;
//  - the subcommand as a whole on string streams (exit codes, one error line).
// The real binary is exercised by test_model_cli_e2e.py.
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli/model_cmd.hpp"
#include "uvms/dynamics.h"
#include "uvms/feedforward.h"
#include "uvms/linalg.h"

using json = nlohmann::json;
using namespace uvms::cli;

namespace {

constexpr bool kFloat = UVMS_REAL_IS_FLOAT != 0;
// Relative tolerance of a few hundred operations in the build's real type.
constexpr double kRelTol = kFloat ? 2e-5 : 1e-12;

// Sum of the link masses of SPEC §3.1: 10.77 + 3.87 + 1.80 + 2.40 + 0.12 + 0.42 + 0.07 [kg].
constexpr double kArmMassKg = 19.45;

// One state as plain doubles, the way a user writes it.
struct RawState {
  double r0[3]{}, q[4]{1, 0, 0, 0}, v0[3]{}, w0[3]{}, a0[3]{}, al0[3]{};
  double th[7]{}, thd[7]{}, thdd[7]{};
  double rho{}, flow[3]{}, g[3]{}, payload{};
  bool aoa{};
};

RawState RandomState(std::mt19937 &rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RawState s;
  for (int k = 0; k < 3; ++k) {
    s.r0[k] = 3 * u(rng);
    s.v0[k] = 0.3 * u(rng);
    s.w0[k] = 0.2 * u(rng);
    s.a0[k] = 0.5 * u(rng);
    s.al0[k] = 0.4 * u(rng);
    s.flow[k] = 0.1 * u(rng);
  }
  for (double &c : s.q) c = u(rng);  // not normalised: the model must normalise it
  for (int j = 0; j < 7; ++j) {
    s.th[j] = 3 * u(rng);
    s.thd[j] = u(rng);
    s.thdd[j] = 2 * u(rng);
  }
  s.rho = 1025;  // an integer in the JSON text: accepted as a number
  s.g[2] = -9.81;
  s.payload = 5 + 5 * u(rng);
  s.aoa = u(rng) > 0;
  return s;
}

json Arr(const double *v, std::size_t n) { return json(std::vector<double>(v, v + n)); }

json ToJson(const RawState &s, std::size_t n = 7) {
  return json{{"vehicle",
               {{"position_m", Arr(s.r0, 3)},
                {"quaternion_wxyz", Arr(s.q, 4)},
                {"velocity_m_s", Arr(s.v0, 3)},
                {"angular_velocity_rad_s", Arr(s.w0, 3)},
                {"acceleration_m_s2", Arr(s.a0, 3)},
                {"angular_acceleration_rad_s2", Arr(s.al0, 3)}}},
              {"joints",
               {{"position_rad", Arr(s.th, n)},
                {"velocity_rad_s", Arr(s.thd, n)},
                {"acceleration_rad_s2", Arr(s.thdd, n)}}},
              {"density_kg_m3", s.rho},
              {"flow_m_s", Arr(s.flow, 3)},
              {"gravity_m_s2", Arr(s.g, 3)},
              {"payload_kg", s.payload},
              {"angle_of_attack", s.aoa}};
}

void Cast(const double *in, std::size_t n, uvms_real_t *out) {
  for (std::size_t i = 0; i < n; ++i) out[i] = uvms_real_t(in[i]);
}

// The firmware inputs built directly, without the CLI.
uvms_base_state_t BaseOf(const RawState &s) {
  uvms_base_state_t b{};
  Cast(s.r0, 3, b.position_m);
  uvms_real_t q[4];
  Cast(s.q, 4, q);
  REQUIRE(uvms_quat_to_rot(q, b.R0) == UVMS_OK);
  Cast(s.v0, 3, b.velocity_m_s);
  Cast(s.w0, 3, b.omega_rad_s);
  Cast(s.a0, 3, b.accel_m_s2);
  Cast(s.al0, 3, b.alpha_rad_s2);
  return b;
}

uvms_fluid_t FluidOf(const RawState &s) {
  uvms_fluid_t f{};
  f.density_kg_m3 = uvms_real_t(s.rho);
  Cast(s.flow, 3, f.flow_m_s);
  Cast(s.g, 3, f.gravity_m_s2);
  f.angle_of_attack = s.aoa ? 1 : 0;
  return f;
}

uvms_arm_params_t PaperParams() {
  uvms_arm_params_t p;
  uvms_arm_params_paper(&p);
  return p;
}

// The InputError message ParseModelInput gives, or "" when it accepts the input.
std::string InputErrorOf(const json &j, std::size_t n = 7) {
  try {
    ParseModelInput(j, n);
  } catch (const InputError &e) {
    return e.what();
  }
  return "";
}

std::string ConfigErrorOf(const json &config) {
  uvms_arm_params_t p = PaperParams();
  try {
    ApplyModelConfig(config, "cfg.json", &p);
    ValidateModelParams(p, "cfg.json");
  } catch (const InputError &e) {
    return e.what();
  }
  return "";
}

bool Contains(const std::string &s, const std::string &part) {
  return s.find(part) != std::string::npos;
}

// Every input field, as a JSON pointer and as the name the errors use.
struct Field {
  const char *pointer;
  const char *name;
  std::size_t length;  // 0: scalar
};
const Field kFields[] = {
    {"/vehicle/position_m", "vehicle.position_m", 3},
    {"/vehicle/quaternion_wxyz", "vehicle.quaternion_wxyz", 4},
    {"/vehicle/velocity_m_s", "vehicle.velocity_m_s", 3},
    {"/vehicle/angular_velocity_rad_s", "vehicle.angular_velocity_rad_s", 3},
    {"/vehicle/acceleration_m_s2", "vehicle.acceleration_m_s2", 3},
    {"/vehicle/angular_acceleration_rad_s2", "vehicle.angular_acceleration_rad_s2", 3},
    {"/joints/position_rad", "joints.position_rad", 7},
    {"/joints/velocity_rad_s", "joints.velocity_rad_s", 7},
    {"/joints/acceleration_rad_s2", "joints.acceleration_rad_s2", 7},
    {"/density_kg_m3", "density_kg_m3", 0},
    {"/flow_m_s", "flow_m_s", 3},
    {"/gravity_m_s2", "gravity_m_s2", 3},
    {"/payload_kg", "payload_kg", 0},
    {"/angle_of_attack", "angle_of_attack", 0},
};

// Erase the member a JSON pointer names.
void Erase(json &j, const char *pointer) {
  const json::json_pointer p(pointer);
  j[p.parent_pointer()].erase(p.back());
}

}  // namespace

TEST_CASE("ValidInputReachesTheFirmwareUnchanged", "[model_cli][parse]") {
  std::mt19937 rng(20240611);
  for (int trial = 0; trial < 5; ++trial) {
    const RawState s = RandomState(rng);
    // Through text, as on stdin.
    const ModelInput in = ParseModelInput(ParseJsonText(ToJson(s).dump(), "stdin"), 7);
    const uvms_base_state_t b = BaseOf(s);
    CHECK(in.num_joints == 7);
    for (int k = 0; k < 3; ++k) {
      CHECK(in.base.position_m[k] == b.position_m[k]);
      CHECK(in.base.velocity_m_s[k] == b.velocity_m_s[k]);
      CHECK(in.base.omega_rad_s[k] == b.omega_rad_s[k]);
      CHECK(in.base.accel_m_s2[k] == b.accel_m_s2[k]);
      CHECK(in.base.alpha_rad_s2[k] == b.alpha_rad_s2[k]);
      CHECK(in.fluid.flow_m_s[k] == uvms_real_t(s.flow[k]));
      CHECK(in.fluid.gravity_m_s2[k] == uvms_real_t(s.g[k]));
    }
    for (int j = 0; j < 7; ++j) {
      CHECK(in.q_rad[j] == uvms_real_t(s.th[j]));
      CHECK(in.qd_rad_s[j] == uvms_real_t(s.thd[j]));
      CHECK(in.qdd_rad_s2[j] == uvms_real_t(s.thdd[j]));
    }
    CHECK(in.fluid.density_kg_m3 == uvms_real_t(s.rho));
    CHECK(in.fluid.angle_of_attack == (s.aoa ? 1 : 0));
    CHECK(in.payload_kg == uvms_real_t(s.payload));
    // The attitude is the normalised quaternion's rotation, vehicle → inertial (Eigen's
    // convention for a body-to-world quaternion), although the input was not normalised.
    const Eigen::Matrix3d R_ref =
        Eigen::Quaterniond(s.q[0], s.q[1], s.q[2], s.q[3]).normalized().toRotationMatrix();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) CHECK(std::abs(double(in.base.R0[3 * r + c]) - R_ref(r, c)) < 10 * kRelTol);
  }
}

TEST_CASE("EveryMissingFieldIsNamed", "[model_cli][parse]") {
  std::mt19937 rng(7);
  const json valid = ToJson(RandomState(rng));
  REQUIRE(InputErrorOf(valid).empty());
  for (const Field &f : kFields) {
    json j = valid;
    Erase(j, f.pointer);
    INFO(f.name);
    CHECK(InputErrorOf(j) == std::string("missing field \"") + f.name + "\"");
  }
  for (const char *group : {"/vehicle", "/joints"}) {
    json j = valid;
    Erase(j, group);
    CHECK(InputErrorOf(j) == std::string("missing field \"") + (group + 1) + "\"");
  }
}

TEST_CASE("UnknownFieldsAreNamed", "[model_cli][parse]") {
  std::mt19937 rng(8);
  const json valid = ToJson(RandomState(rng));
  const std::pair<const char *, const char *> cases[] = {
      {"/payload", "payload"},                          // a near miss at the top level
      {"/vehicle/velocity_ms", "vehicle.velocity_ms"},  // a typo inside "vehicle"
      {"/joints/effort_Nm", "joints.effort_Nm"},
  };
  for (const auto &[pointer, name] : cases) {
    json j = valid;
    j[json::json_pointer(pointer)] = 1.0;
    INFO(name);
    CHECK(InputErrorOf(j) == std::string("unknown field \"") + name + "\"");
  }
  CHECK(Contains(InputErrorOf(json::array({valid})), "must be a JSON object"));
}

// JSON text of `doc` with the member at `pointer` given twice (nlohmann::json keeps the last of
// two equal keys, so the text is built by hand): a copy first, with the value `first`, then the
// original. One level of nesting at most (the input's and the config's objects).
std::string WithDuplicate(const json &doc, const std::string &pointer, const json &first) {
  const json::json_pointer p(pointer);
  const std::string key = p.back();
  const auto object_with = [&](const json &object) {  // "{"key":first," + the object's members
    return "{" + json(key).dump() + ":" + first.dump() + "," + object.dump().substr(1);
  };
  if (p.parent_pointer().empty()) return object_with(doc);
  const std::string group = p.parent_pointer().back();
  json rest = doc;
  rest.erase(group);
  return "{" + json(group).dump() + ":" + object_with(doc[group]) + "," + rest.dump().substr(1);
}

std::string ParseErrorOf(const std::string &text, const std::string &source = "stdin") {
  try {
    ParseJsonText(text, source);
  } catch (const InputError &e) {
    return e.what();
  }
  return "";
}

TEST_CASE("DuplicateKeysAreRefusedAndNamed", "[model_cli][parse]") {
  std::mt19937 rng(12);
  const json valid = ToJson(RandomState(rng));
  REQUIRE(ParseErrorOf(valid.dump()).empty());
  // Every input field given twice, the first time with another value: which was meant?
  for (const Field &f : kFields) {
    INFO(f.name);
    const std::string text = WithDuplicate(valid, f.pointer, json(0.5));
    REQUIRE(json::parse(text) == valid);  // nlohmann alone drops the first value, silently
    CHECK(ParseErrorOf(text) == std::string("stdin: duplicate key \"") + f.name +
                                    "\": each key may appear once in an object");
  }
  for (const char *group : {"/vehicle", "/joints"}) {
    INFO(group);
    CHECK(ParseErrorOf(WithDuplicate(valid, group, json::object())) ==
          std::string("stdin: duplicate key \"") + (group + 1) +
              "\": each key may appear once in an object");
  }
  // In a config: the path through arrays of objects, and arrays of arrays.
  CHECK(ParseErrorOf(R"({"links": [{}, {"mass_kg": 1, "d_m": 0.1, "mass_kg": 2}]})", "cfg.json") ==
        "cfg.json: duplicate key \"links[1].mass_kg\": each key may appear once in an object");
  CHECK(ParseErrorOf(R"({"a": [[1, [2]], {"b": 1}, {"c": {"d": 1, "e": [], "d": 2}}]})", "c") ==
        "c: duplicate key \"a[2].c.d\": each key may appear once in an object");
  // The same key in different objects, or a value equal to a key, is no duplicate.
  CHECK(ParseErrorOf(R"({"vehicle": {"mass_kg": 1}, "links": [{"mass_kg": 1}, {"mass_kg": 2}],
                         "mass_kg": "mass_kg"})").empty());
}

TEST_CASE("WrongTypesAreNamed", "[model_cli][parse]") {
  std::mt19937 rng(9);
  const json valid = ToJson(RandomState(rng));
  for (const Field &f : kFields) {
    const std::string name = std::string("field \"") + f.name;
    INFO(f.name);
    for (const json &bad : {json("1.0"), json(nullptr), json::object(), json(true)}) {
      if (std::string(f.name) == "angle_of_attack" && bad.is_boolean()) continue;
      json j = valid;
      j[json::json_pointer(f.pointer)] = bad;
      CHECK(Contains(InputErrorOf(j), name + "\""));
    }
    json j = valid;
    j[json::json_pointer(f.pointer)] = f.length > 0 ? json(1.0) : json::array({1.0});
    CHECK(Contains(InputErrorOf(j), name + "\""));
    if (f.length > 0) {  // one element of the wrong type
      j = valid;
      j[json::json_pointer(f.pointer)][1] = "x";
      CHECK(Contains(InputErrorOf(j), name + "[1]\": expected a number, got string"));
    }
  }
  // angle_of_attack is a boolean, not 0/1.
  json j = valid;
  j["angle_of_attack"] = 1;
  CHECK(InputErrorOf(j) == "field \"angle_of_attack\": expected true or false, got number");
  // The groups themselves.
  j = valid;
  j["joints"] = json::array();
  CHECK(InputErrorOf(j) == "field \"joints\" must be a JSON object, got array");
}

TEST_CASE("WrongArrayLengthsAreNamed", "[model_cli][parse]") {
  std::mt19937 rng(10);
  const json valid = ToJson(RandomState(rng));
  for (const Field &f : kFields) {
    if (f.length == 0) continue;
    INFO(f.name);
    const std::string prefix = std::string("field \"") + f.name + "\": expected " +
                               std::to_string(f.length) + " elements";
    json longer = valid;
    longer[json::json_pointer(f.pointer)].push_back(0.0);
    CHECK(Contains(InputErrorOf(longer), prefix));
    CHECK(Contains(InputErrorOf(longer), "got " + std::to_string(f.length + 1)));
    json shorter = valid;
    shorter[json::json_pointer(f.pointer)].erase(0);
    CHECK(Contains(InputErrorOf(shorter), prefix));
  }
  // The joint arrays follow the model's joint count (a config with 3 links).
  CHECK(Contains(InputErrorOf(valid, 3), "field \"joints.position_rad\": expected 3 elements"));
  RawState s = RandomState(rng);
  CHECK(InputErrorOf(ToJson(s, 3), 3).empty());
}

TEST_CASE("NonFiniteNumbersAreNamed", "[model_cli][parse]") {
  // JSON text cannot carry NaN or infinity (the parser rejects 1e400 as an overflow), but a
  // json value built in code can; every number is checked.
  std::mt19937 rng(11);
  const json valid = ToJson(RandomState(rng));
  const double bad_values[] = {std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity()};
  for (const Field &f : kFields) {
    if (std::string(f.name) == "angle_of_attack") continue;
    INFO(f.name);
    for (const double x : bad_values) {
      json j = valid;
      std::string where = f.name;
      if (f.length > 0) {
        j[json::json_pointer(f.pointer)][f.length - 1] = x;
        where += "[" + std::to_string(f.length - 1) + "]";
      } else {
        j[json::json_pointer(f.pointer)] = x;
      }
      CHECK(InputErrorOf(j) == "field \"" + where + "\": not a finite number");
    }
  }
  // Through text: an overflowing literal is a JSON error.
  try {
    ParseJsonText(R"({"density_kg_m3": 1e400})", "stdin");
    FAIL("1e400 accepted");
  } catch (const InputError &e) {
    CHECK(Contains(e.what(), "stdin: invalid JSON: "));
    CHECK(Contains(e.what(), "1e400"));
  }
}

TEST_CASE("OutOfRangeValuesAreNamed", "[model_cli][parse]") {
  std::mt19937 rng(12);
  const json valid = ToJson(RandomState(rng));
  json j = valid;
  j["density_kg_m3"] = -1.0;
  CHECK(InputErrorOf(j) == "field \"density_kg_m3\": must be >= 0, got -1");
  j = valid;
  j["payload_kg"] = -0.5;
  CHECK(InputErrorOf(j) == "field \"payload_kg\": must be >= 0, got -0.5");
  j = valid;
  j["vehicle"]["quaternion_wxyz"] = {0.0, 0.0, 0.0, 0.0};
  CHECK(Contains(InputErrorOf(j), "field \"vehicle.quaternion_wxyz\": norm 0 is below 1e-6"));
  j["vehicle"]["quaternion_wxyz"] = {4e-7, 4e-7, 4e-7, 4e-7};  // norm 8e-7
  CHECK(Contains(InputErrorOf(j), "field \"vehicle.quaternion_wxyz\": norm"));
  j["vehicle"]["quaternion_wxyz"] = {0.0, 0.0, 0.0, 2e-6};  // tiny but valid: 180° about z
  CHECK(InputErrorOf(j).empty());
  // Zero density and payload are valid.
  j = valid;
  j["density_kg_m3"] = 0;
  j["payload_kg"] = 0;
  CHECK(InputErrorOf(j).empty());
  if (kFloat) {  // finite in double, infinite in the float controller
    j = valid;
    j["flow_m_s"][2] = 1e39;
    const std::string e = InputErrorOf(j);
    CHECK(Contains(e, "field \"flow_m_s[2]\": "));
    CHECK(Contains(e, "1e+39 is out of range of the controller's real type (float)"));
  }
}

TEST_CASE("ConfigOverridesApplyKeyByKey", "[model_cli][config]") {
  const uvms_arm_params_t paper = PaperParams();
  uvms_arm_params_t p = paper;
  const json config = {
      {"vehicle",
       {{"mass_kg", 80.0}, {"cob_m", {0.0, 0.0, 0.05}}, {"ballast_kg", -1.5},
        {"ballast_offset_m", {-0.3, 0.1, -0.2}}}},
      {"payload_offset_m", {0.0, 0.0, 0.1}},
      {"links", {{{"mass_kg", 5.0}}, json::object(), {{"d_m", 0.4}, {"com_m", {0.0, -0.2, 0.0}}}}},
      {"added_mass_coeff", std::vector<double>(36, 0.0)}};
  ApplyModelConfig(config, "cfg.json", &p);
  ValidateModelParams(p, "cfg.json");
  CHECK(p.vehicle.mass_kg == uvms_real_t(80.0));
  CHECK(p.vehicle.volume_m3 == paper.vehicle.volume_m3);  // untouched
  CHECK(p.vehicle.cob_m[2] == uvms_real_t(0.05));
  CHECK(p.vehicle.ballast_kg == uvms_real_t(-1.5));
  CHECK(p.vehicle.ballast_offset_m[0] == uvms_real_t(-0.3));
  CHECK(p.vehicle.ballast_offset_m[2] == uvms_real_t(-0.2));
  CHECK(p.payload_offset_m[2] == uvms_real_t(0.1));
  CHECK(p.num_joints == 3);  // the length of "links"
  CHECK(p.link[0].mass_kg == uvms_real_t(5.0));
  CHECK(p.link[0].alpha_rad == paper.link[0].alpha_rad);
  CHECK(p.link[1].mass_kg == paper.link[1].mass_kg);
  CHECK(p.link[2].d_m == uvms_real_t(0.4));
  CHECK(p.link[2].com_m[1] == uvms_real_t(-0.2));
  CHECK(p.link[2].a_m == paper.link[2].a_m);
  for (double c : p.added_mass_coeff) CHECK(c == 0.0);
  CHECK(p.payload_kg == paper.payload_kg);  // the payload comes from the input, not the config
}

TEST_CASE("ConfigErrorsNameFileAndKey", "[model_cli][config]") {
  const std::pair<json, std::string> cases[] = {
      {{{"vehicel", json::object()}}, "cfg.json: unknown key \"vehicel\""},
      {{{"vehicle", {{"mass", 80.0}}}}, "cfg.json: unknown key \"vehicle.mass\""},
      {{{"links", {json::object(), {{"length_m", 1.0}}}}}, "cfg.json: unknown key \"links[1].length_m\""},
      {{{"vehicle", {{"mass_kg", "heavy"}}}},
       "cfg.json: key \"vehicle.mass_kg\": expected a number, got string"},
      {{{"vehicle", {{"inertia_kg_m2", {1.0, 2.0}}}}},
       "cfg.json: key \"vehicle.inertia_kg_m2\": expected 3 elements, got 2"},
      {{{"added_mass_coeff", std::vector<double>(35, 0.0)}},
       "cfg.json: key \"added_mass_coeff\": expected 36 elements, got 35"},
      {{{"links", json::object()}}, "cfg.json: key \"links\": expected an array of link objects, got object"},
      {{{"links", {1.0}}}, "cfg.json: key \"links[0]\" must be a JSON object, got number"},
      {json::array(), "cfg.json: the config must be a JSON object, got array"},
  };
  for (const auto &[config, message] : cases) {
    INFO(config.dump());
    CHECK(ConfigErrorOf(config) == message);
  }
  // More links than the arm has (UVMS_MAX_JOINTS = 7).
  const std::string too_many = ConfigErrorOf({{"links", json(std::vector<json>(8, json::object()))}});
  CHECK(Contains(too_many, "cfg.json: key \"links\": 8 entries, at most 7"));
  CHECK(Contains(too_many, "\"links[7]\""));
  CHECK(ConfigErrorOf({{"links", json(std::vector<json>(7, json::object()))}}).empty());
}

TEST_CASE("InvalidParametersReportTheFirmwareStatus", "[model_cli][config]") {
  CHECK(ConfigErrorOf({{"vehicle", {{"mass_kg", 0.0}}}}) ==
        "cfg.json: invalid model parameters: UVMS_ERR_RANGE (uvms_arm_model_init)");
  CHECK(ConfigErrorOf({{"links", {json::object(), {{"mass_kg", -1.0}}}}}) ==
        "cfg.json: invalid model parameters: UVMS_ERR_RANGE (uvms_arm_model_init)");
  CHECK(ConfigErrorOf({{"links", json::array()}}) ==
        "cfg.json: invalid model parameters: UVMS_ERR_SIZE (uvms_arm_model_init)");
}

TEST_CASE("ConfigFileIsReadAndItsErrorsNameIt", "[model_cli][config]") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::string good = (dir / "uvms_model_cli_test_good.json").string();
  const std::string bad = (dir / "uvms_model_cli_test_bad.json").string();
  std::ofstream(good) << R"({"vehicle": {"mass_kg": 60}, "links": [{}, {}]})";
  std::ofstream(bad) << R"({"vehicle": {"mass_kg": 60,}})";
  const uvms_arm_params_t p = LoadModelParams(good);
  CHECK(p.vehicle.mass_kg == uvms_real_t(60.0));
  CHECK(p.num_joints == 2);
  CHECK_THROWS_WITH(LoadModelParams(bad), Catch::StartsWith(bad + ": invalid JSON: "));
  CHECK_THROWS_WITH(LoadModelParams(good + ".missing"),
                    Catch::StartsWith(good + ".missing: cannot open config file"));
  std::remove(good.c_str());
  std::remove(bad.c_str());
  // No config: the paper's parameters.
  const uvms_arm_params_t paper = PaperParams();
  const uvms_arm_params_t def = LoadModelParams("");
  CHECK(def.vehicle.mass_kg == paper.vehicle.mass_kg);
  CHECK(def.num_joints == 7);
}

TEST_CASE("ResultsAreTheFirmwaresBitForBit", "[model_cli][physics]") {
  // The CLI pipeline (text → ParseModelInput → ComputeModel → JSON text) against direct
  // firmware calls in the same real type on inputs built here. Equality is exact: the same
  // functions on the same inputs; the printed numbers read back to the same doubles.
  std::mt19937 rng(31415);
  const uvms_arm_params_t paper = PaperParams();
  static uvms_arm_data_t d, scratch;
  for (int trial = 0; trial < 6; ++trial) {
    RawState s = RandomState(rng);
    if (trial == 5) s.rho = 0;  // vacuum
    const ModelInput in = ParseModelInput(ParseJsonText(ToJson(s).dump(), "stdin"), 7);
    const ModelResult r = ComputeModel(paper, in);
    const json out = json::parse(ModelResultToJson(r).dump());

    uvms_arm_params_t p = paper;
    p.payload_kg = uvms_real_t(s.payload);
    uvms_arm_model_t m;
    REQUIRE(uvms_arm_model_init(&p, &m) == UVMS_OK);
    const uvms_base_state_t b = BaseOf(s);
    const uvms_fluid_t fl = FluidOf(s);
    uvms_real_t q[7], qd[7], qdd[7];
    Cast(s.th, 7, q);
    Cast(s.thd, 7, qd);
    Cast(s.thdd, 7, qdd);
    REQUIRE(uvms_arm_rnea(&m, &d, &b, &fl, q, qd, qdd) == UVMS_OK);
    uvms_feedforward_t ffv, ffb;
    REQUIRE(uvms_feedforward(&m, &scratch, &fl, UVMS_REF_VEHICLE, &b, q, qd, qdd, &ffv) == UVMS_OK);
    REQUIRE(uvms_feedforward(&m, &scratch, &fl, UVMS_REF_BARYCENTER, &b, q, qd, qdd, &ffb) == UVMS_OK);

    auto same = [&](const json &a, const uvms_real_t *v, std::size_t n, const char *what) {
      INFO("trial " << trial << ": " << what);
      REQUIRE(a.size() == n);
      for (std::size_t k = 0; k < n; ++k) CHECK(a[k].get<double>() == double(v[k]));
    };
    same(out["ee_position_m"], d.ee_m, 3, "ee_position_m");
    same(out["barycenter_m"], d.barycenter_m, 3, "barycenter_m");
    same(out["base_point_m"], d.p_m[0], 3, "base_point_m");
    REQUIRE(out["link_com_m"].size() == 7);
    for (std::size_t i = 1; i <= 7; ++i) same(out["link_com_m"][i - 1], d.com_m[i], 3, "link_com_m");
    same(out["base_force_N"], d.f_N[1], 3, "base_force_N");
    same(out["base_moment_Nm"], d.n_Nm[1], 3, "base_moment_Nm");
    same(out["joint_torque_Nm"], &d.tau_Nm[1], 7, "joint_torque_Nm");
    same(out["vehicle_drag_N"], d.drag_N[0], 3, "vehicle_drag_N");
    const json &ff = out["feedforward"];
    same(ff["attitude_moment_Nm"], ffv.moment_att_Nm, 3, "attitude_moment_Nm");
    same(ff["vehicle_force_N"], ffv.force_vehicle_N, 3, "vehicle_force_N");
    same(ff["barycenter_force_N"], ffb.force_barycenter_N, 3, "barycenter_force_N");
    same(ff["attitude_moment_barycenter_Nm"], ffb.moment_att_Nm, 3, "attitude_moment_barycenter_Nm");
    same(ff["barycenter_accel_m_s2"], ffb.base_accel_m_s2, 3, "barycenter_accel_m_s2");
    // Not vacuous: the state really loads the arm, and the input accelerations matter to
    // Newton–Euler but not to the feedforward block.
    CHECK(Eigen::Vector3d(d.f_N[1][0], d.f_N[1][1], d.f_N[1][2]).norm() > 1.0);
    CHECK(d.f_N[1][0] != ffv.base_force_N[0]);
  }
}

TEST_CASE("StillArmInVacuumWithoutGravityLoadsNothing", "[model_cli][physics]") {
  // ρ = 0, g = 0, nothing moves: every force and moment of SPEC §4 is zero, whatever the pose.
  std::mt19937 rng(1618);
  for (int trial = 0; trial < 4; ++trial) {
    RawState s = RandomState(rng);
    for (int k = 0; k < 3; ++k) s.v0[k] = s.w0[k] = s.a0[k] = s.al0[k] = s.flow[k] = s.g[k] = 0;
    for (int j = 0; j < 7; ++j) s.thd[j] = s.thdd[j] = 0;
    s.rho = 0;
    const ModelResult r = ComputeModel(PaperParams(), ParseModelInput(ToJson(s), 7));
    const json out = ModelResultToJson(r);
    for (const char *key : {"base_force_N", "base_moment_Nm", "joint_torque_Nm", "vehicle_drag_N"}) {
      INFO(key << " = " << out[key].dump());
      for (const json &x : out[key]) CHECK(std::abs(x.get<double>()) < 1e-12);
    }
  }
}

TEST_CASE("StillArmUnderGravityHangsItsWeightOnTheVehicle", "[model_cli][physics]") {
  // ρ = 0, arm and vehicle still: the vehicle holds the arm and payload up,
  // f1 = −(Σ m_i + m_payload)·g with Σ m_i from SPEC §3.1, and the moment about the base point
  // is that of the weights: n1 = Σ_k (c_k − p_B) × (−m_k·g) (payload at the EE).
  std::mt19937 rng(4242);
  for (const double payload_kg : {0.0, 2.0, 10.0}) {
    RawState s = RandomState(rng);
    for (int k = 0; k < 3; ++k) s.v0[k] = s.w0[k] = s.a0[k] = s.al0[k] = s.flow[k] = 0;
    for (int j = 0; j < 7; ++j) s.thd[j] = s.thdd[j] = 0;
    s.rho = 0;
    s.g[0] = 0.4;  // a tilted gravity vector: nothing in the model may assume g ∥ z
    s.g[1] = -0.3;
    s.g[2] = -9.81;
    s.payload = payload_kg;
    const json out =
        ModelResultToJson(ComputeModel(PaperParams(), ParseModelInput(ToJson(s), 7)));
    auto vec = [](const json &a) {
      return Eigen::Vector3d(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
    };
    const Eigen::Vector3d g(s.g[0], s.g[1], s.g[2]);
    const Eigen::Vector3d f_expected = -(kArmMassKg + payload_kg) * g;
    const Eigen::Vector3d f1 = vec(out["base_force_N"]);
    INFO("payload " << payload_kg << " kg: f1 = " << f1.transpose());
    CHECK((f1 - f_expected).norm() < kRelTol * f_expected.norm());

    const uvms_arm_params_t p = PaperParams();
    const Eigen::Vector3d pB = vec(out["base_point_m"]);
    Eigen::Vector3d n_expected = (vec(out["ee_position_m"]) - pB).cross(-payload_kg * g);
    for (int i = 0; i < 7; ++i)
      n_expected += (vec(out["link_com_m"][i]) - pB).cross(-double(p.link[i].mass_kg) * g);
    const Eigen::Vector3d n1 = vec(out["base_moment_Nm"]);
    CHECK((n1 - n_expected).norm() < kRelTol * 10 * (1 + n_expected.norm()));
    CHECK(n_expected.norm() > 1.0);
  }
}

TEST_CASE("BarycenterIsTheMassWeightedMeanAndFollowsTheConfigMass", "[model_cli][physics]") {
  // p_cm = (m0·r0 + Σ m_i·c_i + m_p·p_EE) / m_T [5], from the printed positions; a lighter
  // vehicle (config) moves it toward the arm.
  std::mt19937 rng(99);
  const RawState s = RandomState(rng);
  const ModelInput in = ParseModelInput(ToJson(s), 7);
  auto vec = [](const json &a) {
    return Eigen::Vector3d(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
  };
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  for (const double m0 : {120.0, 60.0}) {
    uvms_arm_params_t p = PaperParams();
    ApplyModelConfig({{"vehicle", {{"mass_kg", m0}}}}, "cfg.json", &p);
    const json out = ModelResultToJson(ComputeModel(p, in));
    const Eigen::Vector3d r0(s.r0[0], s.r0[1], s.r0[2]);
    Eigen::Vector3d sum = m0 * r0 + s.payload * vec(out["ee_position_m"]);
    double mT = m0 + s.payload;
    for (int i = 0; i < 7; ++i) {
      sum += double(p.link[i].mass_kg) * vec(out["link_com_m"][i]);
      mT += double(p.link[i].mass_kg);
    }
    const Eigen::Vector3d pcm = vec(out["barycenter_m"]);
    INFO("m0 = " << m0 << " p_cm = " << pcm.transpose());
    CHECK((pcm - sum / mT).norm() < kRelTol * 10 * (1 + r0.norm()));
    if (m0 != 120.0) CHECK((pcm - previous).norm() > 1e-3);
    previous = pcm;
  }
}

TEST_CASE("ArgumentsParse", "[model_cli][args]") {
  CHECK_FALSE(ParseModelArgs({}).help);
  CHECK(ParseModelArgs({}).config_path.empty());
  CHECK(ParseModelArgs({"--config", "a.json"}).config_path == "a.json");
  CHECK(ParseModelArgs({"--config=b.json"}).config_path == "b.json");
  CHECK(ParseModelArgs({"-h"}).help);
  CHECK(ParseModelArgs({"--help", "--config", "a.json"}).help);
  CHECK_THROWS_AS(ParseModelArgs({"--config"}), UsageError);
  CHECK_THROWS_AS(ParseModelArgs({"--config="}), UsageError);
  CHECK_THROWS_AS(ParseModelArgs({"--config", "a", "--config", "b"}), UsageError);
  CHECK_THROWS_WITH(ParseModelArgs({"--bogus"}), "unknown option \"--bogus\"");
  CHECK_THROWS_AS(ParseModelArgs({"input.json"}), UsageError);
}

TEST_CASE("SubcommandExitCodesAndOneErrorLine", "[model_cli][run]") {
  std::mt19937 rng(5);
  const std::string valid = ToJson(RandomState(rng)).dump(2);  // multi-line input is fine
  auto run = [](const std::vector<std::string> &args, const std::string &stdin_text,
                std::string *out, std::string *err) {
    std::istringstream in(stdin_text);
    std::ostringstream o, e;
    const int code = RunModelCli(args, in, o, e);
    *out = o.str();
    *err = e.str();
    return code;
  };
  auto lines = [](const std::string &s) {
    return std::count(s.begin(), s.end(), '\n');
  };
  std::string out, err;
  REQUIRE(run({}, valid, &out, &err) == kExitOk);
  CHECK(err.empty());
  CHECK(lines(out) == 1);
  CHECK(json::parse(out).is_object());

  for (const std::string &bad : std::vector<std::string>{"garbage", "", "{\"vehicle\": {}", valid + " trailing"}) {
    INFO("stdin: " << bad.substr(0, 40));
    CHECK(run({}, bad, &out, &err) == kExitBadInput);
    CHECK(out.empty());
    CHECK(lines(err) == 1);
    CHECK(Contains(err, "uvms model: error: stdin: invalid JSON: "));
  }
  json missing = json::parse(valid);
  missing["joints"].erase("velocity_rad_s");
  CHECK(run({}, missing.dump(), &out, &err) == kExitBadInput);
  CHECK(err == "uvms model: error: missing field \"joints.velocity_rad_s\"\n");

  CHECK(run({"--frobnicate"}, valid, &out, &err) == kExitUsage);
  CHECK(Contains(err, "unknown option \"--frobnicate\""));
  CHECK(Contains(err, "usage: uvms model"));

  CHECK(run({"--help"}, "", &out, &err) == kExitOk);
  CHECK(out == ModelHelpText());
}

TEST_CASE("HelpDocumentsEveryInputOutputAndConfigKey", "[model_cli][help]") {
  const std::string help = ModelHelpText();
  std::set<std::string> keys;
  // Output keys, from the output itself.
  std::mt19937 rng(3);
  const json out = ModelResultToJson(ComputeModel(PaperParams(), ParseModelInput(ToJson(RandomState(rng)), 7)));
  for (const auto &item : out.items()) {
    keys.insert(item.key());
    if (item.value().is_object())
      for (const auto &inner : item.value().items()) keys.insert(inner.key());
  }
  CHECK(keys.size() == 14);  // 9 top-level + 5 feedforward
  // Input keys, from a valid input.
  const json in = ToJson(RandomState(rng));
  for (const auto &item : in.items()) {
    keys.insert(item.key());
    if (item.value().is_object())
      for (const auto &inner : item.value().items()) keys.insert(inner.key());
  }
  // Config keys: every one the parser accepts is documented.
  for (const char *k : {"mass_kg", "volume_m3", "frontal_area_m2", "drag_coeff", "inertia_kg_m2",
                        "cob_m", "base_offset_m", "ballast_kg", "ballast_offset_m",
                        "payload_offset_m", "links",
                        "alpha_rad", "a_m", "d_m", "com_m", "diameter_m", "added_mass_coeff"}) {
    keys.insert(k);
  }
  for (const std::string &k : keys) {
    INFO(k);
    CHECK(Contains(help, "\"" + k + "\""));
  }
  // The feedforward block's acceleration assumption is stated.
  CHECK(Contains(help, "IGNORE the input"));
}
