# SPDX-License-Identifier: Apache-2.0
"""beyond_alloc: the minimum-power allocation (min_power: the thrusts of least Σ|T|^1.5 that
deliver the pseudoinverse's wrench, docs/MODEL.md §7.3) against the pseudoinverse, paired per
case and seed, on the paper's experiment 1 with the feedforward lead (beyond_allocation) and in
the gravity campaign (beyond_gravity): the closed-loop errors, the static potential and the
realised saving of the cost the allocator minimises, the electrical energy, and whether the
allocator changes the answer to the paper's question. Effect and its *_cells are also used by
beyond_lead (the allocators with the lead off and on)."""
import numpy as np

from ..analyses import beyond as B
from ..analyses import stats
from ..figures import beyond as figb
from ..keys import (ALLOC_COST_CMD, ALLOC_COST_PINV, ALLOC_MINPOW, ALLOC_PINV, ALLOC_POTENTIAL, ALLOC_REALISED,
                    ALLOC_UNSOLVED, ATT, BARY, CASES, COND_EXP1_KEYS, COND_EXP1_TEXT, E_EL, ERR,
                    KEY_ALLOC, KEY_CASE, KEY_LEAD, MATCHED_PAIRS, VEH)
from ..load.logs import has
from ..num import div, isnum
from .common import campaign_comment, img
from .beyond_gravity import span
from .fmt import f, fmt_ci, fmt_dist, fmt_n, g, table

CONDS = ["stagnant", "unsteady"]
DIRECTION = {1: "saves", -1: "costs more", 0: "no significant difference", None: "n/a"}
# The criteria: min_power's max attitude error and mean EE error within ERROR_RATIO_MAX × the
# pseudoinverse's (paired per seed); where the static potential is ≥ POTENTIAL_MIN, a realised
# saving of at least REALISED_SHARE_MIN of it.
ERROR_RATIO_MAX = 1.1
POTENTIAL_MIN = 0.01
REALISED_SHARE_MIN = 0.8
NA_POTENTIAL = "n/a (potential < 1 %)"


def _c1(c, k, a):
    return dict(COND_EXP1_KEYS[k], **{KEY_CASE: c, KEY_ALLOC: a})


def within(d, limit, n_failed=0):
    """Whether a paired ratio (its stats.Dist) stays ≤ limit: the upper end of its 95 % CI (one
    run: the ratio) is ≤ limit. False when a seed was left out because a run failed (a failed
    min_power run must not vanish from the comparison); None when nothing was measured or
    there is no interval."""
    if n_failed:
        return False
    if d is None or d.n == 0:
        return None
    if d.n == 1:
        return d.mean <= limit
    return d.hi <= limit if d.has_ci else None


def pass_text(ok):
    return "n/a" if ok is None else ("pass" if ok else "fail")


class Effect:
    """What min_power does against the pseudoinverse in one condition (cond: every key but the
    allocator and the seed), paired per seed:
    - the closed loop: per-seed ratios min_power/pseudoinverse of the max attitude error and
      of the mean EE error ε (stats.Paired);
    - the cost the allocator minimises, C = ∫Σ|T_j|^1.5 dt: the static potential (Dist of
      alloc_static_potential over the pseudoinverse runs), the realised saving 1 −
      C_cmd(min_power)/C_cmd(pseudoinverse) paired per seed (analyses.beyond.Saving), the
      saving realised within the min_power runs (Dist of alloc_realised_saving), the ticks
      on which the optimum was not found (both allocators' runs);
    - the electrical energy: E_el of each and the paired saving."""

    def __init__(self, e, cond):
        old, new = dict(cond, **{KEY_ALLOC: ALLOC_PINV}), dict(cond, **{KEY_ALLOC: ALLOC_MINPOW})
        self.e_old, self.e_new = e.dist(E_EL, old), e.dist(E_EL, new)
        self.saving = B.paired_saving(e.series(E_EL, new), e.series(E_EL, old))
        self.att_old, self.att_new = e.dist(ATT, old), e.dist(ATT, new)
        self.err_old, self.err_new = e.dist(ERR, old), e.dist(ERR, new)
        self.r_att, self.r_err = e.paired(ATT, new, old), e.paired(ERR, new, old)
        self.potential = e.dist(ALLOC_POTENTIAL, old)
        self.realised = B.paired_saving(e.series(ALLOC_COST_CMD, new),
                                        e.series(ALLOC_COST_CMD, old))
        self.in_run = e.dist(ALLOC_REALISED, new)
        # No thrust commanded at all (case I): the potential is undefined, not failed.
        costs = list(e.series(ALLOC_COST_PINV, old).values())
        self.no_thrust = bool(costs) and all(isnum(c) and c == 0 for c in costs)
        self.n_runs = len(costs)
        pot_new, real_new = e.series(ALLOC_POTENTIAL, new), e.series(ALLOC_REALISED, new)
        self.in_run_share = stats.describe([div(real_new[k], pot_new[k]) for k in pot_new
                                            if k in real_new and isnum(pot_new[k]) and pot_new[k] > 0
                                            and isnum(real_new[k])])
        ticks = list(e.series(ALLOC_UNSOLVED, old).values()) + \
            list(e.series(ALLOC_UNSOLVED, new).values())
        self.unsolved = int(sum(ticks)) if ticks else None

    @property
    def errors_ok(self):
        """Both error ratios within ERROR_RATIO_MAX (None when either is unmeasured)."""
        a = within(self.r_att.dist, ERROR_RATIO_MAX, self.r_att.n_failed)
        b = within(self.r_err.dist, ERROR_RATIO_MAX, self.r_err.n_failed)
        return None if a is None or b is None else (a and b)

    @property
    def share(self):
        """What the min_power runs realise of their own static potential: the mean over those
        runs of alloc_realised_saving / alloc_static_potential (the same run's wrenches, so the
        closed loop's differences between the two allocators do not enter); NaN without it."""
        return self.in_run_share.mean if self.in_run_share.n else float("nan")

    @property
    def criterion(self):
        """'met' / 'not met' (where the potential is ≥ 1 %: the lower end of the 95 % CI of
        the in-run share ≥ 80 %, one run: the share), NA_POTENTIAL, or 'n/a' (nothing measured,
        or ticks on which the optimum was not found)."""
        if not self.potential.n or not isnum(self.potential.mean):
            return "n/a"
        if self.potential.mean < POTENTIAL_MIN:
            return NA_POTENTIAL
        if self.unsolved or not self.in_run_share.n:
            return "n/a"
        d = self.in_run_share
        low = d.mean if d.n == 1 else (d.lo if d.has_ci else float("nan"))
        if not isnum(low):
            return "n/a"
        return "met" if low >= REALISED_SHARE_MIN else "not met"


ERROR_HDR = ["n", "max att. error pseudoinverse [mrad]", "min_power [mrad]",
             "att. ratio min_power/pinv", "95 % CI", "≤ 1.1×", "mean ε pseudoinverse [mm]",
             "min_power [mm]", "ε ratio min_power/pinv", "95 % CI", "≤ 1.1×"]
COST_HDR = ["n", "static potential [%]", "95 % CI", "realised, paired [%]", "95 % CI",
            "realised in the min_power run [%]", "realised / potential [%]",
            "criterion (realised ≥ 80 % of a potential ≥ 1 %)", "unsolved ticks"]
ENERGY_HDR = ["n", "E_el pseudoinverse", "E_el min_power", "saving [%]", "95 % CI",
              "min_power cheaper in"]


def error_cells(ef):
    ra, re = ef.r_att.dist, ef.r_err.dist
    return [fmt_n(ra), fmt_dist(ef.att_old, 2, 1e3), fmt_dist(ef.att_new, 2, 1e3),
            fmt_dist(ra, 3), fmt_ci(ra, 3), pass_text(within(ra, ERROR_RATIO_MAX, ef.r_att.n_failed)),
            fmt_dist(ef.err_old, 3, 1e3), fmt_dist(ef.err_new, 3, 1e3), fmt_dist(re, 3),
            fmt_ci(re, 3), pass_text(within(re, ERROR_RATIO_MAX, ef.r_err.n_failed))]


def cost_cells(ef):
    if ef.no_thrust:
        return [str(ef.n_runs)] + ["—"] * 6 + ["n/a (no thrust)", "n/a" if ef.unsolved is None
                                     else str(ef.unsolved)]
    share = ef.share
    return [fmt_n(ef.potential), fmt_dist(ef.potential, 3, 100), fmt_ci(ef.potential, 3, 100),
            fmt_dist(ef.realised.dist, 3, 100), fmt_ci(ef.realised.dist, 3, 100),
            fmt_dist(ef.in_run, 3, 100), f(100 * share, 1) if isnum(share) else "n/a",
            ef.criterion, "n/a" if ef.unsolved is None else str(ef.unsolved)]


def energy_cells(ef, scale=1.0, sig=None, nd=1):
    sv = ef.saving
    return [fmt_n(ef.e_old), fmt_dist(ef.e_old, nd, scale, sig=sig),
            fmt_dist(ef.e_new, nd, scale, sig=sig), fmt_dist(sv.dist, 2, 100),
            fmt_ci(sv.dist, 2, 100), f"{sv.n_cheaper} of {sv.n}" if sv.n else "—"]


def effect_tables(label_hdr, items, unit="J", scale=1.0, sig=None):
    """items: [(label cells, Effect)] → (errors table, cost table, energy table)."""
    ehdr = [h + (f" [{unit}]" if h.startswith("E_el") else "") for h in ENERGY_HDR]
    return (table(label_hdr + ERROR_HDR, [lab + error_cells(ef) for lab, ef in items]),
            table(label_hdr + COST_HDR, [lab + cost_cells(ef) for lab, ef in items]),
            table(label_hdr + ehdr, [lab + energy_cells(ef, scale, sig) for lab, ef in items]))


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


CHANGE_HDR = ["E(bary)/E(veh), pseudoinverse", "min_power", "Δ ratio (min_power − pinv)",
              "95 % CI", "verdict, pseudoinverse", "verdict, min_power", "answer changes"]


def _paper_tables(ea):
    items, eff, changes, crows = [], {}, [], []
    for c in CASES:
        for k in CONDS:
            ef = Effect(ea, dict(COND_EXP1_KEYS[k], **{KEY_CASE: c}))
            eff[(c, CONDS.index(k))] = ef
            items.append(([c, COND_EXP1_TEXT[k]], ef))
    for k in CONDS:
        for v, b in MATCHED_PAIRS:
            changed, cells = _change_row(ea, _c1(b, k, ALLOC_PINV), _c1(v, k, ALLOC_PINV),
                                         _c1(b, k, ALLOC_MINPOW), _c1(v, k, ALLOC_MINPOW))
            changes.append((f"experiment 1, {COND_EXP1_TEXT[k]}, {b}/{v}", *changed))
            crows.append([COND_EXP1_TEXT[k], f"{b} / {v}"] + cells)
    return (effect_tables(["case", "condition"], items),
            table(["condition", "barycenter / vehicle"] + CHANGE_HDR, crows), eff, changes)


def _lead_line(ea):
    """How the pseudoinverse half relates to experiment 1: by the campaign's lead setting."""
    lead = ea.common_value(KEY_LEAD, "mixed")
    if lead is True:
        return ["Every run of `beyond_allocation` has the feedforward lead on "
                "(`control.feedforward_lead = true`, docs/MODEL.md §7.5). Its pseudoinverse half "
                "is therefore not experiment 1: it differs from experiment 1 by the feedforward "
                "lead, and both allocators are compared under the controller with the lead.", ""]
    if lead is False:
        return ["The runs of `beyond_allocation` have the feedforward lead off "
                "(`control.feedforward_lead = false`).", ""]
    return ["The runs of `beyond_allocation` do not share one recorded setting of "
            "`control.feedforward_lead`.", ""]


def _gravity_tables(gr):
    items, eff, crows, changes = [], {}, [], []
    for j, gv in enumerate(gr.gravs):
        for p in gr.pays:
            for c in (VEH, BARY):
                ef = Effect(gr.e, gr.base(gv, c, p))
                eff.setdefault((j, c), []).append(ef)
                items.append(([gr.labels[j], f(p, 0), c], ef))
            changed, cells = _change_row(gr.e, gr.cond(gv, BARY, p, ALLOC_PINV),
                                         gr.cond(gv, VEH, p, ALLOC_PINV),
                                         gr.cond(gv, BARY, p, ALLOC_MINPOW),
                                         gr.cond(gv, VEH, p, ALLOC_MINPOW))
            changes.append((f"{gr.labels[j]}, {f(p, 0)} kg", *changed))
            crows.append([gr.labels[j], f(p, 0)] + cells)
    return (effect_tables(["gravity", "m_P [kg]", "case"], items, "kJ", 1e-3, 3),
            table(["gravity", "m_P [kg]"] + CHANGE_HDR, crows), eff, changes)


def _activity(e, run):
    """analyses.beyond.command_activity of the commanded thrusts (telemetry thrust_des_N) of
    the run; None without its log."""
    lg = e.log(run, ["UVMS_TELEMETRY"])
    if not has(lg, "UVMS_TELEMETRY"):
        return None
    return B.command_activity(lg["UVMS_TELEMETRY"]["t_s"], lg["UVMS_TELEMETRY"]["thrust_des_N"])


def _activity_runs(e, conds):
    """{allocator: the lowest-seed run of each condition}."""
    return {a: [e.one(dict(c, **{KEY_ALLOC: a})) for c in conds]
            for a in (ALLOC_PINV, ALLOC_MINPOW)}


def _activity_row(label, e, runs):
    """label, n conditions, then per allocator (runs: _activity_runs) the mean ∫Σ|T_des| dt
    and total variation."""
    cells = [label, str(len(runs[ALLOC_PINV]))]
    for a in (ALLOC_PINV, ALLOC_MINPOW):
        acts = [x for x in (_activity(e, r) for r in runs[a]) if x]
        cells += ([f(np.mean([x[0] for x in acts]), 1), g(np.mean([x[1] for x in acts]), 3)]
                  if acts else ["n/a", "n/a"])
    return cells


def activity_table(ea, gr):
    """The commanded thrusts of both allocators: impulse and tick-to-tick jumps, averaged over
    the conditions (cases II–VIII in experiment 1; IV, VII × payloads per gravity)."""
    specs = []  # (label, experiment, its _activity_runs)
    if ea is not None:
        specs += [(f"experiment 1, {COND_EXP1_TEXT[k]}", ea, _activity_runs(
            ea, [dict(COND_EXP1_KEYS[k], **{KEY_CASE: c}) for c in CASES[1:]])) for k in CONDS]
    if gr is not None:
        specs += [(gr.labels[j], gr.e, _activity_runs(
            gr.e, [gr.base(gv, c, p) for c in (VEH, BARY) for p in gr.pays]))
            for j, gv in enumerate(gr.gravs)]
    for _, e, runs in specs:
        e.prefetch_logs(r for a in (ALLOC_PINV, ALLOC_MINPOW) for r in runs[a])
    rows = [_activity_row(label, e, runs) for label, e, runs in specs]
    if not rows:
        return []
    return (["**The commanded thrusts.** min_power gives the least Σ|T|^1.5 for each tick's "
             "wrench; the cost is strictly convex, so the optimum is unique and a continuous "
             "function of the wrench, and the command moves from tick to tick only as the "
             "wrench does (docs/MODEL.md §7.3). Impulse and tick-to-tick jumps of the commanded "
             "thrusts (telemetry `thrust_des_N`) of each condition's lowest-seed run, averaged "
             "over the conditions:", ""]
            + table(["campaign / gravity", "conditions", "pseudoinverse: ∫Σ|T_des| dt [N·s]",
                     "Σ|ΔT_des| tick to tick [N]", "min_power: ∫Σ|T_des| dt [N·s]",
                     "Σ|ΔT_des| tick to tick [N]"], rows))


def _pct_span(vals, nd=3):
    return span([100 * v for v in vals if isnum(v)], nd)


def _saving_summary(label, effects):
    """'label: errors within 1.1× in k of n; potential, realised; E_el saves in …'."""
    efs = [x for x in effects if x.r_att.n or x.potential.n or x.saving.n]
    if not efs:
        return f"- {label}: not measured."
    oks = [x.errors_ok for x in efs]
    e_sv = [x for x in efs if x.saving.n]
    dirs = [stats.direction(x.saving.dist) for x in e_sv]
    counts = ", ".join(f"{DIRECTION[d]} in {dirs.count(d)}" for d in (1, -1, 0) if dirs.count(d))
    return (f"- **{label}**: attitude and EE errors of min_power within 1.1× the "
            f"pseudoinverse's in {oks.count(True)} of {len(efs)} conditions (fail in "
            f"{oks.count(False)}; ratio min_power/pinv of the max attitude error "
            f"{span([x.r_att.dist.mean for x in efs], 3)}, of the mean ε "
            f"{span([x.r_err.dist.mean for x in efs], 3)}); static potential "
            f"{_pct_span([x.potential.mean for x in efs])} %, realised saving of Σ|T|^1.5 "
            f"(paired) {_pct_span([x.realised.dist.mean for x in efs if x.realised.n])} %; "
            f"electrical energy: min_power {counts or 'not measured'} of {len(e_sv)} "
            f"conditions, mean saving {_pct_span([x.saving.dist.mean for x in e_sv], 2)} %.")


def lever_summary(effects, where):
    """Whether the static potential is large enough anywhere for the allocator to matter;
    where: e.g. "in the gravity campaign"."""
    meas = [x for x in effects if x.potential.n and isnum(x.potential.mean)]
    if not meas:
        return (f"- **Static potential {where}**: not measured (no `alloc_static_potential` in "
                "the run summaries).")
    top = max(x.potential.mean for x in meas)
    big = [x for x in meas if x.potential.mean >= POTENTIAL_MIN]
    if not big:
        return (f"- **Is the allocator an energy lever {where}?** No. With eight thrusters on "
                "six degrees of freedom the allocation's null space is two-dimensional, and the "
                "static potential (the share of ∫Σ|T|^1.5 dt the optimum saves on the wrenches "
                f"the runs commanded) is below 1 % in all {len(meas)} conditions measured (at "
                f"most {f(100 * top, 3)} %). The realised-saving criterion (≥ 80 % of the "
                "potential) applies where the potential is ≥ 1 %: nowhere here, so it reads "
                f"{NA_POTENTIAL}.")
    met = [x for x in big if x.criterion == "met"]
    return (f"- **Static potential {where}**: ≥ 1 % in {len(big)} of {len(meas)} conditions "
            f"(at most {f(100 * top, 3)} %); there the realised saving reaches ≥ 80 % of the "
            f"potential in {len(met)} of {len(big)}."
            + (f" Elsewhere the potential is below 1 %: {NA_POTENTIAL}." if len(big) < len(meas)
               else ""))


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


INTRO = (
    "min_power commands on every tick the thrusts of least Σ|T_j|^1.5 (the thrusters' "
    "hydrodynamic power up to a constant) that deliver the pseudoinverse's wrench "
    "(docs/MODEL.md §7.3); the pseudoinverse gives the least Σ T_j². Every comparison is paired "
    "per case and seed (the same flow): mean ± half-width of the 95 % CI over the seeds where "
    "seeded (a stagnant row is one deterministic run). Case I has no control and no thrust: "
    "nothing to save.", "",
    "- **Closed loop**: the ratio min_power/pseudoinverse of the max attitude error and of the "
    "mean EE error ε (geometric mean of the per-seed ratios, CI on the log scale). *pass* when "
    "the upper end of its 95 % CI (one run: the ratio) is ≤ 1.1 and no run of either "
    "allocator failed.",
    "- **The cost the allocator minimises**, C = ∫Σ|T_j|^1.5 dt [N^1.5·s]. *Static potential*: "
    "1 − C(T*)/C(P), T* the optimum and P the pseudoinverse's thrusts, both of the wrenches the "
    "run commanded; the mean over the condition's pseudoinverse runs predicts the saving. "
    "*Realised, paired*: 1 − C_cmd(min_power run)/C_cmd(pseudoinverse run) of the thrusts "
    "commanded, paired per seed. *Realised in the min_power run*: 1 − C_cmd/C(P) within the "
    "min_power runs. *Realised / potential*: in each min_power run, its realised saving over "
    "its own static potential (the same wrenches, so the two allocators' different closed "
    "loops do not enter), the mean over the runs. The paired saving also holds what the "
    "allocator changes in the closed loop (at g = 0 with the stiff attitude gain it exceeds "
    "the potential many times: docs/MODEL.md §7.3). "
    "Criterion: where the potential is ≥ 1 %, the lower end of the 95 % CI of the realised "
    "share ≥ 80 % (met / not met; n/a with unsolved ticks); where it "
    f"is below 1 %, {NA_POTENTIAL}. Unsolved ticks: ticks on which the optimum for the "
    "potential was not found (summed over both allocators' runs).",
    "- **Electrical energy**: saving 1 − E_el(min_power)/E_el(pseudoinverse). A condition "
    "counts as *saves* / *costs more* when the 95 % CI of its paired saving lies above / below "
    "0 (one deterministic run: its sign), else *no significant difference*.", "")


def _three(title, tables, energy_note):
    t_err, t_cost, t_en = tables
    return ([f"{title} Closed loop, min_power against the pseudoinverse:", ""] + t_err
            + ["The cost the allocator minimises, Σ|T|^1.5: predicted (static potential) and "
               "realised saving:", ""] + t_cost
            + [f"Electrical energy{energy_note}:", ""] + t_en)


def section(rep, ea, gr):
    """ea: the beyond_allocation Experiment (or None); gr: beyond_gravity's Grid (or None)."""
    md = ["### Minimum-power allocation: min_power against the pseudoinverse", ""]
    md += list(INTRO)
    md += campaign_comment(ea) if ea is not None else []
    summary, body, changes, levers = [], [], [], []
    paper_ef, grav_ef = {}, {}
    if ea is not None:
        tabs, t_chg, paper_ef, ch = _paper_tables(ea)
        changes += ch
        levers.append(lever_summary(list(paper_ef.values()), "in experiment 1 with the lead"))
        for k in CONDS:
            summary.append(_saving_summary(f"Experiment 1 with the lead, {COND_EXP1_TEXT[k]}",
                                           [paper_ef[(c, CONDS.index(k))] for c in CASES]))
        body += _lead_line(ea)
        body += _three("**The paper's experiment 1 with the feedforward lead** (campaign "
                       "`beyond_allocation`).", tabs, "")
        body += ["Barycenter vs vehicle under each allocator (the case pairs that differ only "
                 "in the position reference; ratios paired per seed):", ""] + t_chg
    if gr is not None and ALLOC_PINV in gr.allocs and ALLOC_MINPOW in gr.allocs:
        tabs, t_chg, grav_ef, ch = _gravity_tables(gr)
        changes += ch
        for j, gl in enumerate(gr.labels):
            efs = [x for c in (VEH, BARY) for x in grav_ef.get((j, c), [])]
            summary.append(_saving_summary(f"{gl} (gravity campaign)", efs))
        levers.append(lever_summary([x for v in grav_ef.values() for x in v],
                                    "in the gravity campaign"))
        body += _three("**The gravity campaign** (`beyond_gravity`, unsteady flow).", tabs,
                       " (energies in kJ)")
        body += ["Barycenter (VII) vs vehicle (IV) under each allocator:", ""] + t_chg
    body += activity_table(ea, gr)
    md += summary + levers + [_change_summary(changes), ""] + body
    if paper_ef or grav_ef:
        kinds = {"potential": lambda x: x.potential, "realised": lambda x: x.realised.dist,
                 "energy": lambda x: x.saving.dist}
        paper = {(kd, c, k): fn(x) for kd, fn in kinds.items() for (c, k), x in paper_ef.items()}
        grav = {(kd, j, c): [fn(x) for x in v] for kd, fn in kinds.items()
                for (j, c), v in grav_ef.items()}
        img(md, figb.allocation_saving(rep.figs, paper, [COND_EXP1_TEXT[k] for k in CONDS],
                                       grav, gr.labels if gr else [], gr.pays if gr else []),
            "min_power against the pseudoinverse. Top: the cost the allocator minimises, "
            "Σ|T|^1.5, predicted saving (static potential, hatched / open) and realised saving "
            "(paired per seed, solid / filled); bottom: the electrical-energy saving. Left, the "
            "eight cases of experiment 1 with the lead in both conditions; right, the gravity "
            "campaign per gravity, case and payload (error bars: 95 % CI over seeds).")
    return md
