# SPDX-License-Identifier: Apache-2.0
"""exp4: model fidelity, every combination of the four model options."""
from ..analyses import inference, stats
from ..analyses.paper import PAPER_TABLE_XIII
from ..figures import exp4 as fig4
from ..keys import BARY, E_EL, E_P, ERR, FIDELITY_KEYS, KEY_CASE, KEY_UNSTEADY, VEH
from .common import img, open_experiment
from .fmt import fmt_dist, fmt_minmax, fmt_n, table

NAME = "exp4_fidelity"
YN = {True: "yes", False: "no"}


def combo_label(cmb):
    """'U/ρ/α/-' of (unsteady, density error, angle of attack, variable coefficients)."""
    return "/".join(s if on else "-" for s, on in zip(("U", "ρ", "α", "C"), cmb))


def section(rep):
    e, md = open_experiment(rep, NAME)
    if e is None:
        return md
    combos = sorted({tuple(bool(e.value(r, k)) for k in FIDELITY_KEYS) for r in e.runs})
    rows, labels, pairs = [], [], []
    for cmb in combos:
        kv = dict(zip(FIDELITY_KEYS, cmb))
        lab = combo_label(cmb)
        pa = rep.add_comparison(NAME, "exp4, " + ("unsteady" if cmb[0] else "steady")
                                + "-flow model combinations", kv, row={KEY_UNSTEADY: cmb[0]},
                                sub=lab)
        dv = e.dist(E_EL, dict(kv, **{KEY_CASE: VEH}))
        db = e.dist(E_EL, dict(kv, **{KEY_CASE: BARY}))
        pairs.append(pa)
        labels.append(lab)
        rows.append([YN[cmb[0]], YN[cmb[1]], YN[cmb[2]], YN[cmb[3]], fmt_n(dv),
                     fmt_dist(dv, 1), fmt_dist(db, 1), fmt_dist(pa.dist, 3),
                     fmt_minmax(pa.dist, 3), f"{pa.n_below_1} of {pa.n}",
                     stats.compare(pa) or "n/a",
                     fmt_dist(e.dist(ERR, dict(kv, **{KEY_CASE: VEH})), 2, 1e3),
                     fmt_dist(e.dist(ERR, dict(kv, **{KEY_CASE: BARY})), 2, 1e3)])
    md += ["Mean ± half-width of the 95 % CI over seeds where seeded (unsteady flow); ratios "
           "paired per seed.", ""]
    md += table(["unsteady flow", "density error", "angle of attack", "variable coeff.", "n",
                 "E_el(IV) [J]", "E_el(VII) [J]", "E(VII)/E(IV)", "min–max",
                 "VII cheaper in", "verdict", "mean ε IV [mm]", "mean ε VII [mm]"], rows)
    paper = {tuple(r[:4]): r[6] for r in PAPER_TABLE_XIII}
    ratios = [inference.ratio_or_none(*(e.series(E_P, dict(zip(FIDELITY_KEYS, c), **{KEY_CASE: k}))
                                        for k in (BARY, VEH))) for c in combos]
    img(md, fig4.fidelity_ratio(rep.figs, ratios, labels, [c[0] for c in combos],
                                [paper.get(c, float("nan")) for c in combos]),
        "Propulsive energy ratio E_p(VII)/E_p(IV) for every combination of the four model "
        "options (geometric mean of the per-seed ratios, 95 % CI where seeded), the paper's "
        "Table XIII as stars.")
    return md
