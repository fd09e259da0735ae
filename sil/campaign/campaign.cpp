// SPDX-License-Identifier: Apache-2.0
// campaign.cpp: campaign files expanded into runs with stable ids (campaign.hpp).
#include "campaign/campaign.hpp"
#include "scenario/override_key.hpp"
#include "run/provenance.hpp"
#include "scenario/toml_bounds.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <set>
#include <sstream>

namespace uvms::sil {
namespace fs = std::filesystem;
namespace {

constexpr std::int64_t kMaxReplicates = 100000;  // a guard against typos in `count`

std::string Where(const std::string &file, const toml::node &n) {
  return file + ":" + std::to_string(n.source().begin.line);
}

std::string KeyError(const std::string &at, const std::string &key, const std::string &what) {
  return at + ": key \"" + key + "\": " + what;
}

// A float as TOML text, in the shortest form that reads back to the same double (0.05, not
// toml++'s 0.050000000000000003: it names run directories), always a float to TOML ("5.0").
std::string FloatText(double x) {
  if (!std::isfinite(x)) return std::isnan(x) ? "nan" : (x < 0 ? "-inf" : "inf");
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  std::string t(buf, r.ptr);
  if (t.find_first_of(".e") == std::string::npos) t += ".0";
  return t;
}

// A TOML value as TOML text (strings quoted, arrays in brackets); `key` names it in errors.
std::string TomlText(const toml::node &n, const std::string &key = "") {
  if (n.is_table())
    throw CampaignError(KeyError("line " + std::to_string(n.source().begin.line), key,
                                 "a table value (expected a value; a key inside a table is "
                                 "set by its dotted name, e.g. \"environment.unsteady_flow."
                                 "enabled\")"));
  std::ostringstream s;
  n.visit([&](const auto &v) {
    if constexpr (toml::is_string<decltype(v)>) {
      const std::string &str = v.get();
      if (std::any_of(str.begin(), str.end(), [](char c) { return c == '\n' || c == '\r' || c == '\0'; }))
        throw CampaignError(KeyError("line " + std::to_string(n.source().begin.line), key,
                                     "a string value with a line break or NUL byte (every "
                                     "value becomes one --set line; expected one line)"));
      s << std::quoted(v.get());
    } else if constexpr (toml::is_floating_point<decltype(v)>) {
      s << FloatText(v.get());
    } else if constexpr (!toml::is_table<decltype(v)>) {
      s << toml::toml_formatter(v);
    }
  });
  return s.str();
}

// A key of the campaign file as `--set` will apply it (override_key.hpp: blanks trimmed, then a
// dotted key), so that the duplicate checks compare what is applied. `what` names it in the
// error: "sweep key", "[set] key", "replicates.key".
std::string AppliedKey(const std::string &at, const std::string &what, const std::string &raw) {
  const std::string key = NormalizedKey(raw);
  if (key.empty())
    throw CampaignError(at + ": " + what + " \"" + raw +
                        "\": not a dotted scenario key (expected section.key of letters, digits, "
                        "_ and -, e.g. \"run.seed\")");
  return key;
}

std::string Trim(const std::string &s) { return TrimBlanks(s); }

CampaignAxis ParseSweep(const std::string &path, const toml::node &tn) {
  CampaignAxis axis;
  const toml::table &t = *tn.as_table();
  size_t n = 0;
  for (const auto &[ak, av] : t) {
    const std::string aat = Where(path, av);
    const std::string akey =
        ak.str() == "labels" ? std::string("labels") : AppliedKey(aat, "sweep key", std::string(ak.str()));
    const toml::array *vals = av.as_array();
    if (vals == nullptr || vals->empty())
      throw CampaignError(aat + ": sweep key \"" + akey + "\": expected a non-empty array");
    if (akey == "labels") {
      for (const auto &l : *vals) {
        if (!l.is_string()) throw CampaignError(aat + ": sweep labels must be strings");
        axis.labels.push_back(*l.value<std::string>());
      }
      continue;
    }
    if (n != 0 && vals->size() != n)
      throw CampaignError(aat + ": sweep key \"" + akey + "\" has " + std::to_string(vals->size()) +
                          " values, the axis has " + std::to_string(n) +
                          " (keys of one [[sweep]] vary together)");
    n = vals->size();
    axis.keys.push_back(akey);
    if (axis.values.size() < n) axis.values.resize(n);
    for (size_t i = 0; i < n; ++i) axis.values[i].push_back(TomlText((*vals)[i], akey));
  }
  if (axis.keys.empty())
    throw CampaignError(Where(path, tn) + ": a [[sweep]] needs at least one key");
  if (!axis.labels.empty() && axis.labels.size() != n)
    throw CampaignError(Where(path, tn) + ": sweep labels: " + std::to_string(axis.labels.size()) +
                        " labels for " + std::to_string(n) + " values");
  if (axis.labels.empty())
    for (size_t i = 0; i < n; ++i) axis.labels.push_back(axis.values[i][0]);
  return axis;
}

std::int64_t ReplicateInt(const std::string &path, const toml::node &v, const std::string &key,
                          std::int64_t min) {
  const auto i = v.value_exact<std::int64_t>();
  if (!i || *i < min)
    throw CampaignError(KeyError(Where(path, v), key,
                                 "got " + (v.is_table() ? "a table" : TomlText(v)) +
                                     " (expected an integer >= " + std::to_string(min) + ")"));
  return *i;
}

std::vector<std::int64_t> ReplicateList(const std::string &path, const toml::node &v) {
  const toml::array *arr = v.as_array();
  if (arr == nullptr || arr->empty())
    throw CampaignError(KeyError(Where(path, v), "replicates.values",
                                 "expected a non-empty array of integers >= 0, e.g. [1, 2, 3]"));
  std::vector<std::int64_t> out;
  std::set<std::int64_t> seen;
  for (const toml::node &e : *arr) {
    out.push_back(ReplicateInt(path, e, "replicates.values", 0));
    if (!seen.insert(out.back()).second)
      throw CampaignError(KeyError(Where(path, e), "replicates.values",
                                   std::to_string(out.back()) +
                                       " appears more than once (expected distinct values)"));
  }
  return out;
}

std::vector<std::int64_t> ReplicateRange(const std::string &path, const toml::node &first,
                                         const toml::node &count) {
  const std::int64_t f = ReplicateInt(path, first, "replicates.first", 0);
  const std::int64_t n = ReplicateInt(path, count, "replicates.count", 1);
  if (n > kMaxReplicates)
    throw CampaignError(KeyError(Where(path, count), "replicates.count",
                                 "got " + std::to_string(n) + " (expected at most " +
                                     std::to_string(kMaxReplicates) + ")"));
  if (f > std::numeric_limits<std::int64_t>::max() - (n - 1))
    throw CampaignError(KeyError(Where(path, first), "replicates.first",
                                 "got " + std::to_string(f) + ": first + count - 1 overflows"));
  std::vector<std::int64_t> out;
  for (std::int64_t i = 0; i < n; ++i) out.push_back(f + i);
  return out;
}

std::string ReplicateKey(const std::string &path, const toml::node &v, const std::string &name) {
  const auto s = v.value_exact<std::string>();
  if (!s || NormalizedKey(*s).empty())
    throw CampaignError(KeyError(Where(path, v), name,
                                 "expected a dotted scenario key as a string, e.g. \"run.seed\""));
  return NormalizedKey(*s);
}

CampaignReplicates ParseReplicates(const std::string &path, const toml::node &node) {
  const std::string at = Where(path, node);
  const toml::table *t = node.as_table();
  if (t == nullptr)
    throw CampaignError(KeyError(at, "replicates", "expected a table [replicates]"));
  CampaignReplicates r;
  const toml::node *values = nullptr, *first = nullptr, *count = nullptr;
  for (const auto &[k, v] : *t) {
    const std::string key(k.str());
    if (key == "key") r.key = ReplicateKey(path, v, "replicates.key");
    else if (key == "when") r.when = ReplicateKey(path, v, "replicates.when");
    else if (key == "values") values = &v;
    else if (key == "first") first = &v;
    else if (key == "count") count = &v;
    else
      throw CampaignError(KeyError(Where(path, v), "replicates." + key,
                                   "unknown key (expected key, values, first, count, when)"));
  }
  if (r.key.empty())
    throw CampaignError(KeyError(at, "replicates.key",
                                 "required (the scenario key varied, e.g. \"run.seed\")"));
  if (r.when == r.key)
    throw CampaignError(KeyError(at, "replicates.when", "must differ from replicates.key"));
  if (values != nullptr && (first != nullptr || count != nullptr))
    throw CampaignError(KeyError(at, "replicates.values",
                                 "give either values or first and count, not both"));
  if (values == nullptr && (first == nullptr || count == nullptr))
    throw CampaignError(KeyError(at, "replicates", std::string("missing ") +
                                 (first || count ? (first ? "count" : "first") : "values") +
                                 " (expected values = [...], or first = N and count = M)"));
  r.values = values ? ReplicateList(path, *values) : ReplicateRange(path, *first, *count);
  return r;
}

// Every swept key on one axis only, and the replicate key on none: a second axis (or the
// replicate) setting the same key would silently override the first, leaving runs that differ
// only in their ids. A key both in [set] and on an axis is fine: the axis value wins.
void CheckAxisKeys(const std::string &path, const toml::table &root, const Campaign &c) {
  const toml::array *sweeps = root["sweep"].as_array();
  if (sweeps == nullptr) return;
  std::map<std::string, std::int64_t> first_line;  // swept key -> line of its first axis
  for (const toml::node &tn : *sweeps)
    for (const auto &[k, v] : *tn.as_table()) {
      if (k.str() == "labels") continue;
      const std::string key = NormalizedKey(k.str());  // as applied (checked in ParseSweep)
      const std::int64_t line = v.source().begin.line;
      const auto [it, fresh] = first_line.emplace(key, line);
      if (!fresh)
        throw CampaignError(KeyError(Where(path, v), key,
                                     "on two [[sweep]] axes, lines " + std::to_string(it->second) +
                                         " and " + std::to_string(line) +
                                         " (expected each key on one axis only; keys that vary "
                                         "together go in one [[sweep]])"));
    }
  const auto swept = first_line.find(c.replicates.key);
  if (c.replicates.key.empty() || swept == first_line.end()) return;
  const toml::node *rk = root.at_path("replicates.key").node();
  throw CampaignError(KeyError(rk ? Where(path, *rk) : path, "replicates.key",
                               "\"" + c.replicates.key + "\" is also a [[sweep]] key on line " +
                                   std::to_string(swept->second) +
                                   " (expected a key that is either swept or replicated)"));
}

void ParseRoot(const std::string &path, const toml::table &root, Campaign &c) {
  for (const auto &[k, v] : root) {
    const std::string key(k.str());
    const std::string at = Where(path, v);
    if (key == "name" || key == "description" || key == "base" || key == "transport") {
      if (!v.is_string()) throw CampaignError(at + ": key \"" + key + "\": expected a string");
      const std::string s = *v.value<std::string>();
      if (key == "name") c.name = s;
      else if (key == "description") c.description = s;
      else if (key == "transport") c.transport = s;
      else c.base = (fs::path(path).parent_path() / s).lexically_normal().string();
    } else if (key == "set") {
      if (!v.is_table()) throw CampaignError(at + ": key \"set\": expected a table");
      std::set<std::string> seen;
      for (const auto &[sk, sv] : *v.as_table()) {
        const std::string key = AppliedKey(Where(path, sv), "[set] key", std::string(sk.str()));
        if (!seen.insert(key).second)
          throw CampaignError(Where(path, sv) + ": [set] key \"" + std::string(sk.str()) +
                              "\" is \"" + key + "\" once its blanks are trimmed, set twice "
                              "(expected each key once)");
        c.fixed.push_back(key + "=" + TomlText(sv, key));
      }
    } else if (key == "sweep") {
      const toml::array *arr = v.as_array();
      if (arr == nullptr || !arr->is_array_of_tables())
        throw CampaignError(at + ": key \"sweep\": expected [[sweep]] tables");
      for (const toml::node &tn : *arr) c.axes.push_back(ParseSweep(path, tn));
    } else if (key == "replicates") {
      c.replicates = ParseReplicates(path, v);
    } else {
      throw CampaignError(at + ": unknown key \"" + key +
                          "\" (expected name, description, base, transport, set, sweep, "
                          "replicates)");
    }
  }
  CheckAxisKeys(path, root, c);
}

// toml++'s view of a node, or nullptr.
const toml::node *At(const toml::node &n, const std::string &dotted) {
  if (dotted.empty()) return &n;
  const toml::table *t = n.as_table();
  return t == nullptr ? nullptr : t->at_path(dotted).node();
}

// The effective value of boolean `key` in a run: its last override that sets it (directly or
// inside a table value), else the base scenario file's value. Throws when neither sets it.
bool EffectiveBool(const Campaign &c, const toml::table &base, const CampaignRun &run,
                   const std::string &run_name) {
  const std::string &key = c.replicates.when;
  const std::string what =
      KeyError(c.path, "replicates.when", "run " + run_name + ": \"" + key + "\"");
  auto as_bool = [&](const toml::node &n, const std::string &from) {
    if (const auto b = n.value_exact<bool>()) return *b;
    throw CampaignError(what + " is " + (n.is_table() ? "a table" : TomlText(n)) + " in " + from +
                        " (expected a boolean)");
  };
  for (auto o = run.overrides.rbegin(); o != run.overrides.rend(); ++o) {
    const auto eq = o->find('=');
    const std::string okey = Trim(o->substr(0, eq));
    if (eq == std::string::npos || (okey != key && key.rfind(okey + ".", 0) != 0)) continue;
    toml::table parsed;
    try {
      parsed = toml::parse("v = " + Trim(o->substr(eq + 1)) + "\n");
    } catch (const toml::parse_error &e) {
      throw CampaignError(what + ": the override \"" + *o + "\" is not TOML (" +
                          std::string(e.description()) + ")");
    }
    const std::string rest = okey == key ? "" : key.substr(okey.size() + 1);
    if (const toml::node *n = At(*parsed.get("v"), rest))
      return as_bool(*n, "the override \"" + *o + "\"");
  }
  if (const toml::node *n = At(base, key)) return as_bool(*n, "the base scenario " + c.base);
  throw CampaignError(what + " is set neither by the run's overrides nor by the base scenario " +
                      c.base + " (uvms campaign does not know scenario defaults: set it in [set], "
                      "a [[sweep]] or the base scenario)");
}

// The base scenario as a TOML table: a regular file within the input bounds (toml_bounds.hpp),
// so a directory, a device or a FIFO named as the base is refused, never read.
toml::table ReadBase(const Campaign &c) {
  const char *const why = " (the base scenario, read for replicates.when)";
  std::string text, err;
  if (!ReadBoundedFile(c.base, &text, &err)) throw CampaignError(err + why);
  if (const std::string bounds = TomlBoundsError(text, c.base); !bounds.empty())
    throw CampaignError(bounds + why);
  try {
    return toml::parse(text, c.base);
  } catch (const toml::parse_error &e) {
    const auto line = e.source().begin.line;
    throw CampaignError(c.base + (line ? ":" + std::to_string(line) : std::string()) +
                        ": the base scenario cannot be read for replicates.when (" +
                        std::string(e.description()) + ")");
  }
}

std::string JoinId(const std::vector<std::string> &parts) {
  std::string id;
  for (const auto &p : parts) id += (id.empty() ? "" : "_") + p;
  return id.empty() ? "run" : id;
}

// A decimal count with thousands separators: "1099511627776" -> "1,099,511,627,776".
std::string Grouped(std::string digits) {
  for (size_t i = digits.size(); i > 3; i -= 3) digits.insert(i - 3, ",");
  return digits;
}

// SIZE_MAX + 1 in decimal (18446744073709551616 with a 64-bit size_t): the least count that
// does not fit.
std::string PastSizeMax() {
  std::string d = std::to_string(std::numeric_limits<size_t>::max());
  for (size_t i = d.size(); i-- > 0;) {
    if (d[i] != '9') {
      ++d[i];
      return d;
    }
    d[i] = '0';
  }
  return "1" + d;
}

bool MulOverflows(size_t a, size_t b, size_t *out) {
  if (b != 0 && a > std::numeric_limits<size_t>::max() / b) return true;
  *out = a * b;
  return false;
}

bool AddOverflows(size_t a, size_t b, size_t *out) {
  if (a > std::numeric_limits<size_t>::max() - b) return true;
  *out = a + b;
  return false;
}

[[noreturn]] void ThrowOverflow(const Campaign &c, size_t max_runs) {
  const std::string replicates =
      c.replicates.key.empty()
          ? ""
          : " and " + std::to_string(c.replicates.values.size()) + " replicate values";
  throw CampaignError(c.path + ": the campaign expands to " + Grouped(PastSizeMax()) +
                      " runs or more (overflow): " + std::to_string(c.axes.size()) +
                      " [[sweep]] axes" + replicates + " (expected at most " +
                      Grouped(std::to_string(max_runs)) + " runs, the --max-runs limit)");
}

void CheckLimit(const Campaign &c, size_t runs, bool at_least, size_t max_runs) {
  if (runs <= max_runs) return;
  throw CampaignError(c.path + ": the campaign expands to " + Grouped(std::to_string(runs)) +
                      (at_least ? " runs or more" : " runs") + ", over the limit of " +
                      Grouped(std::to_string(max_runs)) + " (--max-runs N raises it)");
}

// Axis value indices of combination r (the last axis fastest).
std::vector<size_t> Indices(const Campaign &c, size_t r) {
  std::vector<size_t> idx(c.axes.size());
  for (size_t a = c.axes.size(); a-- > 0;) {
    idx[a] = r % c.axes[a].values.size();
    r /= c.axes[a].values.size();
  }
  return idx;
}

// Combination r as a run without its replicate: [set] and extra --set, then the axis values.
CampaignRun Combination(const Campaign &c, size_t r, std::vector<std::string> *parts) {
  const std::vector<size_t> idx = Indices(c, r);
  CampaignRun run;
  run.overrides = c.fixed;
  parts->clear();
  for (size_t a = 0; a < c.axes.size(); ++a) {
    const CampaignAxis &ax = c.axes[a];
    parts->push_back(IdPart(ax.labels[idx[a]]));
    for (size_t k = 0; k < ax.keys.size(); ++k) {
      run.overrides.push_back(ax.keys[k] + "=" + ax.values[idx[a]][k]);
      run.swept.emplace_back(ax.keys[k], ax.values[idx[a]][k]);
    }
  }
  run.id = JoinId(*parts);
  return run;
}

// One run per combination of axis values (the last axis fastest), each replicated in place.
// The run count is checked against overflow and `max_runs` before any run is built: first the
// number of combinations (every combination is at least one run), then with the replicates.
void Expand(Campaign &c, size_t max_runs) {
  const CampaignReplicates &rep = c.replicates;
  const size_t n_rep = rep.key.empty() ? 1 : rep.values.size();
  const bool conditional = !rep.key.empty() && !rep.when.empty();
  size_t combos = 1;
  for (const CampaignAxis &ax : c.axes)
    if (MulOverflows(combos, ax.values.size(), &combos)) ThrowOverflow(c, max_runs);
  size_t total = 0;
  if (!conditional) {
    if (MulOverflows(combos, n_rep, &total)) ThrowOverflow(c, max_runs);
  } else {
    // Which combinations replicate depends on `when`, known only per run: every combination
    // is one run at least, so bound that first, then evaluate `when` once per combination.
    CheckLimit(c, combos, n_rep > 1, max_runs);
  }
  // `when` per combination: combos bits, combos <= max_runs (checked above)
  std::vector<bool> replicated(conditional ? combos : 0, false);
  std::vector<std::string> parts;
  if (conditional) {
    const toml::table base = ReadBase(c);
    for (size_t r = 0; r < combos; ++r) {
      const CampaignRun run = Combination(c, r, &parts);
      replicated[r] = EffectiveBool(c, base, run, run.id);
      if (AddOverflows(total, replicated[r] ? n_rep : 1, &total)) ThrowOverflow(c, max_runs);
    }
  }
  CheckLimit(c, total, false, max_runs);
  c.runs.reserve(total);
  for (size_t r = 0; r < combos; ++r) {
    CampaignRun run = Combination(c, r, &parts);
    if (rep.key.empty() || (conditional && !replicated[r])) {
      c.runs.push_back(std::move(run));
      continue;
    }
    for (const std::int64_t v : rep.values) {
      CampaignRun copy = run;
      copy.overrides.push_back(rep.key + "=" + std::to_string(v));
      copy.swept.emplace_back(rep.key, std::to_string(v));
      copy.replicate = v;
      std::vector<std::string> id_parts = parts;
      id_parts.push_back(ReplicateSuffix(v));
      copy.id = JoinId(id_parts);
      c.runs.push_back(std::move(copy));
    }
  }
}

std::string Describe(const CampaignRun &r) {
  std::string s;
  for (const auto &[k, v] : r.swept) s += (s.empty() ? "" : ", ") + k + " = " + v;
  return s.empty() ? "no swept values" : s;
}

void CheckUniqueIds(const Campaign &c) {
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < c.runs.size(); ++i) {
    const auto [it, fresh] = seen.emplace(c.runs[i].id, i);
    if (fresh) continue;
    const CampaignRun &a = c.runs[it->second], &b = c.runs[i];
    throw CampaignError(c.path + ": two runs get the id \"" + b.id + "\": (" + Describe(a) +
                        ") and (" + Describe(b) +
                        "); give the [[sweep]] values distinct labels (ids keep letters, digits, "
                        "'.' and '-'; everything else becomes '_')");
  }
}

}  // namespace

std::string IdPart(const std::string &text) {
  std::string out;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-') {
      if (!out.empty() || c != '.') out += c;  // no hidden directories, no "." or ".."
    } else if (!out.empty() && out.back() != '_') {
      out += '_';
    }
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out.empty() ? "v" : out;
}

std::string ReplicateSuffix(std::int64_t value) { return "s" + std::to_string(value); }

Campaign LoadCampaign(const std::string &path, const std::vector<std::string> &extra_sets,
                      std::size_t max_runs) {
  std::string text, err;
  if (!ReadBoundedFile(path, &text, &err)) throw CampaignError(err);  // regular, bounded size
  return ParseCampaign(text, path, extra_sets, max_runs);
}

Campaign ParseCampaign(const std::string &text, const std::string &path,
                       const std::vector<std::string> &extra_sets, std::size_t max_runs) {
  if (max_runs == 0)
    throw CampaignError(path + ": the run limit (--max-runs) is 0 (expected at least 1)");
  // size, nesting, dotted keys: before toml++ sees the text
  if (const std::string err = TomlBoundsError(text, path); !err.empty()) throw CampaignError(err);
  toml::table root;
  try {
    root = toml::parse(text, path);
  } catch (const toml::parse_error &e) {
    throw CampaignError(path + ":" + std::to_string(e.source().begin.line) + ": " +
                        std::string(e.description()));
  }
  Campaign c;
  c.path = path;
  c.name = fs::path(path).stem().string();
  ParseRoot(path, root, c);
  c.extra_sets = extra_sets;
  c.fixed.insert(c.fixed.end(), extra_sets.begin(), extra_sets.end());
  if (c.base.empty()) throw CampaignError(path + ": key \"base\" (the base scenario) is required");
  if (c.transport != "memq" && c.transport != "udpm")
    throw CampaignError(path + ": key \"transport\": expected \"memq\" or \"udpm\"");
  Expand(c, max_runs);
  CheckUniqueIds(c);
  return c;
}

namespace {

// The parts as one stream, each as "<decimal byte count>:<bytes>", so that a boundary can never
// move between parts: ("ab", "c") and ("a", "bc") give different streams.
std::string LengthPrefixed(const std::vector<const std::string *> &parts) {
  std::string stream;
  for (const std::string *p : parts) stream += std::to_string(p->size()) + ":" + *p;
  return stream;
}

}  // namespace

std::string CampaignIdentity(const std::string &campaign_text, const std::string &base_text,
                             const std::vector<std::string> &extra_sets,
                             const std::string &version) {
  std::vector<const std::string *> parts = {&campaign_text, &base_text};
  for (const std::string &s : extra_sets) parts.push_back(&s);
  parts.push_back(&version);
  return Sha256Hex(LengthPrefixed(parts));
}

std::string RunSession(const std::string &base_text, const std::vector<std::string> &overrides,
                       std::uint64_t generation) {
  static const std::string kDomain = "uvms campaign run session";
  const std::string gen = "generation " + std::to_string(generation);
  std::vector<const std::string *> parts = {&kDomain, &base_text};
  for (const std::string &o : overrides) parts.push_back(&o);
  if (generation != 0) parts.push_back(&gen);
  const std::string hex = Sha256Hex(LengthPrefixed(parts)).substr(0, 16);
  return hex == std::string(16, '0') ? std::string(15, '0') + "1" : hex;
}

}  // namespace uvms::sil
