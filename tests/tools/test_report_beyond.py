# SPDX-License-Identifier: Apache-2.0
"""The report's "Beyond the paper" section on synthetic data with known answers (no runs
needed):

- report/analyses/beyond.py: the paired saving 1 − new/old (mean and 95 % CI against a
  hand computation with a tabulated t quantile; seeds missing on one side or with a zero
  denominator left out), the paired change of a ratio between two settings (CI around 0 and
  entirely below 0), the change of verdict between two paired ratios, the tally of verdicts,
  distinct values in order; the impulse and tick-to-tick jumps of a thrust command;
- report/text/beyond.py on synthetic campaigns (results.json + plan.json; rows shuffled,
  so that pairing must go by seed and override values, not by order): the barycenter/vehicle
  ratio and the allocator saving of known per-seed energies appear in the tables with the
  right verdicts; min_power against the pseudoinverse: the error ratios with their CI and
  pass/fail against 1.1, the static potential, the realised saving of Σ|T|^1.5 paired per
  seed, the saving realised within the min_power runs, the realised share and its criterion
  (met / not met / n/a below a 1 % potential), recomputed here from the synthetic summaries;
  the pseudoinverse half of beyond_allocation described as differing from experiment 1 by the
  feedforward lead; a campaign that is missing is noted and its part skipped.

The configuration schema is tests/tools/data/schema_small.json (the format of
`uvms scenario schema`).

Usage: test_report_beyond.py SOURCE_DIR
"""
import json
import math
import os
import random
import shutil
import sys
import tempfile

SRC = sys.argv[1]
sys.path.insert(0, os.path.join(SRC, "tools"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_testkit import TABLE_ID  # noqa: E402

from uvms_tools.report.analyses import beyond as B  # noqa: E402
from uvms_tools.report.analyses import stats  # noqa: E402
from uvms_tools.report.context import Report  # noqa: E402
from uvms_tools.report.load import schema as S  # noqa: E402
from uvms_tools.report.text import beyond as text_beyond  # noqa: E402

SCHEMA = S.from_file(os.path.join(SRC, "tests", "tools", "data", "schema_small.json"))
failures = []

# Student t quantiles t_{0.975, dof}, tabulated (NIST/SEMATECH), not computed by stats.py.
T975 = {2: 4.302653, 3: 3.182446, 4: 2.776445, 19: 2.093024}


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


def close(a, b, tol):
    return abs(a - b) <= tol


def ci_by_hand(xs):
    """(mean, half-width of the 95 % CI) with the tabulated t quantile."""
    n = len(xs)
    m = sum(xs) / n
    sd = math.sqrt(sum((x - m) ** 2 for x in xs) / (n - 1))
    return m, T975[n - 1] * sd / math.sqrt(n)


# --- paired_saving: savings 10, 12, 8, 11, 9 % over seeds 1..5; seed 6 only on one side,
# seed 7 with a zero old energy: both left out.
old = {1: 200.0, 2: 50.0, 3: 400.0, 4: 100.0, 5: 1000.0, 7: 0.0}
want = {1: 0.10, 2: 0.12, 3: 0.08, 4: 0.11, 5: 0.09}
new = {s: old[s] * (1.0 - want[s]) for s in want}
new.update({6: 5.0, 7: 3.0})
sv = B.paired_saving(new, old)
m, h = ci_by_hand(list(want.values()))      # 0.10 ± 2.776445 · 0.0158114 / √5 = 0.0196324
check(sv.seeds == [1, 2, 3, 4, 5] and sv.n == 5 and sv.n_cheaper == 5,
      f"paired saving over the common seeds with old ≠ 0: {sv.seeds}")
check(close(sv.dist.mean, 0.10, 1e-12) and close(m, 0.10, 1e-12),
      f"mean saving 10 % ({100 * sv.dist.mean:.6f} %)")
check(close(sv.dist.half_width, h, 1e-6) and close(h, 0.0196324, 1e-6),
      f"95 % CI half-width {sv.dist.half_width:.7f} = t(0.975, 4)·s/√n = {h:.7f}")
check(stats.direction(sv.dist) == 1, "the saving's CI lies above 0")
dearer = B.paired_saving({1: 110.0, 2: 120.0}, {1: 100.0, 2: 100.0})
check(dearer.n_cheaper == 0 and close(dearer.dist.mean, -0.15, 1e-12),
      "a dearer allocator: negative saving, cheaper in 0 seeds")

# --- ratio_change: the per-seed change of a paired ratio from setting a to setting b.
den = {1: 10.0, 2: 20.0, 3: 40.0}
num_a = {s: 0.8 * den[s] for s in den}                    # ratio 0.8 in every seed
num_b = {1: 0.9 * 10.0, 2: 0.7 * 20.0, 3: 0.8 * 40.0}     # ratios 0.9, 0.7, 0.8
ch = B.ratio_change(num_a, den, num_b, den)
m, h = ci_by_hand([0.1, -0.1, 0.0])                        # 0 ± 4.302653 · 0.1 / √3
check(ch.seeds == [1, 2, 3] and close(ch.dist.mean, 0.0, 1e-12)
      and close(ch.dist.half_width, h, 1e-6) and stats.direction(ch) == 0,
      f"ratio change 0.1, −0.1, 0: mean 0 ± {h:.6f}, no significant change")
den4 = {1: 1.0, 2: 2.0, 3: 4.0, 4: 8.0, 5: 3.0}
diffs = [-0.05, -0.04, -0.06, -0.05]
num_a4 = {s: 0.9 * den4[s] for s in den4}
num_b4 = {s: (0.9 + d) * den4[s] for s, d in zip((1, 2, 3, 4), diffs)}   # no seed 5
ch = B.ratio_change(num_a4, den4, num_b4, den4)
m, h = ci_by_hand(diffs)                                  # −0.05 ± 3.182446 · 0.0081650 / 2
check(ch.seeds == [1, 2, 3, 4] and close(ch.dist.mean, -0.05, 1e-12)
      and close(ch.dist.half_width, h, 1e-6) and stats.direction(ch) == -1,
      f"ratio change over the seeds all four have: −0.05 ± {h:.6f}, CI below 0")

# --- answer_change and verdict_tally.
cheap = stats.paired_ratio({1: 8.0, 2: 8.1, 3: 7.9}, {1: 10.0, 2: 10.0, 3: 10.0})
around = stats.paired_ratio({1: 9.0, 2: 11.0, 3: 10.0}, {1: 10.0, 2: 10.0, 3: 10.0})
check(B.answer_change(cheap, around) == (stats.CHEAPER, stats.NO_DIFF, True),
      "verdict changes: cheaper → no significant difference")
check(B.answer_change(cheap, cheap)[2] is False, "the same verdict: no change")
one_a = stats.paired_ratio({None: 0.97}, {None: 1.0})
one_b = stats.paired_ratio({None: 1.01}, {None: 1.0})
check(B.answer_change(one_a, one_b) == (stats.CHEAPER, stats.DEARER, True),
      "deterministic runs: the ratio decides (0.97 cheaper, 1.01 dearer)")
check(B.answer_change(cheap, stats.paired_ratio({}, {}))[2] is None,
      "nothing measured on one side: no verdict on a change")
check(B.verdict_tally([cheap, around, one_a, stats.paired_ratio({}, {})])
      == {stats.CHEAPER: 2, stats.NO_DIFF: 1}, "tally of verdicts, unmeasured left out")
check(B.distinct(["europa", [0, 0, -1.0], "europa", "earth", [0, 0, -1.0]])
      == ["europa", [0, 0, -1.0], "earth"], "distinct values in order, lists allowed")

# --- command_activity: Σ|T| = 2, 4, 4 at t = 0, 1, 2 → ∫ = 3 + 4 = 7 (trapezoids); jumps
# |3 − 1| + |1 − (−1)| = 4.
check(B.command_activity([0.0, 1.0, 2.0], [[1.0, -1.0], [3.0, -1.0], [3.0, 1.0]]) == (7.0, 4.0)
      and B.command_activity([0.0], [[5.0, 5.0]]) == (0.0, 0.0),
      "command activity: impulse ∫Σ|T| dt = 7 N·s, total variation 4 N; one sample: 0")


# --- the section on synthetic campaigns.
def write_campaign(root, name, runs):
    """runs: [(overrides {key: TOML text}, energy, ε, attitude error, {other summary keys})]
    → plan.json and a shuffled results.json."""
    d = os.path.join(root, name)
    os.makedirs(os.path.join(d, "runs"))
    plan, rows = [], []
    for i, (ovr, en, err, att, extra) in enumerate(runs):
        rid = f"r{i}"
        plan.append({"id": rid, "overrides": [f"{k}={v}" for k, v in ovr.items()]})
        rows.append(dict(extra, id=rid, status="finished", thruster_energy_J=en,
                         mean_ee_error_m=err, max_attitude_error_rad=att))
    random.Random(3).shuffle(rows)
    json.dump(dict(TABLE_ID, name=name, runs=plan), open(os.path.join(d, "plan.json"), "w"))
    json.dump(dict(TABLE_ID, name=name, runs=rows), open(os.path.join(d, "results.json"), "w"))


SEEDS = range(1, 6)
ALLOC = {"pseudoinverse": 1.0, "min_power": 0.9}   # min_power saves exactly 10 % of E_el
BARY_FACTOR = {'"europa"': 0.8, '"earth"': 1.1}    # E(VII)/E(IV) per gravity


def cost_keys(a, s, pot, share, scale=1.0, unsolved=0):
    """The allocation-cost keys of one run's summary [N^1.5·s]: the pseudoinverse thrusts'
    cost C_P = 1000 + 10·s (× scale in a min_power run, whose commanded wrenches differ), the
    optimum's C_P·(1 − pot); a pseudoinverse run commands P (C_cmd = C_P), a min_power run
    realises `share` of the potential (C_cmd = C_P·(1 − share·pot))."""
    cp = (1000.0 + 10.0 * (s or 0)) * (1.0 if a == "pseudoinverse" else scale)
    copt = cp * (1.0 - pot)
    ccmd = cp if a == "pseudoinverse" else cp * (1.0 - share * pot)
    return {"alloc_cost_pinv": cp, "alloc_cost_optimal": copt, "alloc_cost_commanded": ccmd,
            "alloc_static_potential": 1.0 - copt / cp, "alloc_realised_saving": 1.0 - ccmd / cp,
            "alloc_potential_unsolved_ticks": unsolved}


# Gravity: static potential 2 % at Europa, realised 90 % of it (met); 1.5 % at Earth, realised
# 50 % (not met). Experiment 1: potential 0.4 % + 0.02 % per seed, min_power's wrenches cost
# 0.1 % more and it realises 95 % of its potential in the run (criterion n/a below 1 %).
GRAV_POT = {'"europa"': (0.02, 0.9), '"earth"': (0.015, 0.5)}
EXP1_SCALE, EXP1_SHARE = 1.001, 0.95


def exp1_pot(s):
    return 0.004 + 0.0002 * (s or 0)


# Experiment 1, min_power against the pseudoinverse: attitude-error ratio per seed (stagnant:
# 1.05), ε ratio 1.0 in case IV and 1.2 in case VII (fails the 1.1 criterion).
ATT_RATIO = {None: 1.05, 1: 0.96, 2: 0.98, 3: 1.0, 4: 1.02, 5: 1.04}
ERR_RATIO = {"IV": 1.0, "VII": 1.2}


def gravity_runs():
    out = []
    for gv, fac in BARY_FACTOR.items():
        for case in ("IV", "VII"):
            for p in (0.0, 10.0):
                for a, af in ALLOC.items():
                    for s in SEEDS:
                        e_iv = 100.0 + 7.0 * s + p
                        en = e_iv * (fac if case == "VII" else 1.0) * af
                        out.append(({"environment.gravity_m_s2": gv, "control.case": f'"{case}"',
                                     "payload.mass_kg": p, "environment.trim_payload_kg": p,
                                     "thrusters.allocation": f'"{a}"', "run.seed": s},
                                    en, 0.001 * s, 0.002, cost_keys(a, s, *GRAV_POT[gv])))
    return out


def allocation_runs():
    out = []
    for case in ("IV", "VII"):
        for unst in (False, True):
            for a, af in ALLOC.items():
                for s in (SEEDS if unst else [None]):
                    ovr = {"control.case": f'"{case}"',
                           "environment.unsteady_flow.enabled": str(unst).lower(),
                           "environment.density_error": str(unst).lower(),
                           "thrusters.allocation": f'"{a}"', "control.feedforward_lead": "true"}
                    if s is not None:
                        ovr["run.seed"] = s
                    en = (50.0 + (s or 0)) * (0.75 if case == "VII" else 1.0) * af
                    mp = a == "min_power"
                    out.append((ovr, en, 0.003 * (ERR_RATIO[case] if mp else 1.0),
                                0.001 * (ATT_RATIO[s] if mp else 1.0),
                                cost_keys(a, s, exp1_pot(s), EXP1_SHARE, EXP1_SCALE,
                                          1 if mp and s == 2 else 0)))
    return out


LEAD_CHAIN = {"thrusters.ka_1_s": 5.0, "thrusters.kb_1_s": 5.0,
              "thrusters.viscous_friction_Nm_s": 0.01, "thrusters.rotor_inertia_kg_m2": 0.01}


def lead_runs():
    """The lead cuts ε to a quarter and the attitude error to a tenth in every run; energy
    unchanged. Stagnant: ε 1.0 mm with the lead (Earth's target, not Europa's 0.3 mm)."""
    out = []
    for gv in ('"europa"', '"earth"'):
        for case in ("IV", "VII"):
            for unst in (False, True):
                for lead in (False, True):
                    for a in ALLOC:
                        for s in (SEEDS if unst else [None]):
                            ovr = dict(LEAD_CHAIN, **{
                                "environment.gravity_m_s2": gv, "control.case": f'"{case}"',
                                "environment.unsteady_flow.enabled": str(unst).lower(),
                                "control.feedforward_lead": str(lead).lower(),
                                "thrusters.allocation": f'"{a}"'})
                            if s is not None:
                                ovr["run.seed"] = s
                            err = (0.004 + 0.001 * (s or 0)) * (0.25 if lead else 1.0)
                            att = 0.01 * (0.1 if lead else 1.0)
                            out.append((ovr, 100.0 + (s or 0), err, att,
                                        cost_keys(a, s, 0.005, 1.0)))
    return out


def bluerov2_runs():
    """The second vehicle: E_p(VII)/E_p(IV) = 0.9 in every unsteady seed (cheaper), 1.02 in the
    stagnant run (dearer); E_el = 3·E_p; static potential 0.05 % in every run."""
    out = []
    for case in ("IV", "VII"):
        for unst in (False, True):
            for a in ALLOC:
                for s in (SEEDS if unst else [None]):
                    ovr = {"control.case": f'"{case}"', "thrusters.allocation": f'"{a}"',
                           "environment.unsteady_flow.enabled": str(unst).lower(),
                           "environment.gravity_m_s2": '"earth"'}
                    if s is not None:
                        ovr["run.seed"] = s
                    ep = (40.0 + (s or 0)) * ((0.9 if unst else 1.02) if case == "VII" else 1.0)
                    out.append((ovr, 3.0 * ep, 0.002, 0.05,
                                dict(cost_keys(a, s, 0.0005, 1.0), propulsive_energy_J=ep,
                                     max_vehicle_excursion_m=0.01, task_error_final_m=0.001)))
    return out


def table_rows(md, first_cells):
    """Table lines of the section starting with the given cells."""
    head = "| " + " | ".join(first_cells) + " |"
    return [ln for ln in md if ln.startswith(head)]


def table_after(md, header_start):
    """The rows of the first table whose header line starts with header_start."""
    for i, ln in enumerate(md):
        if ln.startswith(header_start):
            rows = []
            for r in md[i + 2:]:
                if not r.startswith("|"):
                    break
                rows.append(r)
            return rows
    return []


def cells_of(row):
    """The cells of a Markdown table row."""
    return [c.strip() for c in row.strip().strip("|").split(" | ")]


def pm(m, h, nd, scale=1.0):
    """'mean ± half-width' as the report prints it, from a hand computation."""
    return f"{m * scale:.{nd}f} ± {h * scale:.{nd}f}"


def ci_text(m, h, nd, scale=1.0):
    return f"[{(m - h) * scale:.{nd}f}, {(m + h) * scale:.{nd}f}]"


def log_ci_by_hand(ratios):
    """(geometric mean, lo, hi) of per-seed ratios: exp(mean ± t·sd/√n) of their logs."""
    m, h = ci_by_hand([math.log(r) for r in ratios])
    return math.exp(m), math.exp(m - h), math.exp(m + h)


tmp = tempfile.mkdtemp(prefix="uvms-report-beyond-")
try:
    root = os.path.join(tmp, "root")
    write_campaign(root, "beyond_gravity", gravity_runs())
    write_campaign(root, "beyond_allocation", allocation_runs())
    write_campaign(root, "beyond_lead", lead_runs())
    write_campaign(root, "beyond_bluerov2", bluerov2_runs())
    rep = Report(root, os.path.join(tmp, "out"), SCHEMA)
    md = text_beyond.section(rep)
    text = "\n".join(md)
    check(md[0] == text_beyond.TITLE and "Not found" not in text, "section with both campaigns")
    # The second vehicle: the paper's question per flow, allocator and energy.
    check("### A second vehicle: BlueROV2 Heavy + Reach Alpha 5" in text, "second vehicle's section")
    rows = table_rows(md, ["Earth", "unsteady", "pseudoinverse", "E_p"])
    check(len(rows) == 1 and "| 0.9000 ± 0.0000 |" in rows[0] and "| 5 of 5 | cheaper |" in rows[0],
          f"BlueROV2 unsteady: VII/IV = 0.9 in 5 of 5 seeds, cheaper ({rows[:1]})")
    rows = table_rows(md, ["Earth", "stagnant", "min_power", "E_el"])
    check(len(rows) == 1 and "| 1.0200 |" in rows[0] and "| 0 of 1 | dearer |" in rows[0],
          f"BlueROV2 stagnant: one run, 1.02, dearer ({rows[:1]})")
    rows = table_rows(md, ["`beyond_bluerov2`", "BlueROV2 Heavy + Reach Alpha 5"])
    check(len(rows) == 1 and rows[0].endswith("| 12 | 0.05 | 0.05 |"),
          f"static potential of the second vehicle's 12 pseudoinverse runs: 0.05 % ({rows[:1]})")
    rows = table_rows(md, ["`beyond_allocation`", "the paper's (SPEC §3)"])
    check(len(rows) == 1, f"the paper vehicle's static potential per campaign ({rows[:1]})")
    # Europa: VII/IV = 0.8 in every seed, both allocators → cheaper in 5 of 5, saving 20 %.
    rows = table_rows(md, ["Europa", "10", "pseudoinverse"])
    check(len(rows) == 1 and "| 0.800 ± 0.000 |" in rows[0] and "| 5 of 5 | cheaper |" in rows[0]
          and "| 20.0 ± 0.0 |" in rows[0], f"europa 10 kg: ratio 0.8, cheaper ({rows[:1]})")
    rows = table_rows(md, ["Earth", "0", "min_power"])
    check(len(rows) == 1 and "| 1.100 ± 0.000 |" in rows[0] and "| 0 of 5 | dearer |" in rows[0],
          f"earth 0 kg: ratio 1.1, dearer ({rows[:1]})")
    check("barycenter cheaper at 0 of 2 payloads" in text
          and "barycenter cheaper at 2 of 2 payloads" in text, "the answer per gravity")
    check("min_abs" not in text and "Σ|T| " not in text and "LP" not in text,
          "no text of the retired allocation mode")
    # The allocator saves exactly 10 % of E_el in every condition: gravity and experiment 1.
    en_g = table_after(md, "| gravity | m_P [kg] | case | n | E_el pseudoinverse [kJ]")
    rows = table_rows(en_g, ["Earth", "10", "VII"])
    check(len(rows) == 1 and "| 10.00 ± 0.00 |" in rows[0] and "| 5 of 5 |" in rows[0],
          f"gravity: min_power's E_el saving 10 % in 5 of 5 seeds ({rows[:1]})")
    en_1 = table_after(md, "| case | condition | n | E_el pseudoinverse [J]")
    rows = table_rows(en_1, ["IV", "(a) stagnant flow, no density error"])
    check(len(rows) == 1 and "| 10.00 |" in rows[0] and "| 1 of 1 |" in rows[0],
          f"experiment 1 stagnant: one deterministic run, E_el saving 10 % ({rows[:1]})")
    rows = table_rows(md, ["(b) unsteady flow + density error", "VII / IV"])
    check(len(rows) == 1 and rows[0].count("0.750 ± 0.000") == 2 and "| no |" in rows[0],
          f"experiment 1: the allocator leaves VII/IV at 0.75, answer unchanged ({rows[:1]})")
    check("changes in 0 of" in text, "no verdict changes when the saving is the same for both")
    check("differs from experiment 1 by the feedforward lead" in text
          and "bit for bit" not in text,
          "the pseudoinverse half of beyond_allocation: experiment 1 plus the lead")

    # Experiment 1, closed loop: ratios min_power/pinv with their log-scale CI, pass/fail 1.1.
    UNST, STAG = "(b) unsteady flow + density error", "(a) stagnant flow, no density error"
    err_1 = table_after(md, "| case | condition | n | max att. error pseudoinverse [mrad]")
    gm, lo, hi = log_ci_by_hand([ATT_RATIO[s] for s in SEEDS])
    rows = table_rows(err_1, ["IV", UNST])
    c = cells_of(rows[0]) if len(rows) == 1 else []
    ma, ha = ci_by_hand([ATT_RATIO[s] for s in SEEDS])   # min_power's att. error / 1 mrad
    want = ["5", "1.00 ± 0.00", pm(ma, ha, 2), pm(gm, 0.5 * (hi - lo), 3),
            f"[{lo:.3f}, {hi:.3f}]", "pass", "3.000 ± 0.000", "3.000 ± 0.000", "1.000 ± 0.000",
            "[1.000, 1.000]", "pass"]
    check(c[2:] == want and hi <= 1.1,
          f"experiment 1 IV unsteady: attitude ratio {gm:.4f} [{lo:.4f}, {hi:.4f}] ≤ 1.1, "
          f"ε ratio 1 ({c} vs {want})")
    rows = table_rows(err_1, ["VII", STAG])
    c = cells_of(rows[0]) if len(rows) == 1 else []
    check(len(c) == 13 and c[2] == "1" and c[5] == "1.050" and c[6] == "—" and c[7] == "pass"
          and c[10] == "1.200" and c[12] == "fail",
          f"experiment 1 VII stagnant (one run): attitude ratio 1.05 passes, ε ratio 1.2 "
          f"fails ({c})")
    check("within 1.1× the pseudoinverse's in 1 of 2 conditions (fail in 1" in text,
          "summary: one of the two cases fails the error criterion")

    # Experiment 1, the cost Σ|T|^1.5: potential, realised (paired and in the run), share.
    cost_1 = table_after(md, "| case | condition | n | static potential [%]")
    runs = {(a, s): cost_keys(a, s, exp1_pot(s), EXP1_SHARE, EXP1_SCALE) for a in ALLOC
            for s in SEEDS}
    pots = [runs[("pseudoinverse", s)]["alloc_static_potential"] for s in SEEDS]
    real = [1.0 - runs[("min_power", s)]["alloc_cost_commanded"]
            / runs[("pseudoinverse", s)]["alloc_cost_commanded"] for s in SEEDS]
    inrun = [runs[("min_power", s)]["alloc_realised_saving"] for s in SEEDS]
    # The share: each min_power run's realised saving over its own static potential, averaged.
    share_1 = sum(runs[("min_power", s)]["alloc_realised_saving"]
                  / runs[("min_power", s)]["alloc_static_potential"] for s in SEEDS) / len(SEEDS)
    (mp_, hp), (mr, hr), (mi, hi_) = ci_by_hand(pots), ci_by_hand(real), ci_by_hand(inrun)
    rows = table_rows(cost_1, ["IV", UNST])
    c = cells_of(rows[0]) if len(rows) == 1 else []
    want = ["5", pm(mp_, hp, 3, 100), ci_text(mp_, hp, 3, 100), pm(mr, hr, 3, 100),
            ci_text(mr, hr, 3, 100), pm(mi, hi_, 3, 100), f"{100 * share_1:.1f}",
            "n/a (potential < 1 %)", "1"]
    check(c[2:] == want, f"experiment 1 IV unsteady: potential {100 * mp_:.4f} %, realised "
          f"{100 * mr:.4f} % paired, {100 * mi:.4f} % in the run, share "
          f"{100 * share_1:.1f} %, n/a below 1 %, 1 unsolved tick ({c} vs {want})")
    stag = {a: cost_keys(a, None, exp1_pot(None), EXP1_SHARE, EXP1_SCALE) for a in ALLOC}
    r0 = 1.0 - stag["min_power"]["alloc_cost_commanded"] / stag["pseudoinverse"][
        "alloc_cost_commanded"]
    rows = table_rows(cost_1, ["VII", STAG])
    c = cells_of(rows[0]) if len(rows) == 1 else []
    want = ["1", "0.400", "—", f"{100 * r0:.3f}", "—",
            f"{100 * stag['min_power']['alloc_realised_saving']:.3f}",
            f"{100 * stag['min_power']['alloc_realised_saving'] / stag['min_power']['alloc_static_potential']:.1f}",
            "n/a (potential < 1 %)", "0"]
    check(c[2:] == want, f"experiment 1 VII stagnant (one run): potential 0.4 % ({c} vs {want})")
    check("energy lever in experiment 1 with the lead?** No." in text
          and "null space is two-dimensional" in text
          and "below 1 % in all 4 conditions measured (at most "
              f"{100 * max(sum(pots) / len(pots), exp1_pot(None)):.3f} %)" in text,
          "experiment 1: the potential is below 1 % everywhere, said so")

    # Gravity: potential 2 % realised 90 % (met) at Europa, 1.5 % realised 50 % (not met).
    cost_g = table_after(md, "| gravity | m_P [kg] | case | n | static potential [%]")
    for gl, gv, crit in (("Europa", '"europa"', "met"), ("Earth", '"earth"', "not met")):
        pot, share = GRAV_POT[gv]
        rs = {a: {s: cost_keys(a, s, pot, share) for s in SEEDS} for a in ALLOC}
        real = [1.0 - rs["min_power"][s]["alloc_cost_commanded"]
                / rs["pseudoinverse"][s]["alloc_cost_commanded"] for s in SEEDS]
        mr, hr = ci_by_hand(real)
        mp_ = sum(rs["pseudoinverse"][s]["alloc_static_potential"] for s in SEEDS) / len(SEEDS)
        sh = sum(rs["min_power"][s]["alloc_realised_saving"]
                 / rs["min_power"][s]["alloc_static_potential"] for s in SEEDS) / len(SEEDS)
        rows = table_rows(cost_g, [gl, "10", "IV"])
        c = cells_of(rows[0]) if len(rows) == 1 else []
        check(len(c) == 12 and c[4] == f"{100 * mp_:.3f} ± 0.000"
              and c[6] == pm(mr, abs(hr), 3, 100) and c[9] == f"{100 * sh:.1f}"
              and c[10] == crit and c[11] == "0",
              f"gravity {gl} 10 kg IV: potential {100 * pot:g} %, share "
              f"{100 * sh:.1f} % → {crit} ({c})")
    check("- **Static potential in the gravity campaign**: ≥ 1 % in 8 of 8 conditions (at most "
          "2.000 %); there the realised saving reaches ≥ 80 % of the potential in 4 of 8."
          in text,
          "gravity: potential ≥ 1 % everywhere, criterion met at Europa only")
    # The lead: ε on/off 0.25 and E_el on/off 1 in every seed; the stagnant targets.
    lead_md = md[:md.index("### A second vehicle: BlueROV2 Heavy + Reach Alpha 5")]
    rows = table_rows(lead_md, ["Earth", "IV", "unsteady", "pseudoinverse"])
    check(len(rows) == 1 and "| 0.250 ± 0.000 |" in rows[0] and "| 1.0000 ± 0.0000 |" in rows[0]
          and "| 10.00 ± 0.00 | 1.00 ± 0.00 |" in rows[0],
          f"lead: ε on/off 0.25, E_el unchanged, attitude 10 → 1 mrad ({rows[:1]})")
    # The allocators with the lead off and on: equal errors and energies, potential 0.5 %
    # realised in full (C_cmd of min_power = C_P·(1 − 0.005), C_P the same in both runs).
    al = table_after(md, "| gravity | case | flow | lead | n | att. ratio min_power/pinv")
    rows = table_rows(al, ["Earth", "IV", "unsteady", "on"])
    c = cells_of(rows[0]) if len(rows) == 1 else []
    real = [1.0 - cost_keys("min_power", s, 0.005, 1.0)["alloc_cost_commanded"]
            / cost_keys("pseudoinverse", s, 0.005, 1.0)["alloc_cost_commanded"] for s in SEEDS]
    mr, hr = ci_by_hand(real)
    want = ["5", "1.000 ± 0.000", "pass", "1.000 ± 0.000", "pass", "0.00 ± 0.00",
            "0.500 ± 0.000", pm(mr, abs(hr), 3, 100), f"{100 * mr / 0.005:.1f}",
            "n/a (potential < 1 %)"]
    check(len(al) == 16 and c[4:] == want,
          f"lead campaign, allocators with the lead on: ({c} vs {want})")
    check("energy lever in the lead campaign?** No." in text
          and "below 1 % in all 16 conditions measured (at most 0.500 %)" in text,
          "lead campaign: the potential is below 1 % everywhere, said so")
    check("τ = (KB + b/J)/(KA·KB) = 0.24 s late" in text, "the chain's lag from the runs' settings")
    check(text.count("**met**") == 2 and text.count("**not met**") == 2
          and "Earth, IV, stagnant, lead on (pseudoinverse): max attitude error 0.0573°" in text,
          "targets (stagnant, lead, pseudoinverse; IV and VII): ε 1.0 mm meets Earth's 1.0 mm, not "
          "Europa's 0.3 mm")
    figs = sorted(os.listdir(os.path.join(tmp, "out", "figures")))
    check(figs == ["beyond_allocation_saving.png", "beyond_gravity_metrics.png",
                   "beyond_gravity_ratio.png", "beyond_lead_metrics.png"],
          f"the section's figures written: {figs}")

    # One campaign missing: noted, its part skipped, the other part still written.
    part = os.path.join(tmp, "part")
    os.makedirs(part)
    os.symlink(os.path.join(root, "beyond_gravity"), os.path.join(part, "beyond_gravity"))
    md = text_beyond.section(Report(part, os.path.join(tmp, "out2"), SCHEMA))
    text = "\n".join(md)
    check("Not found among the campaign outputs: `beyond_allocation`" in text
          and "The paper's experiment 1" not in text and "### The paper's question" in text,
          "a missing campaign is noted and its part skipped")
    os.makedirs(os.path.join(tmp, "empty"))
    md = text_beyond.section(Report(os.path.join(tmp, "empty"), os.path.join(tmp, "out3"), SCHEMA))
    check(len(md) == 6 and "`beyond_gravity`, `beyond_allocation`, `beyond_lead`, `beyond_bluerov2`"
          in "\n".join(md),
          "no campaign at all: only the note")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
