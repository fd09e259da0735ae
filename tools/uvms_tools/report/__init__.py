# SPDX-License-Identifier: Apache-2.0
"""report: the campaign report of SPEC §9 (tools/report.py is its command line).

    load/       the configuration schema (`uvms scenario schema`), the campaign outputs
                (results.json, plan.json, summary.json, overrides) as Experiments, run logs
    analyses/   pure functions on arrays and dicts: statistics over seeds, delay, energy
                splits, the motor step, the headline's counting, the paper's numbers, exp8/8b
    figures/    matplotlib, one function per figure
    text/       the Markdown sections (each reads the runs, calls the analyses and figures)
    context.py  the state one report accumulates; document.py the order of the sections;
    cli.py      the command line
"""
