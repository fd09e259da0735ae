# SPDX-License-Identifier: Apache-2.0
"""recordings: the 3D recordings (Rerun .rrd, tools/uvmsviz.py) and the run dashboards (PNG
pages, tools/uvmslog.py --dashboard) found next to the campaigns, as relative links, and how
to open or make them. tools/main writes those of the headline runs to
ROOT/recordings/<campaign>-<run id>.rrd and ROOT/dashboards/<campaign>-<run id>.png."""
import glob
import os

from uvms_tools.log import runlog
from uvms_tools.viz import still
from uvms_tools.viz.kinematics import GeometryError
from uvms_tools.viz.scene import read_scene

from .fmt import table

RECORDINGS_DIR, RECORDING_EXT = "recordings", ".rrd"
DASHBOARDS_DIR, DASHBOARD_EXT = "dashboards", ".png"


def found(root):
    """{stem: {"rrd": path, "png": path}} of ROOT/recordings/*.rrd and ROOT/dashboards/*.png,
    by file name without extension (<campaign>-<run id>)."""
    out = {}
    for sub, ext, kind in ((RECORDINGS_DIR, RECORDING_EXT, "rrd"),
                           (DASHBOARDS_DIR, DASHBOARD_EXT, "png")):
        for p in sorted(glob.glob(os.path.join(root, sub, "*" + ext))):
            out.setdefault(os.path.basename(p)[:-len(ext)], {})[kind] = p
    return out


def split_stem(stem, campaigns):
    """(campaign, run id) of '<campaign>-<run id>' when the prefix is a known campaign name,
    else ('', stem)."""
    head, sep, tail = stem.partition("-")
    return (head, tail) if sep and head in campaigns else ("", stem)


def _link(path, out_dir, text):
    return f"[{text}]({os.path.relpath(path, out_dir)})" if path else "—"


def section(rep):
    md = ["## 3D recordings and run dashboards", ""]
    files = found(rep.root)
    if not files:
        return md + ["No 3D recordings or run dashboards next to the campaigns. Make them from "
                     "any run directory: `tools/uvmsviz.py RUN_DIR --out FILE.rrd` (a 3D "
                     "replay, Rerun format) and `tools/uvmslog.py RUN_DIR --dashboard` "
                     "(RUN_DIR/dashboard.png, one page per run); tools/main writes those of the "
                     f"headline runs to `{RECORDINGS_DIR}/` and `{DASHBOARDS_DIR}/` in the "
                     "campaigns root.", ""]
    rows = []
    for stem, kinds in sorted(files.items()):
        camp, run = split_stem(stem, rep.exps)
        rows.append([f"`{camp}`" if camp else "", f"`{run}`",
                     _link(kinds.get("rrd"), rep.out, "3D recording"),
                     _link(kinds.get("png"), rep.out, "dashboard")])
    n_rrd = sum("rrd" in k for k in files.values())
    n_png = sum("png" in k for k in files.values())
    md += [f"3D recordings: {n_rrd} (`{RECORDINGS_DIR}/*.rrd`, a replay of the run: vehicle, "
           f"hull, arm, thrust and flow arrows, EE and barycenter paths, with its time "
           f"series); run dashboards: {n_png} (`{DASHBOARDS_DIR}/*.png`, one page per run: "
           f"displacement, attitude and EE error, wrench, thrusters, joints, energies). Open a "
           f"recording with `.venv/bin/rerun FILE.rrd` (the viewer of the rerun-sdk package in "
           f"the project's venv), or `rerun FILE.rrd` once the tools package is installed; a "
           f"dashboard with any image viewer. Make more with `tools/uvmsviz.py RUN_DIR --out "
           f"FILE.rrd` and `tools/uvmslog.py RUN_DIR --dashboard`.", ""]
    md += table(["campaign", "run", "recording", "dashboard"], rows)
    return md + stills(rep, files)


def _run_log(rep, camp, run_id):
    """The run log of a recording's run (through the campaign, so the report lists it among
    the logs it read), or of ROOT/<stem>/ for a run outside the campaigns; None if missing."""
    if camp:
        e = rep.exps[camp]
        run = next((r for r in e.runs if r.get("id") == run_id), None)
        return e.log(run)
    path = os.path.join(rep.root, run_id)
    try:
        return runlog.load(path)
    except runlog.LogError:
        return None


def stills(rep, files):
    """A matplotlib still of each recording's final frame (viz/still.py: the same kinematics
    and layout as the recording)."""
    md = []
    for stem, kinds in sorted(files.items()):
        if "rrd" not in kinds:
            continue
        camp, run_id = split_stem(stem, rep.exps)
        log = _run_log(rep, camp, run_id)
        if log is None:
            md += [f"- `{stem}`: no run log to draw its final frame from.", ""]
            continue
        try:
            scene = read_scene(log)
        except (runlog.LogError, GeometryError) as e:
            md += [f"- `{stem}`: its final frame cannot be drawn ({e}).", ""]
            continue
        title = f"{camp}/{run_id}" if camp else run_id
        path = rep.figs.save(still.figure(scene, title), f"recording_{stem}.png")
        md += [f"![Final frame of {title}]({path})", ""]
    if md:
        md = ["Final frames of the recordings, drawn with matplotlib from the same kinematics "
              "and layout as the 3D replay (thrust arrows to the recording's scale; the grey "
              "strut joins the hull to the arm base):", ""] + md
    return md
