# SPDX-License-Identifier: Apache-2.0
"""mcap_export: a run log (LCM event log) as an MCAP file that Foxglove, PlotJuggler and other
MCAP readers decode with no plugin: every channel a topic of JSON messages, each with a JSON
Schema made from its LCM type's definition (log/lcm_schema.py, lcmtypes/*.lcm).

MCAP has no LCM encoding, so raw LCM payloads in MCAP would be opaque to those tools. The export
reads the log through the same checked pass as every other log tool (log/records.py: framing,
CRC-32, fingerprints, one complete run), decodes each message with the generated types and
writes it as JSON (lcm_schema's mapping: int64 as decimal strings, non-finite reals as strings,
byte text as text). Log time and publish time are the message's own `utime`, its simulated time
(µs, as ns): the recorder stamps each event with it, and a log of lcm-logger, whose stamps are
the wall clock of reception, gets the same times. The sequence is the LCM event number. The
metadata record "uvms" names the source log and the uvms tools' version.

    tools/uvmslog.py RUN --mcap OUT.mcap
"""
import json
import math
import os
import tempfile

from . import lcm_schema, records, runlog
from .records import LogError

PROFILE = ""  # no ROS profile: JSON messages with JSON Schemas
LIBRARY = "uvms-tools mcap_export"


def _real(v):
    if math.isfinite(v):
        return v
    return "NaN" if math.isnan(v) else ("Infinity" if v > 0 else "-Infinity")


def _leaf(member, v):
    t = member.type
    if t == "int64_t":
        return str(int(v))
    if t in lcm_schema.REAL:
        return _real(float(v))
    if t == "boolean":
        return bool(v)
    if t in lcm_schema.INTEGER:
        return int(v)
    return v  # string


def _value(member, v, depth=0):
    """A member's decoded value as JSON (lists for its dimensions)."""
    if member.is_text() and depth == len(member.dims) - 1:
        return runlog.byte_text(v)  # up to the first NUL (the rest is padding)
    if depth == len(member.dims):
        return _leaf(member, v)
    return [_value(member, x, depth + 1) for x in v]


def _check_fields(path, type_name, members, cls):
    """The .lcm definition and the generated type that decodes the log name the same fields, in
    order (a build older or newer than lcmtypes/ otherwise): LogError naming the difference."""
    want, have = [m.name for m in members], list(cls.__slots__)
    if want != have:
        raise LogError(f"{path}: uvms.{type_name}: lcmtypes/{type_name}.lcm has the fields "
                       f"{sorted(set(want) - set(have)) or 'in another order'} that the generated "
                       f"type lacks, and it has {sorted(set(have) - set(want))}: rebuild "
                       "(cmake --build --preset host) or set UVMS_LCMTYPES_DIR to the "
                       "lcmtypes/ of the build")


def message_json(members, msg):
    """One decoded LCM message as a JSON-ready dict, by its type's members."""
    return {m.name: _value(m, getattr(msg, m.name)) for m in members}


def _version():
    from uvms_tools.env import version_line
    return version_line("uvmslog")


def export(log_path, out_path, until_damage=False):
    """Writes the log at `log_path` (a file or run directory) to `out_path` as MCAP. Returns
    ({channel: messages}, records.Reading). Nothing is left at out_path if the log fails its
    checks (LogError) or a write fails (OSError): the file is written beside it and renamed.
    until_damage: export the events before the first damage (as --read-until-damage)."""
    from mcap.writer import Writer  # the `mcap` package (tools/requirements.txt)
    path = runlog.log_path(log_path)
    defs = lcm_schema.definitions()
    types = runlog.lcm_types()
    fd, tmp = tempfile.mkstemp(prefix=".uvmslog-", suffix=".mcap.partial",
                               dir=os.path.dirname(os.path.abspath(out_path)))
    counts, schema_ids, channel_ids = {}, {}, {}
    try:
        with os.fdopen(fd, "wb") as fh:
            w = Writer(fh)
            w.start(profile=PROFILE, library=LIBRARY)
            scan = records.Scan(path, types, runlog.CHANNEL_TYPES, None, until_damage)
            for ev, msg in scan:
                type_name = type(msg).__name__
                members = defs.get(type_name)
                if members is None:
                    raise LogError(f"{path}: event {ev.index} on {ev.channel}: no definition "
                                   f"of uvms.{type_name} in {lcm_schema.lcmtypes_dir()}")
                if type_name not in schema_ids:
                    _check_fields(path, type_name, members, type(msg))
                    schema_ids[type_name] = w.register_schema(
                        name=f"uvms.{type_name}", encoding="jsonschema",
                        data=json.dumps(lcm_schema.json_schema(type_name, members)).encode())
                if ev.channel not in channel_ids:
                    channel_ids[ev.channel] = w.register_channel(
                        topic=ev.channel, message_encoding="json",
                        schema_id=schema_ids[type_name],
                        metadata={"lcm_type": f"uvms.{type_name}"})
                stamp_ns = int(msg.utime) * 1000
                w.add_message(channel_id=channel_ids[ev.channel], log_time=stamp_ns,
                              publish_time=stamp_ns, sequence=int(ev.number) & 0xFFFFFFFF,
                              data=json.dumps(message_json(members, msg),
                                              allow_nan=False).encode())
                counts[ev.channel] = counts.get(ev.channel, 0) + 1
            w.add_metadata("uvms", {"source": os.path.abspath(path), "tools": _version(),
                                    "encoding": "json, schemas from lcmtypes/*.lcm"})
            w.finish()
        umask = os.umask(0)  # mkstemp's file is private; the output gets the usual mode
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)
        os.replace(tmp, out_path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    return counts, scan.reading
