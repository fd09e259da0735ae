# SPDX-License-Identifier: Apache-2.0
"""sweeps: energy and the paired energy ratio against a swept setting (experiments 5 and 6),
with what the paper states about the ratio drawn."""
import numpy as np

from ..keys import BARY, VEH
from .common import CASE_COLORS, err_bars, est_bars, plt


def sweep_figure(figs, xs, dv, db, ratios, xlabel, title, fname, paper_band=None):
    """xs: swept values; dv, db: E_p Dists of IV and VII; ratios: inference.Estimate of
    E_p(VII)/E_p(IV) per value; paper_band: (lo, hi, label) of the paper's stated ratio range,
    drawn shaded (None: the paper states only that it stays below 1)."""
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.3))
    x = np.asarray(xs, float)
    for ds, mk, c, lbl in ((dv, "o-", VEH, "IV vehicle stabilization"),
                           (db, "s-", BARY, "VII barycenter stabilization")):
        y, yerr = err_bars(ds)
        axes[0].errorbar(x, y, yerr=yerr, fmt=mk, color=CASE_COLORS[c], lw=2, capsize=3,
                         label=lbl)
    axes[0].set_ylabel("propulsive energy E_p [J]")
    axes[0].legend()
    y, yerr = est_bars(ratios)
    axes[1].errorbar(x, y, yerr=yerr, fmt="d-", color="k", lw=2, capsize=3,
                     label="ours, E_p(VII)/E_p(IV)")
    if paper_band:
        axes[1].axhspan(paper_band[0], paper_band[1], color="0.8", alpha=0.6,
                        label=paper_band[2])
    axes[1].axhline(1.0, color="gray", lw=1, ls=":",
                    label=None if paper_band else "1 (the paper: the ratio stays below it)")
    axes[1].set_ylabel("energy ratio E_p(VII)/E_p(IV) [-]")
    axes[1].legend()
    for ax in axes:
        ax.set_xlabel(xlabel)
    fig.suptitle(title)
    fig.tight_layout()
    return figs.save(fig, fname)
