# SPDX-License-Identifier: Apache-2.0
"""poses: the paper's Fig. 7, the stowed pose and the final poses under vehicle (case IV) and
barycenter (case VII) stabilization, drawn from the runs' own logs.

Every point comes from a logged truth sample (UVMS_TRUTH: vehicle CoM position_m, attitude
quaternion_wxyz, joint_position_rad, barycenter_m) through the forward kinematics of
tools/uvms_tools/viz/kinematics.py (docs/MODEL.md §2, standard DH: p_0 = r0 + R0 s0, p_i = p_{i-1} +
a_i x_i + d_i z_{i-1}, EE = p_N); the geometry and the hull box come from the log's UVMS_SCENE
(the plant's truth), else UVMS_CONFIG (then no hull: the vehicle is drawn as its body axes).
pose_points() is the pure function giving what is drawn (tested against the plant's logged
ee_position_m); draw() makes the figure.
"""
import numpy as np
from matplotlib.lines import Line2D
from matplotlib.ticker import MaxNLocator

from uvms_tools.viz.kinematics import arm_frames, quat_to_rot
from uvms_tools.viz.layout import BOX_EDGES, box_corners
from uvms_tools.viz.scene import read_scene

from .common import CASE_COLORS, plt

STOWED_COLOR = "#7f7f7f"
BODY_AXIS_M = 0.3  # length of the drawn vehicle body axes when the log has no hull [m]
def pose_points(scene, k):
    """What Fig. 7 draws for truth sample k of a run (uvms_tools.viz.scene.Scene), inertial [m]:
    vehicle_m (3,) CoM; rot (3, 3) vehicle -> inertial; arm_m (N+1, 3) DH origins p_0 (base)
    .. p_N (EE); ee_m (3,); barycenter_m (3,) (the plant's logged barycenter); hull_m (8, 3)
    box corners or None; t_s the sample's time [s]."""
    tr = scene.truth
    r0, q = tr["position_m"][k], tr["quaternion_wxyz"][k]
    fr = arm_frames(scene.geometry, r0, q, tr["joint_position_rad"][k])
    rot = quat_to_rot(np.atleast_2d(q))[0]
    arm = fr["origins_m"][0]
    hull = (box_corners(scene.hull_size_m, scene.hull_center_m, r0, rot)
            if scene.hull_size_m is not None else None)
    return {"vehicle_m": np.asarray(r0, float), "rot": rot, "arm_m": arm, "ee_m": arm[-1],
            "barycenter_m": np.asarray(tr["barycenter_m"][k], float), "hull_m": hull,
            "t_s": float(tr["t_s"][k])}


def run_poses(log):
    """(stowed pose = first truth sample, final pose = last truth sample, scene notes) of a
    runlog.Log; runlog.LogError when truth or telemetry is missing, GeometryError when the
    geometry is."""
    scene = read_scene(log)
    return pose_points(scene, 0), pose_points(scene, scene.truth.count - 1), scene.notes


def _segments(pose):
    """Line segments of the vehicle: the hull edges, else the body axes from the CoM; and the
    CoM -> arm base line."""
    if pose["hull_m"] is not None:
        segs = [(pose["hull_m"][a], pose["hull_m"][b]) for a, b in BOX_EDGES]
    else:
        segs = [(pose["vehicle_m"], pose["vehicle_m"] + BODY_AXIS_M * pose["rot"][:, i])
                for i in range(3)]
    return segs + [(pose["vehicle_m"], pose["arm_m"][0])]


def _draw_pose(ax, pose, color, dims, stowed=False):
    """One pose on a 3D (dims = (0, 1, 2)) or projected (dims = (0, 1)) axis."""
    ls, lw_arm, alpha = ("--", 2.2, 0.8) if stowed else ("-", 3.4, 1.0)
    for a, b in _segments(pose):
        ax.plot(*[[a[d], b[d]] for d in dims], color=color, lw=0.9, ls=ls, alpha=0.7 * alpha)
    arm = pose["arm_m"]
    ax.plot(*[arm[:, d] for d in dims], color=color, lw=lw_arm, ls=ls, alpha=alpha,
            marker="o", ms=3.2, solid_capstyle="round")
    ax.plot(*[[pose["ee_m"][d]] for d in dims], color=color, marker="*", ms=13, ls="none",
            markeredgecolor="black", markeredgewidth=0.5)
    ax.plot(*[[pose["barycenter_m"][d]] for d in dims], color=color, marker="X", ms=9,
            ls="none", markeredgecolor="black", markeredgewidth=0.5)
    ax.plot(*[[pose["vehicle_m"][d]] for d in dims], color=color, marker="s", ms=6, ls="none")


def _all_points(poses):
    pts = []
    for p in poses:
        pts += [p["arm_m"], p["vehicle_m"][None], p["barycenter_m"][None]]
        pts += [p["hull_m"]] if p["hull_m"] is not None else \
            [p["vehicle_m"] + BODY_AXIS_M * p["rot"].T]
    return np.vstack(pts)


def _equal_3d(ax, pts, margin_m=0.1):
    """Equal scaling on the three axes: a cube around the points."""
    mid = 0.5 * (pts.max(axis=0) + pts.min(axis=0))
    half = 0.5 * (pts.max(axis=0) - pts.min(axis=0)).max() + margin_m
    for setter, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid):
        setter(m - half, m + half)
    ax.set_box_aspect((1, 1, 1), zoom=1.12)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(MaxNLocator(5))


def _legend_handles():
    k = dict(ls="none", color="black", markeredgecolor="black")
    return [Line2D([], [], color=STOWED_COLOR, lw=2.2, ls="--", label="stowed (initial) pose"),
            Line2D([], [], color=CASE_COLORS["IV"], lw=3.4, label="final, IV vehicle stab."),
            Line2D([], [], color=CASE_COLORS["VII"], lw=3.4, label="final, VII barycenter stab."),
            Line2D([], [], marker="*", ms=12, mfc="white", **k, label="end-effector"),
            Line2D([], [], marker="X", ms=9, mfc="white", **k, label="barycenter"),
            Line2D([], [], marker="s", ms=6, mfc="white", **k, label="vehicle CoM"),
            Line2D([], [], color="black", lw=0.9, label="hull box / body axes")]


def _row(fig, gs_row, title, stowed, finals):
    """A 3D view and a top view (x, y) of one condition. finals: [(case, pose)]."""
    ax3 = fig.add_subplot(gs_row[0], projection="3d")
    ax2 = fig.add_subplot(gs_row[1])
    for ax, dims in ((ax3, (0, 1, 2)), (ax2, (0, 1))):
        _draw_pose(ax, stowed, STOWED_COLOR, dims, stowed=True)
        for case, pose in finals:
            _draw_pose(ax, pose, CASE_COLORS.get(case, "black"), dims)
    _equal_3d(ax3, _all_points([stowed] + [p for _, p in finals]))
    ax3.set_xlabel("x [m]")
    ax3.set_ylabel("y [m]")
    ax3.set_zlabel("z [m]")
    ax3.view_init(elev=22, azim=-58)
    ax3.set_title(f"{title}: 3D view")
    ax2.set_aspect("equal", adjustable="datalim")
    ax2.set_xlabel("x [m]")
    ax2.set_ylabel("y [m]")
    ax2.set_title(f"{title}: top view (x, y)")


def draw(figs, rows, name="exp1_poses.png"):
    """rows: [(title, stowed pose, [(case, final pose)])], one per condition. Returns the
    figure's report path (figures/<name>)."""
    fig = plt.figure(figsize=(14, 6.0 * len(rows) + 2.0))
    gs = fig.add_gridspec(len(rows), 2, width_ratios=[1.25, 1.0], wspace=0.08, hspace=0.22,
                          left=0.02, right=0.98, top=1 - 0.75 / fig.get_figheight(),
                          bottom=1.35 / fig.get_figheight())
    for i, (title, stowed, finals) in enumerate(rows):
        _row(fig, [gs[i, 0], gs[i, 1]], title, stowed, finals)
    fig.legend(handles=_legend_handles(), loc="lower center", ncol=4, frameon=False,
               bbox_to_anchor=(0.5, 0.0))
    fig.suptitle("Fig. 7: stowed pose and final poses, vehicle (IV) vs barycenter (VII) "
                 "stabilization (inertial frame, docs/MODEL.md §2)", y=1.0)
    return figs.save(fig, name)
