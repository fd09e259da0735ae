# SPDX-License-Identifier: Apache-2.0
"""exp7: the energy split between thrusters and manipulator."""
from ..analyses import inference
from ..figures import exp7 as fig7
from ..keys import BARY, E_EL, E_MAN, E_P, KEY_CASE, KEY_PAYLOAD, VEH
from ..num import div
from .common import img, open_experiment
from .fmt import f, g, table

NAME = "exp7_energy_split"
METRIC = {"thr": E_EL, "man": E_MAN}


def section(rep):
    e, md = open_experiment(rep, NAME)
    if e is None:
        return md
    pays = e.values(KEY_PAYLOAD)
    means = {(c, w): [e.dist(METRIC[w], {KEY_CASE: c, KEY_PAYLOAD: p}).mean for p in pays]
             for c in (VEH, BARY) for w in ("thr", "man")}
    ratios = {w: [inference.ratio_or_none(e.series(m, {KEY_CASE: BARY, KEY_PAYLOAD: p}),
                                          e.series(m, {KEY_CASE: VEH, KEY_PAYLOAD: p}))
                  for p in pays] for w, m in (("thr", E_P), ("man", E_MAN))}
    img(md, fig7.energy_split(rep.figs, pays, means, ratios),
        "Left: thruster and manipulator energy per payload (log scale). Right: each over its "
        "vehicle-stabilization value, per payload.")
    rows = []
    for i, p in enumerate(pays):
        ev, mv = means[(VEH, "thr")][i], means[(VEH, "man")][i]
        eb, mb = means[(BARY, "thr")][i], means[(BARY, "man")][i]
        rows.append([f(p, 0), f(ev, 1), g(mv, 3), g(div(ev, mv), 3), f(eb, 1), g(mb, 3),
                     g(div(eb, mb), 3), f(div(mb, mv), 3)])
    md += table(["m_P [kg]", "IV thrusters [J]", "IV manipulator [J]", "IV thr./manip.",
                 "VII thrusters [J]", "VII manipulator [J]", "VII thr./manip.",
                 "manip. VII/IV"], rows)
    return md + ["Manipulator energy is ∫Σ|τ_i·θ̇_i| dt (docs/MODEL.md §5): the ideal joint "
                 "drives' mechanical work, without motor losses.", ""]
