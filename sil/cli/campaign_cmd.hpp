// SPDX-License-Identifier: Apache-2.0
// campaign_cmd.hpp: `uvms campaign FILE.toml --out DIR [-j N] [--max-runs N] [--retry-failed]
// [--force-new] [--no-logs] [--shard I/N] [--dry-run | --plan-only]` and `... --merge`: a base
// scenario plus sweeps over any scenario keys and seed replicates (sil/campaign/campaign.hpp), expanded
// into runs with stable ids, run in parallel, resumable, with a results table. The format is
// documented in docs/SCENARIOS.md ("Campaigns"); shards, --merge, --plan-only and the other
// engines in docs/CAMPAIGNS.md.
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
//   [replicates]                            # optional: one run per seed ...
//   key = "run.seed"
//   first = 1                               # ... first .. first + count - 1 (or values = [...])
//   count = 20
//   when = "environment.unsteady_flow.enabled"  # ... of the runs where this is true
//
// Run id: the axis labels joined with "_" (sanitised), plus "_s7" for a replicate, e.g.
// "VII_5.0" or "VII_unsteady_s7": a pure function of the run's own values.
// A run is `uvms run` in its directory DIR/runs/<id> (--out .) with a session derived from its
// inputs (RunSession), so its log is the same whichever engine runs it.
// Output: DIR/plan.json (provenance and the expanded runs), DIR/runs/<id>/{run.lcmlog,
// summary.json, overrides.json, run.out}, DIR/results.csv and DIR/results.json (provenance, then
// one row per run in plan order: id, every swept key, the summary). A run whose summary.json
// exists with the same overrides is not redone, so adding a sweep value or a seed only runs
// the new runs; a failed one is kept unless --retry-failed.
// Integrity: DIR belongs to the campaign whose identity (CampaignIdentity) is in its plan.json;
// another campaign is refused there (exit 1) unless --force-new (every run again). A campaign
// holds flock(2) on DIR/.campaign.lock while it runs (campaign_lock.hpp; shards hold it shared);
// a second one is refused (exit 4). A write that fails (a run's directory, plan.json, ...)
// stops the campaign with exit 3. The runs are executed by campaign_exec.hpp.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace uvms::sil {

int RunCampaignCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err);

}  // namespace uvms::sil
