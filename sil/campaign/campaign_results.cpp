// SPDX-License-Identifier: Apache-2.0
// campaign_results.cpp: a campaign's run directories read back, and its results table
// (campaign_results.hpp).
#include "campaign/campaign_results.hpp"

#include <algorithm>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>
#include <vector>

#include "run/summary_writer.hpp"

namespace uvms::sil {
namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

json ReadJsonFile(const fs::path &p) {
  std::ifstream f(p);
  json j;
  if (!f) return j;
  try {
    f >> j;
  } catch (const std::exception &) {
    return json();
  }
  return j;
}

namespace {

// "" when the summary is the run `want` names; else what differs (the first field found).
std::string IdentityMismatch(const json &sum, const RunIdentity &want) {
  const json prov = sum.value("provenance", json());
  const auto text = [](const json &o, const char *k) {
    const json v = o.is_object() ? o.value(k, json()) : json();
    return v.is_string() ? v.get<std::string>() : std::string("(none)");
  };
  const std::pair<std::string, std::string> fields[] = {
      {"session", text(sum, "session")},
      {"scenario_sha256", text(prov, "scenario_sha256")},
      {"scenario_sets", text(prov, "scenario_sets")},
      {"version", text(prov, "version")}};
  const std::string wanted[] = {want.session, want.scenario_sha256, want.scenario_sets,
                                want.version};
  for (size_t i = 0; i < 4; ++i)
    if (fields[i].second != wanted[i])
      return "its summary.json is of another run: " + fields[i].first + " \"" +
             fields[i].second + "\", the plan's is \"" + wanted[i] + "\"";
  return "";
}

}  // namespace

Prior PriorRun(const fs::path &dir, const CampaignRun &r, const RunIdentity &want,
               std::string *why, json *summary) {
  std::string scratch;
  std::string &w = why ? *why : scratch;
  w.clear();
  const json ov = ReadJsonFile(dir / "overrides.json");
  json read = ReadJsonFile(dir / "summary.json");
  json &sum = summary ? *summary : read;
  if (summary) sum = std::move(read);
  if (!ov.is_array() || !sum.is_object() || !sum.contains("status")) return Prior::kNone;
  std::vector<std::string> overrides;
  for (const json &o : ov) {
    if (!o.is_string()) return Prior::kNone;
    overrides.push_back(o.get<std::string>());
  }
  if (overrides != r.overrides) {
    w = "its overrides.json holds other overrides";
    return Prior::kNone;
  }
  if (w = IdentityMismatch(sum, want); !w.empty()) return Prior::kNone;
  // An interrupted run (SIGTERM/SIGINT, e.g. the campaign killed) is not done: it runs again.
  if (sum.value("failure", json()) == json("interrupted")) {
    w = "it was interrupted";
    return Prior::kNone;
  }
  return sum["status"] == json("failed") ? Prior::kFailed : Prior::kFinished;
}

json ProvenanceJson(const Provenance &p) {
  json j = json::object();
  for (const auto &[k, v] : p) j[k] = v;
  return j;
}

json ReplicatesJson(const CampaignReplicates &r) {
  if (r.key.empty()) return json();
  return {{"key", r.key}, {"values", r.values}, {"when", r.when.empty() ? json() : json(r.when)}};
}

namespace {

std::string CsvField(const std::string &s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char ch : s) o += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return o + "\"";
}

// The summary fields that go into the results table (in this order), after id and swept keys.
const char *const kResultKeys[] = {
    "status", "failure", "ticks", "missed_ticks", "duration_s", "mean_ee_error_m",
    "max_ee_error_m", "final_ee_error_m", "thruster_energy_J", "thruster_energy_signed_J",
    "manipulator_energy_J", "propulsive_energy_J",
    // Tick analyses (sil/run/tick_analyses.hpp): task-space error, E_p split, motor energies.
    "task_error_reference", "task_error_mean_m", "task_error_max_m", "task_error_final_m",
    "task_error_at_tf_m", "task_error_hold_mean_m", "propulsive_energy_ff_J",
    "propulsive_energy_fb_J", "propulsive_energy_ff_fb_unsplit_J", "propulsive_split_inexact_ticks",
    "propulsive_energy_pos_J", "propulsive_energy_att_J", "propulsive_energy_pos_att_unsplit_J",
    "propulsive_pos_att_inexact_ticks", "propulsive_energy_group_x_J", "propulsive_energy_group_y_J",
    "propulsive_energy_group_z_J", "shaft_energy_J", "friction_energy_J", "copper_energy_J",
    // The minimum-power allocation's potential on the run's wrenches (run/alloc_potential.hpp).
    "alloc_cost_pinv", "alloc_cost_optimal", "alloc_cost_commanded", "alloc_static_potential",
    "alloc_realised_saving", "alloc_potential_unsolved_ticks",
    "drive", "max_attitude_error_rad", "min_clearance_m", "final_ee_position_m",
    "final_barycenter_m", "initial_barycenter_m", "final_vehicle_position_m",
    "initial_vehicle_position_m", "integrator_rhs_evals", "wall_time_s", "real_time_factor",
    "reason"};

std::string JsonCell(const json &v) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array()) {
    std::string s;
    for (size_t i = 0; i < v.size(); ++i) s += (i ? " " : "") + JsonCell(v[i]);
    return s;
  }
  if (v.is_number_float()) {
    std::ostringstream o;
    o << std::setprecision(17) << v.get<double>();
    return o.str();
  }
  return v.dump();
}


// One results row: id, swept keys (as JSON values), then the run's summary.json when it is the
// plan's run (`want`); otherwise a failed row that says why.
json ResultRow(const CampaignRun &r, const fs::path &root, const RunIdentity &want) {
  std::string why;
  const fs::path dir = root / "runs" / r.id;
  json read;  // summary.json as PriorRun read it (read once)
  const bool ours = PriorRun(dir, r, want, &why, &read) != Prior::kNone || why == "it was interrupted";
  const json sum = ours ? std::move(read) : json();
  json row;
  row["id"] = r.id;
  for (const auto &[k, v] : r.swept) {
    try {
      row[k] = json::parse(v);  // numbers, booleans, strings, arrays read as JSON
    } catch (const std::exception &) {
      row[k] = v;
    }
  }
  if (!sum.is_object()) {
    row["status"] = "failed";
    row["reason"] = why.empty() || why == "its overrides.json holds other overrides"
                        ? "no summary.json of this run (see runs/" + r.id + "/run.out)"
                        : "runs/" + r.id + ": " + why;
  }
  for (const auto &[k, v] : sum.items()) row[k] = v;
  return row;
}

std::string CsvHeader(const std::vector<std::string> &swept_keys) {
  std::string h = "id";
  for (const auto &k : swept_keys) h += "," + CsvField(k);
  for (const char *k : kResultKeys) h += std::string(",") + k;
  return h + "\n";
}

std::string CsvRow(const std::string &id, const json &row,
                   const std::vector<std::string> &swept_keys) {
  std::string line = CsvField(id);
  for (const auto &k : swept_keys) line += "," + CsvField(JsonCell(row.value(k, json())));
  for (const char *k : kResultKeys) line += "," + CsvField(JsonCell(row.value(k, json())));
  return line + "\n";
}

// A dump(2) text as it appears nested `by` spaces deeper: every line after the first indented
// (JSON text holds no raw line break inside a string, so this is exact).
std::string Indented(const std::string &text, size_t by) {
  std::string out;
  out.reserve(text.size() + text.size() / 8);
  for (char ch : text) {
    out += ch;
    if (ch == '\n') out.append(by, ' ');
  }
  return out;
}

// The opening of results.json up to the runs array's "[": the head's fields as dump(2) of the
// whole object writes them, then "runs".
std::string JsonHeadFields(const json &head) {
  std::string out = "{\n";
  for (const auto &[k, v] : head.items())
    out += "  " + json(k).dump() + ": " + Indented(v.dump(2), 2) + ",\n";
  return out + "  \"runs\": [";
}

// Adds the row's build ("git_commit controller_precision build_preset" of its provenance) to
// `builds` when it is new there (a row without a summary has none).
void NoteBuild(const json &row, std::vector<std::string> &builds) {
  const json prov = row.value("provenance", json());
  if (!prov.is_object()) return;
  const std::string b = prov.value("git_commit", std::string("?")) + " " +
                        prov.value("controller_precision", std::string("?")) + " " +
                        prov.value("build_preset", std::string("?"));
  if (std::find(builds.begin(), builds.end(), b) == builds.end()) builds.push_back(b);
}

}  // namespace

ResultsWritten WriteResults(const Campaign &c, const fs::path &root, const Provenance &prov,
                            const std::string &identity, std::uint64_t generation,
                            const std::function<RunIdentity(const CampaignRun &)> &want) {
  std::set<std::string> seen;
  std::vector<std::string> swept_keys;
  for (const CampaignAxis &ax : c.axes)
    for (const auto &k : ax.keys)
      if (seen.insert(k).second) swept_keys.push_back(k);
  if (!c.replicates.key.empty()) swept_keys.push_back(c.replicates.key);
  json head;
  head["identity"] = identity;
  head["generation"] = generation;
  head["provenance"] = ProvenanceJson(prov);
  head["name"] = c.name;
  head["description"] = c.description;
  head["base"] = c.base;
  head["swept_keys"] = swept_keys;
  head["replicates"] = ReplicatesJson(c.replicates);
  // Both files are streamed a row at a time, so memory does not grow with the run count, and
  // put in place atomically once complete (summary_writer.hpp): a full disk is an error, never
  // a truncated table. results.json has the bytes of the whole object's dump(2).
  AtomicFile csv((root / "results.csv").string()), js((root / "results.json").string());
  csv.Write(CsvHeader(swept_keys));
  js.Write(JsonHeadFields(head));
  ResultsWritten w;
  for (size_t i = 0; i < c.runs.size(); ++i) {
    const json row = ResultRow(c.runs[i], root, want(c.runs[i]));
    if (row.value("status", std::string()) != "finished") ++w.failed;
    NoteBuild(row, w.builds);
    csv.Write(CsvRow(c.runs[i].id, row, swept_keys));
    js.Write((i == 0 ? "\n    " : ",\n    ") + Indented(row.dump(2), 4));
  }
  js.Write(c.runs.empty() ? "]\n}\n" : "\n  ]\n}\n");
  csv.Commit();
  js.Commit();
  return w;
}

}  // namespace uvms::sil
