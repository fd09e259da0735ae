# SPDX-License-Identifier: Apache-2.0
"""flow: the flow amplitude sweep (experiment 1, condition b): case IV's ε against A_v with the
paper's 3.32 mm, and the paired ratio E_p(VII)/E_p(IV) in both readings with the paper's 0.625,
on shared log axes."""
import numpy as np

from .common import CASE_COLORS, plt


def sweep(figs, amps, eps, ratios, target_mm, paper_ratio, a_cal):
    """eps: [(mean, lo, hi)] of IV's ε [mm] per amplitude; ratios: {reading: [Estimate]}."""
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(13, 4.8))
    m = np.array([e[0] for e in eps])
    err = np.array([[e[0] - e[1], e[2] - e[0]] for e in eps]).T
    a1.errorbar(amps, m, yerr=np.abs(err), fmt="o-", color=CASE_COLORS["IV"], capsize=3,
                label="ours, case IV (mean, 95 % CI, 20 seeds)")
    a1.axhline(target_mm, color="k", ls="--", lw=1, label=f"paper, Table XII: {target_mm} mm")
    if np.isfinite(a_cal):
        a1.axvline(a_cal, color="0.4", ls=":", lw=1, label=f"calibrated A_v = {a_cal:.4f} m/s")
    a1.set_xscale("log")
    a1.set_yscale("log")
    a1.set_xlabel("flow amplitude A_v [m/s]")
    a1.set_ylabel("mean EE error ε [mm]")
    a1.set_title("Case IV's error against the flow amplitude")
    a1.legend()
    styles = {"same task": ("s-", CASE_COLORS["VIII"]), "same motion": ("o-", CASE_COLORS["VII"])}
    for rd, ests in ratios.items():
        y = np.array([e.estimate if e else np.nan for e in ests])
        lo = np.array([e.estimate - e.lo if e and e.has_ci else 0 for e in ests])
        hi = np.array([e.hi - e.estimate if e and e.has_ci else 0 for e in ests])
        fmt, col = styles[rd]
        a2.errorbar(amps, y, yerr=[lo, hi], fmt=fmt, color=col, capsize=3,
                    label=f"ours, {rd} (paired per seed, 95 % CI)")
    a2.axhline(paper_ratio, color="k", ls="--", lw=1, label=f"paper, Table XII: {paper_ratio:.3f}")
    a2.axhline(1.0, color="0.6", lw=0.8)
    if np.isfinite(a_cal):
        a2.axvline(a_cal, color="0.4", ls=":", lw=1)
    a2.set_xscale("log")
    a2.set_xlabel("flow amplitude A_v [m/s]")
    a2.set_ylabel("E_p(VII) / E_p(IV)")
    a2.set_title("Barycenter vs vehicle against the flow amplitude")
    a2.legend()
    return figs.save(fig, "exp1_flow_amplitude.png")
