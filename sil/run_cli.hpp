// SPDX-License-Identifier: Apache-2.0
// run_cli.hpp: `uvms run` (one scenario over LCM, logged) and `uvms replay` (a log's sensors
// through a fresh controller, compared bit for bit with the logged actuators).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace uvms::sil {

/// Exit codes of the run-related commands.
enum RunExit { kRunOk = 0, kRunBadInput = 1, kRunUsage = 2, kRunFailed = 3 };

/// `uvms run SCENARIO.toml [--out DIR] [--set k=v]... [--transport udpm|memq] [--url URL]`.
int RunRunCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err);

/// `uvms replay DIR/run.lcmlog`: 0 identical, 1 a difference (first tick and field printed),
/// 2 usage, 3 unreadable, corrupt or incomplete log (incomplete also when ticks with their
/// sensors logged lack their actuators or telemetry beyond the ticks the run missed), 4 an
/// intact log of an interrupted run.
int RunReplayCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err);

/// `uvms-plant`'s main (the plant node as its own process).
int RunPlantProcess(const std::vector<std::string> &args, std::ostream &out, std::ostream &err);

}  // namespace uvms::sil
