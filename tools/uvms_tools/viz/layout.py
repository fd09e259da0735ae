# SPDX-License-Identifier: Apache-2.0
"""layout: what a picture of a run draws where, shared by the Rerun recording (rerun_export.py)
and the matplotlib still of its final frame (still.py), so that both show the same thing:

  - the thrust arrows' scale, chosen per run so that the arrows are visible for most of it:
    the 1-2-5 step that draws the 90th percentile (over the ticks) of the largest |thrust| as
    THRUST_ARROW_TYPICAL_M; an arrow longer than THRUST_ARROW_CAP_M is drawn at that length,
    flagged as capped (a transient, say, that would otherwise set a scale under which the rest of
    the run is invisible);
  - the flow arrow's scale (the largest |flow| as FLOW_ARROW_MAX_M);
  - the arm's mount: a strut from the nearest point of the hull box to the arm base p_0 (the
    base offset s0 lies outside the paper's hull box: without it the arm floats beside the
    hull);
  - thrust arrows in the inertial frame (origin at the thruster, along u_j, length T_j times
    the scale, capped).
"""
import math

import numpy as np

from .kinematics import quat_to_rot

THRUST_ARROW_TYPICAL_M = 0.3   # length of the typical (90th percentile) largest thrust [m]
THRUST_ARROW_CAP_M = 0.8       # longest thrust arrow drawn [m]; longer ones are capped
FLOW_ARROW_MAX_M = 1.0         # longest flow arrow [m]
ARROW_RADIUS_M = 0.012         # drawn shaft radius of the arrows [m]


def nice_scale(max_value, target):
    """The largest 1-2-5 step <= target / max_value (1 when max_value is 0 or not finite)."""
    if not np.isfinite(max_value) or max_value <= 0:
        return 1.0
    raw = target / max_value
    decade = 10.0 ** math.floor(math.log10(raw))
    return max(s * decade for s in (1, 2, 5) if s * decade <= raw * (1 + 1e-12))


class Scales:
    """Arrow scales of a run: thrust [m/N] (from the 90th percentile of each tick's largest
    |thrust|), flow [m per m/s] (from the largest |flow|)."""

    def __init__(self, scene):
        tr = scene.truth
        n_t = len(scene.thrusters.position_m)
        per_tick = np.abs(np.asarray(tr["thrust_N"], dtype=float)[:, :n_t]).max(axis=1,
                                                                               initial=0.0)
        per_tick = per_tick[np.isfinite(per_tick)]
        self.thrust_typical_N = float(np.percentile(per_tick, 90)) if per_tick.size else 0.0
        self.thrust_max_N = float(per_tick.max(initial=0.0))
        if not self.thrust_typical_N > 0.0:  # idle for most ticks: scale by the largest
            self.thrust_typical_N = self.thrust_max_N
        self.thrust_m_per_N = nice_scale(self.thrust_typical_N, THRUST_ARROW_TYPICAL_M)
        flow = np.linalg.norm(tr["flow_velocity_m_s"], axis=1).max(initial=0.0)
        self.flow_m_per_m_s = nice_scale(flow, FLOW_ARROW_MAX_M)

    def capped_share(self, scene):
        """The share of (tick, thruster) arrows drawn capped."""
        n_t = len(scene.thrusters.position_m)
        t = np.abs(np.asarray(scene.truth["thrust_N"], dtype=float)[:, :n_t])
        return float((t * self.thrust_m_per_N > THRUST_ARROW_CAP_M).mean()) if t.size else 0.0


def thrust_arrows(scene, scales, rows=None):
    """(origins (n, n_t, 3), vectors (n, n_t, 3), capped (n, n_t) bool) of the thrust arrows at
    the truth samples `rows` (default: all), inertial [m]."""
    tr, th = scene.truth, scene.thrusters
    sel = slice(None) if rows is None else rows
    n_t = len(th.position_m)
    r0 = quat_to_rot(np.atleast_2d(tr["quaternion_wxyz"][sel]))
    pos = np.atleast_2d(tr["position_m"][sel])
    origins = pos[:, None, :] + np.einsum("nab,jb->nja", r0, th.position_m)
    length_m = np.atleast_2d(tr["thrust_N"][sel])[:, :n_t] * scales.thrust_m_per_N
    capped = np.abs(length_m) > THRUST_ARROW_CAP_M
    length_m = np.clip(length_m, -THRUST_ARROW_CAP_M, THRUST_ARROW_CAP_M)
    vectors = np.einsum("nab,jb->nja", r0, th.direction) * length_m[..., None]
    return origins, vectors, capped


def mount_strut(scene):
    """(from, to) in the vehicle frame [m] of the arm's mount: the hull box's nearest point to
    the base offset s0, and s0; None without a hull or when s0 is inside it."""
    if scene.hull_size_m is None:
        return None
    base = np.asarray(scene.geometry.base_offset_m, dtype=float)
    lo = scene.hull_center_m - scene.hull_size_m / 2
    hi = scene.hull_center_m + scene.hull_size_m / 2
    near = np.clip(base, lo, hi)
    return None if np.allclose(near, base) else (near, base)


def mount_inertial(scene, rows=None):
    """(from (n, 3), to (n, 3)) of the mount strut in the inertial frame at the truth samples
    `rows`, or None (mount_strut)."""
    strut = mount_strut(scene)
    if strut is None:
        return None
    tr = scene.truth
    sel = slice(None) if rows is None else rows
    r0 = quat_to_rot(np.atleast_2d(tr["quaternion_wxyz"][sel]))
    pos = np.atleast_2d(tr["position_m"][sel])
    return pos + r0 @ strut[0], pos + r0 @ strut[1]


# The 12 edges of a box by corner index (corner bits: x, y, z = bit 0, 1, 2; box_corners).
BOX_EDGES = [(a, b) for a in range(8) for b in range(8) if a < b and bin(a ^ b).count("1") == 1]


def box_corners(size_m, center_m, r0_m, rot):
    """(8, 3) inertial corners of a box (edges size_m along the vehicle axes, center center_m
    from the CoM in the vehicle frame) for the vehicle at r0_m with attitude rot."""
    signs = np.array([[(k >> i & 1) - 0.5 for i in range(3)] for k in range(8)])
    local = np.asarray(center_m, float) + signs * np.asarray(size_m, float)
    return np.asarray(r0_m, float) + local @ np.asarray(rot, float).T


def hull_corners(scene, row):
    """(8, 3) corners of the hull box at truth sample `row`, inertial [m]; None without a hull."""
    if scene.hull_size_m is None:
        return None
    tr = scene.truth
    rot = quat_to_rot(np.atleast_2d(tr["quaternion_wxyz"][row]))[0]
    return box_corners(scene.hull_size_m, scene.hull_center_m, tr["position_m"][row], rot)
