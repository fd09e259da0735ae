// SPDX-License-Identifier: Apache-2.0
// log_policy.hpp: which runs of a campaign keep their run.lcmlog (uvms campaign --logs,
// docs/CAMPAIGNS.md "Which runs keep a log"). A log is about 5.5 MB for the paper's 60 s run;
// summary.json (about 10 kB) holds every analysis the report makes of most runs.
#pragma once

#include <string>
#include <vector>

#include "campaign/campaign.hpp"

namespace uvms::sil {

/// --logs all|failed|none|ID[,ID...]: which runs keep their log.
///   all     every run (the default);
///   failed  only the runs that failed (the evidence of a failure is never thrown away);
///   none    no run writes a log (uvms run --no-log);
///   IDs     the runs named (run ids, or shell patterns such as IV_unsteady_s*), and the failed.
/// Under failed and IDs every run writes its log and a finished run not named deletes it.
struct LogPolicy {
  enum class Mode { kAll, kFailed, kNone, kIds };
  Mode mode{Mode::kAll};
  std::vector<std::string> patterns;  ///< kIds: run ids or fnmatch(3) patterns

  /// Whether the run writes a log at all (every mode but none).
  bool Writes() const { return mode != Mode::kNone; }
  /// Whether run `id` keeps its log once it finished.
  bool KeepsFinished(const std::string &id) const;
  /// The policy as given on the command line (all, failed, none, or the patterns joined by ",").
  std::string Text() const;
};

/// Parses the value of --logs. Throws std::invalid_argument naming what is wrong (an empty
/// value, an empty id between commas).
LogPolicy ParseLogPolicy(const std::string &value);

/// Every pattern of an IDs policy names at least one run of the campaign; throws CampaignError
/// naming the first that names none (with a few of the plan's ids) otherwise.
void CheckLogPolicy(const LogPolicy &policy, const Campaign &c);

}  // namespace uvms::sil
