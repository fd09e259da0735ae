# SPDX-License-Identifier: Apache-2.0
"""verdicts: sign-aware verdicts for the reproduction scorecard, and the range
of a swept parameter over which a verdict holds. Pure functions on numbers, Dists and
Estimates.

The scorecard's rule (stats.scorecard_verdict) accepts a ratio or fraction within ±TOL_RATIO of
the paper's value whatever its sign: a paper effect of +1.0 % and ours of −0.19 % are 1.19
points apart and were "reproduced". Here the sign is a precondition (DIRECTION_RULE_TEXT).

- directional_verdict(paper, ours): a statement "X changes by p" (sign s of p − ref).
- magnitude_verdict(paper, ours): an absolute, possibly signed quantity within a factor.
- verdict_range(verdict, sweep): the parameter values over which a verdict holds, for flagging
  verdicts that depend on a parameter the paper does not print (e.g. the flow amplitude A_v).

`ours` is a number (deterministic), a stats.Dist or an inference.Estimate (its CI), or None.
"""
import math
from dataclasses import dataclass

from . import stats
from .inference import Estimate
from .stats import DIFFERS, NOT_MEASURED, REPRODUCED, SAME_DIRECTION, TOL_FACTOR, TOL_RATIO

DIRECTION_RULE_TEXT = (
    "**Verdict rule for directional statements** (the paper says a quantity rises or falls by p "
    "relative to a reference r: 0 for a change or a saving, 1 for a ratio; s = sign(p − r)). "
    "Our estimate m (a single value, or the mean over seeds with its 95 % confidence interval "
    "[lo, hi]) must first move the same way: if s·(m − r) ≤ 0 the verdict is *differs*, "
    "whatever the interval or the tolerance. Then *reproduced*: p lies inside [lo, hi], or "
    f"|m − p| ≤ {TOL_RATIO:g} (the tolerance of the row). *Same direction*: not reproduced, "
    "but the direction is established: a single value on the paper's side of r, or an interval "
    "lying entirely on that side. *Differs*: otherwise (an interval that contains r and not p "
    "supports neither the paper's value nor its direction). A magnitude (an absolute, possibly "
    f"signed quantity) is *reproduced* when ours has the paper's sign and lies within a factor "
    f"{TOL_FACTOR:g} of it, or p lies inside our interval with our mean of the paper's sign; "
    "it *differs* otherwise.")


def _point_ci(ours):
    """(m, lo, hi) of a number, Dist or Estimate; lo = hi = NaN without an interval (a number,
    a deterministic sample); None when nothing was measured."""
    if ours is None:
        return None
    if isinstance(ours, Estimate):
        m, (lo, hi) = ours.estimate, ((ours.lo, ours.hi) if ours.has_ci else (math.nan,) * 2)
    elif isinstance(ours, stats.Dist):
        m, (lo, hi) = ours.mean, ours.ci
    else:
        m, lo, hi = ours, math.nan, math.nan
    return (float(m), lo, hi) if stats._finite(m) else None


def directional_verdict(paper, ours, tol=TOL_RATIO, ref=0.0):
    """Verdict of "the quantity moves from `ref` by `paper`" (DIRECTION_RULE_TEXT). With
    s = sign(paper − ref) and our m, [lo, hi]:
      s·(m − ref) ≤ 0                                   → DIFFERS (sign first);
      paper ∈ [lo, hi] or |m − paper| ≤ tol              → REPRODUCED;
      no interval, or s·(lo − ref) > 0 and s·(hi − ref) > 0 → SAME_DIRECTION;
      otherwise (interval contains ref, not paper)     → DIFFERS.
    paper == ref is no direction: ValueError (use magnitude_verdict or scorecard_verdict)."""
    pci = _point_ci(ours)
    if pci is None or not stats._finite(paper):
        return NOT_MEASURED
    m, lo, hi = pci
    s = (paper > ref) - (paper < ref)
    if s == 0:
        raise ValueError("directional_verdict: the paper's value equals the reference")
    if s * (m - ref) <= 0.0:
        return DIFFERS
    has_ci = stats._finite(lo) and stats._finite(hi)
    if (has_ci and lo <= paper <= hi) or abs(m - paper) <= tol:
        return REPRODUCED
    if not has_ci or (s * (lo - ref) > 0.0 and s * (hi - ref) > 0.0):
        return SAME_DIRECTION
    return DIFFERS


def magnitude_verdict(paper, ours, tol_factor=TOL_FACTOR, atol=1e-12):
    """Verdict of an absolute, possibly signed quantity (mm, J, N): REPRODUCED when m has the
    paper's sign and 1/tol_factor ≤ m/paper ≤ tol_factor, or paper ∈ [lo, hi] with m of the
    paper's sign; paper = 0: |m| ≤ atol or 0 ∈ [lo, hi]. DIFFERS otherwise."""
    pci = _point_ci(ours)
    if pci is None or not stats._finite(paper):
        return NOT_MEASURED
    m, lo, hi = pci
    in_ci = stats._finite(lo) and stats._finite(hi) and lo <= paper <= hi
    if paper == 0.0:
        return REPRODUCED if (abs(m) <= atol or in_ci) else DIFFERS
    if m * paper <= 0.0:
        return DIFFERS
    return REPRODUCED if (in_ci or 1.0 / tol_factor <= m / paper <= tol_factor) else DIFFERS


@dataclass
class VerdictRange:
    """Where a verdict holds over a parameter sweep. holds / fails: the swept values (sorted)
    where it does / does not; lo, hi: the smallest and largest value where it holds (NaN if
    none); robust: it holds at every swept value; contiguous: the values where it holds are
    one run of consecutive swept values."""
    holds: list
    fails: list
    lo: float
    hi: float
    robust: bool
    contiguous: bool


def verdict_range(verdict, sweep, target=REPRODUCED):
    """verdict: result → verdict (e.g. lambda d: directional_verdict(0.01, d)); sweep:
    {parameter value: result}. The verdict holds at a value when verdict(result) == target.
    A verdict that is not robust depends on the parameter: the report must print the range."""
    xs = sorted(sweep)
    ok = [verdict(sweep[x]) == target for x in xs]
    holds = [x for x, k in zip(xs, ok) if k]
    fails = [x for x, k in zip(xs, ok) if not k]
    first = ok.index(True) if holds else 0
    contiguous = bool(holds) and all(ok[first:first + len(holds)])
    return VerdictRange(holds, fails, holds[0] if holds else math.nan,
                        holds[-1] if holds else math.nan, not fails and bool(holds), contiguous)


def sensitivity_note(name, vr, target=REPRODUCED):
    """One line for the report: '' when the verdict holds at every swept value; else where it
    holds, e.g. "reproduced only for A_v in [0.1, 0.3] (swept: 0.05, 0.1, 0.2, 0.3, 0.5)"."""
    if vr.robust:
        return ""
    swept = ", ".join(f"{x:g}" for x in sorted(vr.holds + vr.fails))
    if not vr.holds:
        return f"{target} for no {name} swept ({swept})"
    where = (f"in [{vr.lo:g}, {vr.hi:g}]" if vr.contiguous
             else "at " + ", ".join(f"{x:g}" for x in vr.holds))
    return f"{target} only for {name} {where} (swept: {swept})"
