# SPDX-License-Identifier: Apache-2.0
"""inference: confidence intervals and tests a referee accepts for per-seed (paired) results
(scorecard and report). numpy and scipy (the bootstrap); the Student t quantile and CDF are
stats.t_quantile / stats.t_cdf, so that the tests can check them against scipy.stats.t.

Every estimator returns an Estimate: point estimate, [lo, hi] at `conf`, n, the method's name
and a two-sided p-value against the null (ratio 1, difference 0). A deterministic sample (one
value, or no spread: the same number in every seed) is a number, not a distribution: its
Estimate has deterministic = True, lo = hi = p = NaN, and fmt_estimate prints
"0.7281 (deterministic)" instead of "0.7281 ± 0.0000".

- paired_t(a, b): mean of the per-seed differences a[s] − b[s], Student t CI, paired t-test.
- ratio_log_t(num, den): geometric-mean ratio exp(mean log(num/den)), its CI back-transformed
  from the t CI of the mean log ratio, p of the one-sample t-test of the logs against 0.
- ratio_bca(num, den): ratio of means Σnum/Σden, BCa bootstrap CI (scipy.stats.bootstrap,
  paired resampling of seeds, fixed seed), p by inverting the BCa interval.
- log_ratio_change(ratios_a, ratios_b): does the answer change between two conditions? The
  per-seed difference of log ratios, its t CI and p (a test of the difference, never a
  comparison of two significances).
- holm(p): Holm–Bonferroni adjusted p-values and rejections (MULTIPLICITY_POLICY).
- fmt_estimate(x): "est [lo, hi]", "mean ± h" or "est (deterministic)".

References: Student t intervals and tests for paired data (e.g. Wasserman, All of Statistics,
§10); Efron B., Better bootstrap confidence intervals, JASA 82 (1987) 171–185 (BCa); Efron &
Tibshirani, An Introduction to the Bootstrap (1993) §14.3, §15.4 (BCa, the p-value of an
interval); Holm S., A simple sequentially rejective multiple test procedure, Scand. J. Statist.
6 (1979) 65–70; Gelman & Stern, The difference between "significant" and "not significant" is
not itself statistically significant, Am. Stat. 60 (2006) 328–331.
"""
import math
from dataclasses import dataclass, replace

import numpy as np
from scipy import special
from scipy import stats as sps

from . import stats

FAMILY_ALPHA = 0.05
MULTIPLICITY_POLICY = (
    "**Multiplicity.** The seed-dependent verdicts of the report (those decided by a confidence "
    "interval or a test over seeds) are one family; their p-values are adjusted by Holm's "
    f"step-down procedure (Holm 1979) at a family-wise error rate of {100 * FAMILY_ALPHA:g} %. "
    "Deterministic rows (one run, or the same value in every seed) have no sampling error and "
    "are not in the family.")
N_RESAMPLES = 9999
BOOT_SEED = 20140901   # fixed: the report's bootstrap intervals are reproducible run to run


@dataclass(frozen=True)
class Estimate:
    """An estimate with its `conf` confidence interval [lo, hi] and a two-sided p-value
    against `null`. deterministic: no sampling spread (n = 1 or zero spread): lo, hi, p NaN."""
    estimate: float
    lo: float
    hi: float
    n: int
    method: str
    p: float
    conf: float = stats.CONFIDENCE
    null: float = 0.0
    deterministic: bool = False

    @property
    def has_ci(self):
        return not self.deterministic and math.isfinite(self.lo) and math.isfinite(self.hi)

    @property
    def excludes_null(self):
        """The CI lies entirely on one side of the null (significant at 1 − conf)."""
        return self.has_ci and (self.lo > self.null or self.hi < self.null)

    def exp(self, method=None):
        """The same estimate back-transformed from a log scale: exp of estimate, lo, hi and
        null (the p-value is invariant under the monotone map)."""
        return replace(self, estimate=math.exp(self.estimate), lo=math.exp(self.lo),
                       hi=math.exp(self.hi), null=math.exp(self.null),
                       method=method or f"exp({self.method})")


# ----------------------------------------------------------------------------------------------
# Paired data


def _as_dict(x):
    """{seed: value} from a dict, a stats.Paired (its seeds and ratios) or a sequence (its
    positions are the seeds)."""
    if isinstance(x, stats.Paired):
        return dict(zip(x.seeds, x.ratios))
    if isinstance(x, dict):
        return x
    return dict(enumerate(np.asarray(x, float).tolist()))


def paired_arrays(a, b, positive=False):
    """The paired values over the seeds both have with finite values (dicts: by seed, sorted;
    sequences: by position). positive=True (log scale): a value ≤ 0 raises ValueError.
    Returns (seeds, a_values, b_values) with numpy arrays."""
    da, db = _as_dict(a), _as_dict(b)
    seeds = sorted((s for s in da if s in db and stats._finite(da[s]) and stats._finite(db[s])),
                   key=lambda s: (s is None, s))
    xa = np.array([float(da[s]) for s in seeds])
    xb = np.array([float(db[s]) for s in seeds])
    if positive and (np.any(xa <= 0.0) or np.any(xb <= 0.0)):
        raise ValueError("paired_arrays: the log scale needs positive values")
    return seeds, xa, xb


def _t_estimate(d, method, null=0.0, conf=stats.CONFIDENCE):
    """Estimate of the mean of the sample d (a numpy array) by Student's t:
    mean ± t_{(1+conf)/2, n−1}·s/√n; p = 2·P(T_{n−1} ≤ −|mean − null|/(s/√n))."""
    n = int(d.size)
    if n == 0:
        return Estimate(math.nan, math.nan, math.nan, 0, method, math.nan, conf, null)
    dist = stats.describe(d.tolist(), conf)
    if dist.deterministic:
        return Estimate(dist.mean, math.nan, math.nan, n, method, math.nan, conf, null, True)
    t = (dist.mean - null) / (dist.sd / math.sqrt(n))
    p = 2.0 * stats.t_cdf(-abs(t), n - 1)
    return Estimate(dist.mean, dist.lo, dist.hi, n, method, p, dist.conf, null)


def paired_t(a, b, conf=stats.CONFIDENCE):
    """Paired t: the mean of d_s = a[s] − b[s] over the common seeds, its Student t CI
    d̄ ± t_{(1+conf)/2, n−1}·s_d/√n and the p-value of H0: E[d] = 0. a, b: {seed: value} or
    sequences (paired by position)."""
    _, xa, xb = paired_arrays(a, b)
    return _t_estimate(xa - xb, "paired t", conf=conf)


def ratio_log_t(num, den, conf=stats.CONFIDENCE):
    """Geometric-mean ratio on the log scale: with l_s = log(num[s]/den[s]),
    estimate exp(l̄), CI exp(l̄ ± t_{(1+conf)/2, n−1}·s_l/√n), p of the one-sample t-test of l
    against 0 (ratio 1). Appropriate when the per-seed ratios are roughly lognormal; the CI is
    asymmetric around the estimate, as a ratio's should be. Values must be positive."""
    _, xn, xd = paired_arrays(num, den, positive=True)
    return _t_estimate(np.log(xn / xd), "log t", conf=conf).exp("log-t (geometric-mean ratio)")


def ratio_or_none(num, den, conf=stats.CONFIDENCE):
    """ratio_log_t, or None when a side is empty or not positive (a row or point without a
    ratio rather than an error)."""
    try:
        return ratio_log_t(num, den, conf)
    except ValueError:
        return None


def _ratio_of_means(x, y, axis=-1):
    return np.mean(x, axis=axis) / np.mean(y, axis=axis)


def _bca_p(boot, theta_hat, jack, null):
    """Two-sided p of H0: θ = null by inverting the BCa interval (Efron & Tibshirani 1993
    §15.4): the level 1 − p at which an endpoint of the interval reaches `null`.

    z0 = Φ⁻¹(F̂(θ̂)) (F̂: the bootstrap CDF, ties counted half, as scipy does); acceleration
    a = Σ U³ / (6 (Σ U²)^{3/2}), U_i = θ̄_(·) − θ_(i) over the jackknife values θ_(i). The BCa
    endpoint of one-sided level α is the F̂-quantile Φ(z0 + (z0 + z_α)/(1 − a(z0 + z_α))).
    Setting it to F̂(null) =: Φ(ζ) (resamples equal to the null counted towards θ̂) gives w = z0 + z_α = (ζ − z0)/(1 + a(ζ − z0)), and
    p = 2·Φ(−|w − z0|). F̂(null) is clipped to [1/(2B), 1 − 1/(2B)]: when the null lies
    beyond every bootstrap value the p returned is that of the extreme resample, an upper
    bound (the resolution of B resamples)."""
    B = boot.size
    z0 = special.ndtri((np.count_nonzero(boot < theta_hat)
                        + np.count_nonzero(boot <= theta_hat)) / (2.0 * B))
    u = jack.mean() - jack
    a = np.sum(u ** 3) / (6.0 * np.sum(u ** 2) ** 1.5)
    # F̂(null) counting resamples equal to the null on the side of θ̂ (conservative when the
    # bootstrap distribution has atoms, as with few seeds: the p never contradicts the CI).
    q = (np.count_nonzero(boot <= null) if null <= theta_hat
         else np.count_nonzero(boot < null)) / B
    zeta = special.ndtri(min(max(q, 0.5 / B), 1.0 - 0.5 / B))
    den = 1.0 + a * (zeta - z0)
    if den <= 0.0:   # beyond the range the BCa map can reach: the null is in the far tail
        return 0.0
    w = (zeta - z0) / den
    return float(2.0 * special.ndtr(-abs(w - z0)))


def ratio_bca(num, den, n_resamples=N_RESAMPLES, seed=BOOT_SEED, conf=stats.CONFIDENCE):
    """Ratio of means R = Σ num / Σ den over the common seeds, with the BCa bootstrap CI
    (Efron 1987): scipy.stats.bootstrap(method='BCa', paired=True) resamples whole seeds
    (n_resamples, rng = np.random.default_rng(seed)); p against R = 1 by inverting the BCa
    interval (_bca_p). Values must be positive. n = 1, or the same ratio in every seed (every
    resample gives the same R): deterministic, no CI. With few seeds (fewer than about 10)
    the bootstrap distribution is coarse and BCa is unreliable: prefer ratio_log_t there."""
    _, xn, xd = paired_arrays(num, den, positive=True)
    n = int(xn.size)
    method = f"BCa bootstrap ({n_resamples} resamples, seed {seed})"
    if n == 0:
        return Estimate(math.nan, math.nan, math.nan, 0, method, math.nan, conf, 1.0)
    r = float(_ratio_of_means(xn, xd))
    if n == 1 or np.ptp(xn / xd) == 0.0:
        return Estimate(r, math.nan, math.nan, n, method, math.nan, conf, 1.0, True)
    res = sps.bootstrap((xn, xd), _ratio_of_means, n_resamples=n_resamples, vectorized=True,
                        paired=True, confidence_level=conf, method="BCa",
                        rng=np.random.default_rng(seed))
    keep = np.ones((n, n), bool)
    np.fill_diagonal(keep, False)   # row i: every seed but i (the jackknife samples)
    jack = np.array([_ratio_of_means(xn[k], xd[k]) for k in keep])
    p = _bca_p(res.bootstrap_distribution, r, jack, 1.0)
    ci = res.confidence_interval
    return Estimate(r, float(ci.low), float(ci.high), n, method, p, conf, 1.0)


def log_ratio_change(ratios_a, ratios_b, conf=stats.CONFIDENCE):
    """Does the answer change between conditions A and B? ratios_a, ratios_b: per-seed ratios
    ({seed: r} or stats.Paired, e.g. barycenter/vehicle energy with and without a change).
    Per common seed d_s = log r_a[s] − log r_b[s]; returns the paired t Estimate of mean d (log
    scale, null 0; .exp() gives the factor by which the geometric-mean ratio changes).

    This is the test of the difference. "A is significant and B is not" says nothing about
    whether A and B differ (Gelman & Stern 2006): never decide a change by comparing the two
    verdicts or their p-values."""
    _, xa, xb = paired_arrays(ratios_a, ratios_b, positive=True)
    return _t_estimate(np.log(xa / xb), "paired t on log-ratio differences", conf=conf)


# ----------------------------------------------------------------------------------------------
# Multiplicity


def holm(pvals, alpha=FAMILY_ALPHA):
    """Holm–Bonferroni (Holm 1979) over a family of p-values. With the m finite p-values sorted,
    p_(1) ≤ … ≤ p_(m), the adjusted values are p̃_(i) = min(1, max_{j ≤ i} (m − j + 1)·p_(j))
    and H_(i) is rejected when p̃_(i) ≤ alpha (the step-down rule: reject while
    p_(i) ≤ alpha/(m − i + 1), stop at the first that is not); family-wise error ≤ alpha under
    any dependence. Non-finite entries (deterministic rows, nothing measured) are not in the
    family: adjusted NaN, not rejected. Returns (adjusted, reject) as lists in input order."""
    p = np.asarray(pvals, float)
    adj = np.full(p.shape, np.nan)
    idx = np.flatnonzero(np.isfinite(p))
    order = idx[np.argsort(p[idx], kind="stable")]
    m = order.size
    scaled = (m - np.arange(m)) * p[order]
    adj[order] = np.minimum(1.0, np.maximum.accumulate(scaled))
    reject = np.isfinite(adj) & (adj <= alpha)
    return adj.tolist(), reject.tolist()


# ----------------------------------------------------------------------------------------------
# Formatting


def fmt_estimate(x, nd=4, unit=""):
    """A stats.Dist or an Estimate as text: 'n/a' when empty; 'v (deterministic)' for one value
    or zero spread (never '± 0.000'); 'mean ± h' for a Dist (symmetric t CI), 'est [lo, hi]' for
    an Estimate; `unit` follows the numbers."""
    est = x.estimate if isinstance(x, Estimate) else x.mean
    if x.n == 0 or not math.isfinite(est):
        return "n/a"
    if x.deterministic:
        return f"{est:.{nd}f}{unit} (deterministic)"
    if not x.has_ci:
        return f"{est:.{nd}f}{unit}"
    if isinstance(x, Estimate):
        return f"{est:.{nd}f}{unit} [{x.lo:.{nd}f}, {x.hi:.{nd}f}]"
    return f"{est:.{nd}f} ± {x.half_width:.{nd}f}{unit}"
