# SPDX-License-Identifier: Apache-2.0
"""The report's statistics and rules on synthetic data with known answers (no runs needed):

- report/analyses/stats.py: Student t quantiles against tabulated values, mean and 95 % CI against
  hand-derived ones, paired ratios and the count of seeds below 1, pooled savings, the
  cheaper/dearer verdict, the scorecard's verdict rule, the impulse integral;
- tools/analytic.py like_for_like and report/analyses/exp8b.py analyse: closed-form
  impulses, and the like-for-like ratio recovered from synthetic thrust signals;
- report/analyses/paper.py: the paper's savings recomputed from its own tables; payload
  trends of seeded series from paired differences;
- stats.py paired differences and their direction; the first crossing of a level,
  interpolated, on a second-order step with a known crossing;
- report (load, context, headline): grouping runs by override values (seeds pooled, ids
  ignored; keys a run does not set take the schema's default) for both results.json forms;
  duplicate (condition, seed) slots raise and failed runs are counted; headline comparisons of
  one configuration in several campaigns counted once; the thruster step response of both
  drives, its 63 % times against the closed form.

The configuration schema is tests/tools/data/schema_small.json (the format of
`uvms scenario schema`).

Usage: test_report_stats.py SOURCE_DIR
"""
import json
import math
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.join(sys.argv[1], "tools"))
import numpy as np  # noqa: E402
from scipy.stats import t as scipy_t  # noqa: E402

from uvms_tools.models import analytic  # noqa: E402
from uvms_tools.report import keys as K  # noqa: E402
from uvms_tools.report.analyses import exp8b as report_exp8b  # noqa: E402
from uvms_tools.report.analyses import paper as P  # noqa: E402
from uvms_tools.report.analyses import stats  # noqa: E402
from uvms_tools.report.analyses.headline import dedupe_comparisons  # noqa: E402
from uvms_tools.report.analyses.motor import motor_step  # noqa: E402
from uvms_tools.report.context import Report  # noqa: E402
from uvms_tools.report.load import schema as schema_mod  # noqa: E402
from uvms_tools.report.load.paths import disp_path  # noqa: E402
from uvms_tools.report.load.runs import AmbiguousCondition, Experiment, TableError  # noqa: E402
from uvms_tools.report.load.runs import discover  # noqa: E402
from uvms_tools.report.text import headline  # noqa: E402
from uvms_tools.report.text.fmt import fmt_dist, fmt_n  # noqa: E402
from report_testkit import write_campaign  # noqa: E402

SCHEMA = schema_mod.from_file(os.path.join(sys.argv[1], "tests", "tools", "data",
                                           "schema_small.json"))
DEFAULTS = SCHEMA.defaults()

failures = []


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


def close(a, b, tol):
    return abs(a - b) <= tol


# --- Student t quantiles: tabulated values (6 decimals, e.g. NIST/SEMATECH t table).
T_TABLE = [(0.975, 19, 2.093024), (0.975, 9, 2.262157), (0.975, 1, 12.706205),
           (0.975, 2, 4.302653), (0.975, 4, 2.776445), (0.975, 29, 2.045230),
           (0.975, 59, 2.000995), (0.995, 10, 3.169273), (0.95, 5, 2.015048),
           (0.90, 3, 1.637744)]
for p, dof, ref in T_TABLE:
    q = stats.t_quantile(p, dof)
    check(close(q, ref, 1e-6), f"t_{{{p},{dof}}} = {q:.7f} (table {ref})")
    check(close(stats.t_quantile(1 - p, dof), -ref, 1e-6), f"t_{{{1 - p:.3f},{dof}}} = −{ref}")
    check(close(stats.t_cdf(q, dof), p, 1e-12), f"t_cdf(t_quantile({p}, {dof})) = {p}")
check(close(stats.t_quantile(0.975, 1e9), 1.959964, 1e-6), "t → normal quantile for large dof")
check(stats.t_quantile(0.5, 7) == 0.0, "median of t is 0")
# Regularized incomplete beta: closed forms.
check(close(stats.betainc(3.5, 3.5, 0.5), 0.5, 1e-14), "I_0.5(a, a) = 1/2")
check(close(stats.betainc(1.0, 1.0, 0.3), 0.3, 1e-14), "I_x(1, 1) = x")
check(close(stats.betainc(2.5, 1.0, 0.7), 0.7 ** 2.5, 1e-13), "I_x(a, 1) = x^a")
check(close(stats.betainc(1.0, 3.0, 0.2), 1 - 0.8 ** 3, 1e-13), "I_x(1, b) = 1 − (1 − x)^b")

# --- describe: hand-derived mean and CI.
d = stats.describe([1, 2, 3, 4, 5])
half = 2.776445 * math.sqrt(2.5) / math.sqrt(5)  # t_{0.975,4}·s/√n, s² = 2.5
check(d.n == 5 and d.mean == 3.0 and close(d.sd, math.sqrt(2.5), 1e-15),
      f"describe([1..5]): n 5, mean 3, sd √2.5 (got {d.n}, {d.mean}, {d.sd})")
check(close(d.lo, 3 - half, 1e-6) and close(d.hi, 3 + half, 1e-6),
      f"95 % CI of [1..5] = 3 ± {half:.6f} (got [{d.lo:.6f}, {d.hi:.6f}])")
d20 = stats.describe(list(range(1, 21)))
half20 = 2.093024 * math.sqrt(35.0) / math.sqrt(20)  # s² of 1..20 = 35
check(close(d20.mean, 10.5, 1e-15) and close(d20.half_width, half20, 1e-5),
      f"95 % CI of 1..20 = 10.5 ± {half20:.6f} (got ± {d20.half_width:.6f})")
check(d20.min == 1 and d20.max == 20, "min/max")
d10 = stats.describe([0.5 * k for k in range(10)])  # 0 .. 4.5, s² = 0.25·55/6
half10 = 2.262157 * math.sqrt(0.25 * 55 / 6) / math.sqrt(10)
check(close(d10.half_width, half10, 1e-6), f"95 % CI, n = 10: ± {half10:.6f}")
d1 = stats.describe([0.7])
check(d1.n == 1 and d1.mean == 0.7 and not d1.has_ci, "one value: no interval")
d0 = stats.describe([float("nan"), None])
check(d0.n == 0 and not d0.has_ci, "non-finite values dropped; empty sample")
dc = stats.describe([2.0] * 20)
check(dc.lo == dc.hi == 2.0, "constant sample: zero-width interval")

# --- paired ratios and counting.
num = {1: 0.9, 2: 1.1, 3: 0.8, 4: 1.0, 6: 2.0}
den = {1: 1.0, 2: 1.0, 3: 1.0, 4: 1.0, 5: 1.0, 6: 0.0}
pa = stats.paired_ratio(num, den)
check(pa.seeds == [1, 2, 3, 4], f"common seeds with a non-zero denominator (got {pa.seeds})")
check(pa.n_below_1 == 2, "ratio < 1 in 2 seeds (a ratio of exactly 1 is not counted)")
gm = (0.9 * 1.1 * 0.8 * 1.0) ** 0.25
check(close(pa.dist.mean, gm, 1e-14), f"geometric mean of the paired ratios ({pa.dist.mean})")
_l = [math.log(r) for r in (0.9, 1.1, 0.8, 1.0)]
_lm = sum(_l) / 4
_half = scipy_t.ppf(0.975, 3) * math.sqrt(sum((x - _lm) ** 2 for x in _l) / 3) / 2
check(close(pa.dist.lo, math.exp(_lm - _half), 1e-9) and close(pa.dist.hi, math.exp(_lm + _half),
                                                                  1e-9),
      f"the ratio's CI is scipy's t interval on the log scale, back-transformed "
      f"([{pa.dist.lo:.6f}, {pa.dist.hi:.6f}])")
check(stats.paired_ratio({1: -1.0, 2: 1.0}, {1: 1.0, 2: 1.0}).dist.mean == 0.0,
      "a negative ratio: no log scale, the arithmetic mean")
pa1 = stats.paired_ratio({None: 3.0}, {None: 4.0})
check(pa1.n == 1 and pa1.ratios == [0.75], "unseeded (deterministic) pair")
seeds, ds = stats.pooled_saving([({1: 1.0, 2: 2.0}, {1: 2.0, 2: 2.0}),
                                 ({1: 1.0, 2: 1.0, 3: 9.0}, {1: 2.0, 2: 2.0, 3: 9.0})])
check(seeds == [1, 2] and close(ds.values[0], 0.5, 1e-15) and close(ds.values[1], 0.25, 1e-15),
      "pooled saving per seed 1 − Σnum/Σden over the seeds all pairs have")
# cheaper / dearer / no difference from the ratio's CI.
check(stats.compare(stats.paired_ratio({s: 0.9 + 0.01 * s for s in range(10)},
                                       {s: 1.0 for s in range(10)})) == stats.CHEAPER,
      "CI entirely below 1: cheaper")
check(stats.compare(stats.paired_ratio({s: 0.8 + 0.04 * s for s in range(10)},
                                       {s: 1.0 for s in range(10)})) == stats.NO_DIFF,
      "CI containing 1: no significant difference")
check(stats.compare(stats.paired_ratio({s: 1.2 + 0.01 * s for s in range(10)},
                                       {s: 1.0 for s in range(10)})) == stats.DEARER,
      "CI entirely above 1: dearer")
check(stats.compare(pa1) == stats.CHEAPER and stats.compare(stats.describe([1.1])) == stats.DEARER,
      "deterministic ratio decides alone")
check(stats.compare(stats.describe([])) is None, "nothing measured: no verdict")

# --- the scorecard's verdict rule (stats.RULE_TEXT).
V = stats.scorecard_verdict
R, S, D, N = stats.REPRODUCED, stats.SAME_DIRECTION, stats.DIFFERS, stats.NOT_MEASURED
cases = [
    (dict(paper=0.574, mean=0.60), R, "ratio within ±0.05"),
    (dict(paper=0.574, mean=0.6239), R, "ratio just inside the tolerance"),
    (dict(paper=0.574, mean=0.6241), S, "ratio just outside the tolerance"),
    (dict(paper=0.574, mean=0.676), S, "ratio off but both below 1"),
    (dict(paper=0.574, mean=1.05), D, "ratio on the other side of 1"),
    (dict(paper=0.574, mean=0.70, lo=0.55, hi=0.85), R, "paper inside our CI"),
    (dict(paper=0.574, mean=0.90, lo=0.85, hi=0.95), S, "CI below 1, paper outside"),
    (dict(paper=0.574, mean=0.99, lo=0.95, hi=1.03), D, "CI straddles 1: not the same side"),
    (dict(paper=1.2, mean=1.6), S, "both above 1"),
    (dict(paper=0.433, mean=0.263, ref=0.0), S, "saving smaller but positive"),
    (dict(paper=0.433, mean=-0.10, ref=0.0), D, "saving of the other sign"),
    (dict(paper=0.433, mean=0.41, ref=0.0), R, "saving within 5 points"),
    (dict(paper=0.3391, mean=727.0, kind="absolute"), D, "absolute ×2000"),
    (dict(paper=0.3391, mean=0.40, kind="absolute"), R, "absolute within ×1.25"),
    (dict(paper=0.3391, mean=0.45, kind="absolute"), D, "absolute ×1.33"),
    (dict(paper=0.3391, mean=0.20, kind="absolute"), D, "absolute ×0.59"),
    (dict(paper=3.32, mean=5.0, lo=3.0, hi=7.0, kind="absolute"), R, "absolute, paper in CI"),
    (dict(paper=0.0, mean=0.0, kind="absolute"), R, "zero and zero"),
    (dict(paper=0.0, mean=1e-3, kind="absolute"), D, "zero vs non-zero"),
    (dict(paper=0.5, mean=float("nan")), N, "nothing measured"),
]
for kw, want, what in cases:
    got = V(**kw)
    check(got == want, f"verdict {what}: {got} (want {want})")
check(stats.statement_verdict(True) == R and stats.statement_verdict("partly") == S
      and stats.statement_verdict(False) == D and stats.statement_verdict(None) == N,
      "statement verdicts")
check(all(w in stats.RULE_TEXT for w in ("Reproduced", "Same direction", "Differs",
                                         "±0.05", "1.25")), "the rule is stated in the report")

# --- the paper's savings recomputed from its own tables (definition check).
s11 = P.paper_saving(P.PAPER_TABLE_XI, K.MATCHED_PAIRS)
s12 = P.paper_saving(P.PAPER_TABLE_XII, K.MATCHED_PAIRS)
s12fb = P.paper_saving(P.PAPER_TABLE_XII, K.FEEDBACK_PAIRS)
check(round(100 * s11, 1) == 43.3, f"Table XI, matched pairs: {100 * s11:.2f} % = the text's 43.3 %")
check(round(100 * s12, 1) == 38.5, f"Table XII, matched pairs: {100 * s12:.2f} % = the text's 38.5 %")
check(round(100 * s12fb, 1) == 37.9, f"Table XII, feedback pairs only: {100 * s12fb:.2f} %")
check(all(abs(v[5] / v[4] - v[6]) < 6e-4 for v in P.PAPER_TABLE_XIII),
      "Table XIII ratios = barycenter / vehicle energy (transcription check)")

# --- the impulse integral on signals with closed-form integrals.
T, A = 60.0, 2.5
t = np.linspace(0.0, T, 20001)
imp = stats.impulse(t, A * np.cos(math.pi * t / T))
check(close(imp, 2 * A * T / math.pi, 1e-7 * A * T),
      f"∫|A cos(πt/T)| dt = 2AT/π: {imp:.9f} vs {2 * A * T / math.pi:.9f}")
vec = np.stack([A * np.cos(3 * t), A * np.sin(3 * t), 0 * t], axis=1)
check(close(stats.impulse(t, vec), A * T, 1e-9), "∫|(A cos, A sin, 0)| dt = A·T")
tt = np.array([0.0, 1.0, 3.0])
check(close(stats.impulse(tt, [1.0, -3.0, 1.0]), 0.5 * (1 + 3) * 1 + 0.5 * (3 + 1) * 2, 1e-15),
      "trapezoid on a non-uniform grid with a sign change in |x|")

# --- analytic.like_for_like: closed forms.
for mp in (1.0, 10.0, 50.0):
    m_a = analytic.added_mass_kg()
    a = analytic.like_for_like(mp, 1.0, 60.0, m_add_kg=0.0)
    check(close(a["barycenter"], a["drag_only"], 1e-6 * a["drag_only"]),
          f"m_P = {mp}: drag-only impulse, numerical vs closed form")
    kappa = mp / analytic.M0_KG
    check(close(a["drag_only"], float(analytic.drag_impulse(kappa, 1.0, 60.0)), 1e-12),
          f"m_P = {mp}: drag impulse = [87] with η → κ = m_P/m0")
    b = analytic.like_for_like(mp, 1.0, 60.0, cd0=0.0, m_add_kg=m_a)
    check(close(b["barycenter"], b["added_mass_only"], 1e-6 * b["added_mass_only"]),
          f"m_P = {mp}: added-mass impulse m_A·κ·r·π/t_F, numerical vs closed form")
    check(close(a["reaction_held"], mp * math.pi / 60.0, 1e-15), "held reaction m_P·r·π/t_F")
check(close(analytic.added_mass_kg(), 0.1 * 1025 * 0.15, 1e-12), "m_A = ρ·V0·0.1 (SPEC §3.3)")

# --- report_exp8b.analyse on synthetic runs whose forces follow the corrected model exactly.
par = dict(rho=1025.0, cd0=1.2, a0_m2=0.5, m0_kg=120.0, m_add_kg=analytic.added_mass_kg(),
           r_delta_m=1.0, t_f_s=60.0)
t = np.linspace(0.0, par["t_f_s"], 6001)
w = math.pi / par["t_f_s"]
runs = {}
for mp in (0.0, 10.0, 50.0):
    kappa = mp / par["m0_kg"]
    acc_p = 0.5 * par["r_delta_m"] * w * w * np.cos(w * t)           # payload, inertial
    f_iv = np.stack([mp * acc_p, 0 * t, 0 * t], axis=1)               # held vehicle
    v0 = -kappa * 0.5 * par["r_delta_m"] * w * np.sin(w * t)
    a0 = -kappa * acc_p
    x0 = -kappa * 0.5 * par["r_delta_m"] * (1 - np.cos(w * t))
    k = 0.5 * par["rho"] * par["cd0"] * par["a0_m2"]
    f_vii = np.stack([par["m_add_kg"] * a0 + k * np.abs(v0) * v0, 0 * t, 0 * t], axis=1)
    runs[("IV", mp)] = dict(t_s=t, thrust_force_N=f_iv, force_des_N=f_iv)
    runs[("VII", mp)] = dict(t_s=t, thrust_force_N=f_vii, force_des_N=f_vii,
                             position_m=np.stack([x0, 0 * t, 0 * t], axis=1))
rows = report_exp8b.analyse(runs, par)
check([r["payload_kg"] for r in rows] == [0.0, 10.0, 50.0], "one row per payload, sorted")
check(math.isnan(rows[0]["ratio_sim"]), "m_P = 0: no reaction, ratio undefined")
for r in rows[1:]:
    pr = r["pred"]
    check(close(r["imp_veh"], pr["reaction_held"], 1e-6 * pr["reaction_held"]),
          f"m_P = {r['payload_kg']}: IV impulse = m_P·r·π/t_F")
    check(close(r["ratio_sim"], pr["ratio"], 1e-5 * pr["ratio"]) and r["agree_pred"],
          f"m_P = {r['payload_kg']}: synthetic ratio {r['ratio_sim']:.6f} = corrected model "
          f"{pr['ratio']:.6f}")
    check(r["agree_89"] is False, f"m_P = {r['payload_kg']}: and not [89] "
          f"({r['ratio_89']:.4f})")
    check(close(r["travel_bary_m"], pr["vehicle_travel_m"], 1e-9), "vehicle travel κ·r measured")
    check(close(r["ratio_des"], r["ratio_sim"], 1e-12), "desired-force ratio from force_des_N")
summ = report_exp8b.summarise(rows)
check(summ["n"] == 2 and summ["agree_pred"] and not summ["agree_89"], "summary verdicts")
# A synthetic system that IS the analytic model ([88]'s reaction m0·η·d̈, [87]'s drag with
# η·d): the comparison must then agree with [89].
runs89 = {}
for mp in (5.0, 20.0):
    eta = mp / (par["m0_kg"] + mp)
    dd = 0.5 * par["r_delta_m"] * w * w * np.cos(w * t)
    v0 = -eta * 0.5 * par["r_delta_m"] * w * np.sin(w * t)
    k = 0.5 * par["rho"] * par["cd0"] * par["a0_m2"]
    runs89[("IV", mp)] = dict(t_s=t, thrust_force_N=par["m0_kg"] * eta * dd)
    runs89[("VII", mp)] = dict(t_s=t, thrust_force_N=k * v0 * v0)
rows89 = report_exp8b.analyse(runs89, par)
check(all(r["agree_89"] and close(r["ratio_sim"], r["ratio_89"], 1e-5) for r in rows89),
      "a system that follows [87–88] agrees with [89]")

# --- runs grouped by override values; both results.json forms.
tmp = tempfile.mkdtemp(prefix="uvms-report-stats-")
try:
    def write_exp(d, wrapped):
        os.makedirs(os.path.join(d, "runs"))
        rows, plan = [], []
        energies = {("IV", None): 10.0, ("VII", None): 7.0}
        for s in range(1, 6):
            energies[("IV", s)] = 10.0 + s
            energies[("VII", s)] = 9.0 + (0.5 if s == 3 else -0.5) * s
        for (case, seed), en in energies.items():
            rid = f"{case}_{'u_s%02d' % seed if seed else 'stag'}"  # ids carry no meaning
            ovr = [f'control.case="{case}"',
                   f"environment.unsteady_flow.enabled={'true' if seed else 'false'}"]
            if seed:
                ovr.append(f"run.seed={seed}")
            plan.append({"id": rid, "overrides": ovr})
            rows.append({"id": rid, "status": "finished", "thruster_energy_J": en})
            os.makedirs(os.path.join(d, "runs", rid))
            with open(os.path.join(d, "runs", rid, "summary.json"), "w") as fh:
                json.dump({"drive": "current", "propulsive_energy_J": en / 1000.0,
                           "provenance": {"git_commit": "abc123"}}, fh)
        with open(os.path.join(d, "plan.json"), "w") as fh:
            json.dump({"name": "exp_test", "runs": plan}, fh)
        res = {"name": "exp_test", "provenance": {"version": "t"}, "runs": rows} if wrapped \
            else rows
        with open(os.path.join(d, "results.json"), "w") as fh:
            json.dump(res, fh)

    for wrapped in (True, False):
        d = os.path.join(tmp, f"w{int(wrapped)}")
        write_exp(d, wrapped)
        with open(os.path.join(d, "results.json")) as fh:
            e = Experiment(d, json.load(fh), DEFAULTS)
        form = "wrapper" if wrapped else "list"
        check(e.name == "exp_test" and len(e.runs) == 12, f"{form}: 12 runs read")
        u = {K.KEY_UNSTEADY: True}
        dv = e.dist("thruster_energy_J", dict(u, **{K.KEY_CASE: "IV"}))
        check(dv.n == 5 and close(dv.mean, 13.0, 1e-12), f"{form}: seeds pooled by overrides")
        ds_ = e.dist("thruster_energy_J", {K.KEY_CASE: "IV", K.KEY_UNSTEADY: False})
        check(ds_.n == 1 and ds_.mean == 10.0, f"{form}: the stagnant run alone")
        pr = e.paired("thruster_energy_J", dict(u, **{K.KEY_CASE: "VII"}),
                      dict(u, **{K.KEY_CASE: "IV"}))
        want = [(9.0 - 0.5 * s if s != 3 else 10.5) / (10.0 + s) for s in range(1, 6)]
        check(pr.n == 5 and all(close(a, b, 1e-15) for a, b in zip(pr.ratios, want))
              and pr.n_below_1 == 5, f"{form}: paired per seed, cheaper in 5 of 5")
        check(e.dist("propulsive_energy_J", dict(u, **{K.KEY_CASE: "IV"})).n == 5,
              f"{form}: summary.json fields merged (propulsive energy)")
        check(all(r.get("drive") == "current" for r in e.runs), f"{form}: drive from summary")
    check(disp_path("/some/where/sil/scenarios/paper/x.toml") ==
          "sil/scenarios/paper/x.toml", "absolute scenario paths shown from sil/")

    # A table is read only beside its own plan: same identity and generation.
    def table_error(d, plan, res):
        os.makedirs(d)
        json.dump(plan, open(os.path.join(d, "plan.json"), "w"))
        json.dump(res, open(os.path.join(d, "results.json"), "w"))
        try:
            discover(d, DEFAULTS)
            return ""
        except TableError as e:
            return str(e)
    ida, idb = "a" * 64, "b" * 64
    check(table_error(os.path.join(tmp, "t_ok"), {"identity": ida, "generation": 1, "runs": []},
                      {"identity": ida, "generation": 1, "runs": []}) == "",
          "a table of its plan's identity and generation is read")
    msg = table_error(os.path.join(tmp, "t_id"), {"identity": idb, "generation": 0, "runs": []},
                      {"identity": ida, "generation": 0, "runs": []})
    check(ida in msg and idb in msg, f"a table of another identity is refused, naming both "
          f"({msg[:90]}...)")
    msg = table_error(os.path.join(tmp, "t_gen"), {"identity": ida, "generation": 1, "runs": []},
                      {"identity": ida, "generation": 0, "runs": []})
    check("generation 0" in msg and "generation 1" in msg,
          "a table of an earlier generation (an interrupted --force-new) is refused")
    check(table_error(os.path.join(tmp, "t_old"), {"runs": []}, []) != "",
          "a table without an identity (an older uvms campaign) is refused")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

# --- the thruster step response of both drives (SPEC §5: ≈ 0.3 s current, ≈ 6 s voltage).
cfg = {k: [v] for k, v in dict(
    motor_resistance_ohm=1.0, motor_inductance_H=1.0, motor_torque_constant_Nm_A=10.0,
    motor_viscous_friction_Nm_s=0.01, rotor_inertia_kg_m2=0.01, speed_gain_1_s=5.0,
    current_gain_1_s=5.0, tick_s=0.03).items()}
ms = motor_step(cfg)
check(0.2 <= ms["tau_current_s"] <= 0.45, f"current drive: 63 % at {ms['tau_current_s']:.2f} s")
check(abs(ms["tau_current_s"] - ms["tau_continuous_s"]) <= 0.06,
      "current drive ≈ the continuous-time law")
check(4.0 <= ms["tau_voltage_s"] <= 8.0, f"voltage drive: 63 % at {ms['tau_voltage_s']:.2f} s")
check(abs(ms["omega_current"][-1] - 1.0) < 1e-6, "current drive settles at ω̂")


# --- first crossing, interpolated (stats.first_crossing): a second-order step with known
# crossing. ω_n = 5 rad/s, ζ = 0.5: y = 1 − e^(−2.5t)(cos 4.330t + 0.5774 sin 4.330t).
def step2(t, wn, zeta):
    wd = wn * math.sqrt(1.0 - zeta * zeta)
    return 1.0 - np.exp(-zeta * wn * t) * (np.cos(wd * t) + zeta * wn / wd * np.sin(wd * t))


def exact_crossing(wn, zeta, level, lo=0.0, hi=1.0):
    for _ in range(200):  # bisection on the closed form (monotone before the first peak)
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if step2(np.array(mid), wn, zeta) < level else (lo, mid)
    return 0.5 * (lo + hi)


LEVEL = 1.0 - math.exp(-1.0)
t_star = exact_crossing(5.0, 0.5, LEVEL)
# 0.30828 s (the rounded coefficients 4.330, 0.5774 give 0.30829 s; y(0.3086) = 0.6329
# already, y(0.33) = 0.663).
check(close(t_star, 0.30828, 1e-5) and close(float(step2(np.array(t_star), 5.0, 0.5)), LEVEL,
                                               1e-12),
      f"ω_n = 5, ζ = 0.5: 1 − e^(−1) crossed at {t_star:.5f} s (closed form, bisection)")
for h, tol in ((1e-3, 2e-5), (0.03, 3e-3)):
    tg = np.arange(0.0, 2.0 + h / 2, h)
    tc = stats.first_crossing(tg, step2(tg, 5.0, 0.5), LEVEL)
    check(close(tc, t_star, tol), f"interpolated crossing on a {h * 1e3:g} ms grid: {tc:.5f} s "
          f"(exact {t_star:.5f}, tolerance {tol:g})")
tg = np.arange(0.0, 2.0, 0.03)
first_sample = tg[np.nonzero(step2(tg, 5.0, 0.5) >= LEVEL)[0][0]]
check(close(first_sample, 0.33, 1e-9), "the first tick-grid sample above the level is 0.33 s: "
      "the quantised reading the interpolation replaces")
check(stats.first_crossing([0.0, 1.0, 2.0], [0.0, 0.5, 1.0], 0.75) == 1.5,
      "linear interpolation between the bracketing samples")
check(stats.first_crossing([0.0, 1.0], [0.7, 0.9], 0.5) == 0.0, "already above at the start")
check(math.isnan(stats.first_crossing([0.0, 1.0], [0.1, 0.2], 0.5)), "never reached: NaN")

# --- paired differences and their direction (the statement rows of seeded series).
a = {1: 3.0, 2: 5.0, 3: 4.0, 4: 6.0, 5: 7.0, 9: 100.0}
b = {1: 1.0, 2: 2.0, 3: 3.0, 4: 4.0, 5: 5.0}
pdf = stats.paired_difference(a, b)
half = 2.776445 * math.sqrt(0.5) / math.sqrt(5)  # diffs 2, 3, 1, 2, 2: mean 2, s² = 0.5
check(pdf.seeds == [1, 2, 3, 4, 5] and pdf.diffs == [2.0, 3.0, 1.0, 2.0, 2.0],
      "paired differences over the common seeds (seed 9 has no partner)")
check(close(pdf.dist.mean, 2.0, 1e-15) and close(pdf.dist.lo, 2 - half, 1e-6)
      and close(pdf.dist.hi, 2 + half, 1e-6),
      f"paired difference: 2 ± {half:.6f} (got [{pdf.dist.lo:.6f}, {pdf.dist.hi:.6f}])")
check(stats.direction(pdf) == 1, "CI above 0: higher")
# Means that differ (3.71 → 3.72, as exp2 C IV's EE error) while the per-seed differences
# straddle 0: no significant change, not "higher".
base = {s: 3.0 + 0.15 * s for s in range(1, 11)}
noise = [0.30, -0.25, 0.12, -0.18, 0.05, 0.21, -0.30, 0.10, -0.02, 0.07]
later = {s: base[s] + noise[s - 1] for s in base}
dd = stats.paired_difference(later, base)
check(dd.dist.mean > 0 and dd.dist.lo < 0 < dd.dist.hi and stats.direction(dd) == 0,
      f"mean difference {dd.dist.mean:+.3f} > 0 but CI [{dd.dist.lo:.3f}, {dd.dist.hi:.3f}] "
      "contains 0: no significant change")
check(stats.direction(stats.paired_difference({s: -v for s, v in a.items()},
                                             {s: -v for s, v in b.items()})) == -1,
      "CI below 0: lower")
check(stats.direction(stats.describe([0.2])) == 1 and stats.direction(stats.describe([-1.0])) == -1
      and stats.direction(stats.describe([0.0])) == 0, "one deterministic value: its sign")
check(stats.direction(stats.describe([])) is None, "nothing measured: no direction")
tr = P.payload_trend([base, {s: v + 0.01 for s, v in base.items()}, later])
check(not tr["rise"] and not tr["mono"] and tr["overall"] == 0,
      "seeded series whose last − first CI contains 0: not higher, not non-decreasing")
tr = P.payload_trend([{None: 1.0}, {None: 1.0}, {None: 2.0}])
check(tr["rise"] and tr["mono"], "deterministic series 1, 1, 2: higher and non-decreasing")
tr = P.payload_trend([{None: 1.0}, {None: 3.0}, {None: 2.0}])
check(tr["rise"] and not tr["mono"], "deterministic series 1, 3, 2: higher, not non-decreasing")
tr = P.payload_trend([b, a])
check(tr["rise"] and tr["mono"], "seeded series with a significant rise: higher and non-decreasing")

tmp = tempfile.mkdtemp(prefix="uvms-report-stats-")


try:
    # --- experiment runs: duplicate slots raise; failed runs are counted, not dropped silently.
    d = os.path.join(tmp, "slots")
    write_campaign(d, "exp_slots", [
        ("a1", ['control.case="IV"', "run.seed=1", "payload.mass_kg=0.0"],
         {"thruster_energy_J": 1.0}),
        ("a2", ['control.case="IV"', "run.seed=1", "payload.mass_kg=5.0"],
         {"thruster_energy_J": 2.0}),
        ("b1", ['control.case="VII"', "run.seed=1", "payload.mass_kg=0.0"],
         {"thruster_energy_J": 0.5}),
        ("b2", ['control.case="VII"', "run.seed=2", "payload.mass_kg=0.0"],
         {"thruster_energy_J": 0.5}),
        ("a3", ['control.case="IV"', "run.seed=2", "payload.mass_kg=0.0"],
         {"thruster_energy_J": 1.0, "status": "failed"}),
        ("a4", ['control.case="IV"', "run.seed=3", "payload.mass_kg=0.0"],
         {"thruster_energy_J": 1.2}),
    ])
    with open(os.path.join(d, "results.json")) as fh:
        e = Experiment(d, json.load(fh), DEFAULTS)
    try:
        e.series("thruster_energy_J", {K.KEY_CASE: "IV"})
        raised = ""
    except AmbiguousCondition as exc:
        raised = str(exc)
    check("a1" in raised and "a2" in raised and "payload.mass_kg" in raised,
          f"two runs in one (condition, seed) slot raise, naming them ({raised[:80]})")
    iv = {K.KEY_CASE: "IV", K.KEY_PAYLOAD: 0.0}
    dv = e.dist("thruster_energy_J", iv)
    check(dv.n == 2 and dv.n_failed == 1, f"a failed run is counted (n {dv.n}, {dv.n_failed} failed)")
    check(fmt_dist(dv, 2).endswith("(1 failed)") and fmt_n(dv) == "2 (1 failed)",
          f"and shown next to the statistic: {fmt_dist(dv, 2)}")
    pa = e.paired("thruster_energy_J", {K.KEY_CASE: "VII", K.KEY_PAYLOAD: 0.0}, iv)
    check(pa.n == 1 and pa.n_failed == 2 and "(2 failed)" in fmt_dist(pa.dist, 3),
          f"pairs lost to a failed run (seed 2) or a missing partner (seed 3): {pa.n_failed}")
    check(fmt_dist(e.dist("thruster_energy_J", {K.KEY_CASE: "VII"}), 2) == "0.50 ± 0.00",
          "no suffix without failures")

    # --- headline: one configuration in several campaigns is counted once.
    root = os.path.join(tmp, "dedupe")
    seeds = range(1, 6)
    e_iv = {s: 10.0 + s for s in seeds}
    e_vii = {s: 9.0 + 0.9 * s for s in seeds}

    def seeded(extra, eiv=e_iv, evii=e_vii):
        return [(f"{c}_s{s}", [f'control.case="{c}"', "environment.unsteady_flow.enabled=true",
                               "environment.density_error=true", f"run.seed={s}"] + extra,
                 {"thruster_energy_J": (eiv if c == "IV" else evii)[s]})
                for c in ("IV", "VII") for s in seeds]
    # A: the reference; B: the same configuration with the default payload written out (and
    # an id that says nothing); C: the same settings written differently (angle of attack,
    # default true) but other energies: not reproducible; D: another payload, other energies;
    # E: another setting but bit-identical energies.
    write_campaign(os.path.join(root, "A"), "expA", seeded([]))
    write_campaign(os.path.join(root, "B"), "expB", seeded(["payload.mass_kg=10.0"]))
    write_campaign(os.path.join(root, "C"), "expC", seeded(
        ["environment.angle_of_attack=true"], {s: v + 1 for s, v in e_iv.items()}))
    write_campaign(os.path.join(root, "D"), "expD", seeded(
        ["payload.mass_kg=5.0"], {s: v - 1 for s, v in e_iv.items()}))
    write_campaign(os.path.join(root, "E"), "expE", seeded(["run.realtime_factor_x=1.0"]))
    rep = Report(root, os.path.join(tmp, "dedupe_out"), SCHEMA)
    for name in ("expA", "expB", "expC", "expD", "expE"):
        rep.add_comparison(name, name, {K.KEY_UNSTEADY: True, K.KEY_DENSITY: True})
    groups, notes = dedupe_comparisons(rep.comparisons, rep.defaults)
    names = [[c["exp"] for c in g_] for g_ in groups]
    check(names == [["expA", "expB", "expC", "expE"], ["expD"]],
          f"A = B (default written out) = C (same settings) = E (identical energies); D apart "
          f"(got {names})")
    check(any("expC" in n and "not reproducible" in n for n in notes)
          and any("expE" in n and "bit-identical" in n for n in notes),
          f"inconsistencies named ({len(notes)} notes)")
    head = "\n".join(headline.section(rep))
    check("5 comparisons in 5 campaigns are 2 distinct configurations" in head,
          "the headline counts configurations, not comparisons")
    check("same 5 seeds" in head and "not independent" in head,
          "and says the seeds are shared across configurations")
    check("25 seed pairs" not in head and "20 of 25" not in head,
          "seed pairs are not summed over comparisons")
finally:
    shutil.rmtree(tmp, ignore_errors=True)

# The continuous law's crossing = the closed-form second-order step it is:
# ω̈ + (KB + b/J)·ω̇ + KA·KB·ω = KA·KB·ω̂ (motor_step's matrix exponentials vs the formula).
wn = math.sqrt(5.0 * 5.0)
zeta = (5.0 + 0.01 / 0.01) / (2 * wn)
t_law = exact_crossing(wn, zeta, LEVEL)
check(close(ms["tau_continuous_s"], t_law, 2e-5) and ms["resolution_s"] <= 1e-3 + 1e-12,
      f"continuous law: 63 % at {ms['tau_continuous_s']:.5f} s = closed form {t_law:.5f} s "
      f"(ζ = {zeta:g}), on a {ms['resolution_s'] * 1e3:g} ms grid")
tf = ms["t_fine_s"]
check(np.allclose(ms["omega_current_fine"][::30], ms["omega_current"], atol=1e-12)
      and np.allclose(ms["omega_continuous_fine"][::30], ms["omega_continuous"], atol=1e-12),
      "the fine grid passes through the tick samples")
check(np.max(np.abs(ms["omega_continuous_fine"] - step2(tf, wn, zeta))) < 1e-9,
      "the continuous law on the fine grid = the closed-form step")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
