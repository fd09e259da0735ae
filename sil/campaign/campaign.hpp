// SPDX-License-Identifier: Apache-2.0
// campaign.hpp: a campaign file (TOML) expanded into runs: a base scenario, fixed overrides,
// sweep axes (Cartesian product), seed replicates, and each run's stable id. The format is
// documented in docs/SCENARIOS.md ("Campaigns"); `uvms campaign` (campaign_cmd.hpp) runs it.
//
// Run ids are a pure function of the run's own values: the labels of its axis values joined
// with "_" (sanitised for file names, IdPart), plus "_s<N>" for a replicated run (its
// replicate value, unpadded, so that no id depends on the other values); "run" when there is
// neither. Adding a sweep value or a replicate therefore never renames the other runs. Two
// runs with the same id are a CampaignError naming both.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace uvms::sil {

/// A bad campaign file: "FILE:LINE: key \"...\": what is wrong (expected ...)".
struct CampaignError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// One [[sweep]]: keys that vary together (equal lengths).
struct CampaignAxis {
  std::vector<std::string> keys;                 ///< dotted scenario keys
  std::vector<std::vector<std::string>> values;  ///< values[i][k]: TOML text of key k at index i
  std::vector<std::string> labels;               ///< one per index: given, or the first key's value
};

/// [replicates]: every run whose `when` is true is run once per value of `key`.
struct CampaignReplicates {
  std::string key;                    ///< scenario key varied, e.g. "run.seed" ("": no table)
  std::vector<std::int64_t> values;   ///< distinct, >= 0, in file order
  std::string when;                   ///< boolean scenario key ("": replicate every run)
};

/// One expanded run.
struct CampaignRun {
  std::string id;                      ///< stable id: the directory name under runs/
  std::vector<std::string> overrides;  ///< "key=value": [set], extra --set, axes, replicate
  std::vector<std::pair<std::string, std::string>> swept;  ///< key, TOML text (axes, replicate)
  std::optional<std::int64_t> replicate;  ///< the replicate value of a replicated run
};

/// A parsed and expanded campaign.
struct Campaign {
  std::string path;         ///< the campaign file as given
  std::string name;         ///< `name`, default: the file's stem
  std::string description;  ///< `description` ("" when absent)
  std::string base;         ///< base scenario, relative to the working directory
  std::string transport{"memq"};
  std::vector<std::string> fixed;       ///< [set] overrides, then the extra --set ones
  std::vector<std::string> extra_sets;  ///< the extra --set overrides alone
  std::vector<CampaignAxis> axes;
  CampaignReplicates replicates;
  std::vector<CampaignRun> runs;  ///< in plan order (the last axis and the replicate vary fastest)
};

/// Default hard limit on the number of runs a campaign may expand to (`uvms campaign --max-runs`).
inline constexpr std::size_t kDefaultMaxRuns = 1000000;

/// Validate and expand campaign file text; `path` names it in errors and anchors its relative
/// paths. The run count is checked against `max_runs` (>= 1) before any run is built: a
/// campaign that expands to more runs, or whose count overflows size_t, is a CampaignError
/// naming the count. A key on two [[sweep]] axes, or the replicate key on an axis, is a
/// CampaignError; a key both in [set] and on an axis is allowed (the axis value wins).
/// Throws CampaignError.
Campaign ParseCampaign(const std::string &text, const std::string &path,
                       const std::vector<std::string> &extra_sets = {},
                       std::size_t max_runs = kDefaultMaxRuns);

/// Read, validate and expand a campaign file. `extra_sets` go after [set] into every run (a
/// sweep or replicate value still wins). With [replicates] `when`, the base scenario file is
/// read too (the run's overrides first, then the base file's value). `max_runs` as for
/// ParseCampaign. Throws CampaignError.
Campaign LoadCampaign(const std::string &path, const std::vector<std::string> &extra_sets = {},
                      std::size_t max_runs = kDefaultMaxRuns);

/// A campaign's identity: lowercase hex SHA-256 over the campaign file's bytes, the base
/// scenario file's bytes, every extra --set in order, and the project version, each part
/// length-prefixed so that no two different inputs give the same byte stream. The stream is
/// each part in that order as "<its size in bytes, decimal>:<its bytes>", nothing between:
/// CampaignIdentity("a", "b", {"c"}, "v") is Sha256Hex("1:a1:b1:c1:v").
std::string CampaignIdentity(const std::string &campaign_text, const std::string &base_text,
                             const std::vector<std::string> &extra_sets,
                             const std::string &version);

/// The session of a campaign's run (sil/msg/session.h; `uvms run --session`): the first 16 hex
/// digits of the SHA-256 of the length-prefixed stream of "uvms campaign run session", the
/// base scenario file's bytes, the run's overrides in order and, for a generation other than
/// 0, "generation <N>" ("0000000000000001" if the digits are all zero). The generation of a
/// campaign's --out DIR starts at 0 and grows by one at each --force-new (plan.json keeps it),
/// so that a run of an earlier generation, in whatever shard, never matches a run of the plan.
/// The same run's inputs give the same session, so a campaign's run gives the same run.lcmlog
/// byte for byte whichever engine runs it, and any two runs that differ in an override have
/// different sessions.
std::string RunSession(const std::string &base_text, const std::vector<std::string> &overrides,
                       std::uint64_t generation = 0);

/// One id component: every run of characters other than letters, digits, '.' and '-' becomes
/// one '_'; leading '.' and '_' and trailing '_' are dropped; "v" when nothing is left.
std::string IdPart(const std::string &text);

/// "s" + the value, unpadded (ReplicateSuffix(7) == "s7"): a padded width would have to grow
/// with the largest seed and so rename every replicated run when a sweep passes 9, 99, ...
std::string ReplicateSuffix(std::int64_t value);

}  // namespace uvms::sil
