# SPDX-License-Identifier: Apache-2.0
"""energies: electrical and propulsive energies of experiment 1 against the paper's joules."""
from ..analyses.paper import PAPER_TABLE_XI, PAPER_TABLE_XII
from ..keys import BARY, COND_EXP1_KEYS, COND_EXP1_TEXT, E_EL, E_P, KEY_CASE, VEH
from ..num import div, isnum
from .fmt import f, fmt_dist, fmt_factor, fmt_range, g, table

HEAD = ["## Energies: electrical and propulsive, against the paper's joules", ""]
WHY = (" Why the absolute values cannot match (docs/MODEL.md §5, \"Energy\"): with the Table "
       "VII–VIII motor (k_m = 10 N·m/A, b = 0.01 N·m·s) and propeller (D = 0.05 m) the "
       "electrical energy is dominated by the shaft friction b·ω², which the tiny "
       "propeller's thrust law makes proportional to the thrust impulse, three orders of "
       "magnitude above the paper's printed energies; no reading of the paper's equations "
       "and parameters gives its absolute values. E_p, the physical lower bound, is a "
       "different quantity again. The report therefore compares ratios (E(VII)/E(IV), "
       "E/E(IV)) with the paper's; the two definitions give different ratios since "
       "E_el ∝ ∫|T| while E_p ∝ ∫|T|^1.5.")


def _cond(k, c):
    return dict(COND_EXP1_KEYS[k], **{KEY_CASE: c})


def _table(e, prop):
    """Rows per condition and case, and {(cond, case): (E_el/paper, E_p/paper)}."""
    rows, fac = [], {}
    for k, paper in (("stagnant", PAPER_TABLE_XI), ("unsteady", PAPER_TABLE_XII)):
        for c in (VEH, BARY):
            de, dp = e.dist(E_EL, _cond(k, c)), e.dist(prop, _cond(k, c))
            fac[(k, c)] = (div(de.mean, paper[c][1]), div(dp.mean, paper[c][1]))
            rows.append([COND_EXP1_TEXT[k], c, g(paper[c][1], 4), fmt_dist(de, 1),
                         fmt_factor(de.mean, paper[c][1]), fmt_dist(dp, 4, sig=3),
                         fmt_factor(dp.mean, paper[c][1])])
        pe = e.paired(E_EL, _cond(k, BARY), _cond(k, VEH))
        pp = e.paired(prop, _cond(k, BARY), _cond(k, VEH))
        rows.append([COND_EXP1_TEXT[k], "ratio VII/IV", f(div(paper[BARY][1], paper[VEH][1]), 3),
                     fmt_dist(pe.dist, 3), "", fmt_dist(pp.dist, 3), ""])
    return table(["condition", "case", "paper [J] (Tables XI, XII)", "E_el ours [J]",
                  "E_el/paper", "E_p ours [J]", "E_p/paper"], rows), fac


def section(rep):
    e = rep.exp("exp1_cases")
    if e is None:
        return HEAD + ["*exp1_cases not found.*", ""]
    prop = rep.metric(e, E_P)
    p11 = PAPER_TABLE_XI
    md, fac = _table(e, prop)
    share = rep.energy_info.get((VEH, "stagnant"), {}).get("fric_share")
    e_iv = e.dist(E_EL, _cond("stagnant", VEH)).mean
    p_iv = e.dist(prop, _cond("stagnant", VEH)).mean
    alle = [x for v in fac.values() for x in v[:1] if isnum(x)]
    allp = [x for v in fac.values() for x in v[1:] if isnum(x)]
    near = bool(allp) and 0.5 <= min(allp) and max(allp) <= 2.0
    rp_s = e.paired(prop, _cond("stagnant", BARY), _cond("stagnant", VEH)).dist.mean
    text = (f"**Which magnitude each definition gives.** The paper's Table XI gives "
            f"{g(p11[VEH][1], 4)} J for case IV. Ours: the electrical (battery) energy "
            f"E_el = {g(e_iv / 1e3, 3)} kJ = {f(e_iv, 1)} J, {fmt_factor(e_iv, p11[VEH][1])} "
            f"the paper's; the propulsive energy E_p (the least any propeller can spend to "
            f"make the same thrust, docs/MODEL.md §5) = {g(p_iv, 3)} J, "
            f"{fmt_factor(p_iv, p11[VEH][1])} the paper's. Over the IV and VII rows of both "
            f"tables the factors ours/paper are {fmt_range(alle, 0)} (E_el) and "
            f"{fmt_range(allp, 2)} (E_p)."
            + (f" In experiment 3 the motor friction ∫Σb·ω² dt is {f(100 * share, 1)} % of "
               f"E_el (case IV, stagnant)." if isnum(share) else "") + WHY
            + (f" E_p lands within a factor {fmt_range(allp, 2)} of the paper's joules in "
               f"these rows, and with the same motion its ratios reproduce Table XI: the "
               f"scorecard's energy verdicts use it. The friction study (docs/MODEL.md §5, "
               f"`sil/campaigns/studies/exp9_friction.toml`) found no reading of the motor's "
               f"parameters that makes ∫V·I give both the paper's joules and its ratios."
               if near else "")
            + _implied(e, e_iv)
            + (" E_p was computed here from the truth logs (thrust per tick) because these "
               "runs' summary.json lacks it." if rep.prop_from_logs else ""))
    return HEAD + md + [text, ""]


def _implied(e, e_iv):
    """What E_el with the paper's motor implies: the mean battery power and the largest motor
    voltage of case IV's stagnant run (its log's truth)."""
    import numpy as np
    run = e.one(_cond("stagnant", VEH))
    lg = e.log(run, ["UVMS_TRUTH"]) if run is not None else None
    dur = run.get("duration_s") if run is not None else None
    if not lg or "UVMS_TRUTH" not in lg or not isnum(dur) or not isnum(e_iv):
        return ""
    v = np.abs(np.asarray(lg["UVMS_TRUTH"]["motor_voltage_V"], float))
    return (f" With the paper's motor, case IV's E_el is a mean battery power of "
            f"{g(e_iv / dur, 3)} W over its {g(dur, 3)} s, at motor voltages up to "
            f"{g(float(v.max()), 3)} V (truth log): the watts of a motor whose friction "
            f"alone turns small thrusts into hundreds of joules. "
            f"`thrusters.motor = \"t200\"` (docs/MODEL.md §5) gives battery watts of a real "
            f"thruster.")
