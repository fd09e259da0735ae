# SPDX-License-Identifier: Apache-2.0
"""What the campaign tests share (test_campaign_e2e.py, test_campaign_shards_e2e.py,
test_campaign_dask.py): the failure report, waiting for a running campaign to reach a point,
the runs a campaign reported and planned, and marks that tell a kept run from a redone one.
Standard library only."""
import json
import os
import re
import sys
import time


def fail(msg):
    """The test's verdict: prints FAIL and the reason, exits 1."""
    print("FAIL:", msg)
    sys.exit(1)


def write_file(directory, name, text):
    """Writes `text` to directory/name; returns the path."""
    path = os.path.join(directory, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def wait_for(path, proc, timeout_s=60.0):
    """Waits until `path` exists while `proc` (a Popen) runs; fails when `proc` ends first or
    after timeout_s seconds."""
    deadline = time.monotonic() + timeout_s
    while not os.path.exists(path):
        if proc.poll() is not None or time.monotonic() > deadline:
            fail(f"{path} did not appear (the campaign's exit status: {proc.poll()})")
        time.sleep(0.01)


def executed(stdout):
    """Run ids the progress lines of either engine (not on a terminal) report as run."""
    return sorted(m.group(1) for m in re.finditer(r"^\[\d+/\d+\] .*  (\S+) (?:finished|FAILED)$",
                                                   stdout, re.M))


def plan_ids(out):
    """The run ids of DIR/plan.json, in plan order."""
    with open(os.path.join(out, "plan.json")) as f:
        return [r["id"] for r in json.load(f)["runs"]]


def mark_summaries(runs):
    """Adds a marker key to every summary.json under the run directories `runs` (a redone run
    loses it); returns {run id: (inode, mtime_ns) of the marked file}."""
    stamps = {}
    for r in sorted(os.listdir(runs)):
        path = os.path.join(runs, r, "summary.json")
        if not os.path.exists(path):
            continue
        with open(path) as f:
            s = json.load(f)
        s.setdefault("test_marker", r)
        with open(path, "w") as f:
            json.dump(s, f, indent=2)
        st = os.stat(path)
        stamps[r] = (st.st_ino, st.st_mtime_ns)
    return stamps


def redone(runs, stamps):
    """The runs of `stamps` whose summary.json was removed or rewritten since mark_summaries."""
    bad = []
    for r, stamp in stamps.items():
        path = os.path.join(runs, r, "summary.json")
        if not os.path.exists(path):
            bad.append(r)
            continue
        with open(path) as f:
            marker = json.load(f).get("test_marker")
        st = os.stat(path)
        if marker != r or (st.st_ino, st.st_mtime_ns) != stamp:
            bad.append(r)
    return bad
