# SPDX-License-Identifier: Apache-2.0
"""exp2: the payload sweep in conditions A, B, C: the paired energy ratio VII/IV and the EE
error of IV and VII against payload, the paper's 10 kg values as stars, one y-axis per
figure."""
import numpy as np

from ..keys import BARY, COND_EXP2_TEXT, VEH
from .common import CASE_COLORS, err_bars, est_bars, paper_marks, plt

CONDS = ("A", "B", "C")


def _offset(pays, dx):
    span = (max(pays) - min(pays)) if len(pays) > 1 else 1.0
    return np.asarray(pays, float) + dx * span


def _title(k, n):
    return COND_EXP2_TEXT[k] + (f"\n95 % CI over {n} seeds" if n > 1 else "\none run each")


def payload_ratio(figs, pays, ratios, paper, n_seeds):
    """ratios: {cond: [inference.Estimate of E_p(VII)/E_p(IV) per payload]}; paper: {cond:
    (payload [kg], ratio)} where the paper prints one; n_seeds: {cond: seeds per payload}."""
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.3), sharey=True)
    for ax, k in zip(axes, CONDS):
        y, yerr = est_bars(ratios[k])
        ax.errorbar(pays, y, yerr=yerr, fmt="d-", color=CASE_COLORS[BARY], lw=2, capsize=3,
                    label="ours, paired per seed")
        if k in paper:
            paper_marks(ax, [paper[k][0]], [paper[k][1]], "paper (Tables XI–XIII)")
        ax.axhline(1.0, color="0.5", lw=1, ls=":")
        ax.set_title(_title(k, n_seeds[k]))
        ax.set_xlabel("payload m_P [kg]")
        ax.legend()
    axes[0].set_ylabel("E_p(VII) / E_p(IV) [-]")
    fig.suptitle("Experiment 2: energy of barycenter (VII) over vehicle (IV) stabilization vs "
                 "payload; below 1: holding the barycenter is cheaper")
    fig.tight_layout()
    return figs.save(fig, "exp2_payload_energy.png")


def payload_error(figs, pays, dists, paper, n_seeds):
    """dists: {(case, cond): [Dist of the mean EE error [m] per payload]}; paper: {(case, cond):
    (payload [kg], error [mm])} where printed."""
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.3), sharey=True)
    for ax, k in zip(axes, CONDS):
        for c, mk, dx in ((VEH, "o-", -0.008), (BARY, "s-", 0.008)):
            y, yerr = err_bars(dists[(c, k)], 1e3)
            ax.errorbar(_offset(pays, dx), y, yerr=yerr, fmt=mk, color=CASE_COLORS[c], lw=2,
                        capsize=3,
                        label=f"{c} ({'vehicle' if c == VEH else 'barycenter'} stab.)")
        for c in (VEH, BARY):
            if (c, k) in paper:
                paper_marks(ax, [paper[(c, k)][0]], [paper[(c, k)][1]],
                            f"paper, {c} (Tables XI, XII)")
        ax.set_title(_title(k, n_seeds[k]))
        ax.set_xlabel("payload m_P [kg]")
        ax.legend(fontsize=8)
    axes[0].set_yscale("log")
    axes[0].set_ylabel("mean EE error ε [mm] (log)")
    fig.suptitle("Experiment 2: EE error vs payload, vehicle (IV) vs barycenter (VII)")
    fig.tight_layout()
    return figs.save(fig, "exp2_payload_error.png")
