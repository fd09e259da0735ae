# SPDX-License-Identifier: Apache-2.0
"""sweeps: energy and ratio against a swept setting (experiments 5 and 6)."""
import numpy as np

from ..keys import BARY, VEH
from .common import CASE_COLORS, err_bars, plt


def sweep_figure(figs, xs, dv, db, pr, xlabel, title, fname):
    """xs: swept values; dv, db: E_el Dists of IV and VII; pr: stats.Paired ratios."""
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.3))
    x = np.asarray(xs, float)
    for ds, mk, c, lbl in ((dv, "o-", VEH, "IV vehicle stabilization"),
                           (db, "s-", BARY, "VII barycenter stabilization")):
        y, yerr = err_bars(ds)
        axes[0].errorbar(x, y, yerr=yerr, fmt=mk, color=CASE_COLORS[c], lw=2, capsize=3,
                         label=lbl)
    axes[0].set_ylabel("thruster energy E_el [J]")
    axes[0].legend()
    y, yerr = err_bars([p.dist for p in pr])
    axes[1].errorbar(x, y, yerr=yerr, fmt="d-", color="k", lw=2, capsize=3,
                     label="E(VII)/E(IV)")
    axes[1].axhline(1.0, color="gray", lw=1, ls=":")
    axes[1].set_ylabel("energy ratio E(VII)/E(IV) [-]")
    axes[1].legend()
    for ax in axes:
        ax.set_xlabel(xlabel)
    fig.suptitle(title)
    fig.tight_layout()
    return figs.save(fig, fname)
