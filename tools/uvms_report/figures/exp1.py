# SPDX-License-Identifier: Apache-2.0
"""exp1: the eight cases of Table X, EE error over time and energy/error bars."""
import math

import numpy as np

from ..keys import BARY, CASES, COND_EXP1_TEXT, VEH
from ..num import isnum
from .common import CASE_COLORS, err_bars, plt


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


def energy_error_bars(figs, dists, conds):
    """dists: {(case, cond): (E_el Dist, E_p Dist, ε Dist)}."""
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.4))
    x = np.arange(len(CASES))
    wdt = 0.38
    for i, k in enumerate(conds):
        en, en_err = err_bars([dists[(c, k)][0] for c in CASES])
        er, er_err = err_bars([dists[(c, k)][2] for c in CASES], 1e3)
        lab = COND_EXP1_TEXT[k] + (" (mean, 95 % CI)" if np.any(en_err > 0) else "")
        axes[0].bar(x + (i - 0.5) * wdt, en, wdt, yerr=en_err, capsize=3, label=lab)
        for xi, v in zip(x, en):
            if isnum(v) and v == 0.0:
                axes[0].text(xi + (i - 0.5) * wdt, 0, "0 J", ha="center", va="bottom",
                             fontsize=8.5)
        axes[1].bar(x + (i - 0.5) * wdt, er, wdt, yerr=er_err, capsize=3, label=lab)
    for ax, yl, ttl in ((axes[0], "thruster energy E_el [J]", "Thruster energy per case"),
                        (axes[1], "mean EE error [mm] (log)", "Mean EE error per case")):
        ax.set_xticks(x, CASES)
        ax.set_xlabel("case (Table X)")
        ax.set_ylabel(yl)
        ax.set_title(ttl)
    axes[1].set_yscale("log")
    h, lab = axes[0].get_legend_handles_labels()
    fig.suptitle("Experiment 1: energy and mean EE error, cases I–VIII")
    fig.tight_layout()
    fig.legend(h, lab, loc="lower center", ncol=2, fontsize=9.5, frameon=False,
               bbox_to_anchor=(0.5, -0.08))
    return figs.save(fig, "exp1_energy_error_bars.png")
