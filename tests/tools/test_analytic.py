# SPDX-License-Identifier: Apache-2.0
"""tools/analytic.py (SPEC §9 item 8, [87–89]): closed forms against a direct numerical
integration of the simplified model's motion, and the limits against the ratio they solve.

Usage: test_analytic.py SOURCE_DIR
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(sys.argv[1], "tools"))
from uvms_tools.models import analytic as A  # noqa: E402

# Tolerance of the closed forms against the numerical integration. np.gradient's second-order
# differences and the trapezoidal rule on 200001 samples give a relative error of order
# (Δt·π/tF)² ≈ 1e-10; 1e-6 leaves four orders of margin yet catches any error in a factor
# (π, 16, η², a missing 2), which would be at least a few percent.
REL_TOL_NUMERIC = 1e-6
# The limits are closed-form solutions of ratio = 1: only rounding separates them from 1.
REL_TOL_LIMIT = 1e-12

failures = []


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


def rel(a, b):
    return abs(a - b) / abs(b)


# Closed form vs numerical integration over payloads, travels and durations, SPEC's fluid and
# vehicle (defaults of analytic.py = SPEC §3.2).
for payload_kg in (1.0, 10.0, 50.0, 300.0):
    for r_delta_m in (0.3, 1.0, 1.82):
        for t_f_s in (6.0, 60.0):
            eta = float(A.eta(payload_kg))
            num = A.numeric_impulses(payload_kg, r_delta_m, t_f_s)
            d_cf = float(A.drag_impulse(eta, r_delta_m, t_f_s))
            f_cf = float(A.reaction_impulse(eta, r_delta_m, t_f_s))
            tag = f"mP={payload_kg} kg rΔ={r_delta_m} m tF={t_f_s} s"
            check(rel(num["drag"], d_cf) < REL_TOL_NUMERIC,
                  f"D̃0 [87] {tag}: numeric {num['drag']:.12g} vs closed {d_cf:.12g}")
            check(rel(num["reaction_free"], f_cf) < REL_TOL_NUMERIC,
                  f"F̃0 [88] {tag}: numeric {num['reaction_free']:.12g} vs closed {f_cf:.12g}")
            # The exact held-vehicle reaction impulse is mP·rΔ·π/tF (∫|d̈| = rΔπ/tF).
            held = payload_kg * r_delta_m * math.pi / t_f_s
            check(rel(num["reaction_held"], held) < REL_TOL_NUMERIC,
                  f"exact reaction {tag}: numeric {num['reaction_held']:.12g} vs {held:.12g}")
            # [89] is the quotient of [87] and [88]; tF cancels.
            check(rel(float(A.ratio(eta, r_delta_m)), d_cf / f_cf) < 1e-12,
                  f"[89] = [87]/[88] {tag}")
            check(rel(float(A.ratio_exact_reaction(eta, r_delta_m)), d_cf / held) < 1e-12,
                  f"exact-reaction ratio = D̃0/(mP rΔ π/tF) {tag}")

# Limits: the ratio is exactly 1 there.
eta_star, mp_star = A.payload_limit(A.ARM_MAX_TRAVEL_M)
check(0.0 < eta_star < 1.0 and math.isfinite(mp_star), f"payload limit exists at rΔ = 1.82 m: "
      f"η* = {eta_star:.6f}, mP* = {mp_star:.3f} kg")
check(abs(float(A.ratio(eta_star, A.ARM_MAX_TRAVEL_M)) - 1.0) < REL_TOL_LIMIT, "ratio(η*) == 1")
check(abs(float(A.ratio(A.eta(mp_star), A.ARM_MAX_TRAVEL_M)) - 1.0) < REL_TOL_LIMIT,
      "ratio(η(mP*)) == 1")
r_star = A.travel_limit()
check(abs(float(A.ratio(1.0, r_star)) - 1.0) < REL_TOL_LIMIT, f"ratio(η=1, rΔ*={r_star:.6f}) == 1")
check(float(A.ratio(0.999999, r_star * 0.999)) < 1.0 < float(A.ratio(0.999999, r_star * 1.001)),
      "below the travel limit the ratio stays < 1 as η → 1, above it exceeds 1")
e_short, m_short = A.payload_limit(0.5 * r_star)
check(e_short >= 1.0 and math.isinf(m_short), "no payload limit for rΔ below the travel limit")

print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
