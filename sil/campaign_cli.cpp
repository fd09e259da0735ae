// SPDX-License-Identifier: Apache-2.0
// campaign_cli.cpp: `uvms campaign` (campaign_cli.hpp).
#include "campaign_cli.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "campaign.hpp"
#include "provenance.hpp"
#include "scenario.hpp"
#include "summary_writer.hpp"
#include "toml_bounds.hpp"

namespace uvms::sil {
namespace fs = std::filesystem;
namespace {

using json = nlohmann::ordered_json;

const char *kHelp =
    "usage: uvms campaign FILE.toml --out DIR [-j N] [--transport memq|udpm]\n"
    "                     [--set section.key=value]... [--dry-run]\n\n"
    "Expands a campaign (a base scenario, fixed overrides in [set], [[sweep]] axes whose keys\n"
    "vary together, combined as a Cartesian product, and optional [replicates]: one run per\n"
    "seed of the runs whose `when` key is true) into runs, checks every run's scenario first,\n"
    "then runs them N at a time (default: all cores). A run's id is its axis labels joined\n"
    "with '_' (plus _s<N> for a replicate), so adding a sweep value or a seed renames nothing.\n"
    "Finished runs (a summary.json with the same overrides under the same id, not interrupted)\n"
    "are kept, so an interrupted or extended campaign only runs what is new.\n"
    "--set adds an override to every run, after the campaign's [set] and before the sweep\n"
    "values (so a sweep still wins), e.g. to shorten every run for a smoke test.\n"
    "--dry-run checks the campaign and every run's scenario, prints the plan (one line per\n"
    "run: id and swept values) and the run count, and writes nothing (--out is optional).\n"
    "Writes DIR/plan.json, DIR/runs/<id>/..., DIR/results.csv and DIR/results.json; plan.json\n"
    "and results.json carry the provenance of this binary and the campaign (docs/SCENARIOS.md).\n"
    "Exit status: 0 every run finished, 1 bad campaign or scenario, 2 usage, 3 some run failed\n"
    "(its row says why).\n";

json ReadJson(const fs::path &p) {
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

bool RunIsDone(const fs::path &dir, const CampaignRun &r) {
  const json ov = ReadJson(dir / "overrides.json");
  const json sum = ReadJson(dir / "summary.json");
  // An interrupted run (SIGTERM/SIGINT, e.g. the campaign killed) is not done: it runs again.
  return ov.is_array() && ov.get<std::vector<std::string>>() == r.overrides && sum.is_object() &&
         sum.contains("status") && sum.value("failure", json()) != json("interrupted");
}

pid_t SpawnRun(const std::string &self, const Campaign &c, const CampaignRun &r,
               const fs::path &dir) {
  std::vector<std::string> argv = {self, "run", c.base, "--out", dir.string(), "--transport",
                                   c.transport};
  for (const auto &o : r.overrides) {
    argv.push_back("--set");
    argv.push_back(o);
  }
  std::vector<char *> cargs;
  for (auto &a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  const std::string log = (dir / "run.out").string();
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    execv(cargs[0], cargs.data());
    _exit(127);
  }
  return pid;
}

std::string Clock(double s) {
  const long t = long(s + 0.5);
  std::ostringstream o;
  o << std::setfill('0') << std::setw(2) << t / 60 << ':' << std::setw(2) << t % 60;
  return o.str();
}

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
    "manipulator_energy_J", "propulsive_energy_J", "drive", "max_attitude_error_rad", "min_clearance_m", "final_ee_position_m",
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


struct CliArgs {
  std::string file, out_dir, transport;
  std::vector<std::string> extra_sets;
  unsigned jobs{std::max(1u, std::thread::hardware_concurrency())};
  bool dry_run{false};
};

// Parses the command line; returns an exit code to stop with, or -1 to go on.
int ParseCliArgs(const std::vector<std::string> &args, CliArgs &a, std::ostream &out,
                 std::ostream &err) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string &o = args[i];
    if (o == "-h" || o == "--help") {
      out << kHelp;
      return 0;
    }
    const bool takes_value = o == "--out" || o == "-j" || o == "--jobs" || o == "--transport" ||
                             o == "--set";
    if (takes_value && i + 1 >= args.size()) {
      err << "uvms campaign: error: " << o << " needs a value\n";
      return 2;
    }
    if (o == "--out") {
      a.out_dir = args[++i];
    } else if (o == "-j" || o == "--jobs") {
      const std::string v = args[++i];
      char *end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (end == v.c_str() || *end != '\0' || n < 1 || n > 256) {
        err << "uvms campaign: error: -j needs a count 1..256, got " << v << '\n';
        return 2;
      }
      a.jobs = unsigned(n);
    } else if (o == "--transport") {
      a.transport = args[++i];
    } else if (o == "--set") {
      a.extra_sets.push_back(args[++i]);
    } else if (o == "--dry-run") {
      a.dry_run = true;
    } else if (!o.empty() && o[0] == '-') {
      err << "uvms campaign: error: unknown option " << o << "\n(see uvms campaign --help)\n";
      return 2;
    } else if (a.file.empty()) {
      a.file = o;
    } else {
      err << "uvms campaign: error: unexpected argument " << o << '\n';
      return 2;
    }
  }
  if (a.file.empty() || (a.out_dir.empty() && !a.dry_run)) {
    err << "uvms campaign: error: needs FILE.toml and --out DIR\n(see uvms campaign --help)\n";
    return 2;
  }
  return -1;
}

// A campaign or base scenario file's bytes: a regular file of bounded size (a directory, a device
// such as /dev/urandom or a FIFO is refused at once, never read). Throws CampaignError.
std::string ReadOrThrow(const std::string &path) {
  std::string bytes, err;
  if (!ReadBoundedFile(path, &bytes, &err)) throw CampaignError(err);
  return bytes;
}

// The campaign, expanded, with every run's scenario checked; and its provenance.
Campaign LoadChecked(const CliArgs &a, Provenance *prov) {
  const std::string text = ReadOrThrow(a.file);
  Campaign c = ParseCampaign(text, a.file, a.extra_sets);
  if (!a.transport.empty()) {
    if (a.transport != "memq" && a.transport != "udpm")
      throw CampaignError("--transport must be memq or udpm, got " + a.transport);
    c.transport = a.transport;
  }
  for (const CampaignRun &r : c.runs) {
    try {
      (void)LoadScenario(c.base, r.overrides);
    } catch (const ScenarioError &e) {
      throw CampaignError("run " + r.id + ": " + e.what());
    }
  }
  *prov = CampaignProvenance(text, a.extra_sets, ReadOrThrow(c.base));
  return c;
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

json PlanJson(const Campaign &c, const Provenance &prov) {
  json plan;
  plan["campaign"] = fs::absolute(c.path).lexically_normal().string();
  plan["name"] = c.name;
  plan["description"] = c.description;
  plan["base"] = c.base;
  plan["transport"] = c.transport;
  plan["provenance"] = ProvenanceJson(prov);
  plan["replicates"] = ReplicatesJson(c.replicates);
  plan["runs"] = json::array();
  for (const CampaignRun &r : c.runs) {
    json run = {{"id", r.id}, {"overrides", r.overrides}};
    if (r.replicate) run["replicate"] = *r.replicate;
    plan["runs"].push_back(run);
  }
  return plan;
}

void PrintPlan(const Campaign &c, std::ostream &out) {
  for (const CampaignRun &r : c.runs) {
    out << r.id;
    for (const auto &[k, v] : r.swept) out << "  " << k << '=' << v;
    out << '\n';
  }
  size_t replicated = 0;
  for (const CampaignRun &r : c.runs) replicated += r.replicate ? 1 : 0;
  out << "uvms campaign: " << c.name << ": " << c.runs.size() << " runs";
  if (!c.replicates.key.empty())
    out << " (" << replicated << " of them replicates: " << c.replicates.values.size()
        << " values of " << c.replicates.key << ")";
  out << "; dry run, nothing written\n";
}

// Directories under runs/ that are no run of this plan (an older id scheme, a removed value).
void NoteStrayDirs(const Campaign &c, const fs::path &runs, std::ostream &out) {
  std::set<std::string> ids;
  for (const CampaignRun &r : c.runs) ids.insert(r.id);
  std::vector<std::string> stray;
  std::error_code ec;
  for (const auto &e : fs::directory_iterator(runs, ec))
    if (e.is_directory() && ids.count(e.path().filename().string()) == 0)
      stray.push_back(e.path().filename().string());
  if (stray.empty()) return;
  std::sort(stray.begin(), stray.end());
  out << "uvms campaign: note: " << stray.size() << " director" << (stray.size() == 1 ? "y" : "ies")
      << " under " << runs.string() << " belong to no run of this plan (left alone, not in the "
      << "results): " << stray.front() << (stray.size() > 1 ? ", ..." : "") << '\n';
}

// Runs what is not done yet, `jobs` at a time, with progress. Returns 0, or 3 when a run
// cannot be started.
int ExecuteRuns(const Campaign &c, const fs::path &root, unsigned jobs, std::ostream &out,
                std::ostream &err) {
  std::error_code ec;
  const std::string self = fs::read_symlink("/proc/self/exe", ec).string();
  std::vector<const CampaignRun *> todo;
  for (const CampaignRun &r : c.runs)
    if (!RunIsDone(root / "runs" / r.id, r)) todo.push_back(&r);
  const size_t total = c.runs.size(), skipped = total - todo.size();
  out << "uvms campaign: " << c.name << ": " << total << " runs (" << skipped
      << " already done), " << jobs << " at a time, transport " << c.transport << '\n';
  NoteStrayDirs(c, root / "runs", out);
  const bool tty = isatty(fileno(stdout)) != 0;
  const auto t0 = std::chrono::steady_clock::now();
  std::map<pid_t, const CampaignRun *> running;
  size_t next = 0, done = 0;
  auto progress = [&](const CampaignRun *finished, int rc) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double eta = done > 0 ? el / double(done) * double(todo.size() - done) : 0.0;
    std::ostringstream line;
    line << "[" << (skipped + done) << "/" << total << "] elapsed " << Clock(el) << ", ETA "
         << (done > 0 ? Clock(eta) : std::string("--:--"));
    if (tty) out << "\r" << line.str() << "   " << std::flush;
    else out << line.str() << "  " << finished->id << (rc == 0 ? " finished" : " FAILED") << '\n';
  };
  while (next < todo.size() || !running.empty()) {
    while (next < todo.size() && running.size() < jobs) {
      const CampaignRun *r = todo[next++];
      const fs::path dir = root / "runs" / r->id;
      fs::create_directories(dir, ec);
      fs::remove(dir / "summary.json", ec);
      try {
        WriteTextFileAtomic(json(r->overrides).dump(2) + "\n", (dir / "overrides.json").string());
      } catch (const std::exception &e) {
        err << "uvms campaign: error: run " << r->id << ": " << e.what() << '\n';
        return 3;
      }
      const pid_t pid = SpawnRun(self, c, *r, dir);
      if (pid < 0) {
        err << "uvms campaign: error: cannot start run " << r->id << ": " << std::strerror(errno)
            << '\n';
        return 3;
      }
      running[pid] = r;
    }
    int st = 0;
    const pid_t pid = waitpid(-1, &st, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    ++done;
    progress(it->second, WIFEXITED(st) ? WEXITSTATUS(st) : 128);
    running.erase(it);
  }
  if (tty) out << '\n';
  return 0;
}

// One results row: id, swept keys (as JSON values), then the run's summary.json.
json ResultRow(const CampaignRun &r, const fs::path &root) {
  const json sum = ReadJson(root / "runs" / r.id / "summary.json");
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
    row["reason"] = "no summary.json (see runs/" + r.id + "/run.out)";
  }
  for (const auto &[k, v] : sum.items()) row[k] = v;
  return row;
}

// results.csv and results.json, one row per run in plan order. Returns the failed runs.
int WriteResults(const Campaign &c, const fs::path &root, const Provenance &prov) {
  std::set<std::string> seen;
  std::vector<std::string> swept_keys;
  for (const CampaignAxis &ax : c.axes)
    for (const auto &k : ax.keys)
      if (seen.insert(k).second) swept_keys.push_back(k);
  if (!c.replicates.key.empty()) swept_keys.push_back(c.replicates.key);
  std::ostringstream csv;
  csv << "id";
  for (const auto &k : swept_keys) csv << ',' << CsvField(k);
  for (const char *k : kResultKeys) csv << ',' << k;
  csv << '\n';
  int failed = 0;
  json rows = json::array();
  for (const CampaignRun &r : c.runs) {
    const json row = ResultRow(r, root);
    if (row.value("status", std::string()) != "finished") ++failed;
    csv << CsvField(r.id);
    for (const auto &k : swept_keys) csv << ',' << CsvField(JsonCell(row.value(k, json())));
    for (const char *k : kResultKeys) csv << ',' << CsvField(JsonCell(row.value(k, json())));
    csv << '\n';
    rows.push_back(row);
  }
  json results;
  results["provenance"] = ProvenanceJson(prov);
  results["name"] = c.name;
  results["description"] = c.description;
  results["base"] = c.base;
  results["swept_keys"] = swept_keys;
  results["replicates"] = ReplicatesJson(c.replicates);
  results["runs"] = rows;
  // Checked and atomic (summary_writer.hpp): a full disk is an error, never a truncated table.
  WriteTextFileAtomic(csv.str(), (root / "results.csv").string());
  WriteTextFileAtomic(results.dump(2) + "\n", (root / "results.json").string());
  return failed;
}

}  // namespace

int RunCampaignCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  CliArgs a;
  if (const int rc = ParseCliArgs(args, a, out, err); rc >= 0) return rc;
  Campaign c;
  Provenance prov;
  try {
    c = LoadChecked(a, &prov);
  } catch (const CampaignError &e) {
    err << "uvms campaign: error: " << e.what() << '\n';
    return 1;
  }
  if (a.dry_run) {
    PrintPlan(c, out);
    return 0;
  }
  const fs::path root(a.out_dir);
  std::error_code ec;
  fs::create_directories(root / "runs", ec);
  if (ec) {
    err << "uvms campaign: error: cannot create " << (root / "runs") << ": " << ec.message() << '\n';
    return 1;
  }
  try {
    WriteTextFileAtomic(PlanJson(c, prov).dump(2) + "\n", (root / "plan.json").string());
  } catch (const std::exception &e) {
    err << "uvms campaign: error: " << e.what() << '\n';
    return 3;
  }
  const auto t0 = std::chrono::steady_clock::now();
  if (const int rc = ExecuteRuns(c, root, a.jobs, out, err); rc != 0) return rc;
  int failed = 0;
  try {
    failed = WriteResults(c, root, prov);
  } catch (const std::exception &e) {
    err << "uvms campaign: error: cannot write the results: " << e.what() << '\n';
    return 3;
  }
  const size_t total = c.runs.size();
  const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out << "uvms campaign: " << c.name << ": " << (total - size_t(failed)) << "/" << total
      << " runs finished in " << std::fixed << std::setprecision(1) << el << " s; "
      << (root / "results.csv").string() << '\n';
  return failed == 0 ? 0 : 3;
}

}  // namespace uvms::sil
