// SPDX-License-Identifier: Apache-2.0
// uvms-plant: the plant node as its own process (started by `uvms run --transport udpm`). It links
// the run library (plant node, recorder, metrics, summary) and nothing of the other commands.
#include <lcm/lcm.h>

#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "link/lcm_pair.h"
#include "msg/cli_version.h"
#include "run/lcm_bus.hpp"
#include "run/plant_node.hpp"
#include "run/run_options.hpp"

namespace uvms::sil {
namespace {
namespace fs = std::filesystem;

int RunPlantProcess(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  const std::optional<RunArgs> parsed = ParseRunArgsOrSay(args, "uvms-plant", "", err);
  if (!parsed) return kRunUsage;
  const RunArgs &ra = *parsed;
  if (ra.help || ra.url.empty() || ra.out_dir.empty()) {
    (ra.help ? out : err) << "usage: uvms-plant SCENARIO.toml --url LCM_URL --out DIR "
                             "[--publish-url LCM_URL]\n"
                             "       [--set k=v]... [--controller host|pil] [--session HEX] [--no-log]\n"
                             "       [--scenario-sha256 HEX] [--name NAME] [--no-summary-fsync]\n"
                             "       uvms-plant --version\n"
                             "(normally started by `uvms run`; without --session, one is drawn)\n";
    return ra.help ? kRunOk : kRunUsage;
  }
  Provenance prov;
  const std::optional<Scenario> loaded = LoadScenarioOrSay(ra, &prov, "uvms-plant", err);
  if (!loaded) return kRunBadInput;
  const Scenario &sc = *loaded;
  // --publish-url: what the plant sends goes out there; it listens on --url only.
  uvms_lcm_pair_t lcm;
  const char *failed_url = nullptr;
  if (uvms_lcm_pair_open(&lcm, ra.url.c_str(),
                         ra.publish_url.empty() ? nullptr : ra.publish_url.c_str(),
                         &failed_url) != 0) {
    err << "uvms-plant: error: cannot start LCM on " << failed_url
        << " (no multicast route? `ip route add 224.0.0.0/4 dev lo`)\n";
    return kRunFailed;
  }
  PlantNodeOptions opt;
  if (!ra.no_log) opt.log_path = (fs::path(ra.out_dir) / "run.lcmlog").string();
  opt.spin_us = LinkSpinUs(sc.link);
  opt.session = ra.session;  // NONE (started by hand): RunPlantNode draws one
  InstallPlantStopHandlers();
  RunSummary s;
  try {
    LcmBus bus(lcm.listen, lcm.publish);
    s = RunPlantNode(sc, bus, opt);
  } catch (const std::exception &e) {
    uvms_lcm_pair_close(&lcm);
    err << "uvms-plant: error: " << e.what() << '\n';
    return kRunFailed;
  }
  uvms_lcm_pair_close(&lcm);
  s.transport = ra.transport_label.empty() ? "udpm" : ra.transport_label;
  s.provenance = prov;
  return WriteSummaryOrFail(s, fs::path(ra.out_dir) / "summary.json", "uvms-plant", err,
                            SummaryFileSync(ra));
}

}  // namespace
}  // namespace uvms::sil

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
