# SPDX-License-Identifier: Apache-2.0
"""The tick analyses of summary.json (sil/run/tick_analyses.hpp, docs/MODEL.md §10) on real runs,
checked against independent computations from the run's log (tools/uvmslog.py) and SPEC.

Usage: test_tick_analyses_e2e.py BUILD_SIL_DIR SOURCE_DIR CASE
CASE: split_additive | task_error_log | short_run | line | min_power | results_columns

Every run is a short paper case IV (stagnant) with its trajectory shortened; each writes into a
fresh temporary directory.
"""
import json
import math
import os
import subprocess
import sys

import numpy as np

from uvms_tools.log import runlog  # tools/uvms_tools/log/runlog.py (PYTHONPATH)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

SIL, SRC, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
# The controller's real type (argument 4, "double" or "float"): the commanded thrusts and the
# line's parameters come from the firmware, so a float build agrees to float rounding.
FLOAT = len(sys.argv) > 4 and sys.argv[4] == "float"
FW_REL = 1e-6 if FLOAT else 1e-9      # relative, quantities from the firmware's real type
FW_ABS_N = 1e-5 if FLOAT else 1e-9    # thrust [N]
UVMS = os.path.join(SIL, "uvms")
SCENARIO = os.path.join(SRC, "sil", "scenarios", "paper", "case_IV_stagnant.toml")
TMP = scratch_dir("uvms-tick-analyses-")  # removed at exit (tests/support/scratch.py)
# The run and trajectory of most cases: t_F = 3 s, the run 4 s (a hold after t_F).
BASE = ["run.duration_s=4", "trajectory.duration_s=3"]
# SPEC §8's target point (2.428, 0.250, 0.404) m in this project's inertial frame: less the arm
# base offset s0 = (0.914, 0, 0.152) m (docs/MODEL.md §10; the offset is checked against the
# kinematics by PaperTargetPointIsVehColumnEePlusBaseOffset).
TARGET = np.array([2.428, 0.250, 0.404]) - np.array([0.914, 0.0, 0.152])  # [m]
# SPEC §3.4: thruster positions a_j [m] and directions u_j, vehicle frame.
A = np.array([(-0.5, 0.5, 0.5), (-0.5, -0.5, 0.5), (-0.5, 0.5, -0.5), (-0.5, -0.5, -0.5),
              (0.1, 0.5, 0), (0.1, -0.5, 0), (0.1, 0, 0.5), (0.1, 0, -0.5)])
U = np.array([(1, 0, 0)] * 4 + [(0, 0, 1)] * 2 + [(0, 1, 0)] * 2, dtype=float)
# SPEC §3.2 / §3.4: ρ, D, b, Rm, Lm, J.
RHO, D, B, RM, LM, JR = 1025.0, 0.05, 0.01, 1.0, 1.0, 0.01
REL = 1e-9  # additivity: the parts add up to E_p up to rounding


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def check(cond, msg):
    if not cond:
        fail(msg)
    print("ok:", msg)


def run(name, overrides):
    out = os.path.join(TMP, name)
    args = [UVMS, "run", SCENARIO, "--out", out, "--transport", "memq"]
    for o in overrides:
        args += ["--set", o]
    p = subprocess.run(args, capture_output=True, text=True, timeout=240)
    print("$", " ".join(args), "->", p.returncode)
    if p.returncode != 0:
        fail(f"uvms run exited {p.returncode}: {p.stdout}{p.stderr}")
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    return out, s


def close(a, b, rel=REL, what=""):
    ok = abs(a - b) <= rel * max(abs(a), abs(b), 1e-300)
    check(ok, f"{what}: {a!r} vs {b!r} (rel {rel})")


def rot(q):
    w, x, y, z = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def trapezoid(t, y):
    return float(np.sum(0.5 * np.diff(t) * (y[1:] + y[:-1])))


def split_additive():
    out, s = run("split", BASE)
    ep = s["propulsive_energy_J"]
    check(ep > 0, "E_p > 0")
    check(s["propulsive_split_inexact_ticks"] == 0, "every tick of case IV (pseudoinverse, "
          "unsaturated) has an exact ff/fb split")
    check(s["propulsive_pos_att_inexact_ticks"] == 0, "... and an exact pos/att split")
    check(abs(s["alloc_realised_saving"]) <= (1e-5 if FLOAT else 1e-12) and s["alloc_static_potential"] > 0,
          "a pseudoinverse run realises none of its static potential "
          f"({s['alloc_static_potential']:.3g})")
    close(s["propulsive_energy_ff_J"] + s["propulsive_energy_fb_J"]
          + s["propulsive_energy_ff_fb_unsplit_J"], ep, what="ff + fb + unsplit = E_p")
    close(s["propulsive_energy_pos_J"] + s["propulsive_energy_att_J"]
          + s["propulsive_energy_pos_att_unsplit_J"], ep, what="pos + att + unsplit = E_p")
    groups = [s[f"propulsive_energy_group_{g}_J"] for g in "xyz"]
    close(sum(groups), ep, what="Σ groups = E_p")
    close(sum(s["propulsive_energy_thruster_J"]), ep, what="Σ thrusters = E_p")
    check(s["propulsive_energy_groups"] == {"x": [1, 2, 3, 4], "y": [7, 8], "z": [5, 6]},
          f"groups by the axis of u_j (SPEC §3.4): {s['propulsive_energy_groups']}")

    log = runlog.load(out, ["UVMS_TRUTH", "UVMS_TELEMETRY"])
    tr, tm = log["UVMS_TRUTH"], log["UVMS_TELEMETRY"]
    close(s["propulsive_energy_J"], float(tr["propulsive_energy_J"][-1]), rel=0,
          what="E_p is the log's final truth")
    # Independent: each group's share from the log's thrusts, P_j = |T_j|^1.5/√(2ρA_d) by the
    # trapezoid over the ticks (the split shares the plant's CVODE integral of each tick by the
    # same weights, so the two agree to the quadrature's error: shares within ~2e-4 here).
    t = tr["t_s"]
    k = 1.0 / math.sqrt(2 * RHO * math.pi * D * D / 4)
    P = np.abs(tr["thrust_N"]) ** 1.5 * k
    per = np.array([trapezoid(t, P[:, j]) for j in range(8)])
    for g, idx in (("x", [0, 1, 2, 3]), ("y", [6, 7]), ("z", [4, 5])):
        mine, theirs = s[f"propulsive_energy_group_{g}_J"] / ep, per[idx].sum() / per.sum()
        check(abs(mine - theirs) < 1e-3, f"group {g}'s share of E_p {mine:.6f} vs the log's "
              f"trapezoid {theirs:.6f}")
    # The allocation is linear (what the ff/fb split relies on): H⁺·(R0ᵀF_des; 0) is the
    # telemetry's thrust_pos, with H of SPEC §3.4 and R0 from the truth (no sensor noise).
    H = np.vstack([U.T, np.cross(A, U).T])
    Hp = H.T @ np.linalg.inv(H @ H.T)
    tm = tm.select(tm["tick"] >= 0)
    ticks = np.intersect1d(tr["tick"], tm["tick"])
    a, b = tr.at_ticks(ticks), tm.at_ticks(ticks)
    worst = 0.0
    for i in range(len(ticks)):
        R0 = rot(a["quaternion_wxyz"][i])
        pos = Hp @ np.concatenate([R0.T @ b["force_des_N"][i], np.zeros(3)])
        worst = max(worst, np.max(np.abs(pos - b["thrust_pos_N"][i])))
    check(worst < FW_ABS_N, f"H⁺(R0ᵀF_des, 0) = thrust_pos on every tick (worst {worst:.2e} N)")
    # Motor energies: friction is b·Σω² by the trapezoid (the same rule, from the log); the
    # energy balance of the motors closes: ∫ΣV·I = copper + friction + shaft + ½JΣω² + ½LmΣI².
    w, i_a = tr["motor_speed_rad_s"], tr["motor_current_A"]
    close(s["friction_energy_J"], trapezoid(t, B * np.sum(w * w, axis=1)), rel=1e-9,
          what="friction energy vs the log")
    close(s["copper_energy_J"], trapezoid(t, RM * np.sum(i_a * i_a, axis=1)), rel=1e-9,
          what="copper energy vs the log")
    stored = 0.5 * JR * np.sum(w[-1] ** 2) + 0.5 * LM * np.sum(i_a[-1] ** 2)
    balance = s["copper_energy_J"] + s["friction_energy_J"] + s["shaft_energy_J"] + stored
    close(balance, s["thruster_energy_signed_J"], rel=1e-4,
          what="motor energy balance (trapezoid over 0.03 s ticks)")


def task_error_log():
    out, s = run("task", BASE)
    check(s["task_error_reference"] == "target", "joint maneuver: the reference is the target")
    check(np.allclose(s["task_reference_end_m"], TARGET, rtol=0, atol=1e-12),
          "the default target is SPEC §8's point less s0")
    tr = runlog.load(out, ["UVMS_TRUTH"])["UVMS_TRUTH"]
    t, ee = tr["t_s"], tr["ee_position_m"]
    check(tr["tick"][-1] == s["ticks"] and len(t) == s["ticks"] + 1,
          "the log has the truth of every tick and of the end")
    e = np.linalg.norm(ee - TARGET, axis=1)
    close(s["task_error_final_m"], float(e[-1]), rel=1e-12, what="final = |EE(end) − target|")
    tf = 3.0
    at = int(np.argmax(t >= tf - 1e-6))
    close(s["task_error_at_tf_m"], float(e[at]), rel=1e-12, what=f"at t_F = the sample at t = {t[at]}")
    close(s["task_error_hold_mean_m"], float(e[t > tf + 1e-6].mean()), rel=1e-12, what="hold mean")
    close(s["task_error_mean_m"], float(e.mean()), rel=1e-12, what="mean over the samples")
    close(s["task_error_max_m"], float(e.max()), rel=1e-12, what="max over the samples")
    # Another target, by the scenario key.
    _, s2 = run("task2", BASE + ["metrics.ee_target_m=[2.0, 0.0, 0.5]"])
    close(s2["task_error_final_m"], float(np.linalg.norm(ee[-1] - [2.0, 0.0, 0.5])), rel=1e-12,
          what="metrics.ee_target_m moves the target")


def short_run():
    _, s = run("short", ["run.duration_s=1", "trajectory.duration_s=3"])
    check(s["status"] == "finished", "the short run finished")
    check(s["task_error_at_tf_m"] is None, "a run that ends before t_F: at t_F is null")
    check(s["task_error_hold_mean_m"] is None, "... and the hold mean is null")
    check(s["task_error_final_m"] is not None, "... the final value is a number")


def line():
    rd, tf, t0 = 0.3, 2.0, 0.5
    # Experiment 5's line (sil/campaigns/paper/exp5_travel.toml): from the "Veh." pose along −x
    # (a +x line from the stowed pose is unreachable, docs/MODEL.md C27).
    out, s = run("line", ["run.duration_s=3", "trajectory.mode=\"cartesian_line\"",
                          "trajectory.theta_start_deg=[169.68, -75.62, 266.00, 108.77, 193.47, "
                          "96.97, 98.33]", "trajectory.cartesian.direction=[-1.0, 0.0, 0.0]",
                          f"trajectory.start_s={t0}", f"trajectory.duration_s={tf}",
                          f"trajectory.cartesian.distance_m={rd}"])
    check(s["task_error_reference"] == "line", "cartesian_line: the reference is the line")
    tr = runlog.load(out, ["UVMS_TRUTH"])["UVMS_TRUTH"]
    t, ee = tr["t_s"], tr["ee_position_m"]
    # SPEC §8 [78], along inertial −x, from the EE at t = 0.
    tp = np.clip(t - t0, 0.0, tf)
    r = ee[0] + np.outer(rd / 2 * (1 - np.cos(np.pi * tp / tf)), [-1.0, 0.0, 0.0])
    e = np.linalg.norm(ee - r, axis=1)
    close(s["task_error_final_m"], float(e[-1]), rel=FW_REL, what="line: final")
    close(s["task_error_mean_m"], float(e.mean()), rel=FW_REL, what="line: mean")
    close(s["task_error_max_m"], float(e.max()), rel=FW_REL, what="line: max")
    check(np.allclose(s["task_reference_end_m"], ee[0] - [rd, 0, 0], rtol=0,
                      atol=1e-6 if FLOAT else 1e-12),
          "the line's end point is r_start − rΔ·x")
    check(s["task_error_max_m"] < 0.05, f"the EE follows the line ({s['task_error_max_m']:.4f} m)")


def min_power():
    _, s = run("minpower", BASE + ["thrusters.allocation=\"min_power\""])
    ep = s["propulsive_energy_J"]
    check(s["propulsive_split_inexact_ticks"] == s["ticks"],
          "min_power is not linear: every tick's ff/fb split counted as inexact")
    # The static potential (alloc_potential.hpp) is realised: the controller's warm-started
    # solver reaches the optimum the harness finds cold on the same wrenches.
    pot, real = s["alloc_static_potential"], s["alloc_realised_saving"]
    check(pot > 0 and s["alloc_potential_unsolved_ticks"] == 0,
          f"a static potential was found on every tick ({pot:.3g})")
    check(abs(real - pot) <= 1e-6 * max(pot, 1e-3) + (1e-6 if FLOAT else 1e-9),
          f"realised saving {real:.6g} = static potential {pot:.6g}")
    close(s["propulsive_energy_ff_fb_unsplit_J"], ep, what="... all of E_p unsplit")
    check(s["propulsive_energy_ff_J"] == 0 and s["propulsive_energy_fb_J"] == 0, "... none ff/fb")
    check(s["propulsive_pos_att_inexact_ticks"] == 0, "pos/att stays exact (P_pos = T − P_att)")
    close(s["propulsive_energy_pos_J"] + s["propulsive_energy_att_J"]
          + s["propulsive_energy_pos_att_unsplit_J"], ep, what="pos + att + unsplit = E_p")


def results_columns():
    """The campaign's results.csv carries the analyses' columns, equal to each run's summary."""
    import csv
    camp = os.path.join(TMP, "c.toml")
    with open(camp, "w") as f:
        f.write(f'name = "tick_analyses"\nbase = "{SCENARIO}"\n[set]\n"run.duration_s" = 1.0\n'
                '[[sweep]]\n"control.case" = ["IV", "VII"]\n')
    out = os.path.join(TMP, "camp")
    p = subprocess.run([UVMS, "campaign", camp, "--out", out, "--no-logs"], capture_output=True,
                       text=True, timeout=240)
    if p.returncode != 0:
        fail(f"uvms campaign exited {p.returncode}: {p.stdout}{p.stderr}")
    cols = ["task_error_reference", "task_error_mean_m", "task_error_max_m", "task_error_final_m",
            "task_error_at_tf_m", "task_error_hold_mean_m", "propulsive_energy_ff_J",
            "propulsive_energy_fb_J", "propulsive_energy_ff_fb_unsplit_J",
            "propulsive_split_inexact_ticks", "propulsive_energy_pos_J", "propulsive_energy_att_J",
            "propulsive_energy_pos_att_unsplit_J", "propulsive_pos_att_inexact_ticks",
            "propulsive_energy_group_x_J", "propulsive_energy_group_y_J",
            "propulsive_energy_group_z_J", "shaft_energy_J", "friction_energy_J",
            "copper_energy_J"]
    with open(os.path.join(out, "results.csv")) as f:
        rows = list(csv.DictReader(f))
    check(len(rows) == 2 and all(c in rows[0] for c in cols), "results.csv has every column")
    for r in rows:
        with open(os.path.join(out, "runs", r["id"], "summary.json")) as f:
            s = json.load(f)
        for c in cols:
            v = s[c]
            cell = "" if v is None else (v if isinstance(v, str) else repr(v))
            if isinstance(v, float):
                ok = float(r[c]) == v
            else:
                ok = r[c] == cell
            if not ok:
                fail(f"{r['id']}: results.csv {c} = {r[c]!r}, summary.json {v!r}")
    check(True, "results.csv's cells are the summaries' values (null: empty)")


CASES = {"results_columns": results_columns, "split_additive": split_additive, "task_error_log": task_error_log,
         "short_run": short_run, "line": line, "min_power": min_power}

if __name__ == "__main__":
    if CASE not in CASES:
        fail(f"unknown case {CASE!r} (expected one of {', '.join(CASES)})")
    CASES[CASE]()
    print("PASS")
