# SPDX-License-Identifier: Apache-2.0
"""logs_read: which run logs the report read (Experiment.logs_read), and how each came to be
there: kept by its campaign, or made again from plan.json (load/regen.py). Built last, after
every section has asked for its logs."""
from .fmt import table


def _ids(ids):
    return ", ".join(f"`{i}`" for i in ids)


def section(rep):
    exps = [e for e in rep.exps.values() if e.logs_read]
    n = sum(len(e.logs_read) for e in exps)
    runs = sum(len(e.runs) for e in rep.exps.values())
    md = ["## Run logs read", ""]
    if not n:
        return md + [f"No run log was read: every number comes from the {runs} runs' "
                     "summary.json.", ""]
    made = sum(v == "made again" for e in exps for v in e.logs_read.values())
    bad = [(e.name, i, v) for e in exps for i, v in e.logs_read.items()
           if v not in ("kept", "made again")]
    md += [f"The report read {n} run logs of {runs} runs (every other number comes from "
           f"summary.json, where each run's per-tick analyses are computed as it runs): "
           f"{n - made - len(bad)} found beside their runs (kept by their campaign, or made "
           f"by an earlier report), {made} made again when read "
           "(`uvms run` with the arguments plan.json records for the run; a run is "
           "deterministic, and its summary.json matched the kept one in every field but the "
           "wall clock, the commit and the run's name), which stay beside the run"
           + (f", {len(bad)} could not be read (below)" if bad else "") + ".", ""]
    rows = [[f"`{e.name}`", str(len(e.logs_read)),
             str(sum(v == "made again" for v in e.logs_read.values())),
             _ids(sorted(e.logs_read))] for e in exps]
    md += table(["experiment", "logs read", "made again", "runs"], rows)
    if bad:
        md += ["Logs that could not be read (the sections that need them say n/a):", ""]
        md += [f"- `{name}/{rid}`: {why}" for name, rid, why in bad] + [""]
    return md
