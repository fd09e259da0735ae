#!/usr/bin/env python3
"""report: the campaign report of SPEC §9 from the paper campaigns.

    tools/report.py CAMPAIGNS_ROOT [--out DIR]

CAMPAIGNS_ROOT holds the output directories of `uvms campaign sil/campaigns/paper/expN_*.toml
--out ROOT/<name>` (tools/main writes out/paper/). Experiments are found by the "name" in their
results.json (exp1_cases ... exp8_analytic, exp8b_analytic_like), wherever they sit below ROOT
(one level); missing ones are noted in the report and their sections skipped. Writes
DIR/report.md and DIR/figures/*.png (DIR defaults to ROOT).

Every number in the report is computed here from the runs (results.json, summary.json, the run
logs via tools/uvmslog.py, the logged controller configuration) or from the analytic model
(tools/analytic.py); the paper's printed numbers are cited constants in
tools/report_scorecard.py. Statistics over seeds (mean, 95 % CI, paired ratios) are
tools/stats.py; runs are grouped by their override values (plan.json / overrides.json), never by
run ids or labels: runs that differ only in run.seed are one condition's distribution.

Report layout: scorecard (paper vs ours), answer, energies, provenance, runs, modeling choices,
one section per experiment, observations, figures. No absolute machine path is written: paths
are relative to the repository or to the campaigns root.

Interpreter: see tools/toolenv.py (re-executes with REPO/.venv/bin/python when needed). The
generated LCM types are found as tools/uvmslog.py describes ($UVMS_LCM_PYTHON_PATH, else
build/host or build/lead lcmgen/python).
"""
import os
import sys

if os.path.dirname(os.path.abspath(__file__)) not in sys.path:
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from toolenv import REPO_ROOT, reexec_in_venv  # noqa: E402

if __name__ == "__main__":
    reexec_in_venv(__file__)

import argparse  # noqa: E402
import hashlib  # noqa: E402
import json  # noqa: E402
import math  # noqa: E402
import re  # noqa: E402
import time  # noqa: E402
import tomllib  # noqa: E402
from collections import Counter  # noqa: E402

import numpy as np  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import analytic  # noqa: E402
import report_exp8b  # noqa: E402
import report_scorecard  # noqa: E402
import stats  # noqa: E402
import uvmslog  # noqa: E402
from report_fmt import (BARY, CASES, E_EL, E_MAN, E_P, ERR, FEEDBACK_PAIRS,  # noqa: E402,F401
                        KEY_AOA, KEY_CASE, KEY_DEFAULTS, KEY_DENSITY, KEY_DIST, KEY_PAYLOAD,
                        KEY_SEED, KEY_TRAJ_DUR, KEY_UNSTEADY, KEY_VARC, MATCHED_PAIRS, VEH, div,
                        f, fmt_ci, fmt_dist, fmt_factor, fmt_minmax, fmt_n, fmt_range, g, isnum,
                        mm, table)

# The experiments of SPEC §9, by campaign name (sil/campaigns/paper/<name>.toml).
EXPERIMENTS = [
    ("exp1_cases", "1. The eight cases of Table X"),
    ("exp2_payload", "2. Payload sweep"),
    ("exp3_tracking", "3. Thruster tracking"),
    ("exp4_fidelity", "4. Model fidelity"),
    ("exp5_travel", "5. Travel distance"),
    ("exp6_duration", "6. Trajectory duration"),
    ("exp7_energy_split", "7. Energy split"),
    ("exp8_analytic", "8. Simplified analytic model: energies of the full system"),
    ("exp8b_analytic_like", "8b. Simplified analytic model, like for like"),
]
# Condition labels (SPEC §9 items 1, 2): (unsteady flow, density error), from override values.
COND_EXP1 = {(False, False): "stagnant", (True, True): "unsteady"}
COND_EXP1_TEXT = {"stagnant": "(a) stagnant flow, no density error",
                  "unsteady": "(b) unsteady flow + density error"}
COND_EXP1_KEYS = {"stagnant": {KEY_UNSTEADY: False, KEY_DENSITY: False},
                  "unsteady": {KEY_UNSTEADY: True, KEY_DENSITY: True}}
COND_EXP2_TEXT = {"A": "(A) stagnant, no density error", "B": "(B) stagnant, density error",
                  "C": "(C) unsteady, density error"}
COND_EXP2_KEYS = {"A": {KEY_UNSTEADY: False, KEY_DENSITY: False},
                  "B": {KEY_UNSTEADY: False, KEY_DENSITY: True},
                  "C": {KEY_UNSTEADY: True, KEY_DENSITY: True}}
# Below this deviation from 1 a ratio's saving is called "small" in the headline (5 %).
RATIO_SMALL = 0.05

CASE_COLORS = {"I": "#7f7f7f", "II": "#bcbd22", "III": "#17becf", "IV": "#1f77b4",
               "V": "#9467bd", "VI": "#8c564b", "VII": "#d62728", "VIII": "#ff7f0e"}
AXIS_COLORS = ["#1f77b4", "#2ca02c", "#d62728"]

plt.rcParams.update({
    "font.size": 11, "axes.titlesize": 11.5, "axes.labelsize": 11, "legend.fontsize": 9,
    "xtick.labelsize": 10, "ytick.labelsize": 10, "figure.dpi": 150, "savefig.dpi": 150,
    "axes.grid": True, "grid.alpha": 0.3,
})


def status_mark(run):
    if run is None:
        return " (missing)"
    return "" if finished(run) else f" ({run.get('status')}: {run.get('failure')})"


def finished(run):
    return run is not None and run.get("status") == "finished"


def disp_path(p, root=None):
    """A path for the report without machine-specific prefixes: relative to the repository,
    to `root` (the campaigns root), or from its 'sil/' component; else its basename."""
    if not p:
        return ""
    p = str(p)
    if not os.path.isabs(p):
        return p
    for base, prefix in ((REPO_ROOT, ""), (root, "")):
        if base and (p == base or p.startswith(base.rstrip("/") + "/")):
            return prefix + (os.path.relpath(p, base) if p != base else ".")
    m = re.search(r"(?:^|/)((?:sil|tools|tests|docs|firmware|plant)/.*)$", p)
    if m:
        return m.group(1)
    return os.path.basename(p)


# ----------------------------------------------------------------------------------------------
# Campaign data


def flatten_toml(d, prefix=""):
    out = {}
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(flatten_toml(v, key + "."))
        else:
            out[key] = v
    return out


def toml_keys(path):
    """Flattened keys of a scenario file (or {} if unreadable)."""
    try:
        with open(path, "rb") as fh:
            return flatten_toml(tomllib.load(fh))
    except (OSError, tomllib.TOMLDecodeError):
        return {}


def header_comment(path):
    """The leading comment block of a TOML file, as one paragraph."""
    lines = []
    try:
        with open(path) as fh:
            for line in fh:
                if not line.startswith("#"):
                    break
                lines.append(line[1:].strip())
    except OSError:
        return ""
    return " ".join(lines)


def parse_override(text):
    """'section.key=VALUE' (TOML value) -> (key, value); (None, None) if unparsable."""
    key, sep, val = str(text).partition("=")
    if not sep:
        return None, None
    try:
        return key.strip(), tomllib.loads("v = " + val.strip())["v"]
    except tomllib.TOMLDecodeError:
        return key.strip(), val.strip()


def same_value(a, b):
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b or (isinstance(a, bool) and isinstance(b, bool) and a == b)
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return abs(float(a) - float(b)) < 1e-9
    return a == b


def run_value(run, key):
    """A run's value of a scenario key: its override, else the documented default."""
    return run[key] if key in run else KEY_DEFAULTS.get(key)


def seed_of(run):
    s = run.get(KEY_SEED)
    return int(s) if isnum(s) else None


def matches(run, cond):
    return all(same_value(run_value(run, k), v) for k, v in cond.items())


class AmbiguousCondition(ValueError):
    """Two runs match one (condition, seed) slot: the condition selects more than one
    configuration."""


def differing_keys(a, b):
    """Override keys whose values differ between two runs."""
    keys = set(a.get("_overrides", [])) | set(b.get("_overrides", []))
    return sorted(k for k in keys if not same_value(run_value(a, k), run_value(b, k)))


_SCENARIO_DEFAULTS = None


def scenario_defaults():
    """{dotted key: default} from docs/SCENARIOS.md's tables, for the defaults that parse as
    TOML values (others are left out: a key set nowhere then compares by its absence)."""
    global _SCENARIO_DEFAULTS
    if _SCENARIO_DEFAULTS is not None:
        return _SCENARIO_DEFAULTS
    out = {}
    try:
        text = open(os.path.join(REPO_ROOT, "docs", "SCENARIOS.md")).read()
    except OSError:
        text = ""
    prefix = None
    for line in text.splitlines():
        m = re.match(r"^(?:### )?`\[([\w.]+)\]`", line)
        if m:
            prefix = m.group(1)
            continue
        m = re.match(r"^\| `(\w+)` \| [^|]* \| ([^|]*) \|", line)
        if m and prefix:
            val = m.group(2).strip()
            if val.startswith("`") and val.endswith("`") and val.count("`") == 2:
                val = val[1:-1]
            try:
                out.setdefault(f"{prefix}.{m.group(1)}", tomllib.loads("v = " + val)["v"])
            except tomllib.TOMLDecodeError:
                pass
    out.update(KEY_DEFAULTS)
    _SCENARIO_DEFAULTS = out
    return out


def _norm_value(v):
    if isinstance(v, bool) or v is None or isinstance(v, str):
        return v
    if isinstance(v, (int, float)):
        return float(f"{float(v):.12g}")
    if isinstance(v, (list, tuple)):
        return [_norm_value(x) for x in v]
    if isinstance(v, dict):
        return {k: _norm_value(x) for k, x in v.items()}
    return str(v)


def normalize_config(cfg, keys=()):
    """A configuration (dotted key → value) as a canonical JSON string: every key of `keys`
    (the union over the configurations being compared) filled with its documented default
    where unset, numbers to 12 significant digits."""
    dflt = scenario_defaults()
    full = dict(cfg)
    for k in keys:
        if k not in full and k in dflt:
            full[k] = dflt[k]
    return json.dumps({k: _norm_value(v) for k, v in full.items()}, sort_keys=True)


def cmp_name(c):
    """A headline comparison's short name: 'exp2, (C) unsteady, density error, 10 kg'."""
    return c["label"] + (f", {c['sub']}" if c.get("sub") else "")


def dedupe_comparisons(comps):
    """Group headline comparisons (dicts with pair, seeds, config, energies; see
    Report.add_comparison) that are the same evidence: the same pair of cases over the same
    seeds and either the same effective configuration (normalize_config, defaults filled over
    the union of keys) or bit-identical per-seed energies. Returns (groups, notes): groups in
    order of first appearance, each a list whose first entry stands for the group; notes name
    any inconsistency (same configuration, different energies: the runs are not
    reproducible; different configuration, identical energies: a setting that changed
    nothing)."""
    keys = set()
    for c in comps:
        keys |= set(c.get("config") or {})
    ident = [(c["pair"], tuple(c.get("seeds") or ()),
              normalize_config(c.get("config") or {}, keys)) for c in comps]
    parent = list(range(len(comps)))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    notes = []
    for i in range(len(comps)):
        for j in range(i):
            same_cfg = bool(comps[i].get("config")) and ident[i] == ident[j]
            ei, ej = comps[i].get("energies"), comps[j].get("energies")
            same_e = bool(ei) and ei == ej and comps[i]["pair"] == comps[j]["pair"]
            if same_cfg or same_e:
                parent[root(i)] = root(j)
            if same_cfg and ei and ej and ei != ej:
                notes.append(f"{cmp_name(comps[i])} and {cmp_name(comps[j])} have the same "
                             f"configuration but different energies (runs not reproducible?)")
            if same_e and not same_cfg:
                notes.append(f"{cmp_name(comps[i])} and {cmp_name(comps[j])} differ in their "
                             f"settings but have bit-identical energies: counted once")
    groups = {}
    for i in range(len(comps)):  # in order: each group's first entry is its earliest
        groups.setdefault(root(i), []).append(comps[i])
    return list(groups.values()), notes


class Experiment:
    """One campaign output directory: results.json (a list of rows, or an object with "runs"
    and optionally "provenance"), plan.json (run ids and their overrides), each run's
    summary.json (fields the results row lacks) and run log.

    Each run dict holds the results row, every override of the run as a key ("run.seed": 7)
    and the summary fields; `_overrides` keeps the override keys."""

    def __init__(self, directory, results):
        meta, rows = ({}, results) if isinstance(results, list) else \
            (results, results.get("runs", []))
        self.dir = directory
        self.plan = {}
        try:
            with open(os.path.join(directory, "plan.json")) as fh:
                self.plan = json.load(fh)
        except (OSError, json.JSONDecodeError):
            pass
        self.name = meta.get("name") or self.plan.get("name") or os.path.basename(directory)
        self.provenance = meta.get("provenance") or self.plan.get("provenance") or {}
        self.swept = meta.get("swept_keys", [])
        plan_ovr = {r.get("id"): r.get("overrides") for r in self.plan.get("runs", [])}
        self.runs = []
        for row in rows:
            r = dict(row)
            rid = r.get("id", "")
            rdir = os.path.join(directory, "runs", rid)
            ovr = plan_ovr.get(rid)
            if ovr is None:
                try:
                    with open(os.path.join(rdir, "overrides.json")) as fh:
                        ovr = json.load(fh)
                except (OSError, json.JSONDecodeError):
                    ovr = []
            applied = {}  # overrides apply in order: the last value of a key wins
            for text in ovr or []:
                k, v = parse_override(text)
                if k is not None:
                    applied[k] = v
            for k, v in applied.items():
                r.setdefault(k, v)  # the results row's own value (the swept one) first
            r["_overrides"] = list(applied)
            try:
                with open(os.path.join(rdir, "summary.json")) as fh:
                    for k, v in json.load(fh).items():
                        r.setdefault(k, v)
            except (OSError, json.JSONDecodeError):
                pass
            self.runs.append(r)
        camp = self.plan.get("campaign", "")
        if not (camp and os.path.exists(camp)):
            cand = os.path.join(REPO_ROOT, "sil", "campaigns", "paper", f"{self.name}.toml")
            camp = cand if os.path.exists(cand) else camp
        self.campaign_path = camp
        self.campaign = {}
        if camp and os.path.exists(camp):
            with open(camp, "rb") as fh:
                self.campaign = tomllib.load(fh)
        self.comment = header_comment(camp) if camp else ""
        base = meta.get("base") or self.plan.get("base", "")
        if base and not os.path.isabs(base):
            base = os.path.join(REPO_ROOT, base)
        if base and not os.path.exists(base):  # written on another machine: the repo's copy
            cand = os.path.join(REPO_ROOT, disp_path(base))
            base = cand if os.path.exists(cand) else base
        self.base_path = base
        self._logs = {}
        self.undecodable = {}  # run id -> {channel: messages of unknown type}
        self._prop_cache = {}

    # -- runs
    def select(self, cond=None, finished_only=True):
        """Runs matching cond ({key: value}; absent keys take their documented default),
        every seed, sorted by seed."""
        out = [r for r in self.runs if (not finished_only or finished(r))
               and matches(r, cond or {})]
        return sorted(out, key=lambda r: (seed_of(r) is None, seed_of(r) or 0))

    def one(self, cond=None):
        """The first run (lowest seed) matching cond, finished or not; None if none."""
        runs = self.select(cond, finished_only=False)
        return runs[0] if runs else None

    def find(self, **cond):
        """Compatibility: runs matching keys given with '__' for '.'."""
        return self.select({k.replace("__", "."): v for k, v in cond.items()},
                           finished_only=False)

    def values(self, key):
        """Sorted distinct values of a key over the runs."""
        vals = {run_value(r, key) for r in self.runs if run_value(r, key) is not None}
        try:
            return sorted(vals)
        except TypeError:
            return list(vals)

    def metric_value(self, run, metric):
        if callable(metric):
            return metric(run)
        v = run.get(metric)
        return float(v) if isnum(v) else None

    def slots(self, cond):
        """{seed: run} of every run matching cond, finished or not (seed None for runs without
        run.seed). Raises AmbiguousCondition when two runs fall in the same (condition, seed)
        slot: the condition is under-specified and would mix distinct configurations."""
        out = {}
        for r in self.select(cond, finished_only=False):
            s = seed_of(r)
            if s in out:
                raise AmbiguousCondition(
                    f"{self.name}: runs {out[s].get('id')!r} and {r.get('id')!r} both match "
                    f"{cond} with run.seed = {s}: the condition is under-specified (they differ "
                    f"in {', '.join(differing_keys(out[s], r)) or 'nothing visible'})")
            out[s] = r
        return out

    def series_full(self, metric, cond):
        """({seed: value}, [runs that gave no value]) of a metric (key or callable(run)) over
        the runs matching cond: a run gives no value when it did not finish or lacks the
        metric. One run per (condition, seed) slot, see slots()."""
        out, lost = {}, []
        for s, r in self.slots(cond).items():
            v = self.metric_value(r, metric) if finished(r) else None
            if v is None or not isnum(v):
                lost.append(r)
            else:
                out[s] = float(v)
        return out, lost

    def series(self, metric, cond):
        """{seed: value} of a metric over the finished runs matching cond (series_full)."""
        return self.series_full(metric, cond)[0]

    def dist(self, metric, cond):
        """stats.Dist of a metric over the seeds of cond; n_failed counts the runs of cond that
        gave no value."""
        vals, lost = self.series_full(metric, cond)
        d = stats.describe(list(vals.values()))
        d.n_failed = len(lost)
        return d

    def paired(self, metric, num_cond, den_cond):
        """Per-seed ratio metric(num)/metric(den) (stats.Paired); n_failed (also on its dist)
        counts the seeds left out because a run of either side failed, lacks the metric or is
        missing."""
        num, lost_n = self.series_full(metric, num_cond)
        den, lost_d = self.series_full(metric, den_cond)
        pa = stats.paired_ratio(num, den)
        every = set(num) | set(den) | {seed_of(r) for r in lost_n + lost_d}
        pa.n_failed = len(every - (set(num) & set(den)))
        pa.dist.n_failed = pa.n_failed
        return pa

    def base_keys(self):
        """Flattened keys of the campaign's base scenario (cached)."""
        if not hasattr(self, "_base_keys"):
            self._base_keys = toml_keys(self.base_path) if self.base_path else {}
        return self._base_keys

    def config(self, run, drop=(KEY_CASE, KEY_SEED)):
        """The run's effective scenario settings: the base scenario's keys, then the run's
        overrides (which include the campaign's [set]), without `drop`; keys set nowhere
        take their documented defaults (normalize_config)."""
        cfg = dict(self.base_keys())
        for k in run.get("_overrides", []):
            cfg[k] = run.get(k)
        return {k: v for k, v in cfg.items() if k not in drop}

    def n_seeds(self, cond):
        return len(self.select(cond))

    def log(self, run, channels=None):
        """The run's log (uvmslog.Log, all channels, decoded once and cached); None if the run
        or its log is missing. With `channels`, only those are decoded and nothing is cached
        (for loops over many seeds)."""
        if run is None:
            return None
        path = os.path.join(self.dir, "runs", run["id"], "run.lcmlog")
        if channels is not None and path not in self._logs:
            if not os.path.exists(path):
                return None
            lg = uvmslog.load(path, channels)
            if lg.skipped:
                self.undecodable[run["id"]] = dict(lg.skipped)
            return lg
        if path not in self._logs:
            self._logs[path] = uvmslog.load(path) if os.path.exists(path) else None
            if self._logs[path] is not None and self._logs[path].skipped:
                self.undecodable[run["id"]] = dict(self._logs[path].skipped)
        return self._logs[path]

    def elapsed_s(self):
        """Campaign wall time: plan.json (written first) to results.json (written last) [s]."""
        try:
            return (os.path.getmtime(os.path.join(self.dir, "results.json"))
                    - os.path.getmtime(os.path.join(self.dir, "plan.json")))
        except OSError:
            return float("nan")


def discover(root):
    """{name: Experiment} for every results.json in ROOT or one level below."""
    found = {}
    cands = [root] + [os.path.join(root, d) for d in sorted(os.listdir(root))
                      if os.path.isdir(os.path.join(root, d))]
    for d in cands:
        p = os.path.join(d, "results.json")
        if not os.path.isfile(p):
            continue
        try:
            with open(p) as fh:
                res = json.load(fh)
        except (OSError, json.JSONDecodeError) as e:
            print(f"report: skipping {p}: {e}", file=sys.stderr)
            continue
        exp = Experiment(d, res)
        if exp.name in found:
            print(f"report: {exp.name} found twice; using {found[exp.name].dir}", file=sys.stderr)
            continue
        found[exp.name] = exp
    return found


def energy(run):
    return run.get(E_EL) if run else None


def switches_text(cfg):
    """Table X meaning from the logged controller configuration (controller_config_t)."""
    att = int(cfg["attitude_control"][0])
    ref = "barycenter" if int(cfg["position_reference"][0]) == 1 else "vehicle"
    ff = int(cfg["position_feedforward"][0])
    fb = int(cfg["position_feedback"][0])
    if not att and not ff and not fb:
        return "no control (thrusters idle)"
    return (f"attitude {'on' if att else 'off'}, {ref} ref., FF {'on' if ff else 'off'}, "
            f"FB {'on' if fb else 'off'}")


def per_tick(log):
    """Telemetry (tick ≥ 0) and truth rows at the same ticks."""
    tm = log["UVMS_TELEMETRY"]
    tm = tm.select(tm["tick"] >= 0)
    tr = log["UVMS_TRUTH"]
    ticks = np.intersect1d(tm["tick"], tr["tick"])
    return tm.at_ticks(ticks), tr.at_ticks(ticks)


def rms(x, axis=0):
    x = np.asarray(x, float)
    return np.sqrt(np.mean(x * x, axis=axis)) if x.size else np.nan


def propulsive_from_truth(tr, rho, diameter_m):
    """E_p = ∫Σ|T_j|^1.5/√(2ρ·A_d) dt (SPEC §5) from a truth log's per-tick thrusts, with the
    thrust held over each tick (left Riemann sum over the tick boundaries)."""
    t = tr["t_s"]
    if len(t) < 2:
        return 0.0
    a_d = math.pi * diameter_m ** 2 / 4.0
    p = np.sum(np.abs(tr["thrust_N"]) ** 1.5, axis=1) / math.sqrt(2.0 * rho * a_d)
    return float(np.sum(p[:-1] * np.diff(t)))


# ----------------------------------------------------------------------------------------------
# Documented defaults and source tables (modeling choices)


def doc_default(key):
    """(unit, default) of a key in docs/SCENARIOS.md's tables, or None."""
    path = os.path.join(REPO_ROOT, "docs", "SCENARIOS.md")
    try:
        text = open(path).read()
    except OSError:
        return None
    m = re.search(r"^\| `" + re.escape(key) + r"` \| ([^|]*) \| ([^|]*) \|", text, re.M)
    return (m.group(1).strip(), m.group(2).strip().strip("`")) if m else None


def default_coeff_table():
    """Rows (distance [diameters], drag factor, added-mass factor) of the plant's
    DefaultCoeffTable() in plant/src/environment.cpp, or []."""
    path = os.path.join(REPO_ROOT, "plant", "src", "environment.cpp")
    try:
        text = open(path).read()
    except OSError:
        return []
    m = re.search(r"DefaultCoeffTable\(\)\s*\{(.*?)\n\}", text, re.S)
    if not m:
        return []
    num = r"([-+]?\d+(?:\.\d*)?(?:[eE][-+]?\d+)?)"
    return [tuple(float(x) for x in row) for row in
            re.findall(r"\{" + num + r",\s*" + num + r",\s*" + num + r"\}", m.group(1))]


def overrides_of(exps, dotted_keys):
    """Where any of dotted_keys is set in the campaigns ([set] or sweeps) or base scenarios."""
    where = []
    for e in exps.values():
        camp = e.campaign
        sets = flatten_toml(camp.get("set", {})) if camp else {}
        for k in list(sets):
            if k in dotted_keys:
                where.append(f"{e.name} [set] {k} = {sets[k]}")
        for sw in camp.get("sweep", []) if camp else []:
            for k in sw:
                if k in dotted_keys:
                    where.append(f"{e.name} sweep {k}")
        rep = camp.get("replicates") if camp else None
        if isinstance(rep, dict) and rep.get("key") in dotted_keys:
            where.append(f"{e.name} [replicates] {rep.get('key')}")
        base = toml_keys(e.base_path)
        for k in dotted_keys:
            if k in base:
                where.append(f"{disp_path(e.base_path)}: {k} = {base[k]}")
    return sorted(set(where))


# ----------------------------------------------------------------------------------------------
# Figures


class Figures:
    def __init__(self, out_dir):
        self.dir = os.path.join(out_dir, "figures")
        os.makedirs(self.dir, exist_ok=True)
        self.written = []

    def save(self, fig, name):
        path = os.path.join(self.dir, name)
        fig.savefig(path, dpi=150, bbox_inches="tight")
        plt.close(fig)
        self.written.append(name)
        return f"figures/{name}"


def img(md, path, caption):
    md += [f"![{caption}]({path})", "", f"*{caption}*", ""]


def err_bars(dists, scale=1.0):
    """(means, 2×n asymmetric error array of the 95 % CI; zeros without a CI)."""
    means = np.array([d.mean * scale if d.n else np.nan for d in dists], float)
    lo = np.array([(d.mean - d.lo) * scale if d.has_ci else 0.0 for d in dists], float)
    hi = np.array([(d.hi - d.mean) * scale if d.has_ci else 0.0 for d in dists], float)
    return means, np.vstack([np.abs(lo), np.abs(hi)])


# ----------------------------------------------------------------------------------------------
# Thruster-loop analysis (motor model of SPEC §5, control law §7.4), from the logged config


def _expm(m):
    """Matrix exponential by scaling and squaring with a Taylor series (small matrices)."""
    norm = np.linalg.norm(m, 1)
    s = max(0, int(math.ceil(math.log2(norm))) + 1) if norm > 0 else 0
    a = m / (2 ** s)
    out = np.eye(len(m))
    term = np.eye(len(m))
    for k in range(1, 25):
        term = term @ a / k
        out = out + term
    for _ in range(s):
        out = out @ out
    return out


def motor_step(cfg, omega_ref=1.0, horizon_ticks=4000, grid_s=1e-3):
    """Speed step response of one motor under the §7.4 loops ([64–66], [53]) without propeller
    load, for both power stages of SPEC §5, the loops evaluated once per controller tick:

    - current drive: the motor current follows the controller's integrated current command,
      I(t) = I_k + İ*_k·(t − t_k) over tick k, İ*_k = KB·(Î_k − I_k), Î_k = (J·KA·(ω̂ − ω_k)
      + b·ω_k)/km [64–66]; the shaft J·ω̇ = km·I − b·ω integrated exactly over the tick;
    - voltage drive: the voltage V_k = Rm·I_k + Lm·İ*_k + km·ω_k [53] is held over the tick and
      the motor L·İ = V − R·I − km·ω, J·ω̇ = km·I − b·ω integrated exactly;
    - and the same law in continuous time (İ = KB·(Î − I)): ω̈ + (KB + b/J)·ω̇ + KA·KB·ω =
      KA·KB·ω̂.

    Each response is evaluated exactly at the ticks and, between them, on a grid of
    `grid_s` (rounded to a whole fraction of the tick; the drives' tick inputs held). The 63 %
    rise times are the first crossings on that grid, linearly interpolated
    (stats.first_crossing). Returns dict: t_s and omega_current, omega_voltage,
    omega_continuous at the ticks; t_fine_s and the same three on the fine grid (keys
    *_fine); tau_current_s, tau_voltage_s, tau_continuous_s; resolution_s (the fine grid's
    step); tick_s."""
    c = {k: float(cfg[k][0]) for k in (
        "motor_resistance_ohm", "motor_inductance_H", "motor_torque_constant_Nm_A",
        "motor_viscous_friction_Nm_s", "rotor_inertia_kg_m2", "speed_gain_1_s",
        "current_gain_1_s", "tick_s")}
    r, l, km = c["motor_resistance_ohm"], c["motor_inductance_H"], c["motor_torque_constant_Nm_A"]
    b, j, ka, kb = (c["motor_viscous_friction_Nm_s"], c["rotor_inertia_kg_m2"],
                    c["speed_gain_1_s"], c["current_gain_1_s"])
    dt = c["tick_s"]
    sub = max(1, int(round(dt / grid_s)))  # fine-grid steps per tick

    def i_dot(i, w):
        i_hat = (j * ka * (omega_ref - w) + b * w) / km
        return kb * (i_hat - i)

    def powers(m):
        """expm(m·dt·q/sub) for q = 0..sub−1, stacked."""
        return np.array([_expm(m * dt * q / sub) for q in range(sub)])

    # voltage drive: x = (I, ω), input V held; augmented (I, ω, V)
    a = np.array([[-r / l, -km / l], [km / j, -b / j]])
    aug = np.zeros((3, 3))
    aug[:2, :2], aug[:2, 2] = a, [1.0 / l, 0.0]
    e = _expm(aug * dt)
    phi, gam = e[:2, :2], e[:2, 2]
    xv = np.zeros((horizon_ticks + 1, 2))
    vv = np.zeros(horizon_ticks)
    for k in range(horizon_ticks):
        i, w = xv[k]
        vv[k] = r * i + l * i_dot(i, w) + km * w
        xv[k + 1] = phi @ xv[k] + gam * vv[k]
    # current drive: x = (ω, I, İ*), İ* held over the tick
    ac = np.array([[-b / j, km / j, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]])
    ec = _expm(ac * dt)
    xi = np.zeros((horizon_ticks + 1, 2))  # (ω, I)
    idv = np.zeros(horizon_ticks)
    for k in range(horizon_ticks):
        w, i = xi[k]
        idv[k] = i_dot(i, w)
        xi[k + 1] = (ec @ np.array([w, i, idv[k]]))[:2]
    # continuous law: İ = KB·(Î − I), J·ω̇ = km·I − b·ω; state (I, ω, ω̂)
    acl = np.array([[-kb, kb * (b - j * ka) / km, kb * j * ka / km],
                    [km / j, -b / j, 0.0], [0.0, 0.0, 0.0]])
    ecl = _expm(acl * dt)
    xc = np.zeros((horizon_ticks + 1, 3))
    xc[0, 2] = omega_ref
    for k in range(horizon_ticks):
        xc[k + 1] = ecl @ xc[k]
    t = np.arange(horizon_ticks + 1) * dt

    # Between the ticks: from each tick's state (and held input), on the fine grid.
    def fine(pw, z, row, last):
        y = np.einsum("qab,kb->kqa", pw, z)[:, :, row].reshape(-1)
        return np.append(y, last)

    w_cur = fine(powers(ac), np.column_stack([xi[:-1], idv]), 0, xi[-1, 0])
    w_vol = fine(powers(aug), np.column_stack([xv[:-1], vv]), 1, xv[-1, 1])
    w_con = fine(powers(acl), xc[:-1], 1, xc[-1, 1])
    h = dt / sub
    tf = np.arange(horizon_ticks * sub + 1) * h
    level = (1.0 - math.exp(-1.0)) * omega_ref

    def rise(w):
        above = np.nonzero(w >= level)[0]
        if not len(above):
            return float("nan")
        k = int(above[0])
        lo = max(k - 1, 0)
        return stats.first_crossing(tf[lo:k + 1], w[lo:k + 1], level)

    return {"t_s": t, "omega_current": xi[:, 0], "omega_voltage": xv[:, 1],
            "omega_continuous": xc[:, 1], "t_fine_s": tf, "omega_current_fine": w_cur,
            "omega_voltage_fine": w_vol, "omega_continuous_fine": w_con,
            "tau_current_s": rise(w_cur), "tau_voltage_s": rise(w_vol),
            "tau_continuous_s": rise(w_con), "resolution_s": h, "tick_s": dt}


def best_lag(des, prod, dt, max_lag_s=15.0):
    """Delay L ≥ 0 [s] minimising the RMS of des(t) − prod(t + L) over the overlap, with that
    RMS and the RMS at L = 0. des, prod: (n, k)."""
    n = len(des)
    max_lag = int(min(max_lag_s / dt, n // 2))
    best = (0, float("inf"))
    errs = []
    for lag in range(max_lag + 1):
        d = des[: n - lag] - prod[lag:]
        e = float(np.sqrt(np.mean(np.sum(d * d, axis=1)))) if len(d) else float("inf")
        errs.append(e)
        if e < best[1]:
            best = (lag, e)
    return best[0] * dt, best[1], errs[0] if errs else float("nan")


# ----------------------------------------------------------------------------------------------
# Sections


class Report:
    def __init__(self, root, out_dir):
        self.root = os.path.abspath(root)
        self.out = os.path.abspath(out_dir)
        self.exps = discover(self.root)
        self.figs = Figures(self.out)
        self.md = []
        self.comparisons = []   # headline entries (dicts, see add_comparison)
        self.notes = []         # observations for the closing section
        self.track_summary = {}  # experiment 3: run -> RMS|F_des − F_prod| / RMS|F_des|
        self.split_summary = {}  # experiment 3, stagnant: case -> (∫Σ|P_pos|, ∫Σ|P_att|)
        self.motor = None
        self.analytic_limits = None
        self.exp8b = None
        self.energy_info = {}
        self._prop = {}

    def exp(self, name):
        return self.exps.get(name)

    def cfg(self, e, run):
        """The logged controller configuration of a run (UVMS_CONFIG), or None."""
        log = e.log(run)
        if log is None or "UVMS_CONFIG" not in log:
            return None
        return log["UVMS_CONFIG"]

    def missing(self, name):
        return [f"*Experiment `{name}` was not found among the campaign outputs: this section "
                f"is skipped.*", ""]

    # -- drive and metrics
    def drives(self):
        return Counter(r.get("drive") for e in self.exps.values() for r in e.runs)

    def drive(self):
        """The drive of the runs ("current", "voltage"), "mixed", or None (not recorded)."""
        d = {k for k in self.drives() if k}
        if not d:
            return None
        return d.pop() if len(d) == 1 else "mixed"

    def drive_text(self):
        d = self.drive()
        if d is None:
            return ("not recorded in summary.json (runs of a build without the drive setting, "
                    "whose only power stage was the voltage drive)")
        if d == "mixed":
            return "mixed: " + ", ".join(f"{k} ({n} runs)" for k, n in self.drives().items() if k)
        return f"**{d}** drive"

    def metric(self, e, name):
        """A metric for Experiment.series: the summary field; for the propulsive energy, when
        summary.json lacks it (older builds), computed from the truth log (SPEC §5)."""
        if name != E_P:
            return name

        def prop(run):
            v = run.get(E_P)
            if isnum(v):
                return float(v)
            key = (e.name, run.get("id"))
            if key not in self._prop:
                lg = e.log(run, ["UVMS_TRUTH", "UVMS_CONFIG"])
                val = None
                if lg is not None and "UVMS_TRUTH" in lg and "UVMS_CONFIG" in lg:
                    rho = run.get("environment.density_kg_m3")
                    if not isnum(rho):
                        d = doc_default("density_kg_m3")
                        rho = float(d[1]) if d else 1025.0
                    val = propulsive_from_truth(lg["UVMS_TRUTH"], float(rho),
                                                float(lg["UVMS_CONFIG"]["propeller_diameter_m"][0]))
                    self.prop_from_logs = True
                self._prop[key] = val
            return self._prop[key]
        return prop

    def add_comparison(self, exp, label, cond_common, unsteady, sub="", num=BARY, den=VEH,
                       with_err=False):
        """Record a barycenter-vs-vehicle comparison (paired per seed) for the headline and
        return its stats.Paired."""
        e = self.exp(exp)
        cn, cd = dict(cond_common, **{KEY_CASE: num}), dict(cond_common, **{KEY_CASE: den})
        pa = e.paired(E_EL, cn, cd)
        # What identifies the configuration (for counting evidence once, sec_headline): the
        # vehicle run's effective settings without case and seed, and the per-seed energies.
        den_runs = e.slots(cd)
        rep_run = next(iter(den_runs.values()), None)
        num_s, den_s = e.series(E_EL, cn), e.series(E_EL, cd)
        ent = dict(exp=exp, label=label, sub=sub, unsteady=bool(unsteady), paired=pa,
                   pair=f"{num}/{den}", verdict=stats.compare(pa),
                   config=e.config(rep_run) if rep_run else {},
                   seeds=tuple(sorted(s for s in den_runs if s is not None)),
                   energies=tuple((s, num_s[s], den_s[s]) for s in pa.seeds))
        if with_err:
            ent["err_den"] = e.dist(ERR, dict(cond_common, **{KEY_CASE: den}))
            ent["err_num"] = e.dist(ERR, dict(cond_common, **{KEY_CASE: num}))
        self.comparisons.append(ent)
        return pa

    def seeds_text(self, e, cond):
        runs = e.select(cond)
        n = len(runs)
        seeds = sorted({seed_of(r) for r in runs if seed_of(r) is not None})
        if n <= 1:
            return "one run"
        return (f"{n} runs, seeds {seeds[0]}–{seeds[-1]}" if seeds and len(seeds) == n
                else f"{n} runs")

    # -- experiment 1
    def sec_exp1(self):
        md = []
        e = self.exp("exp1_cases")
        if e is None:
            return self.missing("exp1_cases")
        md += [f"*Campaign file:* {e.comment}", ""] if e.comment else []
        conds = ["stagnant", "unsteady"]
        cc = {(c, k): dict(COND_EXP1_KEYS[k], **{KEY_CASE: c}) for c in CASES for k in conds}
        rep_runs = {ck: e.one(cond) for ck, cond in cc.items()}
        meaning, series, check = {}, {}, []
        for (c, k), r in rep_runs.items():
            log = e.log(r)
            if log is None:
                continue
            if "UVMS_CONFIG" in log:
                meaning.setdefault(c, switches_text(log["UVMS_CONFIG"]))
            if "UVMS_TRUTH" in log and "UVMS_TELEMETRY" in log:
                _, t, eps = uvmslog.ee_error(log)
                series[(c, k)] = (t, eps)
                if len(eps) and isnum(r.get(ERR)):
                    check.append(abs(eps.mean() - r[ERR]) / max(abs(r[ERR]), 1e-300))
        self.case_meaning = meaning
        # Bands over seeds for IV and VII in the unsteady condition.
        bands = {}
        for c in (VEH, BARY):
            runs = e.select(cc[(c, "unsteady")])
            if len(runs) < 2:
                continue
            eps_all = []
            for r in runs:
                lg = e.log(r, ["UVMS_TRUTH", "UVMS_TELEMETRY"])
                if lg is None or "UVMS_TRUTH" not in lg or "UVMS_TELEMETRY" not in lg:
                    continue
                _, t, eps = uvmslog.ee_error(lg)
                eps_all.append((t, eps))
            m = min((len(t) for t, _ in eps_all), default=0)
            if m and len(eps_all) >= 2:
                arr = np.array([eps[:m] for _, eps in eps_all])
                bands[c] = (eps_all[0][0][:m], arr.min(axis=0), arr.max(axis=0), len(eps_all))

        fig, axes = plt.subplots(1, 2, figsize=(14, 5.6), sharey=True)
        for ax, k in zip(axes, conds):
            for c in CASES:
                if (c, k) not in series:
                    continue
                t, eps = series[(c, k)]
                y = np.where(eps > 0, eps * 1e3, np.nan)
                lw = 2.4 if c in (VEH, BARY) else 1.3
                ax.plot(t, y, color=CASE_COLORS[c], lw=lw,
                        label=f"{c}: {meaning.get(c, '?')}"
                              + (" — vehicle stabilization" if c == VEH else "")
                              + (" — barycenter stabilization" if c == BARY else ""))
                if k == "unsteady" and c in bands:
                    tb, lo, hi, nb = bands[c]
                    ax.fill_between(tb, np.maximum(lo * 1e3, 1e-6), hi * 1e3,
                                    color=CASE_COLORS[c], alpha=0.18, lw=0)
            ax.set_yscale("log")
            rep_seed = seed_of(rep_runs[(VEH, k)]) if rep_runs[(VEH, k)] else None
            ax.set_title(f"EE error, {COND_EXP1_TEXT[k]}"
                         + (f"\nlines: seed {rep_seed}; shaded: range over "
                            f"{max((b[3] for b in bands.values()), default=0)} seeds (IV, VII)"
                            if k == "unsteady" and bands else ""))
            ax.set_xlabel("time t [s]")
        late = [eps[t >= 0.1 * t[-1]] * 1e3 for t, eps in series.values() if len(t)]
        late = np.concatenate(late) if late else np.array([])
        late = late[late > 0]
        if late.size:
            axes[0].set_ylim(10 ** math.floor(math.log10(late.min())),
                             10 ** math.ceil(math.log10(late.max())))
        axes[0].set_ylabel("EE error ε = |p_EE − p̂_EE| [mm] (log)")
        h, lab = axes[0].get_legend_handles_labels()
        fig.legend(h, lab, loc="lower center", ncol=2, fontsize=9.5, frameon=False,
                   bbox_to_anchor=(0.5, -0.16))
        fig.suptitle("Experiment 1: end-effector error of the eight cases (docs/MODEL.md §9 Table X, §10)")
        fig.tight_layout()
        md += ["### EE error over time", ""]
        img(md, self.figs.save(fig, "exp1_ee_error.png"),
            "EE error ε(t) (docs/MODEL.md §10) of the eight cases; left stagnant, right unsteady flow "
            "plus density error (one seed drawn; IV and VII with the range over all seeds "
            "shaded). IV (vehicle) and VII (barycenter) drawn thick.")
        if check:
            md += [f"Check: the mean EE error recomputed from each log drawn (truth "
                   f"`ee_position_m` vs telemetry `ee_estimate_m`, matched by tick) agrees with "
                   f"summary.json to {g(max(check), 2)} relative (worst of {len(check)} runs).", ""]

        # Tables.
        prop = self.metric(e, E_P)
        md += ["### Mean EE error and energies", "",
               f"Stagnant: one deterministic run per case. Unsteady: {self.seeds_text(e, cc[(VEH, 'unsteady')])} "
               f"per case; mean ± half-width of the 95 % confidence interval (Student t). "
               f"E_el = thruster (electrical) energy ∫Σmax(V·I, 0) dt, E_p = propulsive "
               f"(actuator-disk) energy ∫Σ|T|^1.5/√(2ρA_d) dt (docs/MODEL.md §5).", ""]
        rows = []
        dists = {}
        for c in CASES:
            cells = []
            for k in conds:
                de, dp = e.dist(E_EL, cc[(c, k)]), e.dist(prop, cc[(c, k)])
                dr, dx = e.dist(ERR, cc[(c, k)]), e.dist("max_ee_error_m", cc[(c, k)])
                dists[(c, k)] = (de, dp, dr)
                r = rep_runs[(c, k)]
                cells += [fmt_dist(dr, 2, 1e3) + status_mark(r), fmt_dist(dx, 2, 1e3),
                          fmt_dist(de, 1), fmt_dist(dp, 3, sig=3)]
            name = f"**{c}**" if c in (VEH, BARY) else c
            mean = meaning.get(c, "?")
            if c == VEH:
                mean = f"**{mean} = vehicle stabilization**"
            elif c == BARY:
                mean = f"**{mean} = barycenter stabilization**"
            rows.append([name, mean] + cells)
        md += table(["case", "Table X (from the logged config)",
                     "stagnant: mean ε [mm]", "max ε [mm]", "E_el [J]", "E_p [J]",
                     "unsteady: mean ε [mm]", "max ε [mm]", "E_el [J]", "E_p [J]"], rows)
        srows = []
        for c in CASES:
            de, dp, dr = dists[(c, "unsteady")]
            if de.n < 2:
                continue
            srows.append([c, fmt_n(de), g(de.mean, 4), fmt_ci(de, 1), fmt_minmax(de, 1),
                          mm(dr.mean), fmt_ci(dr, 2, 1e3), fmt_minmax(dr, 2, 1e3)])
        if srows:
            md += ["**Unsteady condition over seeds** (E_el and mean ε):", ""]
            md += table(["case", "n", "E_el mean [J]", "95 % CI", "min–max", "ε mean [mm]",
                         "95 % CI", "min–max"], srows)

        # Vehicle vs barycenter pairs, paired per seed.
        rr = []
        for k in conds:
            for v, b in MATCHED_PAIRS:
                fb = (v, b) in FEEDBACK_PAIRS
                common = COND_EXP1_KEYS[k]
                if fb:
                    pa = self.add_comparison("exp1_cases", f"exp1, {COND_EXP1_TEXT[k]}, "
                                             f"{b} vs {v}", common, k == "unsteady", num=b, den=v,
                                             with_err=True)
                else:
                    pa = e.paired(E_EL, dict(common, **{KEY_CASE: b}), dict(common, **{KEY_CASE: v}))
                pp = e.paired(prop, dict(common, **{KEY_CASE: b}), dict(common, **{KEY_CASE: v}))
                pe = e.paired(ERR, dict(common, **{KEY_CASE: b}), dict(common, **{KEY_CASE: v}))
                rr.append([COND_EXP1_TEXT[k], f"{b} / {v}" + ("" if fb else " (no feedback)"),
                           fmt_n(pa.dist), fmt_dist(pa.dist, 3), fmt_ci(pa.dist, 3),
                           fmt_minmax(pa.dist, 3), f"{pa.n_below_1} of {pa.n}",
                           stats.compare(pa) or "n/a", fmt_dist(pp.dist, 3), fmt_dist(pe.dist, 3)])
        md += ["**Vehicle vs barycenter stabilization**, the case pairs that differ only in the "
               "position reference; ratios barycenter/vehicle paired per seed:", ""]
        md += table(["condition", "barycenter / vehicle", "n", "E_el ratio (mean ± CI)", "95 % CI",
                     "min–max", "barycenter cheaper in", "verdict", "E_p ratio", "ε ratio"], rr)

        # Bar chart with CI error bars.
        fig, axes = plt.subplots(1, 2, figsize=(13, 4.4))
        x = np.arange(len(CASES))
        wdt = 0.38
        for i, k in enumerate(conds):
            en, en_err = err_bars([dists[(c, k)][0] for c in CASES])
            er, er_err = err_bars([dists[(c, k)][2] for c in CASES], 1e3)
            lab = COND_EXP1_TEXT[k] + (" (mean, 95 % CI)" if np.any(en_err > 0) else "")
            axes[0].bar(x + (i - 0.5) * wdt, en, wdt, yerr=en_err, capsize=3, label=lab)
            for xi, v in zip(x, en):
                if isnum(v) and v == 0.0:
                    axes[0].text(xi + (i - 0.5) * wdt, 0, "0 J", ha="center", va="bottom",
                                 fontsize=8.5)
            axes[1].bar(x + (i - 0.5) * wdt, er, wdt, yerr=er_err, capsize=3, label=lab)
        for ax, yl, ttl in ((axes[0], "thruster energy E_el [J]", "Thruster energy per case"),
                            (axes[1], "mean EE error [mm] (log)", "Mean EE error per case")):
            ax.set_xticks(x, CASES)
            ax.set_xlabel("case (Table X)")
            ax.set_ylabel(yl)
            ax.set_title(ttl)
        axes[1].set_yscale("log")
        h, lab = axes[0].get_legend_handles_labels()
        fig.suptitle("Experiment 1: energy and mean EE error, cases I–VIII")
        fig.tight_layout()
        fig.legend(h, lab, loc="lower center", ncol=2, fontsize=9.5, frameon=False,
                   bbox_to_anchor=(0.5, -0.08))
        img(md, self.figs.save(fig, "exp1_energy_error_bars.png"),
            "Thruster energy and mean EE error of the eight cases in both conditions; error bars: "
            "95 % confidence interval of the mean over seeds (unsteady).")
        return md

    # -- experiment 2
    def sec_exp2(self):
        e = self.exp("exp2_payload")
        if e is None:
            return self.missing("exp2_payload")
        md = [f"*Campaign file:* {e.comment}", ""] if e.comment else []
        pays = e.values(KEY_PAYLOAD)
        conds = ["A", "B", "C"]

        def cond(c, k, p):
            return dict(COND_EXP2_KEYS[k], **{KEY_CASE: c, KEY_PAYLOAD: p})

        figs = {}
        for what, key, scale, ylab, fname in (
                ("energy", E_EL, 1.0, "thruster energy E_el [J]", "exp2_payload_energy.png"),
                ("error", ERR, 1e3, "mean EE error [mm]", "exp2_payload_error.png")):
            fig, axes = plt.subplots(1, 3, figsize=(14, 4.3), sharey=True)
            for ax, k in zip(axes, conds):
                span = (max(pays) - min(pays)) if len(pays) > 1 else 1.0
                for c, mk, dx in ((VEH, "o-", -0.008), (BARY, "s-", 0.008)):
                    y, yerr = err_bars([e.dist(key, cond(c, k, p)) for p in pays], scale)
                    ax.errorbar(np.asarray(pays, float) + dx * span, y, yerr=yerr, fmt=mk,
                                color=CASE_COLORS[c], lw=2,
                                capsize=3,
                                label=f"{c} ({'vehicle' if c == VEH else 'barycenter'} stab.)")
                n = e.n_seeds(cond(VEH, k, pays[0])) if pays else 0
                ax.set_title(COND_EXP2_TEXT[k] + (f"\nmean and 95 % CI over {n} seeds"
                                                  if n > 1 else ""))
                ax.set_xlabel("payload m_P [kg]")
                ax.legend()
            if what == "error":
                axes[0].set_yscale("log")
                ylab += " (log)"
            axes[0].set_ylabel(ylab)
            fig.suptitle(f"Experiment 2: {what} vs payload, vehicle (IV) vs barycenter (VII)")
            fig.tight_layout()
            figs[what] = self.figs.save(fig, fname)
        img(md, figs["energy"], "Thruster energy vs payload in conditions A, B, C (error bars: "
            "95 % CI over seeds).")
        img(md, figs["error"], "Mean EE error vs payload in conditions A, B, C (error bars: "
            "95 % CI over seeds).")
        prop = self.metric(e, E_P) if all(isnum(r.get(E_P)) for r in e.runs) else None
        rows = []
        for k in conds:
            for p in pays:
                dv, db = e.dist(E_EL, cond(VEH, k, p)), e.dist(E_EL, cond(BARY, k, p))
                pa = self.add_comparison("exp2_payload", f"exp2, {COND_EXP2_TEXT[k]}",
                                         COND_EXP2_KEYS[k] | {KEY_PAYLOAD: p}, k == "C",
                                         sub=f"{f(p, 0)} kg")
                cells = [COND_EXP2_TEXT[k], f(p, 0), fmt_n(dv), fmt_dist(dv, 1), fmt_dist(db, 1)]
                if prop:
                    cells += [fmt_dist(e.dist(prop, cond(VEH, k, p)), 3, sig=3),
                              fmt_dist(e.dist(prop, cond(BARY, k, p)), 3, sig=3)]
                cells += [fmt_dist(pa.dist, 3), fmt_minmax(pa.dist, 3),
                          f"{pa.n_below_1} of {pa.n}",
                          fmt_dist(e.dist(ERR, cond(VEH, k, p)), 2, 1e3),
                          fmt_dist(e.dist(ERR, cond(BARY, k, p)), 2, 1e3)]
                rows.append(cells)
        hdr = ["condition", "m_P [kg]", "n", "E_el(IV) [J]", "E_el(VII) [J]"]
        if prop:
            hdr += ["E_p(IV) [J]", "E_p(VII) [J]"]
        hdr += ["E_el(VII)/E_el(IV) paired", "min–max", "VII cheaper in", "mean ε IV [mm]",
                "mean ε VII [mm]"]
        md += ["Mean ± half-width of the 95 % CI over seeds where seeded (condition C); ratios "
               "paired per seed.", ""]
        md += table(hdr, rows)
        return md

    # -- experiment 3
    def sec_exp3(self):
        e = self.exp("exp3_tracking")
        if e is None:
            return self.missing("exp3_tracking")
        md = [f"*Campaign file:* {e.comment}", ""] if e.comment else []
        order = [(c, k) for c in (VEH, BARY) for k in ("stagnant", "unsteady")]
        conds = {(c, k): dict(COND_EXP1_KEYS[k], **{KEY_CASE: c}) for c, k in order}
        runs = {ck: e.one(conds[ck]) for ck in order}
        logs = {ck: e.log(r) for ck, r in runs.items()}
        logs = {ck: lg for ck, lg in logs.items()
                if lg is not None and "UVMS_TELEMETRY" in lg and "UVMS_TRUTH" in lg}
        if not logs:
            return md + ["*No logs of experiment 3 could be read.*", ""]
        useed = seed_of(runs[(VEH, "unsteady")]) if runs[(VEH, "unsteady")] else None
        nseeds = e.n_seeds(conds[(VEH, "unsteady")])
        if nseeds > 1:
            md += [f"The time series, tracking and energy-breakdown figures and tables below show "
                   f"one seed (run.seed = {useed}) of the {nseeds} of the unsteady condition; the "
                   f"Observations give its energies' distribution over all seeds.", ""]

        fig, axes = plt.subplots(len(order), 2, figsize=(14, 3.0 * len(order)), sharex=True)
        track_rows = []
        for row, ck in enumerate(order):
            if ck not in logs:
                continue
            tm, tr = per_tick(logs[ck])
            t = tm["t_s"]
            for col, (dk, pk, unit, nm) in enumerate((
                    ("force_des_N", "thrust_force_N", "N", "force"),
                    ("moment_des_Nm", "thrust_moment_Nm", "N·m", "moment"))):
                ax = axes[row, col]
                for i, ax_name in enumerate("xyz"):
                    ax.plot(t, tm[dk][:, i], color=AXIS_COLORS[i], lw=1.6,
                            label=f"desired {ax_name}")
                    ax.plot(t, tr[pk][:, i], color=AXIS_COLORS[i], lw=1.4, ls="--",
                            label=f"produced {ax_name}")
                sd = f", seed {useed}" if ck[1] == "unsteady" and nseeds > 1 else ""
                ax.set_title(f"case {ck[0]}, {COND_EXP1_TEXT[ck[1]]}{sd}: {nm}", fontsize=10.5)
                ax.set_ylabel(f"{nm} [{unit}]")
                if row == 0:
                    ax.legend(ncol=3, fontsize=8)
            dt = float(np.median(np.diff(t))) if len(t) > 1 else float("nan")
            des = np.hstack([tm["force_des_N"], tm["moment_des_Nm"]])
            prod = np.hstack([tr["thrust_force_N"], tr["thrust_moment_Nm"]])
            lag, err_lag, err0 = best_lag(des, prod, dt) if len(t) > 2 else (np.nan,) * 3
            track_rows.append((ck, tm, tr, lag, err_lag, err0))
        self.track_lags = track_rows
        for ax in axes[-1]:
            ax.set_xlabel("time t [s]")
        fig.suptitle("Experiment 3: desired (solid, telemetry F_P0, N_P0) vs produced "
                     "(dashed, plant thrust) force and moment, inertial frame", y=1.0)
        fig.tight_layout()
        img(md, self.figs.save(fig, "exp3_force_tracking.png"),
            "Desired vs produced control force and moment, cases IV and VII, both conditions.")
        rows = []
        for ck, tm, tr, lag, err_lag, err0 in track_rows:
            fd, fp = tm["force_des_N"], tr["thrust_force_N"]
            nd, np_ = tm["moment_des_Nm"], tr["thrust_moment_Nm"]
            rf = rms(np.linalg.norm(fd, axis=1))
            rfe = rms(np.linalg.norm(fd - fp, axis=1))
            self.track_summary[f"{ck[0]} {ck[1]}"] = div(rfe, rf)
            rows.append([f"{ck[0]}, {ck[1]}", g(rf, 3), g(rfe, 3), f(100 * div(rfe, rf), 1),
                         g(rms(np.linalg.norm(nd, axis=1)), 3),
                         g(rms(np.linalg.norm(nd - np_, axis=1)), 3),
                         f(lag, 2), g(err0, 3), g(err_lag, 3)])
        md += table(["run", "RMS |F_des| [N]", "RMS |F_des − F_prod| [N]", "relative [%]",
                     "RMS |N_des| [N·m]", "RMS |N_des − N_prod| [N·m]",
                     "best delay of produced [s]", "RMS wrench error at 0 s delay",
                     "at best delay"], rows)
        md += ["The delay column is the shift L ≥ 0 that minimises the RMS of the 6-vector "
               "(F_des, N_des)(t) − (F_prod, N_prod)(t + L) (mixed N and N·m).", ""]

        cfg = next((logs[ck]["UVMS_CONFIG"] for ck in order
                    if ck in logs and "UVMS_CONFIG" in logs[ck]), None)
        if cfg is not None:
            md += self.motor_section(cfg)

        # Position vs attitude thrust components.
        fig, axes = plt.subplots(2, 2, figsize=(13, 7.5), sharey=True)
        xs = np.arange(8)
        split_rows = []
        for ax, ck in zip(axes.flat, order):
            if ck not in logs:
                ax.set_visible(False)
                continue
            tm, tr = per_tick(logs[ck])
            ppos, patt = tm["thrust_pos_N"], tm["thrust_att_N"]
            ax.bar(xs - 0.2, rms(ppos) * 1e3, 0.4, label="position part P_pos (RMS)")
            ax.bar(xs + 0.2, rms(patt) * 1e3, 0.4, label="attitude part P_att (RMS)")
            ax.set_xticks(xs, [str(j + 1) for j in xs])
            ax.set_xlabel("thruster j")
            sd = f", seed {useed}" if ck[1] == "unsteady" and nseeds > 1 else ""
            ax.set_title(f"case {ck[0]}, {COND_EXP1_TEXT[ck[1]]}{sd}", fontsize=10.5)
            ax.legend(fontsize=8.5)
            dt = float(np.median(np.diff(tm["t_s"]))) if len(tm["t_s"]) > 1 else 0.0
            ip, ia = np.abs(ppos).sum() * dt, np.abs(patt).sum() * dt
            if ck[1] == "stagnant":
                self.split_summary[ck[0]] = (ip, ia)
            split_rows.append([f"{ck[0]}, {ck[1]}", g(ip, 3), g(ia, 3),
                               g(np.abs(tm["thrust_des_N"]).sum() * dt, 3)])
        for ax in axes[:, 0]:
            ax.set_ylabel("RMS thrust [mN]")
        fig.suptitle("Experiment 3: position and attitude components of the allocated thrust "
                     "per thruster (docs/MODEL.md §7.3)")
        fig.tight_layout()
        img(md, self.figs.save(fig, "exp3_thrust_split.png"),
            "RMS of the position (H⁺(F;0)) and attitude (H⁺(0;N)) parts of each thruster's "
            "allocated thrust.")
        md += table(["run", "∫Σ|P_pos| dt [N·s]", "∫Σ|P_att| dt [N·s]", "∫Σ|P| dt [N·s]"],
                    split_rows)
        md += self.energy_breakdown(e, runs, logs, order, conds)
        return md

    def motor_section(self, cfg):
        """The thruster speed loop's step response for both drives; the runs' drive named."""
        ms = motor_step(cfg)
        self.motor = ms
        drive = self.drive()
        used = drive if drive in ("current", "voltage") else "voltage"  # unrecorded: old build
        res = ms["resolution_s"]

        def tau_txt(x):
            return f"{f(x, 3)} s"
        md = []
        fig, axes = plt.subplots(1, 2, figsize=(13, 4.2), sharey=True)
        spans = [5 * x for x in (ms["tau_current_s"], ms["tau_voltage_s"]) if isnum(x)] or [2.0]
        tf = ms["t_fine_s"]
        for ax, tmax in zip(axes, (min(spans), max(spans))):
            sel = tf <= tmax
            selk = ms["t_s"] <= tmax
            for key, tau, lbl, col in (("omega_current", "tau_current_s", "current drive",
                                        "#1f77b4"),
                                       ("omega_voltage", "tau_voltage_s", "voltage drive",
                                        "#ff7f0e")):
                is_used = key.endswith(used)
                ax.plot(tf[sel], ms[key + "_fine"][sel], lw=2.6 if is_used else 1.6, color=col,
                        ls="-" if is_used else ":",
                        label=f"{lbl}{' (these runs)' if is_used else ' (alternative)'}: 63 % "
                              f"at {tau_txt(ms[tau])}")
                if is_used and selk.sum() <= 80:
                    ax.plot(ms["t_s"][selk], ms[key][selk], "o", ms=3, color=col,
                            label=f"{lbl} at the controller ticks")
            ax.plot(tf[sel], ms["omega_continuous_fine"][sel], lw=1.4, ls="--", color="gray",
                    label=f"same law in continuous time: 63 % at "
                          f"{tau_txt(ms['tau_continuous_s'])}")
            ax.axhline(1.0 - math.exp(-1.0), color="k", lw=0.8, ls=":")
            for tau, col in (("tau_current_s", "#1f77b4"), ("tau_voltage_s", "#ff7f0e"),
                             ("tau_continuous_s", "gray")):
                if isnum(ms[tau]) and ms[tau] <= tmax:
                    ax.plot([ms[tau]], [1.0 - math.exp(-1.0)], "x", color=col, ms=8, mew=2)
            ax.set_xlabel("time t [s]")
            ax.set_title(f"first {g(tmax, 2)} s")
        axes[0].set_ylabel("shaft speed ω / ω̂ [-]")
        axes[0].legend(loc="lower right", fontsize=8)
        axes[1].legend(loc="lower right", fontsize=8)
        fig.suptitle("Thruster speed loop (docs/MODEL.md §7.4 [64–66], motor §5): unit step of "
                     f"ω̂, loops run every {g(ms['tick_s'], 3)} s tick\nlogged configuration, no "
                     f"propeller load; 63 % times (×) interpolated on a {g(res * 1e3, 2)} ms grid")
        fig.tight_layout()
        tau_used = ms[f"tau_{used}_s"]
        other = "voltage" if used == "current" else "current"
        ka, kb = float(cfg["speed_gain_1_s"][0]), float(cfg["current_gain_1_s"][0])
        b_j = float(cfg["motor_viscous_friction_Nm_s"][0]) / float(cfg["rotor_inertia_kg_m2"][0])
        wn = math.sqrt(ka * kb)
        zeta = (kb + b_j) / (2.0 * wn)
        md += ["**Thruster response.** The loops of docs/MODEL.md §7.4 run once per controller "
               f"tick. The runs used the {self.drive_text()} (docs/MODEL.md §5). For the logged "
               f"motor and loop parameters, a unit step of the desired shaft speed reaches 63 % "
               f"after {tau_txt(tau_used)} with the {used} drive, against "
               f"{tau_txt(ms['tau_continuous_s'])} for the same law in continuous time "
               f"(ω̈ + (KB + b/J)·ω̇ + KA·KB·ω = KA·KB·ω̂: ω_n = {g(wn, 3)} rad/s, ζ = "
               f"{g(zeta, 3)}: b/J = {g(b_j, 3)} 1/s adds to KB in the damping, since the "
               f"friction acts at once and its compensation in Î only through the lagging "
               f"current) and {tau_txt(ms[f'tau_{other}_s'])} with the {other} drive. The "
               "drives are the exact discretisation of the motor equations [53–55] over the "
               "tick; all three responses are evaluated on a "
               f"{g(res * 1e3, 2)} ms grid and each 63 % time is the first crossing, linearly "
               "interpolated between grid points (a tick-grid reading would be quantised to "
               f"{g(ms['tick_s'], 3)} s). "
               + ("With the current drive the power stage makes the current follow the "
                  "controller's integrated command, so the speed loop settles with KA and KB; "
                  "the voltage drive, whose held voltage excites the motor's lightly damped "
                  "electromechanical mode, is an alternative study of a slow drive, not the "
                  "paper's." if used == "current" else
                  "With the voltage drive the held voltage drives ω close to V/k_m within each "
                  "tick and the current loop's correction acts only through the small L·İ* "
                  "term; the current drive (the paper's reading, docs/MODEL.md §5) settles with "
                  "KA and KB. These runs therefore study a slow drive, not the paper's."), ""]
        img(md, self.figs.save(fig, "exp3_motor_step.png"),
            "Step response of one thruster's speed loop with the current and the voltage drive "
            "(loops evaluated every tick, the motor exactly between ticks) and the "
            "continuous-time law; 63 % times are first crossings interpolated on a "
            f"{g(res * 1e3, 2)} ms grid.")
        return md

    def energy_breakdown(self, e, runs, logs, order, conds):
        """Where the thruster energy goes (exp3 logs): motor friction, copper, the rest."""
        md = ["### Where the thruster energy goes", ""]
        rows, per_thr = [], []
        stag_cfg = None
        for ck in order:
            if ck in logs and ck[1] == "stagnant" and "UVMS_CONFIG" in logs[ck]:
                stag_cfg = logs[ck]["UVMS_CONFIG"]
        info = {}
        for ck in order:
            if ck not in logs or "UVMS_ACTUATORS" not in logs[ck]:
                continue
            lg = logs[ck]
            cfg = lg["UVMS_CONFIG"]
            tm, tr = per_tick(lg)
            ac = lg["UVMS_ACTUATORS"].at_ticks(tm["tick"])
            dt = float(cfg["tick_s"][0])
            w, cur, v = tr["motor_speed_rad_s"], tr["motor_current_A"], ac["motor_voltage_V"]
            b, res = float(cfg["motor_viscous_friction_Nm_s"][0]), float(cfg["motor_resistance_ohm"][0])
            e_vi = np.maximum(v * cur, 0.0).sum(axis=0) * dt
            e_fric = (b * w * w).sum() * dt
            e_cu = (res * cur * cur).sum() * dt
            imp = np.abs(tr["thrust_N"]).sum() * dt
            imp_des = np.abs(tm["thrust_des_N"]).sum() * dt
            run = runs[ck]
            rho = float((stag_cfg or cfg)["density_kg_m3"][0])
            c1 = float(cfg["ct2"][0]) * rho * float(cfg["propeller_diameter_m"][0]) ** 4 / \
                (4 * math.pi ** 2)
            info[ck] = dict(imp=imp, imp_des=imp_des, e=energy(run), rho=rho, tm=tm, tr=tr,
                            cfg=cfg, dt=dt, fric_share=div(e_fric, energy(run)), b_c1=b / abs(c1))
            rows.append([f"{ck[0]}, {ck[1]}", f(energy(run), 1), f(e_vi.sum(), 1), f(e_fric, 1),
                         f(e_cu, 2), f(div(e_fric, energy(run)) * 100, 1), g(imp_des, 3),
                         g(imp, 3), f(div(energy(run), imp), 1), f(b / abs(c1), 1)])
            per_thr.append([f"{ck[0]}, {ck[1]}"] + [f(x, 0) for x in e_vi])
        self.energy_info = info
        md += table(["run", "E_el (summary) [J]", "∫Σmax(V·I,0) (tick-sampled) [J]",
                     "∫Σ b·ω² [J]", "∫Σ R·I² [J]", "friction share [%]",
                     "allocated ∫Σ|P| dt [N·s]", "delivered ∫Σ|T| dt [N·s]",
                     "E / ∫Σ|T| [J/(N·s)]", "b/|c1| [W/N]"], rows)
        md += ["Per-thruster energy ∫max(V_j·I_j, 0) dt [J] (tick-sampled):", ""]
        md += table(["run"] + [f"T{j + 1}" for j in range(8)], per_thr)
        md += ["With the paper's motor (b = viscous friction, k_m, J and the tiny propeller "
               "constants of docs/MODEL.md §3.4) the electrical energy is dominated by motor friction "
               "b·ω² (friction-share column), and since the thrust law gives ω² ∝ |T|, **the "
               "thruster energy is close to proportional to the thrust impulse ∫Σ|T_j| dt** "
               "with the constant b/|c1| (last column; measured E/∫Σ|T| next to it). Energy "
               "comparisons between cases are therefore, to that extent, comparisons of "
               "delivered thrust impulse.", ""]
        ratios_imp = [div(d["imp"], d["imp_des"]) for d in info.values()]
        if ratios_imp:
            ms = self.motor or {}
            used = self.drive() if self.drive() in ("current", "voltage") else "voltage"
            self.notes.append(
                f"Experiment 3: the thrusters deliver {fmt_range(ratios_imp, 2)} of the "
                f"allocated thrust impulse (delivered ∫Σ|T_j| dt over allocated ∫Σ|P_j| dt), and "
                f"the produced wrench fits the desired one best with a delay of "
                f"{fmt_range([r[3] for r in getattr(self, 'track_lags', [])], 2)} s. The speed "
                f"loop of the {used} drive these runs used reaches 63 % of a step in "
                f"{f(ms.get(f'tau_{used}_s'), 3)} s (experiment 3, thruster response).")
        # The unsteady condition over seeds (summary energies) and one seed's logs.
        urows = []
        for c in (VEH, BARY):
            s, u = info.get((c, "stagnant")), info.get((c, "unsteady"))
            d_s = e.dist(E_EL, conds[(c, "stagnant")])
            d_u = e.dist(E_EL, conds[(c, "unsteady")])
            if not s or not u:
                continue
            cfg = u["cfg"]
            k_drag = 0.5 * u["rho"] * float(cfg["vehicle_drag_coeff"][0]) * \
                float(cfg["vehicle_frontal_area_m2"][0])
            out = []
            for d in (s, u):
                wrel = d["tr"]["velocity_m_s"] - d["tr"]["flow_velocity_m_s"]
                drag = k_drag * np.linalg.norm(wrel, axis=1)[:, None] * wrel
                out.append(dict(
                    drag_imp=np.linalg.norm(drag, axis=1).sum() * d["dt"],
                    fdes_imp=np.linalg.norm(d["tm"]["force_des_N"], axis=1).sum() * d["dt"],
                    ffb_imp=np.linalg.norm(d["tm"]["force_fb_N"], axis=1).sum() * d["dt"],
                    flow=rms(np.linalg.norm(d["tr"]["flow_velocity_m_s"], axis=1)),
                    vel=rms(np.linalg.norm(d["tr"]["velocity_m_s"], axis=1))))
            for lbl, d, src in (("stagnant", out[0], s), ("unsteady", out[1], u)):
                urows.append([f"{c}, {lbl}", f(d["flow"] * 1e3, 2), f(d["vel"] * 1e3, 2),
                              g(d["drag_imp"], 3), g(d["ffb_imp"], 3), g(d["fdes_imp"], 3),
                              g(src["imp"], 3), f(src["e"], 1)])
            ratio_d = stats.describe([div(x, d_s.mean) for x in d_u.values])
            self.notes.append(
                f"Unsteady flow in case {c} (experiment 3): the thruster energy rises from "
                f"{f(d_s.mean, 1)} J to {fmt_dist(d_u, 1)} J (×{fmt_dist(ratio_d, 2)} over "
                f"{d_u.n} seed(s)). In the run drawn (one seed) the delivered thrust impulse "
                f"∫Σ|T| dt grows from {g(s['imp'], 3)} to {g(u['imp'], 3)} N·s; the flow (RMS "
                f"|v∞| {f(out[1]['flow'] * 1e3, 1)} mm/s) adds a drag impulse ∫|D0| dt of "
                f"{g(out[1]['drag_imp'], 2)} N·s (stagnant: {g(out[0]['drag_imp'], 2)}), and the "
                f"position-feedback impulse ∫|F_fb| dt grows from {g(out[0]['ffb_imp'], 3)} to "
                f"{g(out[1]['ffb_imp'], 3)} N·s: the feedback reacts to the vehicle motion the "
                f"drag causes.")
        if urows:
            md += ["**The unsteady-flow condition** (one seed). Vehicle drag D0 = −½ρ·CD0·A0·|w|·w "
                   "with w = v0 − v∞ recomputed from the truth log (plant ρ), next to the "
                   "controller's position-feedback and desired-force impulses:", ""]
            md += table(["run", "RMS |v∞| [mm/s]", "RMS |v0| [mm/s]", "∫|D0| dt [N·s]",
                         "∫|F_fb| dt [N·s]", "∫|F_des| dt [N·s]", "∫Σ|T| dt [N·s]", "E_el [J]"],
                        urows)
        return md

    # -- experiment 4
    def sec_exp4(self):
        e = self.exp("exp4_fidelity")
        if e is None:
            return self.missing("exp4_fidelity")
        md = [f"*Campaign file:* {e.comment}", ""] if e.comment else []
        combos = sorted({(bool(run_value(r, KEY_UNSTEADY)), bool(run_value(r, KEY_DENSITY)),
                          bool(run_value(r, KEY_AOA)), bool(run_value(r, KEY_VARC)))
                         for r in e.runs})
        rows, labels, pairs = [], [], []
        yn = {True: "yes", False: "no"}
        for cmb in combos:
            kv = {KEY_UNSTEADY: cmb[0], KEY_DENSITY: cmb[1], KEY_AOA: cmb[2], KEY_VARC: cmb[3]}
            lab = "/".join(("U" if cmb[0] else "-", "ρ" if cmb[1] else "-",
                            "α" if cmb[2] else "-", "C" if cmb[3] else "-"))
            pa = self.add_comparison("exp4_fidelity", "exp4, " + ("unsteady" if cmb[0] else
                                     "steady") + "-flow model combinations", kv, cmb[0], sub=lab)
            dv, db = e.dist(E_EL, dict(kv, **{KEY_CASE: VEH})), e.dist(E_EL, dict(kv, **{KEY_CASE: BARY}))
            pairs.append(pa)
            labels.append(lab)
            rows.append([yn[cmb[0]], yn[cmb[1]], yn[cmb[2]], yn[cmb[3]], fmt_n(dv),
                         fmt_dist(dv, 1), fmt_dist(db, 1), fmt_dist(pa.dist, 3),
                         fmt_minmax(pa.dist, 3), f"{pa.n_below_1} of {pa.n}",
                         stats.compare(pa) or "n/a",
                         fmt_dist(e.dist(ERR, dict(kv, **{KEY_CASE: VEH})), 2, 1e3),
                         fmt_dist(e.dist(ERR, dict(kv, **{KEY_CASE: BARY})), 2, 1e3)])
        md += ["Mean ± half-width of the 95 % CI over seeds where seeded (unsteady flow); ratios "
               "paired per seed.", ""]
        md += table(["unsteady flow", "density error", "angle of attack", "variable coeff.", "n",
                     "E_el(IV) [J]", "E_el(VII) [J]", "E(VII)/E(IV)", "min–max",
                     "VII cheaper in", "verdict", "mean ε IV [mm]", "mean ε VII [mm]"], rows)
        fig, ax = plt.subplots(figsize=(12, 4.3))
        cols = ["#d62728" if c[0] else "#1f77b4" for c in combos]
        y, yerr = err_bars([p.dist for p in pairs])
        ax.bar(np.arange(len(pairs)), y, color=cols, yerr=yerr, capsize=4)
        ax.axhline(1.0, color="k", lw=1)
        ax.set_xticks(np.arange(len(pairs)), labels, rotation=45, ha="right")
        ax.set_ylabel("E(VII) / E(IV) [-], paired per seed")
        ax.set_xlabel("model combination: U unsteady flow / ρ density error / α angle of attack "
                      "/ C variable coefficients (- = off)")
        ax.set_title("Experiment 4: energy ratio barycenter/vehicle per model combination "
                     "(blue steady, red unsteady flow; error bars 95 % CI over seeds)")
        fig.tight_layout()
        img(md, self.figs.save(fig, "exp4_fidelity_ratio.png"),
            "Energy ratio E(VII)/E(IV) for every combination of the four model options "
            "(mean over seeds with 95 % CI where seeded).")
        return md

    # -- experiments 5 and 6
    def sweep(self, e, key):
        """(xs, IV dists, VII dists, paired ratios) over the values of a swept key."""
        xs = e.values(key)
        dv = [e.dist(E_EL, {KEY_CASE: VEH, key: x}) for x in xs]
        db = [e.dist(E_EL, {KEY_CASE: BARY, key: x}) for x in xs]
        pr = [e.paired(E_EL, {KEY_CASE: BARY, key: x}, {KEY_CASE: VEH, key: x}) for x in xs]
        return xs, dv, db, pr

    def sweep_figure(self, xs, dv, db, pr, xlabel, title, fname):
        fig, axes = plt.subplots(1, 2, figsize=(13, 4.3))
        x = np.asarray(xs, float)
        for ds, mk, c, lbl in ((dv, "o-", VEH, "IV vehicle stabilization"),
                               (db, "s-", BARY, "VII barycenter stabilization")):
            y, yerr = err_bars(ds)
            axes[0].errorbar(x, y, yerr=yerr, fmt=mk, color=CASE_COLORS[c], lw=2, capsize=3,
                             label=lbl)
        axes[0].set_ylabel("thruster energy E_el [J]")
        axes[0].legend()
        y, yerr = err_bars([p.dist for p in pr])
        axes[1].errorbar(x, y, yerr=yerr, fmt="d-", color="k", lw=2, capsize=3,
                         label="E(VII)/E(IV)")
        axes[1].axhline(1.0, color="gray", lw=1, ls=":")
        axes[1].set_ylabel("energy ratio E(VII)/E(IV) [-]")
        axes[1].legend()
        for ax in axes:
            ax.set_xlabel(xlabel)
        fig.suptitle(title)
        fig.tight_layout()
        return self.figs.save(fig, fname)

    def sec_exp5(self):
        e = self.exp("exp5_travel")
        if e is None:
            return self.missing("exp5_travel")
        md = [f"*Campaign file:* {e.comment}", ""] if e.comment else []
        xs, dv, db, pr = self.sweep(e, KEY_DIST)
        path = self.sweep_figure(xs, dv, db, pr, "EE travel distance r_Δ [m]",
                                 "Experiment 5: energy vs EE travel distance (straight line, "
                                 "cosine profile)", "exp5_travel.png")
        img(md, path, "Thruster energy and ratio vs travel distance.")
        rows = []
        for x, a, b, p in zip(xs, dv, db, pr):
            rv, rb = e.one({KEY_CASE: VEH, KEY_DIST: x}), e.one({KEY_CASE: BARY, KEY_DIST: x})
            self.add_comparison("exp5_travel", f"exp5, travel {fmt_range(xs, 1)} m",
                                {KEY_DIST: x}, False, sub=f"r_Δ = {f(x, 1)} m")
            rows.append([f(x, 2), fmt_dist(a, 2) + status_mark(rv), fmt_dist(b, 2) + status_mark(rb),
                         fmt_dist(p.dist, 3),
                         fmt_dist(e.dist(ERR, {KEY_CASE: VEH, KEY_DIST: x}), 3, 1e3),
                         fmt_dist(e.dist(ERR, {KEY_CASE: BARY, KEY_DIST: x}), 3, 1e3)])
        md += table(["r_Δ [m]", "E_el(IV) [J]", "E_el(VII) [J]", "E(VII)/E(IV)", "mean ε IV [mm]",
                     "mean ε VII [mm]"], rows)
        return md

    def sec_exp6(self):
        e = self.exp("exp6_duration")
        if e is None:
            return self.missing("exp6_duration")
        md = [f"*Campaign file:* {e.comment}", ""] if e.comment else []
        cfg = next((c for c in (self.cfg(e, r) for r in e.runs[:1]) if c is not None), None)
        tick = float(cfg["tick_s"][0]) if cfg is not None else float("nan")
        gaps = [abs(float(r["duration_s"]) - float(r[KEY_TRAJ_DUR])) for r in e.runs
                if isnum(r.get("duration_s")) and isnum(r.get(KEY_TRAJ_DUR))]
        same = bool(gaps) and isnum(tick) and max(gaps) <= tick + 1e-9
        xs, dv, db, pr = self.sweep(e, KEY_TRAJ_DUR)
        path = self.sweep_figure(xs, dv, db, pr, "trajectory duration t_F [s]",
                                 "Experiment 6: energy vs trajectory duration (joint cycloid of "
                                 "experiment 1)", "exp6_duration.png")
        img(md, path, "Thruster energy and ratio vs trajectory duration.")
        rows = []
        for x, a, b, p in zip(xs, dv, db, pr):
            rv = e.one({KEY_CASE: VEH, KEY_TRAJ_DUR: x})
            rb = e.one({KEY_CASE: BARY, KEY_TRAJ_DUR: x})
            self.add_comparison("exp6_duration", f"exp6, durations {fmt_range(xs, 0)} s",
                                {KEY_TRAJ_DUR: x}, False, sub=f"t_F = {f(x, 0)} s")
            rows.append([f(x, 0), f(rv and rv.get("duration_s"), 2), fmt_dist(a, 1) + status_mark(rv),
                         fmt_dist(b, 1) + status_mark(rb), fmt_dist(p.dist, 3),
                         fmt_dist(e.dist(ERR, {KEY_CASE: VEH, KEY_TRAJ_DUR: x}), 2, 1e3),
                         fmt_dist(e.dist(ERR, {KEY_CASE: BARY, KEY_TRAJ_DUR: x}), 2, 1e3)])
        md += table(["t_F [s]", "run length [s]", "E_el(IV) [J]", "E_el(VII) [J]", "E(VII)/E(IV)",
                     "mean ε IV [mm]", "mean ε VII [mm]"], rows)
        ends = (f"ends with its trajectory, to within one tick (largest |run length − t_F| = "
                f"{f(max(gaps), 3)} s, tick {g(tick, 3)} s; run length = ticks × tick from "
                f"summary.json)" if same else "does NOT end with its trajectory (run length and "
                "t_F differ by more than a tick in results.json)")
        md += [f"Every run of this experiment {ends}, so energies of different durations cover "
               "the maneuver only, not a common hold period afterwards.", ""]
        valid = [(x, a.mean) for x, a in zip(xs, dv) if isnum(a.mean)]
        if len(valid) >= 3:
            k = int(np.argmax([a for _, a in valid]))
            if 0 < k < len(valid) - 1:
                slow = (" Consistent with the slow voltage drive of these runs (experiment 3): "
                        "short maneuvers end before the thrusters deliver the demanded force."
                        if self.drive() in (None, "voltage") else " Cause: open.")
                self.notes.append(
                    f"Experiment 6: the vehicle-stabilization energy is not monotonic in the "
                    f"duration: it peaks at t_F = {f(valid[k][0], 0)} s ({f(valid[k][1], 1)} J) "
                    f"and falls for shorter maneuvers ({f(valid[0][1], 1)} J at "
                    f"{f(valid[0][0], 0)} s), while the reaction impulse of the analytic model "
                    f"grows as 1/t_F." + slow)
        return md

    # -- experiment 7
    def sec_exp7(self):
        e = self.exp("exp7_energy_split")
        if e is None:
            return self.missing("exp7_energy_split")
        md = [f"*Campaign file:* {e.comment}", ""] if e.comment else []
        pays = e.values(KEY_PAYLOAD)
        fig, ax = plt.subplots(figsize=(11, 4.6))
        x = np.arange(len(pays))
        wdt = 0.2
        rows = []
        for i, (c, key, lbl, hatch) in enumerate((
                (VEH, E_EL, "IV thrusters", ""), (VEH, E_MAN, "IV manipulator", "//"),
                (BARY, E_EL, "VII thrusters", ""), (BARY, E_MAN, "VII manipulator", "//"))):
            y = [e.dist(key, {KEY_CASE: c, KEY_PAYLOAD: p}).mean for p in pays]
            ax.bar(x + (i - 1.5) * wdt, y, wdt, label=lbl, color=CASE_COLORS[c],
                   alpha=1.0 if not hatch else 0.45, hatch=hatch, edgecolor="k", lw=0.5)
        ax.set_yscale("log")
        lo, hi = ax.get_ylim()
        ax.set_ylim(lo, hi * 30)
        ax.set_xticks(x, [f(p, 0) for p in pays])
        ax.set_xlabel("payload m_P [kg]")
        ax.set_ylabel("energy over the run [J] (log)")
        ax.set_title("Experiment 7: thruster vs manipulator energy, vehicle (IV) and "
                     "barycenter (VII) stabilization")
        ax.legend(ncol=4, loc="upper center")
        fig.tight_layout()
        img(md, self.figs.save(fig, "exp7_energy_split.png"),
            "Thruster and manipulator energy per payload (log scale).")
        for p in pays:
            cv, cb = {KEY_CASE: VEH, KEY_PAYLOAD: p}, {KEY_CASE: BARY, KEY_PAYLOAD: p}
            ev, mv = e.dist(E_EL, cv).mean, e.dist(E_MAN, cv).mean
            eb, mb = e.dist(E_EL, cb).mean, e.dist(E_MAN, cb).mean
            rows.append([f(p, 0), f(ev, 1), g(mv, 3), g(div(ev, mv), 3), f(eb, 1), g(mb, 3),
                         g(div(eb, mb), 3), f(div(mb, mv), 3)])
        md += table(["m_P [kg]", "IV thrusters [J]", "IV manipulator [J]", "IV thr./manip.",
                     "VII thrusters [J]", "VII manipulator [J]", "VII thr./manip.",
                     "manip. VII/IV"], rows)
        md += ["Manipulator energy is ∫Σ|τ_i·θ̇_i| dt (docs/MODEL.md §5): the ideal joint drives' "
               "mechanical work, without motor losses.", ""]
        return md

    # -- experiment 8
    def sec_exp8(self):
        e = self.exp("exp8_analytic")
        if e is None:
            return self.missing("exp8_analytic")
        md = [f"*Campaign file:* {e.comment}", ""] if e.comment else []
        pays = e.values(KEY_PAYLOAD)
        cfg = next((c for c in (self.cfg(e, r) for r in e.runs[:1]) if c is not None), None)
        if cfg is None:
            return md + ["*No log of experiment 8 could be read (the analytic parameters come "
                         "from the logged configuration).*", ""]
        par = dict(rho=float(cfg["density_kg_m3"][0]), cd0=float(cfg["vehicle_drag_coeff"][0]),
                   a0_m2=float(cfg["vehicle_frontal_area_m2"][0]),
                   m0_kg=float(cfg["vehicle_mass_kg"][0]))
        r_sim = float(cfg["cart_distance_m"][0])
        t_f = float(cfg["cart_duration_s"][0])
        arm_kg = float(np.sum(cfg["link_mass_kg"][0]))
        r_max = analytic.ARM_MAX_TRAVEL_M
        eta_star, mp_star = analytic.payload_limit(r_max, **par)
        eta_star_sim, mp_star_sim = analytic.payload_limit(r_sim, **par)
        r_star = analytic.travel_limit(**par)
        self.analytic_limits = (eta_star, mp_star, r_star, r_max)
        pmax = max(pays) if pays else 10.0
        num = analytic.numeric_impulses(pmax, r_sim, t_f, samples=20001, **par)
        eta_max = float(analytic.eta(pmax, par["m0_kg"]))
        d_cf = float(analytic.drag_impulse(eta_max, r_sim, t_f, par["rho"], par["cd0"], par["a0_m2"]))
        f_cf = float(analytic.reaction_impulse(eta_max, r_sim, t_f, par["m0_kg"]))

        etas = [float(analytic.eta(p, par["m0_kg"])) for p in pays]
        sim = []
        rows = []
        for p, et in zip(pays, etas):
            pa = self.add_comparison("exp8_analytic", f"exp8, line r_Δ = {f(r_sim, 2)} m",
                                     {KEY_PAYLOAD: p}, False, sub=f"{f(p, 0)} kg")
            sim.append(pa.dist.mean)
            rv, rb = e.one({KEY_CASE: VEH, KEY_PAYLOAD: p}), e.one({KEY_CASE: BARY, KEY_PAYLOAD: p})
            rows.append([f(p, 0), f(et, 4), f(energy(rv), 1) + status_mark(rv),
                         f(energy(rb), 1) + status_mark(rb), f(pa.dist.mean, 3),
                         f(float(analytic.ratio(et, r_sim, **par)), 4),
                         f(float(analytic.ratio_exact_reaction(et, r_sim, **par)), 4)])
        fig, axes = plt.subplots(1, 2, figsize=(14, 4.8))
        eg = np.linspace(0.0, max(etas + [0.05]) * 1.05, 200)
        ax = axes[0]
        ax.plot(eg, analytic.ratio(eg, r_sim, **par), lw=2, color="k",
                label=r"analytic impulse ratio $\tilde D_0/\tilde F_0$ [89], $r_\Delta$ = "
                      + f"{f(r_sim, 2)} m")
        ax.plot(eg, analytic.ratio_exact_reaction(eg, r_sim, **par), lw=1.5, ls="--", color="gray",
                label="analytic with the exact held-vehicle reaction m_P·r̈")
        ax.plot(etas, sim, "o-", color=CASE_COLORS[BARY], lw=2, ms=6,
                label="simulated ENERGY ratio E(VII)/E(IV), full arm (a different quantity)")
        last = -1.0
        for p, et, s in zip(pays, etas, sim):
            if isnum(s) and et - last > 0.03 * max(etas + [1e-9]):
                last = et
                ax.annotate(f"{f(p, 0)} kg", (et, s), textcoords="offset points", xytext=(4, 6),
                            fontsize=8)
        ax.set_xlabel("payload fraction η = m_P/(m0 + m_P) [-]")
        ax.set_ylabel("ratio barycenter / vehicle [-]")
        ax.set_title("Simulated energy ratio vs analytic impulse ratio (not like for like)")
        ax.legend(fontsize=8)
        ax = axes[1]
        ef = np.linspace(0.0, 1.0, 300)
        for rd, ls in ((r_sim, "-"), (r_max, "-.")):
            ax.plot(ef, analytic.ratio(ef, rd, **par), lw=2, ls=ls,
                    label=f"analytic [89], r_Δ = {f(rd, 2)} m")
        ax.plot([1.0], [1.0], "k*", ms=12,
                label=f"travel limit: ratio = 1 at η → 1 for r_Δ* = {f(r_star, 3)} m")
        ax.axhline(1.0, color="gray", lw=1)
        if eta_star < 1:
            ax.axvline(eta_star, color="#d62728", lw=1.5, ls="--",
                       label=f"payload limit of [89] at r_Δ = {f(r_max, 2)} m: η* = "
                             f"{f(eta_star, 3)} (m_P = {f(mp_star, 1)} kg)")
        ax.set_xlabel("payload fraction η [-]")
        ax.set_ylabel(r"$\tilde D_0/\tilde F_0$ [-]")
        ax.set_ylim(0, 2.0)
        ax.set_title("Analytic ratio over η ∈ [0, 1]: payload and travel limits of [89]")
        ax.legend(fontsize=8.5, loc="upper left")
        fig.suptitle(f"Experiment 8: simplified analytic model (docs/MODEL.md §9 item 8); "
                     f"ρ = {g(par['rho'], 4)} kg/m³, CD0 = {g(par['cd0'], 3)}, "
                     f"A0 = {g(par['a0_m2'], 3)} m², m0 = {g(par['m0_kg'], 4)} kg (logged config)")
        fig.tight_layout()
        img(md, self.figs.save(fig, "exp8_analytic_ratio.png"),
            "Analytic drag/reaction impulse ratio and its limits; the simulated energy ratio of "
            "the full arm is drawn for reference only (see 8b for the like-for-like comparison).")
        md += ["**Not like for like.** The analytic model compares integrated forces of a "
               "massless, dragless arm; this experiment's simulated column is the ratio of "
               f"electrical energies of the full arm (links {f(arm_kg, 2)} kg with drag and added "
               "mass), a different quantity of a different system. Experiment 8b makes the "
               "comparison like for like.", ""]
        md += table(["m_P [kg]", "η", "E_el(IV) [J]", "E_el(VII) [J]", "simulated E(VII)/E(IV)",
                     "analytic [89] (impulses)", "analytic, exact reaction"], rows)
        lim_sim = ("none (η* ≥ 1)" if math.isinf(mp_star_sim)
                   else f"η* = {f(eta_star_sim, 4)}, m_P* = {f(mp_star_sim, 1)} kg")
        lim_max = ("none (η* ≥ 1)" if math.isinf(mp_star)
                   else f"η* = {f(eta_star, 4)}, m_P* = {f(mp_star, 1)} kg")
        md += [f"Analytic parameters from the logged controller configuration of experiment 8: "
               f"ρ = {g(par['rho'], 4)} kg/m³, CD0 = {g(par['cd0'], 3)}, A0 = {g(par['a0_m2'], 3)} "
               f"m², m0 = {g(par['m0_kg'], 4)} kg (the vehicle mass, as docs/MODEL.md writes [88–89]); "
               f"the simulated line has r_Δ = {f(r_sim, 3)} m over t_F = {f(t_f, 1)} s.", "",
               f"- Payload limit of [89] (ratio = 1) for the arm's maximum travel r_Δ = "
               f"{f(r_max, 2)} m (docs/MODEL.md §9 item 8): {lim_max} — arithmetic of [89]; whether the "
               f"simulation supports it is experiment 8b's question.",
               f"- Payload limit of [89] for the simulated r_Δ = {f(r_sim, 2)} m: {lim_sim}.",
               f"- Travel limit of [89] as η → 1: r_Δ* = {f(r_star, 4)} m.",
               f"- Closed form vs numerical integration of the same motion (tools/analytic.py, "
               f"m_P = {f(pmax, 0)} kg): D̃0 {g(d_cf, 6)} vs {g(num['drag'], 6)} N·s, F̃0 "
               f"{g(f_cf, 6)} vs {g(num['reaction_free'], 6)} N·s (relative differences "
               f"{g(abs(num['drag'] / d_cf - 1), 2)}, {g(abs(num['reaction_free'] / f_cf - 1), 2)}).",
               f"- Which m0: docs/MODEL.md's F̃0 = m0·r_Δ·π·η/t_F is m0 times the free vehicle's "
               f"acceleration; the exact reaction on a held vehicle is m_P·r̈ (impulse "
               f"{g(num['reaction_held'], 6)} N·s here, vs F̃0 {g(f_cf, 6)} N·s), which replaces "
               f"m0 by m0 + m_P in [89] (dashed curve). This report follows docs/MODEL.md.", ""]
        return md

    def sec_exp8b(self):
        return report_exp8b.section(self, (plt, img, table))

    # -- runs, modeling choices
    def sec_runs(self):
        rows = []
        tot = dict(n=0, ok=0, sim=0.0, wall=0.0, el=0.0)
        for name, _ in EXPERIMENTS:
            e = self.exp(name)
            if e is None:
                rows.append([name, "missing", "", "", "", "", ""])
                continue
            n = len(e.runs)
            ok = sum(1 for r in e.runs if finished(r))
            sim = sum(float(r.get("duration_s") or 0.0) for r in e.runs)
            wall = sum(float(r.get("wall_time_s") or 0.0) for r in e.runs)
            el = e.elapsed_s()
            seeds = Counter(seed_of(r) is not None for r in e.runs)
            groups = Counter(tuple(sorted((k, json.dumps(r[k], sort_keys=True))
                                          for k in r.get("_overrides", []) if k != KEY_SEED))
                             for r in e.runs)
            reps = sorted(set(groups.values()))
            tot["n"] += n
            tot["ok"] += ok
            tot["sim"] += sim
            tot["wall"] += wall
            tot["el"] += el if isnum(el) else 0.0
            rows.append([name, str(n), f"{ok}" + ("" if ok == n else f" (**{n - ok} failed**)"),
                         f"{len(groups)} conditions; runs per condition "
                         f"{'/'.join(map(str, reps))}" + (f" ({seeds[True]} seeded)"
                                                          if seeds[True] else ""),
                         f(sim, 1), f(wall, 2), f(el, 1)])
        rows.append(["**total**", str(tot["n"]), str(tot["ok"]), "", f(tot["sim"], 1),
                     f(tot["wall"], 2), f(tot["el"], 1)])
        md = table(["experiment", "runs", "finished", "conditions (runs differing only in "
                    "run.seed form one)", "simulated time Σ [s]", "run wall time Σ [s]",
                    "campaign elapsed [s]"], rows)
        md += ["Run wall time: the sum of the runs' `wall_time_s` (summary.json); campaign "
               "elapsed: from plan.json (written when the campaign starts) to results.json "
               "(written when it ends), file modification times.", ""]
        failed = [f"{e.name}/{r['id']}: {r.get('failure')} {r.get('reason')}"
                  for e in self.exps.values() for r in e.runs if not finished(r)]
        if failed:
            md += ["Runs that did not finish:", ""] + [f"- {x}" for x in failed] + [""]
        return md

    def sec_choices(self):
        """Modeling choices the source left open, read from logs, campaign/scenario files and
        the documented defaults."""
        md = []
        e1 = self.exp("exp1_cases") or self.exp("exp3_tracking")
        cfg_s = cfg_u = None
        log_u = None
        if e1 is not None:
            rs = e1.one(dict(COND_EXP1_KEYS["stagnant"], **{KEY_CASE: BARY}))
            ru = e1.one(dict(COND_EXP1_KEYS["unsteady"], **{KEY_CASE: BARY}))
            cfg_s = self.cfg(e1, rs) if rs else None
            cfg_u = self.cfg(e1, ru) if ru else None
            log_u = e1.log(ru) if ru else None
            n_u = e1.n_seeds(dict(COND_EXP1_KEYS["unsteady"], **{KEY_CASE: BARY}))
        cfg = cfg_s if cfg_s is not None else cfg_u
        rows = []

        def v3(a):
            return "(" + ", ".join(g(x, 4) for x in np.asarray(a).ravel()) + ")"

        def docv(key):
            d = doc_default(key)
            return f"{d[1]}" if d else "see docs/SCENARIOS.md"

        def ovr(*keys):
            o = overrides_of(self.exps, set(keys))
            if o:
                return "; overridden: " + "; ".join(o)
            return "; not overridden by any paper campaign or base scenario"

        if cfg is not None:
            grav = cfg["gravity_m_s2"][0]
            derr = ""
            if cfg_s is not None and cfg_u is not None:
                rho_u, rho_s = float(cfg_u["density_kg_m3"][0]), float(cfg_s["density_kg_m3"][0])
                derr = f"{f(100 * (1 - rho_u / rho_s), 1)} % "
            rows.append(["gravity", f"g = {v3(grav)} m/s² (logged config) — docs/MODEL.md §6.3: the paper's "
                         f"energies and its insensitivity to a {derr}density error are only consistent "
                         "with negligible net weight/buoyancy loads (a real vehicle is trimmed neutral; "
                         "the paper's volumes are not)", "§6.3"])
            rows.append(["vehicle drag coefficient CD0", f"{g(cfg['vehicle_drag_coeff'][0], 4)} "
                         "(logged config); not printed in the paper, the value consistent with its "
                         "analytic results", "§3.2"])
            m0 = float(cfg["vehicle_mass_kg"][0])
            side = math.sqrt(6.0 * float(cfg["vehicle_inertia_kg_m2"][0][0]) / m0)
            rows.append(["vehicle inertia", f"diag{v3(cfg['vehicle_inertia_kg_m2'][0])} kg·m² "
                         f"(logged config): not in the paper; that of a uniform cube of side "
                         f"√(6·I/m0) = {f(side, 2)} m and m0 = {g(m0, 4)} kg", "§3.2"])
            rows.append(["vehicle center of buoyancy", f"{v3(cfg['vehicle_cob_m'][0])} m from the "
                         "CoM (logged config)", "§3.2"])
        ampl, harm, seed = docv("amplitude_m_s"), docv("harmonics"), docv("seed")
        seeds = sorted({seed_of(r) for e in self.exps.values() for r in e.runs
                        if seed_of(r) is not None})
        seed_txt = (f"seeds {seeds[0]}–{seeds[-1]} (run.seed replicates: every unsteady "
                    f"condition is a distribution over seeds, docs/MODEL.md §10)" if len(seeds) > 1 else
                    f"seed = {seeds[0] if seeds else seed} (one seed per condition: an anecdote, "
                    f"docs/MODEL.md §10)")
        flow_txt = (f"A_v = {ampl} m/s, n = {harm} harmonics per axis, period t_F = run duration "
                    f"(documented defaults"
                    + ovr("environment.unsteady_flow.amplitude_m_s",
                          "environment.unsteady_flow.harmonics") + "); " + seed_txt)
        if log_u is not None and "UVMS_TRUTH" in log_u:
            fl = log_u["UVMS_TRUTH"]["flow_velocity_m_s"]
            flow_txt += (f"; measured in exp1 VII unsteady (seed {seed_of(ru)}): RMS per axis "
                         f"{v3(rms(fl) * 1e3)} mm/s, peak |v∞| "
                         f"{f(np.max(np.linalg.norm(fl, axis=1)) * 1e3, 1)} mm/s."
                         " The paper gives neither A_v nor n; only the plant sees the unsteady part")
        rows.append(["unsteady flow [28]", flow_txt, "§6.1"])
        if cfg_s is not None and cfg_u is not None:
            rows.append(["density error", f"controller model ρ = {g(cfg_u['density_kg_m3'][0], 5)} "
                         f"kg/m³ under density error, {g(cfg_s['density_kg_m3'][0], 5)} kg/m³ "
                         "otherwise (logged configs); the plant always uses the latter "
                         "(docs/MODEL.md §3.2)", "§6.2"])
        if cfg is not None:
            rows.append(["angle of attack [21]", f"{'on' if int(cfg['angle_of_attack'][0]) else 'off'} "
                         "in experiments 1–3, 5–8 (logged config, C_D = C_D0L·sin²α, in plant "
                         "and model); swept in experiment 4", "§4"])
        ct = default_coeff_table()
        ct_txt = ("; ".join(f"{g(d, 3)} d_L: drag ×{g(dr, 3)}, added mass ×{g(am, 3)}"
                            for d, dr, am in ct) if ct else "see plant/src/environment.cpp")
        rows.append(["variable hydrodynamic coefficients", "plant only (the firmware model keeps "
                     f"constant coefficients); default table, an **approximation** of McLain & Rock "
                     f"(1998) (plant DefaultCoeffTable()): {ct_txt}; used in experiments 4 (swept), "
                     "5 and 6", "§6.4"])
        if cfg is not None:
            ms = self.motor or motor_step(cfg)
            d = self.drive()
            rows.append(["thruster drive (motor power stage)", f"{self.drive_text()} "
                         "(summary.json). Current drive: the power stage makes the motor current "
                         "follow the controller's integrated current command and V = Rm·I + "
                         "Lm·İ + km·ω [53] is evaluated for the energy — the paper's reading "
                         f"(\"power supply response time negligible\"); speed-step 63 % time "
                         f"{f(ms['tau_current_s'], 3)} s with KA = "
                         f"{g(cfg['speed_gain_1_s'][0], 3)}, KB = {g(cfg['current_gain_1_s'][0], 3)} "
                         f"1/s. Voltage drive: the controller's V is held over the tick; "
                         f"{f(ms['tau_voltage_s'], 3)} s to 63 % — an alternative study of a slow "
                         "drive, not the paper's"
                         + ("" if d in ("current", "voltage") else
                            "; these runs predate the setting (voltage drive)"), "§5, §7.4"])
            rows.append(["thruster sign convention", f"CT2 = {g(cfg['ct2'][0], 3)} < 0: positive "
                         "thrust needs negative shaft speed; positive voltage drives positive "
                         "current" + self.sign_check(), "§7.4, §3.4"])
            vmax = self.max_voltage()
            rows.append(["motor voltage limit", f"|V| ≤ {g(cfg['voltage_limit_V'][0], 3)} V (logged "
                         "config): effectively unlimited — the paper sets none, and with k_m = "
                         f"{g(cfg['motor_torque_constant_Nm_A'][0], 3)} V·s/rad a few newtons of thrust "
                         f"need kilovolts; largest |V| commanded in experiments 1 and 3 (one seed per condition): "
                         f"{f(vmax, 1)} V", "§7.4"])
            rows.append(["joint servo gains", f"K_q = {g(cfg['joint_kq_1_s2'][0], 4)} 1/s², K_qd = "
                         f"{g(cfg['joint_kqd_1_s'][0], 4)} 1/s (logged config)"
                         + self.joint_tracking(), "§8"])
            durs = sorted({float(r.get("duration_s") or 0) for r in e1.runs})
            rows.append(["controller period / run length", f"{g(cfg['tick_s'][0], 3)} s tick, "
                         f"trajectory t_F = {g(cfg['traj_duration_s'][0], 4)} s (logged config); "
                         f"run length in {e1.name}: {', '.join(g(x, 4) for x in durs)} s; "
                         "experiment 6 sweeps both", "§3.5"])
        integ = ", ".join(f"{k} = {docv(k)}" for k in ("method", "rel_tol", "abs_tol"))
        rows.append(["CVODE", f"{integ} (documented defaults"
                     + ovr("integrator.method", "integrator.rel_tol", "integrator.abs_tol")
                     + "); the integrator stops at every tick boundary", "§5"])
        e5 = self.exp("exp5_travel")
        if e5 is not None and e5.campaign:
            st = flatten_toml(e5.campaign.get("set", {}))
            rows.append(["travel experiment (5)", "start pose θ = "
                         f"{st.get('trajectory.theta_start_deg', '?')} deg (the sampling pose), "
                         f"direction {st.get('trajectory.cartesian.direction', '?')}: from the "
                         "stowed pose θI a +x line is unreachable after about 2 cm "
                         "(campaign file exp5_travel.toml, README findings)", "§8, §9 item 5"])
        e8b = self.exp("exp8b_analytic_like")
        if e8b is not None and e8b.campaign:
            st = flatten_toml(e8b.campaign.get("set", {}))
            rows.append(["analytic model, like for like (8b)", "the line of experiment 8 with "
                         f"arm.mass_scale = {st.get('arm.mass_scale', '?')}, arm.hydrodynamics = "
                         f"{str(st.get('arm.hydrodynamics', '?')).lower()} (massless, dragless arm "
                         "without volume or added mass, in plant and controller model): payload "
                         "only, compared by integrated thrust force", "§9 item 8"])
        e8 = self.exp("exp8_analytic")
        if e8 is not None and e8.campaign:
            st = flatten_toml(e8.campaign.get("set", {}))
            rows.append(["analytic experiment (8)", "the analytic model's maneuver: straight EE "
                         f"line ({st.get('trajectory.mode', '?')}), r_Δ = "
                         f"{st.get('trajectory.cartesian.distance_m', '?')} m along "
                         f"{st.get('trajectory.cartesian.direction', '?')}, from the sampling pose; "
                         "no unsteady flow, no density error; payload swept", "§9 item 8"])
        e6 = self.exp("exp6_duration")
        if e6 is not None:
            rows.append(["duration experiment (6)", "run.duration_s swept together with "
                         "trajectory.duration_s: every run ends with its trajectory", "§9 item 6"])
        rows.append(["EE estimate / error", "vehicle-reference cases: [3] at the reference pose; "
                     "barycenter cases: initial barycenter + virtual manipulator [4]; sampled every "
                     "tick (telemetry ee_estimate_m vs truth ee_position_m)", "§10"])
        md += table(["choice", "what these runs used", "docs/MODEL.md"], rows)
        md += self.column_check()
        return md

    def sign_check(self):
        e = self.exp("exp3_tracking") or self.exp("exp1_cases")
        if e is None:
            return ""
        n_ok = n = 0
        for r in e.runs[:4]:
            lg = e.log(r, ["UVMS_TRUTH"]) if e.log(r) is None else e.log(r)
            if lg is None or "UVMS_TRUTH" not in lg:
                continue
            tr = lg["UVMS_TRUTH"]
            th, w = tr["thrust_N"], tr["motor_speed_rad_s"]
            m = np.abs(th) > 1e-3
            n += int(m.sum())
            n_ok += int((np.sign(th[m]) == -np.sign(w[m])).sum())
        return (f"; in the logs of {e.name}, {f(100 * div(n_ok, n), 2)} % of samples with "
                f"|T| > 1 mN have sign(T) = −sign(ω)" if n else "")

    def representatives(self, e):
        """One run per condition (the lowest seed) of an experiment, finished ones."""
        seen, out = set(), []
        for r in e.select():
            key = tuple(sorted((k, json.dumps(r[k], sort_keys=True))
                               for k in r.get("_overrides", []) if k != KEY_SEED))
            if key not in seen:
                seen.add(key)
                out.append(r)
        return out

    def max_voltage(self):
        vmax = float("nan")
        for name in ("exp1_cases", "exp3_tracking"):
            e = self.exp(name)
            if e is None:
                continue
            for r in self.representatives(e):
                lg = e.log(r, ["UVMS_ACTUATORS"])
                if lg is None or "UVMS_ACTUATORS" not in lg:
                    continue
                v = float(np.max(np.abs(lg["UVMS_ACTUATORS"]["motor_voltage_V"]), initial=0.0))
                vmax = v if not isnum(vmax) else max(vmax, v)
        return vmax

    def joint_tracking(self):
        e = self.exp("exp1_cases")
        if e is None:
            return ""
        worst = 0.0
        for r in self.representatives(e):
            lg = e.log(r, ["UVMS_TRUTH", "UVMS_TELEMETRY"])
            if lg is None or "UVMS_TRUTH" not in lg or "UVMS_TELEMETRY" not in lg:
                continue
            tm, tr = per_tick(lg)
            d = np.angle(np.exp(1j * (tm["joint_ref_rad"] - tr["joint_position_rad"])))
            worst = max(worst, float(np.max(np.abs(d), initial=0.0)))
        return (f"; largest joint tracking error |θ_ref − θ| over experiment 1: "
                f"{g(worst, 3)} rad (the EE errors measured are millimetres)")

    def final_pose_miss(self):
        """{payload: |p_EE(VII) − p_EE(IV)| at the end [m]} from experiment 2, condition A
        (stagnant, deterministic; summary.json final_ee_position_m): SPEC §8's barycenter
        columns are meant to put the EE at the vehicle column's point."""
        e = self.exp("exp2_payload")
        out = {}
        if e is None:
            return out
        for p in e.values(KEY_PAYLOAD):
            rv = e.one({KEY_CASE: VEH, KEY_UNSTEADY: False, KEY_DENSITY: False, KEY_PAYLOAD: p})
            rb = e.one({KEY_CASE: BARY, KEY_UNSTEADY: False, KEY_DENSITY: False, KEY_PAYLOAD: p})
            if not (finished(rv) and finished(rb)) or "final_ee_position_m" not in rv \
                    or "final_ee_position_m" not in rb:
                continue
            out[p] = float(np.linalg.norm(np.subtract(rb["final_ee_position_m"],
                                                      rv["final_ee_position_m"])))
        return out

    def column_check(self):
        """SPEC §8: every final column should put the EE at the same inertial point."""
        rows = [[f(p, 0), mm(d, 1)] for p, d in self.final_pose_miss().items()]
        if not rows:
            return []
        return (["**docs/MODEL.md §8 final-pose check.** The barycenter columns of the joint "
                 "table (docs/MODEL.md §8, the paper's) are meant to put the EE at the same "
                 "inertial point as the vehicle column. Distance between the final EE positions "
                 "of VII and IV (experiment 2, condition A, summary.json):", ""]
                + table(["m_P [kg] (column)", "|p_EE(VII) − p_EE(IV)| at the end [mm]"], rows))


    # -- headline
    def sec_headline(self):
        md = ["## Answer: is holding the barycenter cheaper than holding the vehicle?", ""]
        if not self.comparisons:
            return md + ["No vehicle/barycenter pair was found in the campaigns.", ""]
        groups, notes = dedupe_comparisons(self.comparisons)
        first = {id(g[0]): g for g in groups}
        dup_of = {id(c): g[0] for g in groups for c in g[1:]}
        md += [f"Thruster drive of these runs: {self.drive_text()} (docs/MODEL.md §5). Energy = "
               "thruster (electrical) energy E_el = ∫Σmax(V_j·I_j, 0) dt. Each comparison is a "
               "pair of runs that differ only in the stabilized point (case IV vs VII, or V vs "
               "VIII), paired per seed; verdict from the 95 % confidence interval of the paired "
               "ratio E(barycenter)/E(vehicle): *cheaper* if it lies entirely below 1, *dearer* "
               "if entirely above, else *no significant difference*; a deterministic (unseeded, "
               "stagnant) comparison is one exact number and its ratio decides.", "",
               "**Counting evidence.** Several campaigns contain the same configuration (e.g. "
               "experiment 1's condition (b) is experiment 2's condition C at 10 kg and "
               "experiment 4's U/ρ/α/- combination): a configuration is counted once, whichever "
               "campaigns ran it (same effective settings: base scenario, campaign settings and "
               "overrides with the documented defaults filled in, and the same seeds; or "
               "bit-identical per-seed energies). Every unsteady-flow comparison uses the same "
               "seeds, i.e. the same flow realisations, so comparisons of different "
               "configurations over those seeds are correlated, not independent samples.", ""]
        lines = []
        # The paper's own test and the size of the saving.
        sc = getattr(self, "scorecard", None)
        sav = getattr(sc, "saving_results", {}) if sc else {}
        key_s = next((c for c in self.comparisons if c["exp"] == "exp1_cases"
                      and c["pair"] == f"{BARY}/{VEH}" and not c["unsteady"]), None)
        key_u = next((c for c in self.comparisons if c["exp"] == "exp1_cases"
                      and c["pair"] == f"{BARY}/{VEH}" and c["unsteady"]), None)
        p11, p12 = report_scorecard.PAPER_TABLE_XI, report_scorecard.PAPER_TABLE_XII
        if key_s is not None or key_u is not None:
            parts = []
            if key_s is not None and key_s["paired"].n:
                d = key_s["paired"].dist
                parts.append(f"{f(100 * (1 - d.mean), 1)} % less energy in stagnant flow (ratio "
                             f"{f(d.mean, 3)}, one deterministic run; the paper's Table XI: "
                             f"{f(100 * (1 - p11[BARY][1] / p11[VEH][1]), 1)} %)")
            if key_u is not None and key_u["paired"].n:
                d = key_u["paired"].dist
                ci = (f" (95 % CI {f(100 * (1 - d.hi), 1)}–{f(100 * (1 - d.lo), 1)} %)"
                      if d.has_ci else "")
                parts.append(f"{f(100 * (1 - d.mean), 1)} %{ci} less under unsteady flow with "
                             f"density error (mean ratio {f(d.mean, 3)} {fmt_ci(d, 3)}, 95 % CI "
                             f"over {fmt_n(d)} seeds; barycenter cheaper in "
                             f"{key_u['paired'].n_below_1} of {d.n} seeds → {key_u['verdict']}; "
                             f"the paper's Table XII: "
                             f"{f(100 * (1 - p12[BARY][1] / p12[VEH][1]), 1)} %)")
            lines.append("- **The paper's own test** (experiment 1, vehicle IV vs barycenter "
                         "VII: the primary evidence; every other seeded comparison reuses its "
                         "seeds): the barycenter uses " + "; and ".join(parts) + ".")
        s_m, u_m = sav.get("stagnant_matched"), sav.get("unsteady_matched")
        u_fb = sav.get("unsteady_feedback")
        if s_m and u_m:
            def pct(dk):
                d = dk[0]
                return (fmt_dist(d.scaled(100), 1, unit=" %")
                        + (f" (mean ± 95 % CI half-width over {d.n} seeds)" if d.n > 1
                           else " (deterministic)"))
            ps, pu = report_scorecard.PAPER_SAVING_STAGNANT, report_scorecard.PAPER_SAVING_UNSTEADY
            fr = [div(s_m[0].mean, ps), div(u_m[0].mean, pu)]
            smaller = (s_m[0].mean < ps and u_m[0].mean < pu and
                       (not s_m[0].has_ci or s_m[0].hi < ps) and
                       (not u_m[0].has_ci or u_m[0].hi < pu))
            lines.append(
                f"- **Direction reproduced, size {'not' if smaller else 'see the scorecard'}.** "
                f"The saving we measure is "
                f"{'smaller than' if smaller else 'to be compared with'} the paper's: over the "
                f"three case pairs that differ only in the reference (the paper's definition, "
                f"scorecard *The text's savings*) it is {pct(s_m)} in stagnant flow against the "
                f"paper's {f(100 * ps, 1)} %, and {pct(u_m)} under unsteady flow against its "
                f"{f(100 * pu, 1)} %"
                + (f"; over the feedback pairs IV/VII and V/VIII only, "
                   f"{fmt_dist(u_fb[0].scaled(100), 1, unit=' %')}" if u_fb else "")
                + f". Ours is {f(fr[0], 2)} (stagnant) and {f(fr[1], 2)} (unsteady) of the "
                  "paper's saving: barycenter stabilization is cheaper in our runs, as the "
                  "paper says, by a clearly smaller amount; why is open (scorecard, *The gap in "
                  "size is open*).")
        for unst, head in ((False, "Without unsteady flow"),
                           (True, "With the unsteady flow of docs/MODEL.md §6.1")):
            comps = [c for c in self.comparisons if c["unsteady"] == unst and c["paired"].n]
            if not comps:
                continue
            uniq = [c for c in comps if id(c) in first]
            dups = [c for c in comps if id(c) in dup_of]
            verd = Counter(c["verdict"] for c in uniq)
            n = len(uniq)
            k = verd.get(stats.CHEAPER, 0)
            answer = ("yes" if k == n else "mostly" if k > n / 2 else "no" if k == 0 else
                      "rarely")
            means = [c["paired"].dist.mean for c in uniq]
            exps = sorted({c["exp"] for c in comps})
            seeded = max(c["paired"].n for c in uniq) > 1
            txt = (f"- **{head}: {answer}.** {len(comps)} comparisons in {len(exps)} "
                   f"campaign{'s' if len(exps) > 1 else ''} are {n} distinct configurations"
                   + (f" ({len(dups)} repeat a configuration counted elsewhere: "
                      + "; ".join(f"{cmp_name(c)} = {cmp_name(dup_of[id(c)])}" for c in dups)
                      + ")" if dups else "")
                   + f". Mean ratio barycenter/vehicle {fmt_range(means, 3)}; verdicts: "
                   + ", ".join(f"{verd[v]}× {v}" for v in (stats.CHEAPER, stats.NO_DIFF,
                                                           stats.DEARER) if verd.get(v))
                   + f" (of {n} configurations).")
            if seeded:
                seedsets = sorted({c["seeds"] for c in uniq})
                shared = len(seedsets) == 1 and n > 1
                ks = [c["paired"].n_below_1 for c in uniq]
                ns = sorted({c["paired"].n for c in uniq})
                sd = seedsets[0] if seedsets and seedsets[0] else ()
                txt += (f" Every one of them runs over the same {len(sd)} seeds "
                        f"(run.seed {sd[0]}–{sd[-1]}), so its seed pairs are shared with the "
                        f"others (the {sum(1 for c in comps if c['exp'] == 'exp4_fidelity')} "
                        f"unsteady rows of experiment 4 among them) and are not independent "
                        f"evidence; per configuration the barycenter is cheaper in "
                        f"{fmt_range(ks, 0)} of {'/'.join(map(str, ns))} seeds, and the "
                        f"independent count is experiment 1's"
                        + (f" {key_u['paired'].n_below_1} of {key_u['paired'].n}"
                           if key_u is not None else "") + "."
                        if shared and sd else
                        f" Barycenter cheaper in {fmt_range(ks, 0)} of "
                        f"{'/'.join(map(str, ns))} seeds per configuration.")
            else:
                txt += (" Deterministic runs: each ratio is one exact number, and the "
                        "configurations are sweeps (payload, travel, duration, model options) "
                        "around the same maneuvers, not replicates.")
            small = [c for c in uniq if c["verdict"] == stats.CHEAPER
                     and c["paired"].dist.mean > 1 - RATIO_SMALL]
            if small:
                txt += (f" Of the cheaper ones, {len(small)} "
                        f"{'saves' if len(small) == 1 else 'save'} less than "
                        f"{f(100 * RATIO_SMALL, 0)} %: "
                        + "; ".join(f"{cmp_name(c)} ({f(c['paired'].dist.mean, 3)})"
                                    for c in small) + ".")
            others = [c for c in uniq if c["verdict"] != stats.CHEAPER]
            if others and k:
                txt += " Not cheaper: " + "; ".join(
                    f"{cmp_name(c)} ({f(c['paired'].dist.mean, 3)})"
                    for c in others[:6]) + (" …" if len(others) > 6 else "") + "."
            lines.append(txt)
        s_key = key_s
        if s_key and "err_den" in s_key:
            lines.append(f"- Accuracy: in experiment 1 (stagnant) the mean EE error is "
                         f"{fmt_dist(s_key['err_den'], 2, 1e3)} mm for IV and "
                         f"{fmt_dist(s_key['err_num'], 2, 1e3)} mm for VII. docs/MODEL.md §1 "
                         f"states the paper's answer: barycenter stabilization uses markedly "
                         f"less energy with similar EE accuracy, provided feedback is present.")
        lost = sum(c["paired"].n_failed for g in groups for c in g[:1])
        lines.append("- Failed runs: " + (
            f"{lost} seed pairs of these configurations are incomplete because a run failed or "
            f"is missing (\"k failed\" next to each statistic; the runs are listed under "
            f"*Runs*)." if lost else
            "none: every run behind these comparisons finished."))
        lines += [f"- Note: {x}" for x in notes]
        md += lines + [""]
        groups_rows = {}
        for c in self.comparisons:
            groups_rows.setdefault((c["label"], c["pair"]), []).append(c)
        rows = []
        for (label, pair), comps in groups_rows.items():
            comps = [c for c in comps if c["paired"].n]
            if not comps:
                rows.append([label, pair, "0", "", "not measured", "", "", "", ""])
                continue
            ns = sorted({fmt_n(c["paired"].dist) for c in comps})
            if len(comps) == 1:
                d = comps[0]["paired"].dist
                rtxt = fmt_dist(d, 3) + (f" {fmt_ci(d, 3)}" if d.has_ci else "")
            else:
                rtxt = fmt_range([c["paired"].dist.mean for c in comps], 3) + \
                    f" ({len(comps)} comparisons: " + ", ".join(c["sub"] for c in comps) + ")"
            verd = Counter(c["verdict"] for c in comps)
            err = ""
            if "err_den" in comps[0]:
                err = (f"{fmt_dist(comps[0]['err_den'], 2, 1e3)} → "
                       f"{fmt_dist(comps[0]['err_num'], 2, 1e3)}")
            ks = [c["paired"].n_below_1 for c in comps]
            nn = sorted({c["paired"].n for c in comps})
            cheaper = (f"{ks[0]} of {nn[0]}" if len(comps) == 1 else
                       f"{sum(ks)} of {len(comps)} comparisons (one run each)" if nn == [1] else
                       f"{fmt_range(ks, 0)} of {'/'.join(map(str, nn))} per comparison (the "
                       f"same seeds)")
            rep = [f"{c['sub'] or 'it'} = {cmp_name(dup_of[id(c)])}" for c in comps
                   if id(c) in dup_of]
            rows.append([label, pair, "/".join(ns), rtxt,
                         ", ".join(f"{verd[v]}× {v}" for v in (stats.CHEAPER, stats.NO_DIFF,
                                                              stats.DEARER) if verd.get(v)),
                         cheaper, err, "; ".join(rep) or "—"])
        md += ["Per experiment (a configuration repeated in several campaigns appears in each "
               "of its rows, and is counted once above; the seeded rows share their seeds):", ""]
        md += table(["comparison", "barycenter/vehicle", "seeds per comparison",
                     "E ratio: mean ± 95 % CI half-width [CI] (or range of means)", "verdicts",
                     "barycenter cheaper in (seed pairs)", "mean ε vehicle → barycenter [mm]",
                     "same configuration as (counted once)"], rows)
        return md

    # -- energies
    def sec_energies(self):
        md = ["## Energies: electrical and propulsive, against the paper's joules", ""]
        e = self.exp("exp1_cases")
        if e is None:
            return md + ["*exp1_cases not found.*", ""]
        prop = self.metric(e, E_P)
        p11, p12 = report_scorecard.PAPER_TABLE_XI, report_scorecard.PAPER_TABLE_XII
        rows = []
        fac = {}
        for k, paper in (("stagnant", p11), ("unsteady", p12)):
            for c in (VEH, BARY):
                cond = dict(COND_EXP1_KEYS[k], **{KEY_CASE: c})
                de, dp = e.dist(E_EL, cond), e.dist(prop, cond)
                fac[(k, c)] = (div(de.mean, paper[c][1]), div(dp.mean, paper[c][1]))
                rows.append([COND_EXP1_TEXT[k], c, g(paper[c][1], 4), fmt_dist(de, 1),
                             fmt_factor(de.mean, paper[c][1]), fmt_dist(dp, 4, sig=3),
                             fmt_factor(dp.mean, paper[c][1])])
            pe = e.paired(E_EL, dict(COND_EXP1_KEYS[k], **{KEY_CASE: BARY}),
                          dict(COND_EXP1_KEYS[k], **{KEY_CASE: VEH}))
            pp = e.paired(prop, dict(COND_EXP1_KEYS[k], **{KEY_CASE: BARY}),
                          dict(COND_EXP1_KEYS[k], **{KEY_CASE: VEH}))
            rows.append([COND_EXP1_TEXT[k], "ratio VII/IV", f(div(paper[BARY][1], paper[VEH][1]), 3),
                         fmt_dist(pe.dist, 3), "", fmt_dist(pp.dist, 3), ""])
        md += table(["condition", "case", "paper [J] (Tables XI, XII)", "E_el ours [J]",
                     "E_el/paper", "E_p ours [J]", "E_p/paper"], rows)
        fe, fp = fac[("stagnant", VEH)]
        info = self.energy_info.get((VEH, "stagnant"), {})
        share = info.get("fric_share")
        e_iv = e.dist(E_EL, dict(COND_EXP1_KEYS["stagnant"], **{KEY_CASE: VEH})).mean
        p_iv = e.dist(prop, dict(COND_EXP1_KEYS["stagnant"], **{KEY_CASE: VEH})).mean
        alle = [x for v in fac.values() for x in v[:1] if isnum(x)]
        allp = [x for v in fac.values() for x in v[1:] if isnum(x)]
        near = bool(allp) and 0.5 <= min(allp) and max(allp) <= 2.0
        rp_s = e.paired(prop, dict(COND_EXP1_KEYS["stagnant"], **{KEY_CASE: BARY}),
                        dict(COND_EXP1_KEYS["stagnant"], **{KEY_CASE: VEH})).dist.mean
        md += [f"**Which magnitude each definition gives.** The paper's Table XI gives "
               f"{g(p11[VEH][1], 4)} J for case IV. Ours: the electrical (battery) energy "
               f"E_el = {g(e_iv / 1e3, 3)} kJ = {f(e_iv, 1)} J, {fmt_factor(e_iv, p11[VEH][1])} "
               f"the paper's; the propulsive energy E_p (the least any propeller can spend to "
               f"make the same thrust, docs/MODEL.md §5) = {g(p_iv, 3)} J, {fmt_factor(p_iv, p11[VEH][1])} "
               f"the paper's. Over the IV and VII rows of both tables the factors ours/paper are "
               f"{fmt_range(alle, 0)} (E_el) and {fmt_range(allp, 2)} (E_p)."
               + (f" In experiment 3 the motor friction ∫Σb·ω² dt is {f(100 * share, 1)} % of "
                  f"E_el (case IV, stagnant)." if isnum(share) else "")
               + " Why the absolute values cannot match (docs/MODEL.md §5, \"Energy\"): with the Table "
               "VII–VIII motor (k_m = 10 N·m/A, b = 0.01 N·m·s) and propeller (D = 0.05 m) the "
               "electrical energy is dominated by the shaft friction b·ω², which the tiny "
               "propeller's thrust law makes proportional to the thrust impulse, three orders of "
               "magnitude above the paper's printed energies; no reading of the paper's equations "
               "and parameters gives its absolute values. E_p, the physical lower bound, is a "
               "different quantity again. The report therefore compares ratios (E(VII)/E(IV), "
               "E/E(IV)) with the paper's; the two definitions give different ratios since "
               "E_el ∝ ∫|T| while E_p ∝ ∫|T|^1.5."
               + (f" Noted, not explained: E_p lands within a factor {fmt_range(allp, 2)} of the "
                  f"paper's joules in these rows, and its stagnant ratio VII/IV is "
                  f"{f(rp_s, 3)} against the paper's {f(div(p11[BARY][1], p11[VEH][1]), 3)}; "
                  "whether the paper's energies are a propulsive quantity is open (its "
                  "equations, read as docs/MODEL.md does, give electrical energy)." if near else "") +
               (" E_p was computed here from the truth logs (thrust per tick) because these "
                "runs' summary.json lacks it." if getattr(self, "prop_from_logs", False) else ""),
               ""]
        return md

    # -- provenance
    def sec_provenance(self):
        md = ["## Provenance", ""]
        keys = ["version", "git_commit", "build_preset", "build_type", "controller_precision"]
        vals = {k: Counter() for k in keys + ["drive", "transport"]}
        scen = {}
        n_with = 0
        for e in self.exps.values():
            for r in e.runs:
                pv = dict(e.provenance or {})
                rp = r.get("provenance")
                if isinstance(rp, dict) and rp:
                    n_with += 1
                    pv.update(rp)
                for k in keys:
                    v = pv.get(k)
                    vals[k][str(v) if v not in (None, "") else "not recorded"] += 1
                vals["drive"][r.get("drive") or "not recorded"] += 1
                vals["transport"][r.get("transport") or "not recorded"] += 1
                path = disp_path(r.get("scenario") or e.base_path, self.root)
                sha = pv.get("scenario_sha256")
                ent = scen.setdefault((path, sha or ""), dict(runs=0, exps=set()))
                ent["runs"] += 1
                ent["exps"].add(e.name)
        nruns = sum(len(e.runs) for e in self.exps.values())
        rows = [[k.replace("_", " "), "; ".join(f"`{v}` ({n} runs)" if len(c) > 1 else f"`{v}`"
                                                 for v, n in c.most_common())]
                for k, c in vals.items()]
        md += [f"Read from each run's summary.json `provenance` (present in {n_with} of {nruns} "
               "runs) and results.json; `not recorded` where the build that wrote them did not "
               "record it.", ""]
        md += table(["item", "value (runs)"], rows)
        srows = []
        for (path, sha), ent in sorted(scen.items()):
            shown = f"`{sha}`" if sha else "not recorded"
            if not sha:
                full = path if os.path.isabs(path) else os.path.join(REPO_ROOT, path)
                try:
                    shown = ("not recorded; the file now: `"
                             + hashlib.sha256(open(full, "rb").read()).hexdigest() + "`")
                except OSError:
                    pass
            srows.append([f"`{path}`", shown, str(ent["runs"]), ", ".join(sorted(ent["exps"]))])
        md += ["Scenario files (base scenarios; each run adds its campaign's overrides):", ""]
        md += table(["scenario file", "SHA-256 of its content", "runs", "experiments"], srows)
        crow = []
        for name, _ in EXPERIMENTS:
            e = self.exp(name)
            if e is None or not e.campaign_path:
                continue
            rec = (e.provenance or {}).get("campaign_sha256")
            try:
                now = hashlib.sha256(open(e.campaign_path, "rb").read()).hexdigest()
            except OSError:
                now = None
            if rec:
                h = f"`{rec}`" + ("" if now in (None, rec) else
                                  f" (**the file has changed since**: now `{now}`)")
            else:
                h = f"not recorded; the file now: `{now}`" if now else "not recorded"
            sets = (e.provenance or {}).get("campaign_sets")
            crow.append([name, f"`{disp_path(e.campaign_path, self.root)}`", h,
                         "; ".join(f"`{x}`" for x in str(sets).split("\n") if x) if sets
                         else "—"])
        if crow:
            md += ["Campaign files (SHA-256 recorded in results.json `provenance`):", ""]
            md += table(["experiment", "campaign file", "SHA-256", "--set given to the campaign"],
                        crow)
        return md

    def build(self):
        t0 = time.time()
        root_txt = ("the directories next to this report" if self.root == self.out else
                    f"`{disp_path(self.root, REPO_ROOT)}`")
        md = ["# Europa UVMS: vehicle vs barycenter station keeping — campaign report", "",
              f"Reproduces {report_scorecard.PAPER_FULL}. Equation numbers [n], tables and "
              "figures cited are the paper's; \"docs/MODEL.md §N\" is section N of "
              "docs/MODEL.md in this repository, the model as implemented (physics, control, "
              "parameters, experiments, metrics, and every choice made where the paper is "
              "silent or wrong).", "",
              f"Campaigns: {root_txt}. Generated by `tools/report.py` from the runs' "
              "results.json, summary.json and run logs; analytic values by `tools/analytic.py`, "
              "statistics by `tools/stats.py`. Case IV = vehicle stabilization, VII = "
              f"barycenter stabilization (docs/MODEL.md §9, the paper's Table X). Thruster "
              f"drive: {self.drive_text()}.", ""]
        sections = []
        for name, title in EXPERIMENTS:
            fn = getattr(self, "sec_" + name.split("_")[0])
            sections += [f"## {title} (`{name}`)", ""] + fn()
        energies = self.sec_energies()
        self.scorecard = report_scorecard.Scorecard(self)
        card = self.scorecard.build()
        bad = {e.name: e.undecodable for e in self.exps.values() if e.undecodable}
        if bad:
            chans = sorted({c for d in bad.values() for u in d.values() for c in u})
            md += [f"**Undecodable log messages.** {sum(len(d) for d in bad.values())} run logs "
                   f"({', '.join(f'{k}: {len(v)}' for k, v in bad.items())}) hold messages on "
                   f"{', '.join(chans)} whose type fingerprint matches none of the generated "
                   f"types in `{disp_path(uvmslog.TYPES_DIR)}`: the logs were written by a build "
                   f"with different lcmtypes/*.lcm. Sections that need those messages are "
                   f"incomplete. Rerun the campaigns with the current build, or set "
                   f"UVMS_LCM_PYTHON_PATH to types generated from the lcmtypes the logs were "
                   f"written with.", ""]
        missing = [n for n, _ in EXPERIMENTS if n not in self.exps]
        if missing:
            md += [f"**Missing experiments:** {', '.join(missing)} (no results.json with that "
                   f"name under the campaigns root); their sections are skipped and the "
                   f"headline uses the others.", ""]
        self.md = md + card + self.sec_headline() + energies + self.sec_provenance()
        self.md += ["## Runs", ""] + self.sec_runs()
        self.md += ["## Modeling choices the source left open", "",
                    "What the paper leaves open and this project chose (docs/MODEL.md), with the values "
                    "read from the runs' logged controller configuration, the campaign and "
                    "scenario files, and the documented defaults.", ""] + self.sec_choices()
        self.md += sections
        if self.notes:
            self.md += ["## Observations", ""] + [f"- {n}" for n in self.notes] + [""]
        self.md += ["## Figures", ""] + [f"- `figures/{n}`" for n in self.figs.written] + [""]
        self.md += [f"*Report generated in {f(time.time() - t0, 1)} s.*", ""]
        text = self.sanitize("\n".join(self.md))
        path = os.path.join(self.out, "report.md")
        with open(path, "w") as fh:
            fh.write(text)
        return path

    def sanitize(self, text):
        """No absolute machine paths in the report: strip the known prefixes, and warn about
        anything that still looks like one."""
        for base in sorted({self.out, self.root, REPO_ROOT}, key=len, reverse=True):
            text = text.replace(base.rstrip("/") + "/", "")
        # Quoted campaign-file comments cite the model as "SPEC §N" (the code's convention):
        # the reader has docs/MODEL.md, whose section N that is.
        text = re.sub(r"\bSPEC §", "docs/MODEL.md §", text)
        if re.search(r"\bSPEC\b", text):
            print("report: warning: 'SPEC' left in the report (cite docs/MODEL.md)",
                  file=sys.stderr)
        left = sorted(set(re.findall(r"(?<![\w.)\]/])/(?:tmp|work|home|root|usr|opt|var|mnt)/"
                                     r"[^\s`|)]*", text)))
        if left:
            print(f"report: warning: absolute paths left in the report: {left[:5]}",
                  file=sys.stderr)
        return text


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="report.py",
        description="Write report.md and figures/*.png from the paper campaigns (docs/MODEL.md §9) under "
                    "CAMPAIGNS_ROOT.")
    ap.add_argument("root", metavar="CAMPAIGNS_ROOT",
                    help="directory holding the campaign outputs (e.g. out/paper)")
    ap.add_argument("--out", help="output directory (default: CAMPAIGNS_ROOT)")
    a = ap.parse_args(argv)
    if not os.path.isdir(a.root):
        print(f"report: error: {a.root}: not a directory", file=sys.stderr)
        return 1
    out = a.out or a.root
    os.makedirs(out, exist_ok=True)
    t0 = time.time()
    try:
        rep = Report(a.root, out)
        if not rep.exps:
            print(f"report: warning: no campaign results.json under {a.root}", file=sys.stderr)
        path = rep.build()
    except uvmslog.LogError as e:
        print(f"report: error: {e}", file=sys.stderr)
        return 1
    print(f"report: wrote {path} and {len(rep.figs.written)} figures in "
          f"{os.path.join(out, 'figures')} ({time.time() - t0:.1f} s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
