# SPDX-License-Identifier: Apache-2.0
"""analytic: the paper's simplified analytic model of SPEC §9 item 8 ([87–89]).

Model. A vehicle of mass m0 carries a massless, dragless arm whose end effector (EE) holds a
point payload mP. The EE moves a distance rΔ along x *relative to the vehicle* with the cosine
profile of SPEC §8 [78]: d(t) = (rΔ/2)·(1 − cos(πt/tF)), 0 ≤ t ≤ tF. Only the vehicle has drag:
D = ½·ρ·CD0·A0·v0² (SPEC §7.1, w0 = v0 with stagnant water).

Barycenter stabilization: the barycenter stays where it is, so m0·x0 + mP·(x0 + d) = const and
the vehicle moves x0(t) = −η·d(t), η = mP/(m0 + mP); its speed is
v0 = −η·ḋ = −η·(rΔ·π/(2tF))·sin(πt/tF). The thrusters must cancel the drag it meets:

    D̃0 = ∫ ½ρ·CD0·A0·v0² dt = ½ρCD0A0·η²·(rΔπ/(2tF))²·(tF/2) = ρ·CD0·A0·η²·rΔ²·π²/(16·tF)  [87]

Vehicle stabilization: the thrusters cancel the arm's reaction. SPEC (as the paper) takes it
as the force that keeps the vehicle from the motion it would make if left free,
F0 = m0·ẍ0,free = m0·η·d̈, with d̈ = (rΔπ²/(2tF²))·cos(πt/tF):

    F̃0 = ∫ m0·η·|d̈| dt = m0·η·(rΔπ²/(2tF²))·(2tF/π) = m0·rΔ·π·η/tF                     [88]

    D̃0/F̃0 = (π/16)·(ρ·CD0·A0·rΔ/m0)·η                                                   [89]

tF cancels. Barycenter stabilization is predicted cheaper while the ratio is < 1:
  payload limit for a given rΔ: η* = 16·m0/(π·ρ·CD0·A0·rΔ), mP* = η*·m0/(1 − η*)
  (no limit when η* ≥ 1: the ratio stays below 1 for every payload);
  travel limit as η → 1: rΔ* = 16·m0/(π·ρ·CD0·A0).

Which "m0"? As SPEC writes it, m0 in [88] and [89] is the vehicle mass (120 kg; the arm is
massless in this model). Note that the exact reaction of a held vehicle is mP·d̈, not m0·η·d̈
= mP·(1 − η)·d̈: with it, F̃0 = mP·rΔ·π/tF and the ratio becomes
(π/16)·(ρ·CD0·A0·rΔ/(m0 + mP))·η, i.e. "m0" would be the total mass m0 + mP. The two agree
to first order in η (small payloads). This tool follows SPEC ([88] with m0) and also offers the
exact-reaction variant (`ratio_exact_reaction`) for comparison.

The closed forms are checked against a direct numerical integration of the same motion
(`numeric_impulses`: positions from the barycenter constraint, velocities and accelerations by
finite differences, impulses by the trapezoidal rule); tests/tools/test_analytic.py.

CLI: tools/analytic.py [--r-delta 1.82] [--payload-kg 0 1 2 5 10] [--rho ...] [--cd0 ...]
     [--a0 ...] [--m0 ...]: prints the ratio per payload and the limits.
"""
import math

import numpy as np
from uvms_tools.env import add_version_option

# SPEC §3.2 values (the analytic model's defaults; report.py takes them from the runs' logged
# controller configuration instead).
RHO_KG_M3 = 1025.0          # fluid density ρ (the plant's, SPEC §3.2)
CD0 = 1.2                   # vehicle drag coefficient CD0 (SPEC §3.2)
A0_M2 = 0.5                 # vehicle frontal area A0 (SPEC §3.2)
M0_KG = 120.0               # vehicle mass m0 (SPEC §3.2)
ARM_MAX_TRAVEL_M = 1.82     # the arm's maximum travel rΔ (SPEC §9 item 8)


def eta(payload_kg, m0_kg=M0_KG):
    """Payload mass fraction η = mP/(m0 + mP) [-]."""
    payload_kg = np.asarray(payload_kg, dtype=float)
    return payload_kg / (m0_kg + payload_kg)


def drag_impulse(eta_, r_delta_m, t_f_s, rho=RHO_KG_M3, cd0=CD0, a0_m2=A0_M2):
    """D̃0 = ρ·CD0·A0·η²·rΔ²·π²/(16·tF) [N·s] (barycenter stabilization, [87])."""
    return rho * cd0 * a0_m2 * np.square(eta_) * r_delta_m ** 2 * math.pi ** 2 / (16.0 * t_f_s)


def reaction_impulse(eta_, r_delta_m, t_f_s, m0_kg=M0_KG):
    """F̃0 = m0·rΔ·π·η/tF [N·s] (vehicle stabilization, [88] as SPEC writes it)."""
    return m0_kg * r_delta_m * math.pi * np.asarray(eta_, dtype=float) / t_f_s


def ratio(eta_, r_delta_m, rho=RHO_KG_M3, cd0=CD0, a0_m2=A0_M2, m0_kg=M0_KG):
    """D̃0/F̃0 = (π/16)·(ρ·CD0·A0·rΔ/m0)·η [-] ([89])."""
    return (math.pi / 16.0) * (rho * cd0 * a0_m2 * r_delta_m / m0_kg) * np.asarray(eta_, float)


def ratio_exact_reaction(eta_, r_delta_m, rho=RHO_KG_M3, cd0=CD0, a0_m2=A0_M2, m0_kg=M0_KG):
    """D̃0 over the exact held-vehicle reaction impulse mP·rΔ·π/tF: (π/16)(ρCD0A0rΔ/(m0+mP))·η."""
    e = np.asarray(eta_, float)
    total_kg = m0_kg / (1.0 - e)  # m0 + mP
    return (math.pi / 16.0) * (rho * cd0 * a0_m2 * r_delta_m / total_kg) * e


def payload_limit(r_delta_m, rho=RHO_KG_M3, cd0=CD0, a0_m2=A0_M2, m0_kg=M0_KG):
    """(η*, mP* [kg]) where the ratio [89] reaches 1 for travel rΔ; (η*, inf) if η* ≥ 1."""
    eta_star = 16.0 * m0_kg / (math.pi * rho * cd0 * a0_m2 * r_delta_m)
    if eta_star >= 1.0:
        return eta_star, math.inf
    return eta_star, eta_star * m0_kg / (1.0 - eta_star)


def travel_limit(rho=RHO_KG_M3, cd0=CD0, a0_m2=A0_M2, m0_kg=M0_KG):
    """rΔ* [m] where the ratio [89] reaches 1 as η → 1."""
    return 16.0 * m0_kg / (math.pi * rho * cd0 * a0_m2)


def numeric_impulses(payload_kg, r_delta_m, t_f_s, rho=RHO_KG_M3, cd0=CD0, a0_m2=A0_M2,
                     m0_kg=M0_KG, samples=200001):
    """Integrate the simplified model's impulses numerically (independent of the closed forms).

    The motion is built from its definition, not from the derived velocities: the arm extension
    d(t) of [78] on a uniform grid; barycenter stabilization solves, at every instant, the 2×2
    system {m0·x0 + mP·xP = m0·0 + mP·0 (barycenter fixed), xP − x0 = d} for the vehicle and
    payload positions; vehicle stabilization holds x0 = 0, xP = d. Velocities and accelerations
    are second-order finite differences (np.gradient), impulses trapezoidal sums.

    Returns a dict [N·s]: drag (∫ drag on the moving vehicle, barycenter stabilization),
    reaction_free (∫ m0·|ẍ0| of the free vehicle: SPEC's F̃0), reaction_held (∫ mP·|ẍP| with the
    vehicle held: the exact reaction a held vehicle feels).
    """
    t = np.linspace(0.0, t_f_s, samples)
    d = 0.5 * r_delta_m * (1.0 - np.cos(math.pi * t / t_f_s))
    a = np.array([[m0_kg, payload_kg], [-1.0, 1.0]])
    rhs = np.vstack([np.zeros_like(d), d])
    x0, _xp = np.linalg.solve(a, rhs)
    v0 = np.gradient(x0, t, edge_order=2)
    a0 = np.gradient(v0, t, edge_order=2)
    drag = 0.5 * rho * cd0 * a0_m2 * v0 ** 2
    xp_held = d
    ap_held = np.gradient(np.gradient(xp_held, t, edge_order=2), t, edge_order=2)
    return {
        "drag": float(np.trapezoid(drag, t)),
        "reaction_free": float(np.trapezoid(m0_kg * np.abs(a0), t)),
        "reaction_held": float(np.trapezoid(payload_kg * np.abs(ap_held), t)),
    }


def added_mass_kg(rho=RHO_KG_M3, volume_m3=0.15, coeff=0.1):
    """Vehicle surge added mass ρ·V0·Ma0[0][0] [kg] (SPEC §3.3; defaults SPEC §3.2–3.3)."""
    return rho * volume_m3 * coeff


def like_for_like(payload_kg, r_delta_m, t_f_s, rho=RHO_KG_M3, cd0=CD0, a0_m2=A0_M2,
                  m0_kg=M0_KG, m_add_kg=0.0, samples=20001):
    """Thrust-force impulses of the simulated system under the analytic model's assumptions
    (massless, dragless arm with a point payload, straight cosine-profile EE line), with the
    two things the simulation has and [87–89] leave out. Used by the report's experiment 8b.

    - The EE line is referenced to the stabilized point (SPEC §8): with vehicle stabilization
      the vehicle is held and the payload moves r_delta along x; with barycenter stabilization
      the payload moves r_delta inertially with the barycenter fixed, so the vehicle moves
      x0 = −κ·d(t), κ = mP/m0 (not −η·d: [87] lets the EE travel r_delta relative to the
      vehicle; both agree to first order in η).
    - The vehicle has a surge added mass m_add (SPEC §3.3), which the barycenter's rigid
      momentum balance does not carry: moving the vehicle takes a thrust m_add·ẍ0 on top of
      the drag ½ρCD0A0|ẋ0|ẋ0.

    Vehicle stabilization: thrust = the exact reaction mP·ẍP, impulse mP·r_delta·π/tF.
    Barycenter stabilization: thrust = m_add·ẍ0 + ½ρCD0A0|ẋ0|ẋ0 (numerical ∫|·| dt; the two
    terms change sign at different times). Returns a dict [N·s unless noted]: reaction_held,
    drag_only (closed form, = [87] with η → κ), added_mass_only (closed form m_add·κ·r·π/tF),
    barycenter (numerical, both terms), ratio (barycenter / reaction_held; NaN for mP = 0),
    vehicle_travel_m (κ·r_delta), vehicle_travel_analytic_m (η·r_delta, [87]'s).
    """
    kappa = payload_kg / m0_kg
    k = 0.5 * rho * cd0 * a0_m2
    held = payload_kg * r_delta_m * math.pi / t_f_s
    drag_cf = rho * cd0 * a0_m2 * kappa ** 2 * r_delta_m ** 2 * math.pi ** 2 / (16.0 * t_f_s)
    added_cf = m_add_kg * kappa * r_delta_m * math.pi / t_f_s
    t = np.linspace(0.0, t_f_s, samples)
    w = math.pi / t_f_s
    v0 = -kappa * 0.5 * r_delta_m * w * np.sin(w * t)
    a0 = -kappa * 0.5 * r_delta_m * w * w * np.cos(w * t)
    thrust = m_add_kg * a0 + k * np.abs(v0) * v0
    bary = float(np.trapezoid(np.abs(thrust), t))
    return {
        "reaction_held": held, "drag_only": drag_cf, "added_mass_only": added_cf,
        "barycenter": bary, "ratio": bary / held if held > 0 else math.nan,
        "vehicle_travel_m": kappa * r_delta_m,
        "vehicle_travel_analytic_m": float(eta(payload_kg, m0_kg)) * r_delta_m,
    }


def like_for_like_payload_limit(r_delta_m, t_f_s=60.0, rho=RHO_KG_M3, cd0=CD0, a0_m2=A0_M2,
                                m0_kg=M0_KG, m_add_kg=0.0, hi_kg=1e5):
    """Payload [kg] where like_for_like's ratio reaches 1 (bisection), inf if it stays < 1 up
    to hi_kg, 0 if it is ≥ 1 already for a vanishing payload."""
    def r(m):
        return like_for_like(m, r_delta_m, t_f_s, rho, cd0, a0_m2, m0_kg, m_add_kg,
                             samples=4001)["ratio"]
    lo = 1e-6
    if r(lo) >= 1.0:
        return 0.0
    if r(hi_kg) < 1.0:
        return math.inf
    hi = hi_kg
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if r(mid) < 1.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def main(argv=None):
    import argparse
    ap = argparse.ArgumentParser(
        description="SPEC §9 item 8: the simplified analytic model's drag / reaction ratio "
                    "[87–89] and its payload and travel limits.")
    add_version_option(ap, "analytic")
    ap.add_argument("--r-delta", type=float, default=ARM_MAX_TRAVEL_M, help="travel rΔ [m]")
    ap.add_argument("--payload-kg", type=float, nargs="*", default=[0, 1, 2, 5, 10, 20, 50],
                    help="payloads mP [kg]")
    ap.add_argument("--rho", type=float, default=RHO_KG_M3, help="ρ [kg/m³]")
    ap.add_argument("--cd0", type=float, default=CD0, help="CD0 [-]")
    ap.add_argument("--a0", type=float, default=A0_M2, help="A0 [m²]")
    ap.add_argument("--m0", type=float, default=M0_KG, help="vehicle mass m0 [kg]")
    a = ap.parse_args(argv)
    p = dict(rho=a.rho, cd0=a.cd0, a0_m2=a.a0, m0_kg=a.m0)
    print(f"ρ = {a.rho} kg/m³, CD0 = {a.cd0}, A0 = {a.a0} m², m0 = {a.m0} kg, "
          f"rΔ = {a.r_delta} m")
    print(f"{'mP [kg]':>8} {'η':>8} {'ratio [89]':>11} {'exact-reaction':>15}")
    for m in a.payload_kg:
        e = float(eta(m, a.m0))
        print(f"{m:8.2f} {e:8.4f} {float(ratio(e, a.r_delta, **p)):11.4f} "
              f"{float(ratio_exact_reaction(e, a.r_delta, **p)):15.4f}")
    e_star, m_star = payload_limit(a.r_delta, **p)
    lim = "none (ratio < 1 for every payload)" if math.isinf(m_star) else f"{m_star:.1f} kg"
    print(f"payload limit at rΔ = {a.r_delta} m: η* = {e_star:.4f}, mP* = {lim}")
    print(f"travel limit (η → 1): rΔ* = {travel_limit(**p):.4f} m")
    return 0
