# SPDX-License-Identifier: Apache-2.0
"""A property of `uvms campaign`: a table holds exactly the runs of its plan, whatever happens to
the campaign on the way.

Random small campaigns (1-3 payloads x 1-2 seeds of a 0.3 s run, no logs) go through a random
sequence of steps: a full run (-j 1 or 2), a run killed after a random delay (SIGKILL, its
children reaped; a plain run or a --force-new), the base scenario edited, the campaign file
extended, --force-new, a shard (with or without --force-new), a merge. After every step:

- a step that exits 0 and writes a table (a run of the whole plan, a merge) leaves a
  results.json equal to that of an uninterrupted campaign of the plan's inputs, run afresh in
  another DIR: the same rows (every key, the wall-clock ones and the session aside), each
  row's session the plan's (its generation), the same identity;
- a step that exits otherwise is a clear refusal: exit 1, 3 or 4, "uvms campaign: error:" on
  stderr, no traceback;
- whatever the exit, a results.json in DIR is never of another identity or generation than
  DIR/plan.json (the report would refuse it).

Usage: test_campaign_property.py UVMS SOURCE_DIR [--examples N] [--seed S]
Default: 60 examples (about 20 s on two idle cores); --examples 1000 is a soak.
"""
import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import psutil
from hypothesis import HealthCheck, Phase, given, seed, settings
from hypothesis import strategies as st

from campaign_compare import WALL_CLOCK_KEYS

ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
ap.add_argument("uvms")
ap.add_argument("src")
ap.add_argument("--examples", type=int, default=60)
ap.add_argument("--seed", type=int, default=20261205)
ARGS = ap.parse_args()
UVMS = ARGS.uvms
BASE = os.path.join(ARGS.src, "sil", "scenarios", "paper", "case_IV_stagnant.toml")
ROOT = tempfile.mkdtemp(prefix="uvms-campaign-property-")
IGNORED = set(WALL_CLOCK_KEYS) | {"session"}
STATS = {"examples": 0, "steps": 0, "tables": 0, "refusals": 0}


class World:
    """One example: its DIR, campaign file, base scenario and the reference tables made so far
    ({(campaign bytes, base bytes): results.json rows})."""

    def __init__(self, k, payloads, seeds):
        self.dir = os.path.join(ROOT, f"ex{k}")
        os.makedirs(self.dir)
        self.out = os.path.join(self.dir, "out")
        self.base = os.path.join(self.dir, "base.toml")
        shutil.copyfile(BASE, self.base)
        self.camp = os.path.join(self.dir, "c.toml")
        self.payloads, self.seeds = list(payloads), list(seeds)
        self.write_campaign()
        self.refs = {}
        self.log = []

    def write_campaign(self):
        with open(self.camp, "w") as f:
            f.write(f'name = "prop"\nbase = "base.toml"\n[set]\n"run.duration_s" = 0.3\n'
                    f'[[sweep]]\n"payload.mass_kg" = {json.dumps(self.payloads)}\n'
                    f'[replicates]\nkey = "run.seed"\nvalues = {json.dumps(self.seeds)}\n')

    def campaign(self, *extra, out=None, kill_after=None):
        logs = [] if "--merge" in extra else ["--no-logs"]  # a merge runs nothing
        argv = [UVMS, "campaign", self.camp, "--out", out or self.out, *logs, *extra]
        if kill_after is None:
            p = subprocess.run(argv, capture_output=True, text=True, timeout=120)
            self.log.append((extra, p.returncode))
            return p.returncode, p.stderr
        p = subprocess.Popen(argv, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        time.sleep(kill_after)
        try:
            kids = psutil.Process(p.pid).children(recursive=True)
        except psutil.NoSuchProcess:
            kids = []
        p.send_signal(signal.SIGKILL)
        p.wait()
        psutil.wait_procs(kids, timeout=10)  # the runs end on PDEATHSIG before the next step
        self.log.append((extra + ("killed",), p.returncode))
        return None, p.stderr.read()

    def reference(self):
        """The rows of an uninterrupted campaign of the current inputs, in a fresh DIR."""
        key = (open(self.camp, "rb").read(), open(self.base, "rb").read())
        if key not in self.refs:
            ref = os.path.join(self.dir, f"ref{len(self.refs)}")
            rc, err = self.campaign("-j", "2", out=ref)
            assert rc == 0, f"the reference campaign failed: {err}"
            self.refs[key] = load(ref)
        return self.refs[key]


def load(out):
    with open(os.path.join(out, "results.json")) as f:
        return json.load(f)


def plan(out):
    with open(os.path.join(out, "plan.json")) as f:
        return json.load(f)


def strip(row):
    return {k: v for k, v in row.items() if k not in IGNORED}


def check_table_matches_plan(w):
    """Whatever the exit: a table in DIR is of DIR's plan (identity and generation)."""
    path = os.path.join(w.out, "results.json")
    if not os.path.exists(path):
        return
    res, pl = load(w.out), plan(w.out)
    assert (res["identity"], res["generation"]) == (pl["identity"], pl["generation"]), \
        f"a table of {res['identity'][:12]}/{res['generation']} beside the plan of " \
        f"{pl['identity'][:12]}/{pl['generation']} after {w.log}"


def check_table_is_the_plans(w):
    """After an exit 0 that writes a table: the table of an uninterrupted campaign."""
    got, ref, pl = load(w.out), w.reference(), plan(w.out)
    assert got["identity"] == ref["identity"], f"identity differs after {w.log}"
    sessions = {r["id"]: r["session"] for r in pl["runs"]}
    assert [r["id"] for r in got["runs"]] == [r["id"] for r in ref["runs"]], \
        f"rows {[r['id'] for r in got['runs']]} after {w.log}"
    for a, b in zip(got["runs"], ref["runs"]):
        assert strip(a) == strip(b), f"row {a['id']} differs from the reference after {w.log}"
        assert a["session"] == sessions[a["id"]], f"row {a['id']}: not the plan's session"
    STATS["tables"] += 1


def check_refusal(w, rc, err):
    assert rc in (1, 3, 4), f"exit {rc} after {w.log}: {err}"
    assert "uvms campaign: error:" in err and "Traceback" not in err, \
        f"not a clear refusal (exit {rc}): {err!r} after {w.log}"
    STATS["refusals"] += 1


def do(w, step):
    kind, arg = step
    writes_table = False
    if kind == "run":
        rc, err = w.campaign("-j", str(arg))
        writes_table = True
    elif kind == "kill":
        delay, force = arg
        w.campaign("-j", "2", *(["--force-new"] if force else []), kill_after=delay)
        rc = None
    elif kind == "force_new":
        rc, err = w.campaign("-j", "2", "--force-new")
        writes_table = True
    elif kind == "shard":
        index, force = arg
        rc, err = w.campaign("--shard", f"{index}/2", *(["--force-new"] if force else []))
    elif kind == "merge":
        rc, err = w.campaign("--merge")
        writes_table = True
    elif kind == "edit_base":
        with open(w.base, "a") as f:
            f.write(f"# edit {len(w.log)}\n")
        w.log.append(("edit_base",))
        rc = None
    elif kind == "extend":
        w.payloads.append(float(len(w.payloads) + 7))
        w.write_campaign()
        w.log.append(("extend",))
        rc = None
    STATS["steps"] += 1
    check_table_matches_plan(w)
    if rc is None:
        return
    if rc == 0 and writes_table:
        check_table_is_the_plans(w)
    elif rc != 0:
        check_refusal(w, rc, err)


STEP = st.one_of(
    st.tuples(st.just("run"), st.sampled_from([1, 2])),
    st.tuples(st.just("kill"), st.tuples(st.floats(0.0, 0.08), st.booleans())),
    st.tuples(st.just("force_new"), st.none()),
    st.tuples(st.just("shard"), st.tuples(st.sampled_from([1, 2]), st.booleans())),
    st.tuples(st.just("merge"), st.none()),
    st.tuples(st.just("edit_base"), st.none()),
    st.tuples(st.just("extend"), st.none()))


@seed(ARGS.seed)
@settings(max_examples=ARGS.examples, deadline=None, database=None,
          phases=[Phase.explicit, Phase.reuse, Phase.generate],  # no shrinking: report as found
          suppress_health_check=list(HealthCheck))
@given(payloads=st.lists(st.sampled_from([0.0, 2.0, 5.0]), min_size=1, max_size=3, unique=True),
       seeds=st.lists(st.integers(1, 4), min_size=1, max_size=2, unique=True),
       steps=st.lists(STEP, min_size=2, max_size=8))
def test_table_holds_exactly_its_plan(payloads, seeds, steps):
    w = World(STATS["examples"], payloads, seeds)
    STATS["examples"] += 1
    for step in steps:
        do(w, step)
    # However it went, the campaign finishes with its plan's table: --force-new, then a run.
    rc, err = w.campaign("-j", "2", "--force-new")
    assert rc == 0, f"the closing --force-new failed after {w.log}: {err}"
    check_table_is_the_plans(w)


if __name__ == "__main__":
    try:
        test_table_holds_exactly_its_plan()
        print(f"campaign property ok: {STATS['examples']} examples, {STATS['steps']} steps, "
              f"{STATS['tables']} tables checked against an uninterrupted campaign, "
              f"{STATS['refusals']} refusals checked (seed {ARGS.seed})")
    finally:
        shutil.rmtree(ROOT, ignore_errors=True)
