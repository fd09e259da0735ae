# SPDX-License-Identifier: Apache-2.0
"""beyond_lead: the figure of the feedforward lead (attitude, EE error and energy with the lead
off and on, both allocators, per gravity and stabilization)."""
import numpy as np

from .common import err_bars, plt

SERIES_STYLE = [("#1f77b4", "o", "none"), ("#1f77b4", "o", None), ("#d62728", "s", "none"),
                ("#d62728", "s", None)]  # (alloc, lead) off/on: open/filled markers
METRICS = [("att", 1e3, "max attitude error [mrad] (log)"), ("err", 1e3, "mean EE error [mm] (log)"),
           ("en", 1e-3, "thruster energy E_el [kJ]")]


def lead_metrics(figs, cond_labels, series, dists, n_seeds):
    """cond_labels: x categories (gravity, case); series: [(allocator, lead) label]; dists:
    {(metric, series index): [Dist per category]} of the unsteady runs."""
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    x = np.arange(len(cond_labels), dtype=float)
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
