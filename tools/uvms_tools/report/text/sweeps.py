# SPDX-License-Identifier: Apache-2.0
"""sweeps: experiments 5 (travel distance) and 6 (trajectory duration)."""
import numpy as np

from ..analyses import inference
from ..analyses.paper import PAPER_FIG25_RATIO
from ..figures.sweeps import sweep_figure
from ..keys import BARY, E_EL, E_P, ERR, KEY_CASE, KEY_DIST, KEY_TRAJ_DUR, VEH
from ..num import isnum
from .common import img, open_experiment, status_mark
from .fmt import f, fmt_dist, fmt_range, g, table


def sweep(e, key):
    """(xs, IV dists, VII dists, paired ratios) over the values of a swept key."""
    xs = e.values(key)
    dv = [e.dist(E_EL, {KEY_CASE: VEH, key: x}) for x in xs]
    db = [e.dist(E_EL, {KEY_CASE: BARY, key: x}) for x in xs]
    pr = [e.paired(E_EL, {KEY_CASE: BARY, key: x}, {KEY_CASE: VEH, key: x}) for x in xs]
    return xs, dv, db, pr


def _figure(rep, e, key, xlabel, title, fname, band=None):
    """The sweep figure on E_p: each case's energy and the paired ratio."""
    xs = e.values(key)
    dv = [e.dist(E_P, {KEY_CASE: VEH, key: x}) for x in xs]
    db = [e.dist(E_P, {KEY_CASE: BARY, key: x}) for x in xs]
    ratios = [inference.ratio_or_none(e.series(E_P, {KEY_CASE: BARY, key: x}),
                                      e.series(E_P, {KEY_CASE: VEH, key: x})) for x in xs]
    return sweep_figure(rep.figs, xs, dv, db, ratios, xlabel, title, fname, band)


def section_exp5(rep):
    name = "exp5_travel"
    e, md = open_experiment(rep, name)
    if e is None:
        return md
    xs, dv, db, pr = sweep(e, KEY_DIST)
    lo, hi = PAPER_FIG25_RATIO
    img(md, _figure(rep, e, KEY_DIST, "EE travel distance r_Δ [m]",
                    "Experiment 5: energy vs EE travel distance (straight line, cosine profile)",
                    "exp5_travel.png", (lo, hi, f"paper, Fig. 25: {f(lo, 2)}–{f(hi, 2)}")),
        "Propulsive energy and its ratio VII/IV vs travel distance; the paper's stated range "
        "of the ratio shaded.")
    rows = []
    for x, a, b, p in zip(xs, dv, db, pr):
        rv, rb = e.one({KEY_CASE: VEH, KEY_DIST: x}), e.one({KEY_CASE: BARY, KEY_DIST: x})
        rep.add_comparison(name, f"exp5, travel {fmt_range(xs, 1)} m", {KEY_DIST: x}, row={},
                           sub=f"r_Δ = {f(x, 1)} m")
        rows.append([f(x, 2), fmt_dist(a, 2) + status_mark(rv), fmt_dist(b, 2) + status_mark(rb),
                     fmt_dist(p.dist, 3),
                     fmt_dist(e.dist(ERR, {KEY_CASE: VEH, KEY_DIST: x}), 3, 1e3),
                     fmt_dist(e.dist(ERR, {KEY_CASE: BARY, KEY_DIST: x}), 3, 1e3)])
    return md + table(["r_Δ [m]", "E_el(IV) [J]", "E_el(VII) [J]", "E(VII)/E(IV)",
                       "mean ε IV [mm]", "mean ε VII [mm]"], rows)


def _ends_text(e):
    """Whether every run ends with its trajectory (run length vs t_F within one tick)."""
    cfg = e.logged_config(e.runs[0]) if e.runs else None
    tick = float(cfg["tick_s"][0]) if cfg is not None else float("nan")
    gaps = [abs(float(r["duration_s"]) - float(r[KEY_TRAJ_DUR])) for r in e.runs
            if isnum(r.get("duration_s")) and isnum(r.get(KEY_TRAJ_DUR))]
    same = bool(gaps) and isnum(tick) and max(gaps) <= tick + 1e-9
    ends = (f"ends with its trajectory, to within one tick (largest |run length − t_F| = "
            f"{f(max(gaps), 3)} s, tick {g(tick, 3)} s; run length = ticks × tick from "
            f"summary.json)" if same else "does NOT end with its trajectory (run length and "
            "t_F differ by more than a tick in results.json)")
    return [f"Every run of this experiment {ends}, so energies of different durations cover "
            "the maneuver only, not a common hold period afterwards.", ""]


def _peak_note(rep, xs, dv):
    valid = [(x, a.mean) for x, a in zip(xs, dv) if isnum(a.mean)]
    if len(valid) < 3:
        return
    k = int(np.argmax([a for _, a in valid]))
    if not 0 < k < len(valid) - 1:
        return
    slow = (" Consistent with the slow voltage drive of these runs (experiment 3): "
            "short maneuvers end before the thrusters deliver the demanded force."
            if rep.drive() in (None, "voltage") else " Cause: open.")
    rep.notes.append(
        f"Experiment 6: the vehicle-stabilization energy is not monotonic in the "
        f"duration: it peaks at t_F = {f(valid[k][0], 0)} s ({f(valid[k][1], 1)} J) "
        f"and falls for shorter maneuvers ({f(valid[0][1], 1)} J at "
        f"{f(valid[0][0], 0)} s), while the reaction impulse of the analytic model "
        f"grows as 1/t_F." + slow)


def section_exp6(rep):
    name = "exp6_duration"
    e, md = open_experiment(rep, name)
    if e is None:
        return md
    ends = _ends_text(e)
    xs, dv, db, pr = sweep(e, KEY_TRAJ_DUR)
    img(md, _figure(rep, e, KEY_TRAJ_DUR, "trajectory duration t_F [s]",
                    "Experiment 6: energy vs trajectory duration (joint cycloid of "
                    "experiment 1)", "exp6_duration.png"),
        "Propulsive energy and its ratio VII/IV vs trajectory duration (the paper: the ratio "
        "stays below 1).")
    rows = []
    for x, a, b, p in zip(xs, dv, db, pr):
        rv = e.one({KEY_CASE: VEH, KEY_TRAJ_DUR: x})
        rb = e.one({KEY_CASE: BARY, KEY_TRAJ_DUR: x})
        rep.add_comparison(name, f"exp6, durations {fmt_range(xs, 0)} s", {KEY_TRAJ_DUR: x},
                           row={}, sub=f"t_F = {f(x, 0)} s")
        rows.append([f(x, 0), f(rv and rv.get("duration_s"), 2), fmt_dist(a, 1) + status_mark(rv),
                     fmt_dist(b, 1) + status_mark(rb), fmt_dist(p.dist, 3),
                     fmt_dist(e.dist(ERR, {KEY_CASE: VEH, KEY_TRAJ_DUR: x}), 2, 1e3),
                     fmt_dist(e.dist(ERR, {KEY_CASE: BARY, KEY_TRAJ_DUR: x}), 2, 1e3)])
    md += table(["t_F [s]", "run length [s]", "E_el(IV) [J]", "E_el(VII) [J]", "E(VII)/E(IV)",
                 "mean ε IV [mm]", "mean ε VII [mm]"], rows)
    _peak_note(rep, xs, dv)
    return md + ends
