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
  right verdicts, a campaign that is missing is noted and its part skipped.

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
    """runs: [(overrides {key: TOML text}, energy, ε, attitude error)] → plan.json and a
    shuffled results.json."""
    d = os.path.join(root, name)
    os.makedirs(os.path.join(d, "runs"))
    plan, rows = [], []
    for i, (ovr, en, err, att) in enumerate(runs):
        rid = f"r{i}"
        plan.append({"id": rid, "overrides": [f"{k}={v}" for k, v in ovr.items()]})
        rows.append({"id": rid, "status": "finished", "thruster_energy_J": en,
                     "mean_ee_error_m": err, "max_attitude_error_rad": att})
    random.Random(3).shuffle(rows)
    json.dump(dict(TABLE_ID, name=name, runs=plan), open(os.path.join(d, "plan.json"), "w"))
    json.dump(dict(TABLE_ID, name=name, runs=rows), open(os.path.join(d, "results.json"), "w"))


SEEDS = range(1, 6)
ALLOC = {"pseudoinverse": 1.0, "min_abs_thrust": 0.9}   # min_abs saves exactly 10 %
BARY_FACTOR = {'"europa"': 0.8, '"earth"': 1.1}         # E(VII)/E(IV) per gravity


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
                                    en, 0.001 * s, 0.002))
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
                           "thrusters.allocation": f'"{a}"'}
                    if s is not None:
                        ovr["run.seed"] = s
                    en = (50.0 + (s or 0)) * (0.75 if case == "VII" else 1.0) * af
                    out.append((ovr, en, 0.003, 0.001))
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
                            out.append((ovr, 100.0 + (s or 0), err, att))
    return out


def table_rows(md, first_cells):
    """Table lines of the section starting with the given cells."""
    head = "| " + " | ".join(first_cells) + " |"
    return [ln for ln in md if ln.startswith(head)]


tmp = tempfile.mkdtemp(prefix="uvms-report-beyond-")
try:
    root = os.path.join(tmp, "root")
    write_campaign(root, "beyond_gravity", gravity_runs())
    write_campaign(root, "beyond_allocation", allocation_runs())
    write_campaign(root, "beyond_lead", lead_runs())
    rep = Report(root, os.path.join(tmp, "out"), SCHEMA)
    md = text_beyond.section(rep)
    text = "\n".join(md)
    check(md[0] == text_beyond.TITLE and "Not found" not in text, "section with both campaigns")
    # Europa: VII/IV = 0.8 in every seed, both allocators → cheaper in 5 of 5, saving 20 %.
    rows = table_rows(md, ["Europa", "10", "pseudoinverse"])
    check(len(rows) == 1 and "| 0.800 ± 0.000 |" in rows[0] and "| 5 of 5 | cheaper |" in rows[0]
          and "| 20.0 ± 0.0 |" in rows[0], f"europa 10 kg: ratio 0.8, cheaper ({rows[:1]})")
    rows = table_rows(md, ["Earth", "0", "min_abs_thrust"])
    check(len(rows) == 1 and "| 1.100 ± 0.000 |" in rows[0] and "| 0 of 5 | dearer |" in rows[0],
          f"earth 0 kg: ratio 1.1, dearer ({rows[:1]})")
    check("barycenter cheaper at 0 of 2 payloads" in text
          and "barycenter cheaper at 2 of 2 payloads" in text, "the answer per gravity")
    # The allocator saves exactly 10 % in every condition: gravity and experiment 1 tables.
    rows = [r for r in table_rows(md, ["Earth", "10", "VII"]) if " of " in r]  # not the metrics
    check(len(rows) == 1 and "| 10.00 ± 0.00 |" in rows[0] and "| 5 of 5 |" in rows[0],
          f"gravity: min_abs saving 10 % in 5 of 5 seeds ({rows[:1]})")
    rows = table_rows(md, ["IV", "(a) stagnant flow, no density error"])
    check(len(rows) == 1 and "| 10.00 |" in rows[0] and "| 1 of 1 |" in rows[0],
          f"experiment 1 stagnant: one deterministic run, saving 10 % ({rows[:1]})")
    rows = table_rows(md, ["(b) unsteady flow + density error", "VII / IV"])
    check(len(rows) == 1 and rows[0].count("0.750 ± 0.000") == 2 and "| no |" in rows[0],
          f"experiment 1: the allocator leaves VII/IV at 0.75, answer unchanged ({rows[:1]})")
    check("changes in 0 of" in text, "no verdict changes when the saving is the same for both")
    # The lead: ε on/off 0.25 and E_el on/off 1 in every seed; the stagnant targets.
    rows = table_rows(md, ["Earth", "IV", "unsteady", "pseudoinverse"])
    check(len(rows) == 1 and "| 0.250 ± 0.000 |" in rows[0] and "| 1.0000 ± 0.0000 |" in rows[0]
          and "| 10.00 ± 0.00 | 1.00 ± 0.00 |" in rows[0],
          f"lead: ε on/off 0.25, E_el unchanged, attitude 10 → 1 mrad ({rows[:1]})")
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
    check(len(md) == 6 and "`beyond_gravity`, `beyond_allocation`, `beyond_lead`" in "\n".join(md),
          "no campaign at all: only the note")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
