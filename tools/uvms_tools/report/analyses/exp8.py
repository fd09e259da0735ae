# SPDX-License-Identifier: Apache-2.0
"""exp8: the simplified analytic model of SPEC §9 item 8 ([87–89], tools/analytic.py) with the
parameters of the runs' logged controller configuration: its limits and the check of its
closed forms against the numerical integration of the same motion."""
import numpy as np

from uvms_tools.models import analytic


def params_from_config(cfg):
    """(par, r_sim, t_f, arm_kg): the model's parameters (rho, cd0, a0_m2, m0_kg), the
    simulated line's length and duration, and the arm's link mass Σ."""
    par = dict(rho=float(cfg["density_kg_m3"][0]), cd0=float(cfg["vehicle_drag_coeff"][0]),
               a0_m2=float(cfg["vehicle_frontal_area_m2"][0]),
               m0_kg=float(cfg["vehicle_mass_kg"][0]))
    return (par, float(cfg["cart_distance_m"][0]), float(cfg["cart_duration_s"][0]),
            float(np.sum(cfg["link_mass_kg"][0])))


def limits(par, r_sim, r_max=analytic.ARM_MAX_TRAVEL_M):
    """The payload limits of [89] at the arm's maximum travel and at the simulated one, and
    the travel limit as η → 1: dict(eta_star, mp_star, eta_star_sim, mp_star_sim, r_star,
    r_max)."""
    eta_star, mp_star = analytic.payload_limit(r_max, **par)
    eta_star_sim, mp_star_sim = analytic.payload_limit(r_sim, **par)
    return dict(eta_star=eta_star, mp_star=mp_star, eta_star_sim=eta_star_sim,
                mp_star_sim=mp_star_sim, r_star=analytic.travel_limit(**par), r_max=r_max)


def closed_form_check(payload_kg, r_sim, t_f, par, samples=20001):
    """Closed forms D̃0 [87], F̃0 [88] against analytic.numeric_impulses of the same motion:
    dict(num (the numerical impulses), drag, reaction)."""
    num = analytic.numeric_impulses(payload_kg, r_sim, t_f, samples=samples, **par)
    eta = float(analytic.eta(payload_kg, par["m0_kg"]))
    return dict(num=num,
                drag=float(analytic.drag_impulse(eta, r_sim, t_f, par["rho"], par["cd0"],
                                                 par["a0_m2"])),
                reaction=float(analytic.reaction_impulse(eta, r_sim, t_f, par["m0_kg"])))


def payload_rows(pays, r_sim, par):
    """Per payload: (η, [89] ratio, [89] with the exact reaction)."""
    out = []
    for p in pays:
        et = float(analytic.eta(p, par["m0_kg"]))
        out.append((et, float(analytic.ratio(et, r_sim, **par)),
                    float(analytic.ratio_exact_reaction(et, r_sim, **par))))
    return out
