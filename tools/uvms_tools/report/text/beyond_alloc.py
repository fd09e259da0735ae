# SPDX-License-Identifier: Apache-2.0
"""beyond_alloc: the energy saving of the least-Σ|T| allocation (min_abs_thrust) against the
pseudoinverse, paired per case and seed, on the paper's experiment 1 (beyond_allocation) and
in the gravity campaign (beyond_gravity), and whether it changes the answer to the paper's
question."""
import numpy as np

from ..analyses import beyond as B
from ..analyses import stats
from ..figures import beyond as figb
from ..keys import (ALLOC_MINABS, ALLOC_PINV, ATT, BARY, CASES, COND_EXP1_KEYS, COND_EXP1_TEXT,
                    E_EL, ERR, KEY_ALLOC, KEY_CASE, MATCHED_PAIRS, VEH)
from ..load.logs import has
from .common import campaign_comment, img
from .beyond_gravity import span
from .fmt import f, fmt_ci, fmt_dist, fmt_n, g, table

CONDS = ["stagnant", "unsteady"]
DIRECTION = {1: "saves", -1: "costs more", 0: "no significant difference", None: "n/a"}


def _c1(c, k, a):
    return dict(COND_EXP1_KEYS[k], **{KEY_CASE: c, KEY_ALLOC: a})


class Effect:
    """What min_abs_thrust does against the pseudoinverse in one condition (paired per seed):
    the energy saving, and the changes of mean EE error and max attitude error."""

    def __init__(self, e, cond):
        old, new = dict(cond, **{KEY_ALLOC: ALLOC_PINV}), dict(cond, **{KEY_ALLOC: ALLOC_MINABS})
        self.e_old, self.e_new = e.dist(E_EL, old), e.dist(E_EL, new)
        self.saving = B.paired_saving(e.series(E_EL, new), e.series(E_EL, old))
        self.d_err = stats.paired_difference(e.series(ERR, new), e.series(ERR, old))
        self.d_att = stats.paired_difference(e.series(ATT, new), e.series(ATT, old))

    def cells(self, scale=1.0, sig=None, nd=1):
        sv = self.saving
        return [fmt_n(self.e_old), fmt_dist(self.e_old, nd, scale, sig=sig),
                fmt_dist(self.e_new, nd, scale, sig=sig), fmt_dist(sv.dist, 2, 100),
                fmt_ci(sv.dist, 2, 100), f"{sv.n_cheaper} of {sv.n}" if sv.n else "—",
                fmt_dist(self.d_err.dist, 3, 1e3), fmt_dist(self.d_att.dist, 3, 1e3)]


EFFECT_HDR = ["n", "E_el pseudoinverse", "E_el min_abs_thrust", "saving [%]", "95 % CI",
              "min_abs cheaper in", "Δ mean ε [mm]", "Δ max att. error [mrad]"]


def _change_row(e, num_p, den_p, num_m, den_m):
    """((verdict changed, direction of the paired ratio change), cells) of one
    barycenter/vehicle comparison under both allocators."""
    pa_p, pa_m = e.paired(E_EL, num_p, den_p), e.paired(E_EL, num_m, den_m)
    ch = B.ratio_change(e.series(E_EL, num_p), e.series(E_EL, den_p),
                        e.series(E_EL, num_m), e.series(E_EL, den_m))
    vp, vm, changed = B.answer_change(pa_p, pa_m)
    cells = [fmt_dist(pa_p.dist, 3), fmt_dist(pa_m.dist, 3), fmt_dist(ch.dist, 3),
             fmt_ci(ch.dist, 3), vp or "n/a", vm or "n/a",
             "n/a" if changed is None else ("**yes**" if changed else "no")]
    return (changed, stats.direction(ch)), cells


CHANGE_HDR = ["E(bary)/E(veh), pseudoinverse", "min_abs_thrust", "Δ ratio (min_abs − pinv)",
              "95 % CI", "verdict, pseudoinverse", "verdict, min_abs_thrust",
              "answer changes"]


def _paper_tables(ea):
    rows, sav, changes = [], {}, []
    for c in CASES:
        for k in CONDS:
            ef = Effect(ea, dict(COND_EXP1_KEYS[k], **{KEY_CASE: c}))
            sav[(c, CONDS.index(k))] = ef
            rows.append([c, COND_EXP1_TEXT[k]] + ef.cells())
    crows = []
    for k in CONDS:
        for v, b in MATCHED_PAIRS:
            changed, cells = _change_row(ea, _c1(b, k, ALLOC_PINV), _c1(v, k, ALLOC_PINV),
                                         _c1(b, k, ALLOC_MINABS), _c1(v, k, ALLOC_MINABS))
            changes.append((f"experiment 1, {COND_EXP1_TEXT[k]}, {b}/{v}", *changed))
            crows.append([COND_EXP1_TEXT[k], f"{b} / {v}"] + cells)
    return (table(["case", "condition"] + [h + (" [J]" if h.startswith("E_el") else "")
                                          for h in EFFECT_HDR], rows),
            table(["condition", "barycenter / vehicle"] + CHANGE_HDR, crows), sav, changes)


def _exp1_check(rep, ea):
    """How many pseudoinverse runs of beyond_allocation give experiment 1's energy exactly."""
    e1 = rep.exp("exp1_cases")
    if e1 is None:
        return []
    same = n = 0
    for c in CASES:
        for k in CONDS:
            a = ea.series(E_EL, _c1(c, k, ALLOC_PINV))
            b = e1.series(E_EL, dict(COND_EXP1_KEYS[k], **{KEY_CASE: c}))
            n += len(set(a) | set(b))
            same += sum(1 for s in a if s in b and a[s] == b[s])
    return [f"Check: the pseudoinverse half repeats experiment 1 (same settings and seeds): "
            f"{same} of {n} runs give its thruster energy bit for bit.", ""]


def _gravity_tables(gr):
    rows, sav, crows, changes = [], {}, [], []
    for j, g in enumerate(gr.gravs):
        for p in gr.pays:
            for c in (VEH, BARY):
                ef = Effect(gr.e, gr.base(g, c, p))
                sav.setdefault((j, c), []).append(ef)
                rows.append([gr.labels[j], f(p, 0), c] + ef.cells(1e-3, sig=3))
            changed, cells = _change_row(gr.e, gr.cond(g, BARY, p, ALLOC_PINV),
                                         gr.cond(g, VEH, p, ALLOC_PINV),
                                         gr.cond(g, BARY, p, ALLOC_MINABS),
                                         gr.cond(g, VEH, p, ALLOC_MINABS))
            changes.append((f"{gr.labels[j]}, {f(p, 0)} kg", *changed))
            crows.append([gr.labels[j], f(p, 0)] + cells)
    return (table(["gravity", "m_P [kg]", "case"] + [h + (" [kJ]" if h.startswith("E_el") else "")
                                                     for h in EFFECT_HDR], rows),
            table(["gravity", "m_P [kg]"] + CHANGE_HDR, crows), sav, changes)


def _activity(e, cond):
    """analyses.beyond.command_activity of the commanded thrusts (telemetry thrust_des_N) of
    the lowest-seed run of cond; None without its log."""
    lg = e.log(e.one(cond), ["UVMS_TELEMETRY"])
    if not has(lg, "UVMS_TELEMETRY"):
        return None
    return B.command_activity(lg["UVMS_TELEMETRY"]["t_s"], lg["UVMS_TELEMETRY"]["thrust_des_N"])


def _activity_row(label, e, conds):
    """label, n conditions, then per allocator the mean ∫Σ|T_des| dt and total variation."""
    cells = [label, str(len(conds))]
    for a in (ALLOC_PINV, ALLOC_MINABS):
        acts = [x for x in (_activity(e, dict(c, **{KEY_ALLOC: a})) for c in conds) if x]
        cells += ([f(np.mean([x[0] for x in acts]), 1), g(np.mean([x[1] for x in acts]), 3)]
                  if acts else ["n/a", "n/a"])
    return cells


def activity_table(ea, gr):
    """The commanded thrusts of both allocators: impulse and tick-to-tick jumps, averaged over
    the conditions (cases II–VIII in experiment 1; IV, VII × payloads per gravity)."""
    rows = []
    if ea is not None:
        rows += [_activity_row(f"experiment 1, {COND_EXP1_TEXT[k]}", ea,
                               [dict(COND_EXP1_KEYS[k], **{KEY_CASE: c}) for c in CASES[1:]])
                 for k in CONDS]
    if gr is not None:
        rows += [_activity_row(gr.labels[j], gr.e,
                               [gr.base(gv, c, p) for c in (VEH, BARY) for p in gr.pays])
                 for j, gv in enumerate(gr.gravs)]
    if not rows:
        return []
    return (["**The commanded thrusts.** The LP gives the least Σ|T| for each tick's wrench; "
             "its solution is a vertex of the feasible set, which can jump from one set of "
             "thrusters to another between ticks, while the thrusters follow with their lag "
             "(docs/MODEL.md §7.4). Impulse and tick-to-tick jumps of the commanded thrusts "
             "(telemetry `thrust_des_N`) of each condition's lowest-seed run, averaged over the "
             "conditions:", ""]
            + table(["campaign / gravity", "conditions", "pseudoinverse: ∫Σ|T_des| dt [N·s]",
                     "Σ|ΔT_des| tick to tick [N]", "min_abs_thrust: ∫Σ|T_des| dt [N·s]",
                     "Σ|ΔT_des| tick to tick [N]"], rows))


def _saving_summary(label, effects):
    """'label: saves in k, costs more in m, … of n; mean saving a to b %; Δε, Δ attitude'."""
    efs = [x for x in effects if x.saving.n]
    if not efs:
        return f"- {label}: not measured."
    dirs = [stats.direction(x.saving.dist) for x in efs]
    counts = ", ".join(f"{DIRECTION[d]} in {dirs.count(d)}" for d in (1, -1, 0) if dirs.count(d))
    return (f"- **{label}**: min_abs_thrust {counts} of {len(efs)} conditions; mean saving "
            f"{span([100 * x.saving.dist.mean for x in efs], 2)} %; mean change of the mean EE "
            f"error {span([1e3 * x.d_err.dist.mean for x in efs], 2)} mm, of the max attitude "
            f"error {span([1e3 * x.d_att.dist.mean for x in efs], 2)} mrad.")


def _change_summary(changes):
    """changes: [(label, verdict changed, direction of the paired ratio change)]."""
    meas = [(lab, c, d) for lab, c, d in changes if c is not None]
    ch = [(lab, d) for lab, c, d in meas if c]
    moved = [lab for lab, _, d in meas if d in (1, -1)]
    return (f"- **Does it change the answer to the paper's question?** The verdict on "
            f"barycenter vs vehicle (cheaper / no significant difference / dearer) changes in "
            f"{len(ch)} of {len(meas)} comparisons"
            + (": " + "; ".join(f"{lab} (the paired ratio itself "
                                 f"{'moves' if d in (1, -1) else 'does not move significantly'})"
                                 for lab, d in ch) if ch else "")
            + f". The paired ratio E(bary)/E(veh) moves significantly (95 % CI of its change "
              f"excludes 0) in {len(moved)} of {len(meas)}.")


def section(rep, ea, gr):
    """ea: the beyond_allocation Experiment (or None); gr: beyond_gravity's Grid (or None)."""
    md = ["### Energy-optimal allocation: min_abs_thrust against the pseudoinverse", "",
          "Saving = 1 − E_el(min_abs_thrust)/E_el(pseudoinverse), paired per case and seed "
          "(same flow); Δ = min_abs_thrust − pseudoinverse, paired per seed; mean ± half-width "
          "of the 95 % CI over seeds where seeded (a stagnant row is one deterministic run). "
          "Case I has no control and no thrust: no saving to measure. A condition counts as "
          "*saves* / *costs more* when the 95 % CI of its paired saving lies above / below 0 "
          "(one deterministic run: its sign), else *no significant difference*.", ""]
    md += campaign_comment(ea) if ea is not None else []
    summary, body, changes = [], [], []
    paper_ef, grav_ef = {}, {}
    if ea is not None:
        t_eff, t_chg, paper_ef, ch = _paper_tables(ea)
        changes += ch
        for k in CONDS:
            summary.append(_saving_summary(f"Experiment 1, {COND_EXP1_TEXT[k]}",
                                           [paper_ef[(c, CONDS.index(k))] for c in CASES]))
        body += ["**The paper's experiment 1** (campaign `beyond_allocation`):", ""] + t_eff
        body += _exp1_check(rep, ea)
        body += ["Barycenter vs vehicle under each allocator (the case pairs that differ only "
                 "in the position reference; ratios paired per seed):", ""] + t_chg
    if gr is not None and ALLOC_PINV in gr.allocs and ALLOC_MINABS in gr.allocs:
        t_eff, t_chg, grav_ef, ch = _gravity_tables(gr)
        changes += ch
        for j, gl in enumerate(gr.labels):
            efs = [x for c in (VEH, BARY) for x in grav_ef.get((j, c), [])]
            summary.append(_saving_summary(f"{gl} (gravity campaign)", efs))
        body += ["**The gravity campaign** (`beyond_gravity`, unsteady flow, energies in kJ):",
                 ""] + t_eff
        body += ["Barycenter (VII) vs vehicle (IV) under each allocator:", ""] + t_chg
    body += activity_table(ea, gr)
    md += summary + [_change_summary(changes), ""] + body
    if paper_ef or grav_ef:
        img(md, figb.allocation_saving(rep.figs, {k: x.saving for k, x in paper_ef.items()},
                                       [COND_EXP1_TEXT[k] for k in CONDS],
                                       {k: [x.saving for x in v] for k, v in grav_ef.items()},
                                       gr.labels if gr else [], gr.pays if gr else []),
            "Energy saving of min_abs_thrust against the pseudoinverse: left, the eight cases "
            "of experiment 1 in both conditions; right, the gravity campaign per gravity, case "
            "and payload (error bars: 95 % CI over seeds).")
    return md

