#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Every paper scenario's metrics from two uvms builds, side by side: what a change of the truth
model or the integrator moved, scenario by scenario.

Runs each sil/scenarios/paper/*.toml (memq, one fixed session) with OLD_UVMS and NEW_UVMS and
compares every metric of their summary.json: the largest relative difference per scenario (and
which metric), and per metric over all scenarios. Relative to max(|old|, |new|, floor), with the
floor FLOOR (default 1e-9) so that metrics near zero compare in their own units. Counters and
identities (ticks, integrator counts, wall times, provenance) are not metrics and are skipped.

Usage: bench/paper_metrics_diff.py OLD_UVMS NEW_UVMS [--floor FLOOR] [-j N] [--markdown] [--update]
                                  [--block NAME] [--labels OLD NEW]
--update (implies --markdown) writes the tables into docs/BENCHMARKS.md between
<!-- NAME:begin --> and <!-- NAME:end -->, NAME from --block (default paper-metrics: the truth
model's speed-up; tick-metrics and tick-metrics-float: the controller tick's rounding-level
changes, double and float builds).
Exit status: 0, or 1 if a run fails or a status differs.
"""
import argparse
import concurrent.futures
import glob
import json
import os
import subprocess
import sys
import tempfile

from doc_block import replace_block

SESSION = "601de4105e551011"
SKIP = {"ticks", "ticks_planned", "missed_ticks", "duration_s", "integrator_steps",
        "integrator_rhs_evals", "wall_time_s", "real_time_factor", "plant_wall_s"}


def run(uvms, scenario, out):
    p = subprocess.run([uvms, "run", scenario, "--out", out, "--transport", "memq", "--session",
                        SESSION], capture_output=True, text=True, timeout=900)
    if p.returncode not in (0, 3):  # 3: the run failed, and its summary.json says why
        raise RuntimeError(f"{uvms} run {scenario}: exit {p.returncode}: {p.stderr.strip()}")
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def numbers(prefix, x, out):
    """Flatten the numeric leaves of a summary into out: {"a.b[2]": value}."""
    if isinstance(x, bool) or x is None or isinstance(x, str):
        return
    if isinstance(x, (int, float)):
        out[prefix] = float(x)
    elif isinstance(x, dict):
        for k, v in x.items():
            if k not in SKIP and k != "provenance":
                numbers(f"{prefix}.{k}" if prefix else k, v, out)
    elif isinstance(x, list):
        for i, v in enumerate(x):
            numbers(f"{prefix}[{i}]", v, out)


def compare(old, new, floor):
    a, b = {}, {}
    numbers("", old, a)
    numbers("", new, b)
    diffs = {}  # key: (relative, absolute, old value)
    for k in sorted(set(a) | set(b)):
        if k not in a or k not in b:
            diffs[k] = (float("inf"), float("inf"), a.get(k, float("nan")))
            continue
        x, y = a[k], b[k]
        if x == y:
            diffs[k] = (0.0, 0.0, x)
        elif x != x or y != y:  # NaN on one side only
            diffs[k] = (float("inf"), float("inf"), x)
        else:
            diffs[k] = (abs(x - y) / max(abs(x), abs(y), floor), abs(x - y), x)
    return diffs


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("old_uvms")
    ap.add_argument("new_uvms")
    ap.add_argument("--floor", type=float, default=1e-9)
    ap.add_argument("-j", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--markdown", action="store_true", help="print the tables as Markdown")
    ap.add_argument("--update", action="store_true", help="write them into docs/BENCHMARKS.md")
    ap.add_argument("--block", default="paper-metrics",
                    help="the docs/BENCHMARKS.md block --update writes (default paper-metrics)")
    ap.add_argument("--labels", nargs=2, metavar=("OLD", "NEW"),
                    help="names of the two builds in the --update text (default: their paths)")
    args = ap.parse_args()
    args.markdown = args.markdown or args.update
    root = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir)
    scenarios = sorted(glob.glob(os.path.join(root, "sil", "scenarios", "paper", "*.toml")))
    status = 0
    with tempfile.TemporaryDirectory(prefix="uvms-metrics-") as tmp, \
            concurrent.futures.ThreadPoolExecutor(args.j) as pool:
        jobs = {}
        for s in scenarios:
            name = os.path.basename(s)[:-5]
            for side, exe in (("old", args.old_uvms), ("new", args.new_uvms)):
                jobs[(name, side)] = pool.submit(run, exe, s, os.path.join(tmp, f"{side}-{name}"))
        rows, per_metric = [], {}
        for s in scenarios:
            name = os.path.basename(s)[:-5]
            old, new = jobs[(name, "old")].result(), jobs[(name, "new")].result()
            if old["status"] != new["status"]:
                status = 1
            d = compare(old, new, args.floor)
            worst = max(d, key=lambda k: d[k][0])
            rows.append((name, old["status"], new["status"], d[worst], worst,
                         old["integrator_rhs_evals"] / old["ticks"],
                         new["integrator_rhs_evals"] / new["ticks"]))
            for k, v in d.items():
                key = k.split("[")[0]
                if key not in per_metric or v[0] > per_metric[key][0]:
                    per_metric[key] = v
    lines = []
    def print_(text=""):
        lines.append(text)
    moved = sorted(((k, v) for k, v in per_metric.items() if v[0] > 0.0), key=lambda kv: -kv[1][0])
    same = sorted(k for k, v in per_metric.items() if v[0] == 0.0)
    if args.markdown:
        print_("| scenario | status (old, new) | largest relative difference | in (old value, absolute difference) | RHS per tick (old → new) |")
        print_("|---|---|---:|---|---:|")
        for n, so, sn, v, k, ro, rn in rows:
            print_(f"| {n} | {so}, {sn} | {v[0]:.1e} | `{k}` ({v[2]:.6g}, {v[1]:.1e}) | {ro:.1f} → {rn:.1f} |")
        print_()
        print_("| metric | largest relative difference over the scenarios | its old value | absolute difference |")
        print_("|---|---:|---:|---:|")
        for k, v in moved:
            print_(f"| `{k}` | {v[0]:.1e} | {v[2]:.6g} | {v[1]:.1e} |")
        print_(f"\nUnchanged in every scenario: {', '.join(f'`{k}`' for k in same)}.")
    else:
        for n, so, sn, v, k, ro, rn in rows:
            print_(f"{n:20s} {so}/{sn}  max rel diff {v[0]:.1e} in {k} (old {v[2]:.6g}, abs diff {v[1]:.1e})"
                  f"  rhs/tick {ro:.1f} -> {rn:.1f}")
        print_()
        for k, v in moved:
            print_(f"{k:40s} rel {v[0]:.1e}  old {v[2]:.6g}  abs {v[1]:.1e}")
        print_(f"unchanged in every scenario: {' '.join(same)}")
    text = "\n".join(lines)
    print(text)
    if args.update:
        old, new = args.labels or (args.old_uvms, args.new_uvms)
        head = (f"`bench/paper_metrics_diff.py`: {old} (old) against {new} (new), the {len(rows)} "
                "paper scenarios, memq, one session.\n\n")
        replace_block(f"<!-- {args.block}:begin -->", f"<!-- {args.block}:end -->", head + text)
    return status


if __name__ == "__main__":
    sys.exit(main())
