// SPDX-License-Identifier: Apache-2.0
// exit_status.hpp: the exit statuses every `uvms` subcommand and process main shares
// (docs/SCENARIOS.md "Exit status"). The run layer's RunExit (run/run_options.hpp) has the same
// values; a static_assert in run_cmd.cpp keeps them equal.
#pragma once

namespace uvms {

constexpr int kExitOk = 0;
constexpr int kExitBadInput = 1;  ///< invalid input: scenario, campaign, JSON, firmware config
constexpr int kExitUsage = 2;     ///< unknown option, missing option argument
constexpr int kExitFailed = 3;    ///< the work ran and failed, or an output could not be written

}  // namespace uvms
