# SPDX-License-Identifier: Apache-2.0
"""flow: what the unsteady rows of the scorecard depend on. The paper prints neither the flow
amplitude A_v nor the number of harmonics n (docs/MODEL.md §6.1 takes 0.01 m/s and 5); the
campaigns exp1_flow_amplitude and exp1_flow_harmonics sweep A_v (at n = 5) and n (at
A_v = 0.01 m/s) for cases IV and VII (both readings) in Table XII's condition, over the same 20
seeds. For those rows the verdict is re-decided at every swept value of each parameter, and
the row names the values where it holds (analyses.verdicts.verdict_range); other unsteady rows
are flagged as depending on A_v and n without a sweep."""
import math

from ..analyses import inference, stats, verdicts
from ..analyses.paper import PAPER_TABLE_XI, PAPER_TABLE_XII
from ..keys import E_P, ERR, KEY_CASE, KEY_DENSITY, KEY_UNSTEADY, VEH

EXP = "exp1_flow_amplitude"
EXP_N = "exp1_flow_harmonics"
KEY_AV = "environment.unsteady_flow.amplitude_m_s"
KEY_N = "environment.unsteady_flow.harmonics"
KEY_THETA = "trajectory.theta_final_deg"
VARIANTS = {"IV": {KEY_CASE: "IV", KEY_THETA: "auto"},
            "VII_task": {KEY_CASE: "VII", KEY_THETA: "auto"},
            "VII_motion": {KEY_CASE: "VII", KEY_THETA: "vehicle"}}
MECHANISM_NOTE = ("where the flow's energy goes: *Unsteady flow, calibrated and explained* "
                  "(E_p split per seed)")
EMPTY = {"eps": [], "energy": [], "ratio": []}


class Sweep:
    """One swept flow parameter (key, its name in notes) of cases IV and VII, paired by seed.
    The amplitude sweep carries the harmonics sweep as .harmonics (None without it)."""

    def __init__(self, e, key=KEY_AV, name="A_v [m/s]"):
        self.e = e
        self.key = key
        self.name = name
        self.amps = [float(a) for a in e.values(key)]
        self.harmonics = None

    def series(self, metric, variant, amp):
        return self.e.series(metric, dict(VARIANTS[variant], **{self.key: amp}))

    def ratio(self, variant, amp, metric=E_P):
        return inference.ratio_or_none(self.series(metric, variant, amp),
                                       self.series(metric, "IV", amp))


def load(rep):
    e = rep.exp(EXP)
    if e is None or not e.runs:
        return None
    sw = Sweep(e)
    en = rep.exp(EXP_N)
    if en is not None and en.runs:
        sw.harmonics = Sweep(en, KEY_N, "n")
    return sw


def _variant(case, reading):
    if case == VEH:
        return "IV"
    if case == "VII":
        return "VII_task" if reading == "same task" else "VII_motion"
    return None


def _entry(sweep, vr, what):
    note = verdicts.sensitivity_note(sweep.name, vr)
    short = sweep.name.split(" ")[0]
    return {"parameter": sweep.key, "printed": False, "swept": sorted(vr.holds + vr.fails),
            "holds_for": vr.holds,
            "note": (f"{what}: " + (note or f"reproduced at every swept {short}"))
            if vr.holds or vr.fails else f"{what}: {short} not swept"}


def _unswept(what):
    return {"parameter": KEY_AV, "printed": False, "swept": [], "holds_for": [],
            "note": f"{what} depends on A_v and n, which the paper does not print "
                    f"(docs/MODEL.md §6.1: 0.01 m/s, 5 harmonics); not swept for this row"}


def _depends_one(sweep, var, case):
    """The dependences of one row on one swept parameter."""
    p_err, p_e = PAPER_TABLE_XII[case]
    out = {}
    vr = verdicts.verdict_range(lambda d: verdicts.magnitude_verdict(p_err, d),
                                {a: stats.describe([1e3 * v for v in
                                                    sweep.series(ERR, var, a).values()])
                                 for a in sweep.amps})
    out["eps"] = _entry(sweep, vr, "ε")
    vr = verdicts.verdict_range(lambda d: verdicts.magnitude_verdict(p_e, d),
                                {a: stats.describe(list(sweep.series(E_P, var, a).values()))
                                 for a in sweep.amps})
    out["energy"] = _entry(sweep, vr, "E_p")
    if var != "IV":
        p_r = p_e / PAPER_TABLE_XII[VEH][1]
        vr = verdicts.verdict_range(lambda d: verdicts.directional_verdict(p_r, d, ref=1.0),
                                    {a: sweep.ratio(var, a) for a in sweep.amps})
        out["ratio"] = _entry(sweep, vr, "E_p/E_p(IV)")
    return out


def depends(sweep, unsteady, case, reading):
    """{"eps", "energy", "ratio"}: lists of parameter dependences of a row, one per swept
    parameter (A_v, then n; empty for the stagnant condition)."""
    if not unsteady:
        return EMPTY
    var = _variant(case, reading)
    if sweep is None or var is None:
        return {k: [_unswept(k if k != "eps" else "ε")] for k in EMPTY}
    out = {k: [] for k in EMPTY}
    for sw in (sweep, sweep.harmonics):
        if sw is None:
            continue
        for k, ent in _depends_one(sw, var, case).items():
            out[k].append(ent)
    return out


def note(dep):
    """The dependences of a row as one clause ('' if none)."""
    return "; ".join(d["note"] for d in dep)


def calibrate(sweep, target_mm=PAPER_TABLE_XII[VEH][0]):
    """A_v at which case IV's mean ε over seeds equals Table XII's 3.32 mm: log-log linear
    interpolation between the two swept amplitudes that bracket it (NaN outside the sweep).
    Returns (A_v [m/s], [(A_v, mean ε [mm])])."""
    pts = []
    for a in sorted(sweep.amps):
        d = stats.describe([1e3 * v for v in sweep.series(ERR, "IV", a).values()])
        if d.n:
            pts.append((a, d.mean))
    for (a0, e0), (a1, e1) in zip(pts, pts[1:]):
        if (e0 - target_mm) * (e1 - target_mm) <= 0 and e0 > 0 and e1 > 0 and e0 != e1:
            t = (math.log(target_mm) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(a0) + t * (math.log(a1) - math.log(a0))), pts
    return math.nan, pts


# -- where the flow's energy goes (per seed, from summary.json's E_p split)
PARTS = (("feedforward", "propulsive_energy_ff_J"), ("feedback", "propulsive_energy_fb_J"),
         ("position thrust", "propulsive_energy_pos_J"),
         ("attitude thrust", "propulsive_energy_att_J"),
         ("x thrusters", "propulsive_energy_group_x_J"),
         ("y thrusters", "propulsive_energy_group_y_J"),
         ("z thrusters", "propulsive_energy_group_z_J"))
TASK_EXP = "exp1_cases"
MOTION_EXP = "exp1_cases_same_motion"


def _mean(series):
    v = list(series.values())
    return sum(v) / len(v) if v else math.nan


def stagnant(rep, variant, metric):
    """The metric of a variant's stagnant run without flow (experiment 1, condition a): the
    reference the flow's increment is measured from."""
    e = rep.exp(MOTION_EXP if variant == "VII_motion" else TASK_EXP)
    if e is None:
        return math.nan
    cond = {KEY_UNSTEADY: False, KEY_DENSITY: False, KEY_CASE: VARIANTS[variant][KEY_CASE]}
    return _mean(e.series(metric, cond))


def increments(rep, sweep, amp):
    """{variant: {part: (flow's increment of the part's mean [J], its mean at amp [J])}} with
    part "E_p" and PARTS; the increment is mean(unsteady at amp) − stagnant."""
    out = {}
    for var in VARIANTS:
        d = {}
        for name, metric in (("E_p", E_P),) + PARTS:
            m = _mean(sweep.series(metric, var, amp))
            d[name] = (m - stagnant(rep, var, metric), m)
        out[var] = d
    return out


def _paper_added(case):
    """The energy the paper's unsteady condition adds to a case: Table XII − Table XI [J]."""
    return PAPER_TABLE_XII[case][1] - PAPER_TABLE_XI[case][1]


def mechanism(rep, sweep, amp=0.01):
    """One measured sentence: how much E_p the flow adds to IV and VII (same motion) at amp, and
    through which part (feedback/feedforward, attitude/position)."""
    if sweep is None or amp not in sweep.amps:
        return MECHANISM_NOTE
    inc = increments(rep, sweep, amp)
    iv, vm = inc["IV"], inc["VII_motion"]
    if not all(math.isfinite(x[n][0]) for x in (iv, vm) for n in ("E_p", "feedback",
                                                                     "attitude thrust")):
        return MECHANISM_NOTE
    def share(d, part):
        return 100.0 * d[part][0] / d["E_p"][0] if d["E_p"][0] else math.nan
    same = abs(iv["E_p"][0] - vm["E_p"][0]) <= 0.1 * abs(iv["E_p"][0])
    return (f"measured at A_v = {amp:g} m/s (means of 20 seeds, against the stagnant run): the "
            f"flow adds {iv['E_p'][0]:.3f} J of E_p to IV and {vm['E_p'][0]:.3f} J to VII with "
            f"the same motion ({inc['VII_task']['E_p'][0]:.3f} J with the same task), where the "
            f"paper's tables add {_paper_added(VEH):.3f} J and {_paper_added('VII'):.3f} J "
            f"(Table XII − XI); feedback carries "
            f"{share(iv, 'feedback'):.0f} % (IV) and {share(vm, 'feedback'):.0f} % (VII) of the "
            f"increment, the position thrust {share(iv, 'position thrust'):.0f} % and "
            f"{share(vm, 'position thrust'):.0f} %"
            + ("; so the flow is rejected by the position loop at the same cost under either "
               "reference, and holding the barycenter saves only the arm reaction's share. "
               "Why the paper's flow costs VII less is an untested hypothesis: its barycenter "
               "loop may reject less of the flow (a reference or gains the paper does not print)"
               if same else ""))
