# SPDX-License-Identifier: Apache-2.0
"""rerun_export: a run (uvms_tools.viz.scene.Scene) as a Rerun recording (.rrd) on the timeline
`sim_time` (simulated time of each tick, a duration in s).

Why: a 3D replay of the vehicle, the arm, the thrusts, the flow and the obstacles next to the
time series that explain them, in one file that the Rerun viewer opens (`rerun run.rrd`).
Everything is drawn from the log (the plant's truth and the controller's telemetry); the arm's
links come from forward kinematics of the truth state (kinematics.py, docs/MODEL.md §2).

Every entity path is in ENTITIES (below), with its archetype, the rows it has and what it
shows; `entity_paths(scene)` expands the templates ({i} joint 1..N, {j} thruster 1..n, {axis},
{energy}, {name} obstacle). Rows: "static" logged once without time; "truth" one per truth
sample (ticks 0..n); "telemetry" one per telemetry tick (0..n-1); "matched" the ticks with
both; "events" only where something happens. Arrow scales (m per N, m per m/s), the capping of
long thrust arrows and the arm's mount strut are layout.py's (shared with the still of the final
frame, still.py) and written in info/legend. Each thrust arrow's label carries its value at the
tick; the points have no labels where they would overlap (the EE estimate sits at the payload):
the legend names their colours.
"""
import math
import re

import numpy as np
import rerun as rr
import rerun.blueprint as rrb

from uvms_tools.log import runlog

from .kinematics import arm_frames
from .layout import (ARROW_RADIUS_M, THRUST_ARROW_CAP_M, Scales, mount_inertial,
                     mount_strut, thrust_arrows)

TIMELINE = "sim_time"  # simulated time of the tick [s] (truth/telemetry utime)
APP_ID = "uvms"

# path template -> (archetype, rows, what it shows). The one table of names.
ENTITIES = {
    "info/legend": ("TextDocument", "static", "sources, units, arrow scales"),
    "world": ("ViewCoordinates", "static", "inertial frame I, right-handed, z up (MODEL §2)"),
    "world/vehicle": ("Transform3D", "truth", "vehicle pose: CoM r0 [m], attitude R0"),
    "world/vehicle/hull": ("Boxes3D", "static", "hull box in the vehicle frame [m] "
                                               "(UVMS_SCENE only)"),
    "world/arm/mount": ("Capsules3D", "truth", "mount strut from the hull box to the arm base "
                                               "p_0 (when p_0 lies outside the hull)"),
    "world/arm/link_{i}": ("Capsules3D", "truth", "link i from p_(i-1) to p_i, radius d_L/2"),
    "world/arm/payload": ("Points3D", "truth", "payload point p_N + R_N offset, label kg"),
    "world/thrusters": ("Arrows3D", "truth", "thrust_N[j] u_j at a_j (inertial), labelled Tj "
                                             "and its value; capped ones red"),
    "world/ee/path": ("LineStrips3D", "truth", "truth EE path up to the tick [m]"),
    "world/ee/estimate": ("Points3D", "telemetry", "controller's EE estimate [m]"),
    "world/barycenter": ("Points3D", "truth", "truth barycenter [m]"),
    "world/barycenter/path": ("LineStrips3D", "truth", "truth barycenter path up to the tick"),
    "world/flow": ("Arrows3D", "truth", "fluid velocity at the vehicle CoM"),
    "world/obstacles/{name}": ("Cylinders3D", "static", "vertical cylinder of the contact "
                                                       "monitor (UVMS_SCENE only)"),
    "world/contact": ("Points3D", "events", "red marker at ticks with min_clearance_m <= "
                                            "clearance (on the closest link)"),
    "log/contact": ("TextLog", "events", "clearance breaches and a contact end of run"),
    "log/closest_pair": ("TextLog", "events", "closest pair at tick 0 and when it changes"),
    "log/status": ("TextLog", "events", "end of run: state, code, reason"),
    "plots/contact/min_clearance_m": ("Scalars", "truth", "smallest distance [m] (NaN: off)"),
    "plots/ee_error_m": ("Scalars", "matched", "|truth EE - telemetry EE estimate| [m]"),
    "plots/attitude_error_rad/{axis}": ("Scalars", "telemetry", "attitude error x, y, z, "
                                                                "norm [rad]"),
    "plots/energy_J/{energy}": ("Scalars", "truth", "truth energies [J]"),
    "plots/thrust_N/T{j}": ("Scalars", "truth", "produced thrust of thruster j [N]"),
    "plots/voltage_V/T{j}": ("Scalars", "truth", "motor voltage of thruster j [V]"),
    "plots/current_A/T{j}": ("Scalars", "truth", "motor current of thruster j [A]"),
    "plots/joint_rad/J{i}": ("Scalars", "truth", "joint angle i [rad]"),
}
AXES = ("x", "y", "z", "norm")
ENERGIES = {"thruster": "thruster_energy_J", "thruster_signed": "thruster_energy_signed_J",
            "manipulator": "manipulator_energy_J", "propulsive": "propulsive_energy_J"}
PER_THRUSTER = {"plots/thrust_N/T{j}": "thrust_N", "plots/voltage_V/T{j}": "motor_voltage_V",
                "plots/current_A/T{j}": "motor_current_A"}

PATH_MAX_POINTS = 250        # history points of a path strip (fixed stride over the run)
PAYLOAD_RADIUS_M = 0.05      # drawn radius of a 10 kg payload; scales with the cube root
CONTACT_RADIUS_M = 0.06
RED, GREY, BLUE, ORANGE, GREEN = (230, 40, 40), (150, 150, 160), (60, 120, 230), \
    (240, 150, 30), (40, 180, 90)


def safe_name(name):
    """An obstacle name as one entity-path part."""
    return re.sub(r"[^A-Za-z0-9_-]", "_", name) or "obstacle"


def expand(template, scene):
    """The paths of one ENTITIES template for this scene."""
    n_j, n_t = scene.geometry.num_joints, len(scene.thrusters.position_m)
    if "{i}" in template:
        return [template.format(i=i) for i in range(1, n_j + 1)]
    if "{j}" in template:
        return [template.format(j=j) for j in range(1, n_t + 1)]
    if "{axis}" in template:
        return [template.format(axis=a) for a in AXES]
    if "{energy}" in template:
        return [template.format(energy=e) for e in ENERGIES]
    if "{name}" in template:
        return [template.format(name=safe_name(o.name)) for o in scene.obstacles]
    return [template]


def entity_paths(scene):
    """{path: (archetype, rows, what)} of every entity this scene can have."""
    return {p: spec for t, spec in ENTITIES.items() for p in expand(t, scene)}


def time_index(utime_us):
    """The sim_time column of messages with these utimes [µs] (exact, integer ns)."""
    ns = np.asarray(utime_us, dtype=np.int64) * 1000
    return [rr.TimeColumn(TIMELINE, duration=ns.astype("timedelta64[ns]"))]


def rot_z_to(d):
    """Quaternions (x, y, z, w) turning +z onto the unit rows of d (n, 3); identity for zero
    rows, a half turn about x for -z."""
    q = np.column_stack([-d[:, 1], d[:, 0], np.zeros(len(d)), 1.0 + d[:, 2]])
    flip = q[:, 3] < 1e-9
    q[flip] = (1.0, 0.0, 0.0, 0.0)
    return q / np.linalg.norm(q, axis=1, keepdims=True)


def quat_xyzw(q_wxyz):
    """Rerun's quaternion order (x, y, z, w) from the log's (w, x, y, z), normalised."""
    q = np.asarray(q_wxyz, dtype=float)
    return (q / np.linalg.norm(q, axis=1, keepdims=True))[:, [1, 2, 3, 0]]


def growing_strips(points):
    """One strip per row k: points 0..k at a fixed stride (<= PATH_MAX_POINTS) plus point k."""
    n = len(points)
    stride = max(1, math.ceil(n / PATH_MAX_POINTS))
    strips = []
    for k in range(n):
        idx = np.arange(0, k + 1, stride)
        if idx[-1] != k:
            idx = np.append(idx, k)
        strips.append(points[idx])
    return strips


def log_static(rec, scene, scales):
    """Frame, hull, obstacles, legend and the constant parts of per-tick entities."""
    rec.log("world", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    if scene.hull_size_m is not None:
        rec.log("world/vehicle/hull", rr.Boxes3D(sizes=[scene.hull_size_m],
                                                 centers=[scene.hull_center_m], colors=[GREY]),
                static=True)
    for ob in scene.obstacles:
        center = ob.base_center_m + np.array([0.0, 0.0, ob.height_m / 2])
        rec.log(f"world/obstacles/{safe_name(ob.name)}",
                rr.Cylinders3D(lengths=[ob.height_m], radii=[ob.radius_m], centers=[center],
                               colors=[(120, 100, 80)], labels=[ob.name]), static=True)
    n_t = len(scene.thrusters.position_m)
    rec.log("world/thrusters", rr.Arrows3D.from_fields(radii=[ARROW_RADIUS_M] * n_t),
            static=True)
    payload_kg = scene.geometry.payload_kg
    radius = PAYLOAD_RADIUS_M * max(payload_kg, 0.5) ** (1 / 3) / 10 ** (1 / 3)
    rec.log("world/arm/payload", rr.Points3D.from_fields(
        radii=[radius], labels=[f"payload {payload_kg:g} kg"], colors=[GREEN]), static=True)
    rec.log("world/flow", rr.Arrows3D.from_fields(
        labels=[f"flow ({scales.flow_m_per_m_s:g} m per m/s)"], colors=[BLUE],
        radii=[ARROW_RADIUS_M]), static=True)
    rec.log("info/legend", rr.TextDocument(legend(scene, scales), media_type="text/markdown"),
            static=True)


def legend(scene, scales):
    """info/legend: what the recording shows and where it comes from (Markdown)."""
    lines = [f"# {scene.truth.count} truth samples, timeline `{TIMELINE}` (simulated time, s)",
             f"- geometry from **{scene.source}**; inertial frame, z up, metres (MODEL §2)",
             f"- thrust arrows: **{scales.thrust_m_per_N:g} m per N** (thrust_N[j] u_j; the "
             f"90th percentile of each tick's largest thrust, {scales.thrust_typical_N:.3g} N, "
             f"drawn at most 0.3 m long); arrows over {THRUST_ARROW_CAP_M:g} m are capped and red "
             f"({100 * scales.capped_share(scene):.1f} % of them; largest thrust "
             f"{scales.thrust_max_N:.3g} N); each label: the thruster and its thrust",
             f"- flow arrow: **{scales.flow_m_per_m_s:g} m per m/s** at the vehicle CoM",
             f"- contact marker: min_clearance_m <= {scene.clearance_m:g} m",
             "- points: payload green (labelled), EE estimate blue, barycenter green with its "
             "path; EE path red; the grey strut joins the hull to the arm base"]
    if scene.contact_enabled is False:
        lines.append("- contact monitor off: no clearance computed (plotted as gaps)")
    lines += [f"- note: {n}" for n in scene.notes]
    if scene.end is not None:
        lines.append(f"- end of run: {scene.end.text()}")
    return "\n".join(lines) + "\n"


def send_scalars(rec, path, utime_us, values, name):
    rec.log(path, rr.SeriesLines(names=[name]), static=True)
    rec.send_columns(path, indexes=time_index(utime_us),
                     columns=rr.Scalars.columns(scalars=np.asarray(values, dtype=float)))


def log_arm(rec, scene, frames):
    """Links as capsules between consecutive frame origins; the mount strut; the payload."""
    tr, geom = scene.truth, scene.geometry
    origins = frames["origins_m"]
    mount = mount_inertial(scene)
    if mount is not None:
        seg = mount[1] - mount[0]
        length = np.linalg.norm(seg, axis=1)
        rec.send_columns("world/arm/mount", indexes=time_index(tr["utime"]),
                         columns=rr.Capsules3D.columns(
                             lengths=length, radii=np.full(len(seg), geom.diameter_m[0] / 2),
                             translations=mount[0], quaternions=rot_z_to(seg / length[:, None]),
                             colors=np.tile(GREY, (len(seg), 1))))
    for i in range(1, geom.num_joints + 1):
        seg = origins[:, i] - origins[:, i - 1]
        length = np.linalg.norm(seg, axis=1)
        unit = np.divide(seg, length[:, None], out=np.zeros_like(seg),
                         where=length[:, None] > 0)
        unit[length == 0] = (0.0, 0.0, 1.0)
        radius = np.full(len(seg), geom.diameter_m[i - 1] / 2)
        rec.send_columns(f"world/arm/link_{i}", indexes=time_index(tr["utime"]),
                         columns=rr.Capsules3D.columns(
                             lengths=length, radii=radius, translations=origins[:, i - 1],
                             quaternions=rot_z_to(unit), colors=np.tile(GREY, (len(seg), 1))))
    rec.send_columns("world/arm/payload", indexes=time_index(tr["utime"]),
                     columns=rr.Points3D.columns(positions=frames["payload_m"]))


def log_vehicle(rec, scene, frames, scales):
    """Vehicle pose, thrust arrows (inertial), flow arrow."""
    tr, th = scene.truth, scene.thrusters
    idx = time_index(tr["utime"])
    rec.send_columns("world/vehicle", indexes=idx, columns=rr.Transform3D.columns(
        translation=tr["position_m"], quaternion=quat_xyzw(tr["quaternion_wxyz"])))
    n, n_t = tr.count, len(th.position_m)
    origins, vectors, capped = thrust_arrows(scene, scales)
    colors = np.where(capped.reshape(-1, 1), np.array(RED), np.array(ORANGE))
    thrust = tr["thrust_N"][:, :n_t]
    labels = [f"T{j + 1} {thrust[k, j]:.2g} N" for k in range(n) for j in range(n_t)]
    rec.send_columns("world/thrusters", indexes=idx, columns=rr.Arrows3D.columns(
        origins=origins.reshape(-1, 3), vectors=vectors.reshape(-1, 3), colors=colors,
        labels=labels).partition([n_t] * n))
    rec.send_columns("world/flow", indexes=idx, columns=rr.Arrows3D.columns(
        origins=tr["position_m"], vectors=tr["flow_velocity_m_s"] * scales.flow_m_per_m_s))


def log_points(rec, scene):
    """EE path, EE estimate, barycenter and its path."""
    tr, tm = scene.truth, scene.telemetry
    idx = time_index(tr["utime"])
    rec.send_columns("world/ee/path", indexes=idx, columns=rr.LineStrips3D.columns(
        strips=growing_strips(tr["ee_position_m"]), colors=np.tile(RED, (tr.count, 1))))
    rec.send_columns("world/barycenter/path", indexes=idx, columns=rr.LineStrips3D.columns(
        strips=growing_strips(tr["barycenter_m"]), colors=np.tile(GREEN, (tr.count, 1))))
    rec.log("world/barycenter", rr.Points3D.from_fields(
        radii=[0.03], colors=[GREEN], labels=["barycenter"]), static=True)
    rec.send_columns("world/barycenter", indexes=idx,
                     columns=rr.Points3D.columns(positions=tr["barycenter_m"]))
    rec.log("world/ee/estimate", rr.Points3D.from_fields(radii=[0.02], colors=[BLUE]),
            static=True)
    rec.send_columns("world/ee/estimate", indexes=time_index(tm["utime"]),
                     columns=rr.Points3D.columns(positions=tm["ee_estimate_m"]))


def log_plots(rec, scene):
    """Time series under plots/ (ENTITIES)."""
    tr, tm = scene.truth, scene.telemetry
    for template, fld in PER_THRUSTER.items():
        for j, path in enumerate(expand(template, scene), start=1):
            send_scalars(rec, path, tr["utime"], tr[fld][:, j - 1], f"T{j}")
    for i, path in enumerate(expand("plots/joint_rad/J{i}", scene), start=1):
        send_scalars(rec, path, tr["utime"], tr["joint_position_rad"][:, i - 1], f"J{i}")
    for name, fld in ENERGIES.items():
        send_scalars(rec, f"plots/energy_J/{name}", tr["utime"], tr[fld], name)
    att = tm["attitude_error_rad"]
    for k, axis in enumerate(AXES):
        values = np.linalg.norm(att, axis=1) if axis == "norm" else att[:, k]
        send_scalars(rec, f"plots/attitude_error_rad/{axis}", tm["utime"], values, axis)
    ticks, _, eps_m = runlog.ee_error({"UVMS_TRUTH": tr, "UVMS_TELEMETRY": tm})
    send_scalars(rec, "plots/ee_error_m", tr.at_ticks(ticks)["utime"], eps_m, "EE error")
    clearance = np.where(np.isfinite(tr["min_clearance_m"]), tr["min_clearance_m"], np.nan)
    send_scalars(rec, "plots/contact/min_clearance_m", tr["utime"], clearance, "min clearance")


def contact_point(scene, frames, k, pair):
    """Where to draw a breach at truth row k: the middle of the first link of `pair`
    ("linkI|other"), else the vehicle CoM."""
    for body in pair.split("|"):
        m = re.fullmatch(r"link(\d+)", body)
        if m and 1 <= int(m.group(1)) <= scene.geometry.num_joints:
            i = int(m.group(1))
            return 0.5 * (frames["origins_m"][k, i - 1] + frames["origins_m"][k, i])
    return scene.truth["position_m"][k]


def log_events(rec, scene, frames):
    """Contact markers and messages, closest-pair changes, the end of the run."""
    tr = scene.truth
    clear, pair = tr["min_clearance_m"], tr["closest_pair"]
    hits = np.flatnonzero(np.isfinite(clear) & (clear <= scene.clearance_m))
    if len(hits):
        pts = np.array([contact_point(scene, frames, k, str(pair[k])) for k in hits])
        rec.log("world/contact", rr.Points3D.from_fields(radii=[CONTACT_RADIUS_M],
                                                        colors=[RED]), static=True)
        rec.send_columns("world/contact", indexes=time_index(tr["utime"][hits]),
                         columns=rr.Points3D.columns(positions=pts, labels=[
                             f"{pair[k]} {clear[k]:.4g} m" for k in hits]))
        rec.send_columns("log/contact", indexes=time_index(tr["utime"][hits]),
                         columns=rr.TextLog.columns(text=[
                             f"tick {tr['tick'][k]}: min clearance {clear[k]:.6g} m <= "
                             f"{scene.clearance_m:g} m ({pair[k]})" for k in hits],
                             level=["WARN"] * len(hits)))
    change = np.flatnonzero(np.r_[True, pair[1:] != pair[:-1]])
    rec.send_columns("log/closest_pair", indexes=time_index(tr["utime"][change]),
                     columns=rr.TextLog.columns(text=[f"closest pair: {pair[k]}"
                                                      for k in change]))
    end = scene.end
    if end is not None:
        rec.set_time(TIMELINE, duration=np.timedelta64(end.utime_us * 1000, "ns"))
        level = "ERROR" if end.failed else "INFO"
        rec.log("log/status", rr.TextLog(f"run {end.text()}", level=level))
        if end.contact:
            rec.log("log/contact", rr.TextLog(f"run ended by contact: {end.reason}",
                                              level="ERROR"))


# Default camera: from the port side, behind and above the middle of the vehicle-arm system at
# its start, far enough to see the vehicle, the arm's reach and a nearby obstacle [m].
EYE_OFFSET_M = (-1.2, -3.6, 1.8)


def camera(scene, frames):
    """EyeControls3D looking at the midpoint of the vehicle CoM and the EE at the first tick."""
    target = 0.5 * (scene.truth["position_m"][0] + frames["origins_m"][0, -1])
    return rrb.EyeControls3D(position=target + np.asarray(EYE_OFFSET_M), look_target=target,
                             eye_up=(0.0, 0.0, 1.0))


def blueprint(eye=None):
    """3D view and time series, readable on opening; `eye`: the 3D view's camera (None: the
    viewer's own choice)."""
    series = [("plots/thrust_N", "thrust [N]"), ("plots/voltage_V", "motor voltage [V]"),
              ("plots/current_A", "motor current [A]"), ("plots/joint_rad", "joints [rad]")]
    errors = [("plots/ee_error_m", "EE error [m]"),
              ("plots/attitude_error_rad", "attitude error [rad]"),
              ("plots/energy_J", "energy [J]"), ("plots/contact", "min clearance [m]")]
    tabs = [rrb.Tabs(*[rrb.TimeSeriesView(origin=o, name=n) for o, n in group])
            for group in (series, errors)]
    left = rrb.Vertical(
        rrb.Spatial3DView(origin="world", name="run (inertial, z up) [m]", eye_controls=eye),
        rrb.Tabs(rrb.TextLogView(origin="log", name="events"),
                 rrb.TextDocumentView(origin="info", name="legend")),
        row_shares=[4, 1])
    return rrb.Blueprint(rrb.Horizontal(left, rrb.Vertical(*tabs), column_shares=[3, 2]),
                         collapse_panels=True)


def export(scene, out_path, name=None):
    """Write the recording of `scene` to out_path (.rrd). Returns the entity paths written."""
    session = int(scene.truth["session"][0]) if "session" in scene.truth else 0
    rec = rr.RecordingStream(APP_ID, recording_id=f"uvms-{session & 0xFFFFFFFFFFFFFFFF:016x}",
                             send_properties=False)
    rec.set_log_time_enabled(False)
    tr = scene.truth
    frames = arm_frames(scene.geometry, tr["position_m"], tr["quaternion_wxyz"],
                        tr["joint_position_rad"])
    rec.save(out_path, default_blueprint=blueprint(camera(scene, frames)))
    if name:
        rec.send_recording_name(name)
    scales = Scales(scene)
    log_static(rec, scene, scales)
    log_vehicle(rec, scene, frames, scales)
    log_arm(rec, scene, frames)
    log_points(rec, scene)
    log_plots(rec, scene)
    log_events(rec, scene, frames)
    rec.flush()
    rec.disconnect()
    return written_paths(scene)


def written_paths(scene):
    """Entity paths this export writes for `scene` (events only where they occur)."""
    paths = dict(entity_paths(scene))
    tr = scene.truth
    clear = tr["min_clearance_m"]
    if not (np.isfinite(clear) & (clear <= scene.clearance_m)).any():
        paths.pop("world/contact")
        if not (scene.end is not None and scene.end.contact):
            paths.pop("log/contact")
    if scene.end is None:
        paths.pop("log/status")
    if scene.hull_size_m is None:
        paths.pop("world/vehicle/hull")
    if mount_strut(scene) is None:
        paths.pop("world/arm/mount")
    return paths
