# SPDX-License-Identifier: Apache-2.0
"""exp3_energy: where the thruster energy goes (experiment 3's logs): motor friction, copper,
the rest; and the unsteady condition's drag and feedback budget."""
from ..analyses import energy, stats
from ..keys import BARY, E_EL, VEH
from ..load.logs import per_tick, scalar, thruster_value
from ..num import div
from .fmt import f, fmt_dist, fmt_range, g, table


def _motor(cfg, rho):
    """Thruster 1's motor (the paper's thrusters are all of one type)."""
    return dict(b=thruster_value(cfg, "motor_viscous_friction_Nm_s"),
                R=thruster_value(cfg, "motor_resistance_ohm"), ct2=thruster_value(cfg, "ct2"),
                rho=rho, diameter_m=thruster_value(cfg, "propeller_diameter_m"))


def _breakdown(runs, logs, order):
    """{(case, cond): analyses.energy.energy_breakdown + the records} of the runs drawn."""
    stag_cfg = None
    for ck in order:
        if ck in logs and ck[1] == "stagnant" and "UVMS_CONFIG" in logs[ck]:
            stag_cfg = logs[ck]["UVMS_CONFIG"]
    info = {}
    for ck in order:
        if ck not in logs or "UVMS_ACTUATORS" not in logs[ck]:
            continue
        lg = logs[ck]
        cfg = lg["UVMS_CONFIG"]
        tm, tr = per_tick(lg)
        ac = lg["UVMS_ACTUATORS"].at_ticks(tm["tick"])
        dt = scalar(cfg, "tick_s")
        rho = scalar(stag_cfg or cfg, "density_kg_m3")
        e_run = runs[ck].get(E_EL) if runs[ck] else None
        d = energy.energy_breakdown(dt, tr["motor_speed_rad_s"], tr["motor_current_A"],
                                    ac["motor_voltage_V"], tr["thrust_N"], tm["thrust_des_N"],
                                    _motor(cfg, rho), e_run)
        info[ck] = dict(d, e=e_run, rho=rho, tm=tm, tr=tr, cfg=cfg, dt=dt)
    return info


def _tables(info):
    rows, per_thr = [], []
    for ck, d in info.items():
        rows.append([f"{ck[0]}, {ck[1]}", f(d["e"], 1), f(d["e_vi"].sum(), 1), f(d["friction"], 1),
                     f(d["copper"], 2), f(d["fric_share"] * 100, 1), g(d["imp_des"], 3),
                     g(d["imp"], 3), f(div(d["e"], d["imp"]), 1), f(d["b_c1"], 1)])
        per_thr.append([f"{ck[0]}, {ck[1]}"] + [f(x, 0) for x in d["e_vi"]])
    md = table(["run", "E_el (summary) [J]", "∫Σmax(V·I,0) (tick-sampled) [J]",
                "∫Σ b·ω² [J]", "∫Σ R·I² [J]", "friction share [%]",
                "allocated ∫Σ|P| dt [N·s]", "delivered ∫Σ|T| dt [N·s]",
                "E / ∫Σ|T| [J/(N·s)]", "b/|c1| [W/N]"], rows)
    md += ["Per-thruster energy ∫max(V_j·I_j, 0) dt [J] (tick-sampled):", ""]
    md += table(["run"] + [f"T{j + 1}" for j in range(8)], per_thr)
    return md + [
        "With the paper's motor (b = viscous friction, k_m, J and the tiny propeller "
        "constants of docs/MODEL.md §3.4) the electrical energy is dominated by motor friction "
        "b·ω² (friction-share column), and since the thrust law gives ω² ∝ |T|, **the "
        "thruster energy is close to proportional to the thrust impulse ∫Σ|T_j| dt** "
        "with the constant b/|c1| (last column; measured E/∫Σ|T| next to it). Energy "
        "comparisons between cases are therefore, to that extent, comparisons of "
        "delivered thrust impulse.", ""]


def _impulse_note(rep, info):
    ratios_imp = [div(d["imp"], d["imp_des"]) for d in info.values()]
    if not ratios_imp:
        return
    ms = rep.motor or {}
    used = rep.drive() if rep.drive() in ("current", "voltage") else "voltage"
    rep.notes.append(
        f"Experiment 3: the thrusters deliver {fmt_range(ratios_imp, 2)} of the "
        f"allocated thrust impulse (delivered ∫Σ|T_j| dt over allocated ∫Σ|P_j| dt), and "
        f"the produced wrench fits the desired one best with a delay of "
        f"{fmt_range([lag for _, lag in rep.track_lags], 2)} s. The speed "
        f"loop of the {used} drive these runs used reaches 63 % of a step in "
        f"{f(ms.get(f'tau_{used}_s'), 3)} s (experiment 3, thruster response).")


def _flow_budget(d, k_drag):
    return energy.drag_impulses(d["dt"], d["tr"]["velocity_m_s"], d["tr"]["flow_velocity_m_s"],
                                d["tm"]["force_des_N"], d["tm"]["force_fb_N"], k_drag)


def _unsteady(rep, e, info, conds):
    """The unsteady condition over seeds (summary energies) and one seed's logs."""
    urows = []
    for c in (VEH, BARY):
        s, u = info.get((c, "stagnant")), info.get((c, "unsteady"))
        d_s = e.dist(E_EL, conds[(c, "stagnant")])
        d_u = e.dist(E_EL, conds[(c, "unsteady")])
        if not s or not u:
            continue
        cfg = u["cfg"]
        k_drag = 0.5 * u["rho"] * scalar(cfg, "vehicle_drag_coeff") * \
            scalar(cfg, "vehicle_frontal_area_m2")
        out = [_flow_budget(s, k_drag), _flow_budget(u, k_drag)]
        for lbl, d, src in (("stagnant", out[0], s), ("unsteady", out[1], u)):
            urows.append([f"{c}, {lbl}", f(d["flow"] * 1e3, 2), f(d["vel"] * 1e3, 2),
                          g(d["drag_imp"], 3), g(d["ffb_imp"], 3), g(d["fdes_imp"], 3),
                          g(src["imp"], 3), f(src["e"], 1)])
        ratio_d = stats.describe([div(x, d_s.mean) for x in d_u.values])
        rep.notes.append(
            f"Unsteady flow in case {c} (experiment 3): the thruster energy rises from "
            f"{f(d_s.mean, 1)} J to {fmt_dist(d_u, 1)} J (×{fmt_dist(ratio_d, 2)} over "
            f"{d_u.n} seed(s)). In the run drawn (one seed) the delivered thrust impulse "
            f"∫Σ|T| dt grows from {g(s['imp'], 3)} to {g(u['imp'], 3)} N·s; the flow (RMS "
            f"|v∞| {f(out[1]['flow'] * 1e3, 1)} mm/s) adds a drag impulse ∫|D0| dt of "
            f"{g(out[1]['drag_imp'], 2)} N·s (stagnant: {g(out[0]['drag_imp'], 2)}), and the "
            f"position-feedback impulse ∫|F_fb| dt grows from {g(out[0]['ffb_imp'], 3)} to "
            f"{g(out[1]['ffb_imp'], 3)} N·s: the feedback reacts to the vehicle motion the "
            f"drag causes.")
    if not urows:
        return []
    md = ["**The unsteady-flow condition** (one seed). Vehicle drag D0 = −½ρ·CD0·A0·|w|·w "
          "with w = v0 − v∞ recomputed from the truth log (plant ρ), next to the "
          "controller's position-feedback and desired-force impulses:", ""]
    return md + table(["run", "RMS |v∞| [mm/s]", "RMS |v0| [mm/s]", "∫|D0| dt [N·s]",
                       "∫|F_fb| dt [N·s]", "∫|F_des| dt [N·s]", "∫Σ|T| dt [N·s]", "E_el [J]"],
                      urows)


def energy_breakdown(rep, e, runs, logs, order, conds):
    info = _breakdown(runs, logs, order)
    rep.energy_info = info
    md = ["### Where the thruster energy goes", ""] + _tables(info)
    _impulse_note(rep, info)
    return md + _unsteady(rep, e, info, conds)

