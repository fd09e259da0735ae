# SPDX-License-Identifier: Apache-2.0
"""runlog: load a UVMS run log (LCM event log) into numpy arrays; list, plot, export.

A run log (`uvms run ... --out DIR` writes DIR/run.lcmlog) holds one LCM event per message;
the event timestamp is the simulated time in µs. `load()` reads it through log/records.py, which
checks every record first (framing, event numbers, each message's CRC-32, fingerprint and
length, one run in order, a complete log; a failure is a LogError naming the event and its
byte offset), decodes every event with the generated Python types (package `uvms`,
lcmtypes/*.lcm), chosen by each message's fingerprint, and stacks every field of every
channel into a numpy array whose first axis is the message index:

    from uvms_tools.log import runlog
    log = runlog.load("out/run/run.lcmlog")
    log["UVMS_TRUTH"]["ee_position_m"]      # (n, 3) float64 [m]
    log["UVMS_TRUTH"]["t_s"]                # (n,) simulated time from the message utime [s]
    log["UVMS_TRUTH"]["tick"]               # (n,) int64
    log["UVMS_TRUTH"]["log_utime"]          # (n,) event timestamps of the log [µs]
    eps = runlog.ee_error(log)              # docs/MODEL.md §10 EE error per tick

Channels (lcmtypes/): UVMS_CONFIG (controller_config_t, once), UVMS_SCENE (scene_t, once at
the start; logs of older builds have none), UVMS_SENSORS, UVMS_ACTUATORS,
UVMS_TELEMETRY (one per tick plus tick = -1, the configuration acknowledgement), UVMS_TRUTH
(one per tick plus a final sample with tick = number of ticks), UVMS_STATUS (start and end).
Strings become numpy str arrays; `byte` arrays (run_status_t.reason) become str; a
variable-length array whose length differs between messages becomes an object array of lists.
Wherever a log is expected, a run directory DIR stands for DIR/run.lcmlog.

Component names (component_labels, one table): the entries of array fields are named for
humans in the listing, the CSV header and plot legends: thrusters T1..T8 and joints J1..J7,
numbered from 1 as in docs/MODEL.md §3.4, §3.1 (sizes from the generated types'
NUM_THRUSTERS / NUM_JOINTS); vectors x, y, z; quaternion_wxyz w, x, y, z; [7][3] J1.x ...
J7.z; [8][3] T1.x ... T8.z; added_mass_coeff r1c1 ... r6c6 (row-major 6x6).

Finding the generated types: the directory in $UVMS_LCM_PYTHON_PATH (a PYTHONPATH-style list;
ctest sets it), else a `uvms` package already importable (e.g. via PYTHONPATH), else
build/host/lcmgen/python under the repo root. A directory counts if it holds uvms/truth_t.py;
if none does, load() raises LogError listing where it looked.

The command line is uvms_tools/uvmslog.py (tools/uvmslog.py; see --help; the listing and --csv
read the log one event at a time):
    tools/uvmslog.py LOG                                    channels, counts, fields, units
    tools/uvmslog.py LOG --plot UVMS_TRUTH.ee_position_m.x --plot UVMS_TRUTH.thrust_N.T3 \\
                         --plot UVMS_TELEMETRY.force_des_N --out fig.png
                                                            fields against simulated time
    tools/uvmslog.py LOG --csv UVMS_TRUTH [--out truth.csv] one row per message (stdout: -)
    tools/uvmslog.py RUN... --dashboard [--out FILE.png]    one page per run (dashboard/)
    tools/uvmslog.py CAMPAIGN_DIR --dashboard [-j N]        a page for every runs/*/

--plot takes CHANNEL.FIELD.LABEL (a component name, thrusters and joints from 1) or
CHANNEL.FIELD[IDX] (a 0-based array index): thrust_N.T3 and thrust_N[2] are thruster 3.

Interpreter: tools/uvmslog.py re-executes itself with REPO/.venv/bin/python (numpy, matplotlib
and lcm are pinned there, tools/requirements.txt), so `tools/uvmslog.py ...`,
`python3 tools/uvmslog.py ...` and `.venv/bin/python tools/uvmslog.py ...` all work (see
uvms_tools/env.py; UVMS_NO_REEXEC=1 uses the current interpreter as is).
"""
import csv
import importlib
import importlib.util
import os
import sys

import numpy as np

from uvms_tools.env import REPO_ROOT
from uvms_tools.log import records
from uvms_tools.log.records import LogDamage, LogError  # noqa: F401 (runlog.LogError, ...)

DEFAULT_TYPE_DIRS = ("build/host/lcmgen/python",)

# Message types per channel (sil/, lcmtypes/). Decoding does not rely on this table (it goes by
# fingerprint); it is used for messages and the listing.
CHANNEL_TYPES = {
    "UVMS_CONFIG": "controller_config_t",
    "UVMS_SENSORS": "sensors_t",
    "UVMS_ACTUATORS": "actuators_t",
    "UVMS_TELEMETRY": "telemetry_t",
    "UVMS_TRUTH": "truth_t",
    "UVMS_STATUS": "run_status_t",
    "UVMS_SCENE": "scene_t",
}
# Types a log may lack and a build may not generate yet (older logs and builds): skipped when
# their module is missing.
OPTIONAL_TYPES = ("scene_t",)

# Field-name unit suffixes (house style: units in names), longest first wins.
UNIT_SUFFIXES = [
    ("_Nm_s_rad", "N·m·s/rad"), ("_N_s_m", "N·s/m"), ("_Nm_rad", "N·m/rad"),
    ("_Nm_A", "N·m/A"), ("_Nm_s", "N·m·s"), ("_A_s", "A/s"), ("_rad_s2", "rad/s²"),
    ("_rad_s", "rad/s"),
    ("_m_s2", "m/s²"), ("_m_s", "m/s"), ("_kg_m3", "kg/m³"), ("_kg_m2", "kg·m²"),
    ("_1_s2", "1/s²"), ("_1_s", "1/s"), ("_N_m", "N/m"), ("_Nm", "N·m"), ("_ohm", "Ω"),
    ("_rad", "rad"), ("_deg", "deg"), ("_m3", "m³"), ("_m2", "m²"), ("_kg", "kg"),
    ("_N", "N"), ("_m", "m"), ("_s", "s"), ("_J", "J"), ("_V", "V"), ("_A", "A"),
    ("_H", "H"), ("_W", "W"),
]
SPECIAL_UNITS = {"utime": "µs", "log_utime": "µs", "t_s": "s", "tick": "-",
                 "quaternion_wxyz": "-"}


def unit_of(field):
    """Unit of a field from its name's suffix (SPEC/house style), '-' when it has none."""
    if field in SPECIAL_UNITS:
        return SPECIAL_UNITS[field]
    for suffix, unit in UNIT_SUFFIXES:
        if field.endswith(suffix):
            return unit
    return "-"


def type_dirs(env=None, with_defaults=True):
    """Candidate directories of the generated `uvms` Python package, in search order:
    $UVMS_LCM_PYTHON_PATH, then (with_defaults) build/host under the repo."""
    env = os.environ if env is None else env
    dirs = []
    if env.get("UVMS_LCM_PYTHON_PATH"):
        dirs += [d for d in env["UVMS_LCM_PYTHON_PATH"].split(os.pathsep) if d]
    if with_defaults:
        dirs += [os.path.join(REPO_ROOT, d) for d in DEFAULT_TYPE_DIRS]
    return dirs


_TYPES = None
TYPES_DIR = None  # where lcm_types() found the generated package


def lcm_types():
    """{packed fingerprint (8 bytes): class} of every generated uvms type; imports them once."""
    global _TYPES, TYPES_DIR
    if _TYPES is not None:
        return _TYPES
    found = next((d for d in type_dirs(with_defaults=False)
                  if os.path.exists(os.path.join(d, "uvms", "truth_t.py"))), None)
    if found is None:  # already importable (e.g. PYTHONPATH)? then use that package
        spec = importlib.util.find_spec("uvms")
        if spec is not None and spec.submodule_search_locations and any(
                os.path.exists(os.path.join(p, "truth_t.py"))
                for p in spec.submodule_search_locations):
            found = os.path.dirname(list(spec.submodule_search_locations)[0])
    if found is None:
        found = next((d for d in type_dirs()
                      if os.path.exists(os.path.join(d, "uvms", "truth_t.py"))), None)
    if found is None:
        raise LogError(
            "generated LCM Python types (package uvms) not found; looked in: "
            + ", ".join(type_dirs())
            + ". Build the project (cmake --build build/host) or set UVMS_LCM_PYTHON_PATH "
              "to the build's lcmgen/python directory.")
    if found not in sys.path:
        sys.path.insert(0, found)
    types = {}
    for name in sorted(set(CHANNEL_TYPES.values())):
        try:
            cls = getattr(importlib.import_module("uvms." + name), name)
        except ImportError:
            if name in OPTIONAL_TYPES:
                continue
            raise
        types[cls._get_packed_fingerprint()] = cls
    _TYPES = types
    TYPES_DIR = found
    return types


def _value_shape(v):
    """(shape, first leaf) of one message's value of a field: () and the value for a scalar or
    a string; the nested lengths for an array (leaf None when it is empty)."""
    if isinstance(v, (str, bytes, bytearray)):
        return (), v
    shape = []
    while isinstance(v, (list, tuple)):
        shape.append(len(v))
        if not v:
            return tuple(shape), None
        v = v[0]
    return tuple(shape), v


def _leaf_kind(leaf):
    if isinstance(leaf, str):
        return "str"
    if isinstance(leaf, (bytes, bytearray)):  # lcm `byte x[n]` decodes to bytes
        return "bytes"
    if isinstance(leaf, bool):
        return "bool"
    return "int" if isinstance(leaf, int) else "float"


NUMERIC_DTYPES = {"float": np.float64, "int": np.int64, "bool": np.bool_}


def byte_text(v):
    """A `byte` array as str: up to its first NUL, UTF-8 (damage: replacement characters)."""
    return bytes(v).split(b"\0", 1)[0].decode("utf-8", "replace")


class FieldShapes:
    """Per field of one channel's messages, seen one message at a time: the shape of its value
    (or that it varies between messages), its kind (str, bytes, bool, int, float) and, for
    the listing, the longest text. Decides each field's numpy array: numbers stacked with a
    first axis per message; strings and `byte` arrays as str; a shape that varies as an object
    array of lists."""

    def __init__(self, cls):
        self.cls = cls
        self.fields = list(cls.__slots__)
        self.count = 0
        self.first, self.kind, self.text_len = {}, {}, {}
        self.varies = set()
        self.tick_range = self.utime_range = None

    def observe(self, msg):
        self.count += 1
        for f in self.fields:
            v = getattr(msg, f)
            shape, leaf = _value_shape(v)
            if self.first.setdefault(f, shape) != shape:
                self.varies.add(f)
            if leaf is not None:
                kind = self.kind.setdefault(f, _leaf_kind(leaf))
                if kind in ("str", "bytes"):
                    n = max(len(t) for t in _texts(v, kind))
                    self.text_len[f] = max(self.text_len.get(f, 1), n)
        for name, attr in (("tick_range", "tick"), ("utime_range", "utime")):
            x = getattr(msg, attr, None)
            if x is not None:
                lo, hi = getattr(self, name) or (x, x)
                setattr(self, name, (min(lo, x), max(hi, x)))

    def column(self, f):
        """(kind, per-message shape, dtype) of field f's array: kind num, str, bytes or obj."""
        if f in self.varies:
            return "obj", (), object
        kind = self.kind.get(f, "float")  # only empty arrays: float64, as numpy has it
        if kind in ("str", "bytes"):
            return kind, self.first[f], None
        return "num", self.first[f], NUMERIC_DTYPES[kind]

    def dtype_text(self, f):
        """The numpy dtype load() gives field f, as the listing prints it."""
        kind, _, dtype = self.column(f)
        if kind == "obj":
            return "object"
        if kind in ("str", "bytes"):
            return f"<U{self.text_len.get(f, 1)}"
        return str(np.dtype(dtype))


def _texts(v, kind):
    """The strings of one value (a string, a `byte` array, or an array of strings)."""
    if kind == "bytes":
        return [byte_text(v)]
    if isinstance(v, str):
        return [v]
    out = []
    stack = [v]
    while stack:
        x = stack.pop()
        if isinstance(x, str):
            out.append(x)
        else:
            stack.extend(x)
    return out or [""]


class Columns:
    """Arrays of one channel's messages, filled one message at a time (add), with room for
    `capacity` messages: numbers go straight into preallocated arrays, so a channel takes the
    size of its numbers, not of Python objects."""

    def __init__(self, name, shapes, capacity):
        self.name, self.type_name, self.capacity, self.n = name, shapes.cls.__name__, capacity, 0
        self.cols = []
        for f in shapes.fields:
            kind, shape, dtype = shapes.column(f)
            if kind == "num":
                store = np.empty((capacity,) + shape, dtype)
            elif kind == "obj":
                store = np.empty(capacity, dtype=object)
            else:
                store = [None] * capacity
            self.cols.append((f, kind, store))
        self.stamps = np.empty(capacity, dtype=np.int64)

    def add(self, msg, stamp):
        i = self.n
        for f, kind, store in self.cols:
            v = getattr(msg, f)
            store[i] = list(v) if kind == "obj" else v
        self.stamps[i] = stamp
        self.n += 1

    def channel(self):
        """The filled rows as a Channel (with log_utime and t_s)."""
        n = self.n
        c = Channel(self.name, self.type_name)
        for f, kind, store in self.cols:
            if kind == "str":
                c[f] = np.array(store[:n], dtype=str)
            elif kind == "bytes":
                c[f] = np.array([byte_text(v) for v in store[:n]], dtype=str)
            else:
                c[f] = store[:n]
        return c.with_times(self.stamps[:n])


def _field_column(values):
    """One field's array over the held messages of a channel (the one-pass load): what Columns,
    filled one message at a time after FieldShapes saw them all, gives. Numbers: numpy converts
    them in one call (a shape that differs between messages fails it or changes the result's
    shape: an object array of lists); strings and `byte` arrays: str."""
    n = len(values)
    first, leaf = _value_shape(values[0])
    for v in values if leaf is None else ():
        leaf = _value_shape(v)[1]
        if leaf is not None:
            break
    kind = "float" if leaf is None else _leaf_kind(leaf)
    if kind in ("str", "bytes"):
        if any(_value_shape(v)[0] != first for v in values):
            return _object_column(values)
        if kind == "bytes":
            return np.array([byte_text(v) for v in values], dtype=str)
        return np.array(values, dtype=str)
    try:
        arr = np.array(values, dtype=NUMERIC_DTYPES[kind])
    except ValueError:  # ragged: the shape varies between messages
        return _object_column(values)
    return arr if arr.shape == (n,) + first else _object_column(values)


def _object_column(values):
    arr = np.empty(len(values), dtype=object)
    for i, v in enumerate(values):
        arr[i] = list(v)
    return arr


def channel_from_messages(name, cls, messages, stamps):
    """The Channel of one channel's held messages (the one-pass load), field by field."""
    c = Channel(name, cls.__name__)
    for f in cls.__slots__:
        c[f] = _field_column([getattr(m, f) for m in messages])
    return c.with_times(np.array(stamps, dtype=np.int64))


class Channel(dict):
    """One channel: field name -> numpy array (first axis = message index), plus metadata."""

    def __init__(self, name, type_name):
        super().__init__()
        self.name = name
        self.type_name = type_name

    def with_times(self, log_utime):
        """Adds the log's stamps (log_utime [µs]) and, for a type with utime, t_s = utime [s];
        returns the channel."""
        self["log_utime"] = log_utime
        if "utime" in self:
            self["t_s"] = self["utime"] * 1e-6
        return self

    @property
    def count(self):
        return len(self["log_utime"])

    @property
    def fields(self):
        """The message's own fields (not the added t_s / log_utime), in declaration order."""
        return [f for f in self if f not in ("t_s", "log_utime")]

    def select(self, mask):
        """A new Channel with the messages where `mask` (bool or index array) holds."""
        out = Channel(self.name, self.type_name)
        for k, v in self.items():
            out[k] = v[mask]
        return out

    def at_ticks(self, ticks):
        """Rows for `ticks` (each must occur exactly once in this channel), in that order."""
        tick = self["tick"]
        order = np.argsort(tick, kind="stable")
        pos = np.searchsorted(tick[order], ticks)
        pos = np.clip(pos, 0, len(tick) - 1)
        idx = order[pos]
        if not np.array_equal(tick[idx], np.asarray(ticks)):
            raise LogError(f"{self.name}: some requested ticks are missing")
        return self.select(idx)


def unknown_type_text(channel, tally):
    """What the log holds on `channel` that no generated type decodes (finding it by
    fingerprint, event and byte offset), and what to do about it."""
    return (f"{channel}: {tally.count} messages of unknown type (skipped): fingerprint "
            f"{tally.detail}, first at {tally.where()}, matches no type generated in "
            f"{TYPES_DIR}; the log was written with different lcmtypes/*.lcm (set "
            f"UVMS_LCM_PYTHON_PATH to types generated from those)")


class Log(dict):
    """channel name -> Channel; `path`; `reading` (what the checked pass found:
    records.Reading); `skipped` (events not decoded per channel: other channels' and
    intact messages of unknown types); `all_channels` (every channel of the file, also those
    load() was told not to keep)."""

    def __init__(self, path, reading=None):
        super().__init__()
        self.path = path
        self.reading = reading
        self.skipped = {}
        self.all_channels = set()
        if reading is not None:
            for table in (reading.foreign, reading.unknown):
                for ch, t in table.items():
                    self.skipped[ch] = self.skipped.get(ch, 0) + t.count
            self.all_channels = set(reading.channels)

    def undecodable(self, channel):
        """The LogError for a channel whose messages are of a type no generated one matches
        (naming its fingerprint, the first such event and its byte offset), or None."""
        unknown = self.reading.unknown.get(channel) if self.reading is not None else None
        return None if unknown is None else LogError(
            f"{self.path}: {unknown_type_text(channel, unknown)}")

    def missing(self, channel):
        """The LogError for a channel the file does not have (listing the ones it has), or
        whose messages are of a type no generated one matches (undecodable)."""
        return self.undecodable(channel) or LogError(f"channel {channel} not in {self.path} (has: "
                        f"{', '.join(sorted(self.all_channels)) or 'no channels'})")


RUN_LOG_NAME = "run.lcmlog"  # the log of a run directory (`uvms run --out DIR`)


def log_path(path):
    """The log file `path` names: the file itself, or DIR/run.lcmlog for a run directory."""
    if os.path.isdir(path):
        inner = os.path.join(path, RUN_LOG_NAME)
        if not os.path.isfile(inner):
            raise LogError(f"{path}: a directory without {RUN_LOG_NAME} (not a run directory)")
        return inner
    if not os.path.isfile(path):
        raise LogError(f"{path}: no such log file or run directory")
    return path


# A log file up to this size is read once: its kept messages are held, decoded, until the arrays
# are made (their Python objects take about 6x the file's bytes); a larger one is read twice
# (load), holding only the arrays.
ONE_PASS_MAX_BYTES = 32 * 2**20


def scan_shapes(path, keep, until_damage=False):
    """The checked first pass over a log file: (Reading, {channel: FieldShapes} of the channels
    in `keep` (None: all)). Each kept message is decoded (its length checked) and dropped:
    memory does not grow with the log."""
    shapes = {}
    scan = records.Scan(path, lcm_types(), CHANNEL_TYPES, keep, until_damage)
    for ev, msg in scan:
        sh = shapes.get(ev.channel)
        if sh is None:
            sh = shapes[ev.channel] = FieldShapes(type(msg))
        sh.observe(msg)
    return scan.reading, shapes


def fill_pass(path, shapes, until_damage=False):
    """The second pass: (channel, message, event timestamp) of every message of the channels
    in `shapes`, decoded."""
    scan = records.Scan(path, lcm_types(), CHANNEL_TYPES, set(shapes), until_damage)
    for ev, msg in scan:
        yield ev.channel, msg, ev.stamp


def changed_while_read(path):
    return LogError(f"{path}: the file changed while it was read")


def load(path, channels=None, until_damage=False):
    """Decode the LCM event log at `path` (a log file or a run directory) into a Log.

    Every record is checked first (log/records.py: framing, event numbers, each message's CRC-32,
    fingerprint and length, one run in order, a complete log); a failed check is a LogError
    (LogDamage naming the event and its byte offset). until_damage: read the events before
    the first damage instead (log.reading.damage says what stopped it). Two passes: the
    checks and the arrays' shapes, then the arrays filled in place; memory is that of the
    kept channels' arrays. A file of up to ONE_PASS_MAX_BYTES is read once (its decoded
    messages held for the filling): the same arrays.

    channels: iterable of channel names to keep (default: all). Events of other channels
    and intact messages of unknown types are counted in `log.skipped`, not decoded.
    Each channel gets, besides its message fields, `log_utime` (event timestamps, µs) and
    `t_s` (the message's `utime` in s, the simulated time of the tick).
    A file without a single LCM event (empty, or not an LCM log) is a LogError.
    """
    path = log_path(path)
    keep = None if channels is None else set(channels)
    if os.path.getsize(path) <= ONE_PASS_MAX_BYTES:
        return _load_once(path, keep, until_damage)
    reading, shapes = scan_shapes(path, keep, until_damage)
    cols = {ch: Columns(ch, sh, sh.count) for ch, sh in shapes.items()}
    for channel, msg, stamp in fill_pass(path, shapes, until_damage):
        c = cols[channel]
        if c.n == c.capacity:
            raise changed_while_read(path)
        c.add(msg, stamp)
    log = Log(path, reading)
    for ch, c in cols.items():
        if c.n != c.capacity:
            raise changed_while_read(path)
        log[ch] = c.channel()
    return log


def _load_once(path, keep, until_damage):
    """load() of a file of up to ONE_PASS_MAX_BYTES: one checked pass, the kept messages held
    (decoded) per channel, then each channel's arrays made field by field."""
    scan = records.Scan(path, lcm_types(), CHANNEL_TYPES, keep, until_damage)
    held = {}
    for ev, msg in scan:
        msgs, stamps = held.setdefault(ev.channel, ([], []))
        msgs.append(msg)
        stamps.append(ev.stamp)
    log = Log(path, scan.reading)
    for ch, (msgs, stamps) in held.items():
        log[ch] = channel_from_messages(ch, type(msgs[0]), msgs, stamps)
    return log


def ee_error(log):
    """SPEC §10 EE error per tick: |truth ee_position_m − telemetry ee_estimate_m|, matched by
    tick (telemetry tick ≥ 0; ticks without both messages are left out).

    Returns (tick, t_s, eps_m) arrays. The run's mean EE error (summary.json) is eps_m.mean().
    """
    tr, tm = log["UVMS_TRUTH"], log["UVMS_TELEMETRY"]
    tm = tm.select(tm["tick"] >= 0)
    ticks = np.intersect1d(tr["tick"], tm["tick"])
    a, b = tr.at_ticks(ticks), tm.at_ticks(ticks)
    eps = np.linalg.norm(a["ee_position_m"] - b["ee_estimate_m"], axis=1)
    return ticks, a["t_s"], eps


# ----------------------------------------------------------------------------------------------
# Component names: the one table of how a human names each entry of an array field (listing,
# CSV header, plot legends, the dashboard). Thrusters and joints are numbered from 1 (SPEC; the
# report's "thruster j", j = 1..8); vector components are x, y, z; quaternions w, x, y, z.

# Axis kinds of the fields whose entries their lengths alone do not name (one kind per axis).
FIELD_AXES = {
    "quaternion_wxyz": ("wxyz",),
    "added_mass_coeff": ("6x6",),  # Ma0, row-major 6x6 (controller_config_t)
    "obstacle_name": ("obstacle",),
    "obstacle_base_center_m": ("obstacle", "xyz"),
    "obstacle_height_m": ("obstacle",),
    "obstacle_radius_m": ("obstacle",),
}


def array_sizes():
    """(NUM_THRUSTERS, NUM_JOINTS): the array sizes the generated types declare (actuators_t)."""
    lcm_types()
    from uvms.actuators_t import actuators_t
    return actuators_t.NUM_THRUSTERS, actuators_t.NUM_JOINTS


def axis_kind(field, axis, n):
    """Kind of axis `axis` (length n) of one message's value of `field`: FIELD_AXES, else by
    length: NUM_THRUSTERS -> thruster, NUM_JOINTS -> joint, 3 -> xyz, else index."""
    kinds = FIELD_AXES.get(field)
    if kinds is not None and axis < len(kinds):
        return kinds[axis]
    num_thrusters, num_joints = array_sizes()
    return {num_thrusters: "thruster", num_joints: "joint", 3: "xyz"}.get(n, "index")


def axis_labels(kind, n):
    """Names of the n entries of an axis of `kind`; "[i]" (0-based index) when it has none."""
    if kind == "thruster":
        return [f"T{j}" for j in range(1, n + 1)]
    if kind == "joint":
        return [f"J{i}" for i in range(1, n + 1)]
    if kind == "obstacle":
        return [f"O{i}" for i in range(1, n + 1)]
    if kind == "xyz" and n == 3:
        return ["x", "y", "z"]
    if kind == "wxyz" and n == 4:
        return ["w", "x", "y", "z"]
    if kind == "6x6" and n == 36:
        return [f"r{r}c{c}" for r in range(1, 7) for c in range(1, 7)]
    return [f"[{i}]" for i in range(n)]


def join_label(*parts):
    """('T1', 'x') -> 'T1.x'; an index part attaches without a dot (('thrust_N', '[3]'))."""
    out = ""
    for p in parts:
        out += p if (not out or p.startswith("[")) else "." + p
    return out


def shape_labels(channel, field, shape):
    """Per-axis label lists of one message's value of `field` (shape without the message axis).
    The names are the same on every channel (the table above); `channel` is for messages."""
    del channel
    return [axis_labels(axis_kind(field, k, n), n) for k, n in enumerate(shape)]


def component_labels(channel, field, shape):
    """Names of the components of `field` of `channel` whose per-message shape is `shape`, in
    row-major order: thrust_N (8,) -> T1..T8; joint_position_rad (7,) -> J1..J7; 3-vectors
    -> x, y, z; quaternion_wxyz -> w, x, y, z; link_com_m (7, 3) -> J1.x ... J7.z;
    thruster_position_m (8, 3) -> T1.x ... T8.z; added_mass_coeff (36,) -> r1c1 ... r6c6.
    A scalar has no components: []."""
    combos = [()]
    for names in shape_labels(channel, field, tuple(shape)):
        combos = [c + (n,) for c in combos for n in names]
    return [join_label(*c) for c in combos] if shape else []


def column_name(field, label):
    """CSV column and legend name of one component: FIELD.LABEL (thrust_N.T3), FIELD alone
    for a scalar (label '')."""
    return join_label(field, label) if label else field



# ----------------------------------------------------------------------------------------------
# CLI


def parse_field_spec(spec):
    """'CHANNEL.FIELD', 'CHANNEL.FIELD[IDX][IDX2]' (0-based array indices) or
    'CHANNEL.FIELD.LABEL[.LABEL2]' (component names, component_labels) -> (channel, field, sel):
    sel is a tuple of ints (indices) or of str (labels), () for the whole field."""
    if "." not in spec:
        raise LogError(f"--plot {spec}: expected CHANNEL.FIELD, CHANNEL.FIELD[IDX] or "
                       "CHANNEL.FIELD.LABEL, e.g. UVMS_TRUTH.thrust_N.T3 or UVMS_TRUTH.thrust_N[2]")
    channel, rest = spec.split(".", 1)
    cut = min((i for i in (rest.find("["), rest.find(".")) if i >= 0), default=len(rest))
    field, tail = rest[:cut], rest[cut:]
    if not tail:
        return channel, field, ()
    if tail.startswith("."):
        return channel, field, tuple(tail[1:].split("."))
    try:
        return channel, field, tuple(int(p) for p in tail[1:].rstrip("]").split("]["))
    except ValueError as e:
        raise LogError(f"--plot {spec}: bad index (expected integers, e.g. [0] or [2][1])") from e


def selection_index(channel, field, shape, sel, spec):
    """Index tuple of `sel` (parse_field_spec) into values of `shape` (no message axis)."""
    if not sel or isinstance(sel[0], int):
        return tuple(sel)
    axes = shape_labels(channel, field, shape)
    if len(sel) > len(axes):
        raise LogError(f"--plot {spec}: {field} has {len(axes)} component axes, not {len(sel)}")
    idx = []
    for label, names in zip(sel, axes):
        if label not in names:
            raise LogError(f"--plot {spec}: no component {label!r} (expected one of "
                           f"{', '.join(names)})")
        idx.append(names.index(label))
    return tuple(idx)


def field_of(log, channel, field):
    if channel not in log:
        raise log.missing(channel)
    ch = log[channel]
    if field not in ch:
        raise LogError(f"field {field} not in {channel} ({ch.type_name}); fields: "
                       + ", ".join(ch.fields))
    return ch


def labels_summary(labels):
    """'x y z', or 'T1 … T8' for a long list: the listing's column of component names."""
    return " ".join(labels) if len(labels) <= 4 else f"{labels[0]} … {labels[-1]}"


def _session_text(session):
    return f"{session & (2**64 - 1):016x}"


def end_text(end):
    """The end record's verdict: "finished" or "failed (code N)"."""
    if end.state == records.FINISHED:
        return "finished"
    return f"failed (code {end.code})" + (f": {byte_text(end.reason)}" if byte_text(end.reason) else "")


def reading_lines(r):
    """What the checked pass found, as the listing's lines after the channels: every count of
    something skipped or ignored, and the damage that stopped a --read-until-damage pass."""
    lines = []
    for ch, t in sorted(r.foreign.items()):
        lines.append(f"{ch}: {t.count} events of no uvms channel or type (first at {t.where()}, "
                     f"fingerprint {t.detail}): ignored")
    for ch, t in sorted(r.unknown.items()):
        lines.append(unknown_type_text(ch, t))
    if r.receive_stamped:
        lines.append(f"event timestamps: {r.receive_stamped} receive times (a logger's, e.g. "
                     "lcm-logger), not the simulated time: ignored; t_s comes from each "
                     "message's utime")
    if r.corrupted_sensors is not None:
        t = r.corrupted_sensors
        lines.append(f"{records.SENSORS}: {t.count} messages fail their CRC-32 (first at "
                     f"{t.where()}): corrupted on the link, a recorded link fault "
                     "(docs/FAULTS.md): left out")
    if r.config_resends:
        lines.append(f"{records.CONFIG}: {r.config_resends} byte-identical re-sends of the "
                     "configuration (handshake retries): ignored")
    if r.late_answers:
        lines.append(f"{r.late_answers} controller messages after the end record (late answers "
                     "of its ticks): ignored")
    if r.truth_gaps:
        lines.append(f"{records.TRUTH}: {r.truth_gaps} ticks missing (lost by the logger)")
    if r.damage is not None:
        lines.append(f"read up to the damage: {r.damage} (--read-until-damage: the "
                     f"{r.events} events before it were read and checked)")
    elif r.incomplete:
        lines.append(f"incomplete: {r.incomplete} (--read-until-damage)")
    return lines


def checked_line(r):
    """One line: how much of the log was checked, the run's session and its end record."""
    session = f", session {_session_text(r.session)}" if r.session is not None else ""
    end = (f"; end record at event {r.end_index}: tick {r.end.tick}, {end_text(r.end)}"
           if r.end is not None else "; no end record")
    return (f"checked: {r.events} events, {r.bytes_read} bytes (framing, event numbers, each "
            f"uvms message's fingerprint, CRC-32 and length, one run in order){session}{end}")


def list_log(path, until_damage=False, out=sys.stdout):
    """The listing of a log: one checked pass, one message in memory at a time."""
    path = log_path(path)
    reading, shapes = scan_shapes(path, None, until_damage)
    print(f"{path}", file=out)
    print(checked_line(reading), file=out)
    for name in sorted(shapes):
        sh = shapes[name]
        span = (f", t = {sh.utime_range[0] * 1e-6:.3f} … {sh.utime_range[1] * 1e-6:.3f} s"
                if sh.utime_range else "")
        ticks = f", ticks {sh.tick_range[0]} … {sh.tick_range[1]}" if sh.tick_range else ""
        print(f"\n{name}  ({sh.cls.__name__}): {sh.count} messages{ticks}{span}", file=out)
        for f in sh.fields:
            kind, shape, _ = sh.column(f)
            shape_text = "varies" if kind == "obj" else "x".join(map(str, shape)) or "scalar"
            comps = labels_summary(component_labels(name, f, shape))
            unit = f"[{unit_of(f)}]"
            print(f"  {f:32s} {shape_text:8s} {unit:11s} {sh.dtype_text(f):8s} {comps}".rstrip(),
                  file=out)
    for line in reading_lines(reading):
        print(f"\n{line}", file=out)
    return reading


def plot_series(log, spec, keep_all_ticks=False):
    """(t_s, values (n, k), legend labels (k)) of one --plot spec."""
    channel, field, sel = parse_field_spec(spec)
    ch = field_of(log, channel, field)
    if not keep_all_ticks and "tick" in ch:
        ch = ch.select(ch["tick"] >= 0)  # drop the configuration acknowledgement
        if not ch.count:
            raise LogError(f"--plot {spec}: {channel} has no message of tick >= 0 "
                           "(--all-ticks keeps tick -1)")
    y = ch[field]
    if y.dtype.kind not in "iuf":
        raise LogError(f"--plot {spec}: field is not numeric ({y.dtype})")
    if y.size == 0:
        raise LogError(f"--plot {spec}: the field is empty in this log (shape "
                       f"{'x'.join(map(str, y.shape[1:]))} per message)")
    idx = selection_index(channel, field, y.shape[1:], sel, spec)
    names = np.array(component_labels(channel, field, y.shape[1:]) if y.ndim > 1 else [""],
                     dtype=object)
    names = names.reshape(y.shape[1:])
    try:
        y, names = y[(slice(None),) + idx], names[idx]
    except IndexError as e:
        raise LogError(f"--plot {spec}: index out of range for shape {names.shape}") from e
    labels = [column_name(field, lab) for lab in np.ravel(names)]
    return ch["t_s"], y.reshape(len(y), -1), labels


def plot_fields(log, specs, out_path, title=None, keep_all_ticks=False):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    series = [plot_series(log, s, keep_all_ticks) for s in specs]
    fig, axes = plt.subplots(len(specs), 1, sharex=True, squeeze=False,
                             figsize=(9, 2.6 + 2.2 * len(specs)))
    for ax, spec, (t, y2, labels) in zip(axes[:, 0], specs, series):
        channel, field, _ = parse_field_spec(spec)
        for k, label in enumerate(labels):
            ax.plot(t, y2[:, k], lw=1.2, label=label)
        ax.set_ylabel(f"{field} [{unit_of(field)}]", fontsize=10)
        ax.set_title(f"{channel}.{field}", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, ncol=min(4, len(labels)), loc="best")
    axes[-1, 0].set_xlabel("simulated time t [s]")
    fig.suptitle(title or os.path.basename(os.path.dirname(os.path.abspath(log.path)))
                 + "/" + os.path.basename(log.path), fontsize=11)
    fig.tight_layout()
    fig.savefig(out_path, dpi=150, format="png")
    plt.close(fig)


def check_out_file(path, ext=None, label=None):
    """LogError unless `path` can name a new file to write, checked before any log is read: no
    directory, in a directory that exists, and (ext) ending in `ext` (case-insensitive). The
    message starts with `label` (default: "--out PATH")."""
    label = f"--out {path}" if label is None else label
    if os.path.isdir(path):
        raise LogError(f"{label}: is a directory (expected a FILE{ext or ''})")
    if ext and not path.lower().endswith(ext):
        raise LogError(f"{label}: expected a file name ending in {ext} ({ext[1:].upper()} only)")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise LogError(f"{label}: cannot write, no directory {folder}")


def check_png_out(path):
    """check_out_file for a PNG: matplotlib would add .png to another name, or write another
    format for .pdf or .svg."""
    check_out_file(path, ".png")


def csv_columns(ch):
    """(header, [per-message 2-D value arrays]) of a channel: t_s, log_utime, then every field,
    one column per component named FIELD.LABEL (component_labels). A scalar (and a
    variable-length field whose length varies between messages: an object array, one cell of
    the list per message) is one column FIELD; an empty field (zero obstacles) has none."""
    cols, header = [], []
    for f in ["t_s", "log_utime"] + ch.fields:
        a = ch[f]
        if a.ndim == 1:
            cols.append(a[:, None])
            header.append(f)
        else:
            cols.append(a.reshape(len(a), -1))
            header += [column_name(f, lab) for lab in component_labels(ch.name, f, a.shape[1:])]
    return header, cols


def csv_cell(v):
    """Shortest round-trip text of a float (repr); str of anything else."""
    return repr(float(v)) if isinstance(v, (float, np.floating)) else str(v)


CSV_CHUNK_ROWS = 4096  # messages decoded into arrays at a time by export_csv


def _open_out(out_path):
    try:
        return sys.stdout if out_path == "-" else open(out_path, "w", newline="")
    except OSError as e:
        raise LogError(f"--out {out_path}: cannot write ({e.strerror or e})") from e


def _write_chunks(chunks, out_path):
    """Write Channels (consecutive pieces of one channel) as one CSV to out_path ("-":
    stdout); returns the number of rows."""
    fh = _open_out(out_path)
    rows = 0
    try:
        w = csv.writer(fh)
        for ch in chunks:
            header, cols = csv_columns(ch)
            if rows == 0:
                w.writerow(header)
            for r in range(ch.count):
                w.writerow([csv_cell(v) for c in cols for v in c[r]])
            rows += ch.count
    finally:
        if fh is not sys.stdout:
            fh.close()
        else:
            fh.flush()
    return rows


def write_csv(log, channel, out_path):
    """Write `channel` of a loaded Log as CSV to out_path ("-": stdout); returns the number of
    rows."""
    ch = log.get(channel)
    if ch is None:
        raise log.missing(channel)
    return _write_chunks([ch], out_path)


def export_csv(path, channel, out_path, until_damage=False):
    """Write `channel` of the log at `path` as CSV to out_path ("-": stdout), streaming: the
    checked first pass (nothing is written if it fails), then CSV_CHUNK_ROWS messages at a
    time, so memory does not grow with the log. Returns (rows, Reading)."""
    path = log_path(path)
    reading, shapes = scan_shapes(path, {channel}, until_damage)
    if channel not in shapes:
        raise Log(path, reading).missing(channel)
    sh = shapes[channel]

    def chunks():
        cols = Columns(channel, sh, CSV_CHUNK_ROWS)
        for _, msg, stamp in fill_pass(path, shapes, until_damage):
            cols.add(msg, stamp)
            if cols.n == CSV_CHUNK_ROWS:
                yield cols.channel()
                cols = Columns(channel, sh, CSV_CHUNK_ROWS)
        if cols.n:
            yield cols.channel()

    rows = _write_chunks(chunks(), out_path)
    if rows != sh.count:
        raise changed_while_read(path)
    return rows, reading


def damage_note(reading):
    """One line on what stopped a --read-until-damage pass early, or None."""
    if reading.damage is not None:
        return (f"read up to the damage, {reading.events} events: {reading.damage}")
    if reading.incomplete:
        return f"read as it is: {reading.path}: incomplete: {reading.incomplete}"
    return None
