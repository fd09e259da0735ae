"""report_exp8b: experiment 8 like for like (tools/report.py's section of exp8b_analytic_like).

The analytic model of SPEC §9 item 8 ([87–89], tools/analytic.py) compares INTEGRATED FORCES
of a massless, dragless arm carrying a point payload along a straight cosine-profile EE line:
the impulse of the drag on the vehicle under barycenter stabilization, D̃0, against the impulse
of the reaction that vehicle stabilization cancels, F̃0. Experiment 8 (exp8_analytic) compares
electrical energies of the full arm, a different quantity of a different system. Campaign
sil/campaigns/paper/exp8b_analytic_like.toml runs the simulation under the model's assumptions
(arm.mass_scale = 0, arm.hydrodynamics = false, payload only, the line of exp8, no unsteady flow,
no density error); this module compares like with like: the time integral of the produced thrust
force |F_thr(t)| (plant truth `thrust_force_N`; controller `force_des_N` as a cross-check) of VII
against IV, per payload, with D̃0/F̃0 and with analytic.like_for_like (the same model with the
two things the simulated system adds: the vehicle's added mass and the barycenter-referenced
line).

Pure functions (`run_impulse`, `analyse`) take arrays, so they are tested on synthetic signals
(tests/tools/test_report_stats.py); `section(rep)` reads the runs.
"""
import math

import numpy as np

import analytic
import stats

NAME = "exp8b_analytic_like"
VEH, BARY = "IV", "VII"
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


# ----------------------------------------------------------------------------------------------
# The report section


def _f(x, nd=3):
    return f"{float(x):.{nd}f}" if x is not None and math.isfinite(float(x)) else "—"


def _g(x, sig=3):
    return f"{float(x):.{sig}g}" if x is not None and math.isfinite(float(x)) else "—"


def section(rep, fig_helpers):
    """Markdown lines of the like-for-like section; sets rep.exp8b (summary dict or None).
    fig_helpers: (plt, img) from report.py."""
    plt, img, table = fig_helpers
    rep.exp8b = None
    e = rep.exp(NAME)
    if e is None:
        return [f"*Experiment `{NAME}` was not found among the campaign outputs: the "
                "like-for-like comparison is skipped (its campaign needs the scenario keys "
                "`arm.mass_scale` and `arm.hydrodynamics`).*", ""]
    md = [f"*Campaign file:* {e.comment}", ""] if e.comment else []
    cfg = None
    for r in e.runs:
        cfg = rep.cfg(e, r)
        if cfg is not None:
            break
    if cfg is None:
        return md + ["*No log of this experiment could be read.*", ""]
    arm_kg = float(np.sum(cfg["link_mass_kg"][0]))
    rho = float(cfg["density_kg_m3"][0])
    m_add = float(cfg["added_mass_coeff"][0][0]) * rho * float(cfg["vehicle_volume_m3"][0])
    par = dict(rho=rho, cd0=float(cfg["vehicle_drag_coeff"][0]),
               a0_m2=float(cfg["vehicle_frontal_area_m2"][0]),
               m0_kg=float(cfg["vehicle_mass_kg"][0]), m_add_kg=m_add,
               r_delta_m=float(cfg["cart_distance_m"][0]), t_f_s=float(cfg["cart_duration_s"][0]))
    runs, failed = {}, []
    for r in e.runs:
        if r.get("status") != "finished":
            failed.append(r.get("id"))
            continue
        lg = e.log(r)
        if lg is None or "UVMS_TRUTH" not in lg:
            continue
        tr = lg["UVMS_TRUTH"]
        tm = lg.get("UVMS_TELEMETRY")
        d = dict(t_s=tr["t_s"], thrust_force_N=tr["thrust_force_N"], position_m=tr["position_m"])
        if tm is not None:
            sel = tm["tick"] >= 0
            d["force_des_N"] = tm["force_des_N"][sel]
            d["t_des_s"] = tm["t_s"][sel]
        runs[(r.get("control.case"), float(r.get("payload.mass_kg", 10.0)))] = d
    rows = analyse(runs, par)
    summ = summarise(rows)
    rep.exp8b = dict(summ, rows=rows, par=par, arm_kg=arm_kg)

    tab = []
    for d in rows:
        pr = d["pred"]
        tab.append([_f(d["payload_kg"], 0), _f(d["eta"], 4),
                    _g(d["imp_veh"], 4), _g(pr["reaction_held"], 4),
                    _g(d["imp_bary"], 4), _g(pr["barycenter"], 4),
                    _f(d["ratio_sim"], 3), _f(d["ratio_des"], 3), _f(d["ratio_89"], 3),
                    _f(d["ratio_exact"], 3), _f(pr["ratio"], 3),
                    _f(1e3 * d["travel_bary_m"], 1), _f(1e3 * pr["vehicle_travel_m"], 1),
                    _f(1e3 * pr["vehicle_travel_analytic_m"], 1)])
    md += [f"Parameters from the logged controller configuration: arm link masses Σ = "
           f"{_g(arm_kg, 3)} kg (the model's arm is massless), ρ = {_g(rho, 4)} kg/m³, "
           f"CD0 = {_g(par['cd0'], 3)}, A0 = {_g(par['a0_m2'], 3)} m², m0 = "
           f"{_g(par['m0_kg'], 4)} kg, vehicle surge added mass m_A = ρ·V0·Ma0[1,1] = "
           f"{_g(m_add, 3)} kg, line r_Δ = {_g(par['r_delta_m'], 3)} m over t_F = "
           f"{_g(par['t_f_s'], 3)} s.", ""]
    md += table(["m_P [kg]", "η", "IV ∫|F_thr| dt [N·s]", "IV model m_P·r_Δ·π/t_F",
                 "VII ∫|F_thr| dt [N·s]", "VII model (added mass + drag)",
                 "sim ratio VII/IV (produced)", "sim ratio (desired F_P0)", "analytic [89]",
                 "[89] with exact reaction", "model with added mass, barycenter line",
                 "VII vehicle travel, sim [mm]", "model κ·r_Δ [mm]", "[87]'s η·r_Δ [mm]"], tab)
    if failed:
        md += [f"Runs that did not finish (left out): {', '.join(map(str, failed))}.", ""]

    # Figure: ratios vs payload.
    fig, ax = plt.subplots(figsize=(9.5, 4.8))
    xs = [d["eta"] for d in rows if d["payload_kg"] > 0]
    ok = [d for d in rows if d["payload_kg"] > 0]
    eg = np.linspace(0.0, max(xs + [0.05]) * 1.08, 200)
    mpar = dict(rho=par["rho"], cd0=par["cd0"], a0_m2=par["a0_m2"], m0_kg=par["m0_kg"])
    ax.plot(eg, analytic.ratio(eg, par["r_delta_m"], **mpar), "k-", lw=2,
            label=r"analytic $\tilde D_0/\tilde F_0$ [89]")
    ax.plot(eg, analytic.ratio_exact_reaction(eg, par["r_delta_m"], **mpar), "--", color="gray",
            lw=1.5, label="[89] with the exact held reaction m_P·r̈")
    mp_grid = eg / np.maximum(1.0 - eg, 1e-9) * par["m0_kg"]
    pred = [analytic.like_for_like(m, par["r_delta_m"], par["t_f_s"], m_add_kg=m_add,
                                   samples=2001, **mpar)["ratio"] if m > 0 else np.nan
            for m in mp_grid]
    ax.plot(eg, pred, "-.", color="#2ca02c", lw=2,
            label=f"model + vehicle added mass ({_g(m_add, 3)} kg) + barycenter-referenced line")
    pred0 = [analytic.like_for_like(m, par["r_delta_m"], par["t_f_s"], m_add_kg=0.0,
                                    samples=2001, **mpar)["ratio"] if m > 0 else np.nan
             for m in mp_grid]
    ax.plot(eg, pred0, ":", color="#2ca02c", lw=1.8,
            label="model + barycenter-referenced line + exact reaction, no added mass")
    ax.plot(xs, [d["ratio_sim"] for d in ok], "o", color="#d62728", ms=7,
            label="simulated ∫|F_thr|(VII) / ∫|F_thr|(IV)")
    ax.plot(xs, [d["ratio_des"] for d in ok], "x", color="#9467bd", ms=7,
            label="simulated, desired force F_P0")
    last = -1.0
    for d in ok:
        if d["eta"] - last > 0.03 * max(xs + [1e-9]):
            last = d["eta"]
            ax.annotate(f"{_f(d['payload_kg'], 0)} kg", (d["eta"], d["ratio_sim"]),
                        textcoords="offset points", xytext=(5, -12), fontsize=8)
    ax.set_xlabel("payload fraction η = m_P/(m0 + m_P) [-]")
    ax.set_ylabel("impulse ratio barycenter / vehicle [-]")
    ax.set_title("Experiment 8b: integrated thrust force, massless dragless arm (like for like)")
    ax.legend(fontsize=8.5, loc="upper left")
    ax.set_ylim(bottom=0)
    fig.tight_layout()
    img(md, rep.figs.save(fig, "exp8b_impulse_ratio.png"),
        "Integrated thrust-force ratio VII/IV of the like-for-like simulation vs the analytic "
        "ratio [89] and the model with the simulated system's added mass and line reference.")

    # Verdict text, from the numbers.
    n = summ["n"]
    if n == 0:
        md += ["No loaded payload pair finished: nothing to compare.", ""]
        return md
    lines = []
    if summ["agree_89"]:
        lines.append(f"- **Agrees with [89]**: at all {n} loaded payloads the simulated impulse "
                     f"ratio is within ±{AGREE_REL:.0%} of D̃0/F̃0 (worst "
                     f"{_f(100 * summ['worst_89'], 1)} %).")
    else:
        fac = [_div(d["ratio_sim"], d["ratio_89"]) for d in ok]
        fac = [x for x in fac if math.isfinite(x)]
        rep.exp8b["factor_89"] = (min(fac), max(fac)) if fac else (math.nan, math.nan)
        lines.append(f"- **Does not agree with [89]**: over the {n} loaded payloads the simulated "
                     f"impulse ratio is {_f(min(fac), 2)}–{_f(max(fac), 2)} × D̃0/F̃0 "
                     f"(tolerance ±{AGREE_REL:.0%}; the factor is largest at the smallest "
                     f"payload, where [89] → 0); with the exact held reaction m_P·r̈ in place of "
                     f"[88]'s m0·η·r̈ the worst relative difference is "
                     f"{_f(100 * summ['worst_exact'], 0)} %.")
    held = [d["veh_vs_held"] for d in ok if math.isfinite(d["veh_vs_held"])]
    if held:
        lines.append(f"- Vehicle stabilization (IV): the produced thrust impulse is "
                     f"{_f(min(held), 3)}–{_f(max(held), 3)} × the exact reaction impulse "
                     f"m_P·r_Δ·π/t_F of the payload, against [88]'s F̃0 = m0·η·r_Δ·π/t_F = "
                     f"(1 − η)·m_P·r_Δ·π/t_F: [88] takes the free vehicle's acceleration times "
                     f"m0, which under-counts the held reaction by the factor 1 − η.")
    bp = [d["bary_vs_pred"] for d in ok if math.isfinite(d["bary_vs_pred"])]
    if bp:
        d1, d2 = ok[0], ok[-1]

        def share(d):
            return _div(d["pred"]["added_mass_only"], d["pred"]["added_mass_only"]
                        + d["pred"]["drag_only"])
        lines.append(f"- Barycenter stabilization (VII): the produced thrust impulse is "
                     f"{_f(min(bp), 3)}–{_f(max(bp), 3)} × that of the model with the vehicle's "
                     f"added mass: moving the vehicle takes m_A·ẍ0 besides the drag, since the "
                     f"barycenter the controller holds is that of the rigid masses (docs/MODEL.md §7), "
                     f"which the fluid's added mass is not part of. The added-mass term is "
                     f"{_f(100 * share(d1), 0)} % of the two terms' impulses at m_P = "
                     f"{_f(d1['payload_kg'], 0)} kg and {_f(100 * share(d2), 0)} % at "
                     f"{_f(d2['payload_kg'], 0)} kg; [87] has none, so [89] → 0 for small "
                     f"payloads while the simulated ratio tends to m_A/m0 = "
                     f"{_f(_div(par['m_add_kg'], par['m0_kg']), 3)}.")
    tb = [(d["travel_bary_m"], d["pred"]["vehicle_travel_m"],
           d["pred"]["vehicle_travel_analytic_m"]) for d in ok if math.isfinite(d["travel_bary_m"])]
    if tb:
        lines.append(f"- Vehicle travel under VII: measured {_f(1e3 * tb[-1][0], 1)} mm at the "
                     f"largest payload, against κ·r_Δ = {_f(1e3 * tb[-1][1], 1)} mm (the EE line "
                     f"is referenced to the held barycenter, docs/MODEL.md §8, so the payload travels r_Δ "
                     f"inertially) and [87]'s η·r_Δ = {_f(1e3 * tb[-1][2], 1)} mm (r_Δ relative "
                     f"to the vehicle): the drag term scales with the square of this travel.")
    if summ["agree_pred"]:
        lines.append(f"- With these corrections (exact held reaction, vehicle added mass, "
                     f"barycenter-referenced line) the model agrees with the simulation at all "
                     f"{n} loaded payloads (worst {_f(100 * summ['worst_pred'], 1)} %): the "
                     f"remaining effects (attitude loop, feedback, thruster response) are "
                     f"within ±{AGREE_REL:.0%}.")
    else:
        lines.append(f"- Even with these corrections the model differs from the simulation "
                     f"by up to {_f(100 * summ['worst_pred'], 0)} %: the remainder (attitude "
                     f"loop coupling, position feedback, thruster response) is **open**.")
    r_max = analytic.ARM_MAX_TRAVEL_M
    _, mp_star = analytic.payload_limit(r_max, **mpar)
    if summ["agree_89"]:
        lines.append(f"- The payload limit of [89], m_P* = {_f(mp_star, 1)} kg at r_Δ = "
                     f"{_g(r_max, 3)} m, is **confirmed** as far as the simulated payloads "
                     f"reach (it extrapolates a law the simulation follows).")
        rep.exp8b["limit_confirmed"] = True
    else:
        lim = analytic.like_for_like_payload_limit(r_max, par["t_f_s"], m_add_kg=m_add, **mpar)
        rep.exp8b["limit_corrected_kg"] = lim if summ["agree_pred"] else math.nan
        lines.append(f"- The payload limit of [89] ({_f(mp_star, 1)} kg at r_Δ = {_g(r_max, 3)} m) "
                     f"is **not confirmed** by the simulation, whose ratio does not follow [89]"
                     + (f"; the corrected model, which the simulation does follow, reaches 1 at "
                        f"m_P ≈ {_f(lim, 1)} kg for that travel (an extrapolation beyond the "
                        f"simulated payloads)" if summ["agree_pred"] and math.isfinite(lim)
                        else "") + ".")
        rep.exp8b["limit_confirmed"] = False
    md += lines + [""]
    return md
