// SPDX-License-Identifier: Apache-2.0
// scenario_reader.cpp: the TOML side of the scenario reader (scenario_reader.hpp).
#include "scenario/scenario_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <utility>

#include "scenario/override_key.hpp"
#include "scenario/toml_bounds.hpp"

namespace uvms::sil {

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

std::string Where(const toml::node *n, const std::string &fallback) {
  if (n == nullptr) return fallback;
  const toml::source_region &r = n->source();
  if (!r.path || r.path->empty()) return fallback;
  if (r.path->rfind("--set ", 0) == 0) return *r.path;
  return *r.path + ":" + std::to_string(r.begin.line);
}

std::string Join(const std::vector<std::string> &v) {
  std::string s;
  for (const auto &x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

std::string Stem(const std::string &source) {
  const std::string stem = std::filesystem::path(source).stem().string();
  return stem.empty() ? source : stem;
}

// ---- input bounds -----------------------------------------------------------------------------

void CheckTomlBounds(std::string_view text, const std::string &source) {
  const std::string err = TomlBoundsError(text, source);
  if (!err.empty()) throw ScenarioError(err);
}

std::string ReadTomlFile(const std::string &path) {
  std::string bytes, err;
  if (!ReadBoundedFile(path, &bytes, &err)) throw ScenarioError(err);
  return bytes;
}

// ---- the document and its overrides ---------------------------------------------------------

namespace {

bool IsBareKey(const std::string &s) {
  if (s.empty()) return false;
  return std::all_of(s.begin(), s.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
}

std::string Trim(const std::string &s) { return TrimBlanks(s); }  // override_key.hpp

/// The dotted parts of an override's key, each a bare key.
std::vector<std::string> OverrideKeyParts(const std::string &key, const std::string &where) {
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
  return parts;
}

/// Put one "section.key=value" override into the tree.
void ApplyOverride(toml::table &root, const std::string &text) {
  const std::string where = "--set " + text;
  if (text.find_first_of(std::string("\n\r\0", 3)) != std::string::npos)
    throw ScenarioError("--set " + Trim(text.substr(0, text.find_first_of(std::string("=\n\r\0", 4)))) +
                        "=...: a value with a line break or NUL byte (key \"" +
                        Trim(text.substr(0, text.find('='))) + "\"; expected one line)");
  CheckTomlBounds(text, where);
  const auto eq = text.find('=');
  if (eq == std::string::npos)
    throw ScenarioError(where + ": expected section.key=value (value in TOML syntax)");
  const std::string key = Trim(text.substr(0, eq));
  const std::string value = Trim(text.substr(eq + 1));
  const std::vector<std::string> parts = OverrideKeyParts(key, where);  // IsDottedKey, per part
  if (value.empty())
    throw ScenarioError(where + ": key \"" + key + "\": no value (expected section.key=value)");
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + value + "\n", where);
  } catch (const toml::parse_error &e) {
    // A bare word (VII, fast, earth) is a string without its quotes: show the quoted fix.
    if (value.find_first_of("\"'[{ ,=") == std::string::npos)
      throw ScenarioError(where + ": key \"" + key + "\": the value is not TOML: a string needs " +
                          "quotes, as in --set '" + key + "=\"" + value + "\"' (expected e.g. 10, " +
                          "1e-6, true, \"VII\", [1, 0, 0])");
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

}  // namespace

toml::table ParseDocument(std::string_view toml_text, const std::string &source,
                          const std::vector<std::string> &overrides) {
  CheckTomlBounds(toml_text, source);
  toml::table root;
  try {
    root = toml::parse(toml_text, source);
  } catch (const toml::parse_error &e) {
    throw ScenarioError(source + ":" + std::to_string(e.source().begin.line) +
                        ": TOML syntax error: " + std::string(e.description()));
  }
  for (const std::string &o : overrides) ApplyOverride(root, o);
  return root;
}

// ---- Reader ----------------------------------------------------------------------------------

void Reader::Fail(const Item &it, const std::string &what) const {
  const toml::node *at = it.node != nullptr ? it.node : it.anchor;
  throw ScenarioError(Where(at, source_) + ": key \"" + it.key + "\": " + what);
}

Item Reader::Get(const Sec &sec, const std::string &name) {
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

Sec Reader::Sub(const Sec &sec, const std::string &name) {
  const Item it = Get(sec, name);
  if (!it) return Sec{nullptr, it.key};
  if (!it.node->is_table()) Fail(it, "expected a table, got " + TypeName(*it.node));
  return Sec{it.node->as_table(), it.key};
}

std::vector<Sec> Reader::Tables(const Sec &sec, const std::string &name) {
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

double Reader::Real(const Item &it, double def) const {
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

std::int64_t Reader::Int(const Item &it, std::int64_t def) const {
  if (!it) return def;
  auto v = it.node->value_exact<int64_t>();
  if (!v) Fail(it, "expected an integer, got " + TypeName(*it.node));
  return *v;
}

bool Reader::Bool(const Item &it, bool def) const {
  if (!it) return def;
  auto v = it.node->value_exact<bool>();
  if (!v) Fail(it, "expected a boolean (true or false), got " + TypeName(*it.node));
  return *v;
}

std::string Reader::Str(const Item &it, const std::string &def) const {
  if (!it) return def;
  auto v = it.node->value_exact<std::string>();
  if (!v) Fail(it, "expected a string, got " + TypeName(*it.node));
  return *v;
}

std::vector<double> Reader::Reals(const Item &it, std::size_t n) const {
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

plant::Vec3 Reader::Vec(const Item &it, const plant::Vec3 &def) const {
  if (!it) return def;
  const auto v = Reals(it, 3);
  const plant::Vec3 out(v[0], v[1], v[2]);
  // Every vector's norm is taken somewhere (normalised directions, magnitudes): it must be finite.
  if (!std::isfinite(out.norm()))
    Fail(it, "has length " + Num(out.norm()) + " (expected a vector whose length is finite)");
  return out;
}

void Reader::CheckUnknown() const {
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

void Reader::Walk(const toml::table &t, const std::string &prefix, std::vector<Unknown> &found) const {
  for (auto &&[k, v] : t) {
    const std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (used_.count(&v) == 0) {
      found.push_back(Unknown{&v, &t, key});
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

// ---- one key of the table: type, then range rule --------------------------------------------

namespace {

using Kind = RangeRule::Kind;

/// A number's range rule (the messages the scenario tests pin). `shown` is x as written in
/// the message (integers in full).
void CheckNumber(const Reader &rd, const Item &it, double x, const std::string &shown,
                 const RangeRule &r) {
  switch (r.kind) {
    case Kind::kAtLeast:
    case Kind::kIntAtLeast:
      if (!(x >= r.lo)) rd.Fail(it, "got " + Num(x) + " (expected a number >= " + Num(r.lo) + ")");
      break;
    case Kind::kAbove:
      if (!(x > r.lo)) rd.Fail(it, "got " + Num(x) + " (expected a number > " + Num(r.lo) + ")");
      break;
    case Kind::kBelow:
      if (!(x < r.lo)) rd.Fail(it, "got " + Num(x) + " (expected a number < " + Num(r.lo) + ")");
      break;
    case Kind::kIntIn:
      if (x < r.lo || x > r.hi)
        rd.Fail(it, "got " + shown + " (expected an integer in " + Num(r.lo) + ".." + Num(r.hi) + ")");
      break;
    case Kind::kProbability:
      if (!(x >= 0.0 && x <= 1.0)) rd.Fail(it, "got " + Num(x) + " (expected a probability in [0, 1])");
      break;
    case Kind::kFraction:
      if (!(x >= 0.0 && x < 1.0)) rd.Fail(it, "got " + Num(x) + " (expected a number in [0, 1))");
      break;
    default:
      break;
  }
}

/// One of the row's choices, by name; its value.
long ReadChoice(const Reader &rd, const Item &it, const RangeRule &r) {
  const std::string s = rd.Str(it, "");
  std::vector<std::string> names;
  for (const Choice &c : r.choices) {
    if (s == c.name) return c.value;
    names.push_back(c.name);
  }
  if (const RetiredChoice *old = RetiredChoiceNamed(it.key, s)) rd.Fail(it, RetiredText(*old));
  if (r.kind == Kind::kOneOf) rd.Fail(it, "got \"" + s + "\" (expected one of: " + Join(names) + ")");
  std::string either;  // "\"a\", \"b\" or \"c\""
  for (std::size_t i = 0; i < names.size(); ++i)
    either += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + ("\"" + names[i] + "\"");
  rd.Fail(it, "got \"" + s + "\" (expected " + either + ")");
}

Json ReadVec3(const Reader &rd, const Item &it, const RangeRule &r) {
  const plant::Vec3 v = rd.Vec(it, plant::Vec3::Zero());
  if (r.kind == Kind::kNonZero && !(v.norm() >= r.lo))
    rd.Fail(it, "has length " + Num(v.norm()) + " (expected a non-zero vector)");
  if (r.kind == Kind::kAbove && !(v.minCoeff() > r.lo))
    rd.Fail(it, "got (" + Num(v[0]) + ", " + Num(v[1]) + ", " + Num(v[2]) + ") (expected each > " +
                    Num(r.lo) + ")");
  return Json::array({v[0], v[1], v[2]});
}

/// An array key: its count (REALS, REALS_GE), and for REALS_GE each element's bound.
Json ReadReals(const Reader &rd, const Item &it, const RangeRule &r) {
  const std::vector<double> xs = rd.Reals(it, static_cast<std::size_t>(r.lo));
  if (r.kind == Kind::kRealsAtLeast)
    for (std::size_t k = 0; k < xs.size(); ++k)
      if (!(xs[k] >= r.hi))
        rd.Fail(it, "element " + std::to_string(k) + " is " + Num(xs[k]) +
                        " (expected each >= " + Num(r.hi) + ")");
  return xs;
}

}  // namespace

Json ReadKey(const Reader &rd, const Item &it, const ConfigRow &row) {
  const RangeRule &r = row.range;
  if (!it || r.kind == Kind::kSpecial || r.kind == Kind::kTables) return nullptr;
  switch (row.type) {
    case KeyType::kReal: {
      const double x = rd.Real(it, 0.0);
      CheckNumber(rd, it, x, Num(x), r);
      return x;
    }
    case KeyType::kInt: {
      const std::int64_t n = rd.Int(it, 0);
      CheckNumber(rd, it, static_cast<double>(n), std::to_string(n), r);
      return n;
    }
    case KeyType::kBool: return rd.Bool(it, false);
    case KeyType::kString: {
      const std::string s = rd.Str(it, "");
      if (r.kind == Kind::kNonEmpty && s.empty()) rd.Fail(it, "got \"\" (expected a non-empty name)");
      return s;
    }
    case KeyType::kEnum: return ReadChoice(rd, it, r);
    case KeyType::kVec3: return ReadVec3(rd, it, r);
    case KeyType::kArray: return ReadReals(rd, it, r);
  }
  return nullptr;
}

}  // namespace uvms::sil
