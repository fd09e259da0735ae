# SPDX-License-Identifier: Apache-2.0
"""beyond: the figures of "Beyond the paper" (gravity × stabilization × allocator, the
barycenter/vehicle ratio per gravity, the minimum-power allocation's predicted and realised
savings)."""
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


COND_COLORS = ["#1f77b4", "#ff7f0e"]   # experiment 1's conditions (a), (b)
SAVING_KINDS = [("potential", "predicted (static potential)"), ("realised", "realised, paired")]


def _bars(ax, xs, dists, wdt, **kw):
    """Bars (in %) with their CI of the measured Dists (None or empty ones left out)."""
    keep = [(x, d) for x, d in zip(xs, dists) if d is not None and d.n]
    if not keep:
        return
    y, yerr = err_bars([d for _, d in keep], 100.0)
    ax.bar([x for x, _ in keep], y, wdt, yerr=yerr, capsize=3, **kw)


def _paper_panel(ax, paper, cond_labels, kinds):
    """Experiment 1's cases on x; per condition and kind one bar (hatched: the potential)."""
    x = np.arange(len(CASES), dtype=float)
    nb = len(cond_labels) * len(kinds)
    wdt = 0.8 / max(nb, 1)
    i = 0
    for k, lab in enumerate(cond_labels):
        for kind, klab in kinds:
            pot = kind == "potential"
            _bars(ax, x + (i - 0.5 * (nb - 1)) * wdt, [paper.get((kind, c, k)) for c in CASES],
                  wdt, color=COND_COLORS[k % 2], alpha=0.45 if pot else 1.0,
                  hatch="//" if pot else None, edgecolor=COND_COLORS[k % 2],
                  label=f"{lab}" + (f": {klab}" if len(kinds) > 1 else ""))
            i += 1
    ax.axhline(0.0, color="k", lw=1)
    ax.set_xticks(x, CASES)
    ax.set_xlabel("case (Table X), g = 0, 10 kg, feedforward lead on")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=8)


def _gravity_panel(ax, grav, glabels, pays, kinds):
    """Per gravity and case, one series per kind against payload (open markers, dotted: the
    potential; filled, solid: the realised saving or the energy saving)."""
    n = 2 * len(glabels) * len(kinds)
    k = 0
    for j, gl in enumerate(glabels):
        color = GRAVITY_COLORS[j % len(GRAVITY_COLORS)]
        for c in (VEH, BARY):
            for kind, klab in kinds:
                ds = grav.get((kind, j, c))
                if ds:
                    pot = kind == "potential"
                    y, yerr = err_bars(ds, 100.0)
                    ax.errorbar(_x(pays, k, n), y, yerr=yerr, fmt="o" if c == VEH else "s",
                                ls=":" if pot else ("-" if c == VEH else "--"), color=color,
                                mfc="none" if pot else color, lw=1.6, capsize=3, ms=5,
                                label=f"{gl}, {c}" + (f": {klab}" if len(kinds) > 1 else ""))
                k += 1
    ax.axhline(0.0, color="k", lw=1)
    ax.set_xlabel("payload m_P [kg]")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=7)


def allocation_saving(figs, paper, cond_labels, grav, glabels, pays):
    """min_power against the pseudoinverse. paper: {(kind, case, condition index): Dist}
    (experiment 1's cases); grav: {(kind, gravity index, case): [Dist per payload]}; kind
    "potential" (static potential of Σ|T|^1.5), "realised" (the paired saving of Σ|T|^1.5) or
    "energy" (the paired saving of E_el); fractions, drawn in %. Top row: the predicted and
    the realised saving of the cost the allocator minimises; bottom row: the energy saving."""
    fig, axes = plt.subplots(2, 2, figsize=(14, 9.2), squeeze=False)
    _paper_panel(axes[0][0], paper, cond_labels, SAVING_KINDS)
    _paper_panel(axes[1][0], paper, cond_labels, [("energy", "")])
    _gravity_panel(axes[0][1], grav, glabels, pays, SAVING_KINDS)
    _gravity_panel(axes[1][1], grav, glabels, pays, [("energy", "")])
    axes[0][0].set_ylabel("saving of ∫Σ|T|^1.5 dt [%]")
    axes[1][0].set_ylabel("saving 1 − E_el(min_power)/E_el(pseudoinverse) [%]")
    axes[0][0].set_title("The paper's experiment 1 with the lead: Σ|T|^1.5")
    axes[1][0].set_title("The paper's experiment 1 with the lead: electrical energy")
    axes[0][1].set_title("Gravity campaign (unsteady flow): Σ|T|^1.5")
    axes[1][1].set_title("Gravity campaign (unsteady flow): electrical energy")
    fig.suptitle("Minimum-power allocation (least Σ|T|^1.5) against the pseudoinverse, paired "
                 "per case and seed (mean and 95 % CI over seeds where seeded; hatched / open: "
                 "static potential)")
    fig.tight_layout()
    return figs.save(fig, "beyond_allocation_saving.png")
