# SPDX-License-Identifier: Apache-2.0
"""energy: where the thruster energy goes, from per-tick records (SPEC §5): the propulsive
energy, the split of the allocated thrust into its position and attitude parts, the motor's
friction and copper losses, and the vehicle drag under unsteady flow."""
import math

import numpy as np

from ..num import div
from .delay import rms


def propulsive_from_truth(t_s, thrust_N, rho, diameter_m):
    """E_p = ∫Σ|T_j|^1.5/√(2ρ·A_d) dt (SPEC §5) from per-tick thrusts (n, 8), with the thrust
    held over each tick (left Riemann sum over the tick boundaries)."""
    t = np.asarray(t_s, float)
    if len(t) < 2:
        return 0.0
    a_d = math.pi * diameter_m ** 2 / 4.0
    p = np.sum(np.abs(np.asarray(thrust_N, float)) ** 1.5, axis=1) / math.sqrt(2.0 * rho * a_d)
    return float(np.sum(p[:-1] * np.diff(t)))


def median_step(t_s, default=float("nan")):
    """The median sample spacing of a time base (default with fewer than two samples)."""
    return float(np.median(np.diff(t_s))) if len(t_s) > 1 else default


def thrust_split(dt, p_pos, p_att, p_des):
    """Impulses ∫Σ|P_pos| dt, ∫Σ|P_att| dt and ∫Σ|P| dt [N·s] of the allocated thrust's
    position and attitude parts and of the whole (n, 8) per tick, held over dt; with the RMS
    of each part per thruster (for the figure)."""
    p_pos, p_att = np.asarray(p_pos, float), np.asarray(p_att, float)
    return dict(pos=float(np.abs(p_pos).sum() * dt), att=float(np.abs(p_att).sum() * dt),
                total=float(np.abs(np.asarray(p_des, float)).sum() * dt),
                rms_pos=rms(p_pos), rms_att=rms(p_att))


def motor_losses(dt, speed, current, voltage, friction, resistance):
    """Per-tick records (n, 8) of shaft speed ω, motor current I and voltage V: the energy
    ∫max(V·I, 0) dt per thruster, the friction ∫Σb·ω² dt and the copper ∫ΣR·I² dt [J]."""
    w, i, v = (np.asarray(x, float) for x in (speed, current, voltage))
    return dict(e_vi=np.maximum(v * i, 0.0).sum(axis=0) * dt,
                friction=float((friction * w * w).sum() * dt),
                copper=float((resistance * i * i).sum() * dt))


def thrust_constant(ct2, rho, diameter_m):
    """c1 = CT2·ρ·D⁴/(4π²) of the thrust law T = c1·ω·|ω| (SPEC §3.4)."""
    return ct2 * rho * diameter_m ** 4 / (4 * math.pi ** 2)


def energy_breakdown(dt, speed, current, voltage, thrust, thrust_des, motor, energy_J):
    """Where one run's thruster energy goes. motor: dict(b, R, ct2, rho, diameter_m);
    energy_J: the run's E_el (summary). Returns motor_losses() plus imp (delivered ∫Σ|T| dt),
    imp_des (allocated ∫Σ|P| dt), fric_share (friction / E_el) and b_c1 (b/|c1| [W/N]: with
    friction dominating and ω² ∝ |T|, E_el ≈ b/|c1| · ∫Σ|T| dt)."""
    out = motor_losses(dt, speed, current, voltage, motor["b"], motor["R"])
    c1 = thrust_constant(motor["ct2"], motor["rho"], motor["diameter_m"])
    out.update(imp=float(np.abs(thrust).sum() * dt), imp_des=float(np.abs(thrust_des).sum() * dt),
               fric_share=div(out["friction"], energy_J), b_c1=motor["b"] / abs(c1))
    return out


def drag_impulses(dt, velocity, flow, force_des, force_fb, k_drag):
    """The unsteady-flow budget of one run: vehicle drag D0 = −k·|w|·w with w = v0 − v∞
    (k = ½ρ·CD0·A0), its impulse ∫|D0| dt, the controller's ∫|F_des| dt and ∫|F_fb| dt, and
    the RMS of |v∞| and |v0|."""
    wrel = np.asarray(velocity, float) - np.asarray(flow, float)
    drag = k_drag * np.linalg.norm(wrel, axis=1)[:, None] * wrel
    return dict(drag_imp=np.linalg.norm(drag, axis=1).sum() * dt,
                fdes_imp=np.linalg.norm(force_des, axis=1).sum() * dt,
                ffb_imp=np.linalg.norm(force_fb, axis=1).sum() * dt,
                flow=rms(np.linalg.norm(flow, axis=1)),
                vel=rms(np.linalg.norm(velocity, axis=1)))
