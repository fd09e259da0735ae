# SPDX-License-Identifier: Apache-2.0
"""exp1: the eight cases of Table X, EE error over time and energy/error bars."""
import math

import numpy as np

from ..keys import BARY, CASES, COND_EXP1_TEXT, VEH
from ..num import isnum
from .common import CASE_COLORS, err_bars, est_bars, paper_marks, plt


def _case_label(c, meaning):
    return (f"{c}: {meaning.get(c, '?')}"
            + (" — vehicle stabilization" if c == VEH else "")
            + (" — barycenter stabilization" if c == BARY else ""))


def ee_error(figs, series, bands, meaning, drawn_seed, conds):
    """series: {(case, cond): (t, ε)}; bands: {case: (t, lo, hi, n seeds)} (unsteady);
    drawn_seed: {cond: seed of the runs drawn}."""
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.6), sharey=True)
    for ax, k in zip(axes, conds):
        for c in CASES:
            if (c, k) not in series:
                continue
            t, eps = series[(c, k)]
            y = np.where(eps > 0, eps * 1e3, np.nan)
            lw = 2.4 if c in (VEH, BARY) else 1.3
            ax.plot(t, y, color=CASE_COLORS[c], lw=lw, label=_case_label(c, meaning))
            if k == "unsteady" and c in bands:
                tb, lo, hi, nb = bands[c]
                ax.fill_between(tb, np.maximum(lo * 1e3, 1e-6), hi * 1e3,
                                color=CASE_COLORS[c], alpha=0.18, lw=0)
        ax.set_yscale("log")
        ax.set_title(f"EE error, {COND_EXP1_TEXT[k]}"
                     + (f"\nlines: seed {drawn_seed.get(k)}; shaded: range over "
                        f"{max((b[3] for b in bands.values()), default=0)} seeds (IV, VII)"
                        if k == "unsteady" and bands else ""))
        ax.set_xlabel("time t [s]")
    late = [eps[t >= 0.1 * t[-1]] * 1e3 for t, eps in series.values() if len(t)]
    late = np.concatenate(late) if late else np.array([])
    late = late[late > 0]
    if late.size:
        axes[0].set_ylim(10 ** math.floor(math.log10(late.min())),
                         10 ** math.ceil(math.log10(late.max())))
    axes[0].set_ylabel("EE error ε = |p_EE − p̂_EE| [mm] (log)")
    h, lab = axes[0].get_legend_handles_labels()
    fig.legend(h, lab, loc="lower center", ncol=2, fontsize=9.5, frameon=False,
               bbox_to_anchor=(0.5, -0.16))
    fig.suptitle("Experiment 1: end-effector error of the eight cases "
                 "(docs/MODEL.md §9 Table X, §10)")
    fig.tight_layout()
    return figs.save(fig, "exp1_ee_error.png")


def ratio_vs_paper(figs, ratios, eps, paper_ratio, paper_eps, conds):
    """Paired per-seed ratios E_p(case)/E_p(IV) per reading (left) and mean ε (right) per case,
    each condition in its own row of panels on a shared y-axis, the paper's values as stars.
    ratios: {(cond, reading): [Estimate or None per case]}; eps: {(cond, reading): [Dist]};
    paper_ratio, paper_eps: {cond: [value per case]}."""
    fig, axes = plt.subplots(len(conds), 2, figsize=(13, 3.6 * len(conds)), sharey="col")
    axes = np.atleast_2d(axes)
    x = np.arange(len(CASES))
    style = {"same task": ("s", "#ff7f0e", -0.12), "same motion": ("o", "#d62728", 0.12)}
    for row, k in enumerate(conds):
        for rd, (mk, col, off) in style.items():
            y, yerr = est_bars(ratios.get((k, rd), []))
            axes[row, 0].errorbar(x + off, y, yerr=yerr, fmt=mk, color=col, capsize=3,
                                  label=f"ours, {rd}")
            m, err = err_bars(eps.get((k, rd), []), 1e3)
            axes[row, 1].errorbar(x + off, m, yerr=err, fmt=mk, color=col, capsize=3,
                                  label=f"ours, {rd}")
        paper_marks(axes[row, 0], x, paper_ratio[k])
        paper_marks(axes[row, 1], x, paper_eps[k])
        axes[row, 0].axhline(1.0, color="0.6", lw=0.8)
        axes[row, 0].set_ylabel("E_p(case) / E_p(IV)")
        axes[row, 1].set_ylabel("mean EE error ε [mm] (log)")
        axes[row, 1].set_yscale("log")
        for ax in axes[row]:
            ax.set_xticks(x, CASES)
            ax.set_title(COND_EXP1_TEXT[k])
        axes[row, 0].legend(fontsize=8, loc="upper left")
    axes[-1, 0].set_xlabel("case (Table X)")
    axes[-1, 1].set_xlabel("case (Table X)")
    fig.suptitle("Experiment 1 against the paper's Tables XI and XII: energy ratio to case IV "
                 "(paired per seed, 95 % CI) and mean EE error")
    fig.tight_layout()
    return figs.save(fig, "exp1_energy_error_bars.png")
