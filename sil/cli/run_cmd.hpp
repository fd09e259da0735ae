// SPDX-License-Identifier: Apache-2.0
// run_cmd.hpp: `uvms run` (one scenario over LCM, logged).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "run/run_options.hpp"  // RunExit

namespace uvms::sil {

/// `uvms run SCENARIO.toml [--out DIR] [--set k=v]... [--transport udpm|memq] [--url URL]`.
int RunRunCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err);

}  // namespace uvms::sil
