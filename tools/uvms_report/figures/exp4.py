# SPDX-License-Identifier: Apache-2.0
"""exp4: the energy ratio per model combination."""
import numpy as np

from .common import err_bars, plt


def fidelity_ratio(figs, pairs, labels, unsteady):
    """pairs: stats.Paired per combination; labels: 'U/ρ/α/C'; unsteady: bool per combination."""
    fig, ax = plt.subplots(figsize=(12, 4.3))
    cols = ["#d62728" if u else "#1f77b4" for u in unsteady]
    y, yerr = err_bars([p.dist for p in pairs])
    ax.bar(np.arange(len(pairs)), y, color=cols, yerr=yerr, capsize=4)
    ax.axhline(1.0, color="k", lw=1)
    ax.set_xticks(np.arange(len(pairs)), labels, rotation=45, ha="right")
    ax.set_ylabel("E(VII) / E(IV) [-], paired per seed")
    ax.set_xlabel("model combination: U unsteady flow / ρ density error / α angle of attack "
                  "/ C variable coefficients (- = off)")
    ax.set_title("Experiment 4: energy ratio barycenter/vehicle per model combination "
                 "(blue steady, red unsteady flow; error bars 95 % CI over seeds)")
    fig.tight_layout()
    return figs.save(fig, "exp4_fidelity_ratio.png")
