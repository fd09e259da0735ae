# SPDX-License-Identifier: Apache-2.0
"""delay: how well, and how late, a produced signal follows a desired one (experiment 3's
wrench tracking)."""
import numpy as np


def rms(x, axis=0):
    """Root mean square along `axis`; NaN for an empty array."""
    x = np.asarray(x, float)
    return np.sqrt(np.mean(x * x, axis=axis)) if x.size else np.nan


def best_lag(des, prod, dt, max_lag_s=15.0):
    """Delay L ≥ 0 [s] minimising the RMS of des(t) − prod(t + L) over the overlap, with that
    RMS and the RMS at L = 0. des, prod: (n, k) sampled every dt; lags are whole samples up to
    min(max_lag_s, half the record)."""
    n = len(des)
    max_lag = int(min(max_lag_s / dt, n // 2))
    best = (0, float("inf"))
    errs = []
    for lag in range(max_lag + 1):
        d = des[: n - lag] - prod[lag:]
        e = float(np.sqrt(np.mean(np.sum(d * d, axis=1)))) if len(d) else float("inf")
        errs.append(e)
        if e < best[1]:
            best = (lag, e)
    return best[0] * dt, best[1], errs[0] if errs else float("nan")


def tracking_errors(f_des, f_prod, n_des, n_prod):
    """RMS of |F_des|, |F_des − F_prod|, |N_des|, |N_des − N_prod| (rows are samples)."""
    return dict(f=rms(np.linalg.norm(f_des, axis=1)),
                f_err=rms(np.linalg.norm(f_des - f_prod, axis=1)),
                n=rms(np.linalg.norm(n_des, axis=1)),
                n_err=rms(np.linalg.norm(n_des - n_prod, axis=1)))
