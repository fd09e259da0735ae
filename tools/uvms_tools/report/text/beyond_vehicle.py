# SPDX-License-Identifier: Apache-2.0
"""beyond_vehicle: the paper's question on a second, real UVMS (campaign beyond_bluerov2: a
BlueROV2 Heavy with a Reach Alpha 5 arm in a pool, docs/MODEL.md §12), and what allocation can
save on each vehicle: the static potential of every campaign's pseudoinverse runs, paper
vehicle against the second one (docs/MODEL.md §7.3)."""
from ..analyses import stats
from ..keys import (ALLOC_MINPOW, ALLOC_PINV, ALLOC_POTENTIAL, ATT, BARY, BEYOND, E_EL, E_P,
                    E_P_ATT, EXPERIMENTS, KEY_ALLOC, KEY_CASE, KEY_GRAVITY, KEY_UNSTEADY,
                    TASK_FINAL, VEH)
from .beyond_gravity import GRAVITY_NAMES
from .common import campaign_comment
from .fmt import fmt_dist, fmt_n, g, table

NAME = "beyond_bluerov2"
SECOND = "BlueROV2 Heavy + Reach Alpha 5"
EXCURSION = "max_vehicle_excursion_m"
FLOWS = ((False, "stagnant"), (True, "unsteady"))


def _cond(gv, case, unsteady, alloc):
    return {KEY_GRAVITY: gv, KEY_CASE: case, KEY_UNSTEADY: unsteady, KEY_ALLOC: alloc}


def _gname(gv):
    return GRAVITY_NAMES.get(gv, gv) if isinstance(gv, str) else f"g = {gv}" 


def _setup(e):
    """The vehicle, its conditions and gains, from the campaign's logged configuration."""
    cfg = e.first_config() or {}

    def val(k):
        v = cfg.get(k)
        return g(float(list(v)[0]), 4) if v is not None and len(v) else "?"
    return [f"Campaign `{NAME}` (sil/campaigns/beyond/bluerov2.toml): a {SECOND} "
            "(sil/scenarios/bluerov2/bluerov2_heavy_alpha5.toml; every parameter and its source "
            "in docs/MODEL.md §12) in a pool: fresh water, Earth gravity, trimmed for the 0.5 kg "
            "sample in its jaws; the g = 0 rows are the same runs without gravity, the control "
            "that shows what the energy at Earth gravity is spent on. Vehicle mass (logged "
            "controller configuration) "
            f"{val('vehicle_mass_kg')} kg, controller density {val('density_kg_m3')} kg/m³, "
            f"gains K_PF = {val('kpf_N_m')} N/m, K_DF = {val('kdf_N_s_m')} N·s/m, "
            f"K_PN = {val('kpn_Nm_rad')} N·m/rad, K_DN = {val('kdn_Nm_s_rad')} N·m·s/rad. "
            "Both cases run the same joint motion (this arm has no SPEC §8 joint-table column, "
            "so there is no \"same task\" pose): case IV holds the vehicle, case VII the "
            "barycenter. Unsteady rows: mean ± half-width of the 95 % CI over the seeds (the "
            "same flow per seed in both cases); stagnant rows: the one deterministic run.", ""]


def _row(e, gv, case, unsteady, alloc, label):
    c = _cond(gv, case, unsteady, alloc)
    d = {k: e.dist(k, c) for k in (E_P, E_P_ATT, E_EL, ATT, TASK_FINAL, EXCURSION,
                                    ALLOC_POTENTIAL)}
    # min_power's thrusts T are not P_pos + P_att: the attitude share T_att,j/T_j of a thrust
    # near zero is unbounded, so its E_p,att is no energy anyone spent (MODEL.md §10).
    att = "n/a" if alloc == ALLOC_MINPOW else fmt_dist(d[E_P_ATT], 2)
    return [_gname(gv), case, label, alloc, fmt_n(d[E_P]), fmt_dist(d[E_P], 2),
            att, fmt_dist(d[E_EL], 1),
            fmt_dist(d[ATT], 1, 1e3), fmt_dist(d[EXCURSION], 2, 1e3),
            fmt_dist(d[TASK_FINAL], 2, 1e3), fmt_dist(d[ALLOC_POTENTIAL], 3, 100.0)]


def _answer(e, gravs, allocs):
    """The paper's question per gravity, flow and allocator: E(VII)/E(IV), paired per seed."""
    rows, verdicts = [], []
    for gv in gravs:
        for unsteady, label in FLOWS:
            for alloc in allocs:
                for metric, name in ((E_P, "E_p"), (E_EL, "E_el")):
                    pa = e.paired(metric, _cond(gv, BARY, unsteady, alloc),
                                  _cond(gv, VEH, unsteady, alloc))
                    verdict = stats.compare(pa) or "n/a"
                    rows.append([_gname(gv), label, alloc, name, fmt_n(pa.dist),
                                 fmt_dist(pa.dist, 4), f"{pa.n_below_1} of {pa.n}", verdict])
                    verdicts.append(verdict)
    md = ["The paper's question on this vehicle: ratio barycenter (VII) / vehicle (IV) of the "
          "propulsive energy E_p and of the thrusters' electrical energy E_el, paired per seed "
          "(geometric mean ± 95 % CI on the log scale; *cheaper* when the whole interval is "
          "below 1, *dearer* when above).", ""]
    md += table(["gravity", "flow", "allocation", "energy", "n", "VII / IV",
                 "seeds with VII cheaper", "verdict"], rows)
    kinds = sorted(set(verdicts))
    md += [f"Verdicts over these {len(verdicts)} comparisons: "
           + ", ".join(f"{verdicts.count(k)} {k}" for k in kinds) + ".", ""]
    return md


def _potential_rows(rep):
    """Static potential of the pseudoinverse runs, per campaign and vehicle."""
    rows = []
    names = [n for n, _ in EXPERIMENTS] + [n for n, _ in BEYOND]
    for name in names:
        e = rep.exp(name)
        if e is None or not e.runs:
            continue
        runs = [r for r in e.select() if e.value(r, KEY_ALLOC) in (None, ALLOC_PINV)]
        vals = [e.metric_value(r, ALLOC_POTENTIAL) for r in runs]
        d = stats.describe([v for v in vals if v is not None])
        if d.n == 0:
            continue
        vehicle = SECOND if name == NAME else "the paper's (SPEC §3)"
        rows.append([f"`{name}`", vehicle, str(d.n), g(100.0 * d.mean, 3), g(100.0 * d.max, 3)])
    return rows


def potential_section(rep):
    """What allocation can save per layout: every campaign's pseudoinverse runs."""
    rows = _potential_rows(rep)
    if not rows:
        return []
    return (["### What allocation can save, per vehicle", "",
             "Static potential of each run: 1 − Σ|T*|^1.5 / Σ|P|^1.5 over its own commanded "
             "wrenches, T* the least-Σ|T|^1.5 thrusts and P the pseudoinverse's "
             "(docs/MODEL.md §7.3), over every pseudoinverse run of each campaign. It bounds what "
             "any allocator could save on that vehicle's thruster layout for those maneuvers.",
             ""]
            + table(["campaign", "vehicle", "runs", "mean [%]", "max [%]"], rows))


def section(rep):
    e = rep.exp(NAME)
    if e is None or not e.runs:
        return potential_section(rep)
    allocs = [a for a in (ALLOC_PINV, ALLOC_MINPOW) if a in e.values(KEY_ALLOC)]
    gravs = e.values(KEY_GRAVITY)
    gravs = [g for g in ("earth", "europa", "paper") if g in gravs] + \
        [g for g in gravs if g not in ("earth", "europa", "paper")]
    md = [f"### A second vehicle: {SECOND}", ""] + campaign_comment(e) + _setup(e)
    rows = [_row(e, gv, case, unsteady, a, label) for gv in gravs for case in (VEH, BARY)
            for unsteady, label in FLOWS for a in allocs]
    md += ["E_p,att: the part of the propulsive energy E_p the attitude wrench accounts for "
           "(docs/MODEL.md §10; the position part is E_p − E_p,att less an unsplit remainder, "
           "and may be negative). n/a with min_power: its thrusts are not the sum of an "
           "attitude and a position allocation, and the attitude share of a thrust it brings "
           "near zero is unbounded, so the split is no energy either part spent.", ""]
    md += table(["gravity", "case", "flow", "allocation", "n", "E_p [J]", "E_p,att [J]", "E_el [J]", "max att. [mrad]", "max excursion [mm]",
                 "final task error [mm]", "static potential [%]"], rows)
    md += _answer(e, gravs, allocs)
    md += _why(e, gravs)
    return md + potential_section(rep)


def _why(e, gravs):
    """What the energy is spent on, from the runs: the attitude part of E_p at Earth gravity
    against E_p without gravity (stagnant, pseudoinverse, case IV)."""
    if "earth" not in gravs or "paper" not in gravs or ALLOC_PINV not in e.values(KEY_ALLOC):
        return []
    c_e, c_0 = _cond("earth", VEH, False, ALLOC_PINV), _cond("paper", VEH, False, ALLOC_PINV)
    ep, att, ep0 = e.dist(E_P, c_e), e.dist(E_P_ATT, c_e), e.dist(E_P, c_0)
    if not (ep.n and att.n and ep0.n) or not ep.mean > 0:
        return []
    return [f"What the energy is spent on (case IV, stagnant, pseudoinverse): at Earth gravity "
            f"the attitude wrench accounts for {g(100.0 * att.mean / ep.mean, 4)} % of "
            f"E_p = {g(ep.mean, 4)} J, and without gravity the same motion needs "
            f"E_p = {g(ep0.mean, 3)} J. The thrusters spend the run holding the vehicle's "
            "attitude against the moment of the arm's weight in water as it reaches out, which "
            "neither position reference changes; the reference decides only the small rest.", ""]
