// SPDX-License-Identifier: Apache-2.0
// uvms-plant: the plant node as its own process (started by `uvms run --transport udpm`).
#include <iostream>
#include <string>
#include <vector>

#include "cli_version.h"
#include "run_cli.hpp"

int main(int argc, char **argv) {
  if (uvms_cli_wants_version(argc, argv)) {
    uvms_cli_print_version(stdout, "uvms-plant");
    return 0;
  }
  try {
    return uvms::sil::RunPlantProcess(std::vector<std::string>(argv + 1, argv + argc), std::cout,
                                      std::cerr);
  } catch (const std::exception &e) {
    std::cerr << "uvms-plant: error: " << e.what() << '\n';
    return uvms::sil::kRunFailed;
  }
}
