# SPDX-License-Identifier: Apache-2.0
"""The report's inference (report/analyses/inference.py, verdicts.py)
against scipy and independent computations, never against numbers copied from its own output:

- stats.t_quantile / t_cdf against scipy.stats.t;
- the paired t and the log-t ratio CI and p against scipy.stats.ttest_rel / ttest_1samp on
  the logs; the BCa ratio CI against a direct scipy.stats.bootstrap call made here, and its
  p-value against the level at which scipy's BCa interval reaches 1;
- coverage of the log-t CI over 2,000 simulated lognormal paired data sets with a known ratio;
- "does the answer change" decided by the paired test of the log-ratio difference, not by two
  significances;
- Holm against the step-down definition written out here (and statsmodels when installed);
- sign-aware verdicts (+1.0 % in the paper, −0.19 % ours is not reproduced); deterministic
  rows have no CI; the parameter range over which a verdict holds.

Usage: test_report_inference.py SOURCE_DIR
"""
import math
import os
import sys

import numpy as np
from scipy import stats as sps

sys.path.insert(0, os.path.join(sys.argv[1], "tools"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checklist  # noqa: E402
from uvms_tools.report.analyses import inference as I  # noqa: E402
from uvms_tools.report.analyses import stats  # noqa: E402
from uvms_tools.report.analyses import verdicts as V  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

TMP = scratch_dir("uvms-report-inference-")  # removed at exit (tests/support/scratch.py)


def paired_lognormal(rng, n, ratio, sigma):
    """n seeds: den lognormal(0, 0.3), num = den·ratio·exp(ε), ε ~ N(0, σ²): the per-seed log
    ratio is N(log ratio, σ²), so the true geometric-mean ratio is `ratio`."""
    den = rng.lognormal(0.0, 0.3, n)
    return den * ratio * np.exp(rng.normal(0.0, sigma, n)), den


def ratio_of_means(x, y, axis=-1):
    return np.mean(x, axis=axis) / np.mean(y, axis=axis)


def t_quantile_and_cdf_match_scipy():
    for dof in (1, 2, 3, 5, 9, 19, 29, 100, 1000):
        for p in (0.6, 0.9, 0.95, 0.975, 0.995, 0.9995):
            q, ref = stats.t_quantile(p, dof), sps.t.ppf(p, dof)
            assert abs(q - ref) <= 1e-9 * max(1.0, abs(ref)), f"t_{{{p},{dof}}}: {q} vs {ref}"
        for x in (-8.0, -2.5, -1.0, -0.1, 0.3, 1.7, 4.0):
            assert abs(stats.t_cdf(x, dof) - sps.t.cdf(x, dof)) <= 1e-12, f"t_cdf({x}, {dof})"


def paired_t_matches_scipy_ttest_rel():
    rng = np.random.default_rng(11)
    for n in (3, 8, 20):
        a, b = rng.normal(1.0, 0.5, n), rng.normal(0.8, 0.5, n)
        e, ref = I.paired_t(a, b), sps.ttest_rel(a, b)
        ci = ref.confidence_interval(0.95)
        assert abs(e.estimate - np.mean(a - b)) <= 1e-12 and e.n == n
        assert abs(e.lo - ci.low) <= 1e-9 and abs(e.hi - ci.high) <= 1e-9, f"n {n}: CI"
        assert abs(e.p - ref.pvalue) <= 1e-10, f"n {n}: p {e.p} vs {ref.pvalue}"
        e90, ci90 = I.paired_t(a, b, conf=0.9), ref.confidence_interval(0.9)
        assert abs(e90.lo - ci90.low) <= 1e-9 and abs(e90.hi - ci90.high) <= 1e-9, "90 % CI"


def log_t_ci_matches_scipy_ttest_1samp_on_logs():
    rng = np.random.default_rng(12)
    for n, ratio in ((4, 0.9), (10, 0.97), (20, 1.2)):
        num, den = paired_lognormal(rng, n, ratio, 0.1)
        e = I.ratio_log_t(num, den)
        ref = sps.ttest_1samp(np.log(num / den), 0.0)
        ci = ref.confidence_interval(0.95)
        assert abs(e.estimate - sps.gmean(num / den)) <= 1e-12, "geometric-mean ratio"
        assert abs(e.lo - math.exp(ci.low)) <= 1e-9 and abs(e.hi - math.exp(ci.high)) <= 1e-9
        assert abs(e.p - ref.pvalue) <= 1e-10, f"p {e.p} vs {ref.pvalue}"
        assert e.null == 1.0 and e.excludes_null == (ref.pvalue < 0.05)
        e90, ci90 = I.ratio_log_t(num, den, conf=0.9), ref.confidence_interval(0.9)
        assert abs(e90.lo - math.exp(ci90.low)) <= 1e-9 and e90.conf == 0.9, "90 % CI"
    # Seeds as dicts: paired by seed, a seed without a partner or with a failed run left out.
    e = I.ratio_log_t({1: 2.0, 2: 3.0, 3: 5.0, 4: math.nan}, {1: 1.0, 2: 2.0, 3: 4.0, 5: 1.0})
    ref = sps.ttest_1samp(np.log([2.0, 1.5, 1.25]), 0.0)
    assert e.n == 3 and abs(e.p - ref.pvalue) <= 1e-10, "dicts paired by seed"
    try:
        I.ratio_log_t([1.0, -1.0], [1.0, 1.0])
        raise AssertionError("a non-positive value on the log scale must raise")
    except ValueError:
        pass


def bca_matches_direct_scipy_bootstrap():
    rng = np.random.default_rng(13)
    for n, seed, b in ((6, 1, 999), (12, 7, 2999), (25, 3, 9999)):
        num, den = paired_lognormal(rng, n, 0.9, 0.15)
        e = I.ratio_bca(num, den, n_resamples=b, seed=seed)
        ref = sps.bootstrap((num, den), ratio_of_means, n_resamples=b, paired=True,
                            vectorized=True, method="BCa", confidence_level=0.95,
                            rng=np.random.default_rng(seed)).confidence_interval
        assert abs(e.estimate - num.sum() / den.sum()) <= 1e-12, "ratio of means"
        assert abs(e.lo - ref.low) <= 1e-12 and abs(e.hi - ref.high) <= 1e-12, (
            f"n {n}: [{e.lo}, {e.hi}] vs scipy [{ref.low}, {ref.high}]")


def bca_p_is_where_scipy_interval_reaches_1():
    """p inverts the interval: scipy's BCa interval at confidence 1 − p (same resamples) has
    an endpoint at 1, up to the spacing of the bootstrap quantiles."""
    rng = np.random.default_rng(14)
    tested = 0
    for _ in range(40):
        num, den = paired_lognormal(rng, 10, 0.96, 0.08)
        e = I.ratio_bca(num, den, n_resamples=9999, seed=5)
        if not 0.005 < e.p < 0.8:
            continue
        ci = sps.bootstrap((num, den), ratio_of_means, n_resamples=9999, paired=True,
                           vectorized=True, method="BCa", confidence_level=1.0 - e.p,
                           rng=np.random.default_rng(5)).confidence_interval
        gap = min(abs(ci.low - 1.0), abs(ci.high - 1.0))
        assert gap <= 2e-3, f"p {e.p:.4f}: interval [{ci.low:.5f}, {ci.high:.5f}] misses 1"
        assert (e.p < 0.05) == e.excludes_null, f"p {e.p:.4f} vs 95 % CI [{e.lo}, {e.hi}]"
        tested += 1
    assert tested >= 10, f"only {tested} data sets with a moderate p"
    # Three seeds: a coarse bootstrap distribution with an atom at 1 (every resample of seed 1
    # alone); scipy's interval touches 1, so the p must not be below 0.05.
    num, den = np.array([1.0, 2.0, 3.0]), np.array([1.0, 1.5, 2.0])
    e = I.ratio_bca(num, den)
    ci = sps.bootstrap((num, den), ratio_of_means, n_resamples=I.N_RESAMPLES, paired=True,
                       vectorized=True, method="BCa",
                       rng=np.random.default_rng(I.BOOT_SEED)).confidence_interval
    assert ci.low <= 1.0 <= ci.high and e.p >= 0.05, f"p {e.p} vs [{ci.low}, {ci.high}]"


def log_t_coverage_by_simulation():
    """2,000 data sets of 8 seeds, true geometric-mean ratio 0.8 (log sd 0.2): the 95 % log-t
    CI covers 0.8 in 95 % ± 2 % of them (binomial sd of the rate: 0.5 %)."""
    rng = np.random.default_rng(15)
    hits = 0
    for _ in range(2000):
        e = I.ratio_log_t(*paired_lognormal(rng, 8, 0.8, 0.2))
        hits += e.lo <= 0.8 <= e.hi
    assert 0.93 <= hits / 2000 <= 0.97, f"coverage {hits / 2000:.3f}"
    print(f"     log-t coverage {hits / 2000:.3f}")


def answer_change_is_a_paired_test_not_two_significances():
    """A: ratio significantly below 1 (p < 0.05); B: not (p > 0.05); comparing significances
    would say "the answer changes". The test of the per-seed log-ratio difference says it does
    not (its CI contains 0), and equals scipy's paired t on the logs."""
    rng = np.random.default_rng(16)
    e = rng.normal(0.0, 1.0, 10)
    e = 0.1 * (e - e.mean()) / e.std(ddof=1)   # log noise: mean 0, sd exactly 0.1
    ra = dict(enumerate(np.exp(-0.08 + e)))     # t = −0.08/(0.1/√10) = −2.53
    rb = dict(enumerate(np.exp(-0.055 + rng.permutation(e))))   # t = −1.74
    pa, pb = I.ratio_log_t(ra, {s: 1.0 for s in ra}), I.ratio_log_t(rb, {s: 1.0 for s in rb})
    assert pa.p < 0.05 < pb.p and pa.excludes_null and not pb.excludes_null, "premises"
    ch = I.log_ratio_change(ra, rb)
    ref = sps.ttest_rel(np.log(list(ra.values())), np.log(list(rb.values())))
    assert abs(ch.p - ref.pvalue) <= 1e-10 and ch.p > 0.05 and not ch.excludes_null, (
        f"change p {ch.p:.3f} (scipy {ref.pvalue:.3f})")
    assert abs(ch.exp().estimate - pa.estimate / pb.estimate) <= 1e-12, (
        "exp(mean difference) = ratio of the geometric-mean ratios")
    # Paired with stats.paired_ratio's output; a real change is detected.
    halved = {s: 0.5 * v * math.exp(0.02 * rng.normal()) for s, v in ra.items()}
    big = I.log_ratio_change(stats.paired_ratio(halved, {s: 1.0 for s in ra}), ra)
    ref = sps.ttest_rel(np.log(list(halved.values())), np.log(list(ra.values())))
    assert big.excludes_null and abs(big.p - ref.pvalue) <= 1e-8 * ref.pvalue, (big.p, ref.pvalue)
    assert big.lo < math.log(0.5) < big.hi, "a halving"


def holm_matches_step_down_definition():
    def brute(p, alpha):
        """Holm (1979) written out: sort; adjusted p_(i) = min(1, max_{j≤i} (m−j+1)·p_(j));
        reject H_(1..k−1) where k is the first i with p_(i) > alpha/(m−i+1)."""
        fin = [i for i, x in enumerate(p) if math.isfinite(x)]
        srt = sorted(fin, key=lambda i: p[i])
        m = len(srt)
        adj, rej = [math.nan] * len(p), [False] * len(p)
        run = 0.0
        for rank, i in enumerate(srt, start=1):
            run = max(run, (m - rank + 1) * p[i])
            adj[i] = min(1.0, run)
        for rank, i in enumerate(srt, start=1):
            if p[i] > alpha / (m - rank + 1):
                break
            rej[i] = True
        return adj, rej

    rng = np.random.default_rng(17)
    fams = [[0.01, 0.04, 0.03, 0.005], [0.2, 0.2, 0.01, math.nan, 0.0001], [0.5], []]
    fams += [list(rng.uniform(0.0, 0.1, k) ** 2) for k in (3, 7, 15)]
    try:
        from statsmodels.stats.multitest import multipletests
    except ImportError:
        multipletests = None
    for fam in fams:
        for alpha in (0.05, 0.01):
            adj, rej = I.holm(fam, alpha)
            badj, brej = brute(fam, alpha)
            assert rej == brej, f"{fam}: reject {rej} vs {brej}"
            assert all((math.isnan(x) and math.isnan(y)) or abs(x - y) <= 1e-15
                       for x, y in zip(adj, badj)), f"{fam}: adjusted {adj} vs {badj}"
            fin = [x for x in fam if math.isfinite(x)]
            if multipletests is not None and fin:
                r, pa, _, _ = multipletests(fin, alpha, method="holm")
                assert np.allclose([x for x in adj if math.isfinite(x)], pa)
    assert "Holm" in I.MULTIPLICITY_POLICY and "5 %" in I.MULTIPLICITY_POLICY


def sign_aware_directional_verdict():
    paper, ours = 0.010, -0.0019   # the paper: +1.0 %; ours: −0.19 %
    assert abs(ours - paper) <= stats.TOL_RATIO and stats.scorecard_verdict(
        paper, ours, kind="ratio", ref=0.0) == stats.REPRODUCED, "premise: the old rule"
    assert V.directional_verdict(paper, ours) == stats.DIFFERS, "+1.0 % vs −0.19 %"
    wide = stats.describe([-0.03, 0.02, 0.01, -0.015, 0.0055])   # mean −0.0019, CI ∋ +0.01
    assert wide.lo <= paper <= wide.hi and abs(wide.mean - ours) < 1e-12
    assert V.directional_verdict(paper, wide) == stats.DIFFERS, "CI contains p, mean opposite"
    assert V.directional_verdict(-0.01, -0.008) == stats.REPRODUCED
    assert V.directional_verdict(-0.01, 0.008) == stats.DIFFERS
    assert V.directional_verdict(0.01, 0.2) == stats.SAME_DIRECTION, "right sign, too big"
    assert V.directional_verdict(0.01, 0.0) == stats.DIFFERS, "no change is not an increase"
    assert V.directional_verdict(0.01, None) == stats.NOT_MEASURED
    up = stats.describe([0.19, 0.21, 0.2, 0.22, 0.18])            # CI above 0, far from 0.01
    assert V.directional_verdict(0.01, up) == stats.SAME_DIRECTION
    straddle = stats.describe([0.3, -0.1, 0.25, -0.05, 0.2])      # mean 0.12, CI ∋ 0, ∌ 0.5
    assert straddle.lo < 0 < straddle.hi < 0.5
    assert V.directional_verdict(0.5, straddle, tol=0.05) == stats.DIFFERS
    # A ratio below 1 (ref 1) from an Estimate.
    num, den = paired_lognormal(np.random.default_rng(18), 10, 0.9, 0.05)
    e = I.ratio_log_t(num, den)
    assert e.hi < 1.0 and V.directional_verdict(0.6, e, ref=1.0) == stats.SAME_DIRECTION
    assert V.directional_verdict(1.4, e, ref=1.0) == stats.DIFFERS
    assert V.directional_verdict(0.9, e, ref=1.0) == stats.REPRODUCED
    assert "differs" in V.DIRECTION_RULE_TEXT and "s·(m − r) ≤ 0" in V.DIRECTION_RULE_TEXT


def magnitude_verdict_handles_sign():
    assert V.magnitude_verdict(-2.0, -2.2) == stats.REPRODUCED
    assert V.magnitude_verdict(-2.0, 2.0) == stats.DIFFERS, "opposite sign, same size"
    assert V.magnitude_verdict(2.0, 2.6) == stats.DIFFERS, "beyond a factor 1.25"
    assert V.magnitude_verdict(2.0, stats.describe([2.4, 2.9, 3.1, 2.0])) == stats.REPRODUCED
    assert V.magnitude_verdict(0.0, 0.0) == stats.REPRODUCED
    assert V.magnitude_verdict(0.0, 0.1) == stats.DIFFERS


def deterministic_rows_have_no_ci():
    for d in (stats.describe([0.7281] * 5), stats.describe([0.7281])):
        assert d.deterministic and all(math.isnan(x) for x in d.ci)
        assert I.fmt_estimate(d) == "0.7281 (deterministic)", I.fmt_estimate(d)
    d = stats.describe([0.7281] * 5)
    assert d.lo == d.hi == d.mean and d.has_ci, "lo/hi kept for existing callers"
    nd = stats.describe([1.0, 2.0, 3.0])
    assert not nd.deterministic and nd.ci == (nd.lo, nd.hi) and "±" in I.fmt_estimate(nd)
    for e in (I.ratio_log_t([2.0, 4.0, 6.0], [1.0, 2.0, 3.0]),   # the same ratio every seed
              I.ratio_bca([2.0, 4.0, 6.0], [1.0, 2.0, 3.0]), I.ratio_bca([3.0], [4.0]),
              I.paired_t([1.0, 2.0], [0.5, 1.5])):
        assert e.deterministic and not e.has_ci and math.isnan(e.lo) and math.isnan(e.p), e
        assert I.fmt_estimate(e, 2).endswith("(deterministic)")
    assert I.ratio_bca([3.0], [4.0]).estimate == 0.75
    assert I.fmt_estimate(stats.describe([])) == "n/a"


def verdict_range_flags_parameter_dependence():
    def verdict(x):
        return V.directional_verdict(0.01, x)
    vr = V.verdict_range(verdict, {0.1: 0.011, 0.05: 0.02, 0.2: 0.012, 0.3: -0.001})
    assert vr.holds == [0.05, 0.1, 0.2] and vr.fails == [0.3] and (vr.lo, vr.hi) == (0.05, 0.2)
    assert not vr.robust and vr.contiguous
    assert V.sensitivity_note("A_v", vr) == (
        "reproduced only for A_v in [0.05, 0.2] (swept: 0.05, 0.1, 0.2, 0.3)")
    gap = V.verdict_range(verdict, {1: 0.01, 2: -0.01, 3: 0.01})
    assert not gap.contiguous and "at 1, 3" in V.sensitivity_note("k", gap)
    ok = V.verdict_range(verdict, {1: 0.01, 2: 0.012})
    assert ok.robust and V.sensitivity_note("k", ok) == ""
    none = V.verdict_range(verdict, {1: -0.01})
    assert not none.holds and math.isnan(none.lo) and not none.robust


CHECKS = [t_quantile_and_cdf_match_scipy, paired_t_matches_scipy_ttest_rel,
          log_t_ci_matches_scipy_ttest_1samp_on_logs, bca_matches_direct_scipy_bootstrap,
          bca_p_is_where_scipy_interval_reaches_1, log_t_coverage_by_simulation,
          answer_change_is_a_paired_test_not_two_significances,
          holm_matches_step_down_definition, sign_aware_directional_verdict,
          magnitude_verdict_handles_sign, deterministic_rows_have_no_ci,
          verdict_range_flags_parameter_dependence]

if __name__ == "__main__":
    sys.exit(checklist.run(CHECKS, TMP))
