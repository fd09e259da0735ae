# SPDX-License-Identifier: Apache-2.0
"""exp8b: experiment 8 like for like (campaign exp8b_analytic_like).

The analytic model of SPEC §9 item 8 ([87–89], tools/analytic.py) compares INTEGRATED FORCES
of a massless, dragless arm carrying a point payload along a straight cosine-profile EE line:
the impulse of the drag on the vehicle under barycenter stabilization, D̃0, against the impulse
of the reaction that vehicle stabilization cancels, F̃0. Experiment 8 compares electrical
energies of the full arm, a different quantity of a different system. Experiment 8b runs the
simulation under the model's assumptions (arm.mass_scale = 0, arm.hydrodynamics = false,
payload only); this module compares like with like: the time integral of the produced thrust
force |F_thr(t)| (plant truth `thrust_force_N`; controller `force_des_N` as a cross-check) of
VII against IV, per payload, with D̃0/F̃0 and with analytic.like_for_like (the same model with
the two things the simulated system adds: the vehicle's added mass and the
barycenter-referenced line).

Pure functions on arrays, tested on synthetic signals (tests/tools/test_report_stats.py).
"""
import math

import numpy as np

from uvms_tools.models import analytic

from ..keys import BARY, VEH
from . import stats

# Relative agreement asked of the simulated impulse ratio with a model's ratio, per payload.
AGREE_REL = 0.10


def run_impulse(t_s, force_N):
    """∫|F(t)| dt [N·s] over the samples (trapezoidal); force_N: (n, 3) or (n,)."""
    return stats.impulse(np.asarray(t_s, float), np.asarray(force_N, float))


def analyse(runs, par):
    """runs: {(case, payload_kg): dict(t_s, thrust_force_N, [force_des_N, t_des_s],
    [position_m])} (t_des_s: the time base of force_des_N when it differs from t_s);
    par: dict(rho, cd0, a0_m2, m0_kg, m_add_kg, r_delta_m, t_f_s).

    Returns a list of per-payload dicts (sorted by payload): payload_kg, eta, imp_veh, imp_bary
    (produced thrust force impulses), imp_des_veh, imp_des_bary (desired, when given), ratio_sim,
    ratio_des, ratio_89 (D̃0/F̃0), ratio_exact (D̃0 over the exact held reaction), pred
    (analytic.like_for_like dict), travel_bary_m (measured |Δx0| of VII, when position given),
    agree_89, agree_pred (|ratio_sim / model − 1| ≤ AGREE_REL), veh_vs_held (imp_veh over the
    exact reaction impulse mP·rΔ·π/tF).
    """
    pays = sorted({p for (_, p) in runs})
    out = []
    mpar = dict(rho=par["rho"], cd0=par["cd0"], a0_m2=par["a0_m2"], m0_kg=par["m0_kg"])
    for p in pays:
        rv, rb = runs.get((VEH, p)), runs.get((BARY, p))
        eta = float(analytic.eta(p, par["m0_kg"]))
        d = dict(payload_kg=p, eta=eta)
        d["imp_veh"] = run_impulse(rv["t_s"], rv["thrust_force_N"]) if rv else math.nan
        d["imp_bary"] = run_impulse(rb["t_s"], rb["thrust_force_N"]) if rb else math.nan
        d["imp_des_veh"] = (run_impulse(rv.get("t_des_s", rv["t_s"]), rv["force_des_N"])
                            if rv and rv.get("force_des_N") is not None else math.nan)
        d["imp_des_bary"] = (run_impulse(rb.get("t_des_s", rb["t_s"]), rb["force_des_N"])
                             if rb and rb.get("force_des_N") is not None else math.nan)
        d["ratio_sim"] = _div(d["imp_bary"], d["imp_veh"])
        d["ratio_des"] = _div(d["imp_des_bary"], d["imp_des_veh"])
        d["ratio_89"] = float(analytic.ratio(eta, par["r_delta_m"], **mpar))
        d["ratio_exact"] = float(analytic.ratio_exact_reaction(eta, par["r_delta_m"], **mpar))
        d["pred"] = analytic.like_for_like(p, par["r_delta_m"], par["t_f_s"],
                                           m_add_kg=par["m_add_kg"], **mpar)
        d["veh_vs_held"] = _div(d["imp_veh"], d["pred"]["reaction_held"])
        d["bary_vs_pred"] = _div(d["imp_bary"], d["pred"]["barycenter"])
        d["travel_bary_m"] = math.nan
        if rb is not None and rb.get("position_m") is not None and len(rb["position_m"]):
            pos = np.asarray(rb["position_m"], float)
            d["travel_bary_m"] = float(np.max(np.linalg.norm(pos - pos[0], axis=1)))
        d["agree_89"] = _agree(d["ratio_sim"], d["ratio_89"])
        d["agree_exact"] = _agree(d["ratio_sim"], d["ratio_exact"])
        d["agree_pred"] = _agree(d["ratio_sim"], d["pred"]["ratio"])
        out.append(d)
    return out


def _div(a, b):
    try:
        a, b = float(a), float(b)
    except (TypeError, ValueError):
        return math.nan
    if not (math.isfinite(a) and math.isfinite(b)) or b == 0.0:
        return math.nan
    return a / b


def _agree(sim, model):
    """True/False when both are finite and the model is non-zero, None otherwise."""
    r = _div(sim, model)
    return None if not math.isfinite(r) else abs(r - 1.0) <= AGREE_REL


def summarise(rows):
    """Verdicts over the loaded payloads (mP > 0, both runs present): dict with
    n, agree_89 (all agree), agree_pred (all agree), worst_89, worst_pred (largest
    |sim/model − 1|)."""
    ok = [d for d in rows if d["payload_kg"] > 0 and math.isfinite(d["ratio_sim"])]

    def worst(key):
        vals = [abs(_div(d["ratio_sim"], d[key] if key != "pred" else d["pred"]["ratio"]) - 1.0)
                for d in ok]
        vals = [v for v in vals if math.isfinite(v)]
        return max(vals) if vals else math.nan

    return dict(n=len(ok),
                agree_89=bool(ok) and all(d["agree_89"] for d in ok),
                agree_exact=bool(ok) and all(d["agree_exact"] for d in ok),
                agree_pred=bool(ok) and all(d["agree_pred"] for d in ok),
                worst_89=worst("ratio_89"), worst_exact=worst("ratio_exact"),
                worst_pred=worst("pred"))


def params_from_config(cfg):
    """The model's parameters from a logged controller configuration: dict(rho, cd0, a0_m2,
    m0_kg, m_add_kg (vehicle surge added mass ρ·V0·Ma0[1,1]), r_delta_m, t_f_s) and the arm's
    link mass Σ [kg]."""
    rho = float(cfg["density_kg_m3"][0])
    m_add = float(cfg["added_mass_coeff"][0][0]) * rho * float(cfg["vehicle_volume_m3"][0])
    par = dict(rho=rho, cd0=float(cfg["vehicle_drag_coeff"][0]),
               a0_m2=float(cfg["vehicle_frontal_area_m2"][0]),
               m0_kg=float(cfg["vehicle_mass_kg"][0]), m_add_kg=m_add,
               r_delta_m=float(cfg["cart_distance_m"][0]), t_f_s=float(cfg["cart_duration_s"][0]))
    return par, float(np.sum(cfg["link_mass_kg"][0]))


def model_params(par):
    """The analytic model's four parameters (rho, cd0, a0_m2, m0_kg) of a params dict."""
    return dict(rho=par["rho"], cd0=par["cd0"], a0_m2=par["a0_m2"], m0_kg=par["m0_kg"])


def loaded(rows):
    """The rows with a payload (m_P > 0)."""
    return [d for d in rows if d["payload_kg"] > 0]


def factor_range(rows, key):
    """(min, max) of ratio_sim / rows' `key` over the loaded rows (NaN, NaN if none)."""
    fac = [_div(d["ratio_sim"], d[key]) for d in loaded(rows)]
    fac = [x for x in fac if math.isfinite(x)]
    return (min(fac), max(fac)) if fac else (math.nan, math.nan)


def added_mass_share(d):
    """The model's added-mass impulse over the added-mass and drag impulses of one row."""
    return _div(d["pred"]["added_mass_only"],
                d["pred"]["added_mass_only"] + d["pred"]["drag_only"])


def model_curves(par, eta_grid, samples=2001):
    """Over η: [89], [89] with the exact held reaction, and the corrected model with and
    without the vehicle's added mass (NaN at η = 0)."""
    mpar = model_params(par)
    mp_grid = eta_grid / np.maximum(1.0 - eta_grid, 1e-9) * par["m0_kg"]

    def corrected(m_add):
        return [analytic.like_for_like(m, par["r_delta_m"], par["t_f_s"], m_add_kg=m_add,
                                       samples=samples, **mpar)["ratio"] if m > 0 else np.nan
                for m in mp_grid]
    return dict(r89=analytic.ratio(eta_grid, par["r_delta_m"], **mpar),
                exact=analytic.ratio_exact_reaction(eta_grid, par["r_delta_m"], **mpar),
                pred=corrected(par["m_add_kg"]), pred0=corrected(0.0))
