#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""bench/plant_speed.py: the truth model's speed against an earlier commit, side by side.

    bench/plant_speed.py [--pairs N] [--base COMMIT] [--uvms EXE] [--callgrind] [--update]

Builds COMMIT (default bc45f0a, the commit before the plant's 2x work) in a git worktree under
build/plant-speed-base/COMMIT (kept: later calls reuse it), with one change applied:
bench/baseline/plant_wall_time.patch, the timer around Plant::Step that writes summary.json's
`plant_wall_s` (the current code has it; the patch adds nothing else). Then runs the 60 s paper
scenarios case VII stagnant and unsteady over memq, alternating the two binaries N times
(default 15) each, and prints per scenario: the median plant time of each binary, the ratio
base/new of every neighbouring pair (median, quartiles, min and max), the whole run's wall
ratio, and the RHS evaluations per tick. Wall times on these 2-core VMs drift by tens of per
cent within minutes: neighbouring pairs see the same machine, so their ratio is the figure.
--callgrind adds the exact one: the instructions executed inside Plant::Step (inclusive) in one
run of each binary and scenario under valgrind's callgrind.

--update writes the table into docs/BENCHMARKS.md (between <!-- plant-speed:begin --> and
<!-- plant-speed:end -->). Needs a built host preset (cmake --workflow --preset host).
"""
import argparse
import datetime
import json
import os
import statistics
import subprocess
import sys
import tempfile

from doc_block import publish

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))
PATCH = os.path.join(ROOT, "bench", "baseline", "plant_wall_time.patch")
SCENARIOS = ("case_VII_stagnant", "case_VII_unsteady")
BEGIN, END = "<!-- plant-speed:begin -->", "<!-- plant-speed:end -->"


def sh(cmd, **kw):
    return subprocess.run(cmd, check=True, text=True, **kw)


def build_base(commit):
    """The baseline uvms: COMMIT plus the timer patch, built once under build/."""
    full = sh(["git", "-C", ROOT, "rev-parse", "--verify", commit + "^{commit}"],
              capture_output=True).stdout.strip()
    src = os.path.join(ROOT, "build", "plant-speed-base", full[:12])
    exe = os.path.join(src, "build", "host", "sil", "uvms")
    if os.path.exists(exe):
        return exe, full
    if not os.path.isdir(src):
        sh(["git", "-C", ROOT, "worktree", "add", "--detach", src, full], capture_output=True)
    if subprocess.run(["git", "-C", src, "diff", "--quiet"]).returncode == 0:  # not applied yet
        sh(["git", "-C", src, "apply", PATCH])
    print(f"plant_speed: building {full[:12]} + {os.path.relpath(PATCH, ROOT)} in {src} "
          "(once; a few minutes)", file=sys.stderr)
    sh(["cmake", "--preset", "host"], cwd=src, stdout=subprocess.DEVNULL)
    sh(["cmake", "--build", "--preset", "host", "--target", "uvms"], cwd=src,
       stdout=subprocess.DEVNULL)
    return exe, full


def run(exe, scenario, out):
    sh([exe, "run", os.path.join(ROOT, "sil", "scenarios", "paper", scenario + ".toml"),
        "--transport", "memq", "--out", out], capture_output=True)
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    if s["status"] != "finished":
        raise SystemExit(f"plant_speed: {exe} {scenario}: {s['status']} {s.get('reason', '')}")
    return s


def quartiles(xs):
    q = statistics.quantiles(xs, n=4, method="inclusive")
    return q[0], q[2]


def measure(base_exe, new_exe, pairs):
    rows = []
    with tempfile.TemporaryDirectory(prefix="uvms-plant-speed-") as tmp:
        for sc in SCENARIOS:
            b, n = [], []
            for i in range(pairs):
                b.append(run(base_exe, sc, os.path.join(tmp, f"b{sc}{i}")))
                n.append(run(new_exe, sc, os.path.join(tmp, f"n{sc}{i}")))
            ratio = [x["plant_wall_s"] / y["plant_wall_s"] for x, y in zip(b, n)]
            whole = [x["wall_time_s"] / y["wall_time_s"] for x, y in zip(b, n)]
            q1, q3 = quartiles(ratio)
            rows.append({
                "scenario": sc, "pairs": pairs,
                "base_plant_s": statistics.median(x["plant_wall_s"] for x in b),
                "new_plant_s": statistics.median(x["plant_wall_s"] for x in n),
                "ratio_median": statistics.median(ratio), "ratio_q1": q1, "ratio_q3": q3,
                "ratio_min": min(ratio), "ratio_max": max(ratio),
                "whole_ratio_median": statistics.median(whole),
                "base_rhs": b[0]["integrator_rhs_evals"] / b[0]["ticks"],
                "new_rhs": n[0]["integrator_rhs_evals"] / n[0]["ticks"],
                "sim_s": n[0]["duration_s"],
            })
    return rows


def step_instructions(exe, scenario, tmp):
    """Instructions inside Plant::Step (inclusive) in one run, from callgrind."""
    out = os.path.join(tmp, "cg-" + os.path.basename(os.path.dirname(os.path.dirname(exe))) + scenario)
    sh(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}.cg", exe, "run",
        os.path.join(ROOT, "sil", "scenarios", "paper", scenario + ".toml"), "--transport", "memq",
        "--no-log", "--out", out], capture_output=True)
    text = sh(["callgrind_annotate", "--inclusive=yes", out + ".cg"], capture_output=True).stdout
    for line in text.splitlines():
        if "uvms::plant::Plant::Step(" in line:
            return int(line.split()[0].replace(",", ""))
    raise SystemExit(f"plant_speed: no Plant::Step in the callgrind profile of {exe}")


def callgrind(base_exe, new_exe):
    import concurrent.futures
    with tempfile.TemporaryDirectory(prefix="uvms-plant-cg-") as tmp, \
            concurrent.futures.ThreadPoolExecutor(2) as pool:
        jobs = {(sc, side): pool.submit(step_instructions, exe, sc, tmp)
                for sc in SCENARIOS for side, exe in (("base", base_exe), ("new", new_exe))}
        return {sc: (jobs[(sc, "base")].result(), jobs[(sc, "new")].result()) for sc in SCENARIOS}


def table(rows, base, new, instr=None):
    out = [f"Measured {datetime.date.today().isoformat()}: base {base[:7]} (+ the timer patch) "
           f"against {new}, `bench/plant_speed.py --pairs {rows[0]['pairs']}`.", "",
           "| scenario (60 s, memq) | plant time per run, base → new (median) | plant speed-up, "
           "pairs: median (quartiles; min–max) | whole run speed-up (median) | RHS per tick, "
           "base → new |",
           "|---|---:|---:|---:|---:|"]
    for r in rows:
        out.append(f"| {r['scenario']} | {r['base_plant_s'] * 1e3:.1f} → {r['new_plant_s'] * 1e3:.1f} ms "
                   f"| **{r['ratio_median']:.2f}×** ({r['ratio_q1']:.2f}–{r['ratio_q3']:.2f}; "
                   f"{r['ratio_min']:.2f}–{r['ratio_max']:.2f}) | {r['whole_ratio_median']:.2f}× "
                   f"| {r['base_rhs']:.1f} → {r['new_rhs']:.1f} |")
    if instr:
        out += ["", "| scenario (60 s, memq) | instructions in Plant::Step, base → new (callgrind) | ratio |",
                "|---|---:|---:|"]
        for sc, (b, n) in instr.items():
            out.append(f"| {sc} | {b / 1e6:.1f} M → {n / 1e6:.1f} M | **{b / n:.2f}×** |")
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog=__doc__.split("\n\n", 2)[2])
    ap.add_argument("--pairs", type=int, default=15, help="runs of each binary per scenario")
    ap.add_argument("--base", default="bc45f0a", help="the commit to compare against")
    ap.add_argument("--uvms", default=os.path.join(ROOT, "build", "host", "sil", "uvms"),
                    help="the binary under test (default: the host build)")
    ap.add_argument("--callgrind", action="store_true",
                    help="also count Plant::Step's instructions (valgrind; a few minutes)")
    ap.add_argument("--update", action="store_true", help="write the table into docs/BENCHMARKS.md")
    args = ap.parse_args()
    if args.pairs < 2:
        ap.error("--pairs must be at least 2")
    base_exe, base = build_base(args.base)
    head = sh(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True).stdout.strip()
    dirty = sh(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
               capture_output=True).stdout.strip()
    rows = measure(base_exe, args.uvms, args.pairs)
    instr = callgrind(base_exe, args.uvms) if args.callgrind else None
    text = table(rows, base, head + ("-dirty" if dirty else ""), instr)
    publish(BEGIN, END, text, args.update)
    return 0


if __name__ == "__main__":
    sys.exit(main())
