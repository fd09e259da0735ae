# SPDX-License-Identifier: Apache-2.0
"""exp4: the paired energy ratio per model combination, the paper's Table XIII as stars."""
import numpy as np

from .common import est_bars, paper_marks, plt


def fidelity_ratio(figs, ratios, labels, unsteady, paper):
    """ratios: inference.Estimate of E_p(VII)/E_p(IV) per combination; labels: 'U/ρ/α/C';
    unsteady: bool per combination; paper: Table XIII's ratio per combination (NaN: none)."""
    fig, ax = plt.subplots(figsize=(12, 4.6))
    x = np.arange(len(ratios))
    y, yerr = est_bars(ratios)
    for un, col, lab in ((False, "#1f77b4", "ours, steady flow"),
                         (True, "#d62728", "ours, unsteady flow (paired per seed, 95 % CI)")):
        sel = np.array([u == un for u in unsteady], bool)
        if sel.any():
            ax.errorbar(x[sel], y[sel], yerr=yerr[:, sel], fmt="o", color=col, ms=7, capsize=4,
                        label=lab)
    paper_marks(ax, x, paper, "paper, Table XIII")
    ax.axhline(1.0, color="0.5", lw=1, ls=":")
    ax.set_xticks(x, labels, rotation=45, ha="right")
    ax.set_ylabel("E_p(VII) / E_p(IV) [-]")
    ax.set_xlabel("model combination: U unsteady flow / ρ density error / α angle of attack "
                  "/ C variable coefficients (- = off)")
    ax.set_title("Experiment 4: energy ratio barycenter/vehicle per model combination")
    ax.legend()
    fig.tight_layout()
    return figs.save(fig, "exp4_fidelity_ratio.png")
