# SPDX-License-Identifier: Apache-2.0
"""exp7: thruster vs manipulator energy per payload, and the paired ratio VII/IV of each."""
import numpy as np

from ..keys import BARY, VEH
from ..text.fmt import f
from .common import CASE_COLORS, est_bars, plt

BARS = ((VEH, "thr", "IV thrusters", ""), (VEH, "man", "IV manipulator", "//"),
        (BARY, "thr", "VII thrusters", ""), (BARY, "man", "VII manipulator", "//"))


def energy_split(figs, pays, means, ratios):
    """means: {(case, "thr" | "man"): [mean energy per payload]}; ratios: {"thr" | "man":
    [inference.Estimate of VII/IV per payload]}."""
    fig, (ax, ax2) = plt.subplots(1, 2, figsize=(15, 4.6), width_ratios=(1.6, 1))
    x = np.arange(len(pays))
    wdt = 0.2
    for i, (c, what, lbl, hatch) in enumerate(BARS):
        ax.bar(x + (i - 1.5) * wdt, means[(c, what)], wdt, label=lbl, color=CASE_COLORS[c],
               alpha=1.0 if not hatch else 0.45, hatch=hatch, edgecolor="k", lw=0.5)
    ax.set_yscale("log")
    lo, hi = ax.get_ylim()
    ax.set_ylim(lo, hi * 30)
    ax.set_xticks(x, [f(p, 0) for p in pays])
    ax.set_xlabel("payload m_P [kg]")
    ax.set_ylabel("energy over the run [J] (log)")
    ax.set_title("Energy of thrusters (E_el) and manipulator")
    ax.legend(ncol=2, loc="upper center")
    for what, mk, lbl in (("thr", "o-", "thrusters, E_p(VII)/E_p(IV)"),
                          ("man", "s--", "manipulator, E_man(VII)/E_man(IV)")):
        y, yerr = est_bars(ratios[what])
        ax2.errorbar(pays, y, yerr=yerr, fmt=mk, lw=2, capsize=3, label=lbl)
    ax2.axhline(1.0, color="k", lw=1, ls=":",
                label="1 (the paper: manipulator energy about equal)")
    ax2.set_xlabel("payload m_P [kg]")
    ax2.set_ylabel("VII / IV [-]")
    ax2.set_title("Barycenter over vehicle stabilization")
    ax2.legend(fontsize=8.5)
    fig.suptitle("Experiment 7: thruster vs manipulator energy, vehicle (IV) and barycenter "
                 "(VII) stabilization")
    fig.tight_layout()
    return figs.save(fig, "exp7_energy_split.png")
