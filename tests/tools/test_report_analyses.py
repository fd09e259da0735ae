# SPDX-License-Identifier: Apache-2.0
"""The report package's analyses, schema loading and structure, on synthetic data with known
answers (no runs needed):

- analyses/delay.py: best_lag recovers a known delay of a multi-channel signal (exactly, and
  capped by max_lag_s); the tracking errors of known signals;
- analyses/energy.py: the position/attitude split of synthetic allocated thrust, the motor's
  friction and copper energies, the energy breakdown (friction share, b/|c1|), the propulsive
  energy of a constant thrust, the drag impulse of a constant relative flow;
- analyses/motor.py: the continuous speed loop's ω_n and ζ;
- analyses/headline.py: per-experiment rows grouped by override values, not by labels;
- load/schema.py: the schema of `uvms scenario schema` read from a file and from a binary
  (a stand-in script), malformed schemas and a missing binary rejected with clear messages,
  and the report's command line failing with that message;
- context.Report: whether a comparison is an unsteady-flow one comes from the runs' values;
- text: defaults shown as the scenario files write them, the coefficient table from the
  schema;
- the package: no function over 100 lines, no grouping by run ids or label substrings, no
  reading of docs/ or source files.

Usage: test_report_analyses.py SOURCE_DIR
"""
import ast
import json
import math
import os
import re
import shutil
import stat
import subprocess
import sys
import tempfile

SRC = sys.argv[1]
sys.path.insert(0, os.path.join(SRC, "tools"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_testkit import TABLE_ID  # noqa: E402
import numpy as np  # noqa: E402

from uvms_tools.report import keys as K  # noqa: E402
from uvms_tools.report.analyses import delay, energy, motor  # noqa: E402
from uvms_tools.report.analyses import headline as H  # noqa: E402
from uvms_tools.report.context import Report  # noqa: E402
from uvms_tools.report.load import schema as S  # noqa: E402
from uvms_tools.report.text.fmt import fmt_setting  # noqa: E402
from uvms_tools.report.text.settings import coeff_rows, default_text  # noqa: E402

FIXTURE = os.path.join(SRC, "tests", "tools", "data", "schema_small.json")
PKG = os.path.join(SRC, "tools", "uvms_tools", "report")
failures = []


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


def close(a, b, tol):
    return abs(a - b) <= tol


# --- delay: a known lag.
dt = 0.03
t = np.arange(0.0, 60.0, dt)
des = np.stack([np.sin(0.7 * t), np.cos(0.31 * t) + 0.2 * np.sin(2.1 * t),
                np.sin(0.05 * t ** 1.5)], axis=1)
for lag_n in (0, 1, 17, 40):
    prod = np.vstack([np.zeros((lag_n, 3)), des[: len(t) - lag_n]])  # prod(t) = des(t − L)
    lag, err_lag, err0 = delay.best_lag(des, prod, dt)
    check(close(lag, lag_n * dt, 1e-12) and err_lag < 1e-12 and (lag_n == 0 or err0 > 1e-3),
          f"best_lag: produced = desired delayed by {lag_n} samples → {lag:.3f} s "
          f"(RMS {err_lag:.1e} at the lag, {err0:.3f} at 0)")
prod = np.vstack([np.zeros((40, 3)), des[: len(t) - 40]])
lag, _, _ = delay.best_lag(des, prod, dt, max_lag_s=0.3)
check(close(lag, 0.3, 1e-12), f"best_lag stays within max_lag_s (0.3 s): {lag:.3f} s")
rng = np.random.default_rng(7)
prod = np.vstack([np.zeros((17, 3)), des[: len(t) - 17]]) + 0.01 * rng.standard_normal(des.shape)
lag, err_lag, err0 = delay.best_lag(des, prod, dt)
check(close(lag, 17 * dt, 1e-12) and close(err_lag, 0.01 * math.sqrt(3), 2e-3),
      f"with 0.01 noise per channel: lag {lag:.3f} s, RMS {err_lag:.4f} ≈ 0.01·√3 at the lag")
f_des = np.tile([3.0, 4.0, 0.0], (10, 1))
te = delay.tracking_errors(f_des, 0.5 * f_des, np.tile([0.0, 0.0, 2.0], (10, 1)),
                           np.zeros((10, 3)))
check(close(te["f"], 5.0, 1e-12) and close(te["f_err"], 2.5, 1e-12) and close(te["n"], 2.0, 1e-12)
      and close(te["n_err"], 2.0, 1e-12), "tracking errors: |(3,4,0)| = 5, half produced: 2.5")
check(close(float(delay.rms(np.array([3.0, -4.0, 3.0, -4.0]))), math.sqrt(12.5), 1e-12)
      and math.isnan(delay.rms(np.array([]))), "rms of ±3, ±4 = √12.5; empty: NaN")

# --- energy: the position/attitude split of the allocated thrust.
n, dt = 200, 0.03
p_pos = np.zeros((n, 8))
p_pos[:, 0], p_pos[:, 1] = 2.0, -1.0           # Σ|P_pos| = 3 N per tick
p_att = np.tile([0.5, -0.5, 0.5, -0.5, 0.25, -0.25, 0.25, -0.25], (n, 1))  # Σ|P_att| = 3 N
sp = energy.thrust_split(dt, p_pos, p_att, p_pos + p_att)
check(close(sp["pos"], 3.0 * n * dt, 1e-9) and close(sp["att"], 3.0 * n * dt, 1e-9),
      f"thrust split: ∫Σ|P_pos| = ∫Σ|P_att| = 3 N × {n * dt:.0f} s = {3 * n * dt:.0f} N·s")
check(close(sp["total"], (2.5 + 1.5 + 0.5 * 2 + 0.25 * 4) * n * dt, 1e-9),
      "∫Σ|P| of the sum (parts add per thruster before |·|)")
check(np.allclose(sp["rms_pos"], [2, 1, 0, 0, 0, 0, 0, 0]) and
      np.allclose(sp["rms_att"], [0.5] * 4 + [0.25] * 4), "RMS per thruster of each part")
# The motor's energies: constant ω, I, V on two of eight thrusters.
w, cur, v = np.zeros((n, 8)), np.zeros((n, 8)), np.zeros((n, 8))
w[:, 0], cur[:, 0], v[:, 0] = -100.0, 2.0, 30.0     # V·I = 60 W
w[:, 1], cur[:, 1], v[:, 1] = 50.0, -1.0, 10.0      # V·I < 0: regenerating, counts 0
ml = energy.motor_losses(dt, w, cur, v, friction=0.01, resistance=1.5)
check(close(ml["e_vi"][0], 60.0 * n * dt, 1e-9) and ml["e_vi"][1] == 0.0
      and ml["e_vi"][2:].sum() == 0.0, "∫max(V·I, 0) dt per thruster, regeneration not counted")
check(close(ml["friction"], 0.01 * (100.0 ** 2 + 50.0 ** 2) * n * dt, 1e-9)
      and close(ml["copper"], 1.5 * (4.0 + 1.0) * n * dt, 1e-9),
      "friction ∫Σb·ω² dt and copper ∫ΣR·I² dt")
mot = dict(b=0.01, R=1.5, ct2=-0.2, rho=1000.0, diameter_m=0.1)
c1 = -0.2 * 1000.0 * 0.1 ** 4 / (4 * math.pi ** 2)
thrust = np.zeros((n, 8))
thrust[:, 0] = 0.4
eb = energy.energy_breakdown(dt, w, cur, v, thrust, 2 * thrust, mot, energy_J=2 * ml["friction"])
check(close(eb["fric_share"], 0.5, 1e-12) and close(eb["b_c1"], 0.01 / abs(c1), 1e-9)
      and close(eb["imp"], 0.4 * n * dt, 1e-12) and close(eb["imp_des"], 0.8 * n * dt, 1e-12),
      f"energy breakdown: friction share 0.5 of E_el, b/|c1| = {0.01 / abs(c1):.1f} W/N, "
      "delivered and allocated impulses")
# Propulsive energy of a constant thrust: 8·|T|^1.5/√(2ρA_d) over the ticks.
tt = np.arange(101) * 0.03
a_d = math.pi * 0.05 ** 2 / 4
ep = energy.propulsive_from_truth(tt, np.full((101, 8), -0.3), 1025.0, 0.05)
check(close(ep, 8 * 0.3 ** 1.5 / math.sqrt(2 * 1025.0 * a_d) * 3.0, 1e-12),
      "E_p of a constant 0.3 N on 8 thrusters over 3 s")
check(energy.propulsive_from_truth([0.0], [[1.0] * 8], 1025.0, 0.05) == 0.0, "E_p of one sample: 0")
# Drag of a constant relative flow.
vel = np.tile([0.02, 0.0, 0.0], (n, 1))
flow = np.tile([-0.01, 0.0, 0.0], (n, 1))
dr = energy.drag_impulses(dt, vel, flow, np.tile([0.0, 3.0, 4.0], (n, 1)), np.zeros((n, 3)), 300.0)
check(close(dr["drag_imp"], 300.0 * 0.03 ** 2 * n * dt, 1e-12) and close(dr["fdes_imp"], 5 * n * dt, 1e-9)
      and dr["ffb_imp"] == 0.0 and close(dr["flow"], 0.01, 1e-15) and close(dr["vel"], 0.02, 1e-15),
      "drag impulse k·|w|² with w = v0 − v∞ = 0.03 m/s; |F_des| = 5 N")
check(energy.median_step([0.0, 0.1, 0.2, 0.4]) == 0.1 and math.isnan(energy.median_step([1.0])),
      "median sample step")

# --- motor: the continuous loop's natural frequency and damping.
cfg = {k: [val] for k, val in dict(speed_gain_1_s=4.0, current_gain_1_s=9.0,
                                   motor_viscous_friction_Nm_s=0.02,
                                   rotor_inertia_kg_m2=0.01).items()}
ld = motor.loop_damping(cfg)
check(close(ld["wn"], 6.0, 1e-12) and close(ld["b_j"], 2.0, 1e-12)
      and close(ld["zeta"], (9.0 + 2.0) / 12.0, 1e-12), "ω_n = √(KA·KB) = 6, ζ = (KB + b/J)/2ω_n")

# --- headline: per-experiment rows by override values, never by labels.
comps = [dict(exp="e", pair="VII/IV", label="same label", row={K.KEY_UNSTEADY: False}),
         dict(exp="e", pair="VII/IV", label="same label", row={K.KEY_UNSTEADY: True}),
         dict(exp="e", pair="VII/IV", label="other label", row={K.KEY_UNSTEADY: False}),
         dict(exp="f", pair="VII/IV", label="same label", row={K.KEY_UNSTEADY: False})]
groups = list(H.row_groups(comps).values())
check([[comps.index(c) for c in g] for g in groups] == [[0, 2], [1], [3]],
      "rows grouped by (experiment, pair, override values): a shared label does not merge, "
      "a different label does not split")
check(H.answer(3, 3) == "yes" and H.answer(2, 3) == "mostly" and H.answer(0, 3) == "no"
      and H.answer(1, 3) == "rarely", "the headline's one-word answer")

# --- schema: from the fixture.
sch = S.from_file(FIXTURE)
check(len(sch) == 16 and sch.default("payload.mass_kg") == 10.0
      and sch.default("control.case") is None and "control.case" not in sch.defaults()
      and sch.unit("environment.density_kg_m3") == "kg/m3",
      "schema read: defaults (null = none), units")
check(sch.default("no.such.key") is None and sch.entry("thrusters.drive")["lcm"] == "drive",
      "unknown key: no default; rows keep their mapping columns")
try:
    sch.require_defaults([K.KEY_PAYLOAD, K.KEY_CASE])
    msg = ""
except S.SchemaError as e:
    msg = str(e)
check("control.case" in msg and "payload" not in msg, f"a selection key without default named: {msg}")
fixture = json.load(open(FIXTURE))
bad = [({**fixture, "schema_version": 2}, "schema_version 2"),
       ({"schema_version": 1, "keys": []}, "no \"keys\""),
       ({"schema_version": 1, "keys": [{"key": "a.b"}]}, "lacks \"key\" or \"default\""),
       ([1, 2], "not a JSON object")]
for data, want in bad:
    try:
        S.Schema(data, "t")
        got = ""
    except S.SchemaError as e:
        got = str(e)
    check(want in got, f"malformed schema rejected: {got}")
try:
    S.parse("{not json", "t")
    got = ""
except S.SchemaError as e:
    got = str(e)
check("not JSON" in got, f"non-JSON rejected: {got}")

tmp = tempfile.mkdtemp(prefix="uvms-report-analyses-")
try:
    missing = os.path.join(tmp, "no_uvms")
    try:
        S.from_binary(missing)
        got = ""
    except S.SchemaError as e:
        got = str(e)
    check("does not exist" in got and "--uvms" in got and "--schema" in got,
          f"missing binary: {got[:100]}…")
    fake = os.path.join(tmp, "uvms")
    with open(fake, "w") as fh:
        fh.write(f"#!/bin/sh\nif [ \"$1 $2\" = \"scenario schema\" ]; then cat '{FIXTURE}'; "
                 f"exit 0; fi\necho 'uvms scenario: error: unknown action \"schema\"' >&2\n"
                 f"exit 2\n")
    os.chmod(fake, os.stat(fake).st_mode | stat.S_IXUSR)
    check(len(S.from_binary(fake)) == 16, "schema from `uvms scenario schema` (a stand-in binary)")
    old = os.path.join(tmp, "uvms_old")
    with open(old, "w") as fh:
        fh.write("#!/bin/sh\necho 'uvms scenario: error: unknown action \"schema\"' >&2\nexit 2\n")
    os.chmod(old, os.stat(old).st_mode | stat.S_IXUSR)
    try:
        S.from_binary(old)
        got = ""
    except S.SchemaError as e:
        got = str(e)
    check("exited with 2" in got and "unknown action" in got,
          f"a binary without the subcommand: {got[:110]}…")
    # The command line: no schema, no report.
    camp = os.path.join(tmp, "camp")
    os.makedirs(camp)
    env = dict(os.environ, UVMS_NO_REEXEC="1")
    p = subprocess.run([sys.executable, os.path.join(SRC, "tools", "report.py"), camp,
                        "--uvms", old], capture_output=True, text=True, env=env)
    check(p.returncode == 1 and "cannot obtain the configuration schema" in p.stderr
          and not os.path.exists(os.path.join(camp, "report.md")),
          f"report.py stops with the schema error ({p.stderr.strip()[:120]}…)")

    # --- context: unsteady or not from the runs' values (the condition does not name it).
    d = os.path.join(tmp, "root", "exp_u")
    os.makedirs(os.path.join(d, "runs"))
    plan, rows = [], []
    for case in ("IV", "VII"):
        for s in (1, 2, 3):
            rid = f"r{case}{s}"
            plan.append({"id": rid, "overrides": [f'control.case="{case}"', f"run.seed={s}",
                                                  "environment.unsteady_flow.enabled=true"]})
            rows.append({"id": rid, "status": "finished",
                         "thruster_energy_J": (10.0 if case == "IV" else 8.0) + s})
    json.dump(dict(TABLE_ID, name="exp_u", runs=plan), open(os.path.join(d, "plan.json"), "w"))
    json.dump(dict(TABLE_ID, name="exp_u", runs=rows), open(os.path.join(d, "results.json"), "w"))
    rep = Report(os.path.join(tmp, "root"), os.path.join(tmp, "out"), sch)
    rep.add_comparison("exp_u", "u", {})
    rep.add_comparison("exp_u", "u, payload default", {K.KEY_PAYLOAD: 10.0})
    c0, c1_ = rep.comparisons
    check(c0["unsteady"] and c0["paired"].n == 3 and c1_["paired"].n == 3,
          "unsteady from the runs' override; payload unset = the schema's default 10 kg")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

# --- text: defaults as the scenario files write them; the coefficient table from the schema.
check([fmt_setting(x) for x in (1e-8, 0.01, 5, 1025.0, "adams", True, [0, 0.5], 2.5e-5)] ==
      ["1e-8", "0.01", "5", "1025", '"adams"', "true", "[0, 0.5]", "2.5e-5"],
      "settings formatted as TOML")
check(default_text(sch, "integrator.rel_tol") == "1e-8" and
      "no single default" in default_text(sch, "control.case"), "schema defaults shown")
check(coeff_rows(sch.default(K.KEY_COEFF_TABLE)) == [(0.0, 0.5, 1.0), (4.0, 1.25, 0.75)]
      and coeff_rows([{"distance_diameters": 1.0}]) == [],
      "coefficient table rows from the schema; an incomplete row is not guessed")

# --- the package's structure.
def path_args(tree):
    """String arguments of open(...) and os.path.join(...) calls: the files a module reads."""
    out = []
    for n in ast.walk(tree):
        if isinstance(n, ast.Call) and ((isinstance(n.func, ast.Name) and n.func.id == "open")
                                        or (isinstance(n.func, ast.Attribute)
                                            and n.func.attr == "join")):
            out += [a.value for a in n.args if isinstance(a, ast.Constant)
                    and isinstance(a.value, str)]
    return out


long_fns, id_groups, reads = [], [], []
for dp, _, fs in os.walk(PKG):
    for fn in fs:
        if not fn.endswith(".py"):
            continue
        path = os.path.join(dp, fn)
        text = open(path).read()
        rel = os.path.relpath(path, PKG)
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                if node.end_lineno - node.lineno + 1 > 100:
                    long_fns.append(f"{rel}:{node.name}")
        if re.search(r"\bin\s+\w+(\[[\"'](id|label)[\"']\]|\.get\([\"'](id|label)[\"']\))", text):
            id_groups.append(rel)
        for c in path_args(ast.parse(text)):
            if c in ("docs", "src", "firmware", "plant") or (
                    re.search(r"\.(md|c|cpp|h|hpp)$", c) and c != "report.md"):  # its output
                reads.append(f"{rel}: {c!r}")
check(not long_fns, f"no function over 100 lines in tools/uvms_tools/report ({long_fns})")
check(not id_groups, f"no selection by substrings of run ids or labels ({id_groups})")
check(not reads, f"no path into docs/ or the sources ({reads})")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
