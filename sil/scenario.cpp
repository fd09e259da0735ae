// scenario.cpp: TOML scenario → controller configuration + plant configuration + harness
// settings (scenario.hpp). The schema (every key, unit, default, range, SPEC section) is
// documented in docs/SCENARIOS.md; keep the two in step.
//
// How a scenario is read:
//   1. toml++ parses the text (syntax errors become ScenarioError "FILE:LINE: ...").
//   2. Each --set override is parsed as the TOML document "v = VALUE" and put into the tree at
//      its dotted key, replacing what the file had (its source region is "--set KEY=VALUE").
//   3. A Reader walks the known sections and keys, type-checks each value it is asked for and
//      marks it as used; then every node nobody asked for is an unknown key.
//   4. Ranges and contradictions are checked, both configurations are filled (controller from
//      uvms_ctrl_config_paper(case), plant from PaperPlantParams()), and finally the libraries
//      themselves validate them: uvms_ctrl_init and the plant::Plant constructor + Reset.
#include "scenario.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <utility>

#include "lcm_wait.h"  // UVMS_SPIN_US_MAX
#include "uvms_plant/environment.hpp"

namespace uvms::sil {
namespace {

/// SPEC §6.2: the controller's model density under "density error" [kg/m³].
constexpr double kDensityErrorModelKgM3 = 1000.0;
/// The paper's arm has 7 joints (SPEC §3.1); trajectory angle arrays have this length.
constexpr std::size_t kJoints = 7;
/// Shortest accepted Cartesian line direction (the firmware's own bound, trajectory.h).
constexpr double kMinDirectionNorm = static_cast<double>(UVMS_TRAJ_MIN_DIRECTION_NORM);

// Exit statuses, as every `uvms` subcommand (sil/model_cli.hpp).
constexpr int kExitOk = 0;
constexpr int kExitBadInput = 1;
constexpr int kExitUsage = 2;

const char *const kRoman[8] = {"I", "II", "III", "IV", "V", "VI", "VII", "VIII"};

// SPEC §8 table [deg]: θI, the "Veh." column and the barycenter columns by payload.
constexpr std::array<double, kJoints> kThetaStartDeg = {180, 90, 180, 180, 0, 0, 0};
constexpr std::array<double, kJoints> kThetaFinalVehicleDeg = {169.68, -75.62, 266.00, 108.77,
                                                               193.47, 96.97,  98.33};
struct BaryColumn {
  double payload_kg;
  std::array<double, kJoints> deg;
};
constexpr BaryColumn kThetaFinalBarycenterDeg[] = {
    {0.0, {170.06, -76.01, 265.62, 102.87, 192.96, 91.56, 97.24}},
    {1.0, {170.32, -76.12, 265.53, 101.58, 192.86, 90.56, 97.02}},
    {2.0, {170.59, -76.24, 265.45, 100.28, 192.76, 89.56, 96.80}},
    {5.0, {171.48, -76.58, 265.17, 96.30, 192.51, 86.53, 96.14}},
    {10.0, {176.19, -77.12, 264.65, 89.32, 192.22, 81.35, 95.12}},
};

std::string Num(double x) {
  std::ostringstream os;
  os << std::setprecision(12) << x;
  return os.str();
}

std::string TypeName(const toml::node &n) {
  switch (n.type()) {
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a float";
    case toml::node_type::boolean: return "a boolean";
    default: return "a date/time";
  }
}

/// "FILE:LINE" of a node; an override's region is named by its "--set KEY=VALUE" text.
std::string Where(const toml::node *n, const std::string &fallback) {
  if (n == nullptr) return fallback;
  const toml::source_region &r = n->source();
  if (!r.path || r.path->empty()) return fallback;
  if (r.path->rfind("--set ", 0) == 0) return *r.path;
  return *r.path + ":" + std::to_string(r.begin.line);
}

/// A key looked up in a section: `node` is null when absent; `anchor` is the section's table
/// (or null), used to place errors about an absent key.
struct Item {
  const toml::node *node{nullptr};
  const toml::node *anchor{nullptr};
  std::string key;  ///< dotted, e.g. "environment.unsteady_flow.enabled"
  explicit operator bool() const { return node != nullptr; }
};

/// A section (table) of the document; `table` is null when the file does not have it.
struct Sec {
  const toml::table *table{nullptr};
  std::string key;  ///< dotted; "" for the root
};

std::string Join(const std::vector<std::string> &v) {
  std::string s;
  for (const auto &x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

class Reader {
 public:
  Reader(const toml::table &root, std::string source) : root_(root), source_(std::move(source)) {}

  Sec Root() const { return Sec{&root_, ""}; }

  [[noreturn]] void Fail(const Item &it, const std::string &what) const {
    const toml::node *at = it.node != nullptr ? it.node : it.anchor;
    throw ScenarioError(Where(at, source_) + ": key \"" + it.key + "\": " + what);
  }

  /// Look up `name` in `sec` (recorded as a known key of that table; marked used if present).
  Item Get(const Sec &sec, const std::string &name) {
    Item it;
    it.key = sec.key.empty() ? name : sec.key + "." + name;
    it.anchor = sec.table;
    if (sec.table == nullptr) return it;
    auto &known = known_[sec.table];
    if (std::find(known.begin(), known.end(), name) == known.end()) known.push_back(name);
    it.node = sec.table->get(name);
    if (it.node != nullptr) used_.insert(it.node);
    return it;
  }

  Sec Sub(const Sec &sec, const std::string &name) {
    const Item it = Get(sec, name);
    if (!it) return Sec{nullptr, it.key};
    if (!it.node->is_table()) Fail(it, "expected a table, got " + TypeName(*it.node));
    return Sec{it.node->as_table(), it.key};
  }

  /// An array of tables ([[section.name]] or [{...}, ...]): one Sec per element.
  std::vector<Sec> Tables(const Sec &sec, const std::string &name) {
    const Item it = Get(sec, name);
    std::vector<Sec> out;
    if (!it) return out;
    const toml::array *arr = it.node->as_array();
    if (arr == nullptr) Fail(it, "expected an array of tables, got " + TypeName(*it.node));
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const toml::node &e = (*arr)[i];
      const std::string key = it.key + "[" + std::to_string(i) + "]";
      if (!e.is_table()) Fail(Item{&e, it.node, key}, "expected a table, got " + TypeName(e));
      used_.insert(&e);
      out.push_back(Sec{e.as_table(), key});
    }
    return out;
  }

  double Real(const Item &it, double def) const {
    if (!it) return def;
    double x = 0.0;
    if (auto v = it.node->value_exact<int64_t>()) {
      x = static_cast<double>(*v);
    } else if (auto d = it.node->value_exact<double>()) {
      x = *d;
    } else {
      Fail(it, "expected a number, got " + TypeName(*it.node));
    }
    if (!std::isfinite(x)) Fail(it, "got " + Num(x) + " (expected a finite number)");
    return x;
  }

  std::int64_t Int(const Item &it, std::int64_t def) const {
    if (!it) return def;
    auto v = it.node->value_exact<int64_t>();
    if (!v) Fail(it, "expected an integer, got " + TypeName(*it.node));
    return *v;
  }

  bool Bool(const Item &it, bool def) const {
    if (!it) return def;
    auto v = it.node->value_exact<bool>();
    if (!v) Fail(it, "expected a boolean (true or false), got " + TypeName(*it.node));
    return *v;
  }

  std::string Str(const Item &it, const std::string &def) const {
    if (!it) return def;
    auto v = it.node->value_exact<std::string>();
    if (!v) Fail(it, "expected a string, got " + TypeName(*it.node));
    return *v;
  }

  /// One of `choices` (a string).
  std::string Choice(const Item &it, const std::string &def,
                     const std::vector<std::string> &choices) const {
    const std::string s = Str(it, def);
    if (std::find(choices.begin(), choices.end(), s) == choices.end())
      Fail(it, "got \"" + s + "\" (expected one of: " + Join(choices) + ")");
    return s;
  }

  /// An array of exactly n finite numbers.
  std::vector<double> Reals(const Item &it, std::size_t n) const {
    const toml::array *arr = it.node->as_array();
    if (arr == nullptr) Fail(it, "expected an array of " + std::to_string(n) + " numbers, got " +
                                     TypeName(*it.node));
    if (arr->size() != n)
      Fail(it, "got " + std::to_string(arr->size()) + " elements (expected an array of " +
                   std::to_string(n) + " numbers)");
    std::vector<double> out;
    for (std::size_t i = 0; i < n; ++i) {
      const Item e{&(*arr)[i], it.node, it.key + "[" + std::to_string(i) + "]"};
      out.push_back(Real(e, 0.0));
    }
    return out;
  }

  plant::Vec3 Vec(const Item &it, const plant::Vec3 &def) const {
    if (!it) return def;
    const auto v = Reals(it, 3);
    return plant::Vec3(v[0], v[1], v[2]);
  }

  // Range checks on a present value (absent values take valid defaults).
  void AtLeast(const Item &it, double x, double lo) const {
    if (it && !(x >= lo)) Fail(it, "got " + Num(x) + " (expected a number >= " + Num(lo) + ")");
  }
  void Above(const Item &it, double x, double lo) const {
    if (it && !(x > lo)) Fail(it, "got " + Num(x) + " (expected a number > " + Num(lo) + ")");
  }

  /// Every node of the document nobody asked for is an unknown key: report the first in the
  /// file (overrides after file keys).
  void CheckUnknown() const {
    struct Unknown {
      const toml::node *node;
      const toml::table *parent;
      std::string key;
    };
    std::vector<Unknown> found;
    Walk(root_, "", found);
    if (found.empty()) return;
    auto order = [](const Unknown &u) {
      const toml::source_region &r = u.node->source();
      const bool file = r.path && r.path->rfind("--set ", 0) != 0;
      return std::make_pair(file ? 0 : 1, r.begin.line);
    };
    const auto first = std::min_element(found.begin(), found.end(), [&](const auto &a, const auto &b) {
      return order(a) < order(b);
    });
    // A table created by an override has no source of its own: place it by a descendant.
    const toml::node *at = first->node;
    while (!at->source().path && at->is_table() && !at->as_table()->empty())
      at = &at->as_table()->begin()->second;
    auto k = known_.find(first->parent);
    const std::string expected = k == known_.end() ? "no keys here" : "one of: " + Join(k->second);
    Fail(Item{at, nullptr, first->key}, "unknown key (expected " + expected + ")");
  }

 private:
  template <typename U>
  void Walk(const toml::table &t, const std::string &prefix, std::vector<U> &found) const {
    for (auto &&[k, v] : t) {
      const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
      if (used_.count(&v) == 0) {
        found.push_back(U{&v, &t, key});
        continue;
      }
      if (const toml::table *sub = v.as_table()) Walk(*sub, key, found);
      if (const toml::array *arr = v.as_array()) {
        for (std::size_t i = 0; i < arr->size(); ++i) {
          const toml::table *e = (*arr)[i].as_table();
          if (e != nullptr && used_.count(e) != 0) Walk(*e, key + "[" + std::to_string(i) + "]", found);
        }
      }
    }
  }

  const toml::table &root_;
  std::string source_;
  std::set<const toml::node *> used_;
  std::map<const toml::table *, std::vector<std::string>> known_;
};

bool IsBareKey(const std::string &s) {
  if (s.empty()) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
}

std::string Trim(const std::string &s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

/// Put one "section.key=value" override into the tree (step 2 of the file comment).
void ApplyOverride(toml::table &root, const std::string &text) {
  const std::string where = "--set " + text;
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw ScenarioError(where + ": expected section.key=value (value in TOML syntax)");
  const std::string key = Trim(text.substr(0, eq));
  const std::string value = Trim(text.substr(eq + 1));
  std::vector<std::string> parts;
  for (std::size_t b = 0;;) {
    const auto dot = key.find('.', b);
    parts.push_back(key.substr(b, dot == std::string::npos ? std::string::npos : dot - b));
    if (dot == std::string::npos) break;
    b = dot + 1;
  }
  for (const auto &p : parts)
    if (!IsBareKey(p))
      throw ScenarioError(where + ": key \"" + key +
                          "\": not a dotted key (expected section.key of letters, digits, _ and -)");
  if (value.empty())
    throw ScenarioError(where + ": key \"" + key + "\": no value (expected section.key=value)");
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value + "\n", where);
  } catch (const toml::parse_error &e) {
    throw ScenarioError(where + ": key \"" + key + "\": the value is not TOML (" +
                        std::string(e.description()) +
                        "; expected e.g. 10, 1e-6, true, \"VII\", [1, 0, 0])");
  }
  toml::node *v = parsed.get("v");
  toml::table *cur = &root;
  std::string sofar;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    sofar += (i ? "." : "") + parts[i];
    toml::node *n = cur->get(parts[i]);
    if (n == nullptr) n = &cur->insert(parts[i], toml::table{}).first->second;
    if (!n->is_table())
      throw ScenarioError(where + ": key \"" + key + "\": \"" + sofar + "\" is " + TypeName(*n) +
                          ", not a section (--set cannot address array elements)");
    cur = n->as_table();
  }
  cur->insert_or_assign(parts.back(), std::move(*v));
}

std::string Stem(const std::string &source) {
  const std::string stem = std::filesystem::path(source).stem().string();
  return stem.empty() ? source : stem;
}

uvms_real_t R(double x) { return static_cast<uvms_real_t>(x); }

void ToReal3(const plant::Vec3 &v, uvms_real_t out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = R(v[k]);
}

/// Z-Y-X (yaw, pitch, roll) angles [deg] → vehicle → inertial rotation.
Eigen::Quaterniond FromRpyDeg(const plant::Vec3 &rpy_deg) {
  const double d = M_PI / 180.0;
  return Eigen::AngleAxisd(rpy_deg[2] * d, plant::Vec3::UnitZ()) *
         Eigen::AngleAxisd(rpy_deg[1] * d, plant::Vec3::UnitY()) *
         Eigen::AngleAxisd(rpy_deg[0] * d, plant::Vec3::UnitX());
}

/// The scenario section a rejected controller part is configured in (for the error message).
const char *SectionOf(uvms_cfg_field_t f) {
  switch (f) {
    case UVMS_CFG_ARM: return "payload";
    case UVMS_CFG_FLUID: return "environment";
    case UVMS_CFG_THRUSTER_GEOMETRY:
    case UVMS_CFG_THRUSTER_RANK:
    case UVMS_CFG_THRUSTER_PARAMS: return "thrusters";
    case UVMS_CFG_GAINS:
    case UVMS_CFG_SWITCHES:
    case UVMS_CFG_JOINT_SERVO: return "control";
    case UVMS_CFG_TICK: return "run";
    case UVMS_CFG_TRAJECTORY: return "trajectory";
    default: return "run";
  }
}

std::string OnOff(bool b) { return b ? "on" : "off"; }

}  // namespace

std::array<double, 7> PaperThetaStartDeg() { return kThetaStartDeg; }

bool PaperThetaFinalDeg(uvms_reference_t reference, double payload_kg, std::array<double, 7> *deg) {
  if (reference == UVMS_REF_VEHICLE) {
    if (deg != nullptr) *deg = kThetaFinalVehicleDeg;
    return true;
  }
  for (const BaryColumn &c : kThetaFinalBarycenterDeg) {
    if (c.payload_kg == payload_kg) {
      if (deg != nullptr) *deg = c.deg;
      return true;
    }
  }
  return false;
}

std::int64_t ScenarioTicks(const Scenario &s) {
  const double r = s.duration_s / s.tick_s;
  const double n = std::round(r);
  if (std::fabs(r - n) <= 1e-9 * std::max(1.0, r)) return static_cast<std::int64_t>(n);
  return static_cast<std::int64_t>(std::ceil(r));
}

std::string ScenarioSummary(const Scenario &s) {
  std::ostringstream os;
  const uvms_switches_t &sw = s.controller.switches;
  os << s.name << ": ";
  if (s.case_number >= 1 && s.case_number <= 8) os << "case " << kRoman[s.case_number - 1] << " (";
  else os << "switches (";
  os << "attitude " << OnOff(sw.attitude_control != 0) << ", "
     << (sw.position_reference == UVMS_REF_BARYCENTER ? "barycenter" : "vehicle")
     << " reference, feedforward " << OnOff(sw.position_feedforward != 0) << ", feedback "
     << OnOff(sw.position_feedback != 0) << "), payload " << Num(s.plant.payload_kg)
     << " kg, duration " << Num(s.duration_s) << " s, tick " << Num(s.tick_s) << " s, "
     << ScenarioTicks(s) << " ticks, flow " << (s.plant.env.unsteady.enabled ? "unsteady" : "steady")
     << ", density error " << OnOff(s.density_error);
  return os.str();
}

bool SensorFaults::any() const {
  for (const SensorNoise *n : {&position_m, &attitude_rad, &velocity_m_s, &angular_velocity_rad_s,
                               &joint_position_rad, &joint_velocity_rad_s, &motor_speed_rad_s,
                               &motor_current_A})
    if (n->std != 0.0 || n->bias != 0.0) return true;
  return false;
}

Scenario ParseScenario(std::string_view toml_text, const std::string &source,
                       const std::vector<std::string> &overrides) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source);
  } catch (const toml::parse_error &e) {
    throw ScenarioError(source + ":" + std::to_string(e.source().begin.line) +
                        ": TOML syntax error: " + std::string(e.description()));
  }
  for (const std::string &o : overrides) ApplyOverride(root, o);

  Reader rd(root, source);
  Scenario s;
  s.source = source;
  s.overrides = overrides;
  const Sec top = rd.Root();

  // ---- [run] (SPEC §3.5) ---------------------------------------------------------------
  const Sec run = rd.Sub(top, "run");
  const Item run_name = rd.Get(run, "name");
  const Item run_duration = rd.Get(run, "duration_s");
  const Item run_tick = rd.Get(run, "tick_s");
  const Item run_seed = rd.Get(run, "seed");
  s.name = rd.Str(run_name, Stem(source));
  if (s.name.empty()) rd.Fail(run_name, "got \"\" (expected a non-empty name)");
  s.duration_s = rd.Real(run_duration, s.duration_s);
  s.tick_s = rd.Real(run_tick, s.tick_s);
  rd.Above(run_tick, s.tick_s, 0.0);
  rd.Above(run_duration, s.duration_s, 0.0);
  if (s.duration_s < s.tick_s)
    rd.Fail(run_duration ? run_duration : run_tick,
            "duration_s " + Num(s.duration_s) + " s is shorter than tick_s " + Num(s.tick_s) +
                " s (expected duration_s >= tick_s)");
  const std::int64_t seed = rd.Int(run_seed, static_cast<std::int64_t>(s.seed));
  rd.AtLeast(run_seed, static_cast<double>(seed), 0.0);
  s.seed = static_cast<std::uint64_t>(seed);

  // ---- [control]: Table X (SPEC §7.2, §9), PD gains (§3.5), joint servo (§8) ------------
  const Sec control = rd.Sub(top, "control");
  const Item c_case = rd.Get(control, "case");
  const Item c_att = rd.Get(control, "attitude");
  const Item c_ref = rd.Get(control, "position_reference");
  const Item c_ff = rd.Get(control, "position_feedforward");
  const Item c_fb = rd.Get(control, "position_feedback");
  if (c_case) {
    if (auto n = c_case.node->value_exact<int64_t>()) {
      if (*n < 1 || *n > 8) rd.Fail(c_case, "got " + std::to_string(*n) + " (expected one of I..VIII or 1..8)");
      s.case_number = static_cast<int>(*n);
    } else if (auto str = c_case.node->value_exact<std::string>()) {
      for (int k = 0; k < 8; ++k)
        if (*str == kRoman[k]) s.case_number = k + 1;
      if (s.case_number == 0) rd.Fail(c_case, "got \"" + *str + "\" (expected one of I..VIII)");
    } else {
      rd.Fail(c_case, "expected a string I..VIII, got " + TypeName(*c_case.node));
    }
  }
  uvms_switches_t sw{};
  if (s.case_number != 0) {
    (void)uvms_switches_case(s.case_number, &sw);
  } else if (!c_att && !c_ref && !c_ff && !c_fb) {
    rd.Fail(c_case, "missing (expected a Table X case \"I\"..\"VIII\", or the four switches "
                    "attitude, position_reference, position_feedforward, position_feedback)");
  } else {
    for (const Item *it : {&c_att, &c_ref, &c_ff, &c_fb})
      if (!*it)
        rd.Fail(*it, "missing (expected all four switches when no case is named, or a "
                     "control.case \"I\"..\"VIII\")");
  }
  {
    const std::string case_name = s.case_number ? std::string("case ") + kRoman[s.case_number - 1] : "";
    auto set_switch = [&](const Item &it, int *field, int value, const std::string &shown,
                          const std::string &case_value) {
      if (!it) return;
      if (s.case_number != 0 && value != *field)
        rd.Fail(it, "got " + shown + ", which contradicts control.case = \"" +
                        kRoman[s.case_number - 1] + "\" (" + case_name + " has " + case_value +
                        "; expected the case's value, or no case with explicit switches)");
      *field = value;
    };
    const bool att = rd.Bool(c_att, sw.attitude_control != 0);
    set_switch(c_att, &sw.attitude_control, att ? 1 : 0, att ? "true" : "false",
               sw.attitude_control ? "true" : "false");
    const std::string ref_now = sw.position_reference == UVMS_REF_BARYCENTER ? "barycenter" : "vehicle";
    const std::string ref = rd.Choice(c_ref, ref_now, {"vehicle", "barycenter"});
    int ref_i = static_cast<int>(sw.position_reference);
    set_switch(c_ref, &ref_i, ref == "barycenter" ? UVMS_REF_BARYCENTER : UVMS_REF_VEHICLE,
               "\"" + ref + "\"", "\"" + ref_now + "\"");
    sw.position_reference = static_cast<uvms_reference_t>(ref_i);
    const bool ff = rd.Bool(c_ff, sw.position_feedforward != 0);
    set_switch(c_ff, &sw.position_feedforward, ff ? 1 : 0, ff ? "true" : "false",
               sw.position_feedforward ? "true" : "false");
    const bool fb = rd.Bool(c_fb, sw.position_feedback != 0);
    set_switch(c_fb, &sw.position_feedback, fb ? 1 : 0, fb ? "true" : "false",
               sw.position_feedback ? "true" : "false");
  }
  // The controller starts from SPEC's configuration of the case (case IV's values for explicit
  // switches, which are then replaced); every scenario setting is written over it below.
  uvms_ctrl_config_t &c = s.controller;
  (void)uvms_ctrl_config_paper(&c, s.case_number != 0 ? s.case_number : 4);
  c.switches = sw;
  c.cart.reference = sw.position_reference;  // SPEC §8: the line refers to the held point
  c.tick_s = R(s.tick_s);

  auto real_into = [&](const Sec &sec, const char *key, uvms_real_t *field, bool positive) {
    const Item it = rd.Get(sec, key);
    const double x = rd.Real(it, static_cast<double>(*field));
    if (positive) rd.Above(it, x, 0.0);
    else rd.AtLeast(it, x, 0.0);
    *field = R(x);
  };
  real_into(control, "kpf_N_m", &c.gains.kpf_N_m, false);
  real_into(control, "kdf_N_s_m", &c.gains.kdf_N_s_m, false);
  real_into(control, "kpn_Nm_rad", &c.gains.kpn_Nm_rad, false);
  real_into(control, "kdn_Nm_s_rad", &c.gains.kdn_Nm_s_rad, false);
  real_into(control, "joint_kq_1_s2", &c.joint_kq_1_s2, false);
  real_into(control, "joint_kqd_1_s", &c.joint_kqd_1_s, false);

  // ---- [thrusters]: the controller's thruster loops (SPEC §3.4, §7.4) ---------------------
  const Sec thrusters = rd.Sub(top, "thrusters");
  real_into(thrusters, "ka_1_s", &c.thruster.speed_gain_1_s, true);
  real_into(thrusters, "kb_1_s", &c.thruster.current_gain_1_s, true);
  real_into(thrusters, "voltage_limit_V", &c.thruster.voltage_limit_V, true);
  {  // the motors' power stage, in the controller and the plant alike (SPEC §5 "Motors")
    const Item dr = rd.Get(thrusters, "drive");
    const std::string d = rd.Str(dr, "current");
    if (d == "current") c.drive = UVMS_DRIVE_CURRENT;
    else if (d == "voltage") c.drive = UVMS_DRIVE_VOLTAGE;
    else rd.Fail(dr, "got \"" + d + "\" (expected \"current\" or \"voltage\")");
  }

  // ---- [limits]: the controller's fault handling (uvms_ctrl_limits_t, docs/FAULTS.md) -------
  // Defaults: uvms_ctrl_config_paper's. 0 switches a check off.
  const Sec limits = rd.Sub(top, "limits");
  {
    uvms_ctrl_limits_t &lim = c.limits;
    real_into(limits, "max_vehicle_speed_m_s", &lim.max_vehicle_speed_m_s, false);
    real_into(limits, "max_vehicle_rate_rad_s", &lim.max_vehicle_rate_rad_s, false);
    real_into(limits, "max_joint_rate_rad_s", &lim.max_joint_rate_rad_s, false);
    real_into(limits, "max_motor_speed_rad_s", &lim.max_motor_speed_rad_s, false);
    real_into(limits, "max_motor_current_A", &lim.max_motor_current_A, false);
    real_into(limits, "quat_norm_tol", &lim.quat_norm_tol, false);
    real_into(limits, "thrust_limit_N", &lim.thrust_limit_N, false);
    const Item hold = rd.Get(limits, "sensor_hold_max_ticks");
    const std::int64_t h = rd.Int(hold, static_cast<std::int64_t>(lim.sensor_hold_max_ticks));
    if (hold && (h < 0 || h > static_cast<std::int64_t>(UVMS_SENSOR_HOLD_MAX_TICKS_LIMIT)))
      rd.Fail(hold, "got " + std::to_string(h) + " (expected an integer in 0.." +
                        std::to_string(UVMS_SENSOR_HOLD_MAX_TICKS_LIMIT) + ")");
    lim.sensor_hold_max_ticks = static_cast<std::uint32_t>(h);
  }

  // ---- [payload] (SPEC §2, §3.2): the same physical payload for controller and plant -----
  plant::PlantParams &p = s.plant;
  p = plant::PaperPlantParams();
  p.propulsion.drive = (c.drive == UVMS_DRIVE_CURRENT) ? plant::MotorDrive::kCurrent
                                                       : plant::MotorDrive::kVoltage;
  const Sec payload = rd.Sub(top, "payload");
  const Item pl_mass = rd.Get(payload, "mass_kg");
  const Item pl_offset = rd.Get(payload, "offset_m");
  p.payload_kg = rd.Real(pl_mass, p.payload_kg);
  rd.AtLeast(pl_mass, p.payload_kg, 0.0);
  p.payload_offset_m = rd.Vec(pl_offset, p.payload_offset_m);
  c.arm.payload_kg = R(p.payload_kg);
  ToReal3(p.payload_offset_m, c.arm.payload_offset_m);

  // ---- [arm]: simplifications of the arm for model studies (SPEC §9 item 8: the analytic
  // model's massless, dragless arm), in the controller's model and the plant alike ----------
  const Sec arm = rd.Sub(top, "arm");
  {
    const Item ms = rd.Get(arm, "mass_scale");
    const double scale = rd.Real(ms, 1.0);
    rd.AtLeast(ms, scale, 0.0);
    const bool hydro = rd.Bool(rd.Get(arm, "hydrodynamics"), true);
    for (size_t i = 0; i < p.links.size() && i < UVMS_MAX_JOINTS; ++i) {
      p.links[i].mass_kg *= scale;  // m_i and I_Bi together: the link's shape is unchanged
      p.links[i].inertia_kg_m2 *= scale;
      c.arm.link[i].mass_kg = R(p.links[i].mass_kg);
      for (int k = 0; k < 3; ++k) c.arm.link[i].inertia_kg_m2[k] = R(p.links[i].inertia_kg_m2[k]);
      if (!hydro) {  // d_L = 0: no volume, buoyancy, drag or added mass (SPEC §3.1)
        p.links[i].diameter_m = 0.0;
        c.arm.link[i].diameter_m = R(0.0);
      }
    }
  }

  // ---- [vehicle]: initial pose, center of buoyancy (SPEC §3.2) ----------------------------
  const Sec vehicle = rd.Sub(top, "vehicle");
  s.initial.r0_m = rd.Vec(rd.Get(vehicle, "position_m"), s.initial.r0_m);
  s.initial.attitude = FromRpyDeg(rd.Vec(rd.Get(vehicle, "attitude_rpy_deg"), plant::Vec3::Zero()));
  p.vehicle.cob_m = rd.Vec(rd.Get(vehicle, "cob_m"), p.vehicle.cob_m);
  ToReal3(p.vehicle.cob_m, c.arm.vehicle.cob_m);

  // ---- [trajectory] (SPEC §8) --------------------------------------------------------------
  const Sec traj = rd.Sub(top, "trajectory");
  const Item t_mode = rd.Get(traj, "mode");
  const Item t_start = rd.Get(traj, "start_s");
  const Item t_duration = rd.Get(traj, "duration_s");
  const Item t_theta_start = rd.Get(traj, "theta_start_deg");
  const Item t_theta_final = rd.Get(traj, "theta_final_deg");
  const std::string mode =
      rd.Choice(t_mode, "joint_cycloid", {"joint_cycloid", "cartesian_line", "hold"});
  c.traj_mode = mode == "joint_cycloid"    ? UVMS_TRAJ_JOINT_CYCLOID
                : mode == "cartesian_line" ? UVMS_TRAJ_CARTESIAN_LINE
                                           : UVMS_TRAJ_HOLD;
  const double start_s = rd.Real(t_start, static_cast<double>(c.traj_start_s));
  rd.AtLeast(t_start, start_s, 0.0);
  c.traj_start_s = R(start_s);
  const double tf_s = rd.Real(t_duration, static_cast<double>(c.traj_duration_s));
  rd.Above(t_duration, tf_s, 0.0);
  c.traj_duration_s = R(tf_s);
  std::array<double, kJoints> theta_start_deg = kThetaStartDeg;
  if (t_theta_start) {
    const auto v = rd.Reals(t_theta_start, kJoints);
    std::copy(v.begin(), v.end(), theta_start_deg.begin());
  }
  std::array<double, kJoints> theta_final_deg = theta_start_deg;
  bool auto_final = true;
  if (t_theta_final) {
    if (auto str = t_theta_final.node->value_exact<std::string>()) {
      if (*str != "auto")
        rd.Fail(t_theta_final, "got \"" + *str + "\" (expected \"auto\" or an array of 7 angles in degrees)");
    } else if (t_theta_final.node->is_array()) {
      const auto v = rd.Reals(t_theta_final, kJoints);
      std::copy(v.begin(), v.end(), theta_final_deg.begin());
      auto_final = false;
    } else {
      rd.Fail(t_theta_final, "expected \"auto\" or an array of 7 angles in degrees, got " +
                                 TypeName(*t_theta_final.node));
    }
  }
  if (auto_final && !PaperThetaFinalDeg(sw.position_reference, p.payload_kg, &theta_final_deg) &&
      c.traj_mode == UVMS_TRAJ_JOINT_CYCLOID) {
    rd.Fail(t_theta_final.node ? t_theta_final : Item{nullptr, traj.table, "trajectory.theta_final_deg"},
            "\"auto\" has no SPEC §8 column for a " + Num(p.payload_kg) +
                " kg payload with the barycenter reference (the table has 0, 1, 2, 5, 10 kg; "
                "expected an explicit theta_final_deg = [7 angles in degrees])");
  }
  const double deg = M_PI / 180.0;
  for (std::size_t j = 0; j < kJoints; ++j) {
    c.theta_start_rad[j] = R(theta_start_deg[j] * deg);
    c.theta_final_rad[j] = R(theta_final_deg[j] * deg);
  }
  s.initial.q_rad.assign(kJoints, 0.0);
  for (std::size_t j = 0; j < kJoints; ++j) s.initial.q_rad[j] = theta_start_deg[j] * deg;

  const Sec cart = rd.Sub(traj, "cartesian");
  {
    const Item it_dist = rd.Get(cart, "distance_m");
    c.cart.distance_m = R(rd.Real(it_dist, static_cast<double>(c.cart.distance_m)));
    const Item it_dir = rd.Get(cart, "direction");
    const plant::Vec3 dir0(c.cart.direction[0], c.cart.direction[1], c.cart.direction[2]);
    const plant::Vec3 dir = rd.Vec(it_dir, dir0);
    if (it_dir && !(dir.norm() >= kMinDirectionNorm))
      rd.Fail(it_dir, "has length " + Num(dir.norm()) + " (expected a non-zero vector)");
    ToReal3(dir, c.cart.direction);
    real_into(cart, "damping_m", &c.cart.damping_m, true);
    real_into(cart, "position_gain_1_s", &c.cart.position_gain_1_s, false);
    real_into(cart, "nullspace_gain_1_s", &c.cart.nullspace_gain_1_s, false);
    real_into(cart, "max_joint_rate_rad_s", &c.cart.max_joint_rate_rad_s, true);
    c.cart.duration_s = c.traj_duration_s;  // one tF for both modes
  }

  // ---- [environment] (SPEC §3.2, §6) -------------------------------------------------------
  const Sec env = rd.Sub(top, "environment");
  plant::EnvironmentParams &e = p.env;
  const Item e_rho = rd.Get(env, "density_kg_m3");
  e.density_kg_m3 = rd.Real(e_rho, e.density_kg_m3);
  rd.Above(e_rho, e.density_kg_m3, 0.0);
  const Item e_err = rd.Get(env, "density_error");
  const Item e_model_rho = rd.Get(env, "model_density_kg_m3");
  s.density_error = rd.Bool(e_err, false);
  double model_rho = s.density_error ? kDensityErrorModelKgM3 : e.density_kg_m3;
  if (e_model_rho) {
    const double x = rd.Real(e_model_rho, model_rho);
    rd.Above(e_model_rho, x, 0.0);
    if (e_err && x != model_rho)
      rd.Fail(e_model_rho, "got " + Num(x) + ", which contradicts environment.density_error = " +
                               (s.density_error ? "true" : "false") + " (that means " +
                               Num(model_rho) + "; expected one of the two keys, or agreeing values)");
    model_rho = x;
    s.density_error = x != e.density_kg_m3;
  }
  c.fluid.density_kg_m3 = R(model_rho);

  const Item e_g = rd.Get(env, "gravity_m_s2");
  if (e_g) {
    if (auto name = e_g.node->value_exact<std::string>()) {
      try {
        e.gravity_m_s2 = plant::GravityPreset(*name);
      } catch (const std::invalid_argument &) {
        rd.Fail(e_g, "got \"" + *name + "\" (expected \"paper\", \"earth\", \"europa\" or [gx, gy, gz])");
      }
    } else if (e_g.node->is_array()) {
      e.gravity_m_s2 = rd.Vec(e_g, e.gravity_m_s2);
    } else {
      rd.Fail(e_g, "expected \"paper\", \"earth\", \"europa\" or [gx, gy, gz], got " + TypeName(*e_g.node));
    }
  }
  ToReal3(e.gravity_m_s2, c.fluid.gravity_m_s2);
  // SPEC §6.3: trim is on by default whenever there is gravity.
  e.trim = rd.Bool(rd.Get(env, "trim"), e.gravity_m_s2.norm() != 0.0);
  const Item e_trim_payload = rd.Get(env, "trim_payload_kg");
  e.trim_payload_kg = rd.Real(e_trim_payload, e.trim_payload_kg);
  rd.AtLeast(e_trim_payload, e.trim_payload_kg, 0.0);

  e.steady_flow_m_s = rd.Vec(rd.Get(env, "steady_flow_m_s"), e.steady_flow_m_s);
  ToReal3(e.steady_flow_m_s, c.fluid.flow_m_s);  // the controller sees v∞0 only (SPEC §6.1)

  e.angle_of_attack = rd.Bool(rd.Get(env, "angle_of_attack"), e.angle_of_attack);
  // The controller's model follows the plant unless set apart (model-fidelity experiments).
  c.fluid.angle_of_attack = rd.Bool(rd.Get(env, "model_angle_of_attack"), e.angle_of_attack) ? 1 : 0;

  const Item e_varc = rd.Get(env, "variable_coefficients");
  e.variable_coefficients = rd.Bool(e_varc, e.variable_coefficients);
  const Item e_table = rd.Get(env, "coeff_table");
  {
    const std::vector<Sec> rows = rd.Tables(env, "coeff_table");
    if (e_table && !e.variable_coefficients)
      rd.Fail(e_table, "given while environment.variable_coefficients is false (expected "
                       "variable_coefficients = true, or no table)");
    if (e_table && rows.empty()) rd.Fail(e_table, "is empty (expected at least one row)");
    for (const Sec &row : rows) {
      plant::CoeffTableRow r;
      const Item d = rd.Get(row, "distance_diameters");
      const Item fd = rd.Get(row, "drag_factor");
      const Item fa = rd.Get(row, "added_mass_factor");
      if (!d) rd.Fail(d, "missing (expected the travelled distance in link diameters, >= 0)");
      r.distance_diameters = rd.Real(d, 0.0);
      r.drag_factor = rd.Real(fd, r.drag_factor);
      r.added_mass_factor = rd.Real(fa, r.added_mass_factor);
      rd.AtLeast(d, r.distance_diameters, 0.0);
      rd.AtLeast(fd, r.drag_factor, 0.0);
      rd.AtLeast(fa, r.added_mass_factor, 0.0);
      if (!e.coeff_table.empty() && !(r.distance_diameters > e.coeff_table.back().distance_diameters))
        rd.Fail(d, "got " + Num(r.distance_diameters) +
                       " (expected distances strictly increasing from row to row)");
      e.coeff_table.push_back(r);
    }
    if (!e.coeff_table.empty()) {
      try {
        plant::ValidateCoeffTable(e.coeff_table);
      } catch (const std::invalid_argument &ex) {
        rd.Fail(e_table, std::string(ex.what()));
      }
    }
  }

  const Sec unsteady = rd.Sub(env, "unsteady_flow");
  {
    plant::UnsteadyFlowParams &u = e.unsteady;
    u.enabled = rd.Bool(rd.Get(unsteady, "enabled"), u.enabled);
    const Item av = rd.Get(unsteady, "amplitude_m_s");
    u.amplitude_m_s = rd.Real(av, u.amplitude_m_s);
    rd.AtLeast(av, u.amplitude_m_s, 0.0);
    const Item nh = rd.Get(unsteady, "harmonics");
    const std::int64_t n = rd.Int(nh, u.harmonics);
    if (nh && (n < 0 || n > plant::UnsteadyFlow::kMaxHarmonics))
      rd.Fail(nh, "got " + std::to_string(n) + " (expected an integer in 0.." +
                      std::to_string(plant::UnsteadyFlow::kMaxHarmonics) + ")");
    u.harmonics = static_cast<int>(n);
    u.period_s = s.duration_s;  // SPEC §6.1: tF = run duration
    u.seed = s.seed;            // the run's seed
  }

  // ---- Trim ballast (SPEC §6.3): the plant computes it at construction; the controller's
  // model carries the same physical ballast (computed with the actual density and the trim
  // payload), so under a density error its model is, correctly, not neutral.
  c.arm.vehicle.ballast_kg =
      R(e.trim ? plant::TrimBallastKg(p, e.density_kg_m3, e.trim_payload_kg) : 0.0);

  // ---- [integrator] (SPEC §5): defaults are the plant's IntegratorParams ------------------
  const Sec integ = rd.Sub(top, "integrator");
  {
    plant::IntegratorParams &ip = p.integrator;
    const Item m = rd.Get(integ, "method");
    const std::string method = rd.Choice(
        m, ip.method == plant::IntegratorParams::Method::kBdf ? "bdf" : "adams", {"adams", "bdf"});
    ip.method = method == "bdf" ? plant::IntegratorParams::Method::kBdf
                                : plant::IntegratorParams::Method::kAdams;
    const Item rt = rd.Get(integ, "rel_tol");
    ip.rel_tol = rd.Real(rt, ip.rel_tol);
    rd.Above(rt, ip.rel_tol, 0.0);
    const Item at = rd.Get(integ, "abs_tol");
    ip.abs_tol = rd.Real(at, ip.abs_tol);
    rd.Above(at, ip.abs_tol, 0.0);
    const Item ms = rd.Get(integ, "max_steps");
    ip.max_steps = static_cast<long>(rd.Int(ms, ip.max_steps));
    rd.AtLeast(ms, static_cast<double>(ip.max_steps), 1.0);
  }

  // ---- [contact] (SPEC §5) -----------------------------------------------------------------
  const Sec contact = rd.Sub(top, "contact");
  {
    plant::ContactParams &cp = p.contact;
    cp.enabled = rd.Bool(rd.Get(contact, "enabled"), cp.enabled);
    const Item cl = rd.Get(contact, "clearance_m");
    cp.clearance_m = rd.Real(cl, cp.clearance_m);
    rd.AtLeast(cl, cp.clearance_m, 0.0);
    cp.self_collision = rd.Bool(rd.Get(contact, "self_collision"), cp.self_collision);
    const Item obs_item = rd.Get(contact, "obstacle");
    const std::vector<Sec> obs = rd.Tables(contact, "obstacle");
    if (obs_item) cp.obstacles.clear();
    for (const Sec &o : obs) {
      plant::CylinderObstacle cyl;
      const Item nm = rd.Get(o, "name");
      cyl.name = rd.Str(nm, cyl.name);
      if (cyl.name.empty()) rd.Fail(nm, "got \"\" (expected a non-empty name)");
      cyl.base_center_m = rd.Vec(rd.Get(o, "base_center_m"), cyl.base_center_m);
      const Item h = rd.Get(o, "height_m");
      cyl.height_m = rd.Real(h, cyl.height_m);
      rd.Above(h, cyl.height_m, 0.0);
      const Item r = rd.Get(o, "radius_m");
      cyl.radius_m = rd.Real(r, cyl.radius_m);
      rd.Above(r, cyl.radius_m, 0.0);
      cp.obstacles.push_back(cyl);
    }
  }

  // ---- [link]: the harness's lockstep link --------------------------------------------------
  const Sec link = rd.Sub(top, "link");
  {
    const Item to = rd.Get(link, "timeout_s");
    s.link.timeout_s = rd.Real(to, s.link.timeout_s);
    rd.Above(to, s.link.timeout_s, 0.0);
    const Item mm = rd.Get(link, "max_missed");
    const std::int64_t missed = rd.Int(mm, s.link.max_missed);
    if (mm && (missed < 1 || missed > 1000000))
      rd.Fail(mm, "got " + std::to_string(missed) + " (expected an integer in 1..1000000)");
    s.link.max_missed = static_cast<int>(missed);
    const Item rf = rd.Get(link, "realtime_factor");
    s.link.realtime_factor = rd.Real(rf, s.link.realtime_factor);
    rd.AtLeast(rf, s.link.realtime_factor, 0.0);
    s.link.publish_truth = rd.Bool(rd.Get(link, "publish_truth"), s.link.publish_truth);
    const Item sp = rd.Get(link, "spin_us");
    const std::int64_t spin = rd.Int(sp, s.link.spin_us);
    if (sp && (spin < 0 || spin > UVMS_SPIN_US_MAX))
      rd.Fail(sp, "got " + std::to_string(spin) + " (expected an integer in 0.." +
                      std::to_string(UVMS_SPIN_US_MAX) + ")");
    s.link.spin_us = static_cast<int>(spin);
  }

  // ---- [faults]: fault injection by the harness (issue 7, docs/FAULTS.md) -------------------
  const Sec faults = rd.Sub(top, "faults");
  {
    for (const Sec &f : rd.Tables(faults, "thruster")) {
      ThrusterFault tf;
      const Item j = rd.Get(f, "thruster");
      if (!j) rd.Fail(Item{nullptr, f.table, f.key + ".thruster"}, "missing (expected the thruster number 1..8)");
      const std::int64_t jj = rd.Int(j, 1);
      if (jj < 1 || jj > static_cast<std::int64_t>(p.thrusters.size()))
        rd.Fail(j, "got " + std::to_string(jj) + " (expected 1.." + std::to_string(p.thrusters.size()) + ")");
      tf.thruster = static_cast<int>(jj);
      const Item mode = rd.Get(f, "mode");
      const std::string m = rd.Str(mode, "off");
      if (m == "off") tf.mode = ThrusterFault::Mode::kOff;
      else if (m == "stuck") tf.mode = ThrusterFault::Mode::kStuck;
      else if (m == "efficiency") tf.mode = ThrusterFault::Mode::kEfficiency;
      else rd.Fail(mode, "got \"" + m + "\" (expected \"off\", \"stuck\" or \"efficiency\")");
      const Item st = rd.Get(f, "start_s");
      tf.start_s = rd.Real(st, tf.start_s);
      rd.AtLeast(st, tf.start_s, 0.0);
      const bool voltage_drive = c.drive == UVMS_DRIVE_VOLTAGE;
      const Item sv = rd.Get(f, "stuck_voltage_V");
      tf.stuck_voltage_V = rd.Real(sv, tf.stuck_voltage_V);
      if (sv && tf.mode != ThrusterFault::Mode::kStuck)
        rd.Fail(sv, "only for mode = \"stuck\" (expected no stuck_voltage_V here)");
      if (sv && !voltage_drive)
        rd.Fail(sv, "only with thrusters.drive = \"voltage\" (the current drive's stuck stage "
                    "holds stuck_current_A)");
      const Item sc = rd.Get(f, "stuck_current_A");
      tf.stuck_current_A = rd.Real(sc, tf.stuck_current_A);
      if (sc && tf.mode != ThrusterFault::Mode::kStuck)
        rd.Fail(sc, "only for mode = \"stuck\" (expected no stuck_current_A here)");
      if (sc && voltage_drive)
        rd.Fail(sc, "only with thrusters.drive = \"current\" (the voltage drive's stuck stage "
                    "holds stuck_voltage_V)");
      const Item ef = rd.Get(f, "efficiency");
      tf.efficiency = rd.Real(ef, tf.mode == ThrusterFault::Mode::kEfficiency ? 0.5 : 1.0);
      if (ef && tf.mode != ThrusterFault::Mode::kEfficiency)
        rd.Fail(ef, "only for mode = \"efficiency\" (expected no efficiency here)");
      if (ef && !(tf.efficiency >= 0.0 && tf.efficiency < 1.0))
        rd.Fail(ef, "got " + Num(tf.efficiency) + " (expected a number in [0, 1))");
      tf.reported = rd.Bool(rd.Get(f, "reported"), tf.reported);
      const Item dd = rd.Get(f, "detect_delay_s");
      tf.detect_delay_s = rd.Real(dd, tf.detect_delay_s);
      rd.AtLeast(dd, tf.detect_delay_s, 0.0);
      s.faults.thrusters.push_back(tf);
    }
    const Sec sens = rd.Sub(faults, "sensors");
    struct Group {
      const char *name, *unit;
      SensorNoise *noise;
    };
    SensorFaults &sf = s.faults.sensors;
    const Group groups[] = {{"position", "m", &sf.position_m},
                            {"attitude", "rad", &sf.attitude_rad},
                            {"velocity", "m_s", &sf.velocity_m_s},
                            {"angular_velocity", "rad_s", &sf.angular_velocity_rad_s},
                            {"joint_position", "rad", &sf.joint_position_rad},
                            {"joint_velocity", "rad_s", &sf.joint_velocity_rad_s},
                            {"motor_speed", "rad_s", &sf.motor_speed_rad_s},
                            {"motor_current", "A", &sf.motor_current_A}};
    for (const Group &g : groups) {
      const Item sd = rd.Get(sens, std::string(g.name) + "_noise_" + g.unit);
      g.noise->std = rd.Real(sd, 0.0);
      rd.AtLeast(sd, g.noise->std, 0.0);
      g.noise->bias = rd.Real(rd.Get(sens, std::string(g.name) + "_bias_" + g.unit), 0.0);
    }
    const Sec lk = rd.Sub(faults, "link");
    LinkFaults &lf = s.faults.link;
    double total = 0.0;
    Item last;
    for (auto [name, rate] : {std::pair<const char *, double *>{"drop_rate", &lf.drop_rate},
                              {"delay_rate", &lf.delay_rate},
                              {"duplicate_rate", &lf.duplicate_rate},
                              {"corrupt_rate", &lf.corrupt_rate}}) {
      const Item r = rd.Get(lk, name);
      *rate = rd.Real(r, 0.0);
      if (r && !(*rate >= 0.0 && *rate <= 1.0))
        rd.Fail(r, "got " + Num(*rate) + " (expected a probability in [0, 1])");
      total += *rate;
      if (r) last = r;
    }
    if (total > 1.0) rd.Fail(last, "the four rates add up to " + Num(total) + " (expected at most 1)");
    lf.sensors = rd.Bool(rd.Get(lk, "sensors"), lf.sensors);
    lf.actuators = rd.Bool(rd.Get(lk, "actuators"), lf.actuators);
  }
  rd.CheckUnknown();

  // ---- The libraries' own validation -------------------------------------------------------
  {
    auto ctrl = std::make_unique<uvms_ctrl_t>();
    const uvms_status_t st = uvms_ctrl_init(ctrl.get(), &c);
    if (st != UVMS_OK) {
      const char *section = SectionOf(ctrl->config_error);
      const Item it = rd.Get(top, section);
      throw ScenarioError(Where(it.node, source) + ": key \"" + section +
                          "\": the controller rejected its configuration: part \"" +
                          uvms_cfg_field_str(ctrl->config_error) + "\" (uvms_ctrl_init: " +
                          uvms_status_str(st) + "; expected values the firmware accepts)");
    }
  }
  try {
    plant::Plant plant(p);
    plant.Reset(s.initial);
  } catch (const std::exception &ex) {
    throw ScenarioError(source + ": the plant rejected its configuration: " + ex.what());
  }
  return s;
}

Scenario LoadScenario(const std::string &path, const std::vector<std::string> &overrides) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ScenarioError(path + ": cannot read the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw ScenarioError(path + ": cannot read the file");
  return ParseScenario(text.str(), path, overrides);
}

namespace {

const char kUsageLine[] =
    "usage: uvms scenario check FILE [--set section.key=value]...  (see uvms scenario --help)";

const char kHelp[] = R"(usage: uvms scenario check FILE [--set section.key=value]...

Read a scenario (TOML), apply the overrides, validate everything (unknown keys, types, ranges,
contradictions, then the firmware's uvms_ctrl_init and the plant's own checks) and print a
one-line summary: name, case, payload, duration, tick count, flow, density error.

Options:
  --set KEY=VALUE   override one setting before validation; KEY is dotted (run.duration_s,
                    environment.unsteady_flow.enabled), VALUE is TOML: 10, 1e-6, true,
                    "VII", [1, 0, 0]. Repeatable; applied in order.
  -h, --help        print this help and exit

Errors name the place and the key: FILE:LINE: key "section.key": what is wrong (expected ...)
Keys, units, defaults and ranges: docs/SCENARIOS.md. Paper scenarios: sil/scenarios/paper/.
Exit status: 0 valid; 1 invalid scenario (one error line on stderr); 2 usage error.
)";

}  // namespace

int RunScenarioCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  const char *prefix = "uvms scenario: error: ";
  auto usage = [&](const std::string &msg) {
    err << prefix << msg << '\n' << kUsageLine << '\n';
    return kExitUsage;
  };
  if (args.empty()) return usage("missing action (expected: check)");
  if (args[0] == "-h" || args[0] == "--help") {
    out << kHelp;
    return kExitOk;
  }
  if (args[0] != "check") return usage("unknown action \"" + args[0] + "\" (expected: check)");
  std::string file;
  bool have_file = false;
  std::vector<std::string> sets;
  for (std::size_t i = 1; i < args.size(); ++i) {
    const std::string &a = args[i];
    if (a == "-h" || a == "--help") {
      out << kHelp;
      return kExitOk;
    }
    if (a == "--set") {
      if (i + 1 >= args.size()) return usage("--set needs a KEY=VALUE argument");
      sets.push_back(args[++i]);
    } else if (a.rfind("--set=", 0) == 0) {
      sets.push_back(a.substr(6));
    } else if (a.size() > 1 && a[0] == '-') {
      return usage("unknown option \"" + a + "\"");
    } else {
      if (have_file) return usage("more than one FILE (\"" + file + "\", \"" + a + "\")");
      file = a;
      have_file = true;
    }
  }
  if (!have_file) return usage("missing FILE");
  try {
    const Scenario s = LoadScenario(file, sets);
    out << "ok: " << ScenarioSummary(s) << '\n';
    return kExitOk;
  } catch (const ScenarioError &e) {
    std::string msg = e.what();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    err << prefix << msg << '\n';
    return kExitBadInput;
  }
}

}  // namespace uvms::sil
