# SPDX-License-Identifier: Apache-2.0
"""checks: consistency checks on logged records (sign convention, joint tracking, final pose,
the EE error recomputed from a log)."""
import numpy as np


def sign_agreement(thrust, speed, min_thrust=1e-3):
    """(n_ok, n): samples with |T| > min_thrust, and those among them with sign(T) =
    −sign(ω) (the CT2 < 0 convention)."""
    th, w = np.asarray(thrust, float), np.asarray(speed, float)
    m = np.abs(th) > min_thrust
    return int((np.sign(th[m]) == -np.sign(w[m])).sum()), int(m.sum())


def max_wrapped_error(ref, actual):
    """The largest |ref − actual| of angles, wrapped to (−π, π]."""
    d = np.angle(np.exp(1j * (np.asarray(ref, float) - np.asarray(actual, float))))
    return float(np.max(np.abs(d), initial=0.0))


def distance(a, b):
    """|a − b| of two points."""
    return float(np.linalg.norm(np.subtract(a, b)))


def relative_gap(mean_recomputed, logged):
    """|recomputed − logged| / |logged| (logged ≠ 0 or a tiny floor)."""
    return abs(mean_recomputed - logged) / max(abs(logged), 1e-300)
