# SPDX-License-Identifier: Apache-2.0
"""exp2: the payload sweep in conditions A, B, C."""
from ..analyses import inference
from ..analyses.paper import PAPER_TABLE_XI, PAPER_TABLE_XII, PAPER_TABLE_XIII
from ..figures import exp2 as fig2
from ..keys import BARY, COND_EXP2_KEYS, COND_EXP2_TEXT, E_EL, E_P, ERR, KEY_CASE, KEY_PAYLOAD, VEH
from ..num import isnum
from .common import img, open_experiment
from .fmt import f, fmt_dist, fmt_minmax, fmt_n, table

NAME = "exp2_payload"
CONDS = ["A", "B", "C"]


def _cond(c, k, p):
    return dict(COND_EXP2_KEYS[k], **{KEY_CASE: c, KEY_PAYLOAD: p})


# The paper's 10 kg points: Table XI (A), Table XIII's stagnant density-error row (B, energy
# only), Table XII (C).
PAPER_PAYLOAD_KG = 10.0


def _paper_ratio():
    b = next(r for r in PAPER_TABLE_XIII if r[:4] == (False, True, False, False))
    return {"A": (PAPER_PAYLOAD_KG, PAPER_TABLE_XI[BARY][1] / PAPER_TABLE_XI[VEH][1]),
            "B": (PAPER_PAYLOAD_KG, b[6]),
            "C": (PAPER_PAYLOAD_KG, PAPER_TABLE_XII[BARY][1] / PAPER_TABLE_XII[VEH][1])}


def _paper_error():
    return {(c, k): (PAPER_PAYLOAD_KG, t[c][0]) for c in (VEH, BARY)
            for k, t in (("A", PAPER_TABLE_XI), ("C", PAPER_TABLE_XII))}


def _figures(rep, e, pays):
    n_seeds = {k: e.n_seeds(_cond(VEH, k, pays[0])) if pays else 0 for k in CONDS}
    ratios = {k: [inference.ratio_or_none(e.series(E_P, _cond(BARY, k, p)),
                                          e.series(E_P, _cond(VEH, k, p))) for p in pays]
              for k in CONDS}
    dists = {(c, k): [e.dist(ERR, _cond(c, k, p)) for p in pays]
             for k in CONDS for c in (VEH, BARY)}
    return {"energy": fig2.payload_ratio(rep.figs, pays, ratios, _paper_ratio(), n_seeds),
            "error": fig2.payload_error(rep.figs, pays, dists, _paper_error(), n_seeds)}


def _row(rep, e, k, p, prop):
    dv, db = e.dist(E_EL, _cond(VEH, k, p)), e.dist(E_EL, _cond(BARY, k, p))
    pa = rep.add_comparison(NAME, f"exp2, {COND_EXP2_TEXT[k]}",
                            COND_EXP2_KEYS[k] | {KEY_PAYLOAD: p}, row=COND_EXP2_KEYS[k],
                            sub=f"{f(p, 0)} kg")
    cells = [COND_EXP2_TEXT[k], f(p, 0), fmt_n(dv), fmt_dist(dv, 1), fmt_dist(db, 1)]
    if prop:
        cells += [fmt_dist(e.dist(prop, _cond(VEH, k, p)), 3, sig=3),
                  fmt_dist(e.dist(prop, _cond(BARY, k, p)), 3, sig=3)]
    return cells + [fmt_dist(pa.dist, 3), fmt_minmax(pa.dist, 3), f"{pa.n_below_1} of {pa.n}",
                    fmt_dist(e.dist(ERR, _cond(VEH, k, p)), 2, 1e3),
                    fmt_dist(e.dist(ERR, _cond(BARY, k, p)), 2, 1e3)]


def section(rep):
    e, md = open_experiment(rep, NAME)
    if e is None:
        return md
    pays = e.values(KEY_PAYLOAD)
    figs = _figures(rep, e, pays)
    img(md, figs["energy"], "Propulsive energy of case VII over case IV vs payload in "
        "conditions A, B, C: the geometric mean of the per-seed ratios with its 95 % CI where "
        "seeded (condition C); the paper's 10 kg ratio as a star; one y-axis.")
    img(md, figs["error"], "Mean EE error vs payload in conditions A, B, C (error bars: "
        "95 % CI over seeds); the paper's 10 kg errors as stars.")
    prop = rep.metric(e, E_P) if all(isnum(r.get(E_P)) for r in e.runs) else None
    rows = [_row(rep, e, k, p, prop) for k in CONDS for p in pays]
    hdr = ["condition", "m_P [kg]", "n", "E_el(IV) [J]", "E_el(VII) [J]"]
    if prop:
        hdr += ["E_p(IV) [J]", "E_p(VII) [J]"]
    hdr += ["E_el(VII)/E_el(IV) paired", "min–max", "VII cheaper in", "mean ε IV [mm]",
            "mean ε VII [mm]"]
    md += ["Mean ± half-width of the 95 % CI over seeds where seeded (condition C); ratios "
           "paired per seed.", ""]
    return md + table(hdr, rows)
