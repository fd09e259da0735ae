# SPDX-License-Identifier: Apache-2.0
"""beyond_gravity: the gravity campaign (beyond_gravity): gravity × stabilization × allocator
(attitude error, EE error, energy over seeds) and the paper's question at each gravity."""
import numpy as np

from ..analyses import beyond as B
from ..analyses import headline as H
from ..analyses import stats
from ..figures import beyond as figb
from ..keys import (ALLOC_MINPOW, ALLOC_PINV, ATT, BARY, E_EL, ERR, KEY_ALLOC, KEY_CASE,
                    KEY_GRAVITY, KEY_PAYLOAD, VEH)
from ..load.logs import has
from ..num import isnum
from .common import img
from .fmt import f, fmt_ci, fmt_dist, fmt_n, table

GRAVITY_NAMES = {"paper": "g = 0 (the paper's)", "europa": "Europa", "earth": "Earth"}
METRIC_KEYS = {"att": ATT, "err": ERR, "en": E_EL}


class Grid:
    """The gravity campaign's axes (gravity, payload, allocator; in the runs' order) and its
    conditions; a gravity's label names its |g| from the logged controller configuration."""

    def __init__(self, e):
        self.e = e
        self.gravs = B.distinct(e.value(r, KEY_GRAVITY) for r in e.runs)
        self.pays = e.values(KEY_PAYLOAD)
        present = B.distinct(e.value(r, KEY_ALLOC) for r in e.runs)
        self.allocs = [a for a in (ALLOC_PINV, ALLOC_MINPOW) if a in present]
        self.labels = [self._label(g) for g in self.gravs]
        self.n_seeds = max((e.n_seeds(self.cond(g, VEH, p, a)) for g in self.gravs
                            for p in self.pays for a in self.allocs), default=0)

    def base(self, g, c, p):
        """The condition of (gravity, case, payload), either allocator."""
        return {KEY_GRAVITY: g, KEY_CASE: c, KEY_PAYLOAD: p}

    def cond(self, g, c, p, a):
        return dict(self.base(g, c, p), **{KEY_ALLOC: a})

    def _label(self, g):
        name = GRAVITY_NAMES.get(g, str(g)) if isinstance(g, str) else f"g = {g}"
        run = self.e.one({KEY_GRAVITY: g})
        lg = self.e.log(run, ["UVMS_CONFIG"])
        if not has(lg, "UVMS_CONFIG"):
            return name
        gn = float(np.linalg.norm(lg["UVMS_CONFIG"]["gravity_m_s2"][0]))
        return name if gn == 0.0 else f"{name}, |g| = {gn:.4g} m/s²"

    def dist(self, metric, g, c, p, a):
        return self.e.dist(METRIC_KEYS.get(metric, metric), self.cond(g, c, p, a))

    def ratio(self, g, p, a):
        """E(VII)/E(IV), paired per seed."""
        return self.e.paired(E_EL, self.cond(g, BARY, p, a), self.cond(g, VEH, p, a))


def _metrics_table(gr):
    rows = []
    for j, g in enumerate(gr.gravs):
        for p in gr.pays:
            for c in (VEH, BARY):
                cells = [gr.labels[j], f(p, 0), c]
                n = None
                for a in gr.allocs:
                    d = {m: gr.dist(m, g, c, p, a) for m in METRIC_KEYS}
                    n = n or fmt_n(d["en"])
                    cells += [fmt_dist(d["att"], 2, 1e3), fmt_dist(d["err"], 2, 1e3),
                              fmt_dist(d["en"], 3, 1e-3, sig=3)]
                rows.append(cells[:3] + [n] + cells[3:])
    hdr = ["gravity", "m_P [kg]", "case", "n"]
    for a in gr.allocs:
        hdr += [f"{a}: max att. error [mrad]", "mean ε [mm]", "E_el [kJ]"]
    return table(hdr, rows)


def _metrics_figure(rep, gr):
    dists = {(j, c, ai, m): [gr.dist(m, g, c, p, a) for p in gr.pays]
             for j, g in enumerate(gr.gravs) for c in (VEH, BARY)
             for ai, a in enumerate(gr.allocs) for m in METRIC_KEYS}
    return figb.gravity_metrics(rep.figs, gr.gravs, gr.labels, gr.pays, gr.allocs, dists,
                                gr.n_seeds)


def metrics_part(rep, gr):
    md = ["### Gravity × stabilization × allocator", "",
          f"Every cell: mean ± half-width of the 95 % CI over the {gr.n_seeds} seeds of the "
          "unsteady flow (Student t). Max attitude error: the largest attitude deviation from "
          "the start over the run (summary.json `max_attitude_error_rad`); mean ε: the mean "
          "EE error (docs/MODEL.md §10); E_el: thruster (electrical) energy.", ""]
    md += _metrics_table(gr)
    img(md, _metrics_figure(rep, gr), "Max attitude error, mean EE error and thruster energy "
        "against payload at each gravity, vehicle (IV) and barycenter (VII) stabilization with "
        "both allocators (error bars: 95 % CI over seeds).")
    return md


def _ratio_row(gr, j, g, p, a):
    pa = gr.ratio(g, p, a)
    dv, db = gr.dist("en", g, VEH, p, a), gr.dist("en", g, BARY, p, a)
    sv = B.paired_saving(gr.e.series(E_EL, gr.cond(g, BARY, p, a)),
                         gr.e.series(E_EL, gr.cond(g, VEH, p, a)))
    return pa, [gr.labels[j], f(p, 0), a, fmt_n(pa.dist), fmt_dist(dv, 3, 1e-3, sig=3),
                fmt_dist(db, 3, 1e-3, sig=3), fmt_dist(pa.dist, 3), fmt_ci(pa.dist, 3),
                fmt_dist(sv.dist, 1, 100), f"{pa.n_below_1} of {pa.n}",
                stats.compare(pa) or "n/a",
                f"{fmt_dist(gr.dist('err', g, VEH, p, a), 2, 1e3)} → "
                f"{fmt_dist(gr.dist('err', g, BARY, p, a), 2, 1e3)}"]


def span(vals, nd=1):
    """'a to b' of the finite values (signed numbers read better than 'a–b'); 'n/a' if none."""
    v = [x for x in vals if isnum(x)]
    if not v:
        return "n/a"
    lo, hi = min(v), max(v)
    return f(lo, nd) if f(lo, nd) == f(hi, nd) else f"{f(lo, nd)} to {f(hi, nd)}"


def _answer_line(gr, j, paireds):
    parts = []
    for ai, a in enumerate(gr.allocs):
        ps = paireds[(j, ai)]
        tally = B.verdict_tally(ps)
        k = tally.get(stats.CHEAPER, 0)
        means = [p.dist.mean for p in ps]
        parts.append(f"with {a}: barycenter cheaper at {k} of {len(ps)} payloads (mean ratio "
                     f"{span(means, 3)}, saving {span([100 * (1 - m) for m in means], 1)} %; "
                     f"{H.verdict_text(tally)})")
    return f"- **{gr.labels[j]}**: " + "; ".join(parts) + "."


def answer_part(rep, gr):
    rows, paireds = [], {}
    for j, g in enumerate(gr.gravs):
        for ai, a in enumerate(gr.allocs):
            paireds[(j, ai)] = []
        for p in gr.pays:
            for ai, a in enumerate(gr.allocs):
                pa, row = _ratio_row(gr, j, g, p, a)
                paireds[(j, ai)].append(pa)
                rows.append(row)
    md = ["### The paper's question at each gravity", "",
          "Is holding the barycenter (VII) cheaper than holding the vehicle (IV)? Ratio "
          "E_el(VII)/E_el(IV) paired per seed (same flow), verdict from its 95 % CI as in the "
          "paper's experiments (*cheaper*: the CI lies below 1); saving = 1 − ratio.", ""]
    md += [_answer_line(gr, j, paireds) for j in range(len(gr.gravs))] + [""]
    md += table(["gravity", "m_P [kg]", "allocation", "n", "E_el(IV) [kJ]", "E_el(VII) [kJ]",
                 "E(VII)/E(IV)", "95 % CI", "saving [%]", "VII cheaper in", "verdict",
                 "mean ε IV → VII [mm]"], rows)
    img(md, figb.gravity_ratio(rep.figs, gr.labels, gr.pays, gr.allocs, paireds, gr.n_seeds),
        "Energy ratio barycenter/vehicle against payload at each gravity, both allocators "
        "(paired per seed; error bars: 95 % CI; below 1: the barycenter is cheaper).")
    return md, paireds


def ballast_line(gr):
    """The trim ballast per payload from the logged controller configurations (gravity ≠ 0)."""
    parts = []
    for p in gr.pays:
        for g in gr.gravs:
            run = gr.e.one({KEY_GRAVITY: g, KEY_PAYLOAD: p})
            lg = gr.e.log(run, ["UVMS_CONFIG"])
            if has(lg, "UVMS_CONFIG") and float(lg["UVMS_CONFIG"]["ballast_kg"][0]) != 0.0:
                parts.append(f"{f(p, 0)} kg: {f(float(lg['UVMS_CONFIG']['ballast_kg'][0]), 2)} kg")
                break
    if not parts:
        return []
    return [f"Trim ballast (logged controller configuration, the same at every gravity ≠ 0): "
            f"payload {'; '.join(parts)}.", ""]
