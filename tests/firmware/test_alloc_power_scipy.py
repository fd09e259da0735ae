# SPDX-License-Identifier: Apache-2.0
"""The firmware's minimum-power allocation (alloc_power.h) against scipy.optimize (SLSQP).

Usage: test_alloc_power_scipy.py DRIVER REAL   (REAL: float or double, the firmware build's type)

DRIVER (tests/firmware/alloc_power_driver.c) runs the firmware's pseudoinverse allocation,
thrust limit and minimum-power solver on the paper's layout for each stdin line. For every
case this test solves the same problem independently, with H written from SPEC §3.4's table
typed in here, the null space of the usable columns from scipy.linalg.null_space (an SVD, not
the firmware's projector) and SLSQP:

    min Σ_{j usable} |T_j|^1.5  s.t.  H_u·T = H_u·P,  |T_j| ≤ T_max

with P the firmware's pseudoinverse thrusts (after the limit). Three checks:

The checks run on the paper's layout, and 1 and 2 also on a second, "vectored" one (four
horizontal thrusters at 45°, four vertical; alloc_power_driver.c), whose null directions each
couple four thrusters; check 1 also on the vectored layout with the weighted cost
Σ w_j·|T_j|^1.5 of thrusters with different propellers (uvms_alloc_min_power_each, weights
WEIGHT, differing inside each null direction), against SLSQP and the KKT conditions of that cost.

1. Optimum: 600 random cases (fixed seed; 300 on the vectored layout): all thrusters, one and two unusable (some of rank
   5), no limit and limits below the largest unlimited thrust (saturated: the raw wrench is
   not producible, so P is the attitude-first scaled one), and zero wrenches. The firmware's T
   must be feasible (status OK, unusable thrusters exactly 0, |T_j| ≤ T_max, H·T = H·P), no
   costlier than P, satisfy the KKT conditions (least-squares multipliers from scipy's
   lsq_linear: a certificate of the optimum that depends on no solver), cost no more than
   SLSQP's optimum, and, where SLSQP itself reached a KKT point, equal its thrusts.
2. Continuity: 300 random cases and a random step Δw of 10⁻³ (double) or 10⁻² (float) of |w|:
   ‖T(w + Δw) − T(w)‖ ≤ L·‖Δw‖ with L ≤ 10·‖H_u⁺‖₂ (the pseudoinverse's own gain, its
   spectral norm, from numpy).
3. Warm start: a slowly varying wrench (a smooth random walk, 400 steps of 0.03 s) solved
   with the previous step's solution as the start and cold, once with every thruster and no
   limit, once with a limit that holds thrusts on their bounds and a thruster lost half way:
   the same thrusts within TOL_T, every solve converged, no more iterations warm than cold.
Every solve of the three checks converges within ITERATIONS_WORST iterations.

Tolerances: SLSQP with ftol 1e-15 is good to ~1e-12 in the cost; the cost is flat at the
optimum (quadratic), so thrusts agree to about the square root of the cost's accuracy. The
firmware stops at a Newton decrement of 1e-12 (double) or 1e-9 (float) of the cost.
"""
import subprocess
import sys

import numpy as np
from scipy.linalg import null_space
from scipy.optimize import lsq_linear, minimize

A = np.array([[-0.5, 0.5, 0.5], [-0.5, -0.5, 0.5], [-0.5, 0.5, -0.5], [-0.5, -0.5, -0.5],
              [0.1, 0.5, 0.0], [0.1, -0.5, 0.0], [0.1, 0.0, 0.5], [0.1, 0.0, -0.5]])
U = np.array([[1, 0, 0], [1, 0, 0], [1, 0, 0], [1, 0, 0],
              [0, 0, 1], [0, 0, 1], [0, 1, 0], [0, 1, 0]], dtype=float)
H = np.vstack([U.T, np.cross(A, U).T])  # 6 × 8: (u_j; a_j × u_j)

# A second layout ("vectored" in the driver): four horizontal thrusters at 45° in the corners,
# four vertical ones; each null direction couples four thrusters.
A_VEC = np.array([[0.16, 0.11, 0.0], [0.16, -0.11, 0.0], [-0.16, 0.11, 0.0], [-0.16, -0.11, 0.0],
                  [0.12, 0.22, 0.05], [0.12, -0.22, 0.05], [-0.12, 0.22, 0.05],
                  [-0.12, -0.22, 0.05]])
U_VEC = np.array([[1, -1, 0], [1, 1, 0], [1, 1, 0], [1, -1, 0],
                  [0, 0, 1], [0, 0, 1], [0, 0, 1], [0, 0, 1]], dtype=float)
U_VEC /= np.linalg.norm(U_VEC, axis=1, keepdims=True)
H_VEC = np.vstack([U_VEC.T, np.cross(A_VEC, U_VEC).T])
# The "weighted" cost Σ w_j·|T_j|^1.5 (thrusters of different propellers, alloc_power.h): the
# driver's kWeight, typed in here; they differ inside each null direction of both layouts.
WEIGHT = np.array([1.0, 1.4, 1.0, 0.7, 0.05 / 0.076, 0.05 / 0.076, 1.2, 1.2])
ONES = np.ones(8)
# layout name: (H, driver arguments, cost weights)
LAYOUTS = {"paper": (H, [], ONES), "vectored": (H_VEC, ["vectored"], ONES),
           "vectored_weighted": (H_VEC, ["vectored", "weighted"], WEIGHT)}

N_CASES, N_CONT, N_WALK = 600, 300, 400
# Iterations of one solve (the firmware caps them at 16): the cold solves of the random cases
# and the walks must stay well inside the cap, and converge.
ITERATIONS_WORST = 10
FRACTIONS = (0.0, 0.8, 0.5, 0.3)  # T_max / max|P_unlimited|; 0: no limit


def run_driver(driver, cases, warm=False, layout="paper"):
    """cases: list of (mask, limit_N, w[6]); returns (status, iters, converged, d, P, T) rows."""
    text = "".join(f"{m} {float(lim)!r} " + " ".join(repr(float(x)) for x in w) + "\n"
                   for m, lim, w in cases)
    args = [driver] + (["warm"] if warm else []) + LAYOUTS[layout][1]
    out = subprocess.run(args, input=text, capture_output=True, text=True, check=True).stdout
    rows = [line.split() for line in out.splitlines()]
    assert len(rows) == len(cases), f"driver answered {len(rows)} of {len(cases)} cases"
    return [(int(r[0]), int(r[1]), int(r[2]), int(r[3]), np.array(r[4:12], float),
             np.array(r[12:20], float)) for r in rows]


def cost(T, wt=ONES):
    a = np.abs(T)
    return float(np.sum(wt * a * np.sqrt(a)))


def random_mask(rng, c):
    mask = 0xFF
    for j in rng.choice(8, size=c % 3, replace=False):
        mask &= ~(1 << int(j))
    return mask


def random_wrench(rng):
    return np.concatenate([20.0 * rng.standard_normal(3), 10.0 * rng.standard_normal(3)])


def scipy_optimum(mask, P, limit, Hm=H, wt=ONES):
    """SLSQP over the null space of the usable columns of H (scipy's SVD basis), from P, for
    the cost Σ wt_j·|T_j|^1.5."""
    usable = [j for j in range(8) if mask >> j & 1]
    Pu, wu = P[usable], wt[usable]
    N = null_space(Hm[:, usable])
    T = np.zeros(8)
    if N.shape[1] == 0 or not np.any(Pu):
        T[usable] = Pu
        return T

    def f(z):
        t = Pu + N @ z
        a = np.abs(t)
        return np.sum(wu * a * np.sqrt(a)), N.T @ (1.5 * wu * np.sign(t) * np.sqrt(a))

    cons = []
    if limit is not None:
        cons = [{"type": "ineq", "fun": lambda z: limit - (Pu + N @ z), "jac": lambda z: -N},
                {"type": "ineq", "fun": lambda z: limit + (Pu + N @ z), "jac": lambda z: N}]
    res = minimize(f, np.zeros(N.shape[1]), jac=True, method="SLSQP", constraints=cons,
                   options=dict(ftol=1e-15, maxiter=1000))
    # 8: no further progress; 9: the iteration limit (a float build's rounded P can keep SLSQP
    # from meeting ftol): its iterate still bounds the cost from above, and the thrusts are
    # compared only where it reached a KKT point (check_optimum).
    assert res.success or res.status in (8, 9), f"SLSQP: {res.message}"
    T[usable] = Pu + N @ res.x
    return T


def kkt_residual(mask, T, limit, Hm=H, wt=ONES):
    """Relative KKT residual of T (independent of how it was found): the least
    ‖g + H_uᵀ·λ + Σ_{j on a bound} μ_j·sign(T_j)·e_j‖ / ‖g‖ over λ free and μ ≥ 0, with
    g = ∇Σ wt_j·|T_j|^1.5 = 1.5·wt·sign(T)·√|T| over the usable thrusters (scipy's lsq_linear)."""
    usable = [j for j in range(8) if mask >> j & 1]
    t = T[usable]
    g = 1.5 * wt[usable] * np.sign(t) * np.sqrt(np.abs(t))
    if not np.any(g):
        return 0.0
    on = [k for k in range(len(t)) if limit is not None and abs(t[k]) >= limit * (1 - 1e-9)]
    B = np.hstack([Hm[:, usable].T] + [np.sign(t[k]) * np.eye(len(t))[:, [k]] for k in on])
    lb = np.r_[np.full(6, -np.inf), np.zeros(len(on))]
    res = lsq_linear(B, -g, bounds=(lb, np.full(B.shape[1], np.inf)), tol=1e-14,
                     lsmr_tol="auto", method="bvls")
    return np.linalg.norm(B @ res.x + g) / np.linalg.norm(g)


def limits_for(driver, real, cases, layout="paper"):
    """Pass 1, unlimited, gives the scale of each case's limit (frac · max|P|)."""
    first = run_driver(driver, [(m, 0.0, w) for m, w, _ in cases], layout=layout)
    out = []
    for (m, w, frac), row in zip(cases, first):
        pmax = np.abs(row[4]).max()
        limit = frac * pmax if frac > 0 and pmax > 0 else 0.0
        # The limit as the firmware holds it (a float build rounds it).
        out.append(float(np.float32(limit)) if real == "float" else limit)
    return out


def check_optimum(driver, real, rng, failures, layout="paper", n_cases=N_CASES):
    tol_cost, tol_t, tol_kkt = (2e-6, 3e-3, 1e-3) if real == "float" else (1e-9, 1e-4, 1e-5)
    cases = []
    Hm, wt = LAYOUTS[layout][0], LAYOUTS[layout][2]
    for c in range(n_cases):
        w = np.zeros(6) if c % 50 == 0 else random_wrench(rng)
        cases.append((random_mask(rng, c), w, FRACTIONS[(c // 3) % len(FRACTIONS)]))
    limits = limits_for(driver, real, cases, layout)
    rows = run_driver(driver, [(m, lim, w) for (m, w, _), lim in zip(cases, limits)],
                      layout=layout)
    worst_cost, worst_t, worst_kkt, compared = -np.inf, 0.0, 0.0, 0
    savings, free_savings, iters, saturated, notconv = [], [], [], 0, 0
    for c, ((mask, w, _), limit, (st, it, conv, d, P, T)) in enumerate(zip(cases, limits, rows)):
        def fail(what):
            failures.append(f"{layout} optimum case {c} mask 0x{mask:02x} limit {limit:.6g}: {what}")
        if st != 0:
            fail(f"status {st}")
            continue
        lim = limit if limit > 0 else None
        unusable = [j for j in range(8) if not mask >> j & 1]
        if any(T[j] != 0.0 for j in unusable):
            fail(f"unusable thruster driven: {T}")
        if lim is not None and np.abs(T).max() > limit:
            fail(f"|T| {np.abs(T).max()} above the limit")
        cp, ct = cost(P, wt), cost(T, wt)
        if ct > cp * (1 + 1e-6):
            fail(f"cost {ct} above the pseudoinverse's {cp}")
        w_star = Hm @ P
        scale = max(np.abs(w_star).max(), np.abs(T).max(), 1e-300)
        if np.abs(Hm @ T - w_star).max() / scale > (1e-5 if real == "float" else 1e-12):
            fail(f"wrench changed by {np.abs(Hm @ T - w_star).max():.3g}")
        ref = scipy_optimum(mask, P, lim, Hm, wt)
        if cp == 0:
            if np.any(T != 0):
                fail("P = 0 must give T = 0")
            continue
        # (a) T satisfies the KKT conditions: an optimality certificate that does not depend
        # on any solver. (b) Its cost is not above SLSQP's. (c) Where SLSQP itself reached a
        # KKT point, the thrusts are SLSQP's (the optimum is unique).
        kkt, kkt_ref = kkt_residual(mask, T, lim, Hm, wt), kkt_residual(mask, ref, lim, Hm, wt)
        worst_kkt = max(worst_kkt, kkt)
        if kkt > tol_kkt:
            fail(f"KKT residual {kkt:.3g}")
        e_cost = (ct - cost(ref, wt)) / cp
        worst_cost = max(worst_cost, e_cost)
        if e_cost > tol_cost:
            fail(f"cost {ct!r} above SLSQP's {cost(ref, wt)!r} (relative {e_cost:.3g})")
        if kkt_ref <= 1e-7:
            compared += 1
            e_t = np.abs(T - ref).max() / np.abs(P).max()
            worst_t = max(worst_t, e_t)
            if e_t > tol_t:
                fail(f"thrusts differ from SLSQP's by {e_t:.3g} of max|P|")
        savings.append(1.0 - ct / cp)
        if limit == 0:
            free_savings.append(1.0 - ct / cp)
        iters.append(it)
        notconv += conv == 0
        saturated += limit > 0 and np.abs(P).max() >= limit * (1 - 1e-6)
    print(f"min_power ({real}, {layout} layout) vs scipy: {len(rows)} cases ({saturated} at the thrust limit, "
          f"{notconv} not converged); KKT residual worst {worst_kkt:.2g}; cost − SLSQP's, "
          f"relative to cost(P), largest {worst_cost:.2g}; thrusts vs SLSQP's where SLSQP "
          f"reached a KKT point ({compared} cases) worst {worst_t:.2g} of max|P|; Σ|T|^1.5 "
          f"saving vs pseudoinverse median {100 * np.median(savings):.2f} %, largest "
          f"{100 * np.max(savings):.2f} % (without a limit: median "
          f"{100 * np.median(free_savings):.2f} %); iterations (cold) median {np.median(iters):.0f}, "
          f"worst {np.max(iters)}")
    if saturated < 100:
        failures.append(f"only {saturated} saturated cases")
    if notconv:
        failures.append(f"{notconv} cases not converged")
    if iters and max(iters) > ITERATIONS_WORST:
        failures.append(f"{max(iters)} iterations (cold) in a case")


def check_continuity(driver, real, rng, failures, layout="paper"):
    step = 1e-2 if real == "float" else 1e-3
    base = [(random_mask(rng, c), random_wrench(rng), FRACTIONS[(c // 3) % len(FRACTIONS)])
            for c in range(N_CONT)]
    Hm = LAYOUTS[layout][0]
    limits = limits_for(driver, real, base, layout)
    moved = []
    for mask, w, _ in base:
        dw = rng.standard_normal(6)
        moved.append(w + step * np.linalg.norm(w) * dw / np.linalg.norm(dw))
    a = run_driver(driver, [(m, lim, w) for (m, w, _), lim in zip(base, limits)], layout=layout)
    b = run_driver(driver, [(m, lim, w2) for (m, _, _), lim, w2 in zip(base, limits, moved)],
                   layout=layout)
    worst = 0.0
    for c, ((mask, w, _), w2, ra, rb) in enumerate(zip(base, moved, a, b)):
        usable = [j for j in range(8) if mask >> j & 1]
        bound = 10.0 * np.linalg.norm(np.linalg.pinv(Hm[:, usable]), 2)
        ratio = np.linalg.norm(rb[5] - ra[5]) / np.linalg.norm(w2 - w)
        worst = max(worst, ratio / bound * 10.0)
        if ra[0] != 0 or rb[0] != 0 or ratio > bound:
            failures.append(f"{layout} continuity case {c} mask 0x{mask:02x}: status {ra[0]}/{rb[0]}, "
                            f"‖ΔT‖/‖Δw‖ {ratio:.3g} > {bound:.3g}")
    print(f"continuity ({real}, {layout} layout): {N_CONT} random steps of {step:g}·|w|: largest ‖ΔT‖/‖Δw‖ "
          f"is {worst:.3g}·‖H_u⁺‖₂ (bound 10)")


def check_warm_start(driver, real, rng, failures):
    """Two walks of a slowly varying wrench, warm against cold: all thrusters and no limit;
    then a thrust limit at half the walk's largest unlimited thrust (bounds become active and
    the warm start must be shrunk into the new bounds) with thruster 4 lost half way (the
    basis changes: the warm start must restart cold)."""
    tol_t = 3e-3 if real == "float" else 1e-6
    w = random_wrench(rng)
    rate = np.zeros(6)
    path = []
    for _ in range(N_WALK):
        rate = 0.95 * rate + 0.05 * random_wrench(rng)
        w = w + 0.03 * rate
        path.append(w.copy())
    free = [(0xFF, 0.0, x) for x in path]
    pmax = max(np.abs(r[4]).max() for r in run_driver(driver, free))
    limit = float(np.float32(0.5 * pmax)) if real == "float" else 0.5 * pmax
    limited = [(0xFF if k < N_WALK // 2 else 0xEF, limit, x) for k, x in enumerate(path)]
    for name, walk in (("free", free), ("limited, thruster 4 lost half way", limited)):
        cold = run_driver(driver, walk)
        warm = run_driver(driver, walk, warm=True)
        worst, at_bound = 0.0, 0
        for k, (rc, rw) in enumerate(zip(cold, warm)):
            e = np.abs(rc[5] - rw[5]).max() / max(np.abs(rc[4]).max(), 1e-300)
            worst = max(worst, e)
            at_bound += walk[k][1] > 0 and np.abs(rw[5]).max() >= walk[k][1] * (1 - 1e-6)
            if rc[0] != 0 or rw[0] != 0 or e > tol_t or not rc[2] or not rw[2]:
                failures.append(f"warm start ({name}) step {k}: status {rc[0]}/{rw[0]}, "
                                f"converged {rc[2]}/{rw[2]}, differs by {e:.3g}")
        ic, iw = [r[1] for r in cold], [r[1] for r in warm]
        print(f"warm start ({real}, {name}): {N_WALK} steps of a slowly varying wrench "
              f"({at_bound} with a thrust on its bound): thrusts equal to the cold solves within "
              f"{worst:.2g} of max|P|; iterations cold median {np.median(ic):.0f} (worst "
              f"{max(ic)}), warm median {np.median(iw):.0f} (worst {max(iw)})")
        if np.median(iw) > np.median(ic):
            failures.append(f"warm start ({name}) needs more iterations than cold")
        if max(ic + iw) > ITERATIONS_WORST:
            failures.append(f"warm start ({name}): {max(ic + iw)} iterations")
    if limited and not any(r[1] for r in run_driver(driver, limited[:1])):
        failures.append("the limited walk did not run")


def main():
    if len(sys.argv) > 1 and sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    driver, real = sys.argv[1], sys.argv[2]
    rng = np.random.default_rng(20261205)
    failures = []
    check_optimum(driver, real, rng, failures)
    check_continuity(driver, real, rng, failures)
    check_warm_start(driver, real, rng, failures)
    check_optimum(driver, real, rng, failures, "vectored", 300)
    check_continuity(driver, real, rng, failures, "vectored")
    check_optimum(driver, real, rng, failures, "vectored_weighted", 300)
    for f in failures[:20]:
        print("FAIL", f)
    print(f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
