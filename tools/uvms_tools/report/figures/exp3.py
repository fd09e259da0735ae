# SPDX-License-Identifier: Apache-2.0
"""exp3: thruster tracking: desired vs produced wrench, the speed loop's step response, the
position and attitude parts of the allocated thrust."""
import math

import numpy as np

from ..keys import COND_EXP1_TEXT
from ..num import isnum
from ..text.fmt import f, g
from .common import AXIS_COLORS, plt


def _title(ck, seed_txt):
    return f"case {ck[0]}, {COND_EXP1_TEXT[ck[1]]}{seed_txt(ck)}"


def force_tracking(figs, order, ticks, seed_txt):
    """ticks: {(case, cond): (telemetry, truth) per tick}; seed_txt(ck): ', seed 7' or ''."""
    fig, axes = plt.subplots(len(order), 2, figsize=(14, 3.0 * len(order)), sharex=True)
    for row, ck in enumerate(order):
        if ck not in ticks:
            continue
        tm, tr = ticks[ck]
        t = tm["t_s"]
        for col, (dk, pk, unit, nm) in enumerate((
                ("force_des_N", "thrust_force_N", "N", "force"),
                ("moment_des_Nm", "thrust_moment_Nm", "N·m", "moment"))):
            ax = axes[row, col]
            for i, ax_name in enumerate("xyz"):
                ax.plot(t, tm[dk][:, i], color=AXIS_COLORS[i], lw=1.6, label=f"desired {ax_name}")
                ax.plot(t, tr[pk][:, i], color=AXIS_COLORS[i], lw=1.4, ls="--",
                        label=f"produced {ax_name}")
            ax.set_title(f"{_title(ck, seed_txt)}: {nm}", fontsize=10.5)
            ax.set_ylabel(f"{nm} [{unit}]")
            if row == 0:
                ax.legend(ncol=3, fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("time t [s]")
    fig.suptitle("Experiment 3: desired (solid, telemetry F_P0, N_P0) vs produced "
                 "(dashed, plant thrust) force and moment, inertial frame", y=1.0)
    fig.tight_layout()
    return figs.save(fig, "exp3_force_tracking.png")


def _tau_txt(x):
    return f"{f(x, 3)} s"


def _motor_panel(ax, ms, used, tmax):
    tf = ms["t_fine_s"]
    sel = tf <= tmax
    selk = ms["t_s"] <= tmax
    for key, tau, lbl, col in (("omega_current", "tau_current_s", "current drive", "#1f77b4"),
                               ("omega_voltage", "tau_voltage_s", "voltage drive", "#ff7f0e")):
        is_used = key.endswith(used)
        ax.plot(tf[sel], ms[key + "_fine"][sel], lw=2.6 if is_used else 1.6, color=col,
                ls="-" if is_used else ":",
                label=f"{lbl}{' (these runs)' if is_used else ' (alternative)'}: 63 % "
                      f"at {_tau_txt(ms[tau])}")
        if is_used and selk.sum() <= 80:
            ax.plot(ms["t_s"][selk], ms[key][selk], "o", ms=3, color=col,
                    label=f"{lbl} at the controller ticks")
    ax.plot(tf[sel], ms["omega_continuous_fine"][sel], lw=1.4, ls="--", color="gray",
            label=f"same law in continuous time: 63 % at {_tau_txt(ms['tau_continuous_s'])}")
    ax.axhline(1.0 - math.exp(-1.0), color="k", lw=0.8, ls=":")
    for tau, col in (("tau_current_s", "#1f77b4"), ("tau_voltage_s", "#ff7f0e"),
                     ("tau_continuous_s", "gray")):
        if isnum(ms[tau]) and ms[tau] <= tmax:
            ax.plot([ms[tau]], [1.0 - math.exp(-1.0)], "x", color=col, ms=8, mew=2)
    ax.set_xlabel("time t [s]")
    ax.set_title(f"first {g(tmax, 2)} s")


def motor_step(figs, ms, used):
    """ms: analyses.motor.motor_step; used: the drive of the runs ("current", "voltage")."""
    res = ms["resolution_s"]
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.2), sharey=True)
    spans = [5 * x for x in (ms["tau_current_s"], ms["tau_voltage_s"]) if isnum(x)] or [2.0]
    for ax, tmax in zip(axes, (min(spans), max(spans))):
        _motor_panel(ax, ms, used, tmax)
    axes[0].set_ylabel("shaft speed ω / ω̂ [-]")
    axes[0].legend(loc="lower right", fontsize=8)
    axes[1].legend(loc="lower right", fontsize=8)
    fig.suptitle("Thruster speed loop (docs/MODEL.md §7.4 [64–66], motor §5): unit step of "
                 f"ω̂, loops run every {g(ms['tick_s'], 3)} s tick\nlogged configuration, no "
                 f"propeller load; 63 % times (×) interpolated on a {g(res * 1e3, 2)} ms grid")
    fig.tight_layout()
    return figs.save(fig, "exp3_motor_step.png")


def thrust_split(figs, order, splits, seed_txt):
    """splits: {(case, cond): analyses.energy.thrust_split dict}."""
    fig, axes = plt.subplots(2, 2, figsize=(13, 7.5), sharey=True)
    xs = np.arange(8)
    for ax, ck in zip(axes.flat, order):
        if ck not in splits:
            ax.set_visible(False)
            continue
        sp = splits[ck]
        ax.bar(xs - 0.2, sp["rms_pos"] * 1e3, 0.4, label="position part P_pos (RMS)")
        ax.bar(xs + 0.2, sp["rms_att"] * 1e3, 0.4, label="attitude part P_att (RMS)")
        ax.set_xticks(xs, [str(j + 1) for j in xs])
        ax.set_xlabel("thruster j")
        ax.set_title(_title(ck, seed_txt), fontsize=10.5)
        ax.legend(fontsize=8.5)
    for ax in axes[:, 0]:
        ax.set_ylabel("RMS thrust [mN]")
    fig.suptitle("Experiment 3: position and attitude components of the allocated thrust "
                 "per thruster (docs/MODEL.md §7.3)")
    fig.tight_layout()
    return figs.save(fig, "exp3_thrust_split.png")
