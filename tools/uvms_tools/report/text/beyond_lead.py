# SPDX-License-Identifier: Apache-2.0
"""beyond_lead: the feedforward-lead campaign (beyond_lead, docs/MODEL.md §7.5): attitude and
EE errors and energy with the lead off and on, paired per seed, against its targets; and the two
allocators (pseudoinverse, min_power) against each other with the lead off and on: errors,
static potential and realised saving of Σ|T|^1.5, energy."""
import math

from ..figures import beyond_lead as figl
from ..keys import (ALLOC_MINPOW, ALLOC_PINV, ATT, BARY, ERR, KEY_ALLOC, KEY_CASE,
                    KEY_GRAVITY, KEY_LEAD, KEY_UNSTEADY, VEH)
from ..num import isnum
from .beyond_alloc import ERROR_RATIO_MAX, Effect, lever_summary, pass_text, within
from .beyond_gravity import GRAVITY_NAMES, METRIC_KEYS
from .common import campaign_comment, img
from .fmt import f, fmt_dist, fmt_n, g, table

# The gravity names and the metrics of the gravity campaign's tables.
METRICS = METRIC_KEYS
# The targets of the lead: 10 kg, trimmed, stagnant, K_PN = 100: gravity → (max attitude
# error [rad], mean EE error [m]).
TARGETS = {"earth": (math.radians(0.2), 1.0e-3), "europa": (math.radians(0.2), 0.3e-3)}


def _cond(gv, case, unsteady, lead, alloc):
    return {KEY_GRAVITY: gv, KEY_CASE: case, KEY_UNSTEADY: unsteady, KEY_LEAD: lead,
            KEY_ALLOC: alloc}


# The thruster-chain keys τ is computed from (the runs' values, else the schema's defaults).
LAG_KEYS = ("thrusters.ka_1_s", "thrusters.kb_1_s", "thrusters.viscous_friction_Nm_s",
            "thrusters.rotor_inertia_kg_m2")


def _lag_line(e):
    """τ = (KB + b/J)/(KA·KB) of the campaign's thrusters (one value shared by every run)."""
    vals = [e.common_value(k, None) for k in LAG_KEYS]
    if not e.runs or any(v is None for v in vals):
        return ["The thruster-chain settings (KA, KB, b, J) are not one known set over the runs: no "
                "single lag to state.", ""]
    ka, kb, b, J = (float(v) for v in vals)
    tau = (kb + b / J) / (ka * kb)
    return [f"The thrusters follow a ramp of the commanded wrench τ = (KB + b/J)/(KA·KB) = "
            f"{g(tau, 3)} s late (KA = {g(ka)} 1/s, KB = {g(kb)} 1/s, b = {g(b)} N·m·s, J = "
            f"{g(J)} kg·m², the runs' settings); with `control.feedforward_lead` the controller "
            "commands its feedforward that much ahead along the feedforward's slope, low-passed "
            "over τ so that sensor noise is averaged rather than multiplied (docs/MODEL.md "
            "§7.5). The feedback is not led.", ""]


def _row(e, gv, case, unsteady, alloc):
    off, on = _cond(gv, case, unsteady, False, alloc), _cond(gv, case, unsteady, True, alloc)
    d = {(m, lead): e.dist(k, c) for m, k in METRICS.items() for lead, c in (("off", off), ("on", on))}
    ratio = {m: e.paired(METRICS[m], on, off) for m in ("err", "en")}
    return [GRAVITY_NAMES.get(gv, gv), case, "unsteady" if unsteady else "stagnant", alloc,
            fmt_n(d[("en", "on")]),
            fmt_dist(d[("att", "off")], 2, 1e3), fmt_dist(d[("att", "on")], 2, 1e3),
            fmt_dist(d[("err", "off")], 3, 1e3), fmt_dist(d[("err", "on")], 3, 1e3),
            fmt_dist(ratio["err"].dist, 3),
            fmt_dist(d[("en", "off")], 2, 1e-3), fmt_dist(d[("en", "on")], 2, 1e-3),
            fmt_dist(ratio["en"].dist, 4)]


def _targets(e, gravs):
    out = []
    for gv in gravs:
        if gv not in TARGETS:
            continue
        att_max, err_max = TARGETS[gv]
        for case in (VEH, BARY):
            run = e.series(ATT, _cond(gv, case, False, True, ALLOC_PINV))
            err = e.series(ERR, _cond(gv, case, False, True, ALLOC_PINV))
            if not run or not err:
                continue
            a, eps = max(run.values()), max(err.values())
            met = a <= att_max and eps <= err_max
            out.append(f"- {GRAVITY_NAMES.get(gv, gv)}, {case}, stagnant, lead on "
                       f"(pseudoinverse): max attitude error {g(math.degrees(a), 3)}° (target ≤ "
                       f"{g(math.degrees(att_max), 2)}°), mean ε {g(eps * 1e3, 3)} mm (target ≤ "
                       f"{g(err_max * 1e3, 2)} mm): **{'met' if met else 'not met'}**.")
    return out + [""] if out else []


def _alloc_cond(gv, case, unsteady, lead):
    """The condition of both allocators' runs."""
    return {KEY_GRAVITY: gv, KEY_CASE: case, KEY_UNSTEADY: unsteady, KEY_LEAD: lead}


ALLOC_HDR = ["gravity", "case", "flow", "lead", "n", "att. ratio min_power/pinv", "≤ 1.1×",
             "ε ratio min_power/pinv", "≤ 1.1×", "E_el saving [%]", "static potential [%]",
             "realised, paired [%]", "realised / potential [%]",
             "criterion (realised ≥ 80 % of a potential ≥ 1 %)"]


def _alloc_row(gv, case, unsteady, lead, ef):
    ra, re = ef.r_att.dist, ef.r_err.dist
    return [GRAVITY_NAMES.get(gv, gv), case, "unsteady" if unsteady else "stagnant",
            "on" if lead else "off", fmt_n(ra), fmt_dist(ra, 3),
            pass_text(within(ra, ERROR_RATIO_MAX, ef.r_att.n_failed)), fmt_dist(re, 3),
            pass_text(within(re, ERROR_RATIO_MAX, ef.r_err.n_failed)), fmt_dist(ef.saving.dist, 2, 100),
            fmt_dist(ef.potential, 3, 100), fmt_dist(ef.realised.dist, 3, 100),
            f(100 * ef.share, 1) if isnum(ef.share) else "n/a", ef.criterion]


def _alloc_part(e, gravs):
    """The allocators against each other with the lead off and on ([] unless both ran);
    returns (lines, {(gravity, case, unsteady, lead): Effect})."""
    if not all(a in e.values(KEY_ALLOC) for a in (ALLOC_PINV, ALLOC_MINPOW)):
        return [], {}
    effs = {(gv, case, unst, lead): Effect(e, _alloc_cond(gv, case, unst, lead))
            for gv in gravs for case in (VEH, BARY) for unst in (False, True)
            for lead in (False, True)}
    rows = [_alloc_row(*k, ef) for k, ef in effs.items()]
    md = ["Allocator against allocator with the lead off and on: min_power against the "
          "pseudoinverse, paired per seed (ratios min_power/pinv of the max attitude error and "
          "of the mean ε, *pass* when the upper end of the 95 % CI is ≤ 1.1; static potential "
          "over the pseudoinverse runs and realised saving of Σ|T|^1.5 paired per seed, as in "
          "the allocation part above; E_el saving 1 − E_el(min_power)/E_el(pseudoinverse)).",
          "", lever_summary(list(effs.values()), "in the lead campaign"), ""]
    return md + table(ALLOC_HDR, rows), effs


def section(rep):
    e = rep.exp("beyond_lead")
    if e is None or not e.runs:
        return []
    gravs = [gv for gv in ("europa", "earth") if gv in e.values(KEY_GRAVITY)]
    allocs = [a for a in (ALLOC_PINV, ALLOC_MINPOW) if a in e.values(KEY_ALLOC)]
    md = ["### Feedforward lead", "", "Campaign `beyond_lead` (sil/campaigns/beyond/lead.toml).",
          ""] + campaign_comment(e) + _lag_line(e)
    md += ["Targets of the lead (10 kg, trimmed, stagnant, K_PN = 100 N·m/rad):"] + _targets(e, gravs)
    rows = [_row(e, gv, case, unst, a) for gv in gravs for case in (VEH, BARY)
            for unst in (False, True) for a in allocs]
    md += ["Lead off → on, paired per seed (the same flow); unsteady rows: mean ± half-width "
           "of the 95 % CI over the seeds, stagnant rows: the one deterministic run.", ""]
    md += table(["gravity", "case", "flow", "allocation", "n", "att. off [mrad]",
                 "att. on [mrad]", "ε off [mm]", "ε on [mm]", "ε on/off", "E_el off [kJ]",
                 "E_el on [kJ]", "E_el on/off"], rows)
    alloc_md, effs = _alloc_part(e, gravs)
    md += alloc_md
    cats = [(gv, case) for gv in gravs for case in (VEH, BARY)]
    series = [(a, lead) for a in allocs for lead in (False, True)]
    dists = {(m, i): [e.dist(k, _cond(gv, case, True, lead, a)) for gv, case in cats]
             for m, k in METRICS.items() for i, (a, lead) in enumerate(series)}
    savings = {(kind, li): [fn(effs[(gv, case, True, lead)]) for gv, case in cats]
               for kind, fn in (("potential", lambda x: x.potential),
                                ("realised", lambda x: x.realised.dist))
               for li, lead in enumerate((False, True))} if effs else None
    n_seeds = max((d.n for ds in dists.values() for d in ds), default=0)
    img(md, figl.lead_metrics(rep.figs, [f"{GRAVITY_NAMES.get(gv, gv)} {c}" for gv, c in cats],
                              [f"{a}, lead {'on' if lead else 'off'}" for a, lead in series],
                              dists, n_seeds, savings),
        "Max attitude error, mean EE error and thruster energy with the feedforward lead off "
        "(open) and on (filled), pseudoinverse and min_power allocation, unsteady flow"
        + ("; last panel: the saving of Σ|T|^1.5 of min_power against the pseudoinverse, "
           "predicted (static potential, hatched) and realised (paired per seed, solid), lead "
           "off and on" if savings else "")
        + " (error bars: 95 % CI over seeds).")
    return md
