# SPDX-License-Identifier: Apache-2.0
"""exp8b: the like-for-like impulse ratio against the analytic models."""
import numpy as np

from ..analyses import exp8b as a8b
from ..text.fmt import f, g
from .common import plt


def impulse_ratio(figs, rows, par):
    """rows: analyses.exp8b.analyse; par: its parameters."""
    fig, ax = plt.subplots(figsize=(9.5, 4.8))
    ok = a8b.loaded(rows)
    xs = [d["eta"] for d in ok]
    eg = np.linspace(0.0, max(xs + [0.05]) * 1.08, 200)
    cur = a8b.model_curves(par, eg)
    ax.plot(eg, cur["r89"], "k-", lw=2, label=r"analytic $\tilde D_0/\tilde F_0$ [89]")
    ax.plot(eg, cur["exact"], "--", color="gray", lw=1.5,
            label="[89] with the exact held reaction m_P·r̈")
    ax.plot(eg, cur["pred"], "-.", color="#2ca02c", lw=2,
            label=f"model + vehicle added mass ({g(par['m_add_kg'], 3)} kg) + "
                  "barycenter-referenced line")
    ax.plot(eg, cur["pred0"], ":", color="#2ca02c", lw=1.8,
            label="model + barycenter-referenced line + exact reaction, no added mass")
    ax.plot(xs, [d["ratio_sim"] for d in ok], "o", color="#d62728", ms=7,
            label="simulated ∫|F_thr|(VII) / ∫|F_thr|(IV)")
    ax.plot(xs, [d["ratio_des"] for d in ok], "x", color="#9467bd", ms=7,
            label="simulated, desired force F_P0")
    last = -1.0
    for d in ok:
        if d["eta"] - last > 0.03 * max(xs + [1e-9]):
            last = d["eta"]
            ax.annotate(f"{f(d['payload_kg'], 0)} kg", (d["eta"], d["ratio_sim"]),
                        textcoords="offset points", xytext=(5, -12), fontsize=8)
    ax.set_xlabel("payload fraction η = m_P/(m0 + m_P) [-]")
    ax.set_ylabel("impulse ratio barycenter / vehicle [-]")
    ax.set_title("Experiment 8b: integrated thrust force, massless dragless arm (like for like)")
    ax.legend(fontsize=8.5, loc="upper left")
    ax.set_ylim(bottom=0)
    fig.tight_layout()
    return figs.save(fig, "exp8b_impulse_ratio.png")
