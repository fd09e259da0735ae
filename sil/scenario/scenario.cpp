// SPDX-License-Identifier: Apache-2.0
// scenario.cpp: TOML scenario → controller configuration + plant configuration + harness
// settings (scenario.hpp). Every key, its parse, range check, targets and default come from the
// table of configuration fields (sil/msg/config_table.h, via config_schema.hpp); this file holds
// the walk over it and the named cross-key rules. docs/SCENARIOS.md's key tables are
// generated from the same table (`uvms scenario schema --markdown`).
//
// How a scenario is read (ParseScenario):
//   1. toml++ parses the text and the --set overrides go into the tree (scenario_reader.hpp).
//   2. ReadKeys: every key of the table, in the table's order, is looked up (marking it known
//      and used), type-checked and range-checked by its row; arrays of tables element by
//      element. Then every node nobody asked for is an unknown key (before any rule judges
//      the keys it was meant for).
//   3. The case and the switches decide the controller's starting configuration
//      (uvms_ctrl_config_paper(case)); the plant starts from PaperPlantParams(), the harness
//      from Scenario{} (PaperScenario).
//   4. ApplyTableKeys: every key given goes to its targets (the firmware gets the same value as
//      the plant or the harness when a key sets both).
//   5. The cross-key rules (kRules) apply the keys with special semantics and check
//      contradictions.
//   6. The libraries themselves validate both configurations: uvms_ctrl_init and the
//      plant::Plant constructor + Reset.
#include "scenario/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <ostream>
#include <sstream>
#include <utility>

#include "scenario/config_schema.hpp"
#include "scenario/motor_sets.hpp"
#include "scenario/scenario_reader.hpp"
#include "uvms_plant/environment.hpp"
#include "uvms_plant/multibody.hpp"

#include <Eigen/Eigenvalues>

namespace uvms::sil {
namespace {

constexpr double kMinTickS = 1e-6;             // run.tick_s: the LCM time unit (1 µs)
constexpr double kMaxDurationS = 1e9;          // run.duration_s, tick_s, link.timeout_s [s]
constexpr std::int64_t kMaxTicks = 1000000000; // duration_s / tick_s
constexpr double kMinRealtime = 1e-3;          // link.realtime_factor > 0
constexpr double kMaxRealtime = 1e3;
constexpr double kMinSquaredLimit = 1e-15;     // limits.*: squares stay normal floats
constexpr double kMaxSquaredLimit = 1e15;

/// SPEC §6.2: the controller's model density under "density error" [kg/m³].
constexpr double kDensityErrorModelKgM3 = 1000.0;
/// The paper's arm has 7 joints (SPEC §3.1): the SPEC §8 joint table's columns have this length.
constexpr std::size_t kJoints = 7;

const char *const kRoman[8] = {"I", "II", "III", "IV", "V", "VI", "VII", "VIII"};

// SPEC §8 table [deg]: one column of the firmware's table (uvms_joint_table_deg, written once
// there), as doubles.
std::array<double, kJoints> JointTableDeg(uvms_joint_table_column_t column) {
  std::array<double, kJoints> deg{};
  const uvms_real_t *col = uvms_joint_table_deg(column);
  for (std::size_t i = 0; i < kJoints && col != nullptr; ++i) deg[i] = static_cast<double>(col[i]);
  return deg;
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
    case UVMS_CFG_ARM: return "arm";  // the vehicle's body, the arm's links and the payload
    case UVMS_CFG_FLUID: return "environment";
    case UVMS_CFG_THRUSTER_GEOMETRY:
    case UVMS_CFG_THRUSTER_RANK:
    case UVMS_CFG_THRUSTER_PARAMS: return "thrusters";
    case UVMS_CFG_GAINS:
    case UVMS_CFG_SWITCHES:
    case UVMS_CFG_JOINT_SERVO: return "control";
    case UVMS_CFG_TICK: return "run";
    case UVMS_CFG_TRAJECTORY: return "trajectory";
    case UVMS_CFG_LIMITS: return "limits";
    case UVMS_CFG_DRIVE:
    case UVMS_CFG_ALLOC_MODE: return "thrusters";
    default: return "run";
  }
}

std::string OnOff(bool b) { return b ? "on" : "off"; }

// ---- step 2: every key of the table, read and checked ----------------------------------------

/// One key as read: where it is (or would be) and its value (null when absent, or when a rule
/// reads it itself).
struct KeyRead {
  const ConfigRow *row{nullptr};
  Item item;
  Json value;
};

/// One element of an array of tables: its fields by name.
struct Element {
  Sec sec;
  std::map<std::string, KeyRead> fields;
};

/// The scenario's keys, read in the table's order (which is also the order of "expected one
/// of" in unknown-key errors).
class Keys {
 public:
  explicit Keys(Reader &rd) : rd_(rd) {
    sections_[""] = rd.Root();
    for (const ConfigRow &row : ConfigTable()) {
      if (!row.HasKey() || row.IsElement()) continue;
      const Sec sec = Section(row.Section());
      KeyRead &kr = keys_[row.key];
      kr.row = &row;
      kr.item = rd.Get(sec, row.Leaf());
      if (row.range.kind == RangeRule::Kind::kTables) ReadElements(row, sec);
      else kr.value = ReadKey(rd, kr.item, row);
    }
  }

  const KeyRead &operator[](const std::string &key) const {
    const auto it = keys_.find(key);
    if (it == keys_.end()) throw std::logic_error("the rules use \"" + key + "\", which is no key of sil/msg/config_table.h");
    return it->second;
  }
  const std::vector<Element> &Elements(const std::string &key) const { return arrays_.at(key); }

 private:
  /// The section at a dotted path, looked up (and recorded) once.
  Sec Section(const std::string &path) {
    const auto found = sections_.find(path);
    if (found != sections_.end()) return found->second;
    const auto dot = path.rfind('.');
    const Sec parent = Section(dot == std::string::npos ? "" : path.substr(0, dot));
    const Sec sec = rd_.Sub(parent, dot == std::string::npos ? path : path.substr(dot + 1));
    sections_[path] = sec;
    return sec;
  }

  void ReadElements(const ConfigRow &array, const Sec &sec) {
    std::vector<Element> &elements = arrays_[array.key];
    const std::vector<const ConfigRow *> rows = ElementRows(array.key);
    for (const Sec &e : rd_.Tables(sec, array.Leaf())) {
      Element el{e, {}};
      for (const ConfigRow *row : rows) {
        KeyRead &kr = el.fields[row->Leaf()];
        kr.row = row;
        kr.item = rd_.Get(e, row->Leaf());
        kr.value = ReadKey(rd_, kr.item, *row);
      }
      elements.push_back(std::move(el));
    }
  }

  Reader &rd_;
  std::map<std::string, Sec> sections_;
  std::map<std::string, KeyRead> keys_;
  std::map<std::string, std::vector<Element>> arrays_;
};

/// A key's value, or its default from the table.
Json ValueOr(const KeyRead &kr) { return kr.value.is_null() ? DefaultJson(*kr.row) : kr.value; }

/// The given fields of an array element into its struct (the rows' element targets).
void ApplyElement(const Element &el, void *target) {
  for (const auto &[name, kr] : el.fields)
    if (!kr.value.is_null() && kr.row->elem_put != nullptr) kr.row->elem_put(target, kr.value);
}

// ---- step 3: case and switches ---------------------------------------------------------------

/// control.case: "I".."VIII" or 1..8 → 1..8; 0 when absent.
int CaseNumber(const Reader &rd, const Item &c) {
  if (!c) return 0;
  if (auto n = c.node->value_exact<int64_t>()) {
    if (*n < 1 || *n > 8) rd.Fail(c, "got " + std::to_string(*n) + " (expected one of I..VIII or 1..8)");
    return static_cast<int>(*n);
  }
  if (auto str = c.node->value_exact<std::string>()) {
    for (int k = 0; k < 8; ++k)
      if (*str == kRoman[k]) return k + 1;
    rd.Fail(c, "got \"" + *str + "\" (expected one of I..VIII)");
  }
  rd.Fail(c, "expected a string I..VIII, got " + TypeName(*c.node));
}

/// One switch key over the case's value: a switch that agrees with the case is accepted.
void ApplySwitch(const Reader &rd, const KeyRead &kr, int case_number, int *field) {
  if (kr.value.is_null()) return;
  const bool is_bool = kr.row->type == KeyType::kBool;
  const int value = is_bool ? (kr.value.get<bool>() ? 1 : 0) : kr.value.get<int>();
  auto text = [&](int v) {
    return is_bool ? std::string(v != 0 ? "true" : "false") : "\"" + ChoiceName(*kr.row, v) + "\"";
  };
  if (case_number != 0 && value != *field) {
    const std::string roman = kRoman[case_number - 1];
    rd.Fail(kr.item, "got " + text(value) + ", which contradicts control.case = \"" + roman +
                         "\" (case " + roman + " has " + text(*field) +
                         "; expected the case's value, or no case with explicit switches)");
  }
  *field = value;
}

/// Table X (SPEC §9): the case's switches, or all four switches when no case is named.
uvms_switches_t SwitchesRule(const Keys &k, const Reader &rd, int case_number) {
  const KeyRead &att = k["control.attitude"], &ref = k["control.position_reference"],
                &ff = k["control.position_feedforward"], &fb = k["control.position_feedback"];
  uvms_switches_t sw{};
  if (case_number != 0) {
    (void)uvms_switches_case(case_number, &sw);
  } else if (!att.item && !ref.item && !ff.item && !fb.item) {
    rd.Fail(k["control.case"].item,
            "missing (expected a Table X case \"I\"..\"VIII\", or the four switches "
            "attitude, position_reference, position_feedforward, position_feedback)");
  } else {
    for (const KeyRead *s : {&att, &ref, &ff, &fb})
      if (!s->item)
        rd.Fail(s->item, "missing (expected all four switches when no case is named, or a "
                         "control.case \"I\"..\"VIII\")");
  }
  ApplySwitch(rd, att, case_number, &sw.attitude_control);
  int reference = static_cast<int>(sw.position_reference);
  ApplySwitch(rd, ref, case_number, &reference);
  sw.position_reference = static_cast<uvms_reference_t>(reference);
  ApplySwitch(rd, ff, case_number, &sw.position_feedforward);
  ApplySwitch(rd, fb, case_number, &sw.position_feedback);
  return sw;
}

// ---- step 4: the table walk ------------------------------------------------------------------

/// Every key given goes to its target (the plant's or the harness's, else the firmware's); a
/// firmware field that shares a key with the plant or the harness then gets the same value
/// (the C++ side's default when the key is absent). Keys with rules are left to the rules.
void ApplyTableKeys(const Keys &k, Scenario &s) {
  for (const ConfigRow &row : ConfigTable()) {
    if (!row.HasKey() || row.by_rule) continue;
    const Json &v = k[row.key].value;
    const auto put = row.cpp_put != nullptr ? row.cpp_put : row.fw_put;
    if (put == nullptr) throw std::logic_error(std::string("key \"") + row.key + "\" has no target");
    if (!v.is_null()) put(s, v);
    if (row.cpp_get != nullptr && row.fw_put != nullptr) row.fw_put(s, row.cpp_get(s));
  }
}

// ---- step 5: the cross-key rules -------------------------------------------------------------

/// An item to place an error at: `a` when the file or an override gives it, else `b`.
const Item &Either(const Keys &k, const char *a, const char *b) {
  return k[a].item ? k[a].item : k[b].item;
}

/// [run]: the run holds at least one tick, and its tick count and simulated time fit their
/// counters (tick at least 1 µs, the LCM time unit; at most kMaxTicks ticks; utime in int64).
void RunDurationRule(const Keys &k, const Reader &rd, Scenario &s) {
  if (s.tick_s < kMinTickS || s.tick_s > kMaxDurationS)
    rd.Fail(k["run.tick_s"].item, "got " + Num(s.tick_s) + " (expected a tick in [" +
                                      Num(kMinTickS) + ", " + Num(kMaxDurationS) + "] s)");
  if (s.duration_s > kMaxDurationS)
    rd.Fail(k["run.duration_s"].item, "got " + Num(s.duration_s) + " (expected at most " +
                                          Num(kMaxDurationS) + " s)");
  if (s.duration_s < s.tick_s)
    rd.Fail(Either(k, "run.duration_s", "run.tick_s"),
            "duration_s " + Num(s.duration_s) + " s is shorter than tick_s " + Num(s.tick_s) +
                " s (expected duration_s >= tick_s)");
  if (s.duration_s / s.tick_s > static_cast<double>(kMaxTicks))
    rd.Fail(Either(k, "run.duration_s", "run.tick_s"),
            "duration_s / tick_s = " + Num(s.duration_s / s.tick_s) + " ticks (expected at most " +
                std::to_string(kMaxTicks) + ")");
}

/// [run]: the name names the run's directory under the output root: one path component.
void RunNameRule(const Keys &k, const Reader &rd, Scenario &s) {
  const std::string &n = s.name;
  const bool bad_char = std::any_of(n.begin(), n.end(), [](char c) {
    return c == '/' || c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
  });
  if (n.empty() || n == "." || n == ".." || bad_char || n.size() > 200)
    rd.Fail(Either(k, "run.name", "run.duration_s"),
            "got \"" + std::string(n.begin(), std::find(n.begin(), n.end(), '\0')) +
                "\" (expected one directory name: no /, \\, NUL or control characters, not . or "
                "..; at most 200 bytes; runs are written under the output root)");
}

/// [link]: pacing at r x real time needs r in [kMinRealtime, kMaxRealtime] (0: unpaced).
void RealtimeFactorRule(const Keys &k, const Reader &rd, Scenario &s) {
  const double r = s.link.realtime_factor;
  if (r != 0.0 && !(r >= kMinRealtime && r <= kMaxRealtime))
    rd.Fail(k["link.realtime_factor"].item, "got " + Num(r) + " (expected 0 or a factor in [" +
                                                Num(kMinRealtime) + ", " + Num(kMaxRealtime) + "])");
  if (s.link.timeout_s > kMaxDurationS)
    rd.Fail(k["link.timeout_s"].item, "got " + Num(s.link.timeout_s) + " (expected at most " +
                                          Num(kMaxDurationS) + " s)");
}

/// [limits]: the controller compares squares of these bounds in its real type (float on the
/// target): a bound > 0 must keep its square a normal, finite float.
void CheckSquaredLimit(const Reader &rd, const KeyRead &kr) {
  if (!kr.item || !kr.value.is_number()) return;
  const double x = kr.value.get<double>();
  if (x != 0.0 && !(x >= kMinSquaredLimit && x <= kMaxSquaredLimit))
    rd.Fail(kr.item, "got " + Num(x) + " (expected 0 (check off) or a bound in [" +
                         Num(kMinSquaredLimit) + ", " + Num(kMaxSquaredLimit) +
                         "], whose square is a normal float)");
}

void LimitSquaresRule(const Keys &k, const Reader &rd, Scenario &) {
  for (const char *key : {"limits.max_vehicle_speed_m_s", "limits.max_vehicle_rate_rad_s",
                          "limits.max_joint_rate_rad_s", "limits.max_motor_speed_rad_s",
                          "limits.max_motor_current_A", "limits.quat_norm_tol",
                          "limits.thrust_limit_N"})
    CheckSquaredLimit(rd, k[key]);
}

/// Thrust limits (docs/FAULTS.md "Thrust limit"): limits.thrust_limit_N for every thruster,
/// a [[thrusters.thruster]]'s own thrust_limit_N for that one (each 0: none, else a bound
/// whose square is a normal float).
void ThrustLimitsRule(const Keys &k, const Reader &rd, Scenario &s) {
  const double all_N = ValueOr(k["limits.thrust_limit_N"]).get<double>();
  for (uvms_real_t &limit_N : s.controller.limits.thrust_limit_N) limit_N = uvms_real_t(all_N);
  if (!k["thrusters.thruster"].item) return;
  const std::vector<Element> &elements = k.Elements("thrusters.thruster");
  for (std::size_t j = 0; j < elements.size() && j < UVMS_MAX_THRUSTERS; ++j) {
    const KeyRead &kr = elements[j].fields.at("thrust_limit_N");
    if (kr.value.is_null()) continue;
    CheckSquaredLimit(rd, kr);
    s.controller.limits.thrust_limit_N[j] = uvms_real_t(kr.value.get<double>());
  }
}

/// [thrusters] motor (sil/scenario/motor_sets.hpp; docs/MODEL.md §5 "Motor parameter sets"): the named
/// set fills each of its keys that the scenario does not give; a key given explicitly keeps
/// its own value (precedence: explicit key > named set; no key and no set: "paper"). Each
/// value goes through its key's row, as the table walk does: the plant member, then the
/// firmware field from it, so the two models get the same value (SPEC §3.4, §5, §7.4).
void MotorSetRule(const Keys &k, const Reader &, Scenario &s) {
  const KeyRead &m = k["thrusters.motor"];
  const std::string name =
      m.value.is_null() ? ValueOr(m).get<std::string>() : ChoiceName(*m.row, m.value.get<long>());
  const MotorSet *set = FindMotorSet(name);
  if (set == nullptr) throw std::logic_error("thrusters.motor: no set \"" + name + "\" in sil/scenario/motor_sets.cpp");
  const plant::PropulsionParams values = set->params();
  for (const MotorSetKey &key : MotorSetKeys()) {
    if (!k[key.key].value.is_null()) continue;  // given explicitly: it overrides the set
    const ConfigRow &row = *k[key.key].row;
    row.cpp_put(s, Json(values.*key.member));
    row.fw_put(s, row.cpp_get(s));
  }
}

/// The wrench axes (rows of H, UVMS_AXIS_* bit order) as an error names them.
const char *const kWrenchAxisNames[UVMS_ALLOC_WRENCH_DIM] = {
    "surge force (x)", "sway force (y)", "heave force (z)",
    "roll moment (about x)", "pitch moment (about y)", "yaw moment (about z)"};

/// The relative eigenvalue threshold of the float build's allocation (UVMS_ALLOC_REL_EIG_TOL
/// there, allocation.h), the stricter of the two builds': a layout accepted here is accepted by
/// the double and the float controller alike, the Cortex-M4F's included.
constexpr double kLayoutRelEigTol = 1e-5;
static_assert(!UVMS_REAL_IS_FLOAT || UVMS_ALLOC_REL_EIG_TOL == UVMS_R(kLayoutRelEigTol),
              "kLayoutRelEigTol is the float build's UVMS_ALLOC_REL_EIG_TOL");

/// The UVMS_AXIS_* bits of the wrench axes a layout cannot produce, by the firmware's criteria
/// (allocation.h) computed here in double with Eigen: an eigenvalue of G = H·Hᵀ at or below
/// kLayoutRelEigTol·λ_max is lost, and axis i is lost when Σ_{k lost} V_ik² is above
/// UVMS_ALLOC_AXIS_RESIDUAL_TOL. H [33–37]: column j = (u_j; a_j × u_j).
unsigned LostWrenchAxes(const std::vector<plant::ThrusterGeometry> &layout, int *rank) {
  Eigen::Matrix<double, 6, Eigen::Dynamic> H(6, static_cast<Eigen::Index>(layout.size()));
  for (std::size_t j = 0; j < layout.size(); ++j) {
    const plant::ThrusterGeometry &g = layout[j];
    H.col(static_cast<Eigen::Index>(j)) << g.direction, g.position_m.cross(g.direction);
  }
  const Eigen::SelfAdjointEigenSolver<plant::Mat6> eig(H * H.transpose());
  const double tol = kLayoutRelEigTol * eig.eigenvalues().maxCoeff();
  Eigen::Matrix<double, 6, 1> residual = Eigen::Matrix<double, 6, 1>::Zero();
  *rank = 0;
  for (int k = 0; k < 6; ++k) {
    if (eig.eigenvalues()[k] > tol) ++*rank;
    else residual += eig.eigenvectors().col(k).cwiseAbs2();
  }
  unsigned lost = 0;
  for (int i = 0; i < 6; ++i)
    if (residual[i] > static_cast<double>(UVMS_ALLOC_AXIS_RESIDUAL_TOL)) lost |= 1u << i;
  return lost;
}

/// The tables of the array of tables `key` when the scenario gives it (nullptr otherwise):
/// 1..max of them, the firmware's fixed maximum `macro`, else an error counting `what`.
const std::vector<Element> *GivenElements(const Keys &k, const Reader &rd, const char *key, std::size_t max,
                                          const char *what, const char *macro) {
  const Item &array = k[key].item;
  if (!array) return nullptr;
  const std::vector<Element> &elements = k.Elements(key);
  if (elements.empty() || elements.size() > max)
    rd.Fail(array, std::to_string(elements.size()) + " " + what + " (expected 1.." + std::to_string(max) +
                       ", the firmware's " + macro + ")");
  return &elements;
}

/// An element's fields that its rows mark required (NOTE("required")), each given.
void RequireFields(const Element &el, const Reader &rd) {
  for (const auto &[name, kr] : el.fields)
    if (!kr.item && kr.row->IsRequired())
      rd.Fail(kr.item, kr.row->type == KeyType::kVec3     ? "missing (expected 3 numbers)"
                       : kr.row->type == KeyType::kString ? "missing (expected a string)"
                                                          : "missing (expected a number)");
}

/// One [[thrusters.thruster]]: its fields given, the direction normalised.
plant::ThrusterGeometry ThrusterOf(const Element &el, const Reader &rd) {
  RequireFields(el, rd);
  plant::ThrusterGeometry g;
  ApplyElement(el, &g);
  g.direction.normalize();
  return g;
}

/// [[thrusters.thruster]] (SPEC §3.4): the layout given replaces the paper's, in the plant and
/// in the controller alike; 1..UVMS_MAX_THRUSTERS of them, able to produce every wrench.
void ThrustersRule(const Keys &k, const Reader &rd, Scenario &s) {
  const std::vector<Element> *elements =
      GivenElements(k, rd, "thrusters.thruster", UVMS_MAX_THRUSTERS, "thrusters", "UVMS_MAX_THRUSTERS");
  if (elements == nullptr) return;
  const Item &array = k["thrusters.thruster"].item;
  std::vector<plant::ThrusterGeometry> layout;
  for (const Element &el : *elements) layout.push_back(ThrusterOf(el, rd));
  int rank = 0;
  const unsigned lost = LostWrenchAxes(layout, &rank);
  if (lost != 0) {
    std::string names;
    for (int i = 0; i < UVMS_ALLOC_WRENCH_DIM; ++i)
      if ((lost >> i) & 1u) names += (names.empty() ? "" : ", ") + std::string(kWrenchAxisNames[i]);
    rd.Fail(array, "the layout cannot produce " + names + " (H has rank " + std::to_string(rank) +
                       " of 6; expected thrusters that push along and turn about every axis)");
  }
  s.plant.thrusters = layout;
  uvms_thruster_geometry_t &geom = s.controller.thrusters;
  geom = uvms_thruster_geometry_t{};
  geom.num_thrusters = layout.size();
  for (std::size_t j = 0; j < layout.size(); ++j) {
    ToReal3(layout[j].position_m, geom.position_m[j]);
    ToReal3(layout[j].direction, geom.direction[j]);
  }
}

/// One [thrusters] propeller/motor key's value for thruster j alone: through the key's row as
/// the table walk does (the plant member, then the firmware field from it), the plant member
/// being PlantParams::propulsion (the caller keeps the default and moves the result).
void PutThrusterKey(const Keys &k, Scenario &s, std::size_t j, const std::string &key, const Json &v) {
  const ConfigRow &row = *k[key].row;
  if (row.cpp_put != nullptr) row.cpp_put(s, v);
  row.fw_link_put(s, j, row.cpp_put != nullptr ? row.cpp_get(s) : v);
}

/// Thruster j gets the type `type` (docs/SCENARIOS.md "Thruster types"): the [thrusters]
/// values, then the type's named set (motor), then the type's own keys, in both models.
void ApplyThrusterType(const Keys &k, const Element &type, std::size_t j, Scenario &s) {
  const plant::PropulsionParams base = s.plant.propulsion;
  const KeyRead &motor = type.fields.at("motor");
  if (!motor.value.is_null()) {
    const std::string name = ChoiceName(*motor.row, motor.value.get<long>());
    const MotorSet *set = FindMotorSet(name);
    if (set == nullptr) throw std::logic_error("thrusters.type[].motor: no set \"" + name + "\"");
    const plant::PropulsionParams values = set->params();
    for (const MotorSetKey &key : MotorSetKeys()) PutThrusterKey(k, s, j, key.key, Json(values.*key.member));
  }
  for (const auto &[leaf, kr] : type.fields)
    if (leaf != "name" && leaf != "motor" && !kr.value.is_null())
      PutThrusterKey(k, s, j, "thrusters." + leaf, kr.value);
  plant::PropulsionParams own = s.plant.propulsion;
  own.drive = base.drive;
  s.plant.propulsion = base;
  if (j < s.plant.thrusters.size()) s.plant.thrusters[j].propulsion = own;
}

/// [[thrusters.type]] (docs/SCENARIOS.md "Thruster types"): named propeller and motor sets; a
/// [[thrusters.thruster]] with type = "name" gets that set, one without keeps the [thrusters]
/// keys'. Names are unique, every name a thruster gives exists, every type is used.
void ThrusterTypesRule(const Keys &k, const Reader &rd, Scenario &s) {
  const Item &types_item = k["thrusters.type"].item;
  std::map<std::string, const Element *> types;
  std::map<std::string, bool> used;
  std::string names;
  if (types_item) {
    for (const Element &el : k.Elements("thrusters.type")) {
      RequireFields(el, rd);
      const KeyRead &name = el.fields.at("name");
      const std::string n = name.value.get<std::string>();
      if (types.count(n) != 0) rd.Fail(name.item, "a second type named \"" + n + "\" (expected unique names)");
      types[n] = &el;
      used[n] = false;
      names += (names.empty() ? "" : ", ") + n;
    }
  }
  const Item &layout = k["thrusters.thruster"].item;
  if (layout) {
    const std::vector<Element> &thrusters = k.Elements("thrusters.thruster");
    for (std::size_t j = 0; j < thrusters.size() && j < UVMS_MAX_THRUSTERS; ++j) {
      const KeyRead &type = thrusters[j].fields.at("type");
      if (type.value.is_null()) continue;
      const std::string n = type.value.get<std::string>();
      const auto found = types.find(n);
      if (found == types.end())
        rd.Fail(type.item, "no [[thrusters.type]] named \"" + n + "\"" +
                               (names.empty() ? std::string(" (none is given)") : " (expected one of: " + names + ")"));
      used[n] = true;
      ApplyThrusterType(k, *found->second, j, s);
    }
  }
  for (const auto &[n, u] : used)
    if (!u)
      rd.Fail(types.at(n)->fields.at("name").item,
              "no [[thrusters.thruster]] has type = \"" + n + "\" (expected every type used" +
                  (layout ? ")" : "; the paper's layout has no tables to name it: give [[thrusters.thruster]])"));
}

/// Principal moments of a rigid body: each at least 0 (> 0 unless zero_allowed: a point mass's
/// are 0) and each at most the sum of the other two (I_x = ∫(y² + z²) dm ≤ I_y + I_z =
/// ∫(x² + y² + 2z²) dm). The reader's error names `it`'s key.
void CheckPrincipalMoments(const Reader &rd, const Item &it, const plant::Vec3 &I, bool zero_allowed,
                           const char *what = "got") {
  const std::string got = std::string(what) + " (" + Num(I[0]) + ", " + Num(I[1]) + ", " +
                          Num(I[2]) + ") kg·m²";
  if (zero_allowed ? !(I.minCoeff() >= 0.0) : !(I.minCoeff() > 0.0))
    rd.Fail(it, got + (zero_allowed ? " (expected principal moments ≥ 0)" : " (expected principal moments > 0)"));
  for (int i = 0; i < 3; ++i)
    if (I[i] > (I[(i + 1) % 3] + I[(i + 2) % 3]) * (1.0 + 1e-12))
      rd.Fail(it, got + ": moment " + std::to_string(i + 1) + " exceeds the sum of the other "
                  "two, which no rigid body has (expected I_i ≤ I_j + I_k)");
}

/// [vehicle] inertia_kg_m2: a rigid body's principal moments, all positive.
void VehicleInertiaRule(const Keys &k, const Reader &rd, Scenario &s) {
  const KeyRead &kr = k["vehicle.inertia_kg_m2"];
  if (!kr.item) return;
  const plant::Vec3 I = rd.Vec(kr.item, plant::Vec3::Zero());
  CheckPrincipalMoments(rd, kr.item, I, false);
  s.plant.vehicle.inertia_kg_m2 = I;
  kr.row->fw_put(s, Json::array({I[0], I[1], I[2]}));
}

/// A 6×6 added-mass matrix given as 36 numbers, row-major: the fluid's kinetic energy
/// ½·νᵀ·M_A·ν is never negative, so it is symmetric positive semidefinite (Fossen 2011, §6.3.1).
plant::Mat6 AddedMassOf(const Reader &rd, const Item &item) {
  const std::vector<double> v = rd.Reals(item, 36);
  const plant::Mat6 M = Eigen::Map<const Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(v.data());
  const double scale = std::max(M.cwiseAbs().maxCoeff(), 1e-300);
  const double asym = (M - M.transpose()).cwiseAbs().maxCoeff();
  if (asym > 1e-9 * scale)
    rd.Fail(item, "not symmetric: |M − Mᵀ| reaches " + Num(asym) +
                      " (expected M[r][c] = M[c][r], row-major 6×6)");
  const Eigen::Matrix<double, 6, 1> lambda = Eigen::SelfAdjointEigenSolver<plant::Mat6>(M).eigenvalues();
  if (lambda.minCoeff() < -1e-9 * scale)
    rd.Fail(item, "not positive semidefinite: smallest eigenvalue " + Num(lambda.minCoeff()) +
                      " (expected every eigenvalue ≥ 0: the fluid's kinetic energy is ≥ 0)");
  return M;
}

void AddedMassRule(const Keys &k, const Reader &rd, Scenario &s) {
  const KeyRead &kr = k["vehicle.added_mass_coeff"];
  if (!kr.item) return;
  s.plant.added_mass_coeff = AddedMassOf(rd, kr.item);
  kr.row->fw_put(s, Json(rd.Reals(kr.item, 36)));
}

/// The vehicle's own absolute added mass (plant only; docs/MODEL.md §3.3).
void VehicleAddedMassRule(const Keys &k, const Reader &rd, Scenario &s) {
  const KeyRead &kr = k["vehicle.added_mass_kg"];
  if (kr.item) s.plant.vehicle.added_mass_kg = AddedMassOf(rd, kr.item);
}

/// One [[arm.link]]: its required fields given, its inertia a rigid body's, its limits ordered.
ArmLink ArmLinkOf(const Element &el, const Reader &rd) {
  RequireFields(el, rd);
  ArmLink link;
  ApplyElement(el, &link);
  const Item &inertia = el.fields.at("inertia_kg_m2").item;
  const Item &products = el.fields.at("inertia_products_kg_m2").item;
  if (inertia) link.inertia_kg_m2 = rd.Vec(inertia, plant::Vec3::Zero());  // SPECIAL: read here
  if (products) {
    // The full tensor's principal moments are its eigenvalues: ≥ 0, and none above the sum of
    // the other two; the error names the off-diagonal key and shows the eigenvalues.
    plant::Vec3 lambda =
        Eigen::SelfAdjointEigenSolver<plant::Mat3>(plant::InertiaTensor(link)).eigenvalues();
    const double tol = 1e-12 * link.inertia_kg_m2.sum();  // rounding of a singular tensor: 0
    for (int i = 0; i < 3; ++i)
      if (lambda[i] < 0.0 && lambda[i] > -tol) lambda[i] = 0.0;
    CheckPrincipalMoments(rd, products, lambda, true, "the tensor's eigenvalues are");
  } else if (inertia) {
    CheckPrincipalMoments(rd, inertia, link.inertia_kg_m2, true);
  }
  const Item &own_added_mass = el.fields.at("added_mass_kg").item;
  if (own_added_mass && plant::HasOwnAddedMass(link) &&
      !(link.diameter_m > 0.0 && plant::LinkLength(link) > 0.0))
    rd.Fail(own_added_mass, "the link has no hydrodynamic cylinder (diameter_m = " + Num(link.diameter_m) +
                                ", length " + Num(plant::LinkLength(link)) +
                                " m); expected diameter_m > 0 and a length > 0 for a link's own "
                                "added mass (both models apply it only to a link with a volume)");
  if (!(link.joint_min_rad < link.joint_max_rad)) {
    const Item &max = el.fields.at("joint_max_rad").item;
    rd.Fail(max ? max : el.fields.at("joint_min_rad").item,
            "joint limits " + Num(link.joint_min_rad) + " .. " + Num(link.joint_max_rad) +
                " rad (expected joint_min_rad < joint_max_rad)");
  }
  return link;
}

/// [[arm.link]] (SPEC §3.1's form, standard DH, optionally general links): the arm given
/// replaces the paper's, in the plant and in the controller alike; 1..UVMS_MAX_JOINTS links
/// from the base.
void ArmLinksRule(const Keys &k, const Reader &rd, Scenario &s) {
  const std::vector<Element> *elements =
      GivenElements(k, rd, "arm.link", UVMS_MAX_JOINTS, "links", "UVMS_MAX_JOINTS");
  if (elements == nullptr) return;
  uvms_arm_params_t &arm = s.controller.arm;
  for (uvms_link_params_t &slot : arm.link) slot = uvms_link_params_t{};
  s.plant.links.clear();
  for (const Element &el : *elements) {
    const ArmLink link = ArmLinkOf(el, rd);
    // Each LINK row carries its field to the controller's link, in the controller's precision.
    for (const ConfigRow *row : ElementRows("arm.link"))
      if (row->fw_link_put != nullptr) row->fw_link_put(s, s.plant.links.size(), row->elem_get(&link));
    s.plant.links.push_back(link);  // the plant's part
  }
  arm.num_joints = s.plant.links.size();
}

/// [arm] (SPEC §9 item 8: the analytic model's massless, dragless arm): mass scale and
/// hydrodynamics, in the controller's model and the plant alike.
void ArmRule(const Keys &k, const Reader &, Scenario &s) {
  const double scale = ValueOr(k["arm.mass_scale"]).get<double>();
  const bool hydro = ValueOr(k["arm.hydrodynamics"]).get<bool>();
  plant::PlantParams &p = s.plant;
  uvms_ctrl_config_t &c = s.controller;
  for (size_t i = 0; i < p.links.size() && i < UVMS_MAX_JOINTS; ++i) {
    p.links[i].mass_kg *= scale;  // m_i and I_Bi together: the link's shape is unchanged
    p.links[i].inertia_kg_m2 *= scale;
    p.links[i].inertia_products_kg_m2 *= scale;
    c.arm.link[i].mass_kg = R(p.links[i].mass_kg);
    for (int j = 0; j < 3; ++j) {
      c.arm.link[i].inertia_kg_m2[j] = R(p.links[i].inertia_kg_m2[j]);
      c.arm.link[i].inertia_products_kg_m2[j] = R(p.links[i].inertia_products_kg_m2[j]);
    }
    if (!hydro) {  // d_L = 0: no volume, buoyancy, drag or added mass (SPEC §3.1)
      p.links[i].diameter_m = 0.0;
      c.arm.link[i].diameter_m = R(0.0);
    }
  }
}

/// [vehicle] attitude_rpy_deg: the initial attitude, R = Rz(yaw)·Ry(pitch)·Rx(roll).
void VehicleAttitudeRule(const Keys &k, const Reader &, Scenario &s) {
  const Json rpy = ValueOr(k["vehicle.attitude_rpy_deg"]);
  s.initial.attitude = FromRpyDeg(plant::Vec3(rpy[0].get<double>(), rpy[1].get<double>(), rpy[2].get<double>()));
}

/// "N angles in degrees" for an arm of n joints.
std::string AnglesText(std::size_t n) {
  return std::to_string(n) + (n == 1 ? " angle in degrees" : " angles in degrees");
}

/// θI [deg]: N angles, or SPEC §8's start pose for the paper's arm (required for an arm given
/// by [[arm.link]], which has none).
std::vector<double> ThetaStartDeg(const KeyRead &kr, const Reader &rd, std::size_t n, bool paper_arm) {
  if (kr.item) return rd.Reals(kr.item, n);
  if (!paper_arm)
    rd.Fail(kr.item, "missing (expected " + AnglesText(n) + ": the arm of [[arm.link]] has no SPEC §8 start pose)");
  const std::array<double, kJoints> paper = PaperThetaStartDeg();
  return {paper.begin(), paper.end()};
}

/// θF (SPEC §8, its two readings): "auto" (same task: the "Veh." column for the vehicle
/// reference, the payload's barycenter column for the barycenter reference, with the 10 kg
/// column's corrected joint 1, docs/MODEL.md C26), "printed" (the same with the paper's printed
/// 176.19°), "vehicle" (same motion: the "Veh." column for every case) or N angles [deg]. The
/// names are columns of the paper arm's table: an arm of [[arm.link]] needs angles for a joint
/// cycloid, and holds θI otherwise.
std::vector<double> ThetaFinalDeg(const KeyRead &kr, const Reader &rd, const Scenario &s,
                                  const std::vector<double> &theta_start_deg, bool paper_arm) {
  const std::size_t n = theta_start_deg.size();
  const std::string expected = "expected \"auto\", \"printed\", \"vehicle\" or an array of " + AnglesText(n);
  const Item &it = kr.item;
  if (it && it.node->is_array()) return rd.Reals(it, n);
  if (it && !it.node->is_string()) rd.Fail(it, expected + ", got " + TypeName(*it.node));
  const std::string name = it ? *it.node->value_exact<std::string>() : std::string("auto");
  if (name != "auto" && name != "printed" && name != "vehicle") rd.Fail(it, "got \"" + name + "\" (" + expected + ")");
  const uvms_ctrl_config_t &c = s.controller;
  const bool cycloid = c.traj_mode == UVMS_TRAJ_JOINT_CYCLOID;
  if (!paper_arm) {
    if (cycloid)
      rd.Fail(it, (it ? "\"" + name + "\" names" : std::string("missing: \"auto\" names")) +
                      " a SPEC §8 column of the paper's 7-joint arm (expected " + AnglesText(n) +
                      " for the arm of [[arm.link]])");
    return theta_start_deg;
  }
  std::array<double, kJoints> deg{};
  std::copy(theta_start_deg.begin(), theta_start_deg.end(), deg.begin());
  const uvms_reference_t reference = name == "vehicle" ? UVMS_REF_VEHICLE : c.switches.position_reference;
  const bool found = PaperThetaFinalDeg(reference, s.plant.payload_kg, &deg);
  if (!found && cycloid)
    rd.Fail(it, "\"" + name + "\" has no SPEC §8 column for a " + Num(s.plant.payload_kg) +
                    " kg payload with the barycenter reference (the table has 0, 1, 2, 5, 10 kg; "
                    "expected an explicit theta_final_deg = [7 angles in degrees])");
  if (found && name == "printed" && reference == UVMS_REF_BARYCENTER && s.plant.payload_kg == 10.0)
    deg[0] = UVMS_JOINT_TABLE_BARY_10KG_J1_PRINTED_DEG;
  return {deg.begin(), deg.end()};
}

/// An angle [deg] to 6 significant digits: the controller's limits are in its own precision
/// (float: 2π rad is 360.00001°).
std::string Deg6(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", x);
  return buf;
}

/// θI, and θF of a joint cycloid, within each joint's limits (arm.link[j].joint_min_rad ..
/// joint_max_rad; the controller flags a sensed angle outside them), the key and joint named.
void CheckJointLimits(const Keys &k, const Reader &rd, const Scenario &s,
                      const std::vector<double> &start_deg, const std::vector<double> &final_deg) {
  const double deg = M_PI / 180.0;
  const bool cycloid = s.controller.traj_mode == UVMS_TRAJ_JOINT_CYCLOID;
  for (std::size_t j = 0; j < start_deg.size() && j < UVMS_MAX_JOINTS; ++j) {
    const double lo = static_cast<double>(s.controller.arm.link[j].joint_min_rad);
    const double hi = static_cast<double>(s.controller.arm.link[j].joint_max_rad);
    const std::pair<const char *, double> angles[] = {{"trajectory.theta_start_deg", start_deg[j]},
                                                      {"trajectory.theta_final_deg", final_deg[j]}};
    for (std::size_t n = 0; n < (cycloid ? 2u : 1u); ++n) {  // θF is a joint cycloid's only
      const auto &[key, a] = angles[n];
      // The controller's limits are in its own precision: compare at that precision's grain.
      const double slack = 4.0 * std::numeric_limits<uvms_real_t>::epsilon() * std::max(1.0, std::fabs(a * deg));
      if (a * deg < lo - slack || a * deg > hi + slack)
        rd.Fail(k[key].item, "joint " + std::to_string(j + 1) + " at " + Num(a) + "° is outside its limits " +
                                 Deg6(lo / deg) + "° .. " + Deg6(hi / deg) + "° (arm.link[" + std::to_string(j) +
                                 "].joint_min_rad .. joint_max_rad)");
    }
  }
}

/// [trajectory] (SPEC §8): θI and θF in degrees → the controller's radians (slots past N
/// zero) and the plant's N initial joints; one tF for both modes. For an arm of [[arm.link]]
/// the trim pose is θI too (the paper's is its stowed pose θI, PaperPlantParams()).
void TrajectoryRule(const Keys &k, const Reader &rd, Scenario &s) {
  uvms_ctrl_config_t &c = s.controller;
  const bool paper_arm = !k["arm.link"].item;
  const std::vector<double> start_deg =
      ThetaStartDeg(k["trajectory.theta_start_deg"], rd, s.plant.links.size(), paper_arm);
  const std::vector<double> final_deg =
      ThetaFinalDeg(k["trajectory.theta_final_deg"], rd, s, start_deg, paper_arm);
  CheckJointLimits(k, rd, s, start_deg, final_deg);
  const double deg = M_PI / 180.0;
  s.initial.q_rad.assign(start_deg.size(), 0.0);
  for (std::size_t j = 0; j < UVMS_MAX_JOINTS; ++j) {
    const bool used = j < start_deg.size();
    c.theta_start_rad[j] = used ? R(start_deg[j] * deg) : R(0.0);
    c.theta_final_rad[j] = used ? R(final_deg[j] * deg) : R(0.0);
    if (used) s.initial.q_rad[j] = start_deg[j] * deg;
  }
  if (!paper_arm) s.plant.env.trim_pose_rad = s.initial.q_rad;
  c.cart.duration_s = c.traj_duration_s;  // one tF for both modes
}

/// [metrics] ee_target_m for an arm of [[arm.link]]: the paper's target point belongs to the
/// paper's arm, so without the key the target is where this arm's EE is at θF with the vehicle
/// at its initial pose (the point the maneuver takes the EE to, as the paper's is for its arm).
void UserArmTargetRule(const Keys &k, const Reader &, Scenario &s) {
  if (!k["arm.link"].item || k["metrics.ee_target_m"].item) return;
  std::vector<double> q(s.plant.links.size());
  for (std::size_t j = 0; j < q.size() && j < UVMS_MAX_JOINTS; ++j)
    q[j] = static_cast<double>(s.controller.theta_final_rad[j]);
  plant::BaseState b;
  b.r0_m = s.initial.r0_m;
  b.R0 = s.initial.attitude.toRotationMatrix();
  const std::vector<double> zero(q.size(), 0.0);
  plant::ArmKinematics kin;
  plant::ComputeArmKinematics(plant::ArmModel::FromParams(s.plant), b, q.data(), zero.data(), zero.data(), kin);
  s.metrics.ee_target_m = kin.ee_m;
}

/// [environment] density: the controller's model ρ is the plant's, 1000 kg/m³ under a density
/// error (SPEC §6.2), or model_density_kg_m3 (which must then agree with density_error).
void DensityRule(const Keys &k, const Reader &rd, Scenario &s) {
  const KeyRead &err = k["environment.density_error"], &model = k["environment.model_density_kg_m3"];
  const double rho = s.plant.env.density_kg_m3;
  if (!err.value.is_null()) s.density_error = err.value.get<bool>();
  double model_rho = s.density_error ? kDensityErrorModelKgM3 : rho;
  if (!model.value.is_null()) {
    const double x = model.value.get<double>();
    if (err.item && x != model_rho)
      rd.Fail(model.item, "got " + Num(x) + ", which contradicts environment.density_error = " +
                              (s.density_error ? "true" : "false") + " (that means " +
                              Num(model_rho) + "; expected one of the two keys, or agreeing values)");
    model_rho = x;
    s.density_error = x != rho;
  }
  s.controller.fluid.density_kg_m3 = R(model_rho);
}

/// [environment] gravity (a preset of the plant's GravityPreset or a vector) in both models;
/// trim is on by default whenever there is gravity (SPEC §6.3).
void GravityAndTrimRule(const Keys &k, const Reader &rd, Scenario &s) {
  plant::EnvironmentParams &e = s.plant.env;
  const Item &g = k["environment.gravity_m_s2"].item;
  if (g && g.node->is_string()) {
    const std::string name = *g.node->value_exact<std::string>();
    try {
      e.gravity_m_s2 = plant::GravityPreset(name);
    } catch (const std::invalid_argument &) {
      rd.Fail(g, "got \"" + name + "\" (expected \"paper\", \"earth\", \"europa\" or [gx, gy, gz])");
    }
  } else if (g && g.node->is_array()) {
    e.gravity_m_s2 = rd.Vec(g, e.gravity_m_s2);
  } else if (g) {
    rd.Fail(g, "expected \"paper\", \"earth\", \"europa\" or [gx, gy, gz], got " + TypeName(*g.node));
  }
  ToReal3(e.gravity_m_s2, s.controller.fluid.gravity_m_s2);
  const KeyRead &trim = k["environment.trim"];
  e.trim = trim.value.is_null() ? e.gravity_m_s2.norm() != 0.0 : trim.value.get<bool>();
}

/// [environment] the controller's angle-of-attack switch follows the plant's unless set apart.
void ModelAngleOfAttackRule(const Keys &k, const Reader &, Scenario &s) {
  const KeyRead &m = k["environment.model_angle_of_attack"];
  const bool aoa = m.value.is_null() ? s.plant.env.angle_of_attack : m.value.get<bool>();
  s.controller.fluid.angle_of_attack = aoa ? 1 : 0;
}

/// [[environment.coeff_table]] (SPEC §6.4): only with variable_coefficients; rows with a
/// distance, strictly increasing; then the plant's own check.
void CoeffTableRule(const Keys &k, const Reader &rd, Scenario &s) {
  plant::EnvironmentParams &e = s.plant.env;
  const Item &table = k["environment.coeff_table"].item;
  const std::vector<Element> &rows = k.Elements("environment.coeff_table");
  if (table && !e.variable_coefficients)
    rd.Fail(table, "given while environment.variable_coefficients is false (expected "
                   "variable_coefficients = true, or no table)");
  if (table && rows.empty()) rd.Fail(table, "is empty (expected at least one row)");
  for (const Element &row : rows) {
    const Item &d = row.fields.at("distance_diameters").item;
    if (!d) rd.Fail(d, "missing (expected the travelled distance in link diameters, >= 0)");
    plant::CoeffTableRow r;
    ApplyElement(row, &r);
    if (!e.coeff_table.empty() && !(r.distance_diameters > e.coeff_table.back().distance_diameters))
      rd.Fail(d, "got " + Num(r.distance_diameters) +
                     " (expected distances strictly increasing from row to row)");
    e.coeff_table.push_back(r);
  }
  if (e.coeff_table.empty()) return;
  try {
    plant::ValidateCoeffTable(e.coeff_table);
  } catch (const std::invalid_argument &ex) {
    rd.Fail(table, std::string(ex.what()));
  }
}

/// [environment.unsteady_flow] (SPEC §6.1): its period tF is the run's duration, its seed the
/// run's seed.
void UnsteadyFlowRule(const Keys &, const Reader &, Scenario &s) {
  s.plant.env.unsteady.period_s = s.duration_s;
  s.plant.env.unsteady.seed = s.seed;
}

/// Trim ballast (SPEC §6.3): the plant computes it at construction; the controller's model
/// carries the same physical ballast, mass and point (computed with the actual density, the
/// trim payload and the metacentric height; never the plant's ballast_error_m), so under a
/// density error its model is, correctly, not neutral.
void TrimBallastRule(const Keys &k, const Reader &rd, Scenario &s) {
  plant::Ballast b;
  if (s.plant.env.trim) {
    try {
      b = plant::TrimBallast(s.plant);
    } catch (const std::invalid_argument &ex) {
      rd.Fail(k["environment.trim"].item, std::string(ex.what()));
    }
  }
  s.controller.arm.vehicle.ballast_kg = R(b.mass_kg);
  ToReal3(b.offset_m, s.controller.arm.vehicle.ballast_offset_m);
}

/// [[contact.obstacle]]: the list given replaces the plant's.
void ObstaclesRule(const Keys &k, const Reader &rd, Scenario &s) {
  std::vector<plant::CylinderObstacle> &obstacles = s.plant.contact.obstacles;
  if (k["contact.obstacle"].item) obstacles.clear();
  for (const Element &el : k.Elements("contact.obstacle")) {
    if (obstacles.size() == kMaxObstacles)
      rd.Fail(k["contact.obstacle"].item, "more than " + std::to_string(kMaxObstacles) +
                                              " obstacles (the run log's scene message holds at most that many)");
    plant::CylinderObstacle cyl;
    ApplyElement(el, &cyl);
    if (cyl.name.size() > kMaxObstacleName)
      rd.Fail(el.fields.at("name").item, "obstacle name of " + std::to_string(cyl.name.size()) +
                                             " bytes (expected at most " + std::to_string(kMaxObstacleName) + ")");
    obstacles.push_back(cyl);
  }
}

/// One [[faults.thruster]]: a thruster of the plant; stuck values only for a stuck fault and
/// its drive's quantity; efficiency only for an efficiency fault (docs/FAULTS.md).
ThrusterFault ThrusterFaultOf(const Element &el, const Reader &rd, const Scenario &s) {
  const std::string n = std::to_string(s.plant.thrusters.size());
  const Item &j = el.fields.at("thruster").item;
  if (!j) rd.Fail(j, "missing (expected the thruster number 1.." + n + ")");
  const std::int64_t jj = rd.Int(j, 1);
  if (jj < 1 || jj > static_cast<std::int64_t>(s.plant.thrusters.size()))
    rd.Fail(j, "got " + std::to_string(jj) + " (expected 1.." + n + ")");
  ThrusterFault tf;
  tf.thruster = static_cast<int>(jj);
  ApplyElement(el, &tf);
  const bool stuck = tf.mode == ThrusterFault::Mode::kStuck;
  const bool voltage_drive = s.controller.drive == UVMS_DRIVE_VOLTAGE;
  const Item &sv = el.fields.at("stuck_voltage_V").item, &sc = el.fields.at("stuck_current_A").item;
  if (sv && !stuck) rd.Fail(sv, "only for mode = \"stuck\" (expected no stuck_voltage_V here)");
  if (sv && !voltage_drive)
    rd.Fail(sv, "only with thrusters.drive = \"voltage\" (the current drive's stuck stage holds "
                "stuck_current_A)");
  if (sc && !stuck) rd.Fail(sc, "only for mode = \"stuck\" (expected no stuck_current_A here)");
  if (sc && voltage_drive)
    rd.Fail(sc, "only with thrusters.drive = \"current\" (the voltage drive's stuck stage holds "
                "stuck_voltage_V)");
  const KeyRead &ef = el.fields.at("efficiency");
  const bool efficiency_mode = tf.mode == ThrusterFault::Mode::kEfficiency;
  if (ef.item && !efficiency_mode)
    rd.Fail(ef.item, "only for mode = \"efficiency\" (expected no efficiency here)");
  if (!ef.item && efficiency_mode) tf.efficiency = DefaultJson(*ef.row).get<double>();
  return tf;
}

/// [[faults.thruster]], in order.
void ThrusterFaultsRule(const Keys &k, const Reader &rd, Scenario &s) {
  for (const Element &el : k.Elements("faults.thruster"))
    s.faults.thrusters.push_back(ThrusterFaultOf(el, rd, s));
}

/// [faults.link]: at most one fault per message, so the four rates add up to at most 1.
void LinkFaultsRule(const Keys &k, const Reader &rd, Scenario &s) {
  const LinkFaults &lf = s.faults.link;
  const double total = lf.drop_rate + lf.delay_rate + lf.duplicate_rate + lf.corrupt_rate;
  if (!(total > 1.0)) return;
  const Item *last = nullptr;
  for (const char *key : {"faults.link.drop_rate", "faults.link.delay_rate",
                          "faults.link.duplicate_rate", "faults.link.corrupt_rate"})
    if (k[key].item) last = &k[key].item;
  rd.Fail(*last, "the four rates add up to " + Num(total) + " (expected at most 1)");
}

using Rule = void (*)(const Keys &, const Reader &, Scenario &);

/// The cross-key rules, in the order they apply (each may use what the ones before set).
constexpr Rule kRules[] = {RunDurationRule,    RunNameRule,      RealtimeFactorRule,
                           LimitSquaresRule,   MotorSetRule,     ThrustersRule,   ThrustLimitsRule,
                           ThrusterTypesRule,
                           VehicleInertiaRule, AddedMassRule,    VehicleAddedMassRule,
                           ArmLinksRule,
                           ArmRule,
                           VehicleAttitudeRule, TrajectoryRule,  UserArmTargetRule,
                           DensityRule,
                           GravityAndTrimRule, ModelAngleOfAttackRule, CoeffTableRule,
                           UnsteadyFlowRule,   TrimBallastRule,  ObstaclesRule,
                           ThrusterFaultsRule, LinkFaultsRule};

// ---- step 6: the libraries' own validation ---------------------------------------------------

void CheckWithTheLibraries(Reader &rd, const Scenario &s) {
  auto ctrl = std::make_unique<uvms_ctrl_t>();
  const uvms_status_t st = uvms_ctrl_init(ctrl.get(), &s.controller);
  if (st != UVMS_OK) {
    const char *section = SectionOf(ctrl->config_error);
    const Item it = rd.Get(rd.Root(), section);
    throw ScenarioError(Where(it.node, s.source) + ": key \"" + section +
                        "\": the controller rejected its configuration: part \"" +
                        uvms_cfg_field_str(ctrl->config_error) + "\" (uvms_ctrl_init: " +
                        uvms_status_str(st) + "; expected values the firmware accepts)");
  }
  try {
    plant::Plant plant(s.plant);
    plant.Reset(s.initial);
  } catch (const std::exception &ex) {
    throw ScenarioError(s.source + ": the plant rejected its configuration: " + ex.what());
  }
}

}  // namespace

std::array<double, 7> PaperThetaStartDeg() { return JointTableDeg(UVMS_JOINT_TABLE_START); }

bool PaperThetaFinalDeg(uvms_reference_t reference, double payload_kg, std::array<double, 7> *deg) {
  if (reference == UVMS_REF_VEHICLE) {
    if (deg != nullptr) *deg = JointTableDeg(UVMS_JOINT_TABLE_VEHICLE);
    return true;
  }
  for (int c = UVMS_JOINT_TABLE_BARY_0KG; c < UVMS_JOINT_TABLE_COLUMNS; ++c) {
    const auto column = static_cast<uvms_joint_table_column_t>(c);
    if (static_cast<double>(uvms_joint_table_payload_kg(column)) == payload_kg) {
      if (deg != nullptr) *deg = JointTableDeg(column);
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
  const toml::table root = ParseDocument(toml_text, source, overrides);
  Reader rd(root, source);
  const Keys keys(rd);
  rd.CheckUnknown();  // a misspelt key is named before any rule judges the keys it was meant for
  const int case_number = CaseNumber(rd, keys["control.case"].item);
  const uvms_switches_t sw = SwitchesRule(keys, rd, case_number);
  // The controller starts from SPEC's configuration of the case (case IV's for explicit
  // switches, which are then replaced), the plant from the paper's, the harness from its own.
  Scenario s = PaperScenario(case_number);
  s.source = source;
  s.overrides = overrides;
  s.name = Stem(source);
  s.case_number = case_number;
  s.controller.switches = sw;
  s.controller.cart.reference = sw.position_reference;  // SPEC §8: the line refers to the held point
  ApplyTableKeys(keys, s);
  for (const Rule rule : kRules) rule(keys, rd, s);
  CheckWithTheLibraries(rd, s);
  return s;
}

Scenario LoadScenario(const std::string &path, const std::vector<std::string> &overrides) {
  return ParseScenario(ReadTomlFile(path), path, overrides);
}

}  // namespace uvms::sil
