// SPDX-License-Identifier: Apache-2.0
// campaign_cmd.cpp: `uvms campaign` (campaign_cmd.hpp).
#include "cli/campaign_cmd.hpp"

#include "cli/exit_status.hpp"
#include "cli/run_cmd.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <iostream>
#include <thread>

#include <nlohmann/json.hpp>

#include "campaign/campaign.hpp"
#include "campaign/campaign_exec.hpp"
#include "campaign/campaign_lock.hpp"
#include "campaign/campaign_results.hpp"
#include "campaign/summary_sync.hpp"
#include "run/provenance.hpp"
#include "run/summary_writer.hpp"
#include "scenario/scenario.hpp"
#include "scenario/toml_bounds.hpp"

namespace uvms::sil {
namespace fs = std::filesystem;
namespace {

using json = nlohmann::ordered_json;

const char *kHelp =
    "usage: uvms campaign FILE.toml --out DIR [-j N] [--transport memq|udpm]\n"
    "                     [--set section.key=value]... [--max-runs N] [--retry-failed]\n"
    "                     [--force-new] [--logs all|failed|none|ID[,ID...]] [--shard I/N]\n"
    "                     [--dry-run | --plan-only]\n"
    "       uvms campaign FILE.toml --out DIR [--set section.key=value]... --merge\n\n"
    "Expands a campaign (a base scenario, fixed overrides in [set], [[sweep]] axes whose keys\n"
    "vary together, combined as a Cartesian product, and optional [replicates]: one run per\n"
    "seed of the runs whose `when` key is true) into runs, checks every run's scenario first,\n"
    "then runs them N at a time (default: all cores). A run's id is its axis labels joined\n"
    "with '_' (plus _s<N> for a replicate), so adding a sweep value or a seed renames nothing.\n"
    "Finished runs (a summary.json of the plan's run: its overrides, session, pinned base and\n"
    "version; not interrupted) are kept, so an interrupted or extended campaign only runs what\n"
    "is new. The base scenario is read once and pinned in DIR/inputs/<sha256>/; every run reads\n"
    "that copy (uvms run --scenario-sha256), never the live file. A run that failed\n"
    "is kept as it is too (its row stays failed); --retry-failed runs the failed runs again.\n"
    "--set adds an override to every run, after the campaign's [set] and before the sweep\n"
    "values (so a sweep still wins), e.g. to shorten every run for a smoke test.\n"
    "--max-runs N refuses a campaign that expands to more than N runs (default %MAX_RUNS%).\n"
    "--dry-run checks the campaign and every run's scenario, prints the plan (one line per\n"
    "run: id and swept values) and the run count, and writes nothing (--out is optional).\n"
    "--logs: which runs keep their run.lcmlog (about 5.5 MB for a 60 s run; summary.json holds\n"
    "every per-tick analysis): all (default); failed (only runs that failed); none (no run\n"
    "writes one: uvms run --no-log; --no-logs is the same); or run ids and shell patterns,\n"
    "comma-separated (e.g. IV_stagnant,VII_unsteady_s*), which keep theirs, as failed runs do.\n"
    "An id or pattern that names no run of the plan is an error. With --logs given, a finished\n"
    "run kept from an earlier campaign without the log the policy keeps is run again to write\n"
    "it; without --logs, done runs are kept as they are.\n"
    "A run is run in its directory DIR/runs/<id> (its working directory) with a\n"
    "session derived from its inputs, so its run.lcmlog is the same byte for byte whichever\n"
    "engine runs it (docs/CAMPAIGNS.md). Its summary.json is not synced to disk one by one\n"
    "(uvms run --no-summary-fsync, which the plan's arguments do not show): the campaign syncs\n"
    "DIR/runs' file system once after its runs (and --merge before it writes results), on\n"
    "Linux 5.8 or later and not on FUSE (elsewhere each run syncs its own); a summary whose\n"
    "write failed is removed, so its run runs again, and the campaign exits 3.\n"
    "--shard I/N runs the plan's runs whose index k (0-based, plan order) has k mod N = I-1, in\n"
    "a DIR shared with the other shards (shards hold a shared lock; each shard its own one),\n"
    "and writes no results; --merge then checks that every run of the plan has a result and\n"
    "writes results.csv and results.json (exit 3, naming them, if some have none).\n"
    "--plan-only does all a campaign does before its first run (lock, identity, plan.json),\n"
    "then prints the plan as JSON Lines: a first line (identity, name, out, uvms, total,\n"
    "shard, runs: the count of lines that follow), then one line per run (id, dir, uvms\n"
    "arguments, overrides.json text, state todo|done|failed), for another engine to run\n"
    "(tools/campaign-dask); memory stays flat however many runs there are.\n"
    "Writes DIR/plan.json, DIR/runs/<id>/..., DIR/results.csv and DIR/results.json; plan.json\n"
    "and results.json carry the provenance of this binary and the campaign (docs/SCENARIOS.md).\n"
    "DIR belongs to one campaign, named by its identity: the SHA-256 of the campaign file's\n"
    "bytes, the base scenario file's bytes, the --set overrides in order and the project\n"
    "version, written into plan.json and results.json. A campaign whose identity differs from\n"
    "the one in DIR/plan.json (or DIR with runs but no identity) is refused and nothing is\n"
    "changed, unless only the campaign file changed (say, extended), per plan.json's\n"
    "provenance: the same base scenario bytes, --set overrides, version and transport; then\n"
    "runs are kept one by one as above. --force-new starts the campaign afresh in any DIR:\n"
    "a new generation (no earlier run counts, in any shard), the old results removed, plan.json\n"
    "replaced and every run run again. A DIR of an older uvms campaign (no pinned inputs) is\n"
    "refused; --force-new runs it afresh.\n"
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
constexpr int kExitBadCampaign = kExitBadInput;  // bad campaign or scenario, or DIR holds another
constexpr int kExitBusy = 4;                      // DIR is locked by another campaign

struct CliArgs {
  std::string file, out_dir, transport;
  std::vector<std::string> extra_sets;
  unsigned jobs{std::max(1u, std::thread::hardware_concurrency())};
  std::size_t max_runs{kDefaultMaxRuns};
  bool dry_run{false};
  bool plan_only{false};     // prepare DIR and print the plan as JSON; run nothing
  bool merge{false};         // write the results of the runs in DIR; run nothing
  std::string logs;          // --logs (or --no-logs: "none"); "" until given (then "all")
  unsigned shard_index{0};   // --shard I/N: I (1-based); 0: no shard, the whole plan
  unsigned shard_count{0};   // N
  bool force_new{false};     // run in a DIR of another campaign: every run again
  bool retry_failed{false};  // failed runs of an earlier campaign in DIR run again
};

// --shard I/N into `a`; false when it is not one (1 <= I <= N <= 100000).
bool ParseShard(const std::string &v, CliArgs &a) {
  const size_t slash = v.find('/');
  const auto digits = [](const std::string &t) {
    return !t.empty() && t.size() <= 6 &&
           std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  if (slash == std::string::npos || !digits(v.substr(0, slash)) || !digits(v.substr(slash + 1)))
    return false;
  const unsigned i = unsigned(std::stoul(v.substr(0, slash)));
  const unsigned n = unsigned(std::stoul(v.substr(slash + 1)));
  if (i < 1 || n < i || n > 100000) return false;
  a.shard_index = i;
  a.shard_count = n;
  return true;
}

// The options that exclude each other; returns kExitUsage (with a message) or -1.
int CheckModes(const CliArgs &a, std::ostream &err) {
  const char *clash = nullptr;
  if (a.dry_run && (a.plan_only || a.merge)) clash = "--dry-run goes with neither --plan-only nor --merge";
  else if (a.plan_only && a.merge) clash = "--plan-only and --merge exclude each other";
  else if (a.merge && (a.shard_count != 0 || a.force_new || a.retry_failed || !a.logs.empty()))
    clash = "--merge runs nothing: it takes no --shard, --force-new, --retry-failed, --logs or "
            "--no-logs";
  if (clash == nullptr) return -1;
  err << "uvms campaign: error: " << clash << "\n(see uvms campaign --help)\n";
  return kExitUsage;
}

// The switch an option without a value sets, or nullptr when o is not one.
bool CliArgs::*FlagOf(const std::string &o) {
  static const std::pair<const char *, bool CliArgs::*> kFlags[] = {
      {"--dry-run", &CliArgs::dry_run},     {"--plan-only", &CliArgs::plan_only},
      {"--merge", &CliArgs::merge},         {"--force-new", &CliArgs::force_new},
      {"--retry-failed", &CliArgs::retry_failed}};
  for (const auto &[name, flag] : kFlags)
    if (o == name) return flag;
  return nullptr;
}

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
                             o == "--set" || o == "--max-runs" || o == "--shard" || o == "--logs";
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
    } else if (o == "--shard") {
      if (!ParseShard(args[++i], a)) {
        err << "uvms campaign: error: --shard needs I/N with 1 <= I <= N <= 100000, got "
            << args[i] << '\n';
        return kExitUsage;
      }
    } else if (o == "--logs" || o == "--no-logs") {
      const std::string v = o == "--logs" ? args[++i] : "none";  // --no-logs: --logs none
      if (!a.logs.empty() && a.logs != v) {
        err << "uvms campaign: error: --logs given twice (" << a.logs << ", " << v
            << "); --no-logs is --logs none\n";
        return kExitUsage;
      }
      try {
        (void)ParseLogPolicy(v);
      } catch (const std::invalid_argument &e) {
        err << "uvms campaign: error: " << e.what() << "\n(see uvms campaign --help)\n";
        return kExitUsage;
      }
      a.logs = v;
    } else if (bool CliArgs::*flag = FlagOf(o)) {
      a.*flag = true;
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
  return CheckModes(a, err);
}

// A campaign or base scenario file's bytes: a regular file of bounded size (a directory, a device
// such as /dev/urandom or a FIFO is refused at once, never read). Throws CampaignError.
std::string ReadOrThrow(const std::string &path) {
  std::string bytes, err;
  if (!ReadBoundedFile(path, &bytes, &err)) throw CampaignError(err);
  return bytes;
}

// The plan.json format this uvms writes: 2 since the base scenario is pinned in DIR/inputs and
// plan.json keeps a generation. A DIR of an earlier format is refused (PrepareOutDir).
constexpr int kPlanFormat = 2;

// The campaign, expanded, with every run's scenario checked; its provenance and identity.
struct Loaded {
  Campaign c;
  RunInputs In() const {
    return RunInputs{&c, base_pinned, base_bytes, base_sha256, generation, version};
  }
  Provenance prov;
  std::string identity;  // CampaignIdentity (campaign.hpp): lowercase hex SHA-256
  std::string version;   // the project version hashed into the identity (= provenance's)
  std::string base_bytes;   // the base scenario file's bytes, read once (every run uses these)
  std::string base_sha256;  // their SHA-256
  std::string base_pinned;  // the absolute path of their copy in DIR/inputs (PinnedPath)
  std::uint64_t generation{0};  // DIR's generation (PrepareOutDir; plan.json)
};

// The base scenario's bytes, read once: every run's scenario is checked from them and every run
// reads their pinned copy, never the live file again.
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
  CheckLogPolicy(ParseLogPolicy(a.logs.empty() ? "all" : a.logs), c);
  l.base_bytes = ReadOrThrow(c.base);
  l.base_sha256 = Sha256Hex(l.base_bytes);
  for (const CampaignRun &r : c.runs) {
    try {
      (void)ParseScenario(l.base_bytes, c.base, r.overrides);
    } catch (const ScenarioError &e) {
      throw CampaignError("run " + r.id + ": " + e.what());
    }
  }
  l.prov = CampaignProvenance(text, a.extra_sets, l.base_bytes);
  for (const auto &[k, v] : l.prov)
    if (k == "version") l.version = v;
  l.identity = CampaignIdentity(text, l.base_bytes, a.extra_sets, l.version);
  return l;
}

// The runs of this invocation: the whole plan, or the shard's (k mod N == I - 1).
std::vector<const CampaignRun *> SelectRuns(const Campaign &c, const CliArgs &a) {
  std::vector<const CampaignRun *> mine;
  for (size_t k = 0; k < c.runs.size(); ++k)
    if (a.shard_count == 0 || k % a.shard_count == a.shard_index - 1) mine.push_back(&c.runs[k]);
  return mine;
}

// Where the base scenario's bytes are pinned, relative to DIR: inputs/<sha256>/<file name> (the
// file name kept, since a scenario's default name is its file's stem).
std::string PinnedRelative(const Loaded &l) {
  return (fs::path("inputs") / l.base_sha256 / fs::path(l.c.base).filename()).string();
}

json PlanJson(const Loaded &l) {
  const Campaign &c = l.c;
  const Provenance &prov = l.prov;
  const std::string &identity = l.identity;
  json plan;
  plan["campaign"] = fs::absolute(c.path).lexically_normal().string();
  plan["format"] = kPlanFormat;
  plan["identity"] = identity;
  plan["generation"] = l.generation;
  plan["name"] = c.name;
  plan["description"] = c.description;
  plan["base"] = c.base;
  plan["inputs"] = {{"base", {{"path", PinnedRelative(l)}, {"sha256", l.base_sha256}}}};
  plan["transport"] = c.transport;
  plan["provenance"] = ProvenanceJson(prov);
  plan["replicates"] = ReplicatesJson(c.replicates);
  plan["runs"] = json::array();
  const RunInputs in = l.In();
  for (const CampaignRun &r : c.runs) {
    // argv: the `uvms run` arguments (in DIR/runs/<id>) that write the run with its log, so a
    // log the campaign did not keep can be made again, the same byte for byte (tools/report.py).
    json run = {{"id", r.id}, {"overrides", r.overrides},
                {"session", RunSession(l.base_bytes, r.overrides, l.generation)},
                {"argv", RunArgs(in, r, true)}};
    if (r.replicate) run["replicate"] = *r.replicate;
    plan["runs"].push_back(run);
  }
  return plan;
}

// --dry-run: the runs of this invocation (the plan, or the shard's), then the count.
void PrintPlan(const Campaign &c, const CliArgs &a, std::ostream &out) {
  const std::vector<const CampaignRun *> mine = SelectRuns(c, a);
  for (const CampaignRun *r : mine) {
    out << r->id;
    for (const auto &[k, v] : r->swept) out << "  " << k << '=' << v;
    out << '\n';
  }
  size_t replicated = 0;
  for (const CampaignRun *r : mine) replicated += r->replicate ? 1 : 0;
  out << "uvms campaign: " << c.name << ": " << mine.size() << (mine.size() == 1 ? " run" : " runs");
  if (a.shard_count != 0)
    out << " of shard " << a.shard_index << "/" << a.shard_count << " (" << c.runs.size()
        << " in the plan)";
  if (!c.replicates.key.empty())
    out << " (" << replicated << " of them replicates: " << c.replicates.values.size()
        << " values of " << c.replicates.key << ")";
  out << "; dry run, nothing written\n";
}

// What an --out DIR holds already: the identity in its plan.json ("" when there is no
// plan.json, it is unreadable or has no identity), whether runs/ has run directories, and
// which inputs other than the campaign file differ from this campaign's, per the plan's
// provenance and transport (empty when only the campaign file's bytes differ).
struct PriorCampaign {
  std::string identity;
  int format{0};                // plan.json's "format" (0: none, a plan of an older uvms)
  std::uint64_t generation{0};  // plan.json's "generation"
  bool has_plan{false};
  bool has_runs{false};
  std::vector<std::string> differing;  // e.g. "the base scenario file (scenario_sha256 a → b)"
};

PriorCampaign ReadPriorCampaign(const fs::path &root, const Loaded &l) {
  PriorCampaign p;
  // runs/ first, plan.json second: a campaign writes its plan.json before its first run
  // directory, so a shard starting beside another that is already running sees either no runs,
  // or runs and their plan (read the other way round it could see the runs of a plan that did
  // not exist yet when it looked, and take DIR for an older campaign's).
  std::error_code ec;
  for (const auto &e : fs::directory_iterator(root / "runs", ec)) {
    std::error_code ec2;
    if (e.is_directory(ec2)) {
      p.has_runs = true;
      break;
    }
  }
  const json plan = ReadJsonFile(root / "plan.json");
  p.has_plan = plan.is_object();
  if (p.has_plan && plan.contains("identity") && plan["identity"].is_string())
    p.identity = plan["identity"].get<std::string>();
  if (p.has_plan && plan.value("format", json()).is_number_integer())
    p.format = plan["format"].get<int>();
  if (p.has_plan && plan.value("generation", json()).is_number_unsigned())
    p.generation = plan["generation"].get<std::uint64_t>();
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

// --force-new: no earlier summary.json of a run of this invocation (the plan, or the shard's
// runs) may count as done, not even after an interruption, so they all go before the new
// plan.json is written.
void ForgetPlannedRuns(const std::vector<const CampaignRun *> &mine, const fs::path &root) {
  for (const CampaignRun *r : mine) {
    const fs::path summary = root / "runs" / r->id / "summary.json";
    std::error_code ec;
    fs::remove(summary, ec);  // no error when there is none
    if (ec) throw OutputError("cannot remove the old " + summary.string() + ": " + ec.message());
  }
}

// Writes results.csv and results.json and prints the closing line; exit 0 when every run
// finished, 3 when some failed or the results could not be written.
int WriteResultsAndReport(const Loaded &l, const fs::path &root, const std::string &took,
                          std::ostream &out, std::ostream &err) {
  ResultsWritten w;
  try {
    const RunInputs in = l.In();
    w = WriteResults(l.c, root, l.prov, l.identity, l.generation,
                     [&in](const CampaignRun &r) { return IdentityOf(in, r); });
  } catch (const std::exception &e) {
    err << "uvms campaign: error: cannot write the results: " << e.what() << '\n';
    return kExitFailed;
  }
  const int failed = w.failed;
  if (w.builds.size() > 1) {  // resumed or sharded with other binaries: said, not hidden
    out << "uvms campaign: note: the runs come from " << w.builds.size()
        << " builds (each row's provenance names its own):";
    for (const std::string &b : w.builds) out << "\n  " << b;
    out << '\n' << std::flush;
  }
  const size_t total = l.c.runs.size();
  out << "uvms campaign: " << l.c.name << ": " << (total - size_t(failed)) << "/" << total
      << " runs finished" << took << "; " << (root / "results.csv").string() << '\n'
      << std::flush;
  return failed == 0 ? kExitOk : kExitFailed;
}

// A shard's closing line (no results: the merge writes them); exit 0 or 3 as a campaign.
int ReportShard(const Loaded &l, const std::vector<const CampaignRun *> &mine,
                const fs::path &root, const RunOptions &o, const std::string &took,
                std::ostream &out) {
  size_t finished = 0;
  const RunInputs in = l.In();
  for (const CampaignRun *r : mine)
    finished += PriorRun(root / "runs" / r->id, *r, IdentityOf(in, *r)) == Prior::kFinished;
  out << "uvms campaign: " << l.c.name << ": shard " << o.shard_index << "/" << o.shard_count
      << ": " << finished << "/" << mine.size() << " runs finished" << took
      << "; results: uvms campaign ... --merge once every shard has run\n"
      << std::flush;
  return finished == mine.size() ? kExitOk : kExitFailed;
}

// The exit status of a lock attempt that did not hold the lock.
int LockExit(LockResult r) {
  switch (r) {
    case LockResult::kHeld: return kExitOk;
    case LockResult::kBusy: return kExitBusy;
    case LockResult::kBadFd: return kExitUsage;
    case LockResult::kFailed: break;
  }
  return kExitFailed;
}

// Creates DIR and takes its locks: exclusive for a campaign, --plan-only and --merge; shared
// plus the shard's own for --shard. Returns kExitOk with the locks held, or the exit status.
int LockOutDir(const CliArgs &a, const fs::path &root, const std::string &identity,
               CampaignLock &campaign, CampaignLock &shard, std::ostream &err) {
  std::error_code ec;
  fs::create_directories(root, ec);
  if (ec) {
    err << "uvms campaign: error: cannot create the output directory " << root.string() << ": "
        << ec.message() << '\n';
    return kExitFailed;
  }
  const bool sharded = a.shard_count != 0;
  if (const LockResult r = campaign.AcquireCampaign(root, sharded, err); r != LockResult::kHeld)
    return LockExit(r);
  if (!sharded) return kExitOk;
  return LockExit(shard.AcquireShard(root, a.shard_index, a.shard_count, identity, err));
}

// The refusal of a DIR written by an older uvms campaign (exit 1): its plan.json has no pinned
// inputs, so its runs cannot be told from runs of other inputs.
void ExplainOldFormat(const CliArgs &a, const PriorCampaign &prior, std::ostream &err) {
  err << "uvms campaign: error: " << a.out_dir << " was written by an older uvms campaign ("
      << (prior.has_plan ? "its plan.json has format " + std::to_string(prior.format)
                         : std::string("run directories under runs/ and no plan.json"))
      << ", this uvms writes format " << kPlanFormat
      << ": the base scenario pinned in DIR/inputs and every run checked against it); its runs "
         "cannot be checked against their inputs, so none is kept.\nuvms campaign: nothing was "
         "changed. Run again with --force-new (every run again in " << a.out_dir
      << "), or give another --out.\n";
}

// results.csv and results.json go before a plan.json of another identity or generation is
// written: a table never stands beside another campaign's plan, even if this one is
// interrupted before it writes its own.
void RemoveStaleResults(const fs::path &root, const PriorCampaign &prior, const Loaded &l) {
  if (prior.identity == l.identity && prior.generation == l.generation &&
      prior.format == kPlanFormat)
    return;
  for (const char *name : {"results.json", "results.csv"}) {
    std::error_code ec;
    fs::remove(root / name, ec);
    if (ec)
      throw OutputError("cannot remove the old " + (root / name).string() + " (a table of "
                        "another campaign): " + ec.message());
  }
}

// The base scenario's bytes pinned in DIR (PinnedRelative): written once, atomically; a copy
// already there is used only if its bytes hash right. Sets l.base_pinned to the path a run
// reads it by, relative to its own directory DIR/runs/<id> (the same for every engine and DIR,
// so summaries do not depend on where DIR is).
void PinInputs(const fs::path &root, Loaded &l) {
  const fs::path rel = PinnedRelative(l);
  const fs::path path = fs::absolute(root / rel).lexically_normal();
  std::string have, why;
  if (!ReadBoundedFile(path.string(), &have, &why) || Sha256Hex(have) != l.base_sha256) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    if (ec)
      throw OutputError("cannot create " + path.parent_path().string() + ": " + ec.message());
    WriteTextFileAtomic(l.base_bytes, path.string());
  }
  l.base_pinned = (fs::path("..") / ".." / rel).string();
}

// The generation of DIR's new plan: the prior plan's, or one more with --force-new over any
// earlier plan or runs (so no summary of theirs can match a run of the new plan), 0 in a new DIR.
std::uint64_t NextGeneration(const CliArgs &a, const PriorCampaign &prior) {
  if (!a.force_new) return prior.generation;
  if (!prior.has_plan && !prior.has_runs) return 0;
  return prior.generation + 1;
}

// Checks that DIR holds this campaign (or none, or this one edited; --force-new takes any) and
// writes its pinned inputs and its plan.json; --force-new forgets the earlier results of this
// invocation's runs, and its new generation those of every shard. Notes go to `note`. Returns
// kExitOk or the exit status.
int PrepareOutDir(const CliArgs &a, Loaded &l, const std::vector<const CampaignRun *> &mine,
                  const fs::path &root, std::ostream &note, std::ostream &err) {
  const PriorCampaign prior = ReadPriorCampaign(root, l);
  const bool old_format = (prior.has_plan && prior.format != kPlanFormat && !prior.identity.empty()) ||
                          (!prior.has_plan && prior.has_runs);
  if (old_format && !a.force_new) {
    ExplainOldFormat(a, prior, err);
    return kExitBadCampaign;
  }
  const bool other = prior.identity.empty() ? prior.has_runs : prior.identity != l.identity;
  // The campaign file alone changed (a sweep value or a seed added, a [set] value changed): the
  // same campaign, edited. Its runs are checked one by one (a run is kept only under its exact
  // overrides and inputs), so an extended campaign runs only its new runs.
  const bool edited = other && !prior.identity.empty() && prior.differing.empty();
  if (other && !edited && !a.force_new) {
    ExplainMismatch(a, l, prior, err);
    return kExitBadCampaign;
  }
  if (edited && !a.force_new)
    note << "uvms campaign: note: the campaign file changed since " << (root / "plan.json").string()
         << " (identity " << prior.identity << ", now " << l.identity
         << "); the base scenario, the --set overrides, the version and the transport are the "
            "same, so every run whose overrides are unchanged is kept\n"
         << std::flush;
  l.generation = NextGeneration(a, prior);
  try {
    if (a.force_new) {
      note << "uvms campaign: --force-new: ";
      if (!other && !old_format)
        note << root.string() << " holds this campaign already";
      else if (prior.identity.empty())
        note << root.string() << " held runs of a campaign without an identity";
      else
        note << root.string() << " held campaign " << prior.identity;
      note << "; plan.json is replaced (generation " << l.generation << ") and every run ("
           << mine.size() << ") is run again\n"
           << std::flush;
      ForgetPlannedRuns(mine, root);
    }
    std::error_code ec;
    fs::create_directories(root / "runs", ec);
    if (ec) throw OutputError("cannot create " + (root / "runs").string() + ": " + ec.message());
    PinInputs(root, l);
    RemoveStaleResults(root, prior, l);
    WriteTextFileAtomic(PlanJson(l).dump(2) + "\n", (root / "plan.json").string());
  } catch (const std::exception &e) {
    err << "uvms campaign: error: " << e.what() << '\n';
    return kExitFailed;
  }
  return kExitOk;
}

RunOptions OptionsOf(const CliArgs &a) {
  RunOptions o;
  o.jobs = a.jobs;
  o.force_new = a.force_new;
  o.retry_failed = a.retry_failed;
  o.logs = ParseLogPolicy(a.logs.empty() ? "all" : a.logs);
  o.logs_given = !a.logs.empty();
  o.shard_index = a.shard_index;
  o.shard_count = a.shard_count;
  // Each run a fork of this process running `uvms run`'s code (RunOptions::run_here).
  o.run_here = [](const std::vector<std::string> &run_args) {
    return RunRunCli(run_args, std::cout, std::cerr);
  };
  return o;
}

// --plan-only: the plan of this invocation as JSON Lines, a head line then a line per run, each
// written as it is made (docs/CAMPAIGNS.md "How a run is executed").
void PrintPlanJson(const Loaded &l, const std::vector<const CampaignRun *> &mine,
                   const fs::path &root, const RunOptions &o, std::ostream &out) {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  json plan;
  plan["identity"] = l.identity;
  plan["name"] = l.c.name;
  plan["out"] = fs::absolute(root).lexically_normal().string();
  plan["uvms"] = self.string();
  plan["total"] = l.c.runs.size();
  plan["shard"] = o.shard_count == 0
                      ? json()
                      : json{{"index", o.shard_index}, {"count", o.shard_count}};
  plan["generation"] = l.generation;
  // The pinned base scenario (path relative to DIR), bytes included: an engine whose workers
  // cannot see DIR lays them out beside the run as DIR has them (a run's argv reads
  // ../../<path>, and --scenario-sha256 checks the bytes).
  plan["inputs"] = {{"base", {{"path", PinnedRelative(l)}, {"sha256", l.base_sha256},
                              {"text", l.base_bytes}}}};
  plan["runs"] = mine.size();  // the number of run lines that follow
  out << plan.dump() << '\n';
  static const char *const kState[] = {"todo", "done", "failed"};
  const RunInputs in = l.In();
  for (const CampaignRun *r : mine)
    out << json{{"id", r->id},
                {"dir", "runs/" + r->id},
                {"argv", RunArgs(in, *r, o.logs.Writes())},
                {"keep_log", o.logs.KeepsFinished(r->id)},
                {"overrides_json", OverridesText(*r)},
                {"state", kState[int(StateOf(root, in, *r, o))]}}
               .dump()
        << '\n';
  out << std::flush;
}

// --merge: DIR must hold this campaign's plan and a result for every run of it; then the
// results are written. Returns the exit status.
int Merge(const CliArgs &a, Loaded &l, const fs::path &root, std::ostream &out,
          std::ostream &err) {
  const PriorCampaign prior = ReadPriorCampaign(root, l);
  if (prior.has_plan && prior.format != kPlanFormat && !prior.identity.empty()) {
    ExplainOldFormat(a, prior, err);
    return kExitBadCampaign;
  }
  if (prior.identity != l.identity) {
    ExplainMismatch(a, l, prior, err);
    return kExitBadCampaign;
  }
  l.generation = prior.generation;
  try {
    PinInputs(root, l);
  } catch (const std::exception &e) {
    err << "uvms campaign: error: " << e.what() << '\n';
    return kExitFailed;
  }
  std::vector<std::string> missing;
  std::string first_why;
  const RunInputs in = l.In();
  for (const CampaignRun &r : l.c.runs) {
    std::string why;
    if (PriorRun(root / "runs" / r.id, r, IdentityOf(in, r), &why) != Prior::kNone) continue;
    missing.push_back(r.id);
    if (first_why.empty() && !why.empty()) first_why = r.id + ": " + why;
  }
  if (!missing.empty()) {
    err << "uvms campaign: error: --merge: " << missing.size() << " of " << l.c.runs.size()
        << " runs have no result of this plan (identity " << l.identity << ", generation "
        << l.generation << ") in " << (root / "runs").string() << ": " << IdList(missing)
        << (first_why.empty() ? std::string() : " (" + first_why + ")")
        << ". Run the shards that hold them (or uvms campaign without --shard); results not "
           "written\n";
    return kExitFailed;
  }
  // A shard stopped before its own sync (killed after its runs) may have left its summaries
  // unsynced (SummarySync): the results list only summaries on disk.
  std::vector<std::string> ids;
  for (const CampaignRun &r : l.c.runs) ids.push_back(r.id);
  const std::string why = SummarySync(root / "runs").Sync(ids, out);
  if (!why.empty()) {
    err << "uvms campaign: error: --merge: " << why << "; results not written\n";
    return kExitFailed;
  }
  return WriteResultsAndReport(l, root, "", out, err);
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
  if (a.dry_run) {
    PrintPlan(l.c, a, out);
    return kExitOk;
  }
  const fs::path root(a.out_dir);
  CampaignLock campaign_lock, shard_lock;  // held until this function returns
  if (const int rc = LockOutDir(a, root, l.identity, campaign_lock, shard_lock, err); rc != kExitOk) return rc;
  if (a.merge) return Merge(a, l, root, out, err);
  const std::vector<const CampaignRun *> mine = SelectRuns(l.c, a);
  std::ostream &note = a.plan_only ? err : out;  // --plan-only: stdout is the JSON alone
  if (const int rc = PrepareOutDir(a, l, mine, root, note, err); rc != kExitOk) return rc;
  const RunOptions opts = OptionsOf(a);
  if (a.plan_only) {
    PrintPlanJson(l, mine, root, opts, out);
    return kExitOk;
  }
  const auto t0 = std::chrono::steady_clock::now();
  if (!ExecuteRuns(l.In(), mine, root, opts, out, err)) return kExitFailed;
  const double elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::ostringstream took;
  took << " in " << std::fixed << std::setprecision(1) << elapsed_s << " s";
  if (a.shard_count == 0) return WriteResultsAndReport(l, root, took.str(), out, err);
  return ReportShard(l, mine, root, opts, took.str(), out);
}

}  // namespace uvms::sil
