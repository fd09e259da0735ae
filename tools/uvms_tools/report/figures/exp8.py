# SPDX-License-Identifier: Apache-2.0
"""exp8: the analytic impulse ratio [89], its limits, and the simulated energy ratio."""
import numpy as np

from uvms_tools.models import analytic

from ..keys import BARY
from ..num import isnum
from ..text.fmt import f, g
from .common import CASE_COLORS, plt


def _left(ax, pays, etas, sim, r_sim, par):
    eg = np.linspace(0.0, max(etas + [0.05]) * 1.05, 200)
    ax.plot(eg, analytic.ratio(eg, r_sim, **par), lw=2, color="k",
            label=r"analytic impulse ratio $\tilde D_0/\tilde F_0$ [89], $r_\Delta$ = "
                  + f"{f(r_sim, 2)} m")
    ax.plot(eg, analytic.ratio_exact_reaction(eg, r_sim, **par), lw=1.5, ls="--", color="gray",
            label="analytic with the exact held-vehicle reaction m_P·r̈")
    ax.plot(etas, sim, "o-", color=CASE_COLORS[BARY], lw=2, ms=6,
            label="simulated ENERGY ratio E(VII)/E(IV), full arm (a different quantity)")
    last = -1.0
    for p, et, s in zip(pays, etas, sim):
        if isnum(s) and et - last > 0.03 * max(etas + [1e-9]):
            last = et
            ax.annotate(f"{f(p, 0)} kg", (et, s), textcoords="offset points", xytext=(4, 6),
                        fontsize=8)
    ax.set_xlabel("payload fraction η = m_P/(m0 + m_P) [-]")
    ax.set_ylabel("ratio barycenter / vehicle [-]")
    ax.set_title("Simulated energy ratio vs analytic impulse ratio (not like for like)")
    ax.legend(fontsize=8)


def _right(ax, r_sim, par, lim):
    ef = np.linspace(0.0, 1.0, 300)
    for rd, ls in ((r_sim, "-"), (lim["r_max"], "-.")):
        ax.plot(ef, analytic.ratio(ef, rd, **par), lw=2, ls=ls,
                label=f"analytic [89], r_Δ = {f(rd, 2)} m")
    ax.plot([1.0], [1.0], "k*", ms=12,
            label=f"travel limit: ratio = 1 at η → 1 for r_Δ* = {f(lim['r_star'], 3)} m")
    ax.axhline(1.0, color="gray", lw=1)
    if lim["eta_star"] < 1:
        ax.axvline(lim["eta_star"], color="#d62728", lw=1.5, ls="--",
                   label=f"payload limit of [89] at r_Δ = {f(lim['r_max'], 2)} m: η* = "
                         f"{f(lim['eta_star'], 3)} (m_P = {f(lim['mp_star'], 1)} kg)")
    ax.set_xlabel("payload fraction η [-]")
    ax.set_ylabel(r"$\tilde D_0/\tilde F_0$ [-]")
    ax.set_ylim(0, 2.0)
    ax.set_title("Analytic ratio over η ∈ [0, 1]: payload and travel limits of [89]")
    ax.legend(fontsize=8.5, loc="upper left")


def analytic_ratio(figs, pays, etas, sim, r_sim, par, lim):
    """pays, etas: payloads and their η; sim: simulated E(VII)/E(IV) per payload; par: the
    model's parameters; lim: analyses.exp8.limits."""
    fig, axes = plt.subplots(1, 2, figsize=(14, 4.8))
    _left(axes[0], pays, etas, sim, r_sim, par)
    _right(axes[1], r_sim, par, lim)
    fig.suptitle(f"Experiment 8: simplified analytic model (docs/MODEL.md §9 item 8); "
                 f"ρ = {g(par['rho'], 4)} kg/m³, CD0 = {g(par['cd0'], 3)}, "
                 f"A0 = {g(par['a0_m2'], 3)} m², m0 = {g(par['m0_kg'], 4)} kg (logged config)")
    fig.tight_layout()
    return figs.save(fig, "exp8_analytic_ratio.png")
