# SPDX-License-Identifier: Apache-2.0
"""exp8: the simplified analytic model against the energies of the full system."""
import math

from ..analyses import exp8 as a8
from ..figures import exp8 as fig8
from ..keys import BARY, E_EL, KEY_CASE, KEY_PAYLOAD, VEH
from .common import img, open_experiment, status_mark
from .fmt import f, g, table

NAME = "exp8_analytic"


def _limit_text(eta, mp):
    return "none (η* ≥ 1)" if math.isinf(mp) else f"η* = {f(eta, 4)}, m_P* = {f(mp, 1)} kg"


def _rows(rep, e, pays, r_sim, par):
    rows, sim = [], []
    for p, (et, r89, rex) in zip(pays, a8.payload_rows(pays, r_sim, par)):
        pa = rep.add_comparison(NAME, f"exp8, line r_Δ = {f(r_sim, 2)} m", {KEY_PAYLOAD: p},
                                row={}, sub=f"{f(p, 0)} kg")
        sim.append(pa.dist.mean)
        rv, rb = e.one({KEY_CASE: VEH, KEY_PAYLOAD: p}), e.one({KEY_CASE: BARY, KEY_PAYLOAD: p})
        rows.append([f(p, 0), f(et, 4), f(rv and rv.get(E_EL), 1) + status_mark(rv),
                     f(rb and rb.get(E_EL), 1) + status_mark(rb), f(pa.dist.mean, 3),
                     f(r89, 4), f(rex, 4)])
    return rows, sim


def _parameters(par, r_sim, t_f, lim, chk, pmax):
    num, d_cf, f_cf = chk["num"], chk["drag"], chk["reaction"]
    return [f"Analytic parameters from the logged controller configuration of experiment 8: "
            f"ρ = {g(par['rho'], 4)} kg/m³, CD0 = {g(par['cd0'], 3)}, A0 = {g(par['a0_m2'], 3)} "
            f"m², m0 = {g(par['m0_kg'], 4)} kg (the vehicle mass, as docs/MODEL.md writes "
            f"[88–89]); "
            f"the simulated line has r_Δ = {f(r_sim, 3)} m over t_F = {f(t_f, 1)} s.", "",
            f"- Payload limit of [89] (ratio = 1) for the arm's maximum travel r_Δ = "
            f"{f(lim['r_max'], 2)} m (docs/MODEL.md §9 item 8): "
            f"{_limit_text(lim['eta_star'], lim['mp_star'])} — arithmetic of [89]; whether the "
            f"simulation supports it is experiment 8b's question.",
            f"- Payload limit of [89] for the simulated r_Δ = {f(r_sim, 2)} m: "
            f"{_limit_text(lim['eta_star_sim'], lim['mp_star_sim'])}.",
            f"- Travel limit of [89] as η → 1: r_Δ* = {f(lim['r_star'], 4)} m.",
            f"- Closed form vs numerical integration of the same motion (tools/analytic.py, "
            f"m_P = {f(pmax, 0)} kg): D̃0 {g(d_cf, 6)} vs {g(num['drag'], 6)} N·s, F̃0 "
            f"{g(f_cf, 6)} vs {g(num['reaction_free'], 6)} N·s (relative differences "
            f"{g(abs(num['drag'] / d_cf - 1), 2)}, {g(abs(num['reaction_free'] / f_cf - 1), 2)}).",
            f"- Which m0: docs/MODEL.md's F̃0 = m0·r_Δ·π·η/t_F is m0 times the free vehicle's "
            f"acceleration; the exact reaction on a held vehicle is m_P·r̈ (impulse "
            f"{g(num['reaction_held'], 6)} N·s here, vs F̃0 {g(f_cf, 6)} N·s), which replaces "
            f"m0 by m0 + m_P in [89] (dashed curve). This report follows docs/MODEL.md.", ""]


def section(rep):
    e, md = open_experiment(rep, NAME)
    if e is None:
        return md
    pays = e.values(KEY_PAYLOAD)
    cfg = e.logged_config(e.runs[0]) if e.runs else None
    if cfg is None:
        return md + ["*No log of experiment 8 could be read (the analytic parameters come "
                     "from the logged configuration).*", ""]
    par, r_sim, t_f, arm_kg = a8.params_from_config(cfg)
    lim = a8.limits(par, r_sim)
    rep.analytic_limits = (lim["eta_star"], lim["mp_star"], lim["r_star"], lim["r_max"])
    pmax = max(pays) if pays else 10.0
    chk = a8.closed_form_check(pmax, r_sim, t_f, par)
    rows, sim = _rows(rep, e, pays, r_sim, par)
    etas = [et for et, _, _ in a8.payload_rows(pays, r_sim, par)]
    img(md, fig8.analytic_ratio(rep.figs, pays, etas, sim, r_sim, par, lim),
        "Analytic drag/reaction impulse ratio and its limits; the simulated energy ratio of "
        "the full arm is drawn for reference only (see 8b for the like-for-like comparison).")
    md += ["**Not like for like.** The analytic model compares integrated forces of a "
           "massless, dragless arm; this experiment's simulated column is the ratio of "
           f"electrical energies of the full arm (links {f(arm_kg, 2)} kg with drag and added "
           "mass), a different quantity of a different system. Experiment 8b makes the "
           "comparison like for like.", ""]
    md += table(["m_P [kg]", "η", "E_el(IV) [J]", "E_el(VII) [J]", "simulated E(VII)/E(IV)",
                 "analytic [89] (impulses)", "analytic, exact reaction"], rows)
    return md + _parameters(par, r_sim, t_f, lim, chk, pmax)
