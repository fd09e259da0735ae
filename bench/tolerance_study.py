#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""bench/tolerance_study.py: what the motor speeds' absolute tolerance costs and buys.

    bench/tolerance_study.py [--uvms EXE] [--update]

Runs case VII stagnant, case VII unsteady and case V stagnant (60 s, memq) at a rel 1e-12 /
abs 1e-14 reference (motor speeds 1e-14 rad/s) and at the defaults with
integrator.motor_speed_abs_tol = 1e-9 ... 1e-5 rad/s, and prints per run the RHS evaluations
per tick and the difference from the reference: mean and final EE error [m], thruster,
manipulator and propulsive energy (relative), and the position part and the feedforward part
of the propulsive energy (relative; the per-tick splits of docs/MODEL.md §10, the most
sensitive figures). --update writes the table into docs/BENCHMARKS.md (between
<!-- tolerance-study:begin --> and <!-- tolerance-study:end -->). Needs a built host preset.
"""
import argparse
import datetime
import json
import math
import os
import subprocess
import sys
import tempfile

from doc_block import publish

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir))
SCENARIOS = ("case_VII_stagnant", "case_VII_unsteady", "case_V_stagnant")
TOLERANCES = ("1e-9", "1e-7", "1e-6", "2e-6", "3e-6", "1e-5")
REFERENCE = ["integrator.rel_tol=1e-12", "integrator.abs_tol=1e-14",
             "integrator.motor_speed_abs_tol=1e-14"]
BEGIN, END = "<!-- tolerance-study:begin -->", "<!-- tolerance-study:end -->"


def run(uvms, scenario, sets, out):
    argv = [uvms, "run", os.path.join(ROOT, "sil", "scenarios", "paper", scenario + ".toml"),
            "--transport", "memq", "--no-log", "--out", out]
    for s in sets:
        argv += ["--set", s]
    subprocess.run(argv, check=True, capture_output=True)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--uvms", default=os.path.join(ROOT, "build", "host", "sil", "uvms"))
    ap.add_argument("--update", action="store_true")
    args = ap.parse_args()
    head = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                          text=True).stdout.strip()
    lines = [f"Measured {datetime.date.today().isoformat()} at {head} by `bench/tolerance_study.py` "
             "(60 s, memq; differences from a rel 1e-12 / abs 1e-14 reference).", "",
             "| motor-speed abs tol [rad/s] | scenario | RHS per tick | mean EE error [m] | final EE "
             "[m] | thruster energy | manipulator energy | propulsive energy | its position part "
             "| its feedforward part |",
             "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    with tempfile.TemporaryDirectory(prefix="uvms-tol-") as tmp:
        refs = {sc: run(args.uvms, sc, REFERENCE, os.path.join(tmp, "ref-" + sc)) for sc in SCENARIOS}
        for tol in TOLERANCES:
            for sc in SCENARIOS:
                r = refs[sc]
                s = run(args.uvms, sc, [f"integrator.motor_speed_abs_tol={tol}"],
                        os.path.join(tmp, f"{tol}-{sc}"))

                def rel(k):
                    return abs(r[k] - s[k]) / abs(r[k]) if r[k] else abs(s[k])
                lines.append(
                    f"| {tol} | {sc} | {s['integrator_rhs_evals'] / s['ticks']:.2f} "
                    f"| {abs(r['mean_ee_error_m'] - s['mean_ee_error_m']):.1e} "
                    f"| {math.dist(r['final_ee_position_m'], s['final_ee_position_m']):.1e} "
                    f"| {rel('thruster_energy_J'):.1e} | {rel('manipulator_energy_J'):.1e} "
                    f"| {rel('propulsive_energy_J'):.1e} | {rel('propulsive_energy_pos_J'):.1e} "
                    f"| {rel('propulsive_energy_ff_J'):.1e} |")
    text = "\n".join(lines)
    publish(BEGIN, END, text, args.update)
    return 0


if __name__ == "__main__":
    sys.exit(main())
