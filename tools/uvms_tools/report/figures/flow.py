# SPDX-License-Identifier: Apache-2.0
"""flow: a sweep of one unprinted flow parameter (experiment 1, condition b: the amplitude A_v
or the number of harmonics n): case IV's ε against it with the paper's 3.32 mm, and the paired
ratio E_p(VII)/E_p(IV) in both readings with the paper's 0.625, on log axes."""
import numpy as np

from .common import CASE_COLORS, est_bars, plt


PARAMS = {"A_v": ("flow amplitude A_v [m/s]", "the flow amplitude", "exp1_flow_amplitude.png"),
          "n": ("number of harmonics n [-]", "the number of harmonics",
                "exp1_flow_harmonics.png")}


def sweep(figs, amps, eps, ratios, target_mm, paper_ratio, a_cal, param="A_v"):
    """amps: the swept values of param (a PARAMS key); eps: [(mean, lo, hi)] of IV's ε [mm] per
    value; ratios: {reading: [Estimate]}; a_cal: the calibrated value (NaN: none drawn)."""
    xlabel, what, fname = PARAMS[param]
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(13, 4.8))
    m = np.array([e[0] for e in eps])
    err = np.array([[e[0] - e[1], e[2] - e[0]] for e in eps]).T
    a1.errorbar(amps, m, yerr=np.abs(err), fmt="o-", color=CASE_COLORS["IV"], capsize=3,
                label="ours, case IV (mean, 95 % CI, 20 seeds)")
    a1.axhline(target_mm, color="k", ls="--", lw=1, label=f"paper, Table XII: {target_mm} mm")
    if np.isfinite(a_cal):
        a1.axvline(a_cal, color="0.4", ls=":", lw=1, label=f"calibrated {param} = {a_cal:.4g}")
    a1.set_xscale("log")
    a1.set_yscale("log")
    a1.set_xlabel(xlabel)
    a1.set_ylabel("mean EE error ε [mm]")
    a1.set_title(f"Case IV's error against {what}")
    a1.legend()
    styles = {"same task": ("s-", CASE_COLORS["VIII"]), "same motion": ("o-", CASE_COLORS["VII"])}
    for rd, ests in ratios.items():
        y, yerr = est_bars(ests)
        fmt, col = styles[rd]
        a2.errorbar(amps, y, yerr=yerr, fmt=fmt, color=col, capsize=3,
                    label=f"ours, {rd} (paired per seed, 95 % CI)")
    a2.axhline(paper_ratio, color="k", ls="--", lw=1, label=f"paper, Table XII: {paper_ratio:.3f}")
    a2.axhline(1.0, color="0.6", lw=0.8)
    if np.isfinite(a_cal):
        a2.axvline(a_cal, color="0.4", ls=":", lw=1)
    a2.set_xscale("log")
    a2.set_xlabel(xlabel)
    a2.set_ylabel("E_p(VII) / E_p(IV)")
    a2.set_title(f"Barycenter vs vehicle against {what}")
    a2.legend()
    return figs.save(fig, fname)
