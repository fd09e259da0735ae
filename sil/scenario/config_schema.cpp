// SPDX-License-Identifier: Apache-2.0
// config_schema.cpp: the runtime table of configuration fields, expanded from
// sil/msg/config_table.h, and the schema printers (config_schema.hpp).
#include "scenario/config_schema.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "msg/config_table.h"
#include "msg/link_limits.h"  // UVMS_SPIN_US_MAX
#include "scenario/motor_sets.hpp"  // MotorSetChoices
#include "uvms_plant/environment.hpp"

namespace uvms::sil {
namespace {

// ---- values <-> the targets' types (the reader's values are JSON) ---------------------------

/// The shortest decimal that reads back as the same float (so a float build prints 0.05, not
/// 0.0500000007, and both builds print the same schema).
double ShortestFloat(float x) {
  char buf[32];
  for (int p = 1; p <= 9; ++p) {
    std::snprintf(buf, sizeof buf, "%.*g", p, static_cast<double>(x));
    const double d = std::strtod(buf, nullptr);
    if (static_cast<float>(d) == x) return d;
  }
  return static_cast<double>(x);
}

Json ToJson(double x) { return x; }
[[maybe_unused]] Json ToJson(float x) { return ShortestFloat(x); }
Json ToJson(bool b) { return b; }
Json ToJson(const std::string &s) { return s; }
template <class T, std::enable_if_t<std::is_integral_v<T>, int> = 0>
Json ToJson(T x) {
  return x;
}
template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
Json ToJson(E e) {
  return static_cast<long>(e);
}
Json ToJson(const plant::Vec3 &v) { return Json::array({v[0], v[1], v[2]}); }
Json ToJson(const Eigen::Quaterniond &q) { return Json::array({q.w(), q.x(), q.y(), q.z()}); }
/// A 6×6 matrix as 36 numbers, row-major (the firmware's layout of the same field).
Json ToJson(const plant::Mat6 &m) {
  Json out = Json::array();
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < 6; ++c) out.push_back(m(r, c));
  return out;
}
/// A matrix that may be absent (null: the default stands in for it).
Json ToJson(const std::optional<plant::Mat6> &m) { return m ? ToJson(*m) : Json(nullptr); }
template <class T, std::size_t N>
Json ToJson(const T (&a)[N]) {
  Json out = Json::array();
  for (const T &x : a) out.push_back(ToJson(x));
  return out;
}
template <class T>
Json ToJson(const std::vector<T> &elements);  // arrays of tables, below

void FromJson(const Json &v, double &x) { x = v.get<double>(); }
[[maybe_unused]] void FromJson(const Json &v, float &x) { x = static_cast<float>(v.get<double>()); }
void FromJson(const Json &v, bool &b) { b = v.is_boolean() ? v.get<bool>() : v.get<long long>() != 0; }
void FromJson(const Json &v, std::string &s) { s = v.get<std::string>(); }
template <class T, std::enable_if_t<std::is_integral_v<T>, int> = 0>
void FromJson(const Json &v, T &x) {
  x = static_cast<T>(v.is_boolean() ? (v.get<bool>() ? 1 : 0) : v.get<long long>());
}
template <class E, std::enable_if_t<std::is_enum_v<E>, int> = 0>
void FromJson(const Json &v, E &e) {
  e = static_cast<E>(v.get<long>());
}
void FromJson(const Json &v, plant::Vec3 &x) {
  for (int k = 0; k < 3; ++k) x[k] = v.at(k).get<double>();
}
template <class T, std::size_t N>
void FromJson(const Json &v, T (&a)[N]) {
  for (std::size_t i = 0; i < N; ++i) FromJson(v.at(i), a[i]);
}

// The two enums that one key sets on both sides must agree value for value.
static_assert(static_cast<int>(plant::MotorDrive::kCurrent) == UVMS_DRIVE_CURRENT &&
                  static_cast<int>(plant::MotorDrive::kVoltage) == UVMS_DRIVE_VOLTAGE,
              "thrusters.drive sets plant::MotorDrive and uvms_drive_t by one value");

/// The array of tables whose elements have type T.
template <class T>
struct ElementKey;
template <>
struct ElementKey<plant::CoeffTableRow> {
  static constexpr const char *kKey = "environment.coeff_table";
};
template <>
struct ElementKey<plant::CylinderObstacle> {
  static constexpr const char *kKey = "contact.obstacle";
};
template <>
struct ElementKey<plant::ThrusterGeometry> {
  static constexpr const char *kKey = "thrusters.thruster";
};
template <>
struct ElementKey<ThrusterFault> {
  static constexpr const char *kKey = "faults.thruster";
};

/// Bools as bools and enums by name (targets hold them as integers).
Json Normalise(const ConfigRow &row, Json v) {
  if (row.type == KeyType::kBool && v.is_number()) return v.get<double>() != 0.0;
  if (row.type == KeyType::kEnum && v.is_number_integer()) return ChoiceName(row, v.get<long>());
  return v;
}

template <class T>
Json ToJson(const std::vector<T> &elements) {
  Json out = Json::array();
  for (const T &e : elements) {
    Json o = Json::object();
    for (const ConfigRow *row : ElementRows(ElementKey<T>::kKey))
      if (row->elem_get != nullptr)  // a field a rule reads (not in T) has no value here
        o[row->Leaf()] = Normalise(*row, row->elem_get(&e));
    out.push_back(o);
  }
  return out;
}

// ---- defaults computed from the libraries (FN rows) ------------------------------------------

Json ThetaStartDegDefault() { return PaperThetaStartDeg(); }
Json CoeffTableDefault() { return ToJson(plant::DefaultCoeffTable()); }
/// limits.thrust_limit_N: the paper configuration's (every thruster has the same).
Json PaperThrustLimitDefault() {
  uvms_ctrl_config_t cfg;
  (void)uvms_ctrl_config_paper(&cfg, 4);
  return ToJson(cfg.limits.thrust_limit_N[0]);
}

// ---- the expansion of sil/msg/config_table.h -----------------------------------------------------

// map kind -> firmware path, LCM field, firmware accessors
#define FW_GET_(fw) [](const Scenario &s) -> Json { return ToJson(s.controller.fw); }
#define FW_PUT_(fw) [](Scenario &s, const Json &v) { FromJson(v, s.controller.fw); }
#define FW_LINK_PUT_(fw)                                                   \
  [](Scenario &s, std::size_t i, const Json &v) {                          \
    if (i < UVMS_MAX_JOINTS) FromJson(v, s.controller.arm.link[i].fw);     \
  }
#define FW_LINK_GET_(fw)                                                                 \
  [](const Scenario &s, std::size_t i) -> Json {                                         \
    return i < UVMS_MAX_JOINTS ? ToJson(s.controller.arm.link[i].fw) : Json(nullptr);    \
  }
#define FWPART_REAL(fw, lcm) #fw, #lcm, FW_GET_(fw), FW_PUT_(fw), nullptr, nullptr
#define FWPART_LINK(fw, lcm) \
  "arm.link[]." #fw, #lcm, nullptr, nullptr, FW_LINK_PUT_(fw), FW_LINK_GET_(fw)
// THR: the key sets every thruster's member (fw_put), reads thruster 1's (fw_get); a type's
// rule sets one thruster's (fw_link_put/fw_link_get by thruster index).
#define FW_THR_PUT_ALL_(fw)                                                          \
  [](Scenario &s, const Json &v) {                                                   \
    for (uvms_thruster_params_t &t : s.controller.thruster) FromJson(v, t.fw);       \
  }
#define FW_THR_PUT_(fw)                                                  \
  [](Scenario &s, std::size_t j, const Json &v) {                        \
    if (j < UVMS_MAX_THRUSTERS) FromJson(v, s.controller.thruster[j].fw); \
  }
#define FW_THR_GET_(fw)                                                                \
  [](const Scenario &s, std::size_t j) -> Json {                                       \
    return j < UVMS_MAX_THRUSTERS ? ToJson(s.controller.thruster[j].fw) : Json(nullptr); \
  }
#define FWPART_THR(fw, lcm)                                                                \
  "thruster[]." #fw, #lcm, FW_GET_(thruster[0].fw), FW_THR_PUT_ALL_(fw), FW_THR_PUT_(fw), \
      FW_THR_GET_(fw)
#define FWPART_COUNT(fw, lcm) FWPART_REAL(fw, lcm)
#define FWPART_FLAG(fw, lcm) FWPART_REAL(fw, lcm)
#define FWPART_SWITCH(fw, lcm) FWPART_REAL(fw, lcm)
#define FWPART_ENUM(fw, lcm) FWPART_REAL(fw, lcm)
#define FWPART_U32(fw, lcm) FWPART_REAL(fw, lcm)
#define FWPART_NONE(fw, lcm) "", "", nullptr, nullptr, nullptr, nullptr
// target -> plant path, harness path, by_rule, plant/harness accessors, element accessors
#define CPP_GET_(ref) [](const Scenario &s) -> Json { return ToJson(s.ref); }
#define CPP_PUT_(ref) [](Scenario &s, const Json &v) { FromJson(v, s.ref); }
#define NO_ELEM_ nullptr, nullptr, nullptr
#define ELEM_(T, member)                                                                    \
  [](const void *e) -> Json { return ToJson(static_cast<const T *>(e)->member); },         \
      []() -> Json { return ToJson(T{}.member); },                                         \
      [](void *e, const Json &v) { FromJson(v, static_cast<T *>(e)->member); }
#define TPART_FW "", "", false, nullptr, nullptr, NO_ELEM_
#define TPART_RULE "", "", true, nullptr, nullptr, NO_ELEM_
#define TPART_P(path) #path, "", false, CPP_GET_(plant.path), CPP_PUT_(plant.path), NO_ELEM_
#define TPART_H(path) "", #path, false, CPP_GET_(path), CPP_PUT_(path), NO_ELEM_
#define TPART_RULE_P(path) #path, "", true, CPP_GET_(plant.path), nullptr, NO_ELEM_
#define TPART_RULE_H(path) "", #path, true, CPP_GET_(path), nullptr, NO_ELEM_
#define TPART_ELEM_P(container, T, member) \
  #container "[]." #member, "", true, nullptr, nullptr, ELEM_(T, member)
#define TPART_ELEM_H(container, T, member) \
  "", #container "[]." #member, true, nullptr, nullptr, ELEM_(T, member)
#define TPART_ELEM(T, member) "", "", true, nullptr, nullptr, ELEM_(T, member)
// type
#define TYPE_real KeyType::kReal
#define TYPE_int KeyType::kInt
#define TYPE_bool KeyType::kBool
#define TYPE_string KeyType::kString
#define TYPE_enum KeyType::kEnum
#define TYPE_vec3 KeyType::kVec3
#define TYPE_array KeyType::kArray
// range rule
#define RULE_(kind, lo, hi) RangeRule{RangeRule::Kind::kind, lo, hi, {}, ""}
#define RANGE_ANY RULE_(kAny, 0.0, 0.0)
#define RANGE_GE(x) RULE_(kAtLeast, static_cast<double>(x), 0.0)
#define RANGE_GT(x) RULE_(kAbove, static_cast<double>(x), 0.0)
#define RANGE_LT(x) RULE_(kBelow, static_cast<double>(x), 0.0)
#define RANGE_INT(lo, hi) RULE_(kIntIn, static_cast<double>(lo), static_cast<double>(hi))
#define RANGE_INT_GE(lo) RULE_(kIntAtLeast, static_cast<double>(lo), 0.0)
#define RANGE_PROB RULE_(kProbability, 0.0, 1.0)
#define RANGE_FRACTION RULE_(kFraction, 0.0, 1.0)
#define RANGE_NONEMPTY RULE_(kNonEmpty, 0.0, 0.0)
#define RANGE_NONZERO(min_norm) RULE_(kNonZero, static_cast<double>(min_norm), 0.0)
#define RANGE_REALS(n) RULE_(kReals, static_cast<double>(n), 0.0)
#define RANGE_REALS_GE(n, x) RULE_(kRealsAtLeast, static_cast<double>(n), static_cast<double>(x))
#define RANGE_ONE_OF(...) RangeRule{RangeRule::Kind::kOneOf, 0.0, 0.0, {__VA_ARGS__}, ""}
#define RANGE_ONE_OF_FN(f) RangeRule{RangeRule::Kind::kOneOf, 0.0, 0.0, f(), ""}
#define RANGE_EITHER(...) RangeRule{RangeRule::Kind::kEither, 0.0, 0.0, {__VA_ARGS__}, ""}
#define RANGE_TABLES RULE_(kTables, 0.0, 0.0)
#define RANGE_SPECIAL(text) RangeRule{RangeRule::Kind::kSpecial, 0.0, 0.0, {}, text}
// default
#define DFLT_PAPER DefaultSpec{DefaultSpec::Kind::kPaper, nullptr, nullptr}
#define DFLT_VAL(v) DefaultSpec{DefaultSpec::Kind::kValue, []() -> Json { return Json(v); }, nullptr}
#define DFLT_FN(f, note) DefaultSpec{DefaultSpec::Kind::kValue, f, note}
#define DFLT_NOTE(text) DefaultSpec{DefaultSpec::Kind::kNote, nullptr, text}

#define SCHEMA_ROW_(map, shape, fw, lcm, key, target, type, unit, range, dflt, doc)       \
  ConfigRow{key,       FWPART_##map(fw, lcm), TPART_##target, TYPE_##type, unit, RANGE_##range, \
            DFLT_##dflt, doc},

std::vector<ConfigRow> BuildTable() { return {UVMS_CONFIG_TABLE(SCHEMA_ROW_)}; }

// ---- text -------------------------------------------------------------------------------------

/// A number as a scenario file would have it: integers below 1e5 in full, others in the
/// shortest form that reads back the same (1e-08 -> 1e-8, 100000 -> 1e5).
std::string FormatNumber(double x) {
  char buf[40];
  if (x == std::floor(x) && std::fabs(x) < 1e5) {
    std::snprintf(buf, sizeof buf, "%.0f", x + 0.0);
    return buf;
  }
  for (int p = 1; p <= 17; ++p) {
    std::snprintf(buf, sizeof buf, "%.*g", p, x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  std::string s = buf;
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  std::string exp = s.substr(e + 1);
  const bool negative = exp[0] == '-';
  exp = exp.substr(exp[0] == '-' || exp[0] == '+' ? 1 : 0);
  exp = exp.substr(std::min(exp.find_first_not_of('0'), exp.size() - 1));
  return s.substr(0, e) + "e" + (negative ? "-" : "") + exp;
}

std::string FormatInteger(double x) { return std::to_string(static_cast<long long>(x)); }

std::string ChoicesText(const RangeRule &r) {
  std::string s;
  for (const Choice &c : r.choices) s += (s.empty() ? "\"" : " | \"") + std::string(c.name) + "\"";
  return s;
}

std::string JsonText(const Json &v) {
  if (v.is_null()) return "–";
  if (v.is_string()) return "`\"" + v.get<std::string>() + "\"`";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number()) return FormatNumber(v.get<double>());
  if (v.empty()) return "none";
  std::string s;
  for (const Json &x : v) s += (s.empty() ? "[" : ", ") + JsonText(x);
  return s + "]";
}

std::string Cell(std::string s) {
  for (std::size_t i = 0; (i = s.find('|', i)) != std::string::npos; i += 2) s.insert(i, "\\");
  return s;
}

std::string MapsTo(const ConfigRow &row) {
  std::string s;
  auto add = [&](const char *path, const char *side) {
    if (*path) s += (s.empty() ? "`" : ", `") + std::string(path) + "` (" + side + ")";
  };
  add(row.firmware, "C");
  add(row.plant, "P");
  add(row.harness, "H");
  return s.empty() ? row.doc : s + ": " + row.doc;
}

std::string DefaultText(const ConfigRow &row) {
  if (row.dflt.note != nullptr) return row.dflt.note;
  const Json d = DefaultJson(row);
  if (d.is_array() && !d.empty() && d[0].is_object()) return "see `uvms scenario schema`";
  return JsonText(d);
}

std::string BeginMarker(const std::string &section) {
  return "<!-- BEGIN generated: uvms scenario schema --markdown [" + section + "] -->";
}
std::string EndMarker(const std::string &section) { return "<!-- END generated [" + section + "] -->"; }

}  // namespace

// ---- rows -------------------------------------------------------------------------------------

const char *KeyTypeName(KeyType type) {
  switch (type) {
    case KeyType::kReal: return "real";
    case KeyType::kInt: return "int";
    case KeyType::kBool: return "bool";
    case KeyType::kString: return "string";
    case KeyType::kEnum: return "enum";
    case KeyType::kVec3: return "vec3";
    case KeyType::kArray: return "array";
  }
  return "?";
}

std::string ConfigRow::Section() const {
  const std::string k = key;
  const auto dot = k.rfind('.');
  return dot == std::string::npos ? "" : k.substr(0, dot);
}

std::string ConfigRow::Leaf() const {
  const std::string k = key;
  const auto dot = k.rfind('.');
  return dot == std::string::npos ? k : k.substr(dot + 1);
}

bool ConfigRow::IsElement() const { return std::string_view(key).find("[].") != std::string_view::npos; }

bool ConfigRow::IsRequired() const {
  return dflt.kind == DefaultSpec::Kind::kNote && std::string_view(dflt.note) == "required";
}

const std::vector<ConfigRow> &ConfigTable() {
  static const std::vector<ConfigRow> table = BuildTable();
  return table;
}

const ConfigRow &ConfigRowOf(std::string_view key) {
  for (const ConfigRow &row : ConfigTable())
    if (key == row.key) return row;
  throw std::logic_error("no row for the scenario key \"" + std::string(key) + "\" in sil/msg/config_table.h");
}

std::vector<const ConfigRow *> ElementRows(std::string_view key) {
  // The rows of every array of tables, grouped once (the table is fixed): every scenario read
  // asks for them per array and per element.
  static const std::map<std::string, std::vector<const ConfigRow *>, std::less<>> by_section = [] {
    std::map<std::string, std::vector<const ConfigRow *>, std::less<>> m;
    for (const ConfigRow &row : ConfigTable())
      if (row.HasKey() && row.IsElement()) m[row.Section()].push_back(&row);
    return m;
  }();
  const auto it = by_section.find(std::string(key) + "[]");
  return it == by_section.end() ? std::vector<const ConfigRow *>{} : it->second;
}

Scenario PaperScenario(int case_number) {
  Scenario s;
  (void)uvms_ctrl_config_paper(&s.controller, case_number != 0 ? case_number : 4);
  s.plant = plant::PaperPlantParams();
  return s;
}

std::string ChoiceName(const ConfigRow &row, long value) {
  for (const Choice &c : row.range.choices)
    if (c.value == value) return c.name;
  return "";
}

namespace {
#define RETIRED_ROW_(key, name, value, replacement, why) RetiredChoice{key, name, value, replacement, why},
const RetiredChoice kRetired[] = {UVMS_RETIRED_CHOICES(RETIRED_ROW_)};
#undef RETIRED_ROW_
}  // namespace

const RetiredChoice *RetiredChoiceNamed(std::string_view key, std::string_view name) {
  for (const RetiredChoice &r : kRetired)
    if (key == r.key && name == r.name) return &r;
  return nullptr;
}

const RetiredChoice *RetiredChoiceValued(std::string_view key, long value) {
  for (const RetiredChoice &r : kRetired)
    if (key == r.key && value == r.value) return &r;
  return nullptr;
}

std::string RetiredText(const RetiredChoice &r) {
  return "\"" + std::string(r.name) + "\" (value " + std::to_string(r.value) + ") is retired: " +
         r.why + "; use \"" + r.replacement + "\"";
}

std::string RangeText(const ConfigRow &row) {
  const RangeRule &r = row.range;
  using K = RangeRule::Kind;
  switch (r.kind) {
    case K::kAtLeast: return "≥ " + FormatNumber(r.lo);
    case K::kAbove: return (row.type == KeyType::kVec3 ? "3 numbers, each > " : "> ") + FormatNumber(r.lo);
    case K::kBelow: return "< " + FormatNumber(r.lo);
    case K::kIntIn: return "integer " + FormatInteger(r.lo) + ".." + FormatInteger(r.hi);
    case K::kIntAtLeast: return "integer ≥ " + FormatInteger(r.lo);
    case K::kProbability: return "[0, 1]";
    case K::kFraction: return "[0, 1)";
    case K::kNonEmpty: return "non-empty string";
    case K::kNonZero: return "3 finite numbers, not all 0";
    case K::kReals: return FormatNumber(r.lo) + " finite numbers";
    case K::kRealsAtLeast: return FormatNumber(r.lo) + " numbers, each ≥ " + FormatNumber(r.hi);
    case K::kOneOf:
    case K::kEither: return ChoicesText(r);
    case K::kTables: return "array of tables";
    case K::kSpecial: return r.text;
    case K::kAny: break;
  }
  switch (row.type) {
    case KeyType::kReal: return "finite";
    case KeyType::kInt: return "integer";
    case KeyType::kBool: return "bool";
    case KeyType::kString: return "string";
    case KeyType::kVec3: return "3 finite numbers";
    default: return "-";
  }
}

Json DefaultJson(const ConfigRow &row) {
  switch (row.dflt.kind) {
    case DefaultSpec::Kind::kNote: return nullptr;
    case DefaultSpec::Kind::kValue: return Normalise(row, row.dflt.value());
    case DefaultSpec::Kind::kPaper: break;
  }
  if (row.elem_default != nullptr) return Normalise(row, row.elem_default());
  static const Scenario paper = PaperScenario(0);
  if (row.cpp_get != nullptr) return Normalise(row, row.cpp_get(paper));
  if (row.fw_get != nullptr) return Normalise(row, row.fw_get(paper));
  return nullptr;
}

// ---- printers ---------------------------------------------------------------------------------

Json SchemaJson() {
  auto path = [](const char *p) -> Json { return *p ? Json(p) : Json(nullptr); };
  Json keys = Json::array();
  for (const ConfigRow &row : ConfigTable()) {
    if (!row.HasKey()) continue;
    keys.push_back({{"key", row.key},
                    {"type", KeyTypeName(row.type)},
                    {"unit", row.unit},
                    {"default", DefaultJson(row)},
                    {"range", RangeText(row)},
                    {"firmware", path(row.firmware)},
                    {"lcm", path(row.lcm)},
                    {"plant", path(row.plant)},
                    {"harness", path(row.harness)},
                    {"doc", row.doc}});
  }
  return {{"schema_version", 1}, {"keys", keys}};
}

std::vector<std::string> SchemaSections() {
  std::vector<std::string> sections;
  for (const ConfigRow &row : ConfigTable()) {
    if (!row.HasKey()) continue;
    const std::string s = row.Section();
    if (std::find(sections.begin(), sections.end(), s) == sections.end()) sections.push_back(s);
  }
  return sections;
}

std::string SchemaMarkdownBlock(const std::string &section) {
  std::string out = BeginMarker(section) + "\n| key | unit | default | range | maps to |\n" +
                    "|---|---|---|---|---|\n";
  for (const ConfigRow &row : ConfigTable()) {
    if (!row.HasKey() || row.Section() != section) continue;
    out += "| `" + row.Leaf() + "` | " + Cell(row.unit) + " | " + Cell(DefaultText(row)) + " | " +
           Cell(RangeText(row)) + " | " + Cell(MapsTo(row)) + " |\n";
  }
  return out + EndMarker(section) + "\n";
}

std::string SchemaMarkdown() {
  std::string out;
  for (const std::string &s : SchemaSections()) out += (out.empty() ? "" : "\n") + SchemaMarkdownBlock(s);
  return out;
}

std::string UpdateGeneratedBlocks(const std::string &doc) {
  const std::vector<std::string> sections = SchemaSections();
  const std::string begin = "<!-- BEGIN generated: uvms scenario schema --markdown [";
  std::set<std::string> seen;
  std::string out;
  std::istringstream in(doc);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(begin, 0) != 0) {
      out += line + (in.eof() ? "" : "\n");
      continue;
    }
    const auto close = line.rfind("] -->");
    const std::string section =
        close == std::string::npos ? "" : line.substr(begin.size(), close - begin.size());
    if (std::find(sections.begin(), sections.end(), section) == sections.end())
      throw std::runtime_error("generated block [" + section + "]: no such section in the schema");
    if (!seen.insert(section).second)
      throw std::runtime_error("generated block [" + section + "] appears twice");
    std::string end;
    while (std::getline(in, end) && end != EndMarker(section)) {
    }
    if (end != EndMarker(section))
      throw std::runtime_error("generated block [" + section + "]: no " + EndMarker(section));
    out += SchemaMarkdownBlock(section);
  }
  for (const std::string &s : sections)
    if (seen.count(s) == 0) throw std::runtime_error("no generated block [" + s + "] (add " + BeginMarker(s) + " and " + EndMarker(s) + ")");
  return out;
}

}  // namespace uvms::sil
