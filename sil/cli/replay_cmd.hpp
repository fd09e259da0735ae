// SPDX-License-Identifier: Apache-2.0
// replay_cmd.hpp: `uvms replay` (a log's sensors through a fresh controller, compared bit for
// bit with the logged actuators).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace uvms::sil {

/// `uvms replay DIR/run.lcmlog`: 0 identical, 1 a difference (first tick and field printed),
/// 2 usage, 3 unreadable, corrupt or incomplete log (incomplete also when ticks with their
/// sensors logged lack their actuators or telemetry beyond the ticks the run missed), 4 an
/// intact log of an interrupted run.
int RunReplayCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err);

}  // namespace uvms::sil
