# SPDX-License-Identifier: Apache-2.0
"""tools/uvmslog.py on a freshly recorded short run: per-channel tick counts against the
summary, the final truth sample against the summary's final EE position, the SPEC §10 EE error
recomputed from the log against the plant's mean (an independent recomputation: Python from the
logged messages vs the C++ plant node's running sum), and the CLI (list, --plot, --csv, errors).
Component names (thrusters T1..T8, joints J1..J7, x/y/z, w/x/y/z, numbered from 1 as in SPEC)
against names written out here; CSV on stdout parsed by the csv module against load()'s arrays
(bit-exact); --plot FIELD.T3 against FIELD[2] and the raw array; run directories as LOG.
Every channel as CSV, of this run (no obstacles: empty obstacle fields) and of a run of the
chimney scene (one obstacle): every row as long as the header, and every cell equal to the
component its column names, parsed back with the names written out here (not the tool's table).
Errors: --out a directory, a channel the log lacks (the message lists the log's channels),
--plot --out not a .png or in a missing directory (one line naming it, nothing created),
--plot of an empty field. --help cites the repository's docs (no "SPEC", no build/lead).
load()'s one-pass reading of a small log against its two-pass reading (every channel, a subset;
a synthetic channel whose shape varies between messages, strings and byte text).

Usage: test_uvmslog.py UVMS_EXE SOURCE_DIR
"""
import csv
import io
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

UVMS, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tools"))
from uvms_tools.log import runlog  # noqa: E402

PY = sys.executable
TOOL = os.path.join(SRC, "tools", "uvmslog.py")
TMP = tempfile.mkdtemp(prefix="uvms-uvmslog-")
# The plant sums ε over ticks in double; numpy's sum and norm differ from it only by rounding
# (a few ulps per tick over 50 ticks), far below 1e-12 relative.
REL_TOL_MEAN = 1e-12
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

failures = []


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


out = os.path.join(TMP, "run")
cmd = [UVMS, "run", os.path.join(SRC, "sil/scenarios/paper/case_VII_stagnant.toml"),
       "--out", out, "--set", "run.duration_s=1.5", "--set", "trajectory.duration_s=1.5",
       "--transport", "memq"]
p = subprocess.run(cmd, capture_output=True, text=True)
check(p.returncode == 0, f"uvms run exits 0 ({p.returncode}: {p.stderr.strip()[-300:]})")
summary = json.load(open(os.path.join(out, "summary.json")))
n = summary["ticks"]
check(summary["status"] == "finished" and n == 50, f"run finished with 50 ticks ({n})")

log = runlog.load(os.path.join(out, "run.lcmlog"))
tm, tr = log["UVMS_TELEMETRY"], log["UVMS_TRUTH"]
check(log["UVMS_SENSORS"].count == n, f"UVMS_SENSORS: {log['UVMS_SENSORS'].count} == ticks")
check(log["UVMS_ACTUATORS"].count == n, f"UVMS_ACTUATORS: {log['UVMS_ACTUATORS'].count} == ticks")
check(int((tm["tick"] >= 0).sum()) == n and int((tm["tick"] == -1).sum()) == 1,
      "UVMS_TELEMETRY: one per tick plus the configuration acknowledgement (tick -1)")
check(tr.count == n + 1 and int(tr["tick"][-1]) == n, "UVMS_TRUTH: one per tick plus the final")
check(log["UVMS_CONFIG"].count == 1 and log["UVMS_STATUS"].count == 2,
      "UVMS_CONFIG once, UVMS_STATUS at start and end")
check(list(log["UVMS_SENSORS"]["tick"]) == list(range(n)), "sensor ticks are 0..n-1 in order")
tick_s = float(log["UVMS_CONFIG"]["tick_s"][0])
check(all(abs(t - k * tick_s) < 1e-6 for t, k in zip(tr["t_s"], tr["tick"])),
      "truth t_s == tick · tick_s (µs resolution)")
check((tr["log_utime"] == tr["utime"]).all(), "event timestamps == message utime (simulated time)")
check(tr["ee_position_m"].shape == (n + 1, 3) and tr["closest_pair"].dtype.kind == "U",
      "field shapes: ee_position_m (n, 3); strings as str")
check(log["UVMS_STATUS"]["state"][-1] == 2 and log["UVMS_STATUS"]["reason"][-1] == "",
      "final status FINISHED with an empty reason")

final = tr.select(tr["tick"] == n)["ee_position_m"][0]
check(list(final) == list(summary["final_ee_position_m"]),
      f"final truth ee_position_m {final.tolist()} == summary {summary['final_ee_position_m']}")

# EE error, twice: by hand from the raw messages (dict by tick, math.fsum) and by the helper.
est = {int(k): e for k, e in zip(tm["tick"], tm["ee_estimate_m"]) if k >= 0}
eps = [math.dist(p, est[int(k)]) for k, p in zip(tr["tick"], tr["ee_position_m"]) if int(k) in est]
mean_by_hand = math.fsum(eps) / len(eps)
ref = summary["mean_ee_error_m"]
check(len(eps) == n, f"{len(eps)} ticks have both truth and telemetry")
check(abs(mean_by_hand - ref) <= REL_TOL_MEAN * abs(ref),
      f"mean EE error from the log {mean_by_hand!r} vs summary {ref!r}")
_, _, eps2 = runlog.ee_error(log)
check(abs(eps2.mean() - ref) <= REL_TOL_MEAN * abs(ref), f"runlog.ee_error mean {eps2.mean()!r}")
check(abs(max(eps) - summary["max_ee_error_m"]) <= REL_TOL_MEAN * summary["max_ee_error_m"],
      "max EE error from the log == summary max")

# CLI.
lg = os.path.join(out, "run.lcmlog")
p = subprocess.run([PY, TOOL, lg], capture_output=True, text=True)
check(p.returncode == 0 and "UVMS_TRUTH  (truth_t): 51 messages" in p.stdout
      and "ee_position_m" in p.stdout and "[rad/s]" in p.stdout,
      "CLI listing names channels, counts, fields and units")
png = os.path.join(TMP, "fig.png")
p = subprocess.run([PY, TOOL, lg, "--plot", "UVMS_TRUTH.ee_position_m[0]", "--plot",
                    "UVMS_TELEMETRY.force_des_N", "--plot", "UVMS_TRUTH.motor_speed_rad_s",
                    "--out", png], capture_output=True, text=True)
check(p.returncode == 0 and os.path.getsize(png) > 1000 and open(png, "rb").read(8) == PNG_MAGIC,
      f"--plot writes a PNG ({p.stderr.strip()[-200:]})")
csv_path = os.path.join(TMP, "truth.csv")
p = subprocess.run([PY, TOOL, lg, "--csv", "UVMS_TRUTH", "--out", csv_path],
                   capture_output=True, text=True)
rows = open(csv_path).read().splitlines() if p.returncode == 0 else []
check(len(rows) == n + 2 and "ee_position_m.z" in rows[0].split(","),
      "--csv writes a header and one row per message")
last = dict(zip(rows[0].split(","), rows[-1].split(","))) if rows else {}
check(float(last.get("ee_position_m.x", "nan")) == final[0], "CSV values round-trip exactly")
p = subprocess.run([PY, TOOL, lg, "--plot", "UVMS_TRUTH.no_such_field", "--out", png],
                   capture_output=True, text=True)
check(p.returncode == 1 and "no_such_field" in p.stderr and "ee_position_m" in p.stderr,
      "an unknown field is an error naming it and listing the fields")

# Component names: written out here from SPEC's numbering, not from the tool's table.
XYZ, THRUSTERS = ["x", "y", "z"], [f"T{j}" for j in range(1, 9)]
JOINTS = [f"J{i}" for i in range(1, 8)]
check(runlog.component_labels("UVMS_TRUTH", "thrust_N", (8,)) == THRUSTERS
      and runlog.component_labels("UVMS_TRUTH", "joint_position_rad", (7,)) == JOINTS
      and runlog.component_labels("UVMS_TRUTH", "position_m", (3,)) == XYZ
      and runlog.component_labels("UVMS_TRUTH", "quaternion_wxyz", (4,)) == ["w", "x", "y", "z"]
      and runlog.component_labels("UVMS_TRUTH", "t_s", ()) == [],
      "component names: T1..T8, J1..J7, x y z, w x y z; none for a scalar")
check(runlog.component_labels("UVMS_CONFIG", "link_com_m", (7, 3))
      == [f"{j}.{c}" for j in JOINTS for c in XYZ]
      and runlog.component_labels("UVMS_CONFIG", "thruster_position_m", (8, 3))
      == [f"{t}.{c}" for t in THRUSTERS for c in XYZ],
      "component names of [7][3] and [8][3]: J1.x ... J7.z, T1.x ... T8.z (row-major)")
mam = runlog.component_labels("UVMS_CONFIG", "added_mass_coeff", (36,))
check(len(mam) == 36 and mam[0] == "r1c1" and mam[7] == "r2c2" and mam[11] == "r2c6"
      and mam[35] == "r6c6", "added_mass_coeff: r1c1 ... r6c6, row-major 6x6")

# CSV on stdout: nothing but CSV; every value bit-exact against load().
p = subprocess.run([PY, TOOL, lg, "--csv", "UVMS_TRUTH", "--out", "-"], capture_output=True,
                   text=True)
table = list(csv.reader(io.StringIO(p.stdout)))
check(p.returncode == 0 and p.stderr == "" and "wrote" not in p.stdout
      and len(table) == tr.count + 1, f"--out -: a header and {tr.count} rows on stdout only")
header = table[0] if table else []
check(all(f"thrust_N.{t}" in header for t in THRUSTERS)
      and all(f"position_m.{c}" in header for c in XYZ)
      and [h for h in header if h.startswith("quaternion_wxyz.")]
      == [f"quaternion_wxyz.{c}" for c in "wxyz"],
      "CSV header: thrust_N.T1..T8, position_m.x/y/z, quaternion_wxyz.w/x/y/z")
expected_cols = ["t_s", "log_utime"] + [f for f in tr.fields if tr[f].ndim == 1] + [
    f"{f}.{k}" for f in tr.fields if tr[f].ndim > 1 for k in (
        THRUSTERS if tr[f].shape[1] == 8 else JOINTS if tr[f].shape[1] == 7 else
        ["w", "x", "y", "z"] if tr[f].shape[1] == 4 else XYZ)]
check(sorted(header) == sorted(expected_cols), "CSV: one column per component, no other")
col = {h: i for i, h in enumerate(header)}


def column_values(h):
    """load()'s values of CSV column h (FIELD or FIELD.LABEL), by the names written out here."""
    field, _, label = h.partition(".")
    a = tr[field]
    if not label:
        return a
    names = {8: THRUSTERS, 7: JOINTS, 4: ["w", "x", "y", "z"], 3: XYZ}[a.shape[1]]
    return a[:, names.index(label)] if label in names else None  # None: a wrong name


rows_csv = table[1:]
bad = [h for h in header if column_values(h) is None or (column_values(h).dtype.kind == "f"
       and [float(r[col[h]]) for r in rows_csv] != column_values(h).tolist())]
check(header and not bad, f"every float column bit-exact via float(repr) ({bad[:3]})")
check(header and [int(r[col["tick"]]) for r in rows_csv] == tr["tick"].tolist()
      and [r[col["closest_pair"]] for r in rows_csv] == tr["closest_pair"].tolist(),
      "integer and string columns (closest_pair, through the csv module) equal load()'s")
p2 = subprocess.run([PY, TOOL, out, "--csv", "UVMS_TRUTH"], capture_output=True, text=True)
check(p2.returncode == 0 and p2.stdout == p.stdout,
      "--csv without --out writes the same CSV to stdout; a run directory works as LOG")

# --plot FIELD.T3 (thruster 3, numbered from 1) selects what FIELD[2] (0-based) does.
t3, y3, lab3 = runlog.plot_series(log, "UVMS_TRUTH.thrust_N.T3")
t2, y2, lab2 = runlog.plot_series(log, "UVMS_TRUTH.thrust_N[2]")
ticks_ok = tr["tick"] >= 0
check(y3.shape == (int(ticks_ok.sum()), 1) and (y3[:, 0] == tr["thrust_N"][ticks_ok, 2]).all()
      and (y3 == y2).all() and (t3 == t2).all() and lab3 == lab2 == ["thrust_N.T3"],
      "--plot thrust_N.T3 == thrust_N[2] == the raw column 2; legend thrust_N.T3")
_, yj, labj = runlog.plot_series(log, "UVMS_CONFIG.link_com_m.J2", True)
check(labj == ["link_com_m.J2.x", "link_com_m.J2.y", "link_com_m.J2.z"]
      and (yj == log["UVMS_CONFIG"]["link_com_m"][:, 1, :]).all(),
      "--plot link_com_m.J2 selects joint 2's row of [7][3]")
p = subprocess.run([PY, TOOL, out, "--plot", "UVMS_TRUTH.thrust_N.T3", "--plot",
                    "UVMS_TRUTH.quaternion_wxyz.w", "--out", png], capture_output=True, text=True)
check(p.returncode == 0 and open(png, "rb").read(8) == PNG_MAGIC, "--plot with labels: a PNG")
p = subprocess.run([PY, TOOL, lg, "--plot", "UVMS_TRUTH.thrust_N.T9", "--out", png],
                   capture_output=True, text=True)
check(p.returncode == 1 and len(p.stderr.strip().splitlines()) == 1 and "T8" in p.stderr,
      f"--plot thrust_N.T9: a one-line error naming the components ({p.stderr.strip()})")



# Every channel as CSV, parsed back. Column names by SPEC's numbering, written out here.
ALL_CHANNELS = ["UVMS_ACTUATORS", "UVMS_CONFIG", "UVMS_SCENE", "UVMS_SENSORS", "UVMS_STATUS",
                "UVMS_TELEMETRY", "UVMS_TRUTH"]


def component_index(field, label):
    """0-based index of a component name: T<j>, J<i>, O<k> numbered from 1; x, y, z (w, x, y, z
    of quaternion_wxyz); r<R>c<C> of a row-major 6x6; [i] 0-based. None for an unknown name."""
    idx = []
    for part in re.findall(r"\[\d+\]|[^.\[]+", label):
        m = re.fullmatch(r"[TJO](\d+)|r([1-6])c([1-6])|\[(\d+)\]|([wxyz])", part)
        axis = "wxyz" if field == "quaternion_wxyz" else "xyz"
        if m is None or (m[5] and m[5] not in axis):
            return None
        if m[1]:
            idx.append(int(m[1]) - 1)
        elif m[2]:
            idx.append(6 * (int(m[2]) - 1) + int(m[3]) - 1)
        elif m[4]:
            idx.append(int(m[4]))
        else:
            idx.append(axis.index(m[5]))
    return tuple(idx)


def cell_matches(cell, v):
    """A CSV cell against load()'s value: floats bit-exact, integers and strings equal."""
    if isinstance(v, (float, np.floating)):
        return float(cell) == float(v) or (math.isnan(float(cell)) and math.isnan(float(v)))
    if isinstance(v, (int, np.integer)):
        return int(cell) == int(v)
    return cell == str(v)


def csv_problems(lg_, channel):
    """What is wrong with `channel` of lg_ as CSV (write_csv, read back by the csv module)."""
    ch = lg_[channel]
    path = os.path.join(TMP, f"{channel}.csv")
    runlog.write_csv(lg_, channel, path)
    with open(path, newline="") as fh:
        head, *body = list(csv.reader(fh))
    bad = [f"row {i}: {len(r)} cells, {len(head)} names" for i, r in enumerate(body)
           if len(r) != len(head)]
    ragged = bool(bad)
    want = {(f, i) for f in ["t_s", "log_utime"] + ch.fields for i in np.ndindex(ch[f].shape[1:])}
    got = []
    for k, h in enumerate(head):
        field, label = re.match(r"(\w+)\.?(.*)", h).groups()
        idx = component_index(field, label) if field in ch else None
        got.append((field, idx))
        if idx is None or (field, idx) not in want:
            bad.append(f"column {h}: names no component")
        elif not ragged and not all(cell_matches(r[k], ch[field][(i,) + idx])
                                 for i, r in enumerate(body)):
            bad.append(f"column {h}: values are not {field}{list(idx)}")
    if sorted(map(str, got)) != sorted(map(str, want)) or len(body) != ch.count:
        bad.append(f"columns != components ({len(got)} vs {len(want)}) or rows != messages")
    return bad

chimney = os.path.join(TMP, "chimney")
p = subprocess.run([UVMS, "run", os.path.join(SRC, "sil/scenarios/scene/vent_chimney_VII.toml"),
                    "--out", chimney, "--set", "run.duration_s=0.3", "--transport", "memq"],
                   capture_output=True, text=True)
check(p.returncode == 0, f"uvms run of the chimney scene exits 0 ({p.stderr.strip()[-200:]})")
logs = {"no obstacles": log, "one obstacle": runlog.load(chimney) if p.returncode == 0 else {}}
for what, lg_ in logs.items():
    check(sorted(lg_) == ALL_CHANNELS, f"{what}: the log has the channels {ALL_CHANNELS}")
    for channel in sorted(lg_):
        bad = csv_problems(lg_, channel)
        check(not bad, f"{what}: --csv {channel}: header == every row's length, every column "
                       f"== the component it names ({bad[:3]})")


def same_arrays(a, b):
    """Two loads' channels field by field: the same names, order, dtypes, shapes and values."""
    def same(x, y):
        if x.dtype == object:
            return y.dtype == object and x.shape == y.shape and all(
                list(u) == list(v) for u, v in zip(x, y))
        return x.dtype == y.dtype and x.shape == y.shape and np.array_equal(
            x, y, equal_nan=x.dtype.kind == "f")
    return (list(a) == list(b) and a.skipped == b.skipped
            and a.all_channels == b.all_channels and all(
        list(a[c]) == list(b[c]) and a[c].type_name == b[c].type_name
        and all(same(a[c][k], b[c][k]) for k in a[c]) for c in a))


# load() reads a small file once (the messages held, each field converted at once) and a large
# one twice (FieldShapes, then Columns filled message by message): the same arrays.
for what, path_ in (("no obstacles", out), ("one obstacle", chimney)):
    for keep in (None, ["UVMS_TRUTH", "UVMS_SCENE"]):
        once = runlog.load(path_, keep)
        saved, runlog.ONE_PASS_MAX_BYTES = runlog.ONE_PASS_MAX_BYTES, -1
        try:
            twice = runlog.load(path_, keep)
        finally:
            runlog.ONE_PASS_MAX_BYTES = saved
        check(same_arrays(once, twice), f"{what}, channels {keep}: one pass == two passes")
# Synthetic channels through both paths (FieldShapes + Columns, message by message, against
# channel_from_messages): a shape that varies between messages, an empty first array, a field
# empty in every message, 2-D numbers, NaN, booleans, ints, strings and byte text.
FIELDS = ["vary", "late", "none", "grid", "nan", "flag", "count", "name", "raw"]
Msg = type("Msg", (), {"__slots__": FIELDS})
ROWS = [
    ([1.0, 2.0], [], [], [[1.0, 2.0], [3.0, 4.0]], float("nan"), True, 7, "a", b"ab\0"),
    ([3.0], [1.0], [], [[5.0, 6.0], [7.0, 8.0]], 1.5, False, -2, "bcd", b"c\0\0"),
    ([], [2.0], [], [[9.0, 0.5], [0.25, 1.0]], 2.5, True, 0, "", b"\0\0\0"),
]
msgs = []
for row in ROWS:
    m = Msg()
    for f, v in zip(FIELDS, row):
        setattr(m, f, v)
    msgs.append(m)
shapes = runlog.FieldShapes(Msg)
for m in msgs:
    shapes.observe(m)
cols = runlog.Columns("C", shapes, len(msgs))
for i, m in enumerate(msgs):
    cols.add(m, i)
ref = cols.channel()
got = runlog.channel_from_messages("C", Msg, msgs, list(range(len(msgs))))
syn = runlog.Log("synthetic")
syn["C"], ref_log = got, runlog.Log("synthetic")
ref_log["C"] = ref
check(same_arrays(syn, ref_log) and got["vary"].dtype == object and got["late"].dtype == object
      and got["none"].shape == (3, 0) and got["grid"].shape == (3, 2, 2)
      and got["flag"].dtype == np.bool_ and got["count"].dtype == np.int64
      and list(got["raw"]) == ["ab", "c", ""],
      "synthetic channel (varying and empty arrays, 2-D, NaN, bool, int, str, byte): both "
      "paths alike")

n_obs = {w: int(lg_["UVMS_SCENE"]["num_obstacles"][0]) for w, lg_ in logs.items() if lg_}
check(n_obs == {"no obstacles": 0, "one obstacle": 1}, f"scene obstacles {n_obs}")
if logs["one obstacle"]:
    scene_head = runlog.csv_columns(logs["one obstacle"]["UVMS_SCENE"])[0]
    check([h for h in scene_head if h.startswith("obstacle_")]
          == ["obstacle_name.O1"] + [f"obstacle_base_center_m.O1.{c}" for c in XYZ]
          + ["obstacle_height_m.O1", "obstacle_radius_m.O1"],
          "one obstacle: columns obstacle_name.O1, obstacle_base_center_m.O1.x/y/z, ...")
p = subprocess.run([PY, TOOL, out, "--csv", "UVMS_SCENE"], capture_output=True, text=True)
table = list(csv.reader(io.StringIO(p.stdout)))
check(p.returncode == 0 and len(table) == 2 and len(table[0]) == len(table[1])
      and dict(zip(*table)).get("crc32") == str(log["UVMS_SCENE"]["crc32"][0])
      and not any(h.startswith("obstacle_") for h in table[0]),
      "CLI --csv UVMS_SCENE without obstacles: no obstacle columns, crc32 under its name")

# Output errors: one line, exit 1, no traceback.
p = subprocess.run([PY, TOOL, out, "--csv", "UVMS_TRUTH", "--out", TMP], capture_output=True,
                   text=True)
check(p.returncode == 1 and p.stderr.startswith("uvmslog: error:") and TMP in p.stderr
      and len(p.stderr.strip().splitlines()) == 1, f"--csv --out DIR: {p.stderr.strip()[-200:]}")
p = subprocess.run([PY, TOOL, out, "--csv", "UVMS_NOPE"], capture_output=True, text=True)
check(p.returncode == 1 and len(p.stderr.strip().splitlines()) == 1 and "UVMS_NOPE" in p.stderr
      and all(c in p.stderr for c in ALL_CHANNELS),
      f"--csv of a missing channel lists the log's channels ({p.stderr.strip()})")
pdf = os.path.join(TMP, "fig.pdf")
p = subprocess.run([PY, TOOL, out, "--plot", "UVMS_TRUTH.thrust_N", "--out", pdf],
                   capture_output=True, text=True)
check(p.returncode == 1 and len(p.stderr.strip().splitlines()) == 1 and ".png" in p.stderr
      and not os.path.exists(pdf), f"--plot --out fig.pdf: an error, no file ({p.stderr.strip()})")
missing_dir = os.path.join(TMP, "no_such_dir")
p = subprocess.run([PY, TOOL, out, "--plot", "UVMS_TRUTH.thrust_N", "--out",
                    os.path.join(missing_dir, "fig.png")], capture_output=True, text=True)
check(p.returncode == 1 and p.stderr.startswith("uvmslog: error: --out")
      and len(p.stderr.strip().splitlines()) == 1 and f"no directory {missing_dir}" in p.stderr
      and "Errno" not in p.stderr and not os.path.exists(missing_dir),
      f"--plot --out in a missing directory: one line naming it ({p.stderr.strip()})")
p = subprocess.run([PY, TOOL, "--help"], capture_output=True, text=True)
check(p.returncode == 0 and "SPEC" not in p.stdout and "build/lead" not in p.stdout
      and "build/host" in p.stdout and "UVMS_LCM_PYTHON_PATH" in p.stdout
      and "docs/MODEL.md" in p.stdout,
      "--help: cites docs/MODEL.md (no SPEC), types from $UVMS_LCM_PYTHON_PATH or build/host")
p = subprocess.run([PY, TOOL, out, "--plot", "UVMS_SCENE.obstacle_radius_m", "--all-ticks",
                    "--out", png], capture_output=True, text=True)
check(p.returncode == 1 and len(p.stderr.strip().splitlines()) == 1 and "empty" in p.stderr,
      f"--plot of an empty field: a one-line error ({p.stderr.strip()})")

# Bad inputs: one-line errors, exit 1.
empty_dir = os.path.join(TMP, "not_a_run")
os.makedirs(empty_dir)
junk = os.path.join(TMP, "junk.lcmlog")
with open(junk, "w") as fh:
    fh.write("not an LCM log\n")
for bad_in, what in ((empty_dir, "run.lcmlog"), (junk, "LCM"),
                     (os.path.join(TMP, "nope"), "no such")):
    p = subprocess.run([PY, TOOL, bad_in], capture_output=True, text=True)
    check(p.returncode == 1 and p.stdout == "" and p.stderr.startswith("uvmslog: error:")
          and len(p.stderr.strip().splitlines()) == 1 and what in p.stderr,
          f"bad LOG {os.path.basename(bad_in)}: {p.stderr.strip()}")

# Without generated types anywhere: a clear error that says where it looked.
iso = os.path.join(TMP, "iso", "tools")
os.makedirs(iso)
shutil.copy(os.path.join(SRC, "tools", "uvmslog.py"), iso)
shutil.copytree(os.path.join(SRC, "tools", "uvms_tools"), os.path.join(iso, "uvms_tools"),
                ignore=shutil.ignore_patterns("__pycache__"))
env = {k: v for k, v in os.environ.items() if k not in ("UVMS_LCM_PYTHON_PATH", "PYTHONPATH")}
p = subprocess.run([PY, os.path.join(iso, "uvmslog.py"), lg], capture_output=True, text=True,
                   env=env)
check(p.returncode == 1 and "not found" in p.stderr and "UVMS_LCM_PYTHON_PATH" in p.stderr
      and "build/host" in p.stderr and "build/lead" not in p.stderr,
      f"missing types: clear error ({p.stderr.strip()[:160]})")

shutil.rmtree(TMP, ignore_errors=True)
print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
