// SPDX-License-Identifier: Apache-2.0
// campaign_exec.hpp: how `uvms campaign` executes the runs of a campaign on this machine: what
// each run's state is given its directory, the `uvms run` arguments of a run (the one
// definition every engine uses, through --plan-only), and the local executor that runs them J
// at a time with progress (docs/CAMPAIGNS.md "How a run is executed").
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

#include "campaign/campaign.hpp"
#include "campaign/campaign_results.hpp"
#include "campaign/log_policy.hpp"

namespace uvms::sil {

/// An output file or directory that cannot be written: the campaign stops (exit 3).
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What a run needs besides its own overrides: the campaign and its base scenario, as pinned in
/// DIR before the first run (docs/CAMPAIGNS.md "Pinned inputs").
struct RunInputs {
  const Campaign *campaign{nullptr};
  std::string base_pinned;   ///< the pinned copy, relative to a run's directory DIR/runs/<id>:
                             ///< ../../inputs/<sha256>/<file name>
  std::string base_bytes;    ///< its bytes (hashed into each run's session, RunSession)
  std::string base_sha256;   ///< their SHA-256 (uvms run --scenario-sha256)
  std::uint64_t generation{0};  ///< DIR's generation (plan.json; RunSession)
  std::string version;       ///< the project version of this binary
};

/// The arguments of `uvms run` for run `r` (after the program's name), run in its own directory
/// (hence "--out ." and the pinned base by its path relative to it, whose bytes
/// --scenario-sha256 pins), with its session (RunSession) and its name <campaign>/<id> (so its
/// summary.json names the run, not the base scenario); `log` false adds --no-log.
std::vector<std::string> RunArgs(const RunInputs &in, const CampaignRun &r, bool log);

/// What run `r`'s summary.json must say to count as the plan's run (PriorRun).
RunIdentity IdentityOf(const RunInputs &in, const CampaignRun &r);

/// overrides.json of a run: its exact bytes (every engine writes these).
std::string OverridesText(const CampaignRun &r);

/// How runs are executed, and which earlier results count.
struct RunOptions {
  unsigned jobs{1};
  bool force_new{false};     ///< no earlier run counts as done
  bool retry_failed{false};  ///< an earlier failed run is run again
  LogPolicy logs;            ///< which runs keep their run.lcmlog (--logs)
  bool logs_given{false};    ///< --logs was given: a done run without the log it keeps is run
                             ///< again (without --logs, done runs are kept as they are)
  unsigned shard_index{0}, shard_count{0};  ///< --shard I/N (0/0: the whole plan)
  /// What a run executes (required by ExecuteRuns): each run is a fork of this process that
  /// calls run_here(arguments of `uvms run`) in the run's directory and exits with its status.
  /// No program load and no one-time library set-up per run (the campaign's own process is
  /// single-threaded, so a fork is a clean copy of it).
  std::function<int(const std::vector<std::string> &run_args)> run_here;
};

/// What to do with a run, given what its directory holds. With --logs given, a finished run
/// whose log the policy keeps but whose directory has none (an earlier campaign kept no log) is
/// to do again: runs are deterministic, so running it again writes the log it would have had.
enum class RunState { kTodo, kDone, kFailedKept };

RunState StateOf(const std::filesystem::path &root, const RunInputs &in, const CampaignRun &r,
                 const RunOptions &o);

/// After run `r` ended with exit status `rc` (0: finished) in `dir`: its run.lcmlog goes when the
/// policy does not keep a finished run's log. Returns "" or why the log could not be removed.
std::string ApplyLogPolicy(const LogPolicy &policy, const CampaignRun &r, int rc,
                           const std::filesystem::path &dir);

/// Up to five ids joined with ", ", then ", ..." when there are more.
std::string IdList(const std::vector<std::string> &ids);

/// Runs the runs of `mine` that are not done, `o.jobs` at a time, with progress on `out` (each
/// line flushed, so a pipe or a `tee` sees it as it happens). Returns true, or false when a run
/// cannot be prepared or started: then no further run is started, the running ones are waited
/// for, and the message on `err` names the path and the cause.
bool ExecuteRuns(const RunInputs &in, const std::vector<const CampaignRun *> &mine,
                 const std::filesystem::path &root, const RunOptions &o, std::ostream &out,
                 std::ostream &err);

}  // namespace uvms::sil
