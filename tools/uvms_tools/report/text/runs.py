# SPDX-License-Identifier: Apache-2.0
"""runs: the runs per experiment (finished, conditions, simulated and wall time) and the runs
that did not finish."""
from collections import Counter

from ..keys import BEYOND, EXPERIMENTS
from ..load.overrides import condition_key, finished, seed_of
from ..num import isnum
from .fmt import f, table


def _row(e, tot):
    n = len(e.runs)
    ok = sum(1 for r in e.runs if finished(r))
    sim = sum(float(r.get("duration_s") or 0.0) for r in e.runs)
    wall = sum(float(r.get("wall_time_s") or 0.0) for r in e.runs)
    el = e.elapsed_s()
    seeds = Counter(seed_of(r) is not None for r in e.runs)
    groups = Counter(condition_key(r) for r in e.runs)
    reps = sorted(set(groups.values()))
    for k, v in (("n", n), ("ok", ok), ("sim", sim), ("wall", wall),
                 ("el", el if isnum(el) else 0.0)):
        tot[k] += v
    return [e.name, str(n), f"{ok}" + ("" if ok == n else f" (**{n - ok} failed**)"),
            f"{len(groups)} conditions; runs per condition {'/'.join(map(str, reps))}"
            + (f" ({seeds[True]} seeded)" if seeds[True] else ""),
            f(sim, 1), f(wall, 2), f(el, 1)]


def section(rep):
    rows = []
    tot = dict(n=0, ok=0, sim=0.0, wall=0.0, el=0.0)
    for name, _ in EXPERIMENTS + BEYOND:
        e = rep.exp(name)
        rows.append(_row(e, tot) if e is not None else [name, "missing", "", "", "", "", ""])
    rows.append(["**total**", str(tot["n"]), str(tot["ok"]), "", f(tot["sim"], 1),
                 f(tot["wall"], 2), f(tot["el"], 1)])
    md = ["## Runs", ""]
    md += table(["experiment", "runs", "finished", "conditions (runs differing only in "
                 "run.seed form one)", "simulated time Σ [s]", "run wall time Σ [s]",
                 "campaign elapsed [s]"], rows)
    md += ["Run wall time: the sum of the runs' `wall_time_s` (summary.json); campaign "
           "elapsed: from plan.json (written when the campaign starts) to results.json "
           "(written when it ends), file modification times.", ""]
    failed = [f"{e.name}/{r['id']}: {r.get('failure')} {r.get('reason')}"
              for e in rep.exps.values() for r in e.runs if not finished(r)]
    if failed:
        md += ["Runs that did not finish:", ""] + [f"- {x}" for x in failed] + [""]
    return md
