# SPDX-License-Identifier: Apache-2.0
"""stats: the statistics of the campaign report (tools/uvms_tools/report). Pure functions, standard
library only (no numpy, no scipy), so that they can be tested against hand-derived values.

Randomness in the runs (SPEC §10): a result that depends on a random draw (the unsteady flow's
seed) is a distribution over seeds, reported as mean, 95 % confidence interval of the mean
(Student t with n − 1 degrees of freedom), range and n; a comparison of two methods over the
same seeds is the distribution of the per-seed (paired) ratio, with the number of seeds in
which it favours one method.

- t_quantile(p, dof): Student t quantile, by inverting the CDF written with the regularized
  incomplete beta function I_x(a, b) (continued fraction, modified Lentz), bisection to 1e-13.
- describe(values): Dist (n, mean, sd, 95 % CI, min, max); Dist.deterministic (one value or
  zero spread) and Dist.ci (NaN, NaN for those: no interval is reported).
- paired_ratio(num, den): per-seed ratios num[s]/den[s] over the common seeds, their Dist and
  the count of seeds with ratio < 1.
- pooled_saving(pairs): per seed, 1 − Σ num / Σ den over several matched pairs.
- paired_difference(a, b): per-seed differences a[s] − b[s] over the common seeds and their
  Dist; direction(d): +1 / −1 / 0 when the CI lies above / below / around 0 (a single
  deterministic value: its sign).
- compare(paired): "cheaper" / "dearer" / "no significant difference" from the ratio's CI.
- first_crossing(t, y, level): the first upward crossing of a level, linearly interpolated
  between samples.
- scorecard_verdict(...): the reproduction scorecard's rule (reproduced / same direction /
  differs), stated in RULE_TEXT.
- impulse(t, x): ∫|x(t)| dt by the trapezoidal rule (x scalar or vector per sample).

Log-scale and bootstrap ratio CIs, p-values, the paired test of a change and Holm's
adjustment are in inference.py (numpy, scipy); sign-aware verdicts in verdicts.py.
"""
import math
from dataclasses import dataclass, field

CONFIDENCE = 0.95


# ----------------------------------------------------------------------------------------------
# Student t


def _betacf(a, b, x, itmax=500, eps=1e-16):
    """Continued fraction of the incomplete beta function (modified Lentz)."""
    tiny = 1e-300
    qab, qap, qam = a + b, a + 1.0, a - 1.0
    c = 1.0
    d = 1.0 - qab * x / qap
    d = 1.0 / (d if abs(d) > tiny else tiny)
    h = d
    for m in range(1, itmax + 1):
        m2 = 2 * m
        aa = m * (b - m) * x / ((qam + m2) * (a + m2))
        d = 1.0 + aa * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + aa / c
        c = c if abs(c) > tiny else tiny
        h *= d * c
        aa = -(a + m) * (qab + m) * x / ((a + m2) * (qap + m2))
        d = 1.0 + aa * d
        d = 1.0 / (d if abs(d) > tiny else tiny)
        c = 1.0 + aa / c
        c = c if abs(c) > tiny else tiny
        de = d * c
        h *= de
        if abs(de - 1.0) < eps:
            break
    return h


def betainc(a, b, x):
    """Regularized incomplete beta function I_x(a, b), a, b > 0, 0 ≤ x ≤ 1."""
    if x <= 0.0:
        return 0.0
    if x >= 1.0:
        return 1.0
    ln_front = (math.lgamma(a + b) - math.lgamma(a) - math.lgamma(b)
                + a * math.log(x) + b * math.log1p(-x))
    front = math.exp(ln_front)
    if x < (a + 1.0) / (a + b + 2.0):
        return front * _betacf(a, b, x) / a
    return 1.0 - front * _betacf(b, a, 1.0 - x) / b


def t_cdf(t, dof):
    """P(T ≤ t) for Student's t with `dof` > 0 degrees of freedom."""
    if dof <= 0:
        raise ValueError("t_cdf: dof must be > 0")
    if t == 0.0:
        return 0.5
    tail = 0.5 * betainc(0.5 * dof, 0.5, dof / (dof + t * t))  # P(T > |t|)
    return 1.0 - tail if t > 0 else tail


def t_quantile(p, dof):
    """The t with P(T ≤ t) = p (0 < p < 1), Student's t with `dof` > 0 degrees of freedom."""
    if not 0.0 < p < 1.0:
        raise ValueError("t_quantile: p must be in (0, 1)")
    if p == 0.5:
        return 0.0
    if p < 0.5:
        return -t_quantile(1.0 - p, dof)
    lo, hi = 0.0, 1.0
    while t_cdf(hi, dof) < p:
        lo, hi = hi, 2.0 * hi
        if hi > 1e12:
            return math.inf
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if t_cdf(mid, dof) < p:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-13 * max(1.0, hi):
            break
    return 0.5 * (lo + hi)


# ----------------------------------------------------------------------------------------------
# Distributions over seeds


def _finite(x):
    try:
        return x is not None and math.isfinite(float(x))
    except (TypeError, ValueError):
        return False


@dataclass
class Dist:
    """A sample (e.g. one metric over seeds): n, mean, sample sd, the `conf` confidence interval
    of the mean [lo, hi] (Student t, n − 1 dof; NaN for n < 2), min, max and the values."""
    n: int = 0
    mean: float = math.nan
    sd: float = math.nan
    lo: float = math.nan
    hi: float = math.nan
    min: float = math.nan
    max: float = math.nan
    values: list = field(default_factory=list)
    conf: float = CONFIDENCE
    n_failed: int = 0   # runs of the condition that gave no value (not finished, or no value)

    @property
    def has_ci(self):
        return self.n >= 2 and _finite(self.lo) and _finite(self.hi)

    @property
    def half_width(self):
        return 0.5 * (self.hi - self.lo) if self.has_ci else math.nan

    @property
    def deterministic(self):
        """One value, or n ≥ 2 identical values (zero spread: e.g. an unseeded condition run
        once per seed): a number, not a distribution, and it has no confidence interval. `lo`
        and `hi` keep their old values (NaN for n = 1, lo = hi = mean for zero spread) so that
        existing callers are unchanged; `ci` is the interval a reader may print."""
        return self.n == 1 or (self.n >= 2 and self.min == self.max)

    @property
    def ci(self):
        """(lo, hi) of the `conf` CI of the mean; (NaN, NaN) when there is none: nothing
        measured, a deterministic sample (see `deterministic`) or no finite interval."""
        if self.deterministic or not self.has_ci:
            return math.nan, math.nan
        return self.lo, self.hi

    def scaled(self, k):
        """The same sample times k (units); n_failed is kept."""
        d = describe([v * k for v in self.values], self.conf)
        d.n_failed = self.n_failed
        return d


def describe(values, conf=CONFIDENCE):
    """Dist of the finite entries of `values` (non-finite ones are dropped)."""
    v = [float(x) for x in values if _finite(x)]
    n = len(v)
    if n == 0:
        return Dist(conf=conf)
    mean = math.fsum(v) / n
    if n == 1:
        return Dist(1, mean, math.nan, math.nan, math.nan, v[0], v[0], v, conf)
    sd = math.sqrt(math.fsum((x - mean) ** 2 for x in v) / (n - 1))
    half = t_quantile(0.5 + 0.5 * conf, n - 1) * sd / math.sqrt(n)
    return Dist(n, mean, sd, mean - half, mean + half, min(v), max(v), v, conf)


def describe_ratios(ratios, conf=CONFIDENCE):
    """Dist of per-seed ratios on the log scale when all are positive: mean = the geometric
    mean exp(l̄) of l_s = log r_s, [lo, hi] = exp(l̄ ± t_{(1+conf)/2, n−1}·s_l/√n) (asymmetric,
    as a ratio's interval should be; the same interval as inference.ratio_log_t); sd, min, max
    and values are the raw ratios'. With a ratio ≤ 0 the log scale does not exist and the
    arithmetic describe() is returned."""
    d = describe(ratios, conf)
    if d.n == 0 or any(v <= 0.0 for v in d.values):
        return d
    logs = describe([math.log(v) for v in d.values], conf)
    d.mean = math.exp(logs.mean)
    if d.n >= 2:
        d.lo, d.hi = math.exp(logs.lo), math.exp(logs.hi)
    return d


@dataclass
class Paired:
    """Per-seed ratios num[s]/den[s] over the seeds both have (den ≠ 0, both finite); dist
    describes them on the log scale (describe_ratios)."""
    seeds: list
    ratios: list
    dist: Dist
    n_below_1: int   # seeds in which the ratio is < 1 (the numerator's method is cheaper)
    n_failed: int = 0  # seeds left out because a run of either side failed or is missing

    @property
    def n(self):
        return len(self.ratios)


def paired_ratio(num, den):
    """num, den: {seed: value}. Paired ratios over the common seeds (sorted)."""
    seeds = sorted((s for s in num if s in den and _finite(num[s]) and _finite(den[s])
                    and float(den[s]) != 0.0), key=lambda s: (s is None, s))
    ratios = [float(num[s]) / float(den[s]) for s in seeds]
    return Paired(seeds, ratios, describe_ratios(ratios), sum(1 for r in ratios if r < 1.0))


@dataclass
class PairedDiff:
    """Per-seed differences a[s] − b[s] over the seeds both have (both finite)."""
    seeds: list
    diffs: list
    dist: Dist

    @property
    def n(self):
        return len(self.diffs)


def paired_difference(a, b):
    """a, b: {seed: value}. Paired differences a[s] − b[s] over the common seeds (sorted)."""
    seeds = sorted((s for s in a if s in b and _finite(a[s]) and _finite(b[s])),
                   key=lambda s: (s is None, s))
    diffs = [float(a[s]) - float(b[s]) for s in seeds]
    return PairedDiff(seeds, diffs, describe(diffs))


def direction(d):
    """+1 when the sample's 95 % CI lies entirely above 0, −1 entirely below, 0 when it
    contains 0 ("no significant change"); one (deterministic) value: its sign. None when
    nothing was measured (or n ≥ 2 without a finite interval)."""
    d = d.dist if isinstance(d, (Paired, PairedDiff)) else d
    if d.n == 0:
        return None
    if d.n == 1:
        return (d.mean > 0.0) - (d.mean < 0.0)
    if not d.has_ci:
        return None
    return 1 if d.lo > 0.0 else (-1 if d.hi < 0.0 else 0)


def first_crossing(t, y, level):
    """The first time y(t) reaches `level` from below, linearly interpolated between the two
    samples that bracket it (t increasing); y[0] ≥ level gives t[0]; NaN if never reached.
    Its error is that of linear interpolation on the grid: O(h²·|y''|/|y'|) for step h."""
    prev_t = prev_y = None
    for ti, yi in zip(t, y):
        ti, yi = float(ti), float(yi)
        if yi >= level:
            if prev_t is None or yi == prev_y:
                return ti
            return prev_t + (level - prev_y) * (ti - prev_t) / (yi - prev_y)
        prev_t, prev_y = ti, yi
    return math.nan


def pooled_saving(pairs):
    """pairs: list of (num, den), each {seed: value} (e.g. barycenter and vehicle energy of
    matched cases). Per seed present in all of them: 1 − Σ num / Σ den. Returns (seeds, Dist)."""
    if not pairs:
        return [], Dist()
    common = None
    for num, den in pairs:
        ok = {s for s in num if s in den and _finite(num[s]) and _finite(den[s])}
        common = ok if common is None else common & ok
    seeds = sorted(common, key=lambda s: (s is None, s))
    vals = []
    for s in seeds:
        sn = math.fsum(float(num[s]) for num, _ in pairs)
        sd = math.fsum(float(den[s]) for _, den in pairs)
        vals.append(1.0 - sn / sd if sd != 0.0 else math.nan)
    return seeds, describe(vals)


CHEAPER, DEARER, NO_DIFF = "cheaper", "dearer", "no significant difference"


def compare(paired):
    """Verdict on a ratio barycenter/vehicle: "cheaper" when its CI lies entirely below 1,
    "dearer" entirely above 1, else "no significant difference". A single (deterministic) run
    has no interval: its ratio decides. None when nothing was measured."""
    d = paired.dist if isinstance(paired, Paired) else paired
    if d.n == 0:
        return None
    lo, hi = (d.lo, d.hi) if d.has_ci else (d.mean, d.mean)
    if d.n >= 2 and not d.has_ci:
        return None
    if hi < 1.0:
        return CHEAPER
    if lo > 1.0:
        return DEARER
    return NO_DIFF


# ----------------------------------------------------------------------------------------------
# The reproduction scorecard's verdict rule

REPRODUCED, SAME_DIRECTION, DIFFERS, NOT_MEASURED = (
    "reproduced", "same direction", "differs", "not measured")
TOL_RATIO = 0.05      # absolute tolerance on dimensionless ratios and fractions (5 points)
TOL_FACTOR = 1.25     # tolerance factor on absolute quantities (±25 %)

RULE_TEXT = (
    f"**Verdict rule.** *Reproduced*: the paper's value lies inside our 95 % confidence interval "
    f"(seeded rows), or within ±{TOL_RATIO:g} of our value for ratios and fractions (energy "
    f"ratios, savings, E/E(IV)), or within a factor {TOL_FACTOR:g} of it for absolute quantities "
    f"(mm, J). *Same direction*: not reproduced, but on the same side of the reference as ours "
    f"(ratio below or above 1, saving above or below 0; for seeded rows our whole interval must "
    f"be on that side); absolute quantities have no reference and are either reproduced or "
    f"differ. *Differs*: otherwise. A statement read from the paper's text or figures is "
    f"reproduced when it holds in our runs by the criterion given in its row, same direction "
    f"when only its sign or trend holds, and differs when our runs contradict it.")


def scorecard_verdict(paper, mean, lo=math.nan, hi=math.nan, kind="ratio", ref=1.0,
                      tol_ratio=TOL_RATIO, tol_factor=TOL_FACTOR):
    """Verdict of one scorecard row (see RULE_TEXT).

    paper: the paper's value; mean: ours; lo, hi: our 95 % CI (NaN when unseeded).
    kind "ratio": dimensionless, compared on an absolute scale, with a reference `ref` (1 for
    a ratio, 0 for a saving) that defines "same direction"; kind "absolute": compared by factor.
    """
    if not _finite(mean) or not _finite(paper):
        return NOT_MEASURED
    paper, mean = float(paper), float(mean)
    in_ci = _finite(lo) and _finite(hi) and lo <= paper <= hi
    if kind == "absolute":
        if paper == 0.0:
            return REPRODUCED if (abs(mean) <= 1e-12 or in_ci) else DIFFERS
        fac = mean / paper
        return REPRODUCED if (in_ci or 1.0 / tol_factor <= fac <= tol_factor) else DIFFERS
    if kind != "ratio":
        raise ValueError(f"scorecard_verdict: unknown kind {kind!r}")
    if in_ci or abs(mean - paper) <= tol_ratio:
        return REPRODUCED
    side_p = (paper > ref) - (paper < ref)
    if _finite(lo) and _finite(hi):
        side_o = 1 if lo > ref else (-1 if hi < ref else 0)
    else:
        side_o = (mean > ref) - (mean < ref)
    return SAME_DIRECTION if side_p != 0 and side_p == side_o else DIFFERS


def statement_verdict(holds):
    """Verdict of a statement: True → reproduced, "partly" → same direction, False → differs,
    None → not measured."""
    if holds is None:
        return NOT_MEASURED
    if holds == "partly":
        return SAME_DIRECTION
    return REPRODUCED if holds else DIFFERS


# ----------------------------------------------------------------------------------------------
# Integrals


def impulse(t, x):
    """∫|x(t)| dt by the trapezoidal rule. t: sequence of n times; x: n scalars or n vectors
    (their Euclidean norm is integrated)."""
    n = len(t)
    if n < 2:
        return 0.0
    mags = []
    for v in x:
        try:
            mags.append(math.sqrt(math.fsum(float(c) * float(c) for c in v)))
        except TypeError:
            mags.append(abs(float(v)))
    return math.fsum(0.5 * (mags[i] + mags[i + 1]) * (float(t[i + 1]) - float(t[i]))
                     for i in range(n - 1))
