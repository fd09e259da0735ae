// campaign_cli.hpp: `uvms campaign FILE.toml --out DIR [-j N]`: a base scenario plus sweeps over
// any scenario keys, expanded into runs, run in parallel, resumable, with a results table.
//
// Campaign file (TOML; paths relative to the campaign file):
//   name = "exp1_cases"                     # optional; default: the file's stem
//   description = "..."                     # optional
//   base = "../../scenarios/paper/case_I_stagnant.toml"
//   transport = "memq"                      # optional: memq (default) or udpm
//   [set]                                   # overrides applied to every run
//   "trajectory.duration_s" = 60.0
//   [[sweep]]                               # one axis: keys varied together (equal lengths)
//   "control.case" = ["IV", "VII"]
//   labels = ["IV", "VII"]                  # optional: names of the axis's values
//   [[sweep]]                               # axes combine as a Cartesian product
//   "payload.mass_kg" = [0.0, 1.0, 2.0]
//
// Output: DIR/plan.json (the expanded runs), DIR/runs/<id>/{run.lcmlog, summary.json,
// overrides.json}, DIR/results.csv and DIR/results.json (one row per run: id, every swept key,
// the summary metrics). A run whose summary.json exists with the same overrides is not redone.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace uvms::sil {

int RunCampaignCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err);

}  // namespace uvms::sil
