# SPDX-License-Identifier: Apache-2.0
"""exp1: the eight cases of Table X in both conditions."""
import numpy as np

from uvms_tools.log import runlog

from ..analyses import checks, inference, stats
from ..analyses.paper import PAPER_TABLE_XI, PAPER_TABLE_XII
from ..figures import exp1 as fig1
from ..keys import (BARY, CASES, COND_EXP1_KEYS, COND_EXP1_TEXT, E_EL, E_P, ERR,
                    FEEDBACK_PAIRS, KEY_CASE, MATCHED_PAIRS, VEH)
from ..load.overrides import seed_of
from ..num import isnum
from ..scorecard.cases import Source
from .common import img, open_experiment, seeds_text, status_mark, switches_text
from .fmt import fmt_ci, fmt_dist, fmt_minmax, fmt_n, g, mm, table

NAME = "exp1_cases"
CONDS = ["stagnant", "unsteady"]


def _cond(c, k):
    return dict(COND_EXP1_KEYS[k], **{KEY_CASE: c})


def _drawn(e, rep_runs):
    """From the run drawn per (case, condition): the Table X meaning of each case (logged
    config), the EE error series, and the recomputed mean ε's gap to summary.json."""
    meaning, series, check = {}, {}, []
    for (c, k), r in rep_runs.items():
        log = e.log(r)
        if log is None:
            continue
        if "UVMS_CONFIG" in log:
            meaning.setdefault(c, switches_text(log["UVMS_CONFIG"]))
        if "UVMS_TRUTH" in log and "UVMS_TELEMETRY" in log:
            _, t, eps = runlog.ee_error(log)
            series[(c, k)] = (t, eps)
            if len(eps) and isnum(r.get(ERR)):
                check.append(checks.relative_gap(eps.mean(), r[ERR]))
    return meaning, series, check


def _band_runs(e):
    """{case: its unsteady runs (every seed)} of IV and VII, where there are two or more."""
    runs = {c: e.select(_cond(c, "unsteady")) for c in (VEH, BARY)}
    return {c: rs for c, rs in runs.items() if len(rs) >= 2}


def _bands(e, band_runs):
    """{case: (t, min ε, max ε, n seeds)} over the runs of _band_runs."""
    bands = {}
    for c, runs in band_runs.items():
        eps_all = []
        for r in runs:
            lg = e.log(r, ["UVMS_TRUTH", "UVMS_TELEMETRY"])
            if lg is None or "UVMS_TRUTH" not in lg or "UVMS_TELEMETRY" not in lg:
                continue
            _, t, eps = runlog.ee_error(lg)
            eps_all.append((t, eps))
        m = min((len(t) for t, _ in eps_all), default=0)
        if m and len(eps_all) >= 2:
            arr = np.array([eps[:m] for _, eps in eps_all])
            bands[c] = (eps_all[0][0][:m], arr.min(axis=0), arr.max(axis=0), len(eps_all))
    return bands


def _case_name(c, meaning):
    mean = meaning.get(c, "?")
    if c == VEH:
        return f"**{c}**", f"**{mean} = vehicle stabilization**"
    if c == BARY:
        return f"**{c}**", f"**{mean} = barycenter stabilization**"
    return c, mean


def _tables(rep, e, rep_runs, meaning):
    """The per-case table (both conditions) and the unsteady one over seeds; returns
    (lines, {(case, cond): (E_el, E_p, ε) Dists})."""
    prop = rep.metric(e, E_P)
    md = ["### Mean EE error and energies", "",
          f"Stagnant: one deterministic run per case. Unsteady: "
          f"{seeds_text(e, _cond(VEH, 'unsteady'))} "
          f"per case; mean ± half-width of the 95 % confidence interval (Student t). "
          f"E_el = thruster (electrical) energy ∫Σmax(V·I, 0) dt, E_p = propulsive "
          f"(actuator-disk) energy ∫Σ|T|^1.5/√(2ρA_d) dt (docs/MODEL.md §5).", ""]
    rows, dists = [], {}
    for c in CASES:
        cells = []
        for k in CONDS:
            cond = _cond(c, k)
            de, dp = e.dist(E_EL, cond), e.dist(prop, cond)
            dr, dx = e.dist(ERR, cond), e.dist("max_ee_error_m", cond)
            dists[(c, k)] = (de, dp, dr)
            cells += [fmt_dist(dr, 2, 1e3) + status_mark(rep_runs[(c, k)]), fmt_dist(dx, 2, 1e3),
                      fmt_dist(de, 1), fmt_dist(dp, 3, sig=3)]
        rows.append(list(_case_name(c, meaning)) + cells)
    md += table(["case", "Table X (from the logged config)",
                 "stagnant: mean ε [mm]", "max ε [mm]", "E_el [J]", "E_p [J]",
                 "unsteady: mean ε [mm]", "max ε [mm]", "E_el [J]", "E_p [J]"], rows)
    srows = []
    for c in CASES:
        de, dp, dr = dists[(c, "unsteady")]
        if de.n < 2:
            continue
        srows.append([c, fmt_n(de), g(de.mean, 4), fmt_ci(de, 1), fmt_minmax(de, 1),
                      mm(dr.mean), fmt_ci(dr, 2, 1e3), fmt_minmax(dr, 2, 1e3)])
    if srows:
        md += ["**Unsteady condition over seeds** (E_el and mean ε):", ""]
        md += table(["case", "n", "E_el mean [J]", "95 % CI", "min–max", "ε mean [mm]",
                     "95 % CI", "min–max"], srows)
    return md, dists


def _pairs(rep, e):
    """Vehicle vs barycenter, the case pairs that differ only in the position reference,
    paired per seed; the feedback pairs go to the headline."""
    prop = rep.metric(e, E_P)
    rr = []
    for k in CONDS:
        for v, b in MATCHED_PAIRS:
            fb = (v, b) in FEEDBACK_PAIRS
            common = COND_EXP1_KEYS[k]
            if fb:
                pa = rep.add_comparison(NAME, f"exp1, {COND_EXP1_TEXT[k]}, {b} vs {v}", common,
                                        num=b, den=v, with_err=True)
            else:
                pa = e.paired(E_EL, _cond(b, k), _cond(v, k))
            pp = e.paired(prop, _cond(b, k), _cond(v, k))
            pe = e.paired(ERR, _cond(b, k), _cond(v, k))
            rr.append([COND_EXP1_TEXT[k], f"{b} / {v}" + ("" if fb else " (no feedback)"),
                       fmt_n(pa.dist), fmt_dist(pa.dist, 3), fmt_ci(pa.dist, 3),
                       fmt_minmax(pa.dist, 3), f"{pa.n_below_1} of {pa.n}",
                       stats.compare(pa) or "n/a", fmt_dist(pp.dist, 3), fmt_dist(pe.dist, 3)])
    md = ["**Vehicle vs barycenter stabilization**, the case pairs that differ only in the "
          "position reference; ratios barycenter/vehicle paired per seed:", ""]
    return md + table(["condition", "barycenter / vehicle", "n", "E_el ratio (mean ± CI)",
                       "95 % CI", "min–max", "barycenter cheaper in", "verdict", "E_p ratio",
                       "ε ratio"], rr)


def section(rep):
    e, md = open_experiment(rep, NAME)
    if e is None:
        return md
    rep_runs = {(c, k): e.one(_cond(c, k)) for c in CASES for k in CONDS}
    band_runs = _band_runs(e)
    e.prefetch_logs([*rep_runs.values(), *(r for rs in band_runs.values() for r in rs)])
    meaning, series, check = _drawn(e, rep_runs)
    bands = _bands(e, band_runs)
    drawn_seed = {k: seed_of(rep_runs[(VEH, k)]) if rep_runs[(VEH, k)] else None for k in CONDS}
    md += ["### EE error over time", ""]
    img(md, fig1.ee_error(rep.figs, series, bands, meaning, drawn_seed, CONDS),
        "EE error ε(t) (docs/MODEL.md §10) of the eight cases; left stagnant, right unsteady flow "
        "plus density error (one seed drawn; IV and VII with the range over all seeds "
        "shaded). IV (vehicle) and VII (barycenter) drawn thick.")
    if check:
        md += [f"Check: the mean EE error recomputed from each log drawn (truth "
               f"`ee_position_m` vs telemetry `ee_estimate_m`, matched by tick) agrees with "
               f"summary.json to {g(max(check), 2)} relative (worst of {len(check)} runs).", ""]
    tables, dists = _tables(rep, e, rep_runs, meaning)
    md += tables + _pairs(rep, e)
    img(md, _ratio_figure(rep),
        "Left: the propulsive energy of each case over case IV's, paired per seed (geometric "
        "mean, 95 % CI on the log scale), in both readings; right: mean EE error ε (95 % CI "
        "over seeds); the paper's Tables XI and XII as stars; rows: the two conditions, each "
        "column on one y-axis.")
    return md


def _ratio_figure(rep):
    """The paired ratios and ε of every case and reading against Tables XI and XII."""
    src = Source(rep)
    tabs = {"stagnant": PAPER_TABLE_XI, "unsteady": PAPER_TABLE_XII}
    ratios, eps = {}, {}
    for k in CONDS:
        un = k == "unsteady"
        for rd in ("same task", "same motion"):
            iv = src.series(E_P, VEH, un, rd)
            ratios[(k, rd)] = [inference.ratio_or_none(src.series(E_P, c, un, rd), iv)
                               if c not in ("I", VEH) else None for c in CASES]
            eps[(k, rd)] = [stats.describe(list(src.series(ERR, c, un, rd).values()))
                            for c in CASES]
    paper_ratio = {k: [t[c][1] / t[VEH][1] if c != "I" else np.nan for c in CASES]
                   for k, t in tabs.items()}
    paper_eps = {k: [t[c][0] for c in CASES] for k, t in tabs.items()}
    return fig1.ratio_vs_paper(rep.figs, ratios, eps, paper_ratio, paper_eps, CONDS)
