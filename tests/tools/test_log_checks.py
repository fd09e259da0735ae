# SPDX-License-Identifier: Apache-2.0
"""The readers of run logs (tools/uvmslog.py: listing, --csv, --plot, --dashboard;
tools/uvmsviz.py) check every record (tools/uvms_tools/log/records.py) on fresh runs and on damaged,
reordered and concatenated copies of them, made here with this file's own LCM log writer.

- Truncation: cut at every event boundary, 5 offsets inside each of the first events and 100
  random offsets: always refused, naming the first event that is not whole and its byte
  offset (at a boundary: no end record); read until the damage, exactly the whole events
  before the cut are read.
- Damage: a message cut short (sealed again, so only its length is wrong) is refused by its
  decoder; 300 random single-bit flips (fixed seed) and one in every field of a truth event
  are each refused naming the event that holds the bit, or the next one (a timestamp flipped
  in the first event), except a flip in a sensor message's data: a corrupted sensor message,
  which the link-fault run records as real traffic (counted, left out). Garbage, text, an empty
  file, bytes before or after a log.
- One run in order: a log concatenated with itself (raw, and renumbered), two runs
  concatenated, truth ticks swapped or repeated, an event dropped, two events swapped: refused,
  naming the event number, tick or sessions that tell. The link-fault run (duplicated, delayed,
  corrupted messages) passes.
- A logger's log: receive-time stamps and LCM_SELF_TEST events, a configuration re-sent, a late
  answer after the end record: read and counted, with the same arrays as the recorder's log; a
  log recorded by lcm-logger from a udpm run (when lcm-logger is installed).
- An intact message of a type not generated here: the listing and every error name its
  fingerprint, channel, event and byte offset.
- Memory: listing and --csv of a 200 s run's log peak within a few MB of a 1.5 s run's.
- No traceback anywhere: every CLI failure is one line on stderr, exit 1; --read-until-damage
  reads what precedes the damage, with a one-line note.

Usage: test_log_checks.py UVMS_EXE SOURCE_DIR
"""
import importlib
import json
import os
import random
import shutil
import struct
import subprocess
import sys
import time
import zlib

import numpy as np

UVMS, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tools"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(SRC, "tests", "sil"))  # lcm_urls
import checklist  # noqa: E402
from uvms_tools.log import runlog, versions  # noqa: E402
from lcm_urls import private_url  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

PY = sys.executable
LOGTOOL = os.path.join(SRC, "tools", "uvmslog.py")
VIZTOOL = os.path.join(SRC, "tools", "uvmsviz.py")
TMP = scratch_dir("uvms-log-checks-")  # removed at exit (tests/support/scratch.py)
SCENARIO = os.path.join(SRC, "sil/scenarios/paper/case_VII_stagnant.toml")
LINK_FAULTS = os.path.join(SRC, "sil/scenarios/faults/link_faults.toml")

SYNC = 0xEDA1DA01
HEADER = struct.Struct(">Iqqii")  # LCM event: sync, number, timestamp, channel len, data len
SESSION_A, SESSION_B = 0xA1, 0xB2
LOGGER_EPOCH_US = 1_700_000_000_000_000  # a wall-clock receive time [µs], as lcm-logger writes
FLIPS = 300
RANDOM_CUTS = 100
SEED = 20240611
# Peak RSS growth allowed from a 1.5 s log to a 200 s one (2 MB to 18 MB) for the listing and
# --csv: one event and one 4,096-row CSV chunk (about 3 MB of truth arrays) are held at a
# time; the rest is the allocator's slack. Holding the log (the old reader) costs ~7x its size.
MAX_RSS_GROWTH_KB = 12_000

LOGS = {}  # name -> log path (fresh runs)


# ----------------------------------------------------------------------------------------------
# LCM logs, read and written here (the format of lcm/eventlog.c), independently of the tools


class Ev:
    def __init__(self, number, stamp, channel, data, offset=None):
        self.number, self.stamp, self.channel, self.data = number, stamp, channel, bytes(data)
        self.offset = offset

    @property
    def size(self):
        return HEADER.size + len(self.channel) + len(self.data)

    @property
    def tick(self):
        return struct.unpack_from(">q", self.data, 16)[0]


def read_log(path):
    with open(path, "rb") as fh:
        blob = fh.read()
    events, off = [], 0
    while off < len(blob):
        sync, number, stamp, cl, dl = HEADER.unpack_from(blob, off)
        assert sync == SYNC, f"{path}: the test's reader lost sync at {off}"
        ch = blob[off + HEADER.size:off + HEADER.size + cl].decode()
        data = blob[off + HEADER.size + cl:off + HEADER.size + cl + dl]
        events.append(Ev(number, stamp, ch, data, off))
        off += HEADER.size + cl + dl
    return events


def encode(events, renumber=True):
    out = bytearray()
    for i, e in enumerate(events):
        ch = e.channel.encode()
        out += HEADER.pack(SYNC, i if renumber else e.number, e.stamp, len(ch), len(e.data))
        out += ch + e.data
    return bytes(out)


def write(name, blob):
    path = os.path.join(TMP, name)
    with open(path, "wb") as fh:
        fh.write(blob)
    return path


def sealed(data):
    """data with its trailing crc32 field set as sil/msg/codec.h does (zlib's CRC-32)."""
    return data[:-4] + (zlib.crc32(data[:-4]) & 0xFFFFFFFF).to_bytes(4, "big")


def offsets(events):
    return [e.offset for e in events]


# ----------------------------------------------------------------------------------------------
# Running the tools


def cli(tool, *args):
    return subprocess.run([PY, tool, *args], capture_output=True, text=True, cwd=TMP)


def refused(p, *words):
    """A CLI failure as required: exit 1, one line on stderr holding `words`, no traceback."""
    lines = p.stderr.strip().splitlines()
    assert "Traceback" not in p.stderr, f"a traceback: {p.stderr[-600:]}"
    assert p.returncode == 1 and len(lines) == 1, \
        f"exit {p.returncode}, {len(lines)} stderr lines: {p.stderr.strip()[-400:]}"
    missing = [w for w in words if w not in lines[0]]
    assert not missing, f"{missing} not in: {lines[0]}"
    return lines[0]


def every_reader_refuses(path, *words):
    """The listing, --csv, --plot, --dashboard and uvmsviz each refuse `path` in one line."""
    png, rrd = os.path.join(TMP, "never.png"), os.path.join(TMP, "never.rrd")
    runs = {"listing": cli(LOGTOOL, path), "--csv": cli(LOGTOOL, path, "--csv", "UVMS_TRUTH"),
            "--plot": cli(LOGTOOL, path, "--plot", "UVMS_TRUTH.thrust_N", "--out", png),
            "--dashboard": cli(LOGTOOL, path, "--dashboard", "--out", png),
            "uvmsviz": cli(VIZTOOL, path, "--out", rrd)}
    for what, p in runs.items():
        try:
            refused(p, *words)
        except AssertionError as e:
            raise AssertionError(f"{what}: {e}") from None
        assert not p.stdout.strip() or what == "--dashboard", f"{what}: stdout {p.stdout[:200]}"
    assert not os.path.exists(png) and not os.path.exists(rrd), "a refused log wrote a file"


def damage_of(path, **kw):
    """The LogError load() raises on `path` (AssertionError when it reads it)."""
    try:
        runlog.load(path, **kw)
    except runlog.LogError as e:
        return e
    raise AssertionError(f"{os.path.basename(path)} was read without complaint")


def run_uvms(name, scenario, *sets, session):
    out = os.path.join(TMP, name)
    args = [UVMS, "run", scenario, "--out", out, "--transport", "memq", "--session",
            f"{session:x}"]
    for s in sets:
        args += ["--set", s]
    p = subprocess.run(args, capture_output=True, text=True)
    assert p.returncode == 0, f"uvms run {name}: {p.stderr[-300:]}"
    LOGS[name] = os.path.join(out, "run.lcmlog")


def setup():
    short = ["run.duration_s=1.5", "trajectory.duration_s=1.5"]
    run_uvms("a", SCENARIO, *short, session=SESSION_A)
    run_uvms("b", SCENARIO, *short, session=SESSION_B)
    run_uvms("faults", LINK_FAULTS, "run.duration_s=6", "trajectory.duration_s=6",
             session=SESSION_A)
    run_uvms("long", SCENARIO, "run.duration_s=200", session=SESSION_A)


# ----------------------------------------------------------------------------------------------
# Checks


def check_fresh_logs_pass():
    for name in ("a", "b", "long"):
        r = runlog.load(LOGS[name], ["UVMS_STATUS"]).reading
        assert r.damage is None and r.end is not None and not r.receive_stamped \
            and not r.foreign and r.corrupted_sensors is None, f"{name}: {vars(r)}"
    a = read_log(LOGS["a"])
    r = runlog.load(LOGS["a"], ["UVMS_STATUS"]).reading
    assert r.events == len(a) and r.bytes_read == os.path.getsize(LOGS["a"]) \
        and r.session == SESSION_A, f"events {r.events} of {len(a)}, session {r.session:x}"


def check_link_faults_run_is_read():
    """Duplicated, delayed and corrupted messages are the run's real traffic: read; the
    corrupted sensor message is counted and left out."""
    summary = json.load(open(os.path.join(os.path.dirname(LOGS["faults"]), "summary.json")))
    f = summary["faults"]
    assert f["sensors_corrupted"] >= 1 and f["sensors_duplicated"] >= 1 \
        and f["actuators_delayed"] >= 1, f"the run should have link faults of each kind: {f}"
    log = runlog.load(LOGS["faults"])
    r = log.reading
    assert r.corrupted_sensors is not None \
        and r.corrupted_sensors.count == f["sensors_corrupted"], "corrupted sensors counted"
    raw = [e for e in read_log(LOGS["faults"]) if e.channel == "UVMS_SENSORS"]
    assert log["UVMS_SENSORS"].count == len(raw) - f["sensors_corrupted"], "left out"
    p = cli(LOGTOOL, LOGS["faults"])
    assert p.returncode == 0 and "UVMS_SENSORS: 1 messages fail their CRC-32" in p.stdout \
        and "link fault" in p.stdout, p.stdout[-500:] + p.stderr


def check_truncated_logs_are_refused_at_the_cut():
    a = read_log(LOGS["a"])
    blob = open(LOGS["a"], "rb").read()
    starts = offsets(a) + [len(blob)]
    cuts = set(starts[1:-1])
    for e in a[:12]:
        cuts |= {e.offset + d for d in (1, 13, HEADER.size, HEADER.size + 1, HEADER.size + 40)}
    rng = random.Random(SEED)
    cuts |= {rng.randrange(1, len(blob)) for _ in range(RANDOM_CUTS)}
    for cut in sorted(cuts):
        whole = sum(1 for s, t in zip(starts, starts[1:]) if t <= cut)
        path = write("cut.lcmlog", blob[:cut])
        err = str(damage_of(path))
        if cut in starts:
            want = f"after event {whole - 1} (byte {cut})"
            assert "incomplete: no end record" in err and want in err, f"cut {cut}: {err}"
        else:
            want = f"event {whole} at byte {starts[whole]}"
            assert want in err and "truncated" in err, f"cut {cut}: {err} (expected {want})"
        if whole == 0:  # nothing precedes the damage: refused all the same
            damage_of(path, until_damage=True)
            continue
        r = runlog.load(path, until_damage=True).reading
        assert r.events == whole, f"cut {cut}: read {r.events} events until the damage, " \
                                  f"{whole} are whole"
    path = write("cut.lcmlog", blob[:starts[30] + 100])
    every_reader_refuses(path, "event 30 at byte", "truncated")


def check_short_message_is_refused_by_its_decoder():
    """A truth message cut to 100 bytes and sealed again: framing and CRC hold, the decoder
    finds it short."""
    a = read_log(LOGS["a"])
    k = next(i for i, e in enumerate(a) if e.channel == "UVMS_TRUTH")
    a[k].data = sealed(a[k].data[:100])
    path = write("short.lcmlog", encode(a))
    err = str(damage_of(path))
    want = f"event {k} at byte {a[k].offset} on UVMS_TRUTH: does not decode as uvms.truth_t"
    assert want in err, err
    every_reader_refuses(path, want)


def flip_expectation(events, byte):
    """(indices the damage may be reported at, or None: a corrupted sensor message counted)."""
    k = max(i for i, e in enumerate(events) if e.offset <= byte)
    e = events[k]
    data_start = e.offset + HEADER.size + len(e.channel)
    if e.channel == "UVMS_SENSORS" and byte >= data_start:
        return None
    stamp = range(e.offset + 12, e.offset + 20)
    channel_length = range(e.offset + 20, e.offset + 24)
    # A shorter channel length can make a UVMS_* name another channel's ("UV"): that event
    # then looks intact, and the next one starts in the wrong place.
    next_too = (k == 0 and byte in stamp) or byte in channel_length
    return (k, k + 1) if next_too else (k,)


def check_single_bit_flips_are_refused():
    a = read_log(LOGS["a"])
    blob = open(LOGS["a"], "rb").read()
    rng = random.Random(SEED)
    spots = [(rng.randrange(len(blob)), rng.randrange(8)) for _ in range(FLIPS)]
    t = next(e for e in a if e.channel == "UVMS_TRUTH" and e.tick == 3)
    d0 = t.offset + HEADER.size + len("UVMS_TRUTH")
    fields = {"sync": 0, "number": 11, "timestamp": 19, "channel length": 23,
              "data length": 27, "channel name": 28 + 9, "fingerprint": d0 - t.offset,
              "utime": d0 + 15 - t.offset, "tick": d0 + 23 - t.offset,
              "session": d0 + 31 - t.offset, "a double": d0 + 40 - t.offset,
              "crc32": d0 + len(t.data) - 1 - t.offset}
    spots += [(t.offset + v, bit) for v in fields.values() for bit in (0, 3)]
    counted = 0
    for byte, bit in spots:
        bad = bytearray(blob)
        bad[byte] ^= 1 << bit
        path = write("flip.lcmlog", bytes(bad))
        where = flip_expectation(a, byte)
        if where is None:
            r = runlog.load(path).reading
            assert r.corrupted_sensors is not None and r.corrupted_sensors.count == 1, \
                f"byte {byte} bit {bit} (sensor data): not counted as a corrupted message"
            counted += 1
            continue
        err = damage_of(path)
        # The offset is where the reader found the event: after a damaged length, not where
        # the intact log has it.
        assert isinstance(err, runlog.LogDamage) and err.index in where \
            and (err.offset == a[err.index].offset or err.index != where[0]), \
            f"byte {byte} bit {bit}: {err} (expected event {where})"
    assert counted < FLIPS // 2, f"{counted} flips fell in sensor data: the sample is skewed"
    bad = bytearray(blob)
    bad[d0 + 40] ^= 1
    every_reader_refuses(write("flip.lcmlog", bytes(bad)),
                         f"event {a.index(t)} at byte {t.offset} on UVMS_TRUTH",
                         "fails its CRC-32")


def check_garbage_is_refused():
    blob = open(LOGS["a"], "rb").read()
    rng = random.Random(SEED)
    cases = {
        "random.lcmlog": (bytes(rng.randrange(256) for _ in range(5000)),
                          ["event 0 at byte 0", "not an LCM log"]),
        "text.lcmlog": (b"not a log\n" * 100, ["event 0 at byte 0", "not an LCM log"]),
        "empty.lcmlog": (b"", ["no LCM events"]),
        "prefixed.lcmlog": (b"\0\0\0\0" + blob, ["event 0 at byte 0", "sync word"]),
        "trailing.lcmlog": (blob + b"junk" * 10,
                            [f"event {len(read_log(LOGS['a']))} at byte {len(blob)}",
                             "sync word"]),
    }
    for name, (data, words) in cases.items():
        path = write(name, data)
        err = str(damage_of(path))
        assert all(w in err for w in words), f"{name}: {err}"
        refused(cli(LOGTOOL, path), *words)
        refused(cli(VIZTOOL, path, "--out", os.path.join(TMP, "g.rrd")), *words)


def check_concatenated_and_reordered_runs_are_refused():
    a, b = read_log(LOGS["a"]), read_log(LOGS["b"])
    n = len(a)
    blob_a = open(LOGS["a"], "rb").read()
    truth = [i for i, e in enumerate(a) if e.channel == "UVMS_TRUTH"]
    swapped = list(a)
    swapped[truth[5]], swapped[truth[6]] = swapped[truth[6]], swapped[truth[5]]
    repeated = a[:truth[5] + 1] + [a[truth[5]]] + a[truth[5] + 1:]
    k = truth[7]
    sensors = [i for i, e in enumerate(a) if e.channel == "UVMS_SENSORS"]
    sensors_swapped = list(a)
    sensors_swapped[sensors[5]], sensors_swapped[sensors[6]] = a[sensors[6]], a[sensors[5]]
    config_b = next(e for e in b if e.channel == "UVMS_CONFIG")
    config_b = Ev(0, config_b.stamp, "UVMS_CONFIG", sealed(  # run b's, with run a's session
        config_b.data[:24] + a[0].data[24:32] + config_b.data[32:]))
    second_config = a[:k] + [config_b] + a[k:]
    start = next(e for e in a if e.channel == "UVMS_STATUS")
    second_start = a[:k] + [start] + a[k:]
    cases = {  # name: (bytes, words the error must hold)
        "log + itself": (blob_a + blob_a,
                         [f"event {n} at byte {len(blob_a)}", f"event number 0 after {n - 1}"]),
        "log + itself, renumbered": (encode(a + a),
                                     [f"event {n} at byte {len(blob_a)}",
                                      f"follows the end record (event {n - 1})"]),
        "two runs, renumbered": (encode(a + b),
                                 [f"event {n} at byte", f"session {SESSION_B:016x}",
                                  f"event 0 has {SESSION_A:016x}", "another run"]),
        "two runs": (blob_a + open(LOGS["b"], "rb").read(),
                     [f"event {n} at byte", f"event number 0 after {n - 1}"]),
        "truth ticks swapped, renumbered": (encode(swapped),
                                            [f"event {truth[5]} at byte",
                                             "tick 6 after tick 4"]),
        "truth tick repeated, renumbered": (encode(repeated),
                                            [f"event {truth[5] + 1} at byte",
                                             "tick 5 after tick 5"]),
        "sensor ticks swapped, renumbered": (encode(sensors_swapped),
                                             [f"event {sensors[6]} at byte",
                                              "tick 5 after tick 6"]),
        "a second configuration": (encode(second_config),
                                   [f"event {k} at byte", "a second configuration (the first "
                                    "is event 0)"]),
        "a second start status": (encode(second_start),
                                  [f"event {k} at byte", "a second start status (the first is "
                                   f"event {a.index(start)})"]),
        "an event dropped": (encode(a[:k] + a[k + 1:], renumber=False),
                             [f"event {k} at byte {a[k].offset}",
                              f"event number {k + 1}, expected {k}", "missing"]),
        "two events swapped": (encode(a[:k] + [a[k + 1], a[k]] + a[k + 2:], renumber=False),
                               [f"event {k} at byte {a[k].offset}",
                                f"event number {k + 1}, expected {k}"]),
    }
    for name, (data, words) in cases.items():
        path = write("order.lcmlog", data)
        err = str(damage_of(path))
        assert all(w in err for w in words), f"{name}: {err} (expected {words})"
    every_reader_refuses(write("twice.lcmlog", blob_a + blob_a),
                         f"event {n} at byte {len(blob_a)}", "number 0 after")


def logger_copy(events):
    """The events as a logger records them: receive-time stamps (wall clock, µs), LCM's
    start-up self tests, a configuration re-sent before the start (a handshake retry) and a
    late actuators answer after the end record."""
    out = [Ev(0, 0, "LCM_SELF_TEST", b"lcm self test"), Ev(0, 0, "LCM_SELF_TEST",
                                                           b"lcm self test")]
    config = next(e for e in events if e.channel == "UVMS_CONFIG")
    last_act = [e for e in events if e.channel == "UVMS_ACTUATORS"][-1]
    for e in events:
        out.append(e)
        if e is config:
            out.append(config)
    out.append(last_act)
    return [Ev(i, LOGGER_EPOCH_US + 1000 * i, e.channel, e.data) for i, e in enumerate(out)]


def same_arrays(x, y):
    """Channels x and y hold the same values in every field but log_utime."""
    bad = [f for f in x if f != "log_utime" and not np.array_equal(x[f], y[f])]
    return not bad and x.count == y.count, bad


def received_subset(ref, got):
    """A logger on a loaded machine may lose UDP datagrams (counted in the truth ticks' gaps,
    docs/VISUALIZATION.md): every message it did receive must equal the recorder's message of
    the same tick, field for field (but log_utime), and at least half must have arrived.
    (ok, what differs, the count received)."""
    index = {int(t): i for i, t in enumerate(ref["tick"])}
    rows = [index.get(int(t), -1) for t in got["tick"]]
    if -1 in rows:
        return False, [f"tick {int(got['tick'][rows.index(-1)])}, which the recorder has not"], \
            got.count
    if got.count * 2 < ref.count:
        return False, [f"the count: {got.count} of {ref.count} messages received"], got.count
    bad = [f for f in ref if f != "log_utime" and not np.array_equal(ref[f][rows], got[f])]
    return not bad, bad, got.count


def check_logger_log_is_read_and_counted():
    a = read_log(LOGS["a"])
    path = write("logger.lcmlog", encode(logger_copy(a)))
    log, ref = runlog.load(path), runlog.load(LOGS["a"])
    r = log.reading
    uvms_events = len(a) + 2  # the re-sent configuration and the late answer
    assert r.stamps == "receive" and r.receive_stamped == uvms_events \
        and r.foreign["LCM_SELF_TEST"].count == 2 and r.config_resends == 1 \
        and r.late_answers == 1, f"counts: {vars(r)}"
    assert log.skipped == {"LCM_SELF_TEST": 2}, log.skipped
    for ch in ref:
        ok, bad = same_arrays(ref[ch], log[ch])
        assert ok, f"{ch}: {bad}"
    p = cli(LOGTOOL, path)
    for words in ("LCM_SELF_TEST: 2 events", f"{uvms_events} receive times",
                  "1 byte-identical re-sends of the configuration", "1 controller messages "
                  "after the end record"):
        assert p.returncode == 0 and words in p.stdout, f"{words!r} not in the listing " \
                                                          f"({p.stderr.strip()})"
    mixed = logger_copy(a)
    mixed[10].stamp = struct.unpack_from(">q", mixed[10].data, 8)[0]  # a recorder's stamp
    err = str(damage_of(write("mixed.lcmlog", encode(mixed))))
    assert "event 10 at byte" in err and "receive times" in err, err


def wait_until_still(path, still_s=0.5, limit_s=10.0):
    """Until the file's size has not changed for still_s seconds (at most limit_s)."""
    size, since, start = -1, time.monotonic(), time.monotonic()
    while time.monotonic() - start < limit_s:
        now = os.path.getsize(path) if os.path.exists(path) else -1
        if now != size:
            size, since = now, time.monotonic()
        elif time.monotonic() - since >= still_s:
            return
        time.sleep(0.05)


def lcm_logger_recording(out):
    """A udpm run recorded by lcm-logger on the run's URL; the logger's log path."""
    url = private_url()  # a kernel-chosen free port: no other test's bus on it
    log = os.path.join(TMP, "lcm-logger.lcmlog")
    logger = subprocess.Popen(["lcm-logger", f"--lcm-url={url}", log],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        for _ in range(100):  # its own self test is its first event: then it listens
            if os.path.exists(log) and os.path.getsize(log) > 0:
                break
            time.sleep(0.05)
        p = subprocess.run([UVMS, "run", SCENARIO, "--out", out, "--url", url,
                            "--set", "run.duration_s=1.5", "--set", "trajectory.duration_s=1.5",
                            "--set", "link.publish_truth=true",
                            # paced (0.15 s): unpaced, the run's burst of datagrams outran a
                            # logger descheduled on a loaded machine, which lost most of them
                            "--set", "link.realtime_factor=10"], capture_output=True, text=True)
        assert p.returncode == 0, f"uvms run over udpm: {p.stderr[-300:]}"
        wait_until_still(log)  # the logger has written what it received (a loaded machine)
    finally:
        logger.terminate()
        logger.wait(timeout=10)
    return log


def check_lcm_logger_recording_is_read():
    if shutil.which("lcm-logger") is None:
        print("     (lcm-logger is not installed: the recording is not made)")
        return
    out = os.path.join(TMP, "udpm")
    log_file = lcm_logger_recording(out)
    log, ref = runlog.load(log_file), runlog.load(out)
    r = log.reading
    assert r.stamps == "receive" and r.receive_stamped > 0 and "LCM_SELF_TEST" in r.foreign, \
        f"{vars(r)}"
    for ch in ("UVMS_TRUTH", "UVMS_SENSORS", "UVMS_ACTUATORS"):
        ok, bad, got = received_subset(ref[ch], log[ch])
        assert ok, f"{ch}: the logger's recording differs from the recorder's: {', '.join(bad)}"
        print(f"     {ch}: the logger received {got} of {ref[ch].count} messages, each equal")
    p = cli(LOGTOOL, log_file)
    assert p.returncode == 0 and "LCM_SELF_TEST:" in p.stdout and "receive times" in p.stdout, \
        p.stdout[-400:] + p.stderr


def with_fingerprint(events, channel, fingerprint):
    """The log's bytes with every message of `channel` carrying `fingerprint`, CRC resealed."""
    return encode([Ev(e.number, e.stamp, e.channel,
                      sealed(fingerprint + e.data[8:]) if e.channel == channel else e.data)
                   for e in events])


def check_unknown_fingerprint_is_named():
    a = read_log(LOGS["a"])
    other = bytes.fromhex("0123456789abcdef")
    first = next(i for i, e in enumerate(a) if e.channel == "UVMS_TRUTH")
    path = write("other_types.lcmlog", with_fingerprint(a, "UVMS_TRUTH", other))
    n_truth = sum(e.channel == "UVMS_TRUTH" for e in a)
    where = [f"fingerprint 0x{other.hex()}", f"event {first} at byte {a[first].offset}"]
    p = cli(LOGTOOL, path)
    assert p.returncode == 0 and all(w in p.stdout for w in where) \
        and f"UVMS_TRUTH: {n_truth} messages of unknown type" in p.stdout, p.stdout[-600:]
    assert runlog.load(path).skipped == {"UVMS_TRUTH": n_truth}, "counted in skipped"
    refused(cli(LOGTOOL, path, "--csv", "UVMS_TRUTH"), "UVMS_TRUTH", *where)
    refused(cli(LOGTOOL, path, "--plot", "UVMS_TRUTH.thrust_N", "--out",
                os.path.join(TMP, "u.png")), "UVMS_TRUTH", *where)
    refused(cli(LOGTOOL, path, "--dashboard", "--out", os.path.join(TMP, "u.png")),
            "UVMS_TRUTH", *where)
    refused(cli(VIZTOOL, path, "--out", os.path.join(TMP, "u.rrd")), "UVMS_TRUTH", *where)
    flipped = list(a)
    flipped[first] = Ev(0, a[first].stamp, "UVMS_TRUTH", other + a[first].data[8:])
    err = str(damage_of(write("fp_flip.lcmlog", encode(flipped))))
    assert all(w in err for w in where) and "CRC-32 fails" in err, err


def check_older_message_version_is_refused_naming_both():
    """lcmtypes/fingerprints.tsv: the current line of each type is the generated type's
    fingerprint; a log whose sensors carry an older listed version is refused, naming both
    versions and fingerprints, with the event and byte offset (no older version is listed
    yet, so the check lists one: version 1 with another fingerprint, today's as version 2)."""
    table = versions.load()
    runlog.load(LOGS["a"])  # puts the build's generated types (package uvms) on the path
    for name, listed in table.items():
        fp = getattr(importlib.import_module("uvms." + name), name)._get_packed_fingerprint()
        assert listed[-1][1] == fp, (f"{name}: lcmtypes/fingerprints.tsv's last version has "
                                     f"0x{listed[-1][1].hex()}, the type has 0x{fp.hex()}: a "
                                     "changed type needs a new version line")
    a = read_log(LOGS["a"])
    old = bytes.fromhex("0123456789abcdef")
    first = next(i for i, e in enumerate(a) if e.channel == "UVMS_SENSORS")
    path = write("older_sensors.lcmlog", with_fingerprint(a, "UVMS_SENSORS", old))
    now = table["sensors_t"][-1][1]
    fake = dict(table, sensors_t=[(1, old), (2, now)])
    real_load = versions.load
    versions.load = lambda path=versions.TABLE: fake
    try:
        err = str(damage_of(path))
    finally:
        versions.load = real_load
    want = ["version 1", f"0x{old.hex()}", "version 2", f"0x{now.hex()}", f"event {first}",
            f"byte {a[first].offset}"]
    assert all(w in err for w in want), err
    p = subprocess.run([UVMS, "replay", path], capture_output=True, text=True, timeout=120)
    out = p.stdout + p.stderr
    assert p.returncode == 3 and f"0x{old.hex()}" in out and f"0x{now.hex()}" in out, \
        f"uvms replay: exit {p.returncode}: {out[-400:]}"


def peak_rss_kb(*args):
    """Peak resident memory [kB] of uvmslog.py with `args`, measured by the process itself."""
    code = ("import resource, runpy, sys; sys.argv = sys.argv[1:]; rc = None\n"
            "try:\n    runpy.run_path(sys.argv[0], run_name='__main__')\n"
            "except SystemExit as e:\n    rc = e.code\n"
            "print(resource.getrusage(resource.RUSAGE_SELF).ru_maxrss, rc, file=sys.stderr)")
    p = subprocess.run([PY, "-c", code, LOGTOOL, *args], capture_output=True, text=True,
                       cwd=TMP)
    kb, rc = p.stderr.strip().splitlines()[-1].split()
    assert rc == "0", f"uvmslog {args}: exit {rc}: {p.stderr[-300:]}"
    return int(kb)


def check_memory_does_not_grow_with_the_log():
    size_a, size_long = os.path.getsize(LOGS["a"]), os.path.getsize(LOGS["long"])
    assert size_long > 8 * size_a, f"logs of {size_a} and {size_long} bytes"
    for args in ([], ["--csv", "UVMS_TRUTH", "--out", os.path.join(TMP, "t.csv")]):
        short, long_ = peak_rss_kb(LOGS["a"], *args), peak_rss_kb(LOGS["long"], *args)
        print(f"     uvmslog {' '.join(args[:2]) or 'listing'}: peak RSS {short} kB "
              f"({size_a} B log), {long_} kB ({size_long} B log)")
        assert long_ - short < MAX_RSS_GROWTH_KB, \
            f"{args[:2]}: peak grows by {long_ - short} kB from a {size_a} B to a " \
            f"{size_long} B log"


def check_read_until_damage_reads_what_precedes():
    a = read_log(LOGS["a"])
    blob = open(LOGS["a"], "rb").read()
    k = int(len(a) * 0.7)
    path = write("cut70.lcmlog", blob[:a[k].offset + 50])
    note = f"event {k} at byte {a[k].offset}"
    p = cli(LOGTOOL, path, "--read-until-damage")
    assert p.returncode == 0 and "UVMS_TRUTH" in p.stdout \
        and len(p.stderr.strip().splitlines()) == 1 and note in p.stderr \
        and p.stderr.startswith("uvmslog: note:"), p.stderr
    p = cli(LOGTOOL, path, "--csv", "UVMS_TRUTH", "--read-until-damage")
    truth = sum(e.channel == "UVMS_TRUTH" for e in a[:k])
    assert p.returncode == 0 and len(p.stdout.splitlines()) == truth + 1 and note in p.stderr, \
        f"{len(p.stdout.splitlines())} CSV lines for {truth} truth messages; {p.stderr}"
    png = os.path.join(TMP, "until.png")
    p = cli(LOGTOOL, path, "--dashboard", "--out", png, "--read-until-damage")
    assert p.returncode == 0 and os.path.getsize(png) > 1000 and note in p.stdout, \
        p.stdout + p.stderr
    rrd = os.path.join(TMP, "until.rrd")
    p = cli(VIZTOOL, path, "--out", rrd, "--read-until-damage")
    assert p.returncode == 0 and os.path.getsize(rrd) > 1000 and note in p.stderr \
        and "Traceback" not in p.stderr, p.stderr


def check_help_describes_the_checks():
    for tool in (LOGTOOL, VIZTOOL):
        before = sorted(os.listdir(TMP))
        p = cli(tool, "--help")
        assert p.returncode == 0 and not p.stderr and "--read-until-damage" in p.stdout \
            and "Exit status" in p.stdout and sorted(os.listdir(TMP)) == before, \
            f"{tool} --help: exit {p.returncode}, {p.stderr[:200]}"
    p = cli(LOGTOOL, "--help")
    for words in ("byte offset", "CRC-32", "lcm-logger", "LCM_SELF_TEST"):
        assert words in " ".join(p.stdout.split()), f"--help does not say {words!r}"


CHECKS = [check_fresh_logs_pass, check_link_faults_run_is_read,
          check_truncated_logs_are_refused_at_the_cut,
          check_short_message_is_refused_by_its_decoder, check_single_bit_flips_are_refused,
          check_garbage_is_refused, check_concatenated_and_reordered_runs_are_refused,
          check_logger_log_is_read_and_counted, check_lcm_logger_recording_is_read,
          check_unknown_fingerprint_is_named, check_older_message_version_is_refused_naming_both,
          check_memory_does_not_grow_with_the_log,
          check_read_until_damage_reads_what_precedes, check_help_describes_the_checks]

if __name__ == "__main__":
    sys.exit(checklist.run(CHECKS, TMP, setup))
