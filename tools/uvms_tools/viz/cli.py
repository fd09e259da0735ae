# SPDX-License-Identifier: Apache-2.0
"""cli: `tools/uvmsviz.py RUN_DIR_OR_LOG [--out FILE.rrd] [--every K] [--name NAME]`."""
import argparse
import os
import sys

from uvms_tools.log import runlog

from . import rerun_export, scene as scene_mod
from .kinematics import GeometryError
from uvms_tools.env import add_version_option

PROG = "uvmsviz"
LOG_NAME = "run.lcmlog"


def parse_args(argv):
    ap = argparse.ArgumentParser(
        description="Turn a UVMS run log into a Rerun recording (.rrd): the vehicle, its hull,\n"
                    "the arm, thrusts, flow, obstacles and contacts in 3D, with time series of\n"
                    "thrusts, motors, joints, errors and energies, on the timeline `sim_time`\n"
                    "(simulated time). Open it with `.venv/bin/rerun FILE.rrd`.",
        epilog="Example:\n  tools/uvmsviz.py out/run --out run.rrd --every 5\n"
               "Geometry comes from the log's UVMS_SCENE message (else UVMS_CONFIG, without "
               "hull and obstacles).\n"
               "Every record of the log is checked as tools/uvmslog.py --help describes\n"
               "(docs/VISUALIZATION.md \"Checked reading\"): a damaged record, a log out of "
               "order,\nof two runs or incomplete is refused, naming the event and its byte "
               "offset.\nExit status: 0 written; 1 an error (one line on stderr); 2 usage.",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    add_version_option(ap, "uvmsviz")
    ap.add_argument("run", metavar="RUN_DIR_OR_LOG",
                    help=f"a run directory (holding {LOG_NAME}) or an LCM log file")
    ap.add_argument("--out", metavar="FILE.rrd",
                    help="recording to write (default: the log's name with .rrd, beside "
                         "the log: RUN_DIR/run.lcmlog -> RUN_DIR/run.rrd)")
    ap.add_argument("--every", metavar="K", type=int, default=1,
                    help="keep every K-th truth sample (ticks 0, K, 2K, ...; default 1)")
    ap.add_argument("--name", help="recording name shown by the viewer (default: the run "
                                   "directory's name)")
    ap.add_argument("--read-until-damage", action="store_true",
                    help="draw a damaged or incomplete log as far as it is intact (a note "
                         "names the first damage) instead of refusing it")
    a = ap.parse_args(argv)
    if a.every < 1:
        ap.error("--every must be >= 1")
    return a


def log_path(run):
    """The log of a run directory or a log file; runlog.LogError if there is none."""
    path = os.path.join(run, LOG_NAME) if os.path.isdir(run) else run
    if not os.path.isfile(path):
        raise runlog.LogError(f"{path}: no such file or directory" if not os.path.isdir(run)
                               else f"{run}: directory without {LOG_NAME}")
    return path


def out_path(out, log_file):
    """The recording's path: `out`, else the log's name with .rrd beside the log (run.lcmlog ->
    run.rrd, so two logs in one directory get two recordings). Checked before anything is
    decoded or written: runlog.LogError when it is a directory, the log itself, or in a
    directory that does not exist."""
    if not out:
        stem = os.path.splitext(os.path.basename(log_file))[0]
        out = os.path.join(os.path.dirname(os.path.abspath(log_file)), stem + ".rrd")
    runlog.check_out_file(out, label=out)
    if os.path.abspath(out) == os.path.abspath(log_file):
        raise runlog.LogError(f"{out}: cannot write over the log it is made from")
    return out


def load_scene(path, every, until_damage=False):
    """(Scene, note or None) of the log at `path`, every record checked (runlog.load)."""
    log = runlog.load(path, until_damage=until_damage)
    if not log:
        raise runlog.LogError(f"{path}: no UVMS messages (not a UVMS run log)")
    scene = scene_mod.subsample(scene_mod.read_scene(log), every)
    return scene, runlog.damage_note(log.reading)


def write(scene, out, name):
    """rerun_export.export, with the Rerun file sink's RuntimeError as an OSError naming out."""
    try:
        return rerun_export.export(scene, out, name)
    except RuntimeError as e:  # the Rerun SDK's file sink
        raise OSError(f"{out}: cannot write ({e})") from e


def main(argv=None):
    a = parse_args(argv)
    try:
        path = log_path(a.run)
        out = out_path(a.out, path)  # before decoding: a bad --out fails fast
        scene, damage = load_scene(path, a.every, a.read_until_damage)
        name = a.name or os.path.basename(os.path.dirname(os.path.abspath(path)))
        for note in scene.notes + ([damage] if damage else []):
            print(f"{PROG}: note: {note}", file=sys.stderr)
        paths = write(scene, out, name)
    except (runlog.LogError, GeometryError, OSError) as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return 1
    size_mb = os.path.getsize(out) / 1e6
    print(f"wrote {out}: {scene.truth.count} ticks, {len(paths)} entities, {size_mb:.1f} MB")
    return 0
