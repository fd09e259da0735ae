# SPDX-License-Identifier: Apache-2.0
"""beyond: the statistics of the "Beyond the paper" section (gravity, minimum-power allocation).
Pure functions on {seed: value} dicts, built on stats.py (paired per seed, mean and 95 % CI
over seeds, Student t).

- paired_saving(new, old): per seed 1 − new[s]/old[s] (the fraction of energy `new` saves
  against `old`), its Dist and the number of seeds in which `new` is cheaper.
- ratio_change(num_a, den_a, num_b, den_b): per seed num_b/den_b − num_a/den_a over the seeds
  all four have: how much a change (e.g. of allocator, a → b) moves a paired ratio (e.g.
  barycenter/vehicle), as stats.PairedDiff.
- answer_change(pa, pb): the verdicts (stats.compare) of two paired ratios and whether they
  differ.
- verdict_tally(paireds): how many of several paired ratios are cheaper / no difference /
  dearer.
- distinct(values): the distinct values in order of first appearance (lists allowed).
- command_activity(t, thrust): of a thrust command sampled per tick (n × thrusters): the
  impulse ∫Σ_j|T_j| dt (trapezoidal rule) and the total variation Σ_k Σ_j |T_j(k+1) − T_j(k)|
  (how much the command jumps from tick to tick).
"""
import json
from collections import Counter
from dataclasses import dataclass

import numpy as np

from . import stats


@dataclass
class Saving:
    """Per-seed savings 1 − new[s]/old[s] over the seeds both have (old ≠ 0, both finite)."""
    seeds: list
    savings: list
    dist: stats.Dist
    n_cheaper: int      # seeds in which new < old (saving > 0)
    n_failed: int = 0   # seeds left out: a run of either side failed or is missing

    @property
    def n(self):
        return len(self.savings)


def paired_saving(new, old):
    """new, old: {seed: energy}. The saving of `new` against `old`, paired per seed."""
    pa = stats.paired_ratio(new, old)
    sv = [1.0 - r for r in pa.ratios]
    return Saving(pa.seeds, sv, stats.describe(sv), pa.n_below_1)


def _ratios(num, den, seeds):
    return {s: float(num[s]) / float(den[s]) for s in seeds}


def ratio_change(num_a, den_a, num_b, den_b):
    """Per seed (num_b/den_b) − (num_a/den_a) over the seeds where all four are finite and both
    denominators ≠ 0 (stats.PairedDiff); its CI says whether b moves the ratio."""
    pa, pb = stats.paired_ratio(num_a, den_a), stats.paired_ratio(num_b, den_b)
    common = sorted(set(pa.seeds) & set(pb.seeds), key=lambda s: (s is None, s))
    return stats.paired_difference(_ratios(num_b, den_b, common), _ratios(num_a, den_a, common))


def answer_change(pa, pb):
    """(verdict of pa, verdict of pb, changed): stats.compare of two paired ratios and whether
    the verdicts differ (None when either was not measured)."""
    va, vb = stats.compare(pa), stats.compare(pb)
    return va, vb, (None if va is None or vb is None else va != vb)


def verdict_tally(paireds):
    """Counter of stats.compare over several paired ratios (unmeasured ones left out)."""
    return Counter(v for v in (stats.compare(p) for p in paireds) if v is not None)


def distinct(values):
    """The distinct values in order of first appearance; values may be lists (compared as
    JSON)."""
    seen, out = set(), []
    for v in values:
        k = json.dumps(v, sort_keys=True)
        if k not in seen:
            seen.add(k)
            out.append(v)
    return out


def command_activity(t, thrust):
    """(∫Σ_j|T_j| dt, Σ_k Σ_j |T_j(k+1) − T_j(k)|) of a thrust command (n samples × thrusters)
    at times t; (0, 0) for fewer than two samples."""
    t = np.asarray(t, float)
    x = np.asarray(thrust, float).reshape(len(t), -1)
    if len(t) < 2:
        return 0.0, 0.0
    s = np.abs(x).sum(axis=1)
    imp = float(np.sum(0.5 * (s[1:] + s[:-1]) * np.diff(t)))
    return imp, float(np.abs(np.diff(x, axis=0)).sum())
