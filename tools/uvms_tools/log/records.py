# SPDX-License-Identifier: Apache-2.0
"""records: a UVMS run log read record by record, every record checked before it is used.

The readers of run logs (tools/uvmslog.py, its --dashboard, tools/uvmsviz.py) read through
`scan()`: one pass over the file, one event in memory at a time (memory independent of the
log's length). Standard library only.

LCM's event log format (lcm/eventlog.c), all big-endian: per event a 28-byte header (sync word
0xEDA1DA01, event number int64, timestamp int64 [µs], channel length int32, data length
int32), then the channel name, then the data. Every uvms message (lcmtypes/*.lcm) begins with
its type's 8-byte fingerprint, then utime, tick and session (int64 each), and ends with its
crc32 field: the CRC-32 (IEEE 802.3, zlib's) of every byte before it (sil/msg/codec.h).

What is checked, in this order (docs/VISUALIZATION.md "Checked reading" says the same for
users):

  framing     every event: the sync word; a channel name of 1..MAX_CHANNEL_BYTES printable
              ASCII bytes; a data length that ends within the file; no partial event at the
              end. A damaged length of an event on another channel (below) shows as damage of
              the next event (its sync word).
  numbers     event numbers 0, 1, 2, ... with none missing, repeated or going back (the run's
              recorder and lcm-logger both number every event they write).
  messages    an event on a uvms channel (named UVMS_*) or carrying a uvms fingerprint: at
              least MIN_MESSAGE_BYTES and at most MAX_MESSAGE_BYTES long, its CRC-32 matches,
              its fingerprint is that of its channel's type and the same on every event of the
              channel; decoded, the message uses exactly its bytes.
              A UVMS_SENSORS message failing its CRC is not damage but counted: the link-fault
              injection records corrupted sensor messages as they were sent (docs/FAULTS.md).
              An intact message (its CRC matches) of a type this build does not generate is
              counted per channel with its fingerprint, not decoded.
  one run     every intact message carries the session of the first one; the timestamps are
              of one kind throughout: the recorder's (each the message's own utime) or a
              logger's receive times (none equal to it: counted, not used); one configuration
              (a byte-identical re-send before the start is a handshake retry: counted, not
              used); one start status; nothing after the end record (in a logger's log, a
              controller message of a tick up to the end record's, a late answer: counted, not
              used);
              on every channel the tick never goes back; on UVMS_TRUTH it goes up by exactly
              one from 0 (a logger's log: it only rises, a gap is a lost packet, counted).
  complete    a log of the recorder ends with the end record (the final run_status_t) and
              its last truth tick is the end record's.

Not checked: the timestamps and the data of events on other channels (LCM_SELF_TEST, ...),
which are counted and skipped; a damaged channel name on such an event. The CRC-32 catches
every error of up to 3 bits in a message of up to 11 kB (Hamming distance 4 up to 91,607 bits;
the harness's messages are under 8 kB) and any burst of up to 32 bits, so it finds damage,
not forgery: anyone can write a log with matching CRCs (docs/FAULTS.md "Sessions").
"""
import io
import os
import struct
import zlib

from . import versions

LCM_SYNC = 0xEDA1DA01
# LCM event header: sync word, event number, timestamp [µs], channel length, data length [bytes]
EVENT_HEADER = struct.Struct(">Iqqii")
# The start of every uvms message: fingerprint, utime [µs], tick, session
MESSAGE_HEAD = struct.Struct(">8sqqq")
CRC_BYTES = 4  # the crc32 field, last in every uvms message
MIN_MESSAGE_BYTES = MESSAGE_HEAD.size + CRC_BYTES
# Larger than any uvms message (controller_config_t, the largest fixed one, is 2,162 bytes;
# scene_t grows by 40 bytes and a name per obstacle): a longer one is a damaged length. Bounds
# the memory one event takes.
MAX_MESSAGE_BYTES = 1 << 20
# LCM's channel names have at most 63 bytes (LCM_MAX_CHANNEL_NAME_LENGTH); its log reader
# accepts up to 999. Beyond this a channel length is damage.
MAX_CHANNEL_BYTES = 255
READ_BUFFER_BYTES = 1 << 20
# Channels told apart in the counts; the events of any further ones are counted together
# under OTHER_CHANNELS (a garbage log's memory stays bounded).
MAX_CHANNELS = 1000
OTHER_CHANNELS = "(other channels)"

UVMS_PREFIX = "UVMS_"  # every uvms channel's name begins so
SENSORS, TRUTH, CONFIG, STATUS = "UVMS_SENSORS", "UVMS_TRUTH", "UVMS_CONFIG", "UVMS_STATUS"
# Sent by the controller: in a logger's log they may arrive after the plant's end record.
CONTROLLER_CHANNELS = ("UVMS_ACTUATORS", "UVMS_TELEMETRY")
# run_status_t.state (lcmtypes/run_status_t.lcm)
RUNNING, FINISHED, FAILED = 1, 2, 3

RECORDER, RECEIVE = "recorder", "receive"  # the two kinds of event timestamps


class LogError(Exception):
    """A log, a field or the generated types could not be found or read."""


class LogDamage(LogError):
    """A record that fails a check: names the event (its position from 0, which is its event
    number in an intact log) and the byte offset where the event starts."""

    def __init__(self, path, index, offset, what, channel=None):
        self.path, self.index, self.offset, self.what = path, index, offset, what
        self.channel = channel
        on = f" on {channel}" if channel else ""
        super().__init__(f"{path}: event {index} at byte {offset}{on}: {what}")


class Event:
    """One event of the file: where it is and what it holds. `data` is the whole data of a
    possible uvms message, else its first 8 bytes (the rest is not read)."""
    __slots__ = ("index", "number", "stamp", "channel", "offset", "size", "data")

    def __init__(self, index, number, stamp, channel, offset, size, data):
        self.index, self.number, self.stamp, self.channel = index, number, stamp, channel
        self.offset, self.size, self.data = offset, size, data


def fingerprint_hex(fp):
    return "0x" + bytes(fp).hex()


def read_events(path, fh, file_size, wanted):
    """The events of an open log, framing checked (LogDamage otherwise). `wanted(channel,
    fingerprint)` says whether an event's data is read whole (a possible uvms message)."""
    offset = index = 0
    while offset < file_size:
        head = fh.read(EVENT_HEADER.size)
        if len(head) < EVENT_HEADER.size:
            sync_prefix = LCM_SYNC.to_bytes(4, "big")[:len(head)]
            raise LogDamage(path, index, offset, (
                f"{len(head)} bytes left, less than an event header ({EVENT_HEADER.size} "
                "bytes): " + ("truncated" if head[:4] == sync_prefix[:len(head[:4])] else
                              "not an LCM log" if index == 0 else "no LCM sync word: damaged")))
        sync, number, stamp, ch_len, size = EVENT_HEADER.unpack(head)
        if sync != LCM_SYNC:
            raise LogDamage(path, index, offset, (
                f"no LCM sync word (0x{sync:08X}, not 0x{LCM_SYNC:08X}): "
                + ("not an LCM log" if index == 0 else
                   "damaged here, or the previous event's data length is damaged")))
        left = file_size - offset - EVENT_HEADER.size
        if not 0 < ch_len <= MAX_CHANNEL_BYTES:
            raise LogDamage(path, index, offset, f"channel length {ch_len} (expected 1 to "
                            f"{MAX_CHANNEL_BYTES} bytes): damaged")
        if size < 0 or ch_len + size > left:
            raise LogDamage(path, index, offset, (
                f"data length {size}: the event needs {ch_len + size} bytes after its header, "
                f"the file has {left}: truncated or damaged"))
        raw = fh.read(ch_len)
        if not all(0x20 <= b < 0x7F for b in raw):
            raise LogDamage(path, index, offset, f"channel name {raw!r} is not printable ASCII: "
                            "damaged")
        channel = raw.decode("ascii")
        data = fh.read(min(size, 8))
        if wanted(channel, data):
            if size > MAX_MESSAGE_BYTES:
                raise LogDamage(path, index, offset, f"data length {size} exceeds any uvms "
                                f"message ({MAX_MESSAGE_BYTES} bytes): damaged", channel)
            data += fh.read(size - len(data))
        elif size > len(data):
            fh.seek(size - len(data), io.SEEK_CUR)
        yield Event(index, number, stamp, channel, offset, size, data)
        offset += EVENT_HEADER.size + ch_len + size
        index += 1


class Tally:
    """A count with where it first happened: event, byte offset, and a detail (a fingerprint)."""
    __slots__ = ("count", "index", "offset", "detail")

    def __init__(self, ev, detail=None):
        self.count, self.index, self.offset, self.detail = 0, ev.index, ev.offset, detail

    def where(self):
        return f"event {self.index} at byte {self.offset}"


class Reading:
    """What one pass over a log found: the counts the listing reports and the run's identity.

    events, bytes_read: events and bytes that passed (all of them unless damage stopped an
    --read-until-damage pass: `damage` is then the LogDamage); session; stamps (RECORDER,
    RECEIVE or None without uvms messages); receive_stamped: events whose timestamp is a
    receive time (ignored); foreign {channel: Tally (detail: first fingerprint)}: events of
    other channels; unknown {channel: Tally (detail: fingerprint)}: intact messages of a type
    not generated here; corrupted_sensors: Tally or None; config_resends, late_answers,
    truth_gaps: counts; end: the end record (run_status_t) or None, at end_index."""

    def __init__(self, path):
        self.path = path
        self.events = self.bytes_read = 0
        self.session = None
        self.stamps = None
        self.receive_stamped = 0
        self.foreign, self.unknown = {}, {}
        self.corrupted_sensors = None
        self.config_resends = self.late_answers = self.truth_gaps = 0
        self.end = None
        self.end_index = None
        self.damage = None
        self.incomplete = None  # why a recorder's log is incomplete (with --read-until-damage)
        self.channels = set()   # every channel met (up to MAX_CHANNELS)

    def met(self, channel):
        """The name `channel` is counted under: itself, or OTHER_CHANNELS past MAX_CHANNELS."""
        if channel in self.channels or len(self.channels) < MAX_CHANNELS:
            self.channels.add(channel)
            return channel
        return OTHER_CHANNELS


def _tally(table, key, ev, detail=None):
    t = table.get(key)
    if t is None:
        t = table[key] = Tally(ev, detail)
    t.count += 1
    return t


class RunCheck:
    """The whole-log checks, fed every event in order (module docstring). `types`: {packed
    fingerprint: generated class}; `channel_types`: {channel: type name}."""

    def __init__(self, path, types, channel_types):
        self.path, self.types, self.channel_types = path, types, channel_types
        self.versions = versions.load()
        self.r = Reading(path)
        self.fingerprints = {}   # channel -> (fingerprint, first event)
        self.last_tick = {}      # channel -> tick of its last intact message
        self.session_index = None
        self.stamps_index = None
        self.config = None       # (event, data) of the first configuration
        self.running_index = None

    def damage(self, ev, what):
        return LogDamage(self.path, ev.index, ev.offset, what, ev.channel)

    def wanted(self, channel, head):
        """Whether an event may be a uvms message (its data is read whole and checked): on a
        channel named UVMS_*, or carrying a uvms type's fingerprint."""
        return (channel.startswith(UVMS_PREFIX) or channel in self.channel_types
                or bytes(head[:8]) in self.types)

    def check(self, ev):
        """The class to decode `ev` with when it is an intact uvms message of a known type;
        None for an event that is counted and skipped. Raises LogDamage."""
        r = self.r
        if ev.number != ev.index:
            raise self.damage(ev, self._number_problem(ev.number, ev.index))
        if not self.wanted(ev.channel, ev.data):
            _tally(r.foreign, r.met(ev.channel), ev, fingerprint_hex(ev.data[:8]))
            return None
        data = ev.data
        if len(data) < MIN_MESSAGE_BYTES:
            raise self.damage(ev, f"{len(data)} data bytes, too short for a uvms message (at "
                                  f"least {MIN_MESSAGE_BYTES}): truncated or damaged")
        if r.met(ev.channel) == OTHER_CHANNELS:
            raise self.damage(ev, f"a uvms message on a channel past the first {MAX_CHANNELS}: "
                                  "not a run log")
        fp = bytes(data[:8])
        cls = self.types.get(fp)
        if cls is None:
            self._check_version(ev, fp)
        stored = int.from_bytes(data[-CRC_BYTES:], "big")
        computed = zlib.crc32(memoryview(data)[:-CRC_BYTES]) & 0xFFFFFFFF
        if stored != computed:
            if ev.channel == SENSORS:
                if r.corrupted_sensors is None:
                    r.corrupted_sensors = Tally(ev)
                r.corrupted_sensors.count += 1
                return None
            raise self.damage(ev, self._crc_problem(cls, fp, stored, computed))
        self._check_type(ev, fp, cls)
        _, utime, tick, session = MESSAGE_HEAD.unpack_from(data)
        self._check_run(ev, utime, session)
        status = decode_message(self.path, ev, cls) if ev.channel == STATUS and cls else None
        if not self._check_order(ev, tick, status):
            return None  # a logger's extra copy: counted, not used
        if cls is None:
            _tally(r.unknown, ev.channel, ev, fingerprint_hex(fp))
        return cls

    @staticmethod
    def _number_problem(number, expected):
        if expected == 0:
            return f"event number {number}, not 0: the log's first events are missing"
        if number < expected:
            return (f"event number {number} after {expected - 1}: the numbers go back (a log "
                    "appended to another, or events repeated or reordered)")
        return (f"event number {number}, expected {expected}: events missing (or reordered)")

    def _crc_problem(self, cls, fp, stored, computed):
        crc = f"stored CRC-32 0x{stored:08x}, computed 0x{computed:08x}"
        if cls is None:
            return (f"fingerprint {fingerprint_hex(fp)} is no uvms type's and the CRC-32 fails "
                    f"({crc}): damaged, or written by a build without CRCs")
        return f"fails its CRC-32 ({crc}): damaged"

    def _check_version(self, ev, fp):
        """A message of an older listed version of its channel's type is refused, naming both
        versions (lcmtypes/fingerprints.tsv)."""
        expected = self.channel_types.get(ev.channel)
        problem = expected and versions.older_version_problem(self.versions, expected, fp)
        if problem:
            raise self.damage(ev, problem)

    def _check_type(self, ev, fp, cls):
        ch = ev.channel
        expected = self.channel_types.get(ch)
        if cls is not None and cls.__name__ != expected:
            where = f"its channel is {self._channel_of(cls.__name__)}" if expected is None \
                else f"{ch} carries uvms.{expected}"
            raise self.damage(ev, f"a uvms.{cls.__name__} message ({where}): damaged channel "
                                  "name or fingerprint")
        first = self.fingerprints.setdefault(ch, (fp, ev.index))
        if first[0] != fp:
            raise self.damage(ev, f"fingerprint {fingerprint_hex(fp)}, but event {first[1]} on "
                                  f"{ch} has {fingerprint_hex(first[0])}: messages of two "
                                  "builds' types (logs of two builds concatenated?)")

    def _channel_of(self, type_name):
        return next((c for c, t in self.channel_types.items() if t == type_name), "none")

    def _check_run(self, ev, utime, session):
        r = self.r
        if session == 0:
            raise self.damage(ev, "session 0 (no run's)")
        if r.session is None:
            r.session, self.session_index = session, ev.index
        elif session != r.session:
            raise self.damage(ev, (
                f"session {session & (2**64 - 1):016x}, but event {self.session_index} "
                f"has {r.session & (2**64 - 1):016x}: a message of another run (logs of "
                "two runs concatenated?)"))
        kind = RECORDER if ev.stamp == utime else RECEIVE
        if r.stamps is None:
            r.stamps, self.stamps_index = kind, ev.index
        elif kind != r.stamps:
            raise self.damage(ev, (
                f"timestamp {ev.stamp} µs, message utime {utime} µs: "
                + (f"unlike event {self.stamps_index} and those after it, whose timestamps "
                   "are their utime (the recorder's): a damaged timestamp"
                   if r.stamps == RECORDER else
                   f"equal, while event {self.stamps_index} and those after it carry receive "
                   "times (a logger's): logs of both kinds mixed, or a damaged timestamp")))
        if kind == RECEIVE:
            r.receive_stamped += 1

    def _check_order(self, ev, tick, status):
        """The run-order checks of one intact message; False for a message a logger recorded
        that the run's recorder does not (a configuration re-sent, a late answer): counted."""
        r, ch = self.r, ev.channel
        if r.end is not None:
            if r.stamps == RECEIVE and ch in CONTROLLER_CHANNELS and tick <= r.end.tick:
                r.late_answers += 1
                return False
            raise self.damage(ev, f"follows the end record (event {r.end_index}): a second run "
                                  "appended, or events reordered")
        last = self.last_tick.get(ch)
        if ch == TRUTH:
            self._check_truth(ev, tick, last)
        elif last is not None and tick < last:
            raise self.damage(ev, f"tick {tick} after tick {last}: the ticks go back (records "
                                  "reordered or repeated, or a second run appended)")
        self.last_tick[ch] = tick
        if ch == CONFIG and not self._check_config(ev):
            return False
        if status is not None:
            self._check_status(ev, status)
        return True

    def _check_truth(self, ev, tick, last):
        if self.r.stamps == RECEIVE:  # a logger may start late and lose packets
            if last is not None and tick <= last:
                raise self.damage(ev, f"tick {tick} after tick {last}: the truth ticks go back "
                                      "or repeat (records reordered or repeated, or a second "
                                      "run appended)")
            if last is not None:
                self.r.truth_gaps += tick - last - 1
            return
        expected = 0 if last is None else last + 1
        if tick != expected:
            after = "as the first" if last is None else f"after tick {last}"
            raise self.damage(ev, f"tick {tick} {after}: the truth ticks go up by one from 0 "
                                  "(records missing, repeated or reordered, or a second run "
                                  "appended)")

    def _check_config(self, ev):
        """False for a re-sent configuration (counted)."""
        if self.config is None:
            self.config = (ev.index, bytes(ev.data))
            return True
        if self.running_index is None and bytes(ev.data) == self.config[1]:
            self.r.config_resends += 1
            return False
        raise self.damage(ev, f"a second configuration (the first is event {self.config[0]}): "
                              "a second run")

    def _check_status(self, ev, status):
        r = self.r
        if status.state == RUNNING:
            if self.running_index is not None:
                raise self.damage(ev, f"a second start status (the first is event "
                                      f"{self.running_index}): a second run")
            self.running_index = ev.index
        elif status.state in (FINISHED, FAILED):
            r.end, r.end_index = status, ev.index

    def finish(self):
        """After the last event: LogError for a file without events, or a recorder's log
        that is incomplete (no end record, or its truth stops short of it)."""
        r = self.r
        if r.events == 0:
            raise LogError(f"{self.path}: no LCM events (an empty log, or not an LCM log)")
        if r.stamps != RECORDER:
            return
        if r.end is None and STATUS not in r.unknown:
            r.incomplete = (f"no end record (the final run_status_t) after event {r.events - 1} "
                            f"(byte {r.bytes_read}): cut short (truncated between events, or "
                            "the run was killed)")
        elif (r.end is not None and self.last_tick.get(TRUTH) is not None
              and self.last_tick[TRUTH] != r.end.tick):
            r.incomplete = (f"the truth ends at tick {self.last_tick[TRUTH]}, the end record "
                            f"(event {r.end_index}) says {r.end.tick} ticks")


def decode_message(path, ev, cls):
    """The message of event `ev` decoded as `cls` (a generated uvms type); LogDamage unless it
    decodes and uses exactly the event's bytes."""
    buf = io.BytesIO(ev.data)
    try:
        msg = cls.decode(buf)
    except (ValueError, struct.error, UnicodeDecodeError, OverflowError) as e:
        raise LogDamage(path, ev.index, ev.offset, f"does not decode as uvms.{cls.__name__} "
                        f"({e})", ev.channel) from e
    if buf.tell() != len(ev.data):
        raise LogDamage(path, ev.index, ev.offset, f"{len(ev.data) - buf.tell()} bytes after "
                        f"the uvms.{cls.__name__} message: a damaged length", ev.channel)
    return msg


class Scan:
    """One checked pass over the log file at `path`: iterating yields (event, message) for
    every intact uvms message of a known type on the channels in `keep` (None: all), in
    order, decoded (`decode_message`); one event is in memory at a time. `reading` (a
    Reading) holds what the pass found, complete once the iteration ends.

    Damage (a LogDamage, or an incomplete recorder's log as LogError) is raised, unless
    `until_damage`: then the pass stops before the damaged event and the Reading's `damage`
    (or `incomplete`) says what stopped it; the events before it were all checked. Damage
    at the first event is raised either way: nothing precedes it."""

    def __init__(self, path, types, channel_types, keep=None, until_damage=False):
        self.path, self.types, self.channel_types = path, types, channel_types
        self.keep, self.until_damage = keep, until_damage
        self.reading = Reading(path)

    def __iter__(self):
        path = self.path
        check = RunCheck(path, self.types, self.channel_types)
        r = self.reading = check.r
        try:
            fh = open(path, "rb", buffering=READ_BUFFER_BYTES)
        except OSError as e:
            raise LogError(f"{path}: cannot open ({e.strerror or e})") from e
        with fh:
            try:
                for ev in read_events(path, fh, os.fstat(fh.fileno()).st_size, check.wanted):
                    cls = check.check(ev)
                    msg = None
                    if cls is not None and (self.keep is None or ev.channel in self.keep):
                        msg = decode_message(path, ev, cls)
                    r.events += 1
                    r.bytes_read = ev.offset + EVENT_HEADER.size + len(ev.channel) + ev.size
                    if msg is not None:
                        yield ev, msg
            except LogDamage as e:
                if not self.until_damage or r.events == 0:
                    raise
                r.damage = e
            except OSError as e:
                raise LogError(f"{path}: cannot read ({e.strerror or e})") from e
        if r.damage is None:
            check.finish()
        if r.incomplete and not self.until_damage:
            raise LogError(f"{path}: incomplete: {r.incomplete}; --read-until-damage reads "
                           "it as far as it goes")
