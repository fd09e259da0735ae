// SPDX-License-Identifier: Apache-2.0
// run_options.hpp: the options shared by `uvms run` and the plant process `uvms-plant`, the
// scenario read once with its provenance, and the summary written with the run's exit status.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "msg/session.h"
#include "run/provenance.hpp"
#include "run/summary_writer.hpp"
#include "scenario/scenario.hpp"

namespace uvms::sil {

/// Exit codes of the run-related commands.
enum RunExit { kRunOk = 0, kRunBadInput = 1, kRunUsage = 2, kRunFailed = 3 };

struct RunArgs {
  std::string scenario, out_dir, transport{"udpm"}, url, transport_label, controller{"host"};
  /// --publish-url: the plant publishes on this URL and listens on `url` ("": both on `url`)
  std::string publish_url;
  std::vector<std::string> sets;  ///< --set overrides, and --limit ones as verdict.NAME=VALUE
  std::int64_t session{UVMS_SESSION_NONE};  ///< --session (msg/session.h); NONE: drawn
  std::string scenario_sha256;  ///< --scenario-sha256: the bytes the scenario must have ("": any)
  std::string name;  ///< --name: the run's name (summary.json "name"; "": the scenario's name)
  bool help{false};
  bool no_log{false};  ///< --no-log: no run.lcmlog, summary.json only
  /// --no-summary-fsync: summary.json renamed into place without its fsync (FileSync)
  bool summary_fsync{true};
};

/// Parses the options shared by `uvms run` and `uvms-plant`. Throws std::invalid_argument.
RunArgs ParseRunArgs(const std::vector<std::string> &args);

/// ParseRunArgs for a command: on a bad option, prints "<who>: error: <what><hint>" on err and
/// returns nothing.
std::optional<RunArgs> ParseRunArgsOrSay(const std::vector<std::string> &args, const char *who,
                                         const char *hint, std::ostream &err);

/// Reads the scenario file once: the same bytes are parsed (as LoadScenario would) and hashed
/// for the summary's provenance; refused when --scenario-sha256 names other bytes. Throws
/// ScenarioError.
Scenario LoadScenarioWithProvenance(const RunArgs &ra, Provenance *prov);

/// LoadScenarioWithProvenance for a command: on a ScenarioError, prints "<who>: error: <what>"
/// on err and returns nothing (the command exits kRunBadInput).
std::optional<Scenario> LoadScenarioOrSay(const RunArgs &ra, Provenance *prov, const char *who,
                                          std::ostream &err);

/// Writes summary.json; returns the run's exit status: kRunOk finished, kRunFailed failed or
/// the summary could not be written (the error is printed on err, prefixed by who).
int WriteSummaryOrFail(const RunSummary &s, const std::filesystem::path &path, const char *who,
                       std::ostream &err, FileSync sync = FileSync::kFsync);

/// How the run's summary.json is written: --no-summary-fsync gives FileSync::kNoFsync.
inline FileSync SummaryFileSync(const RunArgs &ra) {
  return ra.summary_fsync ? FileSync::kFsync : FileSync::kNoFsync;
}

/// A session as 16 lowercase hex digits.
std::string SessionText(std::int64_t session);

}  // namespace uvms::sil
