#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""uvmslog: load a UVMS run log (LCM event log) into numpy arrays; list, plot, export.

A run log (`uvms run ... --out DIR` writes DIR/run.lcmlog) holds one LCM event per message;
the event timestamp is the simulated time in µs. `load()` decodes every event with the
generated Python types (package `uvms`, lcmtypes/*.lcm), chosen by each message's
fingerprint, and stacks every field of every channel into a numpy array whose first axis is
the message index:

    import uvmslog
    log = uvmslog.load("out/run/run.lcmlog")
    log["UVMS_TRUTH"]["ee_position_m"]      # (n, 3) float64 [m]
    log["UVMS_TRUTH"]["t_s"]                # (n,) simulated time from the message utime [s]
    log["UVMS_TRUTH"]["tick"]               # (n,) int64
    log["UVMS_TRUTH"]["log_utime"]          # (n,) event timestamps of the log [µs]
    eps = uvmslog.ee_error(log)             # docs/MODEL.md §10 EE error per tick

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

CLI (see --help):
    tools/uvmslog.py LOG                                    channels, counts, fields, units
    tools/uvmslog.py LOG --plot UVMS_TRUTH.ee_position_m.x --plot UVMS_TRUTH.thrust_N.T3 \\
                         --plot UVMS_TELEMETRY.force_des_N --out fig.png
                                                            fields against simulated time
    tools/uvmslog.py LOG --csv UVMS_TRUTH [--out truth.csv] one row per message (stdout: -)
    tools/uvmslog.py RUN... --dashboard [--out FILE.png]    one page per run (uvms_dashboard)
    tools/uvmslog.py CAMPAIGN_DIR --dashboard [-j N]        a page for every runs/*/

--plot takes CHANNEL.FIELD.LABEL (a component name, thrusters and joints from 1) or
CHANNEL.FIELD[IDX] (a 0-based array index): thrust_N.T3 and thrust_N[2] are thruster 3.

Interpreter: the shebang is `/usr/bin/env python3`; when run as a script outside the
project's venv, the script re-executes itself with REPO/.venv/bin/python (numpy, matplotlib
and lcm are pinned there, tools/requirements.txt), so `tools/uvmslog.py ...`,
`python3 tools/uvmslog.py ...` and `.venv/bin/python tools/uvmslog.py ...` all work. Set
UVMS_NO_REEXEC=1 to use the current interpreter as is.
"""
import os
import sys

if os.path.dirname(os.path.abspath(__file__)) not in sys.path:
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from toolenv import REPO_ROOT, reexec_in_venv  # noqa: E402

if __name__ == "__main__":
    reexec_in_venv(__file__)

import argparse  # noqa: E402
import csv  # noqa: E402
import importlib  # noqa: E402
import importlib.util  # noqa: E402

import numpy as np  # noqa: E402

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


class LogError(Exception):
    """A log, a field or the generated types could not be found or read."""


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


def _to_array(values):
    """Stack one field's per-message values into a numpy array."""
    first = values[0]
    if isinstance(first, str):
        return np.array(values, dtype=str)
    if isinstance(first, (bytes, bytearray)):  # lcm `byte x[n]` decodes to bytes
        return np.array([bytes(v).split(b"\0", 1)[0].decode("utf-8", "replace")
                         for v in values], dtype=str)
    try:
        arr = np.asarray(values)
    except ValueError:  # variable-length arrays of different lengths (scene_t obstacles)
        arr = None
    if arr is None or arr.dtype == object:
        arr = np.empty(len(values), dtype=object)  # one list per message
        for i, v in enumerate(values):
            arr[i] = list(v)
    return arr


class Channel(dict):
    """One channel: field name -> numpy array (first axis = message index), plus metadata."""

    def __init__(self, name, type_name):
        super().__init__()
        self.name = name
        self.type_name = type_name

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


class Log(dict):
    """channel name -> Channel; `path`, `skipped` (events of unknown type per channel),
    `all_channels` (every channel of the file, also those load() was told not to keep)."""

    def __init__(self, path):
        super().__init__()
        self.path = path
        self.skipped = {}
        self.all_channels = set()

    def missing(self, channel):
        """The LogError for a channel the file does not have, listing the ones it has."""
        return LogError(f"channel {channel} not in {self.path} (has: "
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


def load(path, channels=None):
    """Decode the LCM event log at `path` (a log file or a run directory) into a Log.

    channels: iterable of channel names to keep (default: all). Events whose fingerprint
    matches no uvms type are counted in `log.skipped`, not decoded.
    Each channel gets, besides its message fields, `log_utime` (event timestamps, µs) and
    `t_s` (the message's `utime` in s, the simulated time of the tick).
    A file without a single LCM event (empty, or not an LCM log) is a LogError.
    """
    path = log_path(path)
    log = Log(path)
    rows = _read_events(log, None if channels is None else set(channels))
    for ch, (cls, msgs, stamps) in rows.items():
        c = Channel(ch, cls.__name__)
        for f in cls.__slots__:
            try:
                c[f] = _to_array([getattr(m, f) for m in msgs])
            except LogError as e:
                raise LogError(f"{path}: {ch}.{f}: {e}") from e
        c["log_utime"] = np.asarray(stamps, dtype=np.int64)
        if "utime" in c:
            c["t_s"] = c["utime"] * 1e-6
        log[ch] = c
    return log


def _read_events(log, keep):
    """{channel: (class, [messages], [event timestamps µs])} of the events of log.path on the
    channels in `keep` (None: all); counts unknown types in log.skipped."""
    import lcm  # noqa: WPS433 (imported here so that `unit_of` etc. work without lcm)

    types = lcm_types()
    try:
        events = lcm.EventLog(log.path, "r")
    except (IOError, OSError) as e:
        raise LogError(f"{log.path}: cannot open as an LCM log ({e})") from e
    rows, n_events = {}, 0
    for ev in events:
        n_events += 1
        log.all_channels.add(ev.channel)
        if keep is not None and ev.channel not in keep:
            continue
        cls = types.get(bytes(ev.data[:8]))
        if cls is None:
            log.skipped[ev.channel] = log.skipped.get(ev.channel, 0) + 1
            continue
        entry = rows.setdefault(ev.channel, (cls, [], []))
        entry[1].append(cls.decode(ev.data))
        entry[2].append(ev.timestamp)
    events.close()
    if n_events == 0:
        raise LogError(f"{log.path}: no LCM events (an empty log, or not an LCM log)")
    return rows


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


def list_log(log, out=sys.stdout):
    print(f"{log.path}", file=out)
    for name in sorted(log):
        ch = log[name]
        t = ch.get("t_s")
        span = f", t = {t.min():.3f} … {t.max():.3f} s" if t is not None and len(t) else ""
        tick = ch.get("tick")
        ticks = f", ticks {tick.min()} … {tick.max()}" if tick is not None and len(tick) else ""
        print(f"\n{name}  ({ch.type_name}): {ch.count} messages{ticks}{span}", file=out)
        for f in ch.fields:
            a = ch[f]
            shape = "x".join(str(s) for s in a.shape[1:]) or "scalar"
            shape = "varies" if a.dtype == object else shape
            comps = labels_summary(component_labels(name, f, a.shape[1:]))
            unit = f"[{unit_of(f)}]"
            print(f"  {f:32s} {shape:8s} {unit:11s} {str(a.dtype):8s} {comps}".rstrip(),
                  file=out)
    for name, n in sorted(log.skipped.items()):
        print(f"\n{name}: {n} messages of unknown type (skipped): their fingerprint matches no "
              f"type generated in {TYPES_DIR}; the log was written with different "
              f"lcmtypes/*.lcm (set UVMS_LCM_PYTHON_PATH to types generated from those)",
              file=out)


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


def write_csv(log, channel, out_path):
    """Write `channel` as CSV to out_path ("-": stdout); returns the number of rows."""
    ch = log.get(channel)
    if ch is None:
        raise log.missing(channel)
    header, cols = csv_columns(ch)
    try:
        fh = sys.stdout if out_path == "-" else open(out_path, "w", newline="")
    except OSError as e:
        raise LogError(f"--out {out_path}: cannot write ({e.strerror or e})") from e
    try:
        w = csv.writer(fh)
        w.writerow(header)
        for r in range(ch.count):
            w.writerow([csv_cell(v) for c in cols for v in c[r]])
    finally:
        if fh is not sys.stdout:
            fh.close()
        else:
            fh.flush()
    return ch.count


EPILOG = """Examples:
  tools/uvmslog.py out/r                    (a run directory: out/r/run.lcmlog)
  tools/uvmslog.py out/r --plot UVMS_TRUTH.ee_position_m --plot UVMS_TRUTH.thrust_N.T3 \\
                         --plot UVMS_TELEMETRY.thrust_des_N[2] --out fig.png
  tools/uvmslog.py out/r --csv UVMS_TRUTH --out truth.csv
  tools/uvmslog.py out/r --csv UVMS_TRUTH | head           (CSV on stdout; also --out -)
  tools/uvmslog.py out/r --dashboard                       (out/r/dashboard.png)
  tools/uvmslog.py out/exp1 --dashboard -j 8               (a campaign: every runs/*/)

LOG is a log file or a run directory (DIR/run.lcmlog). Components of array fields are named
for humans (listing, CSV header, legends): thrusters T1..T8 and joints J1..J7, numbered
from 1 as in docs/MODEL.md §3.4, §3.1; vectors x, y, z; quaternion_wxyz w, x, y, z;
link_com_m J1.x ... J7.z; thruster_position_m T1.x ... T8.z; added_mass_coeff r1c1 ... r6c6
(row-major 6x6). --plot takes CHANNEL.FIELD.LABEL (UVMS_TRUTH.thrust_N.T3 is thruster 3)
or CHANNEL.FIELD[IDX], a 0-based array index (UVMS_TRUTH.thrust_N[2] is the same thruster 3).
Field units come from the name's suffix (_m: m, _N: N, _rad_s: rad/s, ...).
Generated types: $UVMS_LCM_PYTHON_PATH, else build/host/lcmgen/python."""


def parse_args(argv):
    ap = argparse.ArgumentParser(
        description="List, plot or export a UVMS run log (LCM event log of `uvms run`), or "
                    "draw a dashboard page per run.",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("log", nargs="+", metavar="LOG",
                    help="run.lcmlog or a run directory; with --dashboard also a campaign "
                         "directory (runs/*/run.lcmlog) and several of either")
    ap.add_argument("--plot", action="append", metavar="CHANNEL.FIELD[.LABEL|[IDX]]",
                    help="plot a field (all components without LABEL/IDX) against time; "
                         "repeatable, one panel each")
    ap.add_argument("--csv", metavar="CHANNEL",
                    help="export a channel as CSV, one row per message (to --out, default "
                         "stdout)")
    ap.add_argument("--dashboard", action="store_true",
                    help="one PNG page per run: vehicle motion, EE error, wrench, thrusters, "
                         "joints, energy (default RUN_DIR/dashboard.png)")
    ap.add_argument("--out", help="output file: FILE.png for --plot and --dashboard (one run), CSV "
                                  "for --csv ('-': stdout)")
    ap.add_argument("-j", "--jobs", type=int, default=1, metavar="N",
                    help="--dashboard: runs drawn N at a time (default 1)")
    ap.add_argument("--title", help="figure title (--plot, --dashboard of one run)")
    ap.add_argument("--all-ticks", action="store_true",
                    help="--plot: keep tick -1 (telemetry's configuration acknowledgement)")
    a = ap.parse_args(argv)
    modes = sum(bool(m) for m in (a.plot, a.csv, a.dashboard))
    if modes > 1:
        ap.error("--plot, --csv and --dashboard are exclusive")
    if not a.dashboard and len(a.log) > 1:
        ap.error("one LOG only (several only with --dashboard)")
    if a.plot and not a.out:
        ap.error("--out is required with --plot")
    if a.jobs < 1:
        ap.error("-j must be at least 1")
    return a


def main(argv=None):
    import signal
    if hasattr(signal, "SIGPIPE"):
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `uvmslog.py LOG | head` exits quietly
    a = parse_args(argv)
    try:
        if a.dashboard:
            import uvms_dashboard
            return uvms_dashboard.run_dashboards(a.log, a.out, a.jobs, a.title)
        path = a.log[0]
        if a.plot:
            check_png_out(a.out)
            log = load(path, {parse_field_spec(s)[0] for s in a.plot})
            plot_fields(log, a.plot, a.out, a.title, a.all_ticks)
            print(f"wrote {a.out}")
        elif a.csv:
            out = a.out or "-"
            rows = write_csv(load(path, [a.csv]), a.csv, out)
            if out != "-":
                print(f"wrote {out} ({rows} rows)")
        else:
            list_log(load(path))
    except LogError as e:
        print(f"uvmslog: error: {e}", file=sys.stderr)
        return 1
    except OSError as e:  # the output could not be written (--out in a missing directory, ...)
        print(f"uvmslog: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
