# SPDX-License-Identifier: Apache-2.0
"""exp2: energy and EE error against payload, IV vs VII, conditions A, B, C."""
import numpy as np

from ..keys import BARY, COND_EXP2_TEXT, VEH
from .common import CASE_COLORS, err_bars, plt


def payload_sweep(figs, pays, dists, n_seeds, what, ylab, fname, scale):
    """dists: {(case, cond): [Dist per payload]}; n_seeds: {cond: seeds per payload}."""
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.3), sharey=True)
    for ax, k in zip(axes, ("A", "B", "C")):
        span = (max(pays) - min(pays)) if len(pays) > 1 else 1.0
        for c, mk, dx in ((VEH, "o-", -0.008), (BARY, "s-", 0.008)):
            y, yerr = err_bars(dists[(c, k)], scale)
            ax.errorbar(np.asarray(pays, float) + dx * span, y, yerr=yerr, fmt=mk,
                        color=CASE_COLORS[c], lw=2, capsize=3,
                        label=f"{c} ({'vehicle' if c == VEH else 'barycenter'} stab.)")
        n = n_seeds[k]
        ax.set_title(COND_EXP2_TEXT[k] + (f"\nmean and 95 % CI over {n} seeds" if n > 1 else ""))
        ax.set_xlabel("payload m_P [kg]")
        ax.legend()
    if what == "error":
        axes[0].set_yscale("log")
        ylab += " (log)"
    axes[0].set_ylabel(ylab)
    fig.suptitle(f"Experiment 2: {what} vs payload, vehicle (IV) vs barycenter (VII)")
    fig.tight_layout()
    return figs.save(fig, fname)
