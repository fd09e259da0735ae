# SPDX-License-Identifier: Apache-2.0
"""beyond: the figures of "Beyond the paper" (gravity × stabilization × allocator, the
barycenter/vehicle ratio per gravity, the energy-optimal allocation's saving)."""
import numpy as np

from ..keys import BARY, CASES, VEH
from .common import CASE_COLORS, err_bars, plt

ALLOC_STYLE = {0: ("o", "-"), 1: ("s", "--")}   # allocator index → marker, line style
ALLOC_COLORS = ["#1f77b4", "#d62728"]
GRAVITY_COLORS = ["#7f7f7f", "#1f77b4", "#d62728", "#2ca02c", "#9467bd"]
LOG_SPAN = 20.0   # a panel whose positive means span more than this factor gets a log axis
METRICS = [("att", 1e3, "max attitude error [mrad]"), ("err", 1e3, "mean EE error [mm]"),
           ("en", 1e-3, "thruster energy E_el [kJ]")]


def _x(pays, i, n):
    """Payloads offset a little per series so that error bars do not overlap."""
    span = (max(pays) - min(pays)) if len(pays) > 1 else 1.0
    return np.asarray(pays, float) + (i - 0.5 * (n - 1)) * 0.012 * span


def _series(ax, pays, dists, scale, i, n, color, style, label):
    """One series with its CI bars; returns its means."""
    y, yerr = err_bars(dists, scale)
    ax.errorbar(_x(pays, i, n), y, yerr=yerr, fmt=style[0], ls=style[1], color=color, lw=1.8,
                capsize=3, ms=5, label=label)
    return y


def _auto_log(ax, means):
    """A log y axis when the positive means span more than LOG_SPAN; returns whether."""
    v = np.asarray([m for m in np.ravel(means) if np.isfinite(m) and m > 0], float)
    if v.size and v.max() / v.min() > LOG_SPAN:
        ax.set_yscale("log")
        return True
    return False


def gravity_metrics(figs, gravs, glabels, pays, allocs, dists, n_seeds):
    """dists: {(gravity index, case, allocator index, metric): [Dist per payload]}; one column
    per gravity, one row per metric (attitude, EE error, energy), each row on one y-axis (log
    when its means span more than LOG_SPAN)."""
    fig, axes = plt.subplots(3, len(gravs), figsize=(4.6 * len(gravs), 10.5), squeeze=False,
                             sharey="row")
    for row, (m, scale, ylab) in enumerate(METRICS):
        means = []
        for j in range(len(gravs)):
            ax = axes[row][j]
            k = 0
            for c in (VEH, BARY):
                for ai, a in enumerate(allocs):
                    means.append(_series(ax, pays, dists[(j, c, ai, m)], scale, k,
                                         2 * len(allocs), CASE_COLORS[c], ALLOC_STYLE[ai % 2],
                                         f"{c} ({'vehicle' if c == VEH else 'barycenter'}), {a}"))
                    k += 1
            if row == 0:
                ax.set_title(glabels[j])
            if row == 2:
                ax.set_xlabel("payload m_P (trimmed for) [kg]")
        axes[row][0].set_ylabel(ylab + (" (log)" if _auto_log(axes[row][0], means) else ""))
    h, lab = axes[0][0].get_legend_handles_labels()
    fig.legend(h, lab, loc="lower center", ncol=2, fontsize=9.5, frameon=False,
               bbox_to_anchor=(0.5, -0.05))
    fig.suptitle(f"Beyond the paper: gravity × stabilization × allocator (unsteady flow; mean "
                 f"and 95 % CI over {n_seeds} seeds)")
    fig.tight_layout()
    return figs.save(fig, "beyond_gravity_metrics.png")


def gravity_ratio(figs, glabels, pays, allocs, paireds, n_seeds):
    """paireds: {(gravity index, allocator index): [stats.Paired per payload]} of E(VII)/E(IV)."""
    fig, axes = plt.subplots(1, len(glabels), figsize=(4.6 * len(glabels), 4.2), squeeze=False,
                             sharey=True)
    for j, ax in enumerate(axes[0]):
        for ai, a in enumerate(allocs):
            _series(ax, pays, [p.dist for p in paireds[(j, ai)]], 1.0, ai, len(allocs),
                    ALLOC_COLORS[ai % 2], ALLOC_STYLE[ai % 2], a)
        ax.axhline(1.0, color="k", lw=1)
        ax.set_title(glabels[j])
        ax.set_xlabel("payload m_P [kg]")
        ax.legend()
    axes[0][0].set_ylabel("E_el(VII) / E_el(IV) [-], paired per seed")
    fig.suptitle(f"Is holding the barycenter cheaper than holding the vehicle? Below 1: yes "
                 f"(mean and 95 % CI over {n_seeds} seeds)")
    fig.tight_layout()
    return figs.save(fig, "beyond_gravity_ratio.png")


def allocation_saving(figs, paper_sav, cond_labels, grav_sav, glabels, pays):
    """paper_sav: {(case, condition index): Saving} (experiment 1's cases); grav_sav:
    {(gravity index, case): [Saving per payload]}; savings in % of the pseudoinverse's
    energy."""
    fig, axes = plt.subplots(1, 2, figsize=(14, 4.6))
    x, wdt = np.arange(len(CASES)), 0.38
    for k, lab in enumerate(cond_labels):
        dists = [paper_sav[(c, k)].dist if (c, k) in paper_sav else None for c in CASES]
        y, yerr = err_bars([d for d in dists if d is not None], 100.0)
        xs = [xi for xi, d in zip(x, dists) if d is not None]
        axes[0].bar(np.asarray(xs) + (k - 0.5) * wdt, y, wdt, yerr=yerr, capsize=3, label=lab)
    axes[0].axhline(0.0, color="k", lw=1)
    axes[0].set_xticks(x, CASES)
    axes[0].set_xlabel("case (Table X), g = 0, 10 kg")
    axes[0].set_ylabel("saving 1 − E(min_abs_thrust)/E(pseudoinverse) [%]")
    axes[0].set_title("The paper's experiment 1")
    axes[0].legend()
    n = 2 * len(glabels)
    k = 0
    for j, gl in enumerate(glabels):
        for c in (VEH, BARY):
            sv = grav_sav.get((j, c))
            if sv:
                _series(axes[1], pays, [s.dist for s in sv], 100.0, k, n,
                        GRAVITY_COLORS[j % len(GRAVITY_COLORS)], ("o" if c == VEH else "s",
                                                                  "-" if c == VEH else "--"),
                        f"{gl}, {c}")
            k += 1
    axes[1].axhline(0.0, color="k", lw=1)
    axes[1].set_xlabel("payload m_P [kg]")
    axes[1].set_title("Gravity campaign (unsteady flow)")
    axes[1].legend(fontsize=8)
    fig.suptitle("Energy saving of the least-Σ|T| allocation against the pseudoinverse, "
                 "paired per case and seed (mean and 95 % CI over seeds where seeded)")
    fig.tight_layout()
    return figs.save(fig, "beyond_allocation_saving.png")
