# SPDX-License-Identifier: Apache-2.0
"""motor: the speed step response of one thruster's loops (motor model of SPEC §5, control law
§7.4 [64–66], [53]) for the logged configuration, with both power stages and in continuous
time."""
import math

import numpy as np

from . import stats

MOTOR_FIELDS = ("motor_resistance_ohm", "motor_inductance_H", "motor_torque_constant_Nm_A",
                "motor_viscous_friction_Nm_s", "rotor_inertia_kg_m2", "speed_gain_1_s",
                "current_gain_1_s", "tick_s")


def expm(m):
    """Matrix exponential by scaling and squaring with a Taylor series (small matrices)."""
    norm = np.linalg.norm(m, 1)
    s = max(0, int(math.ceil(math.log2(norm))) + 1) if norm > 0 else 0
    a = m / (2 ** s)
    out = np.eye(len(m))
    term = np.eye(len(m))
    for k in range(1, 25):
        term = term @ a / k
        out = out + term
    for _ in range(s):
        out = out @ out
    return out


def _params(cfg):
    """(R, L, km, b, J, KA, KB, tick) of thruster 1 from a logged configuration (field →
    [value]; per-thruster fields hold one value per thruster)."""
    c = {k: float(np.ravel(cfg[k][0])[0]) for k in MOTOR_FIELDS}
    return (c["motor_resistance_ohm"], c["motor_inductance_H"], c["motor_torque_constant_Nm_A"],
            c["motor_viscous_friction_Nm_s"], c["rotor_inertia_kg_m2"], c["speed_gain_1_s"],
            c["current_gain_1_s"], c["tick_s"])


def _voltage_drive(p, omega_ref, n):
    """Voltage drive: V_k = R·I_k + L·İ*_k + km·ω_k held over the tick, the motor integrated
    exactly. Returns (augmented matrix over (I, ω, V), states (n+1, 2), voltages (n,))."""
    r, l, km, b, j, ka, kb, dt = p
    a = np.array([[-r / l, -km / l], [km / j, -b / j]])
    aug = np.zeros((3, 3))
    aug[:2, :2], aug[:2, 2] = a, [1.0 / l, 0.0]
    e = expm(aug * dt)
    phi, gam = e[:2, :2], e[:2, 2]
    xv = np.zeros((n + 1, 2))
    vv = np.zeros(n)
    for k in range(n):
        i, w = xv[k]
        vv[k] = r * i + l * _i_dot(p, omega_ref, i, w) + km * w
        xv[k + 1] = phi @ xv[k] + gam * vv[k]
    return aug, xv, vv


def _i_dot(p, omega_ref, i, w):
    """The controller's current-rate command İ* = KB·(Î − I), Î = (J·KA·(ω̂ − ω) + b·ω)/km."""
    r, l, km, b, j, ka, kb, dt = p
    i_hat = (j * ka * (omega_ref - w) + b * w) / km
    return kb * (i_hat - i)


def _current_drive(p, omega_ref, n):
    """Current drive: I follows the integrated command, İ*_k held over the tick. Returns
    (matrix over (ω, I, İ*), states (ω, I) (n+1, 2), rates (n,))."""
    r, l, km, b, j, ka, kb, dt = p
    ac = np.array([[-b / j, km / j, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, 0.0]])
    ec = expm(ac * dt)
    xi = np.zeros((n + 1, 2))
    idv = np.zeros(n)
    for k in range(n):
        w, i = xi[k]
        idv[k] = _i_dot(p, omega_ref, i, w)
        xi[k + 1] = (ec @ np.array([w, i, idv[k]]))[:2]
    return ac, xi, idv


def _continuous_law(p, omega_ref, n):
    """İ = KB·(Î − I), J·ω̇ = km·I − b·ω in continuous time; state (I, ω, ω̂) at the ticks."""
    r, l, km, b, j, ka, kb, dt = p
    acl = np.array([[-kb, kb * (b - j * ka) / km, kb * j * ka / km],
                    [km / j, -b / j, 0.0], [0.0, 0.0, 0.0]])
    ecl = expm(acl * dt)
    xc = np.zeros((n + 1, 3))
    xc[0, 2] = omega_ref
    for k in range(n):
        xc[k + 1] = ecl @ xc[k]
    return acl, xc


def _between_ticks(m, z, row, last, dt, sub):
    """From each tick's state z[k] (with its held input), the response at sub points per tick:
    row `row` of expm(m·dt·q/sub)·z[k], q = 0..sub−1, then `last`."""
    pw = np.array([expm(m * dt * q / sub) for q in range(sub)])
    y = np.einsum("qab,kb->kqa", pw, z)[:, :, row].reshape(-1)
    return np.append(y, last)


def _rise(tf, w, level):
    """First crossing of `level` on the fine grid, interpolated (stats.first_crossing)."""
    above = np.nonzero(w >= level)[0]
    if not len(above):
        return float("nan")
    k = int(above[0])
    lo = max(k - 1, 0)
    return stats.first_crossing(tf[lo:k + 1], w[lo:k + 1], level)


def motor_step(cfg, omega_ref=1.0, horizon_ticks=4000, grid_s=1e-3):
    """Speed step response of one motor under the §7.4 loops ([64–66], [53]) without propeller
    load, for both power stages of SPEC §5, the loops evaluated once per controller tick:

    - current drive: the motor current follows the controller's integrated current command,
      I(t) = I_k + İ*_k·(t − t_k) over tick k, İ*_k = KB·(Î_k − I_k), Î_k = (J·KA·(ω̂ − ω_k)
      + b·ω_k)/km [64–66]; the shaft J·ω̇ = km·I − b·ω integrated exactly over the tick;
    - voltage drive: the voltage V_k = Rm·I_k + Lm·İ*_k + km·ω_k [53] is held over the tick and
      the motor L·İ = V − R·I − km·ω, J·ω̇ = km·I − b·ω integrated exactly;
    - and the same law in continuous time (İ = KB·(Î − I)): ω̈ + (KB + b/J)·ω̇ + KA·KB·ω =
      KA·KB·ω̂.

    Each response is evaluated exactly at the ticks and, between them, on a grid of
    `grid_s` (rounded to a whole fraction of the tick; the drives' tick inputs held). The 63 %
    rise times are the first crossings on that grid, linearly interpolated
    (stats.first_crossing). Returns dict: t_s and omega_current, omega_voltage,
    omega_continuous at the ticks; t_fine_s and the same three on the fine grid (keys
    *_fine); tau_current_s, tau_voltage_s, tau_continuous_s; resolution_s (the fine grid's
    step); tick_s."""
    p = _params(cfg)
    dt = p[-1]
    n = horizon_ticks
    sub = max(1, int(round(dt / grid_s)))  # fine-grid steps per tick
    aug, xv, vv = _voltage_drive(p, omega_ref, n)
    ac, xi, idv = _current_drive(p, omega_ref, n)
    acl, xc = _continuous_law(p, omega_ref, n)
    w_cur = _between_ticks(ac, np.column_stack([xi[:-1], idv]), 0, xi[-1, 0], dt, sub)
    w_vol = _between_ticks(aug, np.column_stack([xv[:-1], vv]), 1, xv[-1, 1], dt, sub)
    w_con = _between_ticks(acl, xc[:-1], 1, xc[-1, 1], dt, sub)
    h = dt / sub
    tf = np.arange(n * sub + 1) * h
    level = (1.0 - math.exp(-1.0)) * omega_ref
    return {"t_s": np.arange(n + 1) * dt, "omega_current": xi[:, 0], "omega_voltage": xv[:, 1],
            "omega_continuous": xc[:, 1], "t_fine_s": tf, "omega_current_fine": w_cur,
            "omega_voltage_fine": w_vol, "omega_continuous_fine": w_con,
            "tau_current_s": _rise(tf, w_cur, level), "tau_voltage_s": _rise(tf, w_vol, level),
            "tau_continuous_s": _rise(tf, w_con, level), "resolution_s": h, "tick_s": dt}


def loop_damping(cfg):
    """ω_n = √(KA·KB), ζ = (KB + b/J)/(2ω_n) and b/J of thruster 1's continuous speed loop."""
    def first(k):
        return float(np.ravel(cfg[k][0])[0])
    ka, kb = first("speed_gain_1_s"), first("current_gain_1_s")
    b_j = first("motor_viscous_friction_Nm_s") / first("rotor_inertia_kg_m2")
    wn = math.sqrt(ka * kb)
    return dict(wn=wn, zeta=(kb + b_j) / (2.0 * wn), b_j=b_j, ka=ka, kb=kb)
