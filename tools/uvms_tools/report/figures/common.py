# SPDX-License-Identifier: Apache-2.0
"""common: the figure writer, the report's style and colours, error bars from distributions."""
import os

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

CASE_COLORS = {"I": "#7f7f7f", "II": "#bcbd22", "III": "#17becf", "IV": "#1f77b4",
               "V": "#9467bd", "VI": "#8c564b", "VII": "#d62728", "VIII": "#ff7f0e"}
AXIS_COLORS = ["#1f77b4", "#2ca02c", "#d62728"]

plt.rcParams.update({
    "font.size": 11, "axes.titlesize": 11.5, "axes.labelsize": 11, "legend.fontsize": 9,
    "xtick.labelsize": 10, "ytick.labelsize": 10, "figure.dpi": 150, "savefig.dpi": 150,
    "axes.grid": True, "grid.alpha": 0.3,
})


class Figures:
    """Writes OUT/figures/*.png and keeps the names written, in order."""

    def __init__(self, out_dir):
        self.dir = os.path.join(out_dir, "figures")
        os.makedirs(self.dir, exist_ok=True)
        self.written = []

    def save(self, fig, name):
        path = os.path.join(self.dir, name)
        fig.savefig(path, dpi=150, bbox_inches="tight")
        plt.close(fig)
        self.written.append(name)
        return f"figures/{name}"


def err_bars(dists, scale=1.0):
    """(means, 2×n asymmetric error array of the 95 % CI; zeros without a CI)."""
    means = np.array([d.mean * scale if d.n else np.nan for d in dists], float)
    lo = np.array([(d.mean - d.lo) * scale if d.has_ci else 0.0 for d in dists], float)
    hi = np.array([(d.hi - d.mean) * scale if d.has_ci else 0.0 for d in dists], float)
    return means, np.vstack([np.abs(lo), np.abs(hi)])


def est_bars(ests):
    """(estimates, 2×n asymmetric error array of the CI) of inference.Estimates (None: NaN;
    deterministic, no CI: zero bars)."""
    y = np.array([e.estimate if e else np.nan for e in ests], float)
    lo = np.array([e.estimate - e.lo if e and e.has_ci else 0.0 for e in ests], float)
    hi = np.array([e.hi - e.estimate if e and e.has_ci else 0.0 for e in ests], float)
    return y, np.vstack([np.abs(lo), np.abs(hi)])


def paper_marks(ax, x, y, label="paper"):
    """The paper's values as black stars (NaN: not printed, not drawn)."""
    y = np.asarray(y, float)
    ok = np.isfinite(y)
    if ok.any():
        ax.plot(np.asarray(x, float)[ok], y[ok], "k*", ms=11, zorder=5, label=label)
