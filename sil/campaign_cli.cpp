// SPDX-License-Identifier: Apache-2.0
// campaign_cli.cpp: `uvms campaign` (campaign_cli.hpp).
#include "campaign_cli.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
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
    "                     [--set section.key=value]... [--max-runs N] [--retry-failed]\n"
    "                     [--force-new] [--dry-run]\n\n"
    "Expands a campaign (a base scenario, fixed overrides in [set], [[sweep]] axes whose keys\n"
    "vary together, combined as a Cartesian product, and optional [replicates]: one run per\n"
    "seed of the runs whose `when` key is true) into runs, checks every run's scenario first,\n"
    "then runs them N at a time (default: all cores). A run's id is its axis labels joined\n"
    "with '_' (plus _s<N> for a replicate), so adding a sweep value or a seed renames nothing.\n"
    "Finished runs (a summary.json with the same overrides under the same id, not interrupted)\n"
    "are kept, so an interrupted or extended campaign only runs what is new. A run that failed\n"
    "is kept as it is too (its row stays failed); --retry-failed runs the failed runs again.\n"
    "--set adds an override to every run, after the campaign's [set] and before the sweep\n"
    "values (so a sweep still wins), e.g. to shorten every run for a smoke test.\n"
    "--max-runs N refuses a campaign that expands to more than N runs (default %MAX_RUNS%).\n"
    "--dry-run checks the campaign and every run's scenario, prints the plan (one line per\n"
    "run: id and swept values) and the run count, and writes nothing (--out is optional).\n"
    "Writes DIR/plan.json, DIR/runs/<id>/..., DIR/results.csv and DIR/results.json; plan.json\n"
    "and results.json carry the provenance of this binary and the campaign (docs/SCENARIOS.md).\n"
    "DIR belongs to one campaign, named by its identity: the SHA-256 of the campaign file's\n"
    "bytes, the base scenario file's bytes, the --set overrides in order and the project\n"
    "version, written into plan.json and results.json. A campaign whose identity differs from\n"
    "the one in DIR/plan.json (or DIR with runs but no identity) is refused and nothing is\n"
    "changed, unless only the campaign file changed (say, extended), per plan.json's\n"
    "provenance: the same base scenario bytes, --set overrides, version and transport; then\n"
    "runs are kept one by one as above. --force-new starts the campaign afresh in any DIR:\n"
    "plan.json is replaced and every run is run again.\n"
    "One campaign at a time per DIR: a campaign holds a lock on DIR/.campaign.lock (flock(2),\n"
    "released by the kernel when the process ends, so a crash leaves no stale lock) and a\n"
    "second one on the same DIR is refused at once (exit 4). --dry-run takes no lock.\n"
    "Exit status: 0 every run finished; 1 bad campaign or scenario, or DIR holds another\n"
    "campaign; 2 usage; 3 some run failed (its row says why), or an output file or directory\n"
    "could not be written (the message names it; the campaign stops); 4 DIR is in use by\n"
    "another campaign.\n";

// kHelp with the default run limit filled in from its one definition (campaign.hpp).
std::string HelpText() {
  std::string h = kHelp;
  const std::string mark = "%MAX_RUNS%";
  h.replace(h.find(mark), mark.size(), std::to_string(kDefaultMaxRuns));
  return h;
}

// Exit statuses (kHelp, docs/SCENARIOS.md "Exit status").
constexpr int kExitOk = 0;
constexpr int kExitBadCampaign = 1;  // bad campaign or scenario, or DIR holds another campaign
constexpr int kExitUsage = 2;
constexpr int kExitFailed = 3;       // a run failed, or an output could not be written
constexpr int kExitBusy = 4;         // DIR is locked by another campaign

// An output file or directory that cannot be written: the campaign stops with kExitFailed.
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

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

// What a run's directory holds from an earlier campaign in the same DIR.
enum class Prior {
  kNone,      // nothing to keep: no summary, other overrides, or an interrupted run
  kFinished,  // a summary.json (status other than "failed") under the same overrides
  kFailed,    // a summary.json with status "failed" (not interrupted) under the same overrides
};

Prior PriorRun(const fs::path &dir, const CampaignRun &r) {
  const json ov = ReadJson(dir / "overrides.json");
  const json sum = ReadJson(dir / "summary.json");
  if (!ov.is_array() || !sum.is_object() || !sum.contains("status")) return Prior::kNone;
  std::vector<std::string> overrides;
  for (const json &o : ov) {
    if (!o.is_string()) return Prior::kNone;
    overrides.push_back(o.get<std::string>());
  }
  if (overrides != r.overrides) return Prior::kNone;
  // An interrupted run (SIGTERM/SIGINT, e.g. the campaign killed) is not done: it runs again.
  if (sum.value("failure", json()) == json("interrupted")) return Prior::kNone;
  return sum["status"] == json("failed") ? Prior::kFailed : Prior::kFinished;
}

// Starts `uvms run` for one run with its output (stdout and stderr) into `log_fd` (run.out,
// opened by the caller, close-on-exec). Returns the child's pid, or -1 (errno set).
pid_t SpawnRun(const std::string &self, const Campaign &c, const CampaignRun &r,
               const fs::path &dir, int log_fd) {
  std::vector<std::string> argv = {self, "run", c.base, "--out", dir.string(), "--transport",
                                   c.transport};
  for (const auto &o : r.overrides) {
    argv.push_back("--set");
    argv.push_back(o);
  }
  std::vector<char *> cargs;
  for (auto &a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  const std::string exec_error = "uvms campaign: cannot execute " + self + ": ";
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);
    if (dup2(log_fd, 1) < 0 || dup2(log_fd, 2) < 0) _exit(127);
    execv(cargs[0], cargs.data());
    // Into run.out, which the results row points to (no summary.json).
    const char *why = std::strerror(errno);
    if (write(2, exec_error.data(), exec_error.size()) < 0 || write(2, why, std::strlen(why)) < 0 ||
        write(2, "\n", 1) < 0) {
    }
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
  std::size_t max_runs{kDefaultMaxRuns};
  bool dry_run{false};
  bool force_new{false};     // run in a DIR of another campaign: every run again
  bool retry_failed{false};  // failed runs of an earlier campaign in DIR run again
};

// Parses the command line; returns an exit code to stop with, or -1 to go on.
int ParseCliArgs(const std::vector<std::string> &args, CliArgs &a, std::ostream &out,
                 std::ostream &err) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string &o = args[i];
    if (o == "-h" || o == "--help") {
      out << HelpText();
      return kExitOk;
    }
    const bool takes_value = o == "--out" || o == "-j" || o == "--jobs" || o == "--transport" ||
                             o == "--set" || o == "--max-runs";
    if (takes_value && i + 1 >= args.size()) {
      err << "uvms campaign: error: " << o << " needs a value\n";
      return kExitUsage;
    }
    if (o == "--out") {
      a.out_dir = args[++i];
    } else if (o == "-j" || o == "--jobs") {
      const std::string v = args[++i];
      char *end = nullptr;
      const long n = std::strtol(v.c_str(), &end, 10);
      if (end == v.c_str() || *end != '\0' || n < 1 || n > 256) {
        err << "uvms campaign: error: -j needs a count 1..256, got " << v << '\n';
        return kExitUsage;
      }
      a.jobs = unsigned(n);
    } else if (o == "--transport") {
      a.transport = args[++i];
    } else if (o == "--set") {
      a.extra_sets.push_back(args[++i]);
    } else if (o == "--max-runs") {
      const std::string v = args[++i];
      char *end = nullptr;
      errno = 0;
      const unsigned long long n = std::strtoull(v.c_str(), &end, 10);
      if (v.empty() || !std::isdigit(static_cast<unsigned char>(v[0])) || *end != '\0' ||
          errno == ERANGE || n < 1 || n > std::numeric_limits<std::size_t>::max()) {
        err << "uvms campaign: error: --max-runs needs a run count >= 1, got " << v << '\n';
        return kExitUsage;
      }
      a.max_runs = std::size_t(n);
    } else if (o == "--dry-run") {
      a.dry_run = true;
    } else if (o == "--force-new") {
      a.force_new = true;
    } else if (o == "--retry-failed") {
      a.retry_failed = true;
    } else if (!o.empty() && o[0] == '-') {
      err << "uvms campaign: error: unknown option " << o << "\n(see uvms campaign --help)\n";
      return kExitUsage;
    } else if (a.file.empty()) {
      a.file = o;
    } else {
      err << "uvms campaign: error: unexpected argument " << o << '\n';
      return kExitUsage;
    }
  }
  if (a.file.empty() || (a.out_dir.empty() && !a.dry_run)) {
    err << "uvms campaign: error: needs FILE.toml and --out DIR\n(see uvms campaign --help)\n";
    return kExitUsage;
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

// The campaign, expanded, with every run's scenario checked; its provenance and identity.
struct Loaded {
  Campaign c;
  Provenance prov;
  std::string identity;  // CampaignIdentity (campaign.hpp): lowercase hex SHA-256
  std::string version;   // the project version hashed into the identity (= provenance's)
};

Loaded LoadChecked(const CliArgs &a) {
  const std::string text = ReadOrThrow(a.file);
  Loaded l;
  Campaign &c = l.c;
  c = ParseCampaign(text, a.file, a.extra_sets, a.max_runs);
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
  const std::string base_bytes = ReadOrThrow(c.base);
  l.prov = CampaignProvenance(text, a.extra_sets, base_bytes);
  for (const auto &[k, v] : l.prov)
    if (k == "version") l.version = v;
  l.identity = CampaignIdentity(text, base_bytes, a.extra_sets, l.version);
  return l;
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

json PlanJson(const Campaign &c, const Provenance &prov, const std::string &identity) {
  json plan;
  plan["campaign"] = fs::absolute(c.path).lexically_normal().string();
  plan["identity"] = identity;
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
      << "results): " << stray.front() << (stray.size() > 1 ? ", ..." : "") << '\n' << std::flush;
}

// Up to five ids joined with ", ", then ", ..." when there are more.
std::string IdList(const std::vector<std::string> &ids) {
  std::string s;
  for (size_t i = 0; i < ids.size() && i < 5; ++i) s += (i ? ", " : "") + ids[i];
  return ids.size() > 5 ? s + ", ..." : s;
}

// Makes a run's directory ready for a new run: the directory exists, no summary.json of an
// earlier run is left, overrides.json holds the run's overrides. Returns the descriptor of a
// fresh run.out (close-on-exec). Every step is checked: throws OutputError naming the path.
int PrepareRunDir(const fs::path &dir, const CampaignRun &r) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!ec && !fs::is_directory(dir, ec) && !ec)
    ec = std::make_error_code(std::errc::not_a_directory);
  if (ec)
    throw OutputError("cannot create the run directory " + dir.string() + ": " + ec.message());
  const fs::path summary = dir / "summary.json";
  fs::remove(summary, ec);  // no error when there is none
  if (ec) throw OutputError("cannot remove the old " + summary.string() + ": " + ec.message());
  try {
    WriteTextFileAtomic(json(r.overrides).dump(2) + "\n", (dir / "overrides.json").string());
  } catch (const std::exception &e) {
    throw OutputError(e.what());
  }
  const fs::path log = dir / "run.out";
  const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) throw OutputError("cannot create " + log.string() + ": " + std::strerror(errno));
  return fd;
}

struct RunOptions {
  unsigned jobs{1};
  bool force_new{false};     // no earlier run counts as done
  bool retry_failed{false};  // an earlier failed run is run again
};

// Runs what is not done yet, `jobs` at a time, with progress (each line flushed, so a pipe or
// a `tee` sees it as it happens). Returns 0, or kExitFailed when a run cannot be prepared or
// started: then no further run is started, the running ones are waited for, and the message
// names the path and the cause.
int ExecuteRuns(const Campaign &c, const fs::path &root, const RunOptions &o, std::ostream &out,
                std::ostream &err) {
  std::error_code ec;
  const fs::path self_path = fs::read_symlink("/proc/self/exe", ec);
  if (ec) {
    err << "uvms campaign: error: cannot find this program's path (/proc/self/exe): "
        << ec.message() << '\n';
    return kExitFailed;
  }
  const std::string self = self_path.string();
  std::vector<const CampaignRun *> todo;
  std::vector<std::string> kept_failed, retried;
  for (const CampaignRun &r : c.runs) {
    const Prior prior = o.force_new ? Prior::kNone : PriorRun(root / "runs" / r.id, r);
    if (prior == Prior::kNone) {
      todo.push_back(&r);
    } else if (prior == Prior::kFailed && o.retry_failed) {
      todo.push_back(&r);
      retried.push_back(r.id);
    } else if (prior == Prior::kFailed) {
      kept_failed.push_back(r.id);
    }
  }
  const size_t total = c.runs.size(), skipped = total - todo.size();
  out << "uvms campaign: " << c.name << ": " << total << " runs (" << skipped
      << " already done), " << o.jobs << " at a time, transport " << c.transport << '\n'
      << std::flush;
  if (!kept_failed.empty())
    out << "uvms campaign: note: " << kept_failed.size() << " of the done runs failed and "
        << (kept_failed.size() == 1 ? "is" : "are") << " kept as "
        << (kept_failed.size() == 1 ? "it is" : "they are")
        << " (--retry-failed runs failed runs again): " << IdList(kept_failed) << '\n'
        << std::flush;
  if (!retried.empty())
    out << "uvms campaign: --retry-failed: " << retried.size() << " failed run"
        << (retried.size() == 1 ? "" : "s") << " run again: " << IdList(retried) << '\n'
        << std::flush;
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
    else
      out << line.str() << "  " << finished->id << (rc == 0 ? " finished" : " FAILED") << '\n'
          << std::flush;
  };
  std::string stop;  // why the campaign stopped starting runs ("" while it goes on)
  while ((stop.empty() && next < todo.size()) || !running.empty()) {
    while (stop.empty() && next < todo.size() && running.size() < o.jobs) {
      const CampaignRun *r = todo[next];
      int log_fd = -1;
      try {
        log_fd = PrepareRunDir(root / "runs" / r->id, *r);
      } catch (const OutputError &e) {
        stop = std::string("run ") + r->id + ": " + e.what();
      }
      const pid_t pid = stop.empty() ? SpawnRun(self, c, *r, root / "runs" / r->id, log_fd) : -1;
      const int spawn_errno = errno;
      if (log_fd >= 0) close(log_fd);
      if (stop.empty() && pid < 0)
        stop = "cannot start run " + r->id + ": " + std::strerror(spawn_errno);
      if (!stop.empty()) {
        err << "uvms campaign: error: " << stop << '\n';  // at once, not after the running runs
        break;
      }
      ++next;
      running[pid] = r;
    }
    if (running.empty()) break;
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
  if (tty) out << '\n' << std::flush;
  if (!stop.empty()) {
    err << "uvms campaign: the campaign stopped: "
        << todo.size() - next << " of " << todo.size()
        << " runs to do were not started (the started ones ran to their end); results not "
           "written\n";
    return kExitFailed;
  }
  return kExitOk;
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
int WriteResults(const Campaign &c, const fs::path &root, const Provenance &prov,
                 const std::string &identity) {
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
  results["identity"] = identity;
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

// The lock of one --out DIR: an flock(2) on DIR/.campaign.lock, held for the whole campaign
// by this open file description (close-on-exec, so no run inherits it). The kernel drops it
// when the process ends, however it ends: a crashed campaign leaves no stale lock. The file
// stays (removing it would race with a campaign that has just opened it); it holds the pid of
// the campaign holding the lock, for the message of a refused second campaign.
class OutDirLock {
 public:
  OutDirLock() = default;
  OutDirLock(const OutDirLock &) = delete;
  OutDirLock &operator=(const OutDirLock &) = delete;
  ~OutDirLock() {
    if (fd_ >= 0) close(fd_);
  }

  // Returns kExitOk with the lock held, kExitBusy when another campaign holds it, or
  // kExitFailed when the lock file cannot be created or written; the message is in `err`.
  int Acquire(const fs::path &root, std::ostream &err) {
    const fs::path path = root / ".campaign.lock";
    fd_ = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd_ < 0) {
      err << "uvms campaign: error: cannot create the lock file " << path.string() << ": "
          << std::strerror(errno) << '\n';
      return kExitFailed;
    }
    if (flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      const int e = errno;
      if (e != EWOULDBLOCK) {
        err << "uvms campaign: error: cannot lock " << path.string() << ": " << std::strerror(e)
            << '\n';
        return kExitFailed;
      }
      char buf[32] = {};
      const ssize_t n = pread(fd_, buf, sizeof buf - 1, 0);
      std::string holder = n > 0 ? std::string(buf, size_t(n)) : std::string();
      while (!holder.empty() && !std::isdigit(static_cast<unsigned char>(holder.back())))
        holder.pop_back();
      err << "uvms campaign: error: " << root.string() << " is in use by another campaign"
          << (holder.empty() ? std::string() : " (process " + holder + ")")
          << ": it holds the lock " << path.string()
          << ". One campaign at a time per --out: wait until it ends, or give another --out\n";
      return kExitBusy;
    }
    const std::string pid = std::to_string(getpid()) + "\n";
    if (ftruncate(fd_, 0) != 0 || pwrite(fd_, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
      err << "uvms campaign: error: cannot write " << path.string() << ": "
          << std::strerror(errno) << '\n';
      return kExitFailed;
    }
    return kExitOk;
  }

 private:
  int fd_{-1};
};

// What an --out DIR holds already: the identity in its plan.json ("" when there is no
// plan.json, it is unreadable or has no identity), whether runs/ has run directories, and
// which inputs other than the campaign file differ from this campaign's, per the plan's
// provenance and transport (empty when only the campaign file's bytes differ).
struct PriorCampaign {
  std::string identity;
  bool has_runs{false};
  std::vector<std::string> differing;  // e.g. "the base scenario file (scenario_sha256 a → b)"
};

PriorCampaign ReadPriorCampaign(const fs::path &root, const Loaded &l) {
  PriorCampaign p;
  const json plan = ReadJson(root / "plan.json");
  if (plan.is_object() && plan.contains("identity") && plan["identity"].is_string())
    p.identity = plan["identity"].get<std::string>();
  std::error_code ec;
  for (const auto &e : fs::directory_iterator(root / "runs", ec)) {
    std::error_code ec2;
    if (e.is_directory(ec2)) {
      p.has_runs = true;
      break;
    }
  }
  const json prov = plan.is_object() ? plan.value("provenance", json()) : json();
  auto compare = [&](const std::string &what, const std::string &key, const std::string &now,
                     const json &was) {
    if (was.is_string() && was.get<std::string>() == now) return;
    const std::string old = was.is_string() ? was.get<std::string>() : std::string("(none)");
    p.differing.push_back(what + " (" + key + " \"" + old + "\" then, \"" + now + "\" now)");
  };
  std::string sha, sets;
  for (const auto &[k, v] : l.prov) {
    if (k == "scenario_sha256") sha = v;
    if (k == "campaign_sets") sets = v;
  }
  const auto get = [](const json &o, const char *k) {
    return o.is_object() ? o.value(k, json()) : json();
  };
  compare("the base scenario file's bytes", "scenario_sha256", sha, get(prov, "scenario_sha256"));
  compare("the --set overrides", "campaign_sets", sets, get(prov, "campaign_sets"));
  compare("the project version", "version", l.version, get(prov, "version"));
  compare("the transport", "transport", l.c.transport, get(plan, "transport"));
  return p;
}

// The refusal of a campaign whose identity is not DIR's (exit 1): both identities, what is
// hashed, what differs as far as DIR's plan.json tells, and how to go on.
void ExplainMismatch(const CliArgs &a, const Loaded &l, const PriorCampaign &prior,
                     std::ostream &err) {
  const fs::path root(a.out_dir);
  err << "uvms campaign: error: " << root.string() << " holds another campaign: ";
  if (prior.identity.empty())
    err << "it has run directories under runs/ but its plan.json has no identity (a campaign of "
           "an older uvms or of another kind, or no plan.json)";
  else
    err << "its plan.json has identity " << prior.identity;
  err << ", this campaign's identity is " << l.identity << ".\n"
      << "uvms campaign: the identity is the SHA-256 of the campaign file's bytes (" << a.file
      << "), the base scenario file's bytes (" << l.c.base << "), the --set overrides in order ("
      << a.extra_sets.size() << " given) and the project version (" << l.version
      << "); which of them differs is not recorded";
  if (!prior.differing.empty()) {
    err << ", but the provenance in its plan.json says these differ: ";
    for (size_t i = 0; i < prior.differing.size(); ++i)
      err << (i ? "; " : "") << prior.differing[i];
  }
  err << ".\nuvms campaign: nothing was changed. To run this campaign in " << root.string()
      << " anyway, every run again (plan.json replaced, each run's directory overwritten), add "
         "--force-new; or give another --out.\n";
}

// --force-new: no earlier summary.json of a planned run may count as done, not even after an
// interruption of this campaign, so they all go before the new plan.json is written.
void ForgetPlannedRuns(const Campaign &c, const fs::path &root) {
  for (const CampaignRun &r : c.runs) {
    const fs::path summary = root / "runs" / r.id / "summary.json";
    std::error_code ec;
    fs::remove(summary, ec);  // no error when there is none
    if (ec) throw OutputError("cannot remove the old " + summary.string() + ": " + ec.message());
  }
}

}  // namespace

int RunCampaignCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  CliArgs a;
  if (const int rc = ParseCliArgs(args, a, out, err); rc >= 0) return rc;
  Loaded l;
  try {
    l = LoadChecked(a);
  } catch (const CampaignError &e) {
    err << "uvms campaign: error: " << e.what() << '\n';
    return kExitBadCampaign;
  }
  const Campaign &c = l.c;
  if (a.dry_run) {
    PrintPlan(c, out);
    return kExitOk;
  }
  const fs::path root(a.out_dir);
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec) {
    err << "uvms campaign: error: cannot create the output directory " << root.string() << ": "
        << ec.message() << '\n';
    return kExitFailed;
  }
  OutDirLock lock;  // held until this function returns (or the process ends)
  if (const int rc = lock.Acquire(root, err); rc != kExitOk) return rc;
  const PriorCampaign prior = ReadPriorCampaign(root, l);
  const bool other = prior.identity.empty() ? prior.has_runs : prior.identity != l.identity;
  // The campaign file alone changed (a sweep value or a seed added, a [set] value changed): the
  // same campaign, edited. Its runs are checked one by one (a run is kept only under its exact
  // overrides), so an extended campaign runs only its new runs.
  const bool edited = other && !prior.identity.empty() && prior.differing.empty();
  if (other && !edited && !a.force_new) {
    ExplainMismatch(a, l, prior, err);
    return kExitBadCampaign;
  }
  if (edited && !a.force_new)
    out << "uvms campaign: note: the campaign file changed since " << (root / "plan.json").string()
        << " (identity " << prior.identity << ", now " << l.identity
        << "); the base scenario, the --set overrides, the version and the transport are the "
           "same, so every run whose overrides are unchanged is kept\n"
        << std::flush;
  try {
    if (a.force_new) {
      out << "uvms campaign: --force-new: ";
      if (!other)
        out << root.string() << " holds this campaign already";
      else if (prior.identity.empty())
        out << root.string() << " held runs of a campaign without an identity";
      else
        out << root.string() << " held campaign " << prior.identity;
      out << "; plan.json is replaced and every run (" << c.runs.size() << ") is run again\n"
          << std::flush;
      ForgetPlannedRuns(c, root);
    }
    fs::create_directories(root / "runs", ec);
    if (ec)
      throw OutputError("cannot create " + (root / "runs").string() + ": " + ec.message());
    WriteTextFileAtomic(PlanJson(c, l.prov, l.identity).dump(2) + "\n",
                        (root / "plan.json").string());
  } catch (const std::exception &e) {
    err << "uvms campaign: error: " << e.what() << '\n';
    return kExitFailed;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const RunOptions opts{a.jobs, a.force_new, a.retry_failed};
  if (const int rc = ExecuteRuns(c, root, opts, out, err); rc != kExitOk) return rc;
  int failed = 0;
  try {
    failed = WriteResults(c, root, l.prov, l.identity);
  } catch (const std::exception &e) {
    err << "uvms campaign: error: cannot write the results: " << e.what() << '\n';
    return kExitFailed;
  }
  const size_t total = c.runs.size();
  const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out << "uvms campaign: " << c.name << ": " << (total - size_t(failed)) << "/" << total
      << " runs finished in " << std::fixed << std::setprecision(1) << el << " s; "
      << (root / "results.csv").string() << '\n' << std::flush;
  return failed == 0 ? kExitOk : kExitFailed;
}

}  // namespace uvms::sil
