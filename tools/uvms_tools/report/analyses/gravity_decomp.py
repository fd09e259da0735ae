# SPDX-License-Identifier: Apache-2.0
"""gravity_decomp: the gravity campaign's VII/IV ratio split into its two factors, per gravity
and payload, paired per seed (the same flow in every run of a seed):
  E(VII, same task)/E(IV) = [E(VII, same motion)/E(IV)] × [E(VII, same task)/E(VII, same motion)]
            total         =        strategy effect        ×            pose effect
The strategy effect holds the arm's motion fixed and changes only the point held; the pose
effect holds the point fixed and changes only the final pose (docs/MODEL.md §8's readings).
Sources: beyond_gravity (IV and VII, same task) and beyond_gravity_same_motion (VII, same
motion), pseudoinverse allocation."""
from . import inference
from ..keys import (ALLOC_PINV, BARY, KEY_ALLOC, KEY_CASE, KEY_GRAVITY, KEY_PAYLOAD, VEH)

TASK, MOTION = "beyond_gravity", "beyond_gravity_same_motion"


def _ratio(num, den):
    try:
        return inference.ratio_log_t(num, den)
    except ValueError:
        return None


def decompose(rep, metric):
    """{(gravity, payload): {"total", "strategy", "pose": Estimate}} over the payloads both
    campaigns ran; {} when either is missing."""
    et, em = rep.exp(TASK), rep.exp(MOTION)
    if et is None or em is None or not em.runs:
        return {}
    out = {}
    for g in em.values(KEY_GRAVITY):
        for p in em.values(KEY_PAYLOAD):
            base = {KEY_GRAVITY: g, KEY_PAYLOAD: p, KEY_ALLOC: ALLOC_PINV}
            iv = et.series(metric, dict(base, **{KEY_CASE: VEH}))
            vt = et.series(metric, dict(base, **{KEY_CASE: BARY}))
            vm = em.series(metric, {KEY_GRAVITY: g, KEY_PAYLOAD: p})
            if iv and vt and vm:
                out[(g, p)] = {"total": _ratio(vt, iv), "strategy": _ratio(vm, iv),
                               "pose": _ratio(vt, vm), "iv": iv, "vm": vm}
    return out


def strategy_change(dec, g_from, g_to, payload):
    """Does the strategy effect change between two gravities? The paired per-seed difference of
    log E(VII, motion)/E(IV) (inference.log_ratio_change; a test of the difference)."""
    a, b = dec.get((g_to, payload)), dec.get((g_from, payload))
    if a is None or b is None:
        return None
    ra = {s: a["vm"][s] / a["iv"][s] for s in a["iv"] if s in a["vm"]}
    rb = {s: b["vm"][s] / b["iv"][s] for s in b["iv"] if s in b["vm"]}
    try:
        return inference.log_ratio_change(ra, rb)
    except ValueError:
        return None
