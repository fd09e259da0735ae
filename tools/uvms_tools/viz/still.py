# SPDX-License-Identifier: Apache-2.0
"""still: a matplotlib picture of a run's final frame, drawn from the same kinematics and layout
as its Rerun recording (kinematics.arm_frames, layout.py): hull box, mount strut and arm links,
payload, true EE, barycenter, thrust arrows (capped ones red) and the flow arrow, obstacles.
The report shows one beside each recording (report/text/recordings.py), so a reader sees what
the replay shows without a 3D viewer. Names go in the legend, not as labels beside the points,
so none overlap."""
import numpy as np

from .kinematics import arm_frames
from .layout import BOX_EDGES, Scales, hull_corners, mount_inertial, thrust_arrows
COLORS = {"hull": "0.45", "arm": "0.3", "thrust": "tab:orange", "capped": "tab:red",
          "flow": "tab:blue", "ee": "tab:red", "bary": "tab:green", "payload": "tab:green",
          "obstacle": "tab:brown"}


def _cylinder(ax, ob):
    a = np.linspace(0, 2 * np.pi, 40)
    x = ob.base_center_m[0] + ob.radius_m * np.cos(a)
    y = ob.base_center_m[1] + ob.radius_m * np.sin(a)
    for z in (ob.base_center_m[2], ob.base_center_m[2] + ob.height_m):
        ax.plot(x, y, np.full_like(x, z), color=COLORS["obstacle"], lw=0.8)
    for k in range(0, 40, 10):
        ax.plot([x[k]] * 2, [y[k]] * 2, [ob.base_center_m[2], ob.base_center_m[2] + ob.height_m],
                color=COLORS["obstacle"], lw=0.8)


def _equal_axes(ax, pts):
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    mid, half = (lo + hi) / 2, max((hi - lo).max() / 2, 0.3) * 1.1
    for set_lim, m in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), mid):
        set_lim(m - half, m + half)
    ax.set_box_aspect((1, 1, 1))


def draw(scene, out_png, title=None):
    """Writes the final frame of `scene` (viz.scene.Scene) to out_png; returns the path."""
    import matplotlib.pyplot as plt
    fig = figure(scene, title)
    fig.savefig(out_png, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return out_png


def figure(scene, title=None):
    """The matplotlib figure of the final frame of `scene` (viz.scene.Scene)."""
    import matplotlib.pyplot as plt
    tr = scene.truth
    k = tr.count - 1
    frames = arm_frames(scene.geometry, tr["position_m"][k:k + 1], tr["quaternion_wxyz"][k:k + 1],
                        tr["joint_position_rad"][k:k + 1])
    scales = Scales(scene)
    fig = plt.figure(figsize=(7.0, 5.6))
    ax = fig.add_subplot(projection="3d")
    pts = [frames["origins_m"][0]]
    corners = hull_corners(scene, k)
    if corners is not None:
        for i, (a, b) in enumerate(BOX_EDGES):
            ax.plot(*corners[[a, b]].T, color=COLORS["hull"], lw=1.0,
                    label="hull" if i == 0 else None)
        pts.append(corners)
    mount = mount_inertial(scene, [k])
    chain = frames["origins_m"][0]
    if mount is not None:
        chain = np.vstack([mount[0], chain])
    ax.plot(*chain.T, color=COLORS["arm"], lw=4, solid_capstyle="round",
            label="mount and arm links")
    ax.scatter(*frames["payload_m"][0], color=COLORS["payload"], s=50, marker="o",
               label=f"payload {scene.geometry.payload_kg:g} kg")
    ax.scatter(*tr["ee_position_m"][k], color=COLORS["ee"], s=25, marker="x", label="EE (true)")
    ax.scatter(*tr["barycenter_m"][k], color=COLORS["bary"], s=40, marker="^",
               label="barycenter")
    origins, vectors, capped = thrust_arrows(scene, scales, [k])
    for j in range(origins.shape[1]):
        color = COLORS["capped"] if capped[0, j] else COLORS["thrust"]
        ax.quiver(*origins[0, j], *vectors[0, j], color=color, lw=2, arrow_length_ratio=0.25)
    now_N = float(np.abs(tr["thrust_N"][k][:origins.shape[1]]).max(initial=0.0))
    ax.plot([], [], color=COLORS["thrust"], lw=2,
            label=f"thrust, {scales.thrust_m_per_N:g} m per N (largest now {now_N:.2g} N)")
    if capped.any():
        ax.plot([], [], color=COLORS["capped"], lw=2, label="thrust, capped")
    flow = tr["flow_velocity_m_s"][k] * scales.flow_m_per_m_s
    if np.linalg.norm(flow) > 0:
        ax.quiver(*tr["position_m"][k], *flow, color=COLORS["flow"], lw=2,
                  arrow_length_ratio=0.2, label=f"flow, {scales.flow_m_per_m_s:g} m per m/s")
    for ob in scene.obstacles:
        _cylinder(ax, ob)
        pts.append(ob.base_center_m[None, :])
    pts += [origins[0], origins[0] + vectors[0], tr["ee_position_m"][k][None, :]]
    _equal_axes(ax, np.vstack(pts))
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    ax.view_init(elev=22, azim=-60)
    ax.set_title(f"{title or 'run'}: final frame, t = {tr['t_s'][k]:.4g} s", fontsize=10)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, frameon=False)
    fig.tight_layout()
    return fig
