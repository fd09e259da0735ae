# SPDX-License-Identifier: Apache-2.0
"""tools/uvmslog.py --mcap (log/mcap_export.py) on a real run (case VII, 2 s, with a fault so the
status reason text is not empty): the MCAP file read back with the `mcap` package's reader
holds, in order, one message per LCM event of the log, on the event's channel, with log time
and publish time the message's utime (µs -> ns; the recorder stamps the event with it) and
sequence its event number; every field of
every message equals the LCM decode of that event (int64 as its decimal string, byte text up to
its NUL padding); each schema is a valid JSON Schema (draft 2020-12) of encoding jsonschema and
every message validates against its channel's schema; the stream reader reads every record with
its CRCs checked, as many messages as the statistics say. If the `mcap` CLI (Go) is on PATH or in
.venv/bin, `mcap doctor` finds nothing wrong. Bad outputs and a damaged log are refused with
exit 1 and leave no file.

Usage: test_mcap_export.py UVMS_EXE SOURCE_DIR
"""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

UVMS, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tools"))
from uvms_tools.log import lcm_schema, mcap_export, records, runlog  # noqa: E402

TMP = tempfile.mkdtemp(prefix="uvms-mcap-")
UVMSLOG = [sys.executable, os.path.join(SRC, "tools", "uvmslog.py")]
failures = []


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


def expected(member, v, depth=0):
    """The JSON value the mapping promises for a decoded LCM value (lcm_schema docstring)."""
    if member.is_text() and depth == len(member.dims) - 1:
        raw = bytes(v)
        text = raw.split(b"\0", 1)[0]
        assert raw[len(text):] == b"\0" * (len(raw) - len(text)), "text not NUL-padded"
        return text.decode()
    if depth < len(member.dims):
        return [expected(member, x, depth + 1) for x in v]
    if member.type == "int64_t":
        return str(v)
    return v


def compare_messages(log, out):
    from jsonschema import Draft202012Validator
    from mcap.reader import make_reader
    defs = lcm_schema.definitions()
    scan = records.Scan(runlog.log_path(log), runlog.lcm_types(), runlog.CHANNEL_TYPES)
    events = iter(scan)
    n = bad = 0
    validators, seen_topics = {}, set()
    with open(out, "rb") as f:
        reader = make_reader(f)
        summary = reader.get_summary()
        for schema in summary.schemas.values():
            Draft202012Validator.check_schema(json.loads(schema.data))
        check(all(s.encoding == "jsonschema" for s in summary.schemas.values())
              and all(c.message_encoding == "json" for c in summary.channels.values()),
              f"{len(summary.schemas)} JSON Schemas, {len(summary.channels)} JSON channels")
        for schema, channel, message in reader.iter_messages(log_time_order=False):
            ev, msg = next(events)
            n += 1
            seen_topics.add(channel.topic)
            data = json.loads(message.data)
            members = defs[type(msg).__name__]
            want = {m.name: expected(m, getattr(msg, m.name)) for m in members}
            v = validators.setdefault(schema.id, Draft202012Validator(json.loads(schema.data)))
            errors = list(v.iter_errors(data))
            stamp_ns = msg.utime * 1000  # the message's simulated time (= the recorder's stamp)
            if (channel.topic != ev.channel or message.log_time != stamp_ns or ev.stamp != msg.utime
                    or message.publish_time != stamp_ns or message.sequence != ev.number
                    or data != want or errors or schema.name != f"uvms.{type(msg).__name__}"):
                bad += 1
                if bad <= 3:
                    diff = [k for k in want if data.get(k) != want[k]]
                    print(f"  event {ev.index} {ev.channel}: topic {channel.topic}, time "
                          f"{message.log_time} vs {ev.stamp * 1000}, fields differing {diff[:5]}, "
                          f"schema errors {[e.message for e in errors[:2]]}")
    left = sum(1 for _ in events)
    check(n > 100 and bad == 0 and left == 0,
          f"{n} messages: each is its LCM event (channel, time, sequence, every field) and "
          f"valid against its schema ({bad} differ, {left} events not exported)")
    return seen_topics


def main():
    run = os.path.join(TMP, "run")
    p = subprocess.run([UVMS, "run", os.path.join(SRC, "sil", "scenarios", "paper",
                                                  "case_VII_unsteady.toml"),
                        "--out", run, "--transport", "memq", "--set", "run.duration_s=2",
                        "--set", "verdict.max_ee_error_m=1e-9"],
                       capture_output=True, text=True, timeout=120)
    check(p.returncode == 3, f"a short run that fails its verdict (a reason text): exit "
                             f"{p.returncode}")
    out = os.path.join(TMP, "run.mcap")
    p = subprocess.run(UVMSLOG + [run, "--mcap", out], capture_output=True, text=True,
                       timeout=120)
    print(p.stdout, p.stderr)
    check(p.returncode == 0 and os.path.exists(out) and "wrote" in p.stdout,
          f"uvmslog --mcap exits 0 and writes {out}")
    if os.path.exists(out):
        topics = compare_messages(run, out)
        log = runlog.load(run)
        check(topics == set(log.keys()), f"every channel of the log is a topic: {sorted(topics)}")
        status = [m for m in mcap_messages(out, "UVMS_STATUS")]
        check(status and status[-1]["reason"] and isinstance(status[-1]["session"], str)
              and int(status[-1]["session"]) == int(log["UVMS_STATUS"]["session"][-1]),
              f"the end status: reason text {status[-1]['reason'][:40]!r}, session as the exact "
              f"decimal string {status[-1]['session'] if status else None}")
        doctor(out)
    check(mcap_export._real(float("nan")) == "NaN" and mcap_export._real(float("-inf"))
          == "-Infinity" and mcap_export._real(1.5) == 1.5,
          "non-finite reals become the strings NaN, Infinity, -Infinity")
    refused(run)
    shutil.rmtree(TMP, ignore_errors=True)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


def mcap_messages(out, topic):
    from mcap.reader import make_reader
    with open(out, "rb") as f:
        return [json.loads(m.data) for _, _, m in make_reader(f).iter_messages(topics=[topic])]


def doctor(out):
    """The file's structure: every record read in order by the mcap package's stream reader
    with CRC checks (chunks, data section), the summary and footer consistent; and `mcap
    doctor` when the Go CLI is installed (the Go module proxy here does not serve
    github.com/foxglove/mcap/go/cli/mcap: 403 for its version list and for every version
    tried, so tools/bootstrap cannot install it)."""
    from mcap.reader import make_reader
    from mcap.records import Footer, Message
    from mcap.stream_reader import StreamReader
    with open(out, "rb") as f:
        kinds = [type(r).__name__ for r in StreamReader(f, validate_crcs=True).records]
    with open(out, "rb") as f:
        stats = make_reader(f, validate_crcs=True).get_summary().statistics
    n_msgs = kinds.count(Message.__name__)
    check(kinds[-1] == Footer.__name__ and stats is not None and n_msgs > 0
          and stats.message_count == n_msgs,
          f"the stream reader reads {len(kinds)} records with their CRCs checked; statistics "
          f"count {stats.message_count if stats else None} messages")
    cli = shutil.which("mcap") or os.path.join(SRC, ".venv", "bin", "mcap")
    if not os.path.exists(cli):
        print("skip mcap doctor: the mcap CLI (Go) is not installed")
        return
    p = subprocess.run([cli, "doctor", out], capture_output=True, text=True, timeout=60)
    print(p.stdout, p.stderr)
    check(p.returncode == 0 and "error" not in (p.stdout + p.stderr).lower(),
          f"mcap doctor finds nothing wrong (exit {p.returncode})")


def refused(run):
    cases = [("a directory", [run, "--mcap", TMP], "is a directory"),
             ("another extension", [run, "--mcap", os.path.join(TMP, "x.json")], "ending in .mcap"),
             ("a missing directory", [run, "--mcap", os.path.join(TMP, "no", "x.mcap")],
              "no directory")]
    damaged = os.path.join(TMP, "damaged.lcmlog")
    with open(os.path.join(run, "run.lcmlog"), "rb") as f:
        data = bytearray(f.read())
    data[len(data) // 2] ^= 0xFF
    with open(damaged, "wb") as f:
        f.write(data)
    cases.append(("a damaged log", [damaged, "--mcap", os.path.join(TMP, "d.mcap")], "event"))
    for what, args, needle in cases:
        p = subprocess.run(UVMSLOG + args, capture_output=True, text=True, timeout=60)
        out = args[-1]
        left = os.path.isfile(out) or bool(glob.glob(os.path.join(os.path.dirname(out),
                                                                   ".uvmslog-*.partial")))
        check(p.returncode == 1 and needle in p.stderr and not left,
              f"{what}: exit {p.returncode}, says {needle!r}, leaves no file "
              f"({p.stderr.strip()[:100]})")


if __name__ == "__main__":
    sys.exit(main())
