# SPDX-License-Identifier: Apache-2.0
"""exp3: thruster tracking (cases IV and VII, both conditions): desired vs produced wrench,
the thruster response, the thrust split and where the energy goes."""
import numpy as np

from ..analyses import delay, energy
from ..figures import exp3 as fig3
from ..keys import BARY, COND_EXP1_KEYS, KEY_CASE, VEH
from ..load.logs import has, per_tick
from ..load.overrides import seed_of
from ..num import div
from .common import img, open_experiment
from .exp3_energy import energy_breakdown
from .exp3_motor import motor_section
from .fmt import f, g, table

NAME = "exp3_tracking"
ORDER = [(c, k) for c in (VEH, BARY) for k in ("stagnant", "unsteady")]


def _tracking(rep, ticks):
    """Per run drawn: RMS tracking errors and the best delay of the produced wrench; fills
    rep.track_summary and rep.track_lags."""
    rows, lags = [], []
    for ck in ORDER:
        if ck not in ticks:
            continue
        tm, tr = ticks[ck]
        dt = energy.median_step(tm["t_s"])
        des = np.hstack([tm["force_des_N"], tm["moment_des_Nm"]])
        prod = np.hstack([tr["thrust_force_N"], tr["thrust_moment_Nm"]])
        lag, err_lag, err0 = (delay.best_lag(des, prod, dt) if len(tm["t_s"]) > 2
                              else (np.nan,) * 3)
        lags.append((ck, lag))
        te = delay.tracking_errors(tm["force_des_N"], tr["thrust_force_N"],
                                   tm["moment_des_Nm"], tr["thrust_moment_Nm"])
        rep.track_summary[f"{ck[0]} {ck[1]}"] = div(te["f_err"], te["f"])
        rows.append([f"{ck[0]}, {ck[1]}", g(te["f"], 3), g(te["f_err"], 3),
                     f(100 * div(te["f_err"], te["f"]), 1), g(te["n"], 3), g(te["n_err"], 3),
                     f(lag, 2), g(err0, 3), g(err_lag, 3)])
    rep.track_lags = lags
    md = table(["run", "RMS |F_des| [N]", "RMS |F_des − F_prod| [N]", "relative [%]",
                "RMS |N_des| [N·m]", "RMS |N_des − N_prod| [N·m]",
                "best delay of produced [s]", "RMS wrench error at 0 s delay",
                "at best delay"], rows)
    return md + ["The delay column is the shift L ≥ 0 that minimises the RMS of the 6-vector "
                 "(F_des, N_des)(t) − (F_prod, N_prod)(t + L) (mixed N and N·m).", ""]


def _split(rep, ticks, seed_txt):
    """Position vs attitude parts of the allocated thrust; fills rep.split_summary."""
    splits, rows = {}, []
    for ck in ORDER:
        if ck not in ticks:
            continue
        tm, _ = ticks[ck]
        sp = energy.thrust_split(energy.median_step(tm["t_s"], 0.0), tm["thrust_pos_N"],
                                 tm["thrust_att_N"], tm["thrust_des_N"])
        splits[ck] = sp
        if ck[1] == "stagnant":
            rep.split_summary[ck[0]] = (sp["pos"], sp["att"])
        rows.append([f"{ck[0]}, {ck[1]}", g(sp["pos"], 3), g(sp["att"], 3), g(sp["total"], 3)])
    md = []
    img(md, fig3.thrust_split(rep.figs, ORDER, splits, seed_txt),
        "RMS of the position (H⁺(F;0)) and attitude (H⁺(0;N)) parts of each thruster's "
        "allocated thrust.")
    return md + table(["run", "∫Σ|P_pos| dt [N·s]", "∫Σ|P_att| dt [N·s]", "∫Σ|P| dt [N·s]"],
                      rows)


def section(rep):
    e, md = open_experiment(rep, NAME)
    if e is None:
        return md
    conds = {(c, k): dict(COND_EXP1_KEYS[k], **{KEY_CASE: c}) for c, k in ORDER}
    runs = {ck: e.one(conds[ck]) for ck in ORDER}
    e.prefetch_logs(runs.values())
    logs = {ck: e.log(r) for ck, r in runs.items()}
    logs = {ck: lg for ck, lg in logs.items() if has(lg, "UVMS_TELEMETRY", "UVMS_TRUTH")}
    if not logs:
        return md + ["*No logs of experiment 3 could be read.*", ""]
    useed = seed_of(runs[(VEH, "unsteady")]) if runs[(VEH, "unsteady")] else None
    nseeds = e.n_seeds(conds[(VEH, "unsteady")])
    if nseeds > 1:
        md += [f"The time series, tracking and energy-breakdown figures and tables below show "
               f"one seed (run.seed = {useed}) of the {nseeds} of the unsteady condition; the "
               f"Observations give its energies' distribution over all seeds.", ""]

    def seed_txt(ck):
        return f", seed {useed}" if ck[1] == "unsteady" and nseeds > 1 else ""
    ticks = {ck: per_tick(logs[ck]) for ck in ORDER if ck in logs}
    img(md, fig3.force_tracking(rep.figs, ORDER, ticks, seed_txt),
        "Desired vs produced control force and moment, cases IV and VII, both conditions.")
    md += _tracking(rep, ticks)
    cfg = next((logs[ck]["UVMS_CONFIG"] for ck in ORDER
                if ck in logs and "UVMS_CONFIG" in logs[ck]), None)
    if cfg is not None:
        md += motor_section(rep, cfg)
    md += _split(rep, ticks, seed_txt)
    return md + energy_breakdown(rep, e, runs, logs, ORDER, conds)
