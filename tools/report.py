#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""report: the campaign report of SPEC §9 from the paper campaigns.

    tools/report.py CAMPAIGNS_ROOT [--out DIR] [--uvms PATH | --schema FILE]

CAMPAIGNS_ROOT holds the output directories of `uvms campaign sil/campaigns/paper/expN_*.toml
--out ROOT/<name>` (tools/main writes out/paper/). Experiments are found by the "name" in their
results.json (exp1_cases ... exp8_analytic, exp8b_analytic_like), wherever they sit below ROOT
(one level); missing ones are noted in the report and their sections skipped. Writes
DIR/report.md, DIR/report.html (the same report as one self-contained page, figures embedded)
and DIR/figures/*.png (DIR defaults to ROOT).

Configuration facts come only from the runs' logged configurations (results.json,
summary.json, the overrides in plan.json / overrides.json, the controller configuration message
in run.lcmlog) and from the build's configuration schema, the JSON printed by
`uvms scenario schema` (--uvms, default build/host/sil/uvms in the repository; or a saved copy
with --schema): the default of every key a run does not set. Without the schema the report
stops with an error.

The report is the package tools/uvms_tools/report/ (this file is its command line):
load/ (schema, campaign outputs, logs), analyses/ (pure functions: statistics over seeds,
delay, energy splits, the motor step, the headline's counting, the paper's numbers, exp8/8b),
figures/ (matplotlib), text/ (the Markdown sections), document.py (their order).

Interpreter: see tools/uvms_tools/env.py (re-executes with REPO/.venv/bin/python when
needed). The generated LCM types are found as tools/uvmslog.py describes
($UVMS_LCM_PYTHON_PATH, else build/host lcmgen/python).
"""
from uvms_tools.env import run_tool  # tools/ is sys.path[0]; run_tool re-executes in the venv

if __name__ == "__main__":
    run_tool(__file__, "uvms_tools.report.cli:main")
