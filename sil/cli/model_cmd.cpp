// SPDX-License-Identifier: Apache-2.0
// model_cmd.cpp: `uvms model`, the arm model of the firmware library as a host command
// (SPEC §2–4, §7.1). See model_cmd.hpp for the structure and ModelHelpText() for the schemas.
#include "cli/model_cmd.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <iterator>
#include <set>
#include <sstream>
#include <utility>

#include "uvms/dynamics.h"
#include "uvms/linalg.h"

namespace uvms::cli {
namespace {

using json = nlohmann::json;

constexpr const char *kErrorPrefix = "uvms model: error: ";
// uvms_quat_to_rot rejects quaternions below this norm (linalg.h); checked first here so that
// the error names the field.
constexpr double kMinQuaternionNorm = 1e-6;

// Where a JSON value came from, for error messages: stdin ("field ...") or a config file
// ("cfg.json: key ...").
struct Origin {
  std::string prefix;  // prepended to every message: "" for stdin, "<file>: " for a config
  const char *noun;    // "field" or "key"
  const char *whole;   // the top-level value: "the input" or "the config"
};

[[noreturn]] void Fail(const Origin &o, const std::string &message) {
  throw InputError(o.prefix + message);
}

std::string Quoted(const std::string &s) { return "\"" + s + "\""; }

std::string Child(const std::string &parent, const std::string &key) {
  return parent.empty() ? key : parent + "." + key;
}

std::string Indexed(const std::string &parent, std::size_t i) {
  return parent + "[" + std::to_string(i) + "]";
}

// "field "vehicle.position_m"" / "key "links[2].mass_kg"".
std::string Name(const Origin &o, const std::string &path) {
  return std::string(o.noun) + " " + Quoted(path);
}

// x in the shortest of %.15g / %.17g that reads back to x ("-0.5", "1e+39").
std::string FormatDouble(double x) {
  for (const int digits : {15, 17}) {
    std::ostringstream s;
    s.precision(digits);
    s << x;
    if (digits == 17 || std::strtod(s.str().c_str(), nullptr) == x) return s.str();
  }
  return {};
}

// One JSON object with a fixed set of allowed keys: unknown keys are rejected on construction
// (the likeliest cause is a typo, so that error wins over "missing"); Require / Find look keys up.
class ObjectFields {
 public:
  ObjectFields(const Origin &origin, const json &value, std::string path,
               std::initializer_list<const char *> allowed)
      : origin_(origin), value_(value), path_(std::move(path)) {
    if (!value_.is_object()) {
      Fail(origin_, (path_.empty() ? std::string(origin_.whole) : Name(origin_, path_)) +
                        " must be a JSON object, got " + value_.type_name());
    }
    for (const auto &item : value_.items()) {
      bool known = false;
      for (const char *k : allowed) known = known || item.key() == k;
      if (!known) Fail(origin_, "unknown " + Name(origin_, Child(path_, item.key())));
    }
  }

  const json &Require(const char *key) const {
    const auto it = value_.find(key);
    if (it == value_.end()) Fail(origin_, "missing " + Name(origin_, Child(path_, key)));
    return *it;
  }

  const json *Find(const char *key) const {
    const auto it = value_.find(key);
    return it == value_.end() ? nullptr : &*it;
  }

  const Origin &origin() const { return origin_; }
  std::string PathOf(const char *key) const { return Child(path_, key); }

 private:
  const Origin &origin_;
  const json &value_;
  std::string path_;
};

// A finite JSON number that is also finite in the controller's real type (float overflows
// above 3.4e38).
uvms_real_t ReadReal(const Origin &o, const std::string &path, const json &j) {
  if (!j.is_number()) Fail(o, Name(o, path) + ": expected a number, got " + j.type_name());
  const double x = j.get<double>();
  if (!std::isfinite(x)) Fail(o, Name(o, path) + ": not a finite number");
  const auto r = static_cast<uvms_real_t>(x);
  if (!std::isfinite(r)) {
    Fail(o, Name(o, path) + ": " + FormatDouble(x) + " is out of range of the controller's " +
                "real type (" + (UVMS_REAL_IS_FLOAT ? "float" : "double") + ")");
  }
  return r;
}

// An array of exactly n numbers; raw (optional) receives the values as parsed, in double.
void ReadRealArray(const Origin &o, const std::string &path, const json &j, std::size_t n,
                   uvms_real_t *out, double *raw = nullptr, const char *what = "") {
  if (!j.is_array()) {
    Fail(o, Name(o, path) + ": expected an array of " + std::to_string(n) + " numbers, got " +
                j.type_name());
  }
  if (j.size() != n) {
    Fail(o, Name(o, path) + ": expected " + std::to_string(n) + " elements" + what + ", got " +
                std::to_string(j.size()));
  }
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = ReadReal(o, Indexed(path, i), j[i]);
    if (raw != nullptr) raw[i] = j[i].get<double>();
  }
}

void ReadNonNegative(const ObjectFields &f, const char *key, uvms_real_t *out) {
  const std::string path = f.PathOf(key);
  *out = ReadReal(f.origin(), path, f.Require(key));
  if (*out < uvms_real_t(0)) {
    Fail(f.origin(), Name(f.origin(), path) + ": must be >= 0, got " + FormatDouble(double(*out)));
  }
}

// Config overrides: absent keys leave the parameter as it is.
void OverrideReal(const ObjectFields &f, const char *key, uvms_real_t *out) {
  if (const json *j = f.Find(key)) *out = ReadReal(f.origin(), f.PathOf(key), *j);
}

void OverrideArray(const ObjectFields &f, const char *key, std::size_t n, uvms_real_t *out) {
  if (const json *j = f.Find(key)) ReadRealArray(f.origin(), f.PathOf(key), *j, n, out);
}

void ApplyLinkOverrides(const Origin &o, const json &entry, const std::string &path,
                        uvms_link_params_t *link) {
  const ObjectFields f(o, entry, path,
                       {"alpha_rad", "a_m", "d_m", "placement_m", "placement_rotvec_rad",
                        "mass_kg", "com_m", "inertia_kg_m2", "inertia_products_kg_m2",
                        "diameter_m", "drag_coeff"});
  OverrideReal(f, "alpha_rad", &link->alpha_rad);
  OverrideReal(f, "a_m", &link->a_m);
  OverrideReal(f, "d_m", &link->d_m);
  OverrideArray(f, "placement_m", 3, link->placement_m);
  OverrideArray(f, "placement_rotvec_rad", 3, link->placement_rotvec_rad);
  OverrideReal(f, "mass_kg", &link->mass_kg);
  OverrideArray(f, "com_m", 3, link->com_m);
  OverrideArray(f, "inertia_kg_m2", 3, link->inertia_kg_m2);
  OverrideArray(f, "inertia_products_kg_m2", 3, link->inertia_products_kg_m2);
  OverrideReal(f, "diameter_m", &link->diameter_m);
  OverrideReal(f, "drag_coeff", &link->drag_coeff);
}

std::string ReadStream(std::istream &in, const std::string &source) {
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw InputError(source + ": read error");
  return text;
}

// The message of a nlohmann exception without its "[json.exception.parse_error.101] " tag.
std::string JsonErrorDetail(const char *what) {
  const std::string s(what);
  const auto close = s.find("] ");
  return (s.rfind("[json.exception.", 0) == 0 && close != std::string::npos) ? s.substr(close + 2)
                                                                               : s;
}

// Duplicate keys, seen while parsing (json::parse's callback: nlohmann::json itself keeps the
// last value of a key given twice, silently). Each open object or array is a frame: its path,
// the keys seen (an object) or the index of the next element (an array). Throws InputError
// naming the key's path ("vehicle.mass_kg", "links[1].mass_kg").
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(const std::string &source) : source_(source) {}

  bool operator()(int /*depth*/, json::parse_event_t event, json &parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        stack_.push_back({event == json::parse_event_t::array_start, 0, {}, ChildPath()});
        break;
      case json::parse_event_t::key: {
        Frame &f = stack_.back();
        key_ = parsed.get<std::string>();
        if (!f.keys.insert(key_).second)
          throw InputError(source_ + ": duplicate key " + Quoted(Child(f.path, key_)) +
                           ": each key may appear once in an object");
        break;
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        stack_.pop_back();
        ElementDone();
        break;
      case json::parse_event_t::value: ElementDone(); break;
    }
    return true;  // keep every value: this only watches
  }

 private:
  struct Frame {
    bool array;
    std::size_t index;           // an array's next element
    std::set<std::string> keys;  // an object's keys so far
    std::string path;
  };

  // The path of the value about to start: the top level, an array's element, an object's member.
  std::string ChildPath() const {
    if (stack_.empty()) return "";
    const Frame &f = stack_.back();
    return f.array ? Indexed(f.path, f.index) : Child(f.path, key_);
  }

  void ElementDone() {
    if (!stack_.empty() && stack_.back().array) ++stack_.back().index;
  }

  const std::string &source_;
  std::vector<Frame> stack_;
  std::string key_;  // the last key read: names the value that follows it
};

std::string OneLine(std::string s) {
  for (char &c : s) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  return s;
}

nlohmann::ordered_json Vec(const uvms_real_t *v, std::size_t n) {
  auto a = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < n; ++i) a.push_back(static_cast<double>(v[i]));
  return a;
}

bool AllFinite(const uvms_real_t *v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

// Every value ModelResultToJson prints is finite (JSON has no NaN; nlohmann would print null).
bool ResultIsFinite(const ModelResult &r) {
  const uvms_arm_data_t &d = r.rnea;
  bool ok = AllFinite(d.ee_m, 3) && AllFinite(d.barycenter_m, 3) && AllFinite(d.p_m[0], 3) &&
            AllFinite(d.f_N[1], 3) && AllFinite(d.n_Nm[1], 3) && AllFinite(d.drag_N[0], 3) &&
            AllFinite(&d.tau_Nm[1], r.num_joints);
  for (std::size_t i = 1; i <= r.num_joints; ++i) ok = ok && AllFinite(d.com_m[i], 3);
  for (const uvms_feedforward_t *ff : {&r.ff_vehicle, &r.ff_barycenter}) {
    ok = ok && AllFinite(ff->moment_att_Nm, 3) && AllFinite(ff->force_vehicle_N, 3) &&
         AllFinite(ff->force_barycenter_N, 3) && AllFinite(ff->base_accel_m_s2, 3);
  }
  return ok;
}

void Check(uvms_status_t st, const char *function) {
  if (st != UVMS_OK) {
    throw InputError(std::string(function) + " failed: " + uvms_status_str(st));
  }
}

}  // namespace

const char *ModelUsageLine() {
  return "usage: uvms model [--config FILE] < input.json > output.json  (see uvms model --help)";
}

const std::string &ModelHelpText() {
  static const std::string text = R"(usage: uvms model [--config FILE] < input.json > output.json

Evaluate the controller's arm model (the firmware library: Newton-Euler with hydrodynamics,
SPEC section 4, and the feedforward wrenches of SPEC section 7.1) at one state. Reads one JSON
object on stdin, writes one JSON object (one line) on stdout. Numbers are printed so that they
read back to the same double (shortest round-trip form, up to 17 significant digits).

Options:
  --config FILE   JSON file of parameter overrides (schema below). Without it the model
                  uses the paper's parameters (SPEC section 3).
  -h, --help      print this help and exit

Frames and units: SI; inertial frame I, z up; R0 maps vehicle to inertial coordinates. Every
vector below, input and output, is in inertial coordinates unless it says otherwise.

Input (every field required; unknown fields and a field given twice are errors):
  {"vehicle": {
     "position_m": [3]                  r0, the vehicle CoM [m]
     "quaternion_wxyz": [4]             attitude (w, x, y, z), vehicle -> inertial; normalised
                                        by the model (norm must be >= 1e-6)
     "velocity_m_s": [3]                v0, velocity of the vehicle CoM [m/s]
     "angular_velocity_rad_s": [3]      w0 [rad/s]
     "acceleration_m_s2": [3]           dv0/dt, acceleration of the vehicle CoM [m/s^2]
     "angular_acceleration_rad_s2": [3] dw0/dt [rad/s^2]},
   "joints": {
     "position_rad": [N]                joint angles theta_1..theta_N [rad]
     "velocity_rad_s": [N]              joint rates [rad/s]
     "acceleration_rad_s2": [N]},       joint accelerations [rad/s^2]
   "density_kg_m3": number >= 0         fluid density rho [kg/m^3]
   "flow_m_s": [3]                      steady fluid velocity v_inf [m/s]
   "gravity_m_s2": [3]                  gravity vector g, e.g. [0, 0, -9.81] [m/s^2]
   "payload_kg": number >= 0            point payload at the EE (+ payload_offset_m) [kg]
   "angle_of_attack": true|false}       link drag coefficient C_D0L*sin^2(alpha) [21] (true)
                                        or C_D0L (false)
  N is the number of joints: 7, or the length of "links" in the config.

Output (inertial coordinates; positions [m], forces [N], moments [N*m]):
  From Newton-Euler (uvms_arm_rnea) at the input state AND the input accelerations:
  "ee_position_m": [3]        end effector, the origin of frame N
  "barycenter_m": [3]         p_cm of vehicle + links + payload [5]
  "base_point_m": [3]         manipulator base point p_0* = r0 + R0*s0
  "link_com_m": [N][3]        link centers of mass c_1..c_N
  "base_force_N": [3]         f1: force the vehicle exerts on link 1 [24] (the arm pushes
                              the vehicle with -f1)
  "base_moment_Nm": [3]       n1: moment the vehicle exerts on link 1, about base_point_m [25]
  "joint_torque_Nm": [N]      tau_i = n_i . z_i [29]
  "vehicle_drag_N": [3]       D0 = -1/2 rho C_D0 A0 |w0| w0, w0 = v0 - v_inf, on the vehicle
  "feedforward": {            SPEC 7.1 wrenches (uvms_feedforward). They IGNORE the input
                              accelerations: as the controller does (SPEC 7), the model takes
                              dw0/dt = 0, and dv0/dt = 0 under the vehicle reference or the
                              value that leaves the barycenter unaccelerated by the arm under
                              the barycenter reference. Moments about the vehicle CoM.
    "attitude_moment_Nm": [3]            N_r = n1 + (R0*s0) x f1 + (R0*c_b) x (rho*V0*g)
                                         - (R0*b_b) x (ballast*g), vehicle reference
    "vehicle_force_N": [3]               F_r,0 = f1 - D0 - (m0 + ballast)*g + rho*V0*g [31],
                                         vehicle reference
    "barycenter_force_N": [3]            F_r,cm = sum over vehicle, links, payload of
                                         (-D_k - m_k*g + rho*V_k*g) [32], barycenter reference
    "attitude_moment_barycenter_Nm": [3] N_r under the barycenter reference
    "barycenter_accel_m_s2": [3]}        dv0/dt the barycenter reference assumes [m/s^2]

Config file (every key optional; unknown keys and a key given twice are errors; frames as in
SPEC section 2):
  {"vehicle": {"mass_kg", "volume_m3", "frontal_area_m2", "drag_coeff",
               "inertia_kg_m2": [3] (diagonal about the CoM, vehicle axes),
               "cob_m": [3] (center of buoyancy from the CoM, vehicle frame),
               "base_offset_m": [3] (s0, vehicle frame), "base_rotvec_rad": [3] (the
               arm base axes' rotation from the vehicle's), "ballast_kg" (weight only),
               "linear_damping", "quadratic_damping": [6] (Fossen, docs/MODEL.md 3.2),
               "ballast_offset_m": [3] (the ballast's point from the CoM, vehicle frame)},
   "payload_offset_m": [3]   (EE -> payload, frame N),
   "links": [{"alpha_rad", "a_m", "d_m", "placement_m": [3], "placement_rotvec_rad": [3]
              (a general link's fixed placement after its DH transform, docs/MODEL.md 2),
              "mass_kg", "com_m": [3] (frame i),
              "inertia_kg_m2": [3] (diagonal about the CoM, frame i),
              "inertia_products_kg_m2": [3] (I_xy, I_xz, I_yz of that tensor),
              "diameter_m", "drag_coeff"}, ...],
   "added_mass_coeff": [36]} (unscaled Ma0, row-major 6x6, SPEC 3.3)
  The length of "links" (1..7) sets N; each entry overrides the paper's link of the same
  index, key by key. Parameters the firmware rejects are reported with its status name
  (uvms_arm_model_init).

Exit status: 0 success; 1 invalid JSON, bad or missing field, bad config, or a firmware
error (one line on stderr naming the cause); 2 usage error.
)";
  return text;
}

ModelOptions ParseModelArgs(const std::vector<std::string> &args) {
  ModelOptions opt;
  bool have_config = false;
  auto set_config = [&](const std::string &path) {
    if (have_config) throw UsageError("--config given more than once");
    if (path.empty()) throw UsageError("--config needs a non-empty FILE");
    have_config = true;
    opt.config_path = path;
  };
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string &a = args[i];
    if (a == "-h" || a == "--help") {
      opt.help = true;
    } else if (a == "--config") {
      if (i + 1 >= args.size()) throw UsageError("--config needs a FILE argument");
      set_config(args[++i]);
    } else if (a.rfind("--config=", 0) == 0) {
      set_config(a.substr(std::strlen("--config=")));
    } else if (!a.empty() && a[0] == '-') {
      throw UsageError("unknown option " + Quoted(a));
    } else {
      throw UsageError("unexpected argument " + Quoted(a) + " (the input is read from stdin)");
    }
  }
  return opt;
}

nlohmann::json ParseJsonText(const std::string &text, const std::string &source) {
  DuplicateKeyCheck duplicates(source);
  try {
    // strict: trailing content after the value is an error; a key given twice too
    return json::parse(text, [&](int depth, json::parse_event_t event, json &parsed) {
      return duplicates(depth, event, parsed);
    });
  } catch (const json::exception &e) {
    throw InputError(source + ": invalid JSON: " + JsonErrorDetail(e.what()));
  }
}

void ApplyModelConfig(const nlohmann::json &config, const std::string &source,
                      uvms_arm_params_t *params) {
  const Origin o{source + ": ", "key", "the config"};
  const ObjectFields top(o, config, "", {"vehicle", "payload_offset_m", "links", "added_mass_coeff"});
  if (const json *v = top.Find("vehicle")) {
    const ObjectFields f(o, *v, "vehicle",
                         {"mass_kg", "volume_m3", "frontal_area_m2", "drag_coeff",
                          "inertia_kg_m2", "cob_m", "base_offset_m", "base_rotvec_rad",
                          "ballast_kg", "ballast_offset_m", "linear_damping",
                          "quadratic_damping"});
    uvms_vehicle_params_t &veh = params->vehicle;
    OverrideReal(f, "mass_kg", &veh.mass_kg);
    OverrideReal(f, "volume_m3", &veh.volume_m3);
    OverrideReal(f, "frontal_area_m2", &veh.frontal_area_m2);
    OverrideReal(f, "drag_coeff", &veh.drag_coeff);
    OverrideArray(f, "inertia_kg_m2", 3, veh.inertia_kg_m2);
    OverrideArray(f, "cob_m", 3, veh.cob_m);
    OverrideArray(f, "base_offset_m", 3, veh.base_offset_m);
    OverrideArray(f, "base_rotvec_rad", 3, veh.base_rotvec_rad);
    OverrideArray(f, "linear_damping", 6, veh.linear_damping);
    OverrideArray(f, "quadratic_damping", 6, veh.quadratic_damping);
    OverrideReal(f, "ballast_kg", &veh.ballast_kg);
    OverrideArray(f, "ballast_offset_m", 3, veh.ballast_offset_m);
  }
  OverrideArray(top, "payload_offset_m", 3, params->payload_offset_m);
  if (const json *links = top.Find("links")) {
    if (!links->is_array()) {
      Fail(o, Name(o, "links") + ": expected an array of link objects, got " + links->type_name());
    }
    if (links->size() > UVMS_MAX_JOINTS) {
      Fail(o, Name(o, "links") + ": " + std::to_string(links->size()) + " entries, at most " +
                  std::to_string(UVMS_MAX_JOINTS) + " (UVMS_MAX_JOINTS); " +
                  Quoted(Indexed("links", UVMS_MAX_JOINTS)) + " is beyond the arm");
    }
    params->num_joints = links->size();  // 0 is left to uvms_arm_model_init (UVMS_ERR_SIZE)
    for (std::size_t i = 0; i < links->size(); ++i) {
      ApplyLinkOverrides(o, (*links)[i], Indexed("links", i), &params->link[i]);
    }
  }
  OverrideArray(top, "added_mass_coeff", 36, params->added_mass_coeff);
}

void ValidateModelParams(const uvms_arm_params_t &params, const std::string &source) {
  uvms_arm_model_t model;
  const uvms_status_t st = uvms_arm_model_init(&params, &model);
  if (st != UVMS_OK) {
    throw InputError(source + ": invalid model parameters: " + uvms_status_str(st) +
                     " (uvms_arm_model_init)");
  }
}

uvms_arm_params_t LoadModelParams(const std::string &config_path) {
  uvms_arm_params_t params;
  uvms_arm_params_paper(&params);
  if (config_path.empty()) return params;
  std::ifstream file(config_path, std::ios::binary);
  if (!file) {
    throw InputError(config_path + ": cannot open config file: " + std::strerror(errno));
  }
  const json config = ParseJsonText(ReadStream(file, config_path), config_path);
  ApplyModelConfig(config, config_path, &params);
  ValidateModelParams(params, config_path);
  return params;
}

ModelInput ParseModelInput(const nlohmann::json &input, std::size_t num_joints) {
  if (num_joints < 1 || num_joints > UVMS_MAX_JOINTS) {
    throw std::invalid_argument("ParseModelInput: num_joints out of range");
  }
  const Origin o{"", "field", "the input"};
  ModelInput in;
  in.num_joints = num_joints;
  const ObjectFields top(o, input, "",
                         {"vehicle", "joints", "density_kg_m3", "flow_m_s", "gravity_m_s2",
                          "payload_kg", "angle_of_attack"});

  const ObjectFields veh(o, top.Require("vehicle"), "vehicle",
                         {"position_m", "quaternion_wxyz", "velocity_m_s",
                          "angular_velocity_rad_s", "acceleration_m_s2",
                          "angular_acceleration_rad_s2"});
  uvms_base_state_t &b = in.base;
  ReadRealArray(o, veh.PathOf("position_m"), veh.Require("position_m"), 3, b.position_m);
  uvms_real_t q[4];
  double q_raw[4];
  const std::string q_path = veh.PathOf("quaternion_wxyz");
  ReadRealArray(o, q_path, veh.Require("quaternion_wxyz"), 4, q, q_raw);
  const double q_norm = std::sqrt(q_raw[0] * q_raw[0] + q_raw[1] * q_raw[1] +
                                  q_raw[2] * q_raw[2] + q_raw[3] * q_raw[3]);
  if (!(q_norm >= kMinQuaternionNorm)) {
    Fail(o, Name(o, q_path) + ": norm " + FormatDouble(q_norm) + " is below 1e-6");
  }
  const uvms_status_t st = uvms_quat_to_rot(q, b.R0);  // normalises q
  if (st != UVMS_OK) Fail(o, Name(o, q_path) + ": " + uvms_status_str(st) + " (uvms_quat_to_rot)");
  ReadRealArray(o, veh.PathOf("velocity_m_s"), veh.Require("velocity_m_s"), 3, b.velocity_m_s);
  ReadRealArray(o, veh.PathOf("angular_velocity_rad_s"), veh.Require("angular_velocity_rad_s"),
                3, b.omega_rad_s);
  ReadRealArray(o, veh.PathOf("acceleration_m_s2"), veh.Require("acceleration_m_s2"), 3,
                b.accel_m_s2);
  ReadRealArray(o, veh.PathOf("angular_acceleration_rad_s2"),
                veh.Require("angular_acceleration_rad_s2"), 3, b.alpha_rad_s2);

  const ObjectFields joints(o, top.Require("joints"), "joints",
                            {"position_rad", "velocity_rad_s", "acceleration_rad_s2"});
  const char *per_joint = " (one per joint)";
  ReadRealArray(o, joints.PathOf("position_rad"), joints.Require("position_rad"), num_joints,
                in.q_rad, nullptr, per_joint);
  ReadRealArray(o, joints.PathOf("velocity_rad_s"), joints.Require("velocity_rad_s"), num_joints,
                in.qd_rad_s, nullptr, per_joint);
  ReadRealArray(o, joints.PathOf("acceleration_rad_s2"), joints.Require("acceleration_rad_s2"),
                num_joints, in.qdd_rad_s2, nullptr, per_joint);

  ReadNonNegative(top, "density_kg_m3", &in.fluid.density_kg_m3);
  ReadRealArray(o, "flow_m_s", top.Require("flow_m_s"), 3, in.fluid.flow_m_s);
  ReadRealArray(o, "gravity_m_s2", top.Require("gravity_m_s2"), 3, in.fluid.gravity_m_s2);
  ReadNonNegative(top, "payload_kg", &in.payload_kg);
  const json &aoa = top.Require("angle_of_attack");
  if (!aoa.is_boolean()) {
    Fail(o, Name(o, "angle_of_attack") + ": expected true or false, got " + aoa.type_name());
  }
  in.fluid.angle_of_attack = aoa.get<bool>() ? 1 : 0;
  return in;
}

ModelResult ComputeModel(const uvms_arm_params_t &params, const ModelInput &input) {
  if (input.num_joints != params.num_joints) {
    throw std::invalid_argument("ComputeModel: input and parameters differ in num_joints");
  }
  uvms_arm_params_t p = params;
  p.payload_kg = input.payload_kg;
  uvms_arm_model_t model;
  const uvms_status_t st = uvms_arm_model_init(&p, &model);
  if (st != UVMS_OK) {
    throw InputError(std::string("invalid model parameters: ") + uvms_status_str(st) +
                     " (uvms_arm_model_init)");
  }
  ModelResult r;
  r.num_joints = p.num_joints;
  Check(uvms_arm_rnea(&model, &r.rnea, &input.base, &input.fluid, input.q_rad, input.qd_rad_s,
                      input.qdd_rad_s2),
        "uvms_arm_rnea");
  uvms_arm_data_t scratch;
  Check(uvms_feedforward(&model, &scratch, &input.fluid, UVMS_REF_VEHICLE, &input.base,
                         input.q_rad, input.qd_rad_s, input.qdd_rad_s2, &r.ff_vehicle),
        "uvms_feedforward (vehicle reference)");
  Check(uvms_feedforward(&model, &scratch, &input.fluid, UVMS_REF_BARYCENTER, &input.base,
                         input.q_rad, input.qd_rad_s, input.qdd_rad_s2, &r.ff_barycenter),
        "uvms_feedforward (barycenter reference)");
  if (!ResultIsFinite(r)) {
    throw InputError("the model's result is not finite (inputs beyond the model's range)");
  }
  return r;
}

nlohmann::ordered_json ModelResultToJson(const ModelResult &r) {
  const uvms_arm_data_t &d = r.rnea;
  const std::size_t n = r.num_joints;
  nlohmann::ordered_json out;
  out["ee_position_m"] = Vec(d.ee_m, 3);
  out["barycenter_m"] = Vec(d.barycenter_m, 3);
  out["base_point_m"] = Vec(d.p_m[0], 3);
  auto coms = nlohmann::ordered_json::array();
  for (std::size_t i = 1; i <= n; ++i) coms.push_back(Vec(d.com_m[i], 3));
  out["link_com_m"] = coms;
  out["base_force_N"] = Vec(d.f_N[1], 3);
  out["base_moment_Nm"] = Vec(d.n_Nm[1], 3);
  out["joint_torque_Nm"] = Vec(&d.tau_Nm[1], n);
  out["vehicle_drag_N"] = Vec(d.drag_N[0], 3);
  nlohmann::ordered_json ff;
  ff["attitude_moment_Nm"] = Vec(r.ff_vehicle.moment_att_Nm, 3);
  ff["vehicle_force_N"] = Vec(r.ff_vehicle.force_vehicle_N, 3);
  ff["barycenter_force_N"] = Vec(r.ff_barycenter.force_barycenter_N, 3);
  ff["attitude_moment_barycenter_Nm"] = Vec(r.ff_barycenter.moment_att_Nm, 3);
  ff["barycenter_accel_m_s2"] = Vec(r.ff_barycenter.base_accel_m_s2, 3);
  out["feedforward"] = ff;
  return out;
}

int RunModelCli(const std::vector<std::string> &args, std::istream &in, std::ostream &out,
                std::ostream &err) {
  ModelOptions opt;
  try {
    opt = ParseModelArgs(args);
  } catch (const UsageError &e) {
    err << kErrorPrefix << OneLine(e.what()) << '\n' << ModelUsageLine() << '\n';
    return kExitUsage;
  }
  if (opt.help) {
    out << ModelHelpText();
    return kExitOk;
  }
  try {
    // Parameters first: a bad config is reported before stdin is read.
    const uvms_arm_params_t params = LoadModelParams(opt.config_path);
    const json j = ParseJsonText(ReadStream(in, "stdin"), "stdin");
    const ModelInput input = ParseModelInput(j, params.num_joints);
    const ModelResult result = ComputeModel(params, input);
    out << ModelResultToJson(result).dump() << '\n' << std::flush;
    if (!out) throw InputError("cannot write the result to stdout");
  } catch (const std::exception &e) {  // InputError, and anything unexpected (bad_alloc)
    err << kErrorPrefix << OneLine(e.what()) << '\n';
    return kExitBadInput;
  }
  return kExitOk;
}

}  // namespace uvms::cli
