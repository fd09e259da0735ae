# SPDX-License-Identifier: Apache-2.0
"""tools/uvmsviz.py (run log -> Rerun recording) on fresh 1.5 s runs, the .rrd read back with
the Rerun SDK (rerun.chunk.RrdReader) and compared with things the tool did not compute:
  - the entity paths the viewer must have (REQUIRED, written here) are in the file; every path
    of the tool's table (uvms_tools.viz.rerun_export.ENTITIES) is in the file and nothing else is;
  - per-tick entities, templated ones included (T1..T8, J1..J7, energies, attitude axes), have
    one sim_time sample per UVMS_TRUTH (or UVMS_TELEMETRY) event, counted straight from the
    LCM event log, at the events' timestamps;
  - the thrust, voltage, current, joint and energy series equal the log's columns; the last
    link capsule ends at the plant's truth ee_position_m; thrust arrows start at r0 + R0 a_j
    with R0 from the recorded vehicle transform (rotated here with the quaternion formula, not
    the tool's matrices);
  - a copy of the log whose truth attitude is a fixed 30 degree turn about (1, 2, 3) (truth_t
    re-encoded and re-sealed with its CRC-32): the thrust arrows are thrust_N[j] s R u_j and
    start at r0 + R a_j, R from the axis-angle (Rodrigues) formula, s the largest 1-2-5 step
    [m/N] that keeps the longest arrow <= 0.5 m (and the one the legend states); R^T or
    vehicle-frame arrows would be off by far more than the tolerance (checked too);
  - the hull box and an obstacle (scene_t) are static and have the scene's sizes;
  - a run ended by contact: red markers, the end reason in the event log;
  - a log without UVMS_SCENE (older logs): geometry from UVMS_CONFIG, a note, no hull;
  - --every K keeps ceil(n/K) samples; without --out the recording is LOG_STEM.rrd beside the
    log; bad input (a directory or a missing directory as --out included, checked before the
    log is read) is one error line and exit 1; --help.

Usage: test_uvmsviz.py UVMS_EXE SOURCE_DIR
"""
import math
import os
import subprocess
import sys
import zlib

import lcm
import numpy as np
import pyarrow as pa
from rerun.chunk import RrdReader

UVMS, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tools"))
from uvms_tools.log import runlog  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checklist  # noqa: E402
from uvms_tools.viz import rerun_export, scene as scene_mod  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

PY = sys.executable
TOOL = os.path.join(SRC, "tools", "uvmsviz.py")
SCENARIO = "sil/scenarios/paper/case_VII_stagnant.toml"
TMP = scratch_dir("uvms-uvmsviz-")  # removed at exit (tests/support/scratch.py)
SHORT = ["--set", "run.duration_s=1.5", "--set", "trajectory.duration_s=1.5"]
CHIMNEY = ('contact.obstacle=[{name="chimney", base_center_m=[2.5, 0, -2], height_m=1.5, '
           'radius_m=0.3}]')
# In the arm's way in the 1.5 s motion: the run ends by contact (link 7) around tick 35.
POLE = ('contact.obstacle=[{name="pole", base_center_m=[1.4, 0.3, -1], height_m=2, '
        'radius_m=0.05}]')
# Rerun stores positions, lengths and quaternions as float32: ~1e-7 relative, arm ~1.5 m.
TOL_F32_M = 2e-6
EVERY = 4
THRUSTERS = range(1, 9)  # T1..T8, the paper's vehicle
JOINTS = range(1, 8)     # J1..J7
TRUTH_SERIES = {"thrust_N": "thrust_N", "voltage_V": "motor_voltage_V",
                "current_A": "motor_current_A"}  # plots/<name>/Tj -> UVMS_TRUTH column
ENERGIES = {"plots/energy_J/thruster": "thruster_energy_J",
            "plots/energy_J/thruster_signed": "thruster_energy_signed_J",
            "plots/energy_J/manipulator": "manipulator_energy_J",
            "plots/energy_J/propulsive": "propulsive_energy_J"}
ATT_AXES = ("x", "y", "z", "norm")
# The paths the viewer must write (issue 19), with the events that give their samples:
# "truth" one per UVMS_TRUTH event, "telemetry" one per UVMS_TELEMETRY event of tick >= 0,
# "static" none. Written here, not taken from the tool.
REQUIRED = {
    "world/vehicle": "truth", "world/vehicle/hull": "static",
    **{f"world/arm/link_{i}": "truth" for i in JOINTS},
    "world/arm/payload": "truth", "world/thrusters": "truth", "world/ee/path": "truth",
    "world/ee/estimate": "telemetry", "world/barycenter": "truth", "world/flow": "truth",
    "world/obstacles/chimney": "static", "plots/ee_error_m": "telemetry",
    **{f"plots/attitude_error_rad/{a}": "telemetry" for a in ATT_AXES},
    **{path: "truth" for path in ENERGIES},
    **{f"plots/{name}/T{j}": "truth" for name in TRUTH_SERIES for j in THRUSTERS},
    **{f"plots/joint_rad/J{i}": "truth" for i in JOINTS},
}
# The synthetic attitude: a 30 degree turn about (1, 2, 3) (no axis of R is an axis of I).
TILT_RAD = math.radians(30.0)
TILT_AXIS = np.array([1.0, 2.0, 3.0]) / math.sqrt(14.0)
TILT_WXYZ = [math.cos(TILT_RAD / 2), *(math.sin(TILT_RAD / 2) * TILT_AXIS)]
# Documented (viz/layout.py, docs/VISUALIZATION.md): the 90th percentile of each tick's largest
# |thrust| is drawn at most 0.3 m (1-2-5 steps); arrows are capped at 0.8 m.
THRUST_ARROW_TYPICAL_M, THRUST_ARROW_CAP_M = 0.3, 0.8

TALLY = checklist.Tally()
check = TALLY.check


def run(name, *sets):
    out = os.path.join(TMP, name)
    args = [UVMS, "run", SCENARIO, *SHORT, "--out", out]
    for s in sets:
        args += ["--set", s]
    p = subprocess.run(args, cwd=SRC, capture_output=True, text=True)
    if not os.path.exists(os.path.join(out, "run.lcmlog")):
        raise SystemExit(f"uvms run {name} wrote no log ({p.returncode}): {p.stderr[-300:]}")
    return out


def viz(*args):
    return subprocess.run([PY, TOOL, *args], capture_output=True, text=True)


def event_utimes(log_path, channel):
    """Timestamps [µs] of a channel's events, straight from the LCM log."""
    ev = lcm.EventLog(log_path, "r")
    stamps = [e.timestamp for e in ev if e.channel == channel]
    ev.close()
    return np.array(stamps, dtype=np.int64)


def read_rrd(path):
    """{entity path: {"static": {column: row values}, "time_ns": array, column: [rows]}}."""
    out = {}
    for chunk in RrdReader(path).stream().to_chunks():
        rb = chunk.to_record_batch()
        ent = out.setdefault(chunk.entity_path.lstrip("/"), {"static": {}, "time_ns": []})
        cols = [c for c in rb.schema.names if c not in ("rerun.controls.RowId", "sim_time")]
        if chunk.is_static:
            ent["static"].update({c: rb.column(c).to_pylist()[-1] for c in cols})
            continue
        ent["time_ns"] += rb.column("sim_time").cast(pa.int64()).to_pylist()
        for c in cols:
            ent.setdefault(c, []).extend(rb.column(c).to_pylist())
    return out


def convert(run_dir, rrd, *extra):
    p = viz(run_dir, "--out", rrd, *extra)
    check(p.returncode == 0 and p.stdout.startswith(f"wrote {rrd}: "),
          f"uvmsviz {os.path.basename(run_dir)} {' '.join(extra)}: exit 0, one summary line "
          f"({p.stdout.strip()} {p.stderr.strip()[-300:]})")
    return read_rrd(rrd), p


def expected_paths(run_dir):
    log = runlog.load(os.path.join(run_dir, "run.lcmlog"))
    return set(rerun_export.entity_paths(scene_mod.read_scene(log))), log


def check_paths(rec, expected, absent, tag):
    stored = set(rec) - {"__properties"}
    missing = expected - absent - stored
    check(not missing, f"{tag}: every table path is in the file (missing: {sorted(missing)})")
    extra = stored - expected
    check(not extra, f"{tag}: nothing outside the table (extra: {sorted(extra)})")
    check(not (stored & absent), f"{tag}: no {sorted(absent)}")


def check_required(rec, tag):
    """The paths of REQUIRED (written in this test, not the tool's table) are in the file."""
    missing = sorted(set(REQUIRED) - set(rec))
    check(not missing, f"{tag}: the {len(REQUIRED)} required paths (world/vehicle .. "
                       f"plots/current_A/T8) are in the file (missing: {missing})")


def check_samples(rec, log_file, n_truth_expected=None):
    """Per-tick entities: one sample per truth (telemetry) event, at its timestamp: the
    tool's table rows, and REQUIRED's templated series (T1..T8, J1..J7, energies, axes)."""
    truth_us = event_utimes(log_file, "UVMS_TRUTH")
    tele = runlog.load(log_file, ["UVMS_TELEMETRY"])["UVMS_TELEMETRY"]
    tele_us = np.sort(tele["log_utime"][tele["tick"] >= 0])
    if n_truth_expected is not None:
        truth_us = truth_us[::EVERY]
        tele_us = tele_us[np.isin(tele_us, truth_us)]
    want_rows = {path: rows for path, (_, rows, _) in rerun_export.ENTITIES.items()
                 if rows in ("truth", "telemetry", "matched") and "{" not in path}
    want_rows.update({path: rows for path, rows in REQUIRED.items() if rows != "static"})
    bad = []
    for path, rows in sorted(want_rows.items()):
        want = truth_us if rows == "truth" else tele_us
        got = np.unique(rec.get(path, {"time_ns": []})["time_ns"])
        if not np.array_equal(got, want * 1000):
            bad.append(f"{path} {len(got)} vs {len(want)}")
    n = len(truth_us)
    check(not bad, f"{len(want_rows)} per-tick entities have {n} sim_time samples = UVMS_TRUTH "
                   f"events in the log (telemetry ones {len(tele_us)}) ({bad})")
    if n_truth_expected is not None:
        check(n == n_truth_expected, f"--every {EVERY}: {n} samples == ceil(n/{EVERY}) = "
                                     f"{n_truth_expected}")


def series(rec, path):
    return np.array([v[0] for v in rec[path]["Scalars:scalars"]])


def check_values(rec, log):
    """Thrust series, EE at the end of the last link, thruster arrows vs the vehicle pose."""
    tr = log["UVMS_TRUTH"]
    t3 = series(rec, "plots/thrust_N/T3")
    check(np.array_equal(t3, tr["thrust_N"][:, 2]), "plots/thrust_N/T3 == log thrust_N[:, 2] "
          "(thruster 3), exactly")
    check_series(rec, log)
    cap = rec["world/arm/link_7"]
    start = np.array([v[0] for v in cap["Capsules3D:translations"]])
    length = np.array([v[0] for v in cap["Capsules3D:lengths"]])
    quat = np.array([v[0] for v in cap["Capsules3D:quaternions"]])  # x, y, z, w
    end = start + rotate_xyzw(quat, np.array([0.0, 0.0, 1.0])) * length[:, None]
    err = np.abs(end - tr["ee_position_m"]).max()
    check(err < TOL_F32_M, f"link_7 capsule end == truth ee_position_m (max {err:.2g} m)")
    veh = rec["world/vehicle"]
    r0 = np.array([v for v in veh["Transform3D:translation"]]).reshape(-1, 3)
    q0 = np.array([v for v in veh["Transform3D:quaternion"]]).reshape(-1, 4)
    a_m = scene_mod.thrusters_of(log["UVMS_SCENE"]).position_m
    origins = np.array(rec["world/thrusters"]["Arrows3D:origins"])  # (n, 8, 3)
    want = r0[:, None, :] + np.stack([rotate_xyzw(q0, a) for a in a_m], axis=1)
    err = np.abs(origins - want).max()
    check(err < TOL_F32_M, f"thruster arrows start at r0 + R0 a_j of the recorded vehicle "
                           f"transform (max {err:.2g} m)")
    labels = rec["world/thrusters"]["Arrows3D:labels"]  # (n, 8): Tj and its thrust at the tick
    thrust = tr["thrust_N"][:, :8]
    bad = [k for k in (0, len(labels) // 2, len(labels) - 1)
           if list(labels[k]) != [f"T{j} {thrust[k, j - 1]:.2g} N" for j in THRUSTERS]]
    check(not bad, f"thruster labels: Tj and its thrust at the tick ({list(labels[-1])[:2]})")
    # The mount strut: from the hull box's surface to the arm base p_0 (link 1's start).
    mount, link1 = rec["world/arm/mount"], rec["world/arm/link_1"]
    m_start = np.array([v[0] for v in mount["Capsules3D:translations"]])
    m_len = np.array([v[0] for v in mount["Capsules3D:lengths"]])
    m_quat = np.array([v[0] for v in mount["Capsules3D:quaternions"]])
    m_end = m_start + rotate_xyzw(m_quat, np.array([0.0, 0.0, 1.0])) * m_len[:, None]
    p0 = np.array([v[0] for v in link1["Capsules3D:translations"]])
    hull = scene_mod.read_scene(log)
    inv = [rotate_xyzw((q0[k] * np.array([-1, -1, -1, 1]))[None], m_start[k] - r0[k])[0]
           for k in (0, len(q0) - 1)]  # the strut's start in the vehicle frame
    lo = hull.hull_center_m - hull.hull_size_m / 2
    hi = hull.hull_center_m + hull.hull_size_m / 2
    on_box = all(np.all(v >= lo - 1e-5) and np.all(v <= hi + 1e-5)
                 and np.min(np.minimum(np.abs(v - lo), np.abs(v - hi))) < 1e-5 for v in inv)
    err = np.abs(m_end - p0).max()
    check(err < TOL_F32_M and on_box and m_len.min() > 0.1,
          f"the mount strut joins the hull box's surface to the arm base p_0 (end error "
          f"{err:.2g} m, length {m_len.min():.3g} m)")


def check_series(rec, log):
    """Every truth series of REQUIRED equals its UVMS_TRUTH column; attitude axes equal the
    telemetry's attitude_error_rad (tick >= 0) and its norm."""
    tr, tm = log["UVMS_TRUTH"], log["UVMS_TELEMETRY"]
    want = {f"plots/{name}/T{j}": tr[fld][:, j - 1] for name, fld in TRUTH_SERIES.items()
            for j in THRUSTERS}
    want.update({f"plots/joint_rad/J{i}": tr["joint_position_rad"][:, i - 1] for i in JOINTS})
    want.update({path: tr[fld] for path, fld in ENERGIES.items()})
    bad = [p for p, v in want.items() if not np.array_equal(series(rec, p), v)]
    check(not bad, f"{len(want)} thrust, voltage, current, joint and energy series == their "
                   f"UVMS_TRUTH columns, exactly ({bad})")
    att = tm["attitude_error_rad"][tm["tick"] >= 0]
    att = np.column_stack([att, np.sqrt((att ** 2).sum(axis=1))])
    err = max(np.abs(series(rec, f"plots/attitude_error_rad/{a}") - att[:, k]).max()
              for k, a in enumerate(ATT_AXES))
    check(err < 1e-12, f"attitude error x, y, z, norm == telemetry attitude_error_rad and its "
                       f"norm (max {err:.2g} rad)")


def rotate_xyzw(q, v):
    """v rotated by unit quaternions q (n, 4) in Rerun's (x, y, z, w) order."""
    u, w = q[:, :3], q[:, 3:4]
    t = 2.0 * np.cross(u, v)
    return v + w * t + np.cross(u, t)


def sealed(data):
    """An encoded uvms message with its trailing crc32 field set as sil/msg/codec.h does: CRC-32
    (IEEE 802.3, zlib's) of every byte before it, fingerprint included, big-endian."""
    return data[:-4] + (zlib.crc32(data[:-4]) & 0xFFFFFFFF).to_bytes(4, "big")


def tilted_copy(src_log, dst_log):
    """Copy of a log whose UVMS_TRUTH attitudes are all TILT_WXYZ (truth_t re-encoded and
    re-sealed); returns how many original truth messages had a valid CRC (all expected)."""
    from uvms.truth_t import truth_t  # generated; on sys.path after runlog.load
    src, dst = lcm.EventLog(src_log, "r"), lcm.EventLog(dst_log, "w", overwrite=True)
    n_ok = n = 0
    for ev in src:
        data = ev.data
        if ev.channel == "UVMS_TRUTH":
            n += 1
            n_ok += sealed(data) == data
            msg = truth_t.decode(data)
            msg.quaternion_wxyz = list(TILT_WXYZ)
            data = sealed(msg.encode())
        dst.write_event(ev.timestamp, ev.channel, data)
    src.close()
    dst.close()
    return n_ok, n


def axis_angle_rot(axis, angle_rad):
    """Rodrigues: R = cos a I + sin a [k]x + (1 - cos a) k k^T (vehicle -> inertial)."""
    k = np.asarray(axis, dtype=float)
    kx = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    return c * np.eye(3) + s * kx + (1 - c) * np.outer(k, k)


def arrow_scale(thrust):
    """The largest 1-2-5 step [m/N] that draws the 90th percentile of each tick's largest
    |thrust| at most THRUST_ARROW_TYPICAL_M long."""
    typical = np.percentile(np.abs(thrust).max(axis=1), 90)
    typical = typical if typical > 0 else np.abs(thrust).max()  # idle most of the run
    steps = [m * 10.0 ** e for e in range(-6, 7) for m in (1, 2, 5)]
    return max(x for x in steps if x * typical <= THRUST_ARROW_TYPICAL_M * (1 + 1e-12))


def check_tilted(run_dir):
    """Thrust arrows of a run turned by 30 degrees: inertial, R u_j (not R^T, not u_j)."""
    tilted = os.path.join(TMP, "tilted.lcmlog")
    n_ok, n = tilted_copy(os.path.join(run_dir, "run.lcmlog"), tilted)
    check(n and n_ok == n, f"the plant's truth messages carry valid CRC-32s ({n_ok} of {n}): "
                           f"the copy is sealed the same way")
    p = viz(tilted)  # no --out: LOG_STEM.rrd beside the log
    rrd = os.path.join(TMP, "tilted.rrd")
    check(p.returncode == 0 and p.stdout.startswith(f"wrote {rrd}: ") and os.path.isfile(rrd),
          f"no --out: writes tilted.rrd beside tilted.lcmlog ({p.stdout.strip()} "
          f"{p.stderr.strip()[-200:]})")
    if not os.path.isfile(rrd):
        return
    rec, log = read_rrd(rrd), runlog.load(tilted)
    tr, sc = log["UVMS_TRUTH"], log["UVMS_SCENE"]
    thrust = tr["thrust_N"][:, :8]
    a_m = np.asarray(sc["thruster_position_m"][0], dtype=float).reshape(-1, 3)[:8]
    u = np.asarray(sc["thruster_direction"][0], dtype=float).reshape(-1, 3)[:8]
    rot = axis_angle_rot(TILT_AXIS, TILT_RAD)
    t_max = np.abs(thrust).max()
    scale = arrow_scale(thrust)
    check(t_max > 1e-6, f"the run has thrust (max {t_max:.3g} N): arrows to compare")
    legend = "".join(rec["info/legend"]["static"].get("TextDocument:text") or [])
    check(f"**{scale:g} m per N**" in legend, f"legend states the scale {scale:g} m per N "
                                             f"(1-2-5 step of the 90th percentile)")
    vec = np.array(rec["world/thrusters"]["Arrows3D:vectors"])  # (n, 8, 3)
    length = np.clip(thrust * scale, -THRUST_ARROW_CAP_M, THRUST_ARROW_CAP_M)
    want = length[..., None] * (u @ rot.T)[None]
    err = np.abs(vec - want).max()
    longest = np.linalg.norm(vec, axis=2).max()
    check(err < TOL_F32_M and longest <= THRUST_ARROW_CAP_M + TOL_F32_M,
          f"thrust arrows == thrust_N[j] {scale:g} m/N R u_j, capped at 0.8 m (max "
          f"{err:.2g} m), longest {longest:.3g} m")
    wrong = min(np.abs(length[..., None] * (u @ m.T)[None] - want).max()
                for m in (rot.T, np.eye(3)))
    check(wrong > 1e3 * TOL_F32_M, f"the check tells R from R^T and the vehicle frame (they "
                                   f"differ by {wrong:.3g} m)")
    origins = np.array(rec["world/thrusters"]["Arrows3D:origins"])
    err = np.abs(origins - (tr["position_m"][:, None, :] + (a_m @ rot.T)[None])).max()
    check(err < TOL_F32_M, f"thrust arrows start at r0 + R a_j (max {err:.2g} m)")
    q = np.array(rec["world/vehicle"]["Transform3D:quaternion"]).reshape(-1, 4)
    q_want = np.array(TILT_WXYZ)[[1, 2, 3, 0]]
    err = np.abs(np.abs(q @ q_want) - 1).max()
    check(err < 1e-6, f"world/vehicle carries the 30 degree attitude (1 - |q.q_tilt| max "
                      f"{err:.2g})")


def check_static(rec, log):
    scene = log["UVMS_SCENE"]
    hull = rec["world/vehicle/hull"]
    check(not hull["time_ns"] and np.allclose(hull["static"]["Boxes3D:half_sizes"][0],
                                              np.asarray(scene["hull_size_m"][0]) / 2),
          "hull: static box with the scene's size")
    ob = rec.get("world/obstacles/chimney", {"static": {}, "time_ns": [1]})
    st = ob["static"]
    ok = (not ob["time_ns"] and np.isclose(st.get("Cylinders3D:radii", [0])[0], 0.3)
          and np.allclose(st.get("Cylinders3D:centers", [[0] * 3])[0], [2.5, 0, -1.25])
          and np.isclose(st.get("Cylinders3D:lengths", [0])[0], 1.5))
    check(ok, f"obstacle chimney: static cylinder r 0.3 m, 1.5 m high on (2.5, 0, -2) ({st})")


def check_contact(rec, log):
    """A run ended by contact: markers at the breach ticks, the end reason logged."""
    tr, st = log["UVMS_TRUTH"], log["UVMS_STATUS"]
    reason = str(st["reason"][-1])
    from uvms.run_status_t import run_status_t  # generated; on sys.path after runlog.load
    check(int(st["code"][-1]) == run_status_t.CONTACT and "pole" in reason,
          f"the pole run ends by contact ({reason})")
    hits = tr["log_utime"][tr["min_clearance_m"] <= float(log["UVMS_SCENE"]["clearance_m"][0])]
    got = rec.get("world/contact", {"time_ns": []})["time_ns"]
    check(len(hits) > 0 and np.array_equal(np.unique(got), hits * 1000),
          f"world/contact markers at the {len(hits)} ticks with min_clearance_m <= clearance")
    texts = [t[0] for t in rec.get("log/contact", {}).get("TextLog:text", [])]
    check(any(reason in t for t in texts), "log/contact carries the end-of-run reason")
    status = rec.get("log/status", {})
    check(status.get("TextLog:level") == [["ERROR"]] and reason in status["TextLog:text"][0][0],
          f"log/status: ERROR with the reason ({status.get('TextLog:text')})")


def check_without_scene(run_dir, expected):
    old = os.path.join(TMP, "old.lcmlog")
    full = os.path.join(run_dir, "run.lcmlog")  # without UVMS_SCENE, as before scene_t
    copy_channels(full, old, set(runlog.load(full)) - {"UVMS_SCENE"})
    rrd = os.path.join(TMP, "old.rrd")
    rec, p = convert(old, rrd)
    check(p.stderr.count("uvmsviz: note: no UVMS_SCENE") == 1, f"without UVMS_SCENE: one note "
                                                               f"({p.stderr.strip()[:200]})")
    absent = {"world/vehicle/hull", "world/arm/mount", "world/obstacles/chimney", "world/contact",
              "log/contact"}  # no hull: no mount strut from it either
    check_paths(rec, expected, absent, "without UVMS_SCENE")
    missing = sorted(set(REQUIRED) - absent - set(rec))
    check(not missing, f"without UVMS_SCENE: the required paths but hull and obstacle are in "
                       f"the file (missing: {missing})")


def copy_channels(src_log, dst_log, keep):
    """Copy of a log with only the events of the channels in `keep`."""
    src, dst = lcm.EventLog(src_log, "r"), lcm.EventLog(dst_log, "w", overwrite=True)
    for ev in src:
        if ev.channel in keep:
            dst.write_event(ev.timestamp, ev.channel, ev.data)
    src.close()
    dst.close()


def check_bad_input(run_dir):
    text = os.path.join(TMP, "notes.txt")
    with open(text, "w") as fh:
        fh.write("not a log\n" * 100)
    foreign = os.path.join(TMP, "foreign.lcmlog")
    ev = lcm.EventLog(foreign, "w", overwrite=True)
    ev.write_event(0, "SOMETHING_ELSE", b"\0" * 16)
    ev.close()
    config_only = os.path.join(TMP, "config_only.lcmlog")
    copy_channels(os.path.join(run_dir, "run.lcmlog"), config_only, {"UVMS_CONFIG"})
    for arg, what in ((os.path.join(TMP, "missing"), "missing directory"),
                      (TMP, "directory without run.lcmlog"), (text, "text file"),
                      (foreign, "log without UVMS messages"),
                      (config_only, "log without UVMS_TRUTH")):
        p = viz(arg, "--out", os.path.join(TMP, "bad.rrd"))
        lines = p.stderr.strip().splitlines()
        check(p.returncode == 1 and len(lines) == 1 and lines[0].startswith("uvmsviz: error: ")
              and not os.path.exists(os.path.join(TMP, "bad.rrd")),
              f"{what}: exit 1, one error line ({p.returncode}: {p.stderr.strip()[:160]})")
    for out, what in ((os.path.join(TMP, "no", "x.rrd"), "in a missing directory"),
                      (TMP, "an existing directory")):
        p = viz(run_dir, "--out", out)
        check(p.returncode == 1 and p.stderr.startswith(f"uvmsviz: error: {out}: ")
              and len(p.stderr.strip().splitlines()) == 1 and not p.stdout,
              f"--out {what}: exit 1, one error line ({p.stderr.strip()[:200]})")
    p = viz(text, "--out", os.path.join(TMP, "no", "x.rrd"))
    check(p.returncode == 1 and p.stderr.startswith(f"uvmsviz: error: {TMP}/no/x.rrd: "),
          f"a bad --out fails before the log is read ({p.stderr.strip()[:200]})")
    p = viz("--help")
    check(p.returncode == 0 and "--every" in p.stdout and not p.stderr, "--help: help, exit 0")
    p = viz(TMP, "--every", "0")
    check(p.returncode == 2 and "--every" in p.stderr, "--every 0: usage error (exit 2)")


def steps():
    chimney = run("chimney", CHIMNEY)
    log_file = os.path.join(chimney, "run.lcmlog")
    expected, log = expected_paths(chimney)
    rec, _ = convert(chimney, os.path.join(TMP, "chimney.rrd"), "--name", "chimney")
    n_bp = len(RrdReader(os.path.join(TMP, "chimney.rrd")).blueprints())
    check(n_bp == 1, f"the file carries its blueprint (default layout) ({n_bp})")
    check("world/obstacles/chimney" in expected, "the table expands to the scene's obstacle")
    check_required(rec, "chimney run")
    check_paths(rec, expected, {"world/contact", "log/contact"}, "chimney run")
    check_samples(rec, log_file)
    check_values(rec, log)
    check_static(rec, log)
    check_tilted(chimney)
    rec, _ = convert(chimney, os.path.join(TMP, "every.rrd"), "--every", str(EVERY))
    check_samples(rec, log_file, math.ceil(log["UVMS_TRUTH"].count / EVERY))
    pole = run("pole", POLE)
    rec, _ = convert(pole, os.path.join(TMP, "pole.rrd"))
    check_contact(rec, runlog.load(os.path.join(pole, "run.lcmlog")))
    check_without_scene(chimney, expected)
    check_bad_input(chimney)


def main():
    return TALLY.run(steps, TMP)


if __name__ == "__main__":
    sys.exit(main())
