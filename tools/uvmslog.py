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
    eps = uvmslog.ee_error(log)             # SPEC §10 EE error per tick

Channels (lcmtypes/): UVMS_CONFIG (controller_config_t, once), UVMS_SENSORS, UVMS_ACTUATORS,
UVMS_TELEMETRY (one per tick plus tick = -1, the configuration acknowledgement), UVMS_TRUTH
(one per tick plus a final sample with tick = number of ticks), UVMS_STATUS (start and end).
Strings become numpy str arrays; `byte` arrays (run_status_t.reason) become str.

Finding the generated types: the directory in $UVMS_LCM_PYTHON_PATH (a PYTHONPATH-style list;
ctest sets it), else a `uvms` package already importable (e.g. via PYTHONPATH), else
build/host/lcmgen/python, else build/lead/lcmgen/python under the repo root. A directory counts
if it holds uvms/truth_t.py; if none does, load() raises LogError listing where it looked.

CLI (see --help):
    tools/uvmslog.py LOG                                    channels, counts, fields, units
    tools/uvmslog.py LOG --plot UVMS_TRUTH.ee_position_m[0] --plot UVMS_TELEMETRY.force_des_N \\
                         --out fig.png                      fields against simulated time
    tools/uvmslog.py LOG --csv UVMS_TRUTH --out truth.csv   one row per message

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

DEFAULT_TYPE_DIRS = ("build/host/lcmgen/python", "build/lead/lcmgen/python")

# Message types per channel (sil/, lcmtypes/). Decoding does not rely on this table (it goes by
# fingerprint); it is used for messages and the listing.
CHANNEL_TYPES = {
    "UVMS_CONFIG": "controller_config_t",
    "UVMS_SENSORS": "sensors_t",
    "UVMS_ACTUATORS": "actuators_t",
    "UVMS_TELEMETRY": "telemetry_t",
    "UVMS_TRUTH": "truth_t",
    "UVMS_STATUS": "run_status_t",
}

# Field-name unit suffixes (house style: units in names), longest first wins.
UNIT_SUFFIXES = [
    ("_Nm_s_rad", "N·m·s/rad"), ("_N_s_m", "N·s/m"), ("_Nm_rad", "N·m/rad"),
    ("_Nm_A", "N·m/A"), ("_Nm_s", "N·m·s"), ("_rad_s2", "rad/s²"), ("_rad_s", "rad/s"),
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
    $UVMS_LCM_PYTHON_PATH, then (with_defaults) build/host and build/lead under the repo."""
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
        cls = getattr(importlib.import_module("uvms." + name), name)
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
    arr = np.asarray(values)
    if arr.dtype == object:
        raise LogError("ragged field (variable-length arrays are not supported)")
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
    """channel name -> Channel; `path`, `skipped` (events of unknown type per channel)."""

    def __init__(self, path):
        super().__init__()
        self.path = path
        self.skipped = {}


def load(path, channels=None):
    """Decode the LCM event log at `path` into a Log.

    channels: iterable of channel names to keep (default: all). Events whose fingerprint
    matches no uvms type are counted in `log.skipped`, not decoded.
    Each channel gets, besides its message fields, `log_utime` (event timestamps, µs) and
    `t_s` (the message's `utime` in s, the simulated time of the tick).
    """
    import lcm  # noqa: WPS433 (imported here so that `unit_of` etc. work without lcm)

    types = lcm_types()
    if not os.path.isfile(path):
        raise LogError(f"{path}: no such log file")
    keep = None if channels is None else set(channels)
    rows = {}
    try:
        events = lcm.EventLog(path, "r")
    except (IOError, OSError) as e:
        raise LogError(f"{path}: cannot open as an LCM log ({e})") from e
    log = Log(path)
    for ev in events:
        if keep is not None and ev.channel not in keep:
            continue
        cls = types.get(bytes(ev.data[:8]))
        if cls is None:
            log.skipped[ev.channel] = log.skipped.get(ev.channel, 0) + 1
            continue
        msg = cls.decode(ev.data)
        entry = rows.setdefault(ev.channel, (cls, [], []))
        entry[1].append(msg)
        entry[2].append(ev.timestamp)
    events.close()
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
# CLI


def parse_field_spec(spec):
    """'CHANNEL.FIELD[IDX][IDX2]' -> (channel, field, index tuple)."""
    if "." not in spec:
        raise LogError(f"--plot {spec}: expected CHANNEL.FIELD[IDX], e.g. UVMS_TRUTH.ee_position_m[0]")
    channel, rest = spec.split(".", 1)
    field, idx = rest, ()
    if "[" in rest:
        field, tail = rest.split("[", 1)
        try:
            idx = tuple(int(p) for p in tail.rstrip("]").split("]["))
        except ValueError as e:
            raise LogError(f"--plot {spec}: bad index (expected integers, e.g. [0] or [2][1])") from e
    return channel, field, idx


def field_of(log, channel, field):
    if channel not in log:
        raise LogError(f"channel {channel} not in {log.path} (has: {', '.join(sorted(log))})")
    ch = log[channel]
    if field not in ch:
        raise LogError(f"field {field} not in {channel} ({ch.type_name}); fields: "
                       + ", ".join(ch.fields))
    return ch


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
            print(f"  {f:32s} {shape:8s} [{unit_of(f)}]  {a.dtype}", file=out)
    for name, n in sorted(log.skipped.items()):
        print(f"\n{name}: {n} messages of unknown type (skipped): their fingerprint matches no "
              f"type generated in {TYPES_DIR}; the log was written with different "
              f"lcmtypes/*.lcm (set UVMS_LCM_PYTHON_PATH to types generated from those)",
              file=out)


def plot_fields(log, specs, out_path, title=None, keep_all_ticks=False):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    parsed = [parse_field_spec(s) for s in specs]
    fig, axes = plt.subplots(len(parsed), 1, sharex=True, squeeze=False,
                             figsize=(9, 2.6 + 2.2 * len(parsed)))
    for ax, spec, (channel, field, idx) in zip(axes[:, 0], specs, parsed):
        ch = field_of(log, channel, field)
        if not keep_all_ticks and "tick" in ch:
            ch = ch.select(ch["tick"] >= 0)  # drop the configuration acknowledgement
        y = ch[field]
        if y.dtype.kind not in "iuf":
            raise LogError(f"--plot {spec}: field is not numeric ({y.dtype})")
        try:
            y = y[(slice(None),) + idx]
        except IndexError as e:
            raise LogError(f"--plot {spec}: index out of range for shape {y.shape[1:]}") from e
        y2 = y.reshape(len(y), -1)
        comps = list(np.ndindex(*y.shape[1:])) if y.ndim > 1 else [()]
        for k, comp in enumerate(comps):
            label = f"{field}{''.join(f'[{i}]' for i in idx + comp)}"
            ax.plot(ch["t_s"], y2[:, k], lw=1.2, label=label)
        ax.set_ylabel(f"{field} [{unit_of(field)}]", fontsize=10)
        ax.set_title(f"{channel}.{field}", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, ncol=min(4, len(comps)), loc="best")
    axes[-1, 0].set_xlabel("simulated time t [s]")
    fig.suptitle(title or os.path.basename(os.path.dirname(os.path.abspath(log.path)))
                 + "/" + os.path.basename(log.path), fontsize=11)
    fig.tight_layout()
    fig.savefig(out_path, dpi=150)
    plt.close(fig)


def write_csv(log, channel, out_path):
    ch = log.get(channel)
    if ch is None:
        raise LogError(f"channel {channel} not in {log.path} (has: {', '.join(sorted(log))})")
    cols, header = [], []
    for f in ["t_s", "log_utime"] + ch.fields:
        a = ch[f]
        if a.ndim == 1:
            cols.append(a[:, None])
            header.append(f)
        else:
            flat = a.reshape(len(a), -1)
            cols.append(flat)
            header += [f + "".join(f"[{i}]" for i in ix) for ix in np.ndindex(*a.shape[1:])]
    with open(out_path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for r in range(ch.count):
            row = []
            for c in cols:
                for v in c[r]:
                    row.append(repr(float(v)) if isinstance(v, np.floating) else str(v))
            w.writerow(row)


def main(argv=None):
    import signal
    if hasattr(signal, "SIGPIPE"):
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `uvmslog.py LOG | head` exits quietly
    ap = argparse.ArgumentParser(
        prog="uvmslog.py",
        description="List, plot or export a UVMS run log (LCM event log of `uvms run`).",
        epilog="Examples:\n"
               "  tools/uvmslog.py out/r/run.lcmlog\n"
               "  tools/uvmslog.py out/r/run.lcmlog --plot UVMS_TRUTH.ee_position_m "
               "--plot UVMS_TELEMETRY.thrust_des_N[3] --out fig.png\n"
               "  tools/uvmslog.py out/r/run.lcmlog --csv UVMS_TRUTH --out truth.csv\n"
               "Field units come from the name's suffix (_m: m, _N: N, _rad_s: rad/s, ...).\n"
               "Generated types: $UVMS_LCM_PYTHON_PATH, else build/host or build/lead "
               "lcmgen/python.",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("log", help="run.lcmlog")
    ap.add_argument("--plot", action="append", metavar="CHANNEL.FIELD[IDX]",
                    help="plot a field (all components without IDX) against time; repeatable, "
                         "one panel each")
    ap.add_argument("--csv", metavar="CHANNEL", help="export a channel as CSV")
    ap.add_argument("--out", help="output file (PNG for --plot, CSV for --csv)")
    ap.add_argument("--title", help="figure title (--plot)")
    ap.add_argument("--all-ticks", action="store_true",
                    help="--plot: keep tick -1 (telemetry's configuration acknowledgement)")
    a = ap.parse_args(argv)
    if a.plot and a.csv:
        ap.error("--plot and --csv are exclusive")
    if (a.plot or a.csv) and not a.out:
        ap.error("--out is required with --plot or --csv")
    try:
        if a.plot:
            chans = {parse_field_spec(s)[0] for s in a.plot}
            log = load(a.log, chans)
            plot_fields(log, a.plot, a.out, a.title, a.all_ticks)
            print(f"wrote {a.out}")
        elif a.csv:
            log = load(a.log, [a.csv])
            write_csv(log, a.csv, a.out)
            print(f"wrote {a.out} ({log[a.csv].count if a.csv in log else 0} rows)")
        else:
            list_log(load(a.log))
    except LogError as e:
        print(f"uvmslog: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
