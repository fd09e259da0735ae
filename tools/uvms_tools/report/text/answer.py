# SPDX-License-Identifier: Apache-2.0
"""answer: the answer box that opens the report: the paper's question (is holding the
barycenter, case VII, cheaper than holding the vehicle, case IV?) in each reading of
docs/MODEL.md §8 and at each gravity, with numbers and 95 % CIs, and one figure. Numbers come
from the scorecard's rows (g = 0) and the gravity decomposition (Europa, Earth)."""
from ..analyses import gravity_decomp as GD
from ..analyses.paper import PAPER_SAVING_STAGNANT, PAPER_TABLE_XI, PAPER_TABLE_XII
from ..figures import answer as figanswer
from ..keys import E_P, VEH
from ..scorecard.rows import BOTH, READINGS
from .fmt import f, fmt_interval, table
from .gravity_decomp import EQUAL_WITHIN


def _row(card, reference, quantity, reading):
    for r in card.rows:
        if r.reference == reference and r.quantity == quantity and r.reading in (reading, BOTH) \
                and (r.row == "case VII" or reference == "Text"):
            return r
    return None


def _scorecard_ratio(card, which, reading):
    r = _row(card, f"Table {which}", "E_p/E_p(IV)", reading)
    return r.ours if r is not None else None


def _saving(card, reading):
    r = _row(card, "Text", "1 − ΣE_p(III, VII, VIII)/ΣE_p(VI, IV, V)", reading)
    return r


def section(rep):
    card = rep.scorecard
    conds, ests, paper = [], {rd: [] for rd in READINGS}, []
    conds += ["g = 0, stagnant (Table XI)", "g = 0, unsteady flow (Table XII)"]
    for which, tab in (("XI", PAPER_TABLE_XI), ("XII", PAPER_TABLE_XII)):
        for rd in READINGS:
            ests[rd].append(_scorecard_ratio(card, which, rd))
        paper.append(tab["VII"][1] / tab[VEH][1])
    dec = GD.decompose(rep, E_P)
    pmax = max((p for _, p in dec), default=None)
    for g, name in (("europa", "Europa"), ("earth", "Earth")):
        d = dec.get((g, pmax))
        if d is None:
            continue
        conds.append(f"{name} gravity, {f(pmax, 0)} kg, unsteady")
        ests["same task"].append(d["total"])
        ests["same motion"].append(d["strategy"])
        paper.append(None)
    rows = [[c, fmt_interval(ests["same task"][i]), fmt_interval(ests["same motion"][i]),
             f(paper[i], 3) if paper[i] is not None else "— (not in the paper)"]
            for i, c in enumerate(conds)]
    md = ["## The answer", "",
          "**Is holding the barycenter (case VII) cheaper than holding the vehicle (case IV)?** "
          "Ratio of propulsive energies E_p(VII)/E_p(IV) (below 1: cheaper), paired per seed "
          "with 95 % CIs over 20 seeds where the flow is random, in both readings of the "
          "paper's experiment: *same task* (each case ends at its reference's joint column, as "
          "the paper states) and *same motion* (every case drives the arm to the vehicle "
          "column, which is what reproduces the paper's energies).", ""]
    md += table(["condition", "same task", "same motion", "paper"], rows)
    md += _sentences(card, dec, pmax)
    md += [f"![The answer: E_p(VII)/E_p(IV) per condition and reading, 95 % CIs, paper's "
           f"values as stars]({figanswer.forest(rep.figs, conds, ests, paper)})", "",
           "Details: the scorecard below (`scorecard.json`), *Unsteady flow, calibrated and "
           "explained* (experiment 1) and *Gravity, decomposed* (beyond the paper).", ""]
    return md


def _sentences(card, dec, pmax):
    out = []
    st, sm = _saving(card, "same task"), _saving(card, "same motion")
    if st is not None and sm is not None and st.ours is not None and sm.ours is not None:
        yes = st.ours.estimate > 0 and sm.ours.estimate > 0
        out.append(f"- **At g = 0, {'yes' if yes else 'not in both readings'}.** In stagnant "
                   f"flow the three reference pairs save {f(100 * sm.ours.estimate, 1)} % with "
                   f"the same motion ({sm.verdict} against the paper's "
                   f"{f(100 * PAPER_SAVING_STAGNANT, 1)} %) and {f(100 * st.ours.estimate, 1)} % "
                   f"with the same task; the unsteady flow's energy, which the position loop "
                   f"pays alike under either reference (experiment 1, *Where the flow's energy "
                   f"goes*), shrinks the saving.")
    acc = {r.reading: r for r in card.rows if r.reference == "Table XI"
           and r.quantity == "task-space error at t_F, VII − IV"}
    if "same motion" in acc and "same task" in acc:
        out.append(f"- **The readings trade energy for the task.** The same motion reproduces "
                   f"the paper's energies, but it leaves the barycenter case's EE away from the "
                   f"target ({acc['same motion'].ours_text}, stagnant); the same task reaches "
                   f"it ({acc['same task'].ours_text}). ε, measured against the controller's "
                   f"own estimate, sees neither.")
    d = dec.get(("earth", pmax)) if pmax is not None else None
    if d is not None and d["strategy"] is not None:
        s = d["strategy"]
        equal = s.has_ci and 1 - EQUAL_WITHIN < s.lo and s.hi < 1 + EQUAL_WITHIN
        head = ("no saving, and no penalty from the strategy" if equal else
                ("the barycenter is cheaper" if s.estimate < 1 else "the barycenter is dearer"))
        out.append(f"- **At Europa and Earth gravity, {head}.** With the same motion VII/IV = "
                   f"{fmt_interval(s)} (Earth, {f(pmax, 0)} kg); with the same task {fmt_interval(d['total'])}, "
                   f"the factor of the barycenter column's pose ({fmt_interval(d['pose'])}).")
    return out + [""]
