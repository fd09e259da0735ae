// SPDX-License-Identifier: Apache-2.0
// campaign_results.hpp: what a campaign's --out DIR holds, read back, and its results table.
// A run's result is its directory DIR/runs/<id>/ (summary.json, overrides.json, run.out and,
// unless --no-logs, run.lcmlog); PriorRun says whether it counts as done for a plan's run, and
// WriteResults assembles DIR/results.csv and DIR/results.json from the runs of a plan. Used by
// `uvms campaign` for a campaign, a shard and a merge alike (campaign_cmd.hpp), so that every
// engine gives the same table.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "campaign/campaign.hpp"
#include "run/provenance.hpp"

namespace uvms::sil {

/// A JSON file's contents; null when it is missing or not valid JSON.
nlohmann::ordered_json ReadJsonFile(const std::filesystem::path &p);

/// What a run's summary.json must say for the run to belong to the plan: the session of the
/// plan's run (RunSession, with DIR's generation), and the provenance of the run's inputs.
struct RunIdentity {
  std::string session;          ///< 16 hex digits
  std::string scenario_sha256;  ///< the pinned base scenario's SHA-256
  std::string scenario_sets;    ///< the run's overrides joined with "\n" (JoinLines)
  std::string version;          ///< the project version of this binary
};

/// What a run's directory holds from an earlier campaign in the same DIR.
enum class Prior {
  kNone,      ///< nothing to keep: no summary, other overrides, an interrupted run, or a
              ///< summary of another run (its identity is not the plan's)
  kFinished,  ///< a summary.json (status other than "failed") under the same overrides
  kFailed,    ///< a summary.json with status "failed" (not interrupted) under the same overrides
};

/// The state of run `r`'s directory `dir` (DIR/runs/<id>): a summary counts only when its
/// session, scenario_sha256, scenario_sets and version are `want`'s. When it is kNone and `why`
/// is given, *why says what was found ("" for no summary at all). When `summary` is given, it
/// receives summary.json as read (null when there is none or it does not parse).
Prior PriorRun(const std::filesystem::path &dir, const CampaignRun &r, const RunIdentity &want,
               std::string *why = nullptr, nlohmann::ordered_json *summary = nullptr);

/// The provenance as a JSON object (key order kept).
nlohmann::ordered_json ProvenanceJson(const Provenance &p);

/// [replicates] as JSON (null without one).
nlohmann::ordered_json ReplicatesJson(const CampaignReplicates &r);

/// What WriteResults found in the rows.
struct ResultsWritten {
  int failed{0};                    ///< rows whose status is not "finished"
  std::vector<std::string> builds;  ///< distinct "git_commit controller_precision build_preset"
                                    ///< of the rows' provenance, in order of first appearance
};

/// Writes `root`/results.csv and `root`/results.json: one row per run of `c` in plan order (id,
/// every swept key, then the run's summary.json; a run without one, or whose summary is not of
/// the plan's run (`want(run)`, PriorRun), is a failed row that says why). results.json's head
/// carries the identity and the generation, as plan.json does. Both are written atomically
/// and checked: throws std::runtime_error naming the file.
ResultsWritten WriteResults(const Campaign &c, const std::filesystem::path &root,
                            const Provenance &prov, const std::string &identity,
                            std::uint64_t generation,
                            const std::function<RunIdentity(const CampaignRun &)> &want);

}  // namespace uvms::sil
