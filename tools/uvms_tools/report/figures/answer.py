# SPDX-License-Identifier: Apache-2.0
"""answer: the answer box's one figure: the ratio E_p(VII)/E_p(IV) per condition and reading,
with 95 % CIs (paired per seed) and the paper's values, on one shared log axis."""
import numpy as np

from .common import CASE_COLORS, plt

MARK = {"same task": ("s", CASE_COLORS["VIII"]), "same motion": ("o", CASE_COLORS["VII"])}


def forest(figs, conds, ests, paper):
    """conds: labels top to bottom; ests: {reading: [Estimate or None]}; paper: [value|None]."""
    fig, ax = plt.subplots(figsize=(8.6, 0.42 * len(conds) + 0.9))
    y = np.arange(len(conds))[::-1].astype(float)
    for k, (rd, es) in enumerate(ests.items()):
        mk, col = MARK[rd]
        off = 0.13 if k == 0 else -0.13
        for yi, e in zip(y, es):
            if e is None:
                continue
            lo = e.estimate - e.lo if e.has_ci else 0.0
            hi = e.hi - e.estimate if e.has_ci else 0.0
            ax.errorbar([e.estimate], [yi + off], xerr=[[lo], [hi]], fmt=mk, color=col,
                        capsize=3, ms=6)
        ax.plot([], [], mk, color=col, label=f"ours, {rd}")
    py = [yi for yi, p in zip(y, paper) if p is not None]
    ax.plot([p for p in paper if p is not None], py, "k*", ms=11, label="paper")
    ax.axvline(1.0, color="0.5", lw=1)
    ax.set_xscale("log")
    ax.set_xticks([0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.2])
    ax.get_xaxis().set_major_formatter(plt.matplotlib.ticker.ScalarFormatter())
    ax.set_yticks(y)
    ax.set_yticklabels(conds)
    ax.set_xlabel("E_p(VII) / E_p(IV)   (below 1: holding the barycenter is cheaper)")
    ax.legend(loc="lower left", fontsize=8, ncol=3)
    ax.grid(True, axis="x", alpha=0.3)
    return figs.save(fig, "answer.png")
