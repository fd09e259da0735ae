# SPDX-License-Identifier: Apache-2.0
"""uvmslog: the command line of tools/uvmslog.py (and of the uvmslog console script): list,
plot or export a run log (log/runlog.py), or draw a dashboard page per run (dashboard/page.py).

The one command that spans two subpackages, so it sits above both: log/ imports nothing of
dashboard/, which reads logs through log/ (the layers: uvms_tools/__init__.py).
"""
import argparse
import os
import signal
import sys

from uvms_tools.dashboard import page
from uvms_tools.log import lcm_schema, mcap_export, runlog
from uvms_tools.log.records import LogError
from uvms_tools.env import add_version_option

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
Generated types: $UVMS_LCM_PYTHON_PATH, else build/host/lcmgen/python.

Every record is checked before it is used (docs/VISUALIZATION.md "Checked reading"): each
event's framing (sync word, channel and data lengths), event numbers 0, 1, 2, ..., each uvms
message's fingerprint, CRC-32 and length, one run in order (one session, one configuration,
ticks never going back, truth ticks one by one, nothing after the end record) and, in a
recorder's log, the end record. Other channels (LCM_SELF_TEST, ...) and a logger's receive
timestamps (lcm-logger) are counted in the listing and ignored; so are corrupted sensor
messages, a link fault the run recorded. The log is read one event at a time: the listing
and --csv take the same memory for any log length.

Exit status: 0 done; 1 an error, one line on stderr: a damaged record (naming the event
number and its byte offset), a log out of order, of two runs or incomplete, a missing log,
channel or field, an output that cannot be written; 2 usage."""


def parse_args(argv):
    ap = argparse.ArgumentParser(
        description="List, plot or export a UVMS run log (LCM event log of `uvms run`), or "
                    "draw a dashboard page per run.",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    add_version_option(ap, "uvmslog")
    ap.add_argument("log", nargs="+", metavar="LOG",
                    help="run.lcmlog or a run directory; with --dashboard also a campaign "
                         "directory (runs/*/run.lcmlog) and several of either")
    ap.add_argument("--plot", action="append", metavar="CHANNEL.FIELD[.LABEL|[IDX]]",
                    help="plot a field (all components without LABEL/IDX) against time; "
                         "repeatable, one panel each")
    ap.add_argument("--csv", metavar="CHANNEL",
                    help="export a channel as CSV, one row per message (to --out, default "
                         "stdout)")
    ap.add_argument("--mcap", metavar="OUT.mcap",
                    help="write the log as MCAP for Foxglove, PlotJuggler and other MCAP "
                         "readers: every channel a topic of JSON messages with a JSON Schema "
                         "made from its LCM type (int64 as strings), log time = the message's "
                         "simulated time (docs/VISUALIZATION.md)")
    ap.add_argument("--dashboard", action="store_true",
                    help="one PNG page per run: vehicle motion, EE error, wrench, thrusters, "
                         "joints, energy (default RUN_DIR/dashboard.png)")
    ap.add_argument("--out", help="output file: FILE.png for --plot and --dashboard (one run), CSV "
                                  "for --csv ('-': stdout)")
    ap.add_argument("-j", "--jobs", type=int, default=os.cpu_count() or 1, metavar="N",
                    help="--dashboard: runs drawn N at a time (default: all cores, as uvms "
                         "campaign -j)")
    ap.add_argument("--title", help="figure title (--plot, --dashboard of one run)")
    ap.add_argument("--all-ticks", action="store_true",
                    help="--plot: keep tick -1 (telemetry's configuration acknowledgement)")
    ap.add_argument("--read-until-damage", action="store_true",
                    help="read a damaged or incomplete log as far as it is intact: every "
                         "event before the first failed check (a note names it), instead of "
                         "refusing the log")
    a = ap.parse_args(argv)
    modes = sum(bool(m) for m in (a.plot, a.csv, a.dashboard, a.mcap))
    if modes > 1:
        ap.error("--plot, --csv, --mcap and --dashboard are exclusive")
    if not a.dashboard and len(a.log) > 1:
        ap.error("one LOG only (several only with --dashboard)")
    if a.plot and not a.out:
        ap.error("--out is required with --plot")
    if a.jobs < 1:
        ap.error("-j must be at least 1")
    return a


def print_damage_note(reading, prog="uvmslog"):
    note = runlog.damage_note(reading)
    if note:
        print(f"{prog}: note: {note}", file=sys.stderr)


def main(argv=None):
    if hasattr(signal, "SIGPIPE"):
        signal.signal(signal.SIGPIPE, signal.SIG_DFL)  # `uvmslog.py LOG | head` exits quietly
    a = parse_args(argv)
    until = a.read_until_damage
    try:
        if a.dashboard:
            return page.run_dashboards(a.log, a.out, a.jobs, a.title, until)
        path = a.log[0]
        if a.plot:
            runlog.check_png_out(a.out)
            log = runlog.load(path, {runlog.parse_field_spec(s)[0] for s in a.plot}, until)
            runlog.plot_fields(log, a.plot, a.out, a.title, a.all_ticks)
            print_damage_note(log.reading)
            print(f"wrote {a.out}")
        elif a.mcap:
            runlog.check_out_file(a.mcap, ".mcap", f"--mcap {a.mcap}")
            counts, reading = mcap_export.export(path, a.mcap, until)
            print_damage_note(reading)
            print(f"wrote {a.mcap} ({sum(counts.values())} messages on {len(counts)} topics: "
                  + ", ".join(f"{c} {n}" for c, n in counts.items()) + ")")
        elif a.csv:
            out = a.out or "-"
            rows, reading = runlog.export_csv(path, a.csv, out, until)
            print_damage_note(reading)
            if out != "-":
                print(f"wrote {out} ({rows} rows)")
        else:
            print_damage_note(runlog.list_log(path, until))
    except (LogError, lcm_schema.LcmSchemaError) as e:
        print(f"uvmslog: error: {e}", file=sys.stderr)
        return 1
    except OSError as e:  # the output could not be written (--out in a missing directory, ...)
        print(f"uvmslog: error: {e}", file=sys.stderr)
        return 1
    return 0
