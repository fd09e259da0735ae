# SPDX-License-Identifier: Apache-2.0
"""gravity_decomp: *Gravity, decomposed*: the gravity campaign's VII/IV ratio as a strategy
effect (same motion) times a pose effect (same task vs same motion), with the change of the
strategy effect from g = 0 to each gravity tested as a paired difference."""
from ..analyses import gravity_decomp as GD
from ..keys import E_EL, E_P
from .beyond_gravity import GRAVITY_NAMES
from .fmt import f, fmt_interval, table


# A ratio whose 95 % CI lies within 1 ± 1 % is reported as equal: a difference below 1 % is
# below what the paper's printed energies resolve between methods.
EQUAL_WITHIN = 0.01


def _verdict(est):
    if est is None:
        return "n/a"
    if not est.has_ci:
        if abs(est.estimate - 1) < EQUAL_WITHIN:
            return f"equal within {100 * EQUAL_WITHIN:g} %"
        return "cheaper" if est.estimate < 1 else "dearer"
    if 1 - EQUAL_WITHIN < est.lo and est.hi < 1 + EQUAL_WITHIN:
        return f"equal within {100 * EQUAL_WITHIN:g} %"
    if est.hi < 1:
        return "cheaper"
    if est.lo > 1:
        return "dearer"
    return "no significant difference"


def headline(rep):
    """One sentence per gravity ≠ 0 at the largest payload: which effect the penalty or saving
    of VII is (for the Europa headline and the answer box); [] without the campaigns."""
    dec = GD.decompose(rep, E_P)
    if not dec:
        return []
    pmax = max(p for _, p in dec)
    out = []
    for g in ("europa", "earth"):
        d = dec.get((g, pmax))
        if d is None:
            continue
        out.append(f"{GRAVITY_NAMES[g]}, {f(pmax, 0)} kg: VII/IV = {fmt_interval(d['total'])}; with the "
                   f"same motion (the strategy effect) {fmt_interval(d['strategy'])}, "
                   f"{_verdict(d['strategy'])}; the barycenter column's pose adds a factor "
                   f"{fmt_interval(d['pose'])} ({_verdict(d['pose'])}): the difference is "
                   + ("a pose effect, not a strategy effect"
                      if abs(d["strategy"].estimate - 1) < abs(d["pose"].estimate - 1)
                      else "mainly the strategy"))
    return out


def section(rep):
    md = ["### Gravity, decomposed: strategy and pose", ""]
    dec = GD.decompose(rep, E_P)
    if not dec:
        return md + ["*beyond_gravity_same_motion not found: the decomposition needs it.*", ""]
    md += ["The gravity campaign compares IV (arm to \"Veh.\") with VII at its payload's "
           "barycenter column (same task), so its ratio mixes two effects. "
           "`beyond_gravity_same_motion` runs VII with the arm driven to \"Veh.\" (same motion) "
           "under the same settings and seeds (pseudoinverse allocation). Per seed, "
           "E(VII, task)/E(IV) = [E(VII, motion)/E(IV)] × [E(VII, task)/E(VII, motion)]: the "
           "*strategy effect* (only the point held differs) times the *pose effect* (only the "
           "final pose differs). Energy E_p (the scorecard's); E_el beside it; geometric-mean "
           "ratios with 95 % CIs, paired per seed on the log scale, 20 seeds.", ""]
    del_el = GD.decompose(rep, E_EL)
    rows = []
    for (g, p), d in sorted(dec.items(), key=lambda kv: (list(GRAVITY_NAMES).index(kv[0][0]),
                                                           kv[0][1])):
        de = del_el.get((g, p), {})
        rows.append([GRAVITY_NAMES[g], f(p, 0), fmt_interval(d["total"]), fmt_interval(d["strategy"]),
                     _verdict(d["strategy"]), fmt_interval(d["pose"]), fmt_interval(de.get("strategy")),
                     fmt_interval(de.get("pose"))])
    md += table(["gravity", "m_P [kg]", "total VII/IV (E_p)", "strategy (same motion)",
                 "strategy verdict", "pose (task/motion)", "strategy, E_el", "pose, E_el"], rows)
    md += ["**Does the strategy effect change with gravity?** Paired per-seed difference of "
           "log E(VII, motion)/E(IV) against g = 0 (a test of the difference, not a comparison "
           "of two verdicts); the factor by which the ratio changes, with its 95 % CI and p:", ""]
    lines = []
    for g in ("europa", "earth"):
        for p in sorted({p for _, p in dec}):
            ch = GD.strategy_change(dec, "paper", g, p)
            if ch is not None:
                x = ch.exp()
                lines.append(f"- {GRAVITY_NAMES[g]}, {f(p, 0)} kg: × {fmt_interval(x)} (p = "
                             f"{ch.p:.2g})")
    md += lines + [""]
    md += [f"- {h}." for h in headline(rep)] + [""]
    return md


T200 = "beyond_gravity_t200"
T200_VARIANTS = (("IV", {"control.case": "IV", "trajectory.theta_final_deg": "auto"}),
                 ("VII, same task", {"control.case": "VII", "trajectory.theta_final_deg": "auto"}),
                 ("VII, same motion", {"control.case": "VII",
                                       "trajectory.theta_final_deg": "vehicle"}))


def t200_section(rep):
    """The gravity question in battery joules: the T200 set's E_el per variant, and the ratios
    to IV paired per seed (campaign beyond_gravity_t200)."""
    from ..analyses import inference, stats
    from ..keys import E_EL, ERR, KEY_GRAVITY
    e = rep.exp(T200)
    md = ["### Gravity in battery joules: the T200 thrusters (`beyond_gravity_t200`)", ""]
    if e is None:
        return md + ["*beyond_gravity_t200 not found.*", ""]
    md += ["The same question with every thruster a Blue Robotics T200 at a 16 V bus "
           "(`thrusters.motor = \"t200\"`, fitted to its published bollard data, docs/MODEL.md "
           "§5): E_el = ∫Σ max(V·I, 0) dt is what the battery gives. 10 kg payload, trimmed, "
           "K_PN = 100, unsteady flow, 20 seeds; ratios paired per seed (log scale, 95 % CI).", ""]
    rows = []
    for g in ("europa", "earth"):
        iv = e.series(E_EL, dict(T200_VARIANTS[0][1], **{KEY_GRAVITY: g}))
        for name, cond in T200_VARIANTS:
            c = dict(cond, **{KEY_GRAVITY: g})
            s = e.series(E_EL, c)
            d = stats.describe(list(s.values()))
            err = stats.describe([1e3 * v for v in e.series(ERR, c).values()])
            r = None if name == "IV" else inference.ratio_log_t(s, iv)
            rows.append([GRAVITY_NAMES[g], name,
                         f"{f(d.mean, 1)} [{f(d.lo, 1)}, {f(d.hi, 1)}]" if d.n else "n/a",
                         f"{f(d.mean / 60.0, 2)}" if d.n else "n/a",
                         "—" if r is None else fmt_interval(r), "—" if r is None else _verdict(r),
                         f(err.mean, 2) if err.n else "n/a"])
    md += table(["gravity", "case", "E_el [J], mean [95 % CI]", "mean battery power [W]",
                 "E_el / E_el(IV)", "verdict", "mean ε [mm]"], rows)
    md += ["The speed and current loops keep the paper's gains (K_A, K_B), which were not tuned "
           "for this motor: compare ε with `beyond_gravity`'s before reading these energies as "
           "the cost of equally good station keeping.", ""]
    return md
