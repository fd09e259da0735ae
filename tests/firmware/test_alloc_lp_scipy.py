# SPDX-License-Identifier: Apache-2.0
"""The firmware's least-Σ|T| allocation (alloc_lp.h) against scipy.optimize.linprog (HiGHS).

Usage: test_alloc_lp_scipy.py DRIVER REAL   (REAL: float or double, the firmware build's type)

DRIVER (tests/firmware/alloc_lp_driver.c) runs the firmware's pseudoinverse allocation, thrust
limit and LP on the paper's layout for each stdin line. For every case this test solves the same
linear program with HiGHS, written from SPEC §3.4's table typed in here:

    min Σ (T⁺ + T⁻)  s.t.  H_u·(T⁺ − T⁻) = w* = H·P,  0 ≤ T± ≤ T_max

with P the firmware's pseudoinverse thrusts (after the limit), and checks the firmware's T:
status OK, unusable thrusters exactly 0, |T_j| ≤ T_max, H·T = w*, Σ|T| ≤ Σ|P|, and Σ|T| equal
to HiGHS's optimum. 500 random cases (fixed seed): all thrusters, one and two unusable (some of
rank 5), no limit and limits below the largest unlimited thrust (saturated: the raw wrench is
not producible). Prints the agreement, the saving and the iteration counts.

Tolerance (relative to Σ|P|, and for the residual to max(|w*|, Σ|T|)): HiGHS is run with
feasibility tolerances of 1e-10 (its objective is then good to ~1e-10 relative); the firmware in
double is good to ~1e-15, in float to ~1e-7 (a few hundred float eps through the pivots). So
1e-8 for double and 2e-5 for float.
"""
import subprocess
import sys

import numpy as np
from scipy.optimize import linprog

A = np.array([[-0.5, 0.5, 0.5], [-0.5, -0.5, 0.5], [-0.5, 0.5, -0.5], [-0.5, -0.5, -0.5],
              [0.1, 0.5, 0.0], [0.1, -0.5, 0.0], [0.1, 0.0, 0.5], [0.1, 0.0, -0.5]])
U = np.array([[1, 0, 0], [1, 0, 0], [1, 0, 0], [1, 0, 0],
              [0, 0, 1], [0, 0, 1], [0, 1, 0], [0, 1, 0]], dtype=float)
H = np.vstack([U.T, np.cross(A, U).T])  # 6 × 8: (u_j; a_j × u_j)

N_CASES = 500
FRACTIONS = (0.0, 0.8, 0.5, 0.3)  # T_max / max|P_unlimited|; 0: no limit


def run_driver(driver, cases):
    """cases: list of (mask, limit_N, w[6]); returns the parsed output rows."""
    text = "".join(f"{m} {float(lim)!r} " + " ".join(repr(float(x)) for x in w) + "\n"
                   for m, lim, w in cases)
    out = subprocess.run([driver], input=text, capture_output=True, text=True, check=True).stdout
    rows = [line.split() for line in out.splitlines()]
    assert len(rows) == len(cases), f"driver answered {len(rows)} of {len(cases)} cases"
    return [(int(r[0]), int(r[1]), np.array(r[2:10], float), np.array(r[10:18], float))
            for r in rows]


def random_cases(rng):
    cases = []
    for c in range(N_CASES):
        mask = 0xFF
        for j in rng.choice(8, size=c % 3, replace=False):
            mask &= ~(1 << int(j))
        w = np.concatenate([20.0 * rng.standard_normal(3), 10.0 * rng.standard_normal(3)])
        if c % 50 == 0:
            w[:] = 0.0
        cases.append((mask, w, FRACTIONS[(c // 3) % len(FRACTIONS)]))
    return cases


def highs_optimum(mask, w_star, limit):
    usable = [j for j in range(8) if mask >> j & 1]
    Hu = H[:, usable]
    n = len(usable)
    res = linprog(np.ones(2 * n), A_eq=np.hstack([Hu, -Hu]), b_eq=w_star,
                  bounds=[(0.0, limit)] * (2 * n), method="highs",
                  options=dict(primal_feasibility_tolerance=1e-10,
                               dual_feasibility_tolerance=1e-10))
    assert res.status == 0, f"HiGHS: {res.message}"
    return res.fun


def main():
    driver, real = sys.argv[1], sys.argv[2]
    tol = 2e-5 if real == "float" else 1e-8
    rng = np.random.default_rng(20261216)
    cases = random_cases(rng)
    # Pass 1: unlimited, for the scale of the limits; pass 2: the cases as tested.
    first = run_driver(driver, [(m, 0.0, w) for m, w, _ in cases])
    limits = []
    for (m, w, frac), (_, _, P, _) in zip(cases, first):
        pmax = np.abs(P).max()
        limit = frac * pmax if frac > 0 and pmax > 0 else 0.0
        # The limit as the firmware holds it (a float build rounds it): P and T are bounded
        # by that value, and so is the reference LP.
        limits.append(float(np.float32(limit)) if real == "float" else limit)
    second = run_driver(driver, [(m, lim, w) for (m, w, _), lim in zip(cases, limits)])

    failures, worst_obj, worst_res, savings, iters, saturated = [], 0.0, 0.0, [], [], 0
    for c, ((mask, w, _), limit, (status, it, P, T)) in enumerate(zip(cases, limits, second)):
        def fail(what):
            failures.append(f"case {c} mask 0x{mask:02x} limit {limit:.6g}: {what}")
        if status != 0:
            fail(f"status {status}")
            continue
        lim = limit if limit > 0 else None
        w_star = H @ P
        opt = highs_optimum(mask, w_star, lim)
        sum_p, sum_t = np.abs(P).sum(), np.abs(T).sum()
        unusable = [j for j in range(8) if not mask >> j & 1]
        if any(T[j] != 0.0 for j in unusable):
            fail(f"unusable thruster driven: {T}")
        if lim is not None and np.abs(T).max() > limit:
            fail(f"|T| {np.abs(T).max()} above the limit")
        if sum_t > sum_p * (1 + 4 * np.finfo(np.float32 if real == "float" else float).eps):
            fail(f"Σ|T| {sum_t} above the pseudoinverse's {sum_p}")
        scale = max(np.abs(w_star).max(), sum_t)
        if scale > 0:
            res = np.abs(H @ T - w_star).max() / scale
            worst_res = max(worst_res, res)
            if res > tol:
                fail(f"residual {res:.3g}")
        if sum_p > 0:
            err = abs(sum_t - opt) / sum_p
            worst_obj = max(worst_obj, err)
            if err > tol:
                fail(f"Σ|T| {sum_t!r} vs HiGHS {opt!r} (relative {err:.3g})")
            savings.append(1.0 - sum_t / sum_p)
            iters.append(it)
            saturated += limit > 0 and np.abs(P).max() >= limit * (1 - 1e-6)
        elif sum_t != 0.0 or opt > 1e-12:
            fail("w = 0 must give T = 0")
    print(f"alloc LP ({real}) vs scipy {__import__('scipy').__version__} linprog HiGHS: "
          f"{len(second)} cases ({saturated} at the thrust limit); |Σ|T| − HiGHS| / Σ|P| worst "
          f"{worst_obj:.2g}, residual worst {worst_res:.2g}; Σ|T| saving vs pseudoinverse mean "
          f"{100 * np.mean(savings):.2f} %, largest {100 * np.max(savings):.2f} %; iterations "
          f"median {np.median(iters):.0f}, worst {np.max(iters)}")
    for f in failures[:20]:
        print("FAIL", f)
    if saturated < 100:
        failures.append(f"only {saturated} saturated cases")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
