// SPDX-License-Identifier: Apache-2.0
// scenario_cmd.hpp: `uvms scenario check FILE [--set k=v]...` and `uvms scenario schema`.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace uvms::sil {

/// `uvms scenario check FILE [--set k=v ...]`: 0 valid (prints a one-line summary to out),
/// 1 invalid (the error on err), 2 usage. `uvms scenario schema [--markdown [--update DOC]]`.
int RunScenarioCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err);

}  // namespace uvms::sil
