# SPDX-License-Identifier: Apache-2.0
"""beyond_lead: the figure of the feedforward lead (attitude, EE error and energy with the lead
off and on, both allocators, per gravity and stabilization; and the predicted and realised
saving of Σ|T|^1.5 of min_power against the pseudoinverse, lead off and on)."""
import numpy as np

from .common import err_bars, plt

SERIES_STYLE = [("#1f77b4", "o", "none"), ("#1f77b4", "o", None), ("#d62728", "s", "none"),
                ("#d62728", "s", None)]  # (alloc, lead) off/on: open/filled markers
METRICS = [("att", 1e3, "max attitude error [mrad] (log)"), ("err", 1e3, "mean EE error [mm] (log)"),
           ("en", 1e-3, "thruster energy E_el [kJ]")]


LEAD_COLORS = ["#7f7f7f", "#2ca02c"]   # lead off, on


def _savings_panel(ax, x, savings):
    """savings: {(kind, lead index): [Dist per category]}, kind "potential" (hatched) or
    "realised" (solid); fractions drawn in %."""
    wdt = 0.2
    i = 0
    for li, lead in enumerate(("off", "on")):
        for kind, klab in (("potential", "predicted (static potential)"),
                           ("realised", "realised, paired")):
            ds = savings.get((kind, li)) or []
            keep = [(xi, d) for xi, d in zip(x, ds) if d is not None and d.n]
            if keep:
                y, yerr = err_bars([d for _, d in keep], 100.0)
                pot = kind == "potential"
                ax.bar(np.asarray([xi for xi, _ in keep]) + (i - 1.5) * wdt, y, wdt, yerr=yerr,
                       capsize=3, color=LEAD_COLORS[li], alpha=0.45 if pot else 1.0,
                       hatch="//" if pot else None, edgecolor=LEAD_COLORS[li],
                       label=f"lead {lead}: {klab}")
            i += 1
    ax.axhline(0.0, color="k", lw=1)
    ax.set_ylabel("saving of ∫Σ|T|^1.5 dt, min_power vs pinv [%]")
    ax.legend(fontsize=8)


def lead_metrics(figs, cond_labels, series, dists, n_seeds, savings=None):
    """cond_labels: x categories (gravity, case); series: [(allocator, lead) label]; dists:
    {(metric, series index): [Dist per category]} of the unsteady runs; savings (optional,
    a fourth panel): {(kind, lead index): [Dist per category]} of min_power against the
    pseudoinverse, kind "potential" or "realised"."""
    npan = 4 if savings else 3
    fig, axes = plt.subplots(1, npan, figsize=(5 * npan, 4.6))
    x = np.arange(len(cond_labels), dtype=float)
    if savings:
        _savings_panel(axes[3], x, savings)
        axes[3].set_xticks(x)
        axes[3].set_xticklabels(cond_labels, rotation=20)
    for ax, (m, scale, ylab) in zip(axes, METRICS):
        for i, label in enumerate(series):
            color, marker, face = SERIES_STYLE[i % len(SERIES_STYLE)]
            y, yerr = err_bars(dists[(m, i)], scale)
            ax.errorbar(x + (i - 1.5) * 0.12, y, yerr=yerr, fmt=marker, color=color,
                        mfc=face if face else color, ms=6, capsize=3, ls="none", label=label)
        ax.set_xticks(x)
        ax.set_xticklabels(cond_labels, rotation=20)
        ax.set_ylabel(ylab)
        if m != "en":
            ax.set_yscale("log")
    axes[0].legend(fontsize=8.5)
    fig.suptitle("Feedforward lead (docs/MODEL.md §7.5), 10 kg, trimmed, unsteady flow: mean "
                 f"and 95 % CI over {n_seeds} seeds (open: lead off, filled: on)")
    fig.tight_layout()
    return figs.save(fig, "beyond_lead_metrics.png")
