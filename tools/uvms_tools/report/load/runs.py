# SPDX-License-Identifier: Apache-2.0
"""runs: one campaign output directory as an Experiment, and the discovery of every campaign
under the campaigns root."""
import json
import os
import sys

from uvms_tools.log import runlog
from uvms_tools.env import REPO_ROOT

from ..analyses import stats
from ..keys import KEY_CASE, KEY_SEED
from ..num import isnum
from .overrides import (apply_overrides, differing_keys, finished, matches, run_value,
                        seed_of)
from .paths import disp_path
from .regen import BuildMismatch, regenerate, regenerate_ahead
from .tomlfiles import header_comment, toml_keys


class AmbiguousCondition(ValueError):
    """Two runs match one (condition, seed) slot: the condition selects more than one
    configuration."""


def _read_json(path, default):
    try:
        with open(path) as fh:
            return json.load(fh)
    except (OSError, json.JSONDecodeError):
        return default


def load_run(directory, row, plan_overrides):
    """One run's dict: the results row, every override of the run as a key ("run.seed": 7)
    and the summary.json fields; `_overrides` keeps the override keys."""
    r = dict(row)
    rid = r.get("id", "")
    rdir = os.path.join(directory, "runs", rid)
    ovr = plan_overrides.get(rid)
    if ovr is None:
        ovr = _read_json(os.path.join(rdir, "overrides.json"), [])
    applied = apply_overrides(ovr)
    for k, v in applied.items():
        r.setdefault(k, v)  # the results row's own value (the swept one) first
    r["_overrides"] = list(applied)
    for k, v in _read_json(os.path.join(rdir, "summary.json"), {}).items():
        r.setdefault(k, v)
    return r


def _input_path(recorded, fallback):
    """A campaign input (campaign or base scenario file) named in plan.json: as recorded if it
    exists, else the repository's copy."""
    p = recorded
    if p and not os.path.isabs(p):
        p = os.path.join(REPO_ROOT, p)
    if p and os.path.exists(p):
        return p
    cand = fallback(p)
    return cand if cand and os.path.exists(cand) else p


def _campaign_file(name):
    """The repository's campaign file of a campaign name: sil/campaigns/paper/<name>.toml, or
    sil/campaigns/beyond/<file>.toml for name = "beyond_<file>"."""
    cands = [os.path.join(REPO_ROOT, "sil", "campaigns", "paper", f"{name}.toml")]
    if name.startswith("beyond_"):
        cands.append(os.path.join(REPO_ROOT, "sil", "campaigns", "beyond",
                                  f"{name[len('beyond_'):]}.toml"))
    return next((c for c in cands if os.path.exists(c)), cands[0])


class Experiment:
    """One campaign output directory: results.json (a list of rows, or an object with "runs"
    and optionally "provenance"), plan.json (run ids and their overrides), each run's
    summary.json (fields the results row lacks) and run log. `defaults` ({key: default}, the
    schema's) gives the value of a key a run does not set."""

    def __init__(self, directory, results, defaults=None):
        meta, rows = ({}, results) if isinstance(results, list) else \
            (results, results.get("runs", []))
        self.dir = directory
        self.defaults = dict(defaults or {})
        self.plan = _read_json(os.path.join(directory, "plan.json"), {})
        self.name = meta.get("name") or self.plan.get("name") or os.path.basename(directory)
        self.provenance = meta.get("provenance") or self.plan.get("provenance") or {}
        plan_ovr = {r.get("id"): r.get("overrides") for r in self.plan.get("runs", [])}
        self.runs = [load_run(directory, row, plan_ovr) for row in rows]
        self.campaign_path = _input_path(self.plan.get("campaign", ""),
                                         lambda p: _campaign_file(self.name))
        self.comment = header_comment(self.campaign_path) if self.campaign_path else ""
        # written on another machine: the repo's copy
        self.base_path = _input_path(meta.get("base") or self.plan.get("base", ""),
                                     lambda p: os.path.join(REPO_ROOT, disp_path(p)) if p
                                     else "")
        self._logs = {}
        self._argv = {r.get("id"): r.get("argv") for r in self.plan.get("runs", [])}
        # run id -> "kept" (the campaign kept its log), "made again" (regen), or why the
        # report could not read it: every log the report asked for (the report lists them)
        self.logs_read = {}
        self._regen_stopped = None  # a BuildMismatch: no further log of this campaign is made
        self._ahead = {}  # run id -> Future of regen.regenerate's outcome (prefetch_logs)
        self._base_keys = None
        self.undecodable = {}  # run id -> {channel: messages of unknown type}

    # -- runs
    def value(self, run, key):
        """The run's value of a scenario key (its own, else the schema's default)."""
        return run_value(run, key, self.defaults)

    def select(self, cond=None, finished_only=True):
        """Runs matching cond ({key: value}; keys a run does not set take their default),
        every seed, sorted by seed."""
        out = [r for r in self.runs if (not finished_only or finished(r))
               and matches(r, cond or {}, self.defaults)]
        return sorted(out, key=lambda r: (seed_of(r) is None, seed_of(r) or 0))

    def one(self, cond=None):
        """The first run (lowest seed) matching cond, finished or not; None if none."""
        runs = self.select(cond, finished_only=False)
        return runs[0] if runs else None

    def values(self, key):
        """Sorted distinct values of a key over the runs."""
        vals = {self.value(r, key) for r in self.runs if self.value(r, key) is not None}
        try:
            return sorted(vals)
        except TypeError:
            return list(vals)

    def common_value(self, key, default="?"):
        """The value of a key shared by every run, else `default`."""
        vals = {json.dumps(self.value(r, key), sort_keys=True) for r in self.runs}
        return self.value(self.runs[0], key) if len(vals) == 1 and self.runs else default

    def n_seeds(self, cond):
        return len(self.select(cond))

    # -- metrics over seeds
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
                diff = differing_keys(out[s], r, self.defaults)
                raise AmbiguousCondition(
                    f"{self.name}: runs {out[s].get('id')!r} and {r.get('id')!r} both match "
                    f"{cond} with run.seed = {s}: the condition is under-specified (they differ "
                    f"in {', '.join(diff) or 'nothing visible'})")
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

    # -- configuration
    def base_keys(self):
        """Flattened keys of the campaign's base scenario (cached)."""
        if self._base_keys is None:
            self._base_keys = toml_keys(self.base_path) if self.base_path else {}
        return self._base_keys

    def config(self, run, drop=(KEY_CASE, KEY_SEED)):
        """The run's effective scenario settings: the base scenario's keys, then the run's
        overrides (which include the campaign's [set]), without `drop`; keys set nowhere
        take their defaults (analyses.headline.normalize_config)."""
        cfg = dict(self.base_keys())
        for k in run.get("_overrides", []):
            cfg[k] = run.get(k)
        return {k: v for k, v in cfg.items() if k not in drop}

    # -- logs
    def log(self, run, channels=None):
        """The run's log (runlog.Log, all channels, decoded once and cached); None if the run
        or its log is missing. With `channels`, only those are decoded and nothing is cached
        (for loops over many seeds)."""
        if run is None:
            return None
        path = self._log_path(run)
        if channels is not None and path not in self._logs:
            if not os.path.exists(path):
                return None
            lg = runlog.load(path, channels)
            if lg.skipped:
                self.undecodable[run["id"]] = dict(lg.skipped)
            return lg
        if path not in self._logs:
            self._logs[path] = runlog.load(path) if os.path.exists(path) else None
            if self._logs[path] is not None and self._logs[path].skipped:
                self.undecodable[run["id"]] = dict(self._logs[path].skipped)
        return self._logs[path]

    def prefetch_logs(self, runs):
        """Starts making again, $UVMS_JOBS at a time (regen.regenerate_ahead), the logs that
        reading `runs` would make one by one (_to_make). Reading them then notes each in
        logs_read exactly as without it: in the order read, with the same warnings, the first
        BuildMismatch stopping the rest (_make_again). For a loop over many runs' logs: give
        only the runs it reads (a log made ahead and never read would stay, unlisted)."""
        for r in runs:
            if r is not None and self._to_make(r):
                rid = r["id"]
                self._ahead[rid] = regenerate_ahead(self.dir, rid, self._argv.get(rid))

    def _to_make(self, run):
        """Whether reading the run's log would make it again: a finished run, not read yet nor
        being made ahead, with no run.lcmlog, in a campaign whose regeneration did not stop."""
        rid = run["id"]
        return (self._regen_stopped is None and rid not in self.logs_read
                and rid not in self._ahead and finished(run)
                and not os.path.exists(self._path(rid)))

    def _path(self, rid):
        return os.path.join(self.dir, "runs", rid, "run.lcmlog")

    def _log_path(self, run):
        """The run's run.lcmlog, made again (regen) the first time it is asked for when the
        campaign did not keep it and the run finished; notes the outcome in logs_read."""
        rid = run["id"]
        path = self._path(rid)
        if rid in self.logs_read:
            return path
        if os.path.exists(path) and rid not in self._ahead:
            self.logs_read[rid] = "kept"
        elif not finished(run):
            self.logs_read[rid] = "the run did not finish and kept no log"
        elif self._regen_stopped is not None:  # the same cause for every run: not tried again
            self.logs_read[rid] = f"not made again (as {self._regen_stopped.run_id}): " \
                                  f"{self._regen_stopped}"
        else:
            self._make_again(rid)
        return path

    def _make_again(self, rid):
        """Makes the run's log again (regen.regenerate now, or the one prefetch_logs started)
        and notes it in logs_read: "made again", or why not, with a warning; a BuildMismatch
        stops the campaign's regeneration."""
        ahead = self._ahead.pop(rid, None)
        why = ahead.result() if ahead is not None else \
            regenerate(self.dir, rid, self._argv.get(rid))
        self.logs_read[rid] = "made again" if why is None else why
        if why is not None:
            print(f"report: warning: {self.name}/{rid}: no log: {why}", file=sys.stderr)
        if isinstance(why, BuildMismatch):
            self._regen_stopped = why
            why.run_id = rid
            self._drop_ahead()

    def _drop_ahead(self):
        """Once the campaign's regeneration stopped: cancels the logs prefetch_logs has yet to
        make and removes those it made (read one by one, none would have been made)."""
        started = [(rid, ahead) for rid, ahead in self._ahead.items() if not ahead.cancel()]
        self._ahead.clear()
        for rid, ahead in started:  # a run that raised made no log (and is not read)
            if ahead.exception() is None and ahead.result() is None:
                os.remove(self._path(rid))

    def logged_config(self, run):
        """The logged controller configuration of a run (UVMS_CONFIG), or None."""
        lg = self.log(run)
        if lg is None or "UVMS_CONFIG" not in lg:
            return None
        return lg["UVMS_CONFIG"]

    def first_config(self):
        """The logged controller configuration of the first run that has one, or None."""
        for r in self.runs:
            cfg = self.logged_config(r)
            if cfg is not None:
                return cfg
        return None

    def elapsed_s(self):
        """Campaign wall time: plan.json (written first) to results.json (written last) [s]."""
        try:
            return (os.path.getmtime(os.path.join(self.dir, "results.json"))
                    - os.path.getmtime(os.path.join(self.dir, "plan.json")))
        except OSError:
            return float("nan")


class TableError(ValueError):
    """A results table that does not belong to its directory's plan.json."""


def check_table(directory, results):
    """Refuses (TableError) a results.json whose campaign is not its plan.json's: another
    identity or generation (a table left behind by an interrupted --force-new, or written by an
    older uvms campaign without them). Both identities are named."""
    plan = _read_json(os.path.join(directory, "plan.json"), None)
    if plan is None:
        raise TableError(f"{directory}: results.json has no plan.json beside it, so its campaign "
                         "cannot be checked")
    meta = results if isinstance(results, dict) else {}
    have = (meta.get("identity"), meta.get("generation"))
    want = (plan.get("identity"), plan.get("generation"))
    if None in have or have != want:
        raise TableError(
            f"{directory}: results.json is the table of identity {have[0]} (generation "
            f"{have[1]}), but plan.json is of identity {want[0]} (generation {want[1]}): the "
            "table belongs to another campaign; run the campaign (or its --merge) again to "
            "write this plan's table")


def discover(root, defaults=None):
    """{name: Experiment} for every results.json in ROOT or one level below; a table of another
    campaign than its plan.json's is refused (check_table)."""
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
        check_table(d, res)
        exp = Experiment(d, res, defaults)
        if exp.name in found:
            print(f"report: {exp.name} found twice; using {found[exp.name].dir}", file=sys.stderr)
            continue
        found[exp.name] = exp
    return found
