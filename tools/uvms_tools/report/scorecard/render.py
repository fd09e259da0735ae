# SPDX-License-Identifier: Apache-2.0
"""render: the markdown scorecard, generated from the Scorecard's rows (the same rows as
scorecard.json): Tables XI and XII and the savings with the two readings side by side, then
Table XIII, the statements and the analytic limits."""
import math

from ..analyses import inference, stats, verdicts
from ..analyses.paper import PAPER
from ..text.fmt import f, g, table
from ..text.tally import EXCLUDED_LABEL, EXCLUDED_WHY
from . import cases
from .rows import BOTH, READINGS

DIGITS = {"mm": 2, "J": 4, "kg": 1, "m": 3}


def _num(x, unit, quantity):
    if "E_p/E_p" in quantity or "change" in quantity:
        return f(x, 3)
    if quantity.startswith("1 − "):
        return f(100 * x, 1) + " %"
    return g(x, 4) if unit == "J" else f(x, DIGITS.get(unit, 3))


def ours_text(r):
    o = r.ours
    if r.rule["kind"] == "statement" or o is None:
        return r.ours_text or "n/a"
    pct = r.quantity.startswith("1 − ") or "change" in r.quantity or r.rule.get("ref") == 0.0
    sc, nd = (100.0, 1) if pct else (1.0, DIGITS.get(r.unit, 3))
    unit = " %" if pct else ""
    if o.deterministic:
        return f"{f(sc * o.estimate, nd)}{unit} (deterministic)"
    return (f"{f(sc * o.estimate, nd)}{unit} [{f(sc * o.lo, nd)}, {f(sc * o.hi, nd)}] "
            f"(n = {o.n})" + (" †" if _holm_dagger(r) else ""))


def paper_text(r):
    if r.paper is None:
        return "—"
    pct = r.quantity.startswith("1 − ") or r.rule.get("ref") == 0.0
    return f"{f(100 * r.paper, 1)} %" if pct else _num(r.paper, r.unit, r.quantity)


def _holm_dagger(r):
    """The row's direction rests on a CI over seeds but does not survive Holm's adjustment."""
    return (r.rule["kind"] == "directional" and r.ours is not None and r.ours.excludes_null
            and math.isfinite(r.p_holm) and r.p_holm >= inference.FAMILY_ALPHA)


def verdict_text(r):
    if r.excluded:
        return f"{r.verdict} (not tallied: {EXCLUDED_LABEL[r.excluded]})"
    return r.verdict if r.verdict == stats.REPRODUCED else f"**{r.verdict}**"


def cause_text(r):
    parts = [] if r.cause in ("", "—") else [r.cause]
    extra = [d["note"] for d in r.depends_on if d["note"] not in r.cause]
    return "; ".join(parts + extra) or "—"


def _pivot(rows, key_cols):
    """{key: {reading: row}} for rows sharing reference/row/quantity."""
    out = {}
    for r in rows:
        out.setdefault(key_cols(r), {})[r.reading] = r
    return out


def _causes_cell(causes):
    """One cause when both readings give the same, else each prefixed by its reading."""
    texts = {c for _, c in causes}
    if len(texts) == 1:
        return texts.pop()
    return "; ".join(f"*{rd}*: {c}" for rd, c in causes if c != "—") or "—"


def readings_table(rows, first_col):
    """Rows with two readings side by side; a row of BOTH fills both columns."""
    piv = _pivot(rows, lambda r: (r.row, r.quantity))
    body = []
    for (row, qty), by in piv.items():
        any_r = next(iter(by.values()))
        cells = [row, qty + (f" [{any_r.unit}]" if any_r.unit else ""), paper_text(any_r)]
        causes = []
        for rd in READINGS:
            r = by.get(rd) or by.get(BOTH)
            if r is None:
                cells += ["—", "—"]
                continue
            same = " (same runs)" if r.reading == BOTH else ""
            cells += [ours_text(r) + same, verdict_text(r)]
            causes.append((rd, cause_text(r)))
        txt = _causes_cell(causes)
        body.append(cells + [txt or "—"])
    return table([first_col, "quantity", "paper", "ours, same task", "verdict",
                  "ours, same motion", "verdict", "cause of differences"], body)


def plain_table(rows):
    body = [[r.reference, r.row, r.quantity + (f" [{r.unit}]" if r.unit else ""), r.reading,
             paper_text(r), ours_text(r), verdict_text(r), cause_text(r)] for r in rows]
    return table(["reference", "row", "quantity", "reading", "paper", "ours", "verdict",
                  "cause of differences"], body)


def _tally_line(card):
    parts = []
    for rd in READINGS:
        t = card.tally(rd)
        n = sum(t.values())
        parts.append(f"*{rd}*: {t[stats.REPRODUCED]} reproduced, {t[stats.SAME_DIRECTION]} "
                     f"same direction, {t[stats.DIFFERS]} differ"
                     + (f", {t[stats.NOT_MEASURED]} not measured" if t[stats.NOT_MEASURED]
                        else "") + f" (of {n})")
    excl = {}
    for r in card.rows:
        if r.excluded:
            excl[r.excluded] = excl.get(r.excluded, 0) + 1
    ex = "; ".join(f"{n} {EXCLUDED_LABEL[c]} ({EXCLUDED_WHY[c]})" for c, n in excl.items())
    return (f"**Tally over the substantive verdicts, per reading** (a row whose runs are the "
            f"same in both readings counts in each; experiments 2–8 run the same task only, so "
            f"their rows count for it alone): " + "; ".join(parts) + "."
            + (f" Not tallied: {ex}." if ex else ""))


def _which_line(card, refs):
    out = []
    for ref in refs:
        best, score = card.reading_for(ref)
        sc = ", ".join(f"{rd} {score[rd][0]} of {score[rd][1]}" for rd in READINGS)
        out.append(f"{ref}: " + (f"**{best}** reproduces it best" if best else "a tie")
                   + f" (reproduced: {sc})")
    return "**Which reading reproduces each table.** " + "; ".join(out) + "."


def _energy_basis(card):
    b = cases.energy_basis(card.rep)
    if not b:
        return ""
    (p0, p1), (e0, e1) = b["ep_factor"], b["eel_factor"]
    return ("**Energy.** Every energy verdict uses the propulsive energy E_p = ∫Σ|T|^1.5/"
            "√(2ρA_d) dt (docs/MODEL.md §5): in Table XI's stagnant runs with the same motion "
            f"its joules are {f(p0, 2)}–{f(p1, 2)} × the paper's, while the electrical energy "
            f"E_el = ∫Σ max(V·I, 0) dt with the paper's motor is {g(e0, 3)}–{g(e1, 3)} × them "
            "(friction-dominated, docs/MODEL.md §5, *Energies*). E_el stays in the results and "
            "the Energies section.")


def markdown(card):
    rows = card.rows
    md = ["## Reproduction scorecard", "",
          f"The paper's printed numbers ({PAPER}) beside this project's, one row per number, "
          "each in the readings of docs/MODEL.md §8 that apply: *same task* (every case ends "
          "at its reference's column of the joint table) and *same motion* (every case drives "
          "the arm to the \"Veh.\" column). The rows are generated from `scorecard.json` "
          "(one object per row: reference, row, quantity, reading, the paper's value, ours "
          "with CI and n, the rule, the verdict and its cause).", "",
          _energy_basis(card), "", _tally_line(card), "",
          _which_line(card, ("Table XI", "Table XII", "Text")), "",
          verdicts.DIRECTION_RULE_TEXT, "",
          inference.MULTIPLICITY_POLICY + " Verdicts use each row's own 95 % interval; a † marks "
          "a direction that rests on an interval over seeds but does not survive Holm's "
          "adjustment. Intervals: ratios are paired per seed on the log scale (geometric mean "
          "ratio, Student t on the log ratios); means of ε and E_p are Student t intervals; a "
          "deterministic row (one run, or no spread) has no interval.", ""]
    for which in ("XI", "XII"):
        ref = f"Table {which}"
        sel = [r for r in rows if r.reference == ref and r.rule["kind"] != "statement"]
        acc = [r for r in rows if r.reference == ref and r.rule["kind"] == "statement"]
        if sel:
            title = ("stagnant flow, no density error" if which == "XI"
                     else "unsteady flow + density error, 20 seeds")
            md += [f"### {ref} — {title} (experiment 1)", ""] + readings_table(sel, "case")
        if acc:
            md += [f"Accuracy in the task (Table {which}'s ε are the paper's evidence of "
                   "similar accuracy; ε compares the EE with the controller's own estimate, so "
                   "the task-space error, the EE's distance from the target point, docs/MODEL.md "
                   "§10, judges it):", ""] + plain_table(acc)
    sel = [r for r in rows if r.reference == "Text"]
    if sel:
        md += ["### The text's savings", ""] + readings_table(sel, "claim")
    for title, pick in (("Table XIII — model fidelity (experiment 4)",
                         lambda r: r.reference == "Table XIII"),
                        ("Statements read from the text and figures",
                         lambda r: r.reference.startswith("Fig")),
                        ("Analytic model [87–89] (experiments 8 and 8b)",
                         lambda r: r.reference.startswith("[8"))):
        sel = [r for r in rows if pick(r)]
        if sel:
            md += [f"### {title}", ""] + plain_table(sel)
    return md
