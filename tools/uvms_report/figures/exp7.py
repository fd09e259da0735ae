# SPDX-License-Identifier: Apache-2.0
"""exp7: thruster vs manipulator energy per payload."""
import numpy as np

from ..keys import BARY, VEH
from ..text.fmt import f
from .common import CASE_COLORS, plt

BARS = ((VEH, "thr", "IV thrusters", ""), (VEH, "man", "IV manipulator", "//"),
        (BARY, "thr", "VII thrusters", ""), (BARY, "man", "VII manipulator", "//"))


def energy_split(figs, pays, means):
    """means: {(case, "thr" | "man"): [mean energy per payload]}."""
    fig, ax = plt.subplots(figsize=(11, 4.6))
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
    ax.set_title("Experiment 7: thruster vs manipulator energy, vehicle (IV) and "
                 "barycenter (VII) stabilization")
    ax.legend(ncol=4, loc="upper center")
    fig.tight_layout()
    return figs.save(fig, "exp7_energy_split.png")
