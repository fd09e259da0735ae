# SPDX-License-Identifier: Apache-2.0
"""checks: consistency checks on the runs that the modeling choices and the scorecard cite
(the sign convention, the largest voltage, joint tracking, the final EE pose)."""
import numpy as np

from ..analyses import checks
from ..keys import BARY, KEY_CASE, KEY_DENSITY, KEY_PAYLOAD, KEY_UNSTEADY, VEH
from ..load.logs import has, per_tick
from ..load.overrides import condition_key, finished
from ..num import div, isnum
from .fmt import f, g


def representatives(e):
    """One run per condition (the lowest seed) of an experiment, finished ones."""
    seen, out = set(), []
    for r in e.select():
        key = condition_key(r)
        if key not in seen:
            seen.add(key)
            out.append(r)
    return out


def sign_check(rep):
    """'; in the logs of exp3, 100 % of samples with |T| > 1 mN have sign(T) = −sign(ω)'."""
    e = rep.exp("exp3_tracking") or rep.exp("exp1_cases")
    if e is None:
        return ""
    n_ok = n = 0
    for r in e.runs[:4]:
        lg = e.log(r, ["UVMS_TRUTH"]) if e.log(r) is None else e.log(r)
        if not has(lg, "UVMS_TRUTH"):
            continue
        k, m = checks.sign_agreement(lg["UVMS_TRUTH"]["thrust_N"],
                                     lg["UVMS_TRUTH"]["motor_speed_rad_s"])
        n_ok, n = n_ok + k, n + m
    return (f"; in the logs of {e.name}, {f(100 * div(n_ok, n), 2)} % of samples with "
            f"|T| > 1 mN have sign(T) = −sign(ω)" if n else "")


def max_voltage(rep):
    """The largest |V| commanded in experiments 1 and 3 (one run per condition)."""
    vmax = float("nan")
    for name in ("exp1_cases", "exp3_tracking"):
        e = rep.exp(name)
        if e is None:
            continue
        for r in representatives(e):
            lg = e.log(r, ["UVMS_ACTUATORS"])
            if not has(lg, "UVMS_ACTUATORS"):
                continue
            v = float(np.max(np.abs(lg["UVMS_ACTUATORS"]["motor_voltage_V"]), initial=0.0))
            vmax = v if not isnum(vmax) else max(vmax, v)
    return vmax


def joint_tracking(rep):
    """'; largest joint tracking error |θ_ref − θ| over experiment 1: … rad …'."""
    e = rep.exp("exp1_cases")
    if e is None:
        return ""
    worst = 0.0
    for r in representatives(e):
        lg = e.log(r, ["UVMS_TRUTH", "UVMS_TELEMETRY"])
        if not has(lg, "UVMS_TRUTH", "UVMS_TELEMETRY"):
            continue
        tm, tr = per_tick(lg)
        worst = max(worst, checks.max_wrapped_error(tm["joint_ref_rad"], tr["joint_position_rad"]))
    return (f"; largest joint tracking error |θ_ref − θ| over experiment 1: "
            f"{g(worst, 3)} rad (the EE errors measured are millimetres)")


def final_pose_miss(rep):
    """{payload: |p_EE(VII) − p_EE(IV)| at the end [m]} from experiment 2, condition A
    (stagnant, deterministic; summary.json final_ee_position_m): SPEC §8's barycenter
    columns are meant to put the EE at the vehicle column's point."""
    e = rep.exp("exp2_payload")
    out = {}
    if e is None:
        return out
    for p in e.values(KEY_PAYLOAD):
        cond = {KEY_UNSTEADY: False, KEY_DENSITY: False, KEY_PAYLOAD: p}
        rv, rb = e.one(dict(cond, **{KEY_CASE: VEH})), e.one(dict(cond, **{KEY_CASE: BARY}))
        if not (finished(rv) and finished(rb)) or "final_ee_position_m" not in rv \
                or "final_ee_position_m" not in rb:
            continue
        out[p] = checks.distance(rb["final_ee_position_m"], rv["final_ee_position_m"])
    return out
