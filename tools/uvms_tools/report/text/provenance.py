# SPDX-License-Identifier: Apache-2.0
"""provenance: the builds, scenario and campaign files the runs came from (summary.json and
results.json `provenance`), and the configuration schema the report read."""
import hashlib
import os
from collections import Counter

from uvms_tools.env import REPO_ROOT

from ..keys import BEYOND, EXPERIMENTS
from ..load.paths import disp_path
from .fmt import table

KEYS = ["version", "git_commit", "build_preset", "build_type", "controller_precision"]


def _sha256(path):
    try:
        with open(path, "rb") as fh:
            return hashlib.sha256(fh.read()).hexdigest()
    except OSError:
        return None


def _tally(rep):
    """Counters of each provenance item over the runs, scenario files with their hashes, and
    the number of runs that recorded a provenance."""
    vals = {k: Counter() for k in KEYS + ["drive", "transport"]}
    scen, n_with = {}, 0
    for e in rep.exps.values():
        for r in e.runs:
            pv = dict(e.provenance or {})
            rp = r.get("provenance")
            if isinstance(rp, dict) and rp:
                n_with += 1
                pv.update(rp)
            for k in KEYS:
                v = pv.get(k)
                vals[k][str(v) if v not in (None, "") else "not recorded"] += 1
            vals["drive"][r.get("drive") or "not recorded"] += 1
            vals["transport"][r.get("transport") or "not recorded"] += 1
            path = disp_path(r.get("scenario") or e.base_path, rep.root)
            ent = scen.setdefault((path, pv.get("scenario_sha256") or ""), dict(runs=0, exps=set()))
            ent["runs"] += 1
            ent["exps"].add(e.name)
    return vals, scen, n_with


def _scenario_rows(scen):
    rows = []
    for (path, sha), ent in sorted(scen.items()):
        shown = f"`{sha}`" if sha else "not recorded"
        if not sha:
            now = _sha256(path if os.path.isabs(path) else os.path.join(REPO_ROOT, path))
            if now:
                shown = f"not recorded; the file now: `{now}`"
        rows.append([f"`{path}`", shown, str(ent["runs"]), ", ".join(sorted(ent["exps"]))])
    return rows


def _campaign_rows(rep):
    rows = []
    for name, _ in EXPERIMENTS + BEYOND:
        e = rep.exp(name)
        if e is None or not e.campaign_path:
            continue
        rec = (e.provenance or {}).get("campaign_sha256")
        now = _sha256(e.campaign_path)
        if rec:
            h = f"`{rec}`" + ("" if now in (None, rec) else
                              f" (**the file has changed since**: now `{now}`)")
        else:
            h = f"not recorded; the file now: `{now}`" if now else "not recorded"
        sets = (e.provenance or {}).get("campaign_sets")
        rows.append([name, f"`{disp_path(e.campaign_path, rep.root)}`", h,
                     "; ".join(f"`{x}`" for x in str(sets).split("\n") if x) if sets else "—"])
    return rows


def _schema_line(rep):
    kind, path = rep.schema.origin
    src = (f"printed by `{disp_path(path, rep.root)} scenario schema`, i.e. by the build the "
           f"report ran with, which need not be the build that ran the campaigns (git commit "
           f"above)" if kind == "binary" else f"read from `{disp_path(path, rep.root)}`")
    return [f"Defaults of the settings a run does not set (for selecting runs, for comparing "
            f"configurations and in the modeling choices): the configuration schema "
            f"(schema_version {rep.schema.version}, {len(rep.schema)} keys) {src}.", ""]


def section(rep):
    md = ["## Provenance", ""]
    vals, scen, n_with = _tally(rep)
    nruns = sum(len(e.runs) for e in rep.exps.values())
    rows = [[k.replace("_", " "), "; ".join(f"`{v}` ({n} runs)" if len(c) > 1 else f"`{v}`"
                                            for v, n in c.most_common())]
            for k, c in vals.items()]
    md += [f"Read from each run's summary.json `provenance` (present in {n_with} of {nruns} "
           "runs) and results.json; `not recorded` where the build that wrote them did not "
           "record it.", ""]
    md += table(["item", "value (runs)"], rows)
    md += _schema_line(rep)
    md += ["Scenario files (base scenarios; each run adds its campaign's overrides):", ""]
    md += table(["scenario file", "SHA-256 of its content", "runs", "experiments"],
                _scenario_rows(scen))
    crow = _campaign_rows(rep)
    if crow:
        md += ["Campaign files (SHA-256 recorded in results.json `provenance`):", ""]
        md += table(["experiment", "campaign file", "SHA-256", "--set given to the campaign"],
                    crow)
    return md
