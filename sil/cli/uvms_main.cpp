// SPDX-License-Identifier: Apache-2.0
// uvms_main.cpp: the project's runner executable. `uvms <subcommand> [options]`; each
// subcommand is one entry of kSubcommands (run, replay, scenario check and campaign join it
// later). Exit status: the subcommand's (0..4, listed in --help); 2 for an unknown or missing
// subcommand.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli/campaign_cmd.hpp"
#include "cli/model_cmd.hpp"
#include "cli/replay_cmd.hpp"
#include "cli/run_cmd.hpp"
#include "cli/scenario_cmd.hpp"
#include "msg/cli_version.h"

namespace {

using SubcommandFn = int (*)(const std::vector<std::string> &args);

struct Subcommand {
  const char *name;
  const char *summary;
  SubcommandFn run;
};

// `uvms vehicle`: the Python tool tools/uvms_vehicle.py (URDF parsing and the frame algebra
// in numpy, checked against Pinocchio: tests/tools/test_urdf_import.py), run in place of this
// process with the same arguments; it prints its own help and errors (exit 0, 1, 2).
int RunVehicle(const std::vector<std::string> &args) {
  const std::string src = UVMS_SOURCE_DIR;
  const std::string tool = src + "/tools/uvms_vehicle.py", python = src + "/.venv/bin/python";
  // The project's venv (numpy) when it exists, else the script's own shebang.
  const bool venv = access(python.c_str(), X_OK) == 0;
  std::vector<char *> argv;
  if (venv) argv.push_back(const_cast<char *>(python.c_str()));
  argv.push_back(const_cast<char *>(tool.c_str()));
  for (const std::string &a : args) argv.push_back(const_cast<char *>(a.c_str()));
  argv.push_back(nullptr);
  std::cout.flush();
  execv(venv ? python.c_str() : tool.c_str(), argv.data());
  std::cerr << "uvms vehicle: error: cannot run " << tool << ": " << std::strerror(errno)
            << " (the source tree's tools/; run tools/bootstrap)\n";
  return uvms::cli::kExitBadInput;
}

int RunModel(const std::vector<std::string> &args) {
  return uvms::cli::RunModelCli(args, std::cin, std::cout, std::cerr);
}

int RunRun(const std::vector<std::string> &args) {
  return uvms::sil::RunRunCli(args, std::cout, std::cerr);
}

int RunReplay(const std::vector<std::string> &args) {
  return uvms::sil::RunReplayCli(args, std::cout, std::cerr);
}

int RunCampaign(const std::vector<std::string> &args) {
  return uvms::sil::RunCampaignCli(args, std::cout, std::cerr);
}

constexpr Subcommand kSubcommands[] = {
    {"run", "run one scenario over LCM (plant and controller in lockstep), log and summary",
     RunRun},
    {"replay", "re-run a log's sensors through a fresh controller; compare bit for bit",
     RunReplay},
    {"campaign", "expand a campaign (base scenario + sweeps) into runs, run them in parallel",
     RunCampaign},
    {"scenario", "check a scenario file (TOML), or print the schema of its keys: uvms scenario check FILE [--set k=v]..., uvms scenario schema [--markdown]", [](const std::vector<std::string> &a) { return uvms::sil::RunScenarioCli(a, std::cout, std::cerr); }},
    {"model", "evaluate the arm model (Newton-Euler, feedforward) at one JSON state from stdin",
     RunModel},
    {"vehicle", "describe your own vehicle: uvms vehicle import-urdf ARM.urdf [--hydro FILE] "
     "writes the arm part of a description from URDF", RunVehicle},
};

std::string SubcommandNames() {
  std::string names;
  for (const Subcommand &s : kSubcommands) names += (names.empty() ? "" : ", ") + std::string(s.name);
  return names;
}

void PrintUsageLine(std::ostream &os) {
  os << "usage: uvms <subcommand> [options]  (subcommands: " << SubcommandNames()
     << "; see uvms --help)\n";
}

void PrintHelp(std::ostream &os) {
  os << "usage: uvms <subcommand> [options]\n"
        "       uvms --version\n\n"
        "Europa UVMS runner: the host side of the station-keeping controller.\n\n"
        "Subcommands:\n";
  for (const Subcommand &s : kSubcommands) {
    os << "  " << s.name << std::string(10 - std::strlen(s.name), ' ') << s.summary << '\n';
  }
  os << "\nRun 'uvms <subcommand> --help' for a subcommand's options, input and output, and\n"
        "'uvms <subcommand> --version' (or 'uvms --version') for the version.\n"
        "Exit status (each subcommand's help says which it uses and when):\n"
        "  0 success; 1 bad input (scenario, campaign, log or arguments' values); 2 usage error;\n"
        "  3 a run failed, or a log is unreadable, corrupt or incomplete, or an output cannot be\n"
        "    written; 4 a campaign directory in use by another campaign, or the log of an\n"
        "    interrupted run (intact as far as it goes).\n";
}

}  // namespace

int main(int argc, char **argv) {
  try {
    if (argc < 2) {
      std::cerr << "uvms: error: missing subcommand\n";
      PrintUsageLine(std::cerr);
      return uvms::cli::kExitUsage;
    }
    const std::string name = argv[1];
    if (name == "-h" || name == "--help" || name == "help") {
      PrintHelp(std::cout);
      return uvms::cli::kExitOk;
    }
    if (uvms_cli_wants_version(argc, argv)) {
      uvms_cli_print_version(stdout, "uvms");
      return uvms::cli::kExitOk;
    }
    const std::vector<std::string> args(argv + 2, argv + argc);
    for (const Subcommand &s : kSubcommands) {
      if (name != s.name) continue;
      if (args.size() == 1 && args[0] == "--version") {  // uvms <subcommand> --version
        uvms_cli_print_version(stdout, "uvms");
        return uvms::cli::kExitOk;
      }
      return s.run(args);
    }
    std::cerr << "uvms: error: unknown subcommand \"" << name << "\"\n";
    PrintUsageLine(std::cerr);
    return uvms::cli::kExitUsage;
  } catch (const std::exception &e) {  // subcommands report their own errors; this is a backstop
    std::cerr << "uvms: error: " << e.what() << '\n';
    return uvms::cli::kExitBadInput;
  }
}
