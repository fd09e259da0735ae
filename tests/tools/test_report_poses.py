# SPDX-License-Identifier: Apache-2.0
"""The report's Fig. 7 (tools/uvms_tools/report/figures/poses.py, text/poses.py) on two fresh short
runs, case IV and case VII in stagnant flow:

- the pose data the figure plots (pose_points) puts the end-effector at the plant's own logged
  ee_position_m and the vehicle at its logged position_m (first and final truth samples), and
  agrees with the plant's summary.json (final EE, final and initial vehicle position, final
  barycenter): independent of the Python forward kinematics;
- the arm's segments have the standard-DH closed-form lengths √(a_i² + d_i²) of the logged
  scene, the hull box its logged edge lengths and center;
- a log without UVMS_SCENE still gives the arm (from UVMS_CONFIG), no hull, and a note;
- through the report's loaders (a campaign directory laid out like `uvms campaign` writes it,
  with the build's schema): the figure is written and not blank, and the section's table shows
  the truth final EE position; with the runs missing the section says so;
- the recordings section (text/recordings.py): without ROOT/recordings and ROOT/dashboards one
  sentence on how to make them; with them, a relative link per file, no absolute path.

Usage: test_report_poses.py UVMS_BINARY REPO_ROOT
"""
import json
import os
import shutil
import subprocess
import sys

import numpy as np

UVMS, REPO = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(REPO, "tools"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report_testkit import TABLE_ID  # noqa: E402
from uvms_tools.log import runlog  # noqa: E402
from PIL import Image  # noqa: E402

from uvms_tools.report.context import Report  # noqa: E402
from uvms_tools.report.figures import poses as fig_poses  # noqa: E402
from uvms_tools.report.load import schema as schema_mod  # noqa: E402
from uvms_tools.report.text import poses as text_poses  # noqa: E402
from uvms_tools.report.text import recordings  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checklist  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

TMP = scratch_dir("uvms-report-poses-")  # removed at exit (tests/support/scratch.py)
ROOT = os.path.join(TMP, "campaigns")
EXP_DIR = os.path.join(ROOT, "exp1")
CASES = {"IV": "IV_stagnant", "VII": "VII_stagnant"}
DURATION_S = 1.5
# The plant computes the EE in double with the same DH recursion: agreement to rounding.
TOL_M = 1e-9
RUNS = {}  # case -> (run dir, runlog.Log, summary dict)


def make_runs():
    for case, rid in CASES.items():
        out = os.path.join(EXP_DIR, "runs", rid)
        scen = os.path.join(REPO, "sil", "scenarios", "paper", f"case_{rid}.toml")
        p = subprocess.run([UVMS, "run", scen, "--set", f"run.duration_s={DURATION_S}",
                            "--out", out], capture_output=True, text=True, cwd=REPO)
        assert p.returncode == 0, f"uvms run {rid}: {p.stderr.strip()[-300:]}"
        summary = json.load(open(os.path.join(out, "summary.json")))
        RUNS[case] = (out, runlog.load(os.path.join(out, "run.lcmlog")), summary)
    rows = [dict(id=rid, **{"control.case": case, "environment.density_error": False,
                            "environment.unsteady_flow.enabled": False,
                            "status": RUNS[case][2]["status"]})
            for case, rid in CASES.items()]
    with open(os.path.join(EXP_DIR, "results.json"), "w") as fh:
        json.dump(dict(TABLE_ID, name="exp1_cases", runs=rows), fh)
    with open(os.path.join(EXP_DIR, "plan.json"), "w") as fh:
        json.dump(dict(TABLE_ID, name="exp1_cases",
                       runs=[{"id": r["id"], "overrides": []} for r in rows]), fh)


def close(a, b, tol=TOL_M):
    return float(np.max(np.abs(np.asarray(a, float) - np.asarray(b, float)))) <= tol


def check_poses_match_truth():
    for case, (_, log, summ) in RUNS.items():
        stowed, final, _ = fig_poses.run_poses(log)
        tr = log["UVMS_TRUTH"]
        assert close(final["ee_m"], tr["ee_position_m"][-1]), \
            f"{case}: final EE {final['ee_m']} vs truth {tr['ee_position_m'][-1]}"
        assert close(stowed["ee_m"], tr["ee_position_m"][0]), f"{case}: stowed EE vs truth"
        assert close(final["vehicle_m"], tr["position_m"][-1]), f"{case}: final vehicle"
        assert close(final["ee_m"], summ["final_ee_position_m"]), \
            f"{case}: final EE vs summary.json {summ['final_ee_position_m']}"
        assert close(final["vehicle_m"], summ["final_vehicle_position_m"]), \
            f"{case}: final vehicle vs summary.json"
        assert close(stowed["vehicle_m"], summ["initial_vehicle_position_m"]), \
            f"{case}: stowed vehicle vs summary.json"
        assert close(final["barycenter_m"], summ["final_barycenter_m"]), \
            f"{case}: barycenter vs summary.json"
        assert final["t_s"] >= DURATION_S - 1e-6, f"{case}: final sample at {final['t_s']} s"


def check_arm_and_hull_geometry():
    _, log, _ = RUNS["VII"]
    sc = log["UVMS_SCENE"]
    n = int(sc["num_joints"][0])
    a, d = np.asarray(sc["link_a_m"][0][:n]), np.asarray(sc["link_d_m"][0][:n])
    _, final, notes = fig_poses.run_poses(log)
    seg = np.linalg.norm(np.diff(final["arm_m"], axis=0), axis=1)
    assert final["arm_m"].shape == (n + 1, 3), f"arm points {final['arm_m'].shape}"
    assert close(seg, np.hypot(a, d), 1e-12), f"segment lengths {seg} vs √(a²+d²)"
    hull = final["hull_m"]
    assert hull is not None and not notes, f"scene log: hull drawn, no note ({notes})"
    rot = final["rot"]
    local = (hull - final["vehicle_m"]) @ rot  # corners in the vehicle frame
    assert close(local.max(0) - local.min(0), sc["hull_size_m"][0], 1e-12), "hull edge lengths"
    assert close(0.5 * (local.max(0) + local.min(0)), sc["hull_center_m"][0], 1e-12), \
        "hull center"


def check_fallback_without_scene():
    out = RUNS["IV"][0]
    chans = ["UVMS_CONFIG", "UVMS_TRUTH", "UVMS_TELEMETRY", "UVMS_STATUS"]
    log = runlog.load(os.path.join(out, "run.lcmlog"), chans)
    _, final, notes = fig_poses.run_poses(log)
    assert final["hull_m"] is None and notes, "no scene: no hull, a note"
    assert close(final["ee_m"], log["UVMS_TRUTH"]["ee_position_m"][-1]), "EE from UVMS_CONFIG"


def report():
    schema = schema_mod.from_binary(UVMS)
    return Report(ROOT, os.path.join(TMP, "out"), schema)


def check_section_through_loaders():
    rep = report()
    md = "\n".join(text_poses.section(rep))
    png = os.path.join(TMP, "out", "figures", "exp1_poses.png")
    assert "(figures/exp1_poses.png)" in md and os.path.isfile(png), "figure written and cited"
    im = np.asarray(Image.open(png).convert("L"), float)
    assert im.shape[0] > 500 and im.shape[1] > 1000 and im.std() > 10, f"figure {im.shape}"
    for case in CASES:
        ee = RUNS[case][1]["UVMS_TRUTH"]["ee_position_m"][-1]
        txt = ", ".join(f"{v:.4f}" for v in ee)
        assert txt in md, f"{case}: truth final EE {txt} in the section"
    assert "not drawn" not in md


def check_section_without_runs():
    for rid in CASES.values():
        shutil.rmtree(os.path.join(EXP_DIR, "runs", rid))
    md = "\n".join(text_poses.section(report()))
    assert "not drawn" in md and "exp1_poses.png" not in md, "missing runs: said so, no figure"


def check_recordings_section():
    md = "\n".join(recordings.section(report()))
    assert "tools/uvmsviz.py RUN_DIR" in md and "](" not in md, "none: how to make them"
    names = {"recordings": "exp1_cases-IV_stagnant.rrd", "dashboards": "exp1_cases-IV_stagnant.png"}
    for sub, name in names.items():
        os.makedirs(os.path.join(ROOT, sub))
        open(os.path.join(ROOT, sub, name), "wb").close()
    rep = Report(ROOT, ROOT, schema_mod.from_binary(UVMS))
    md = "\n".join(recordings.section(rep))
    for sub, name in names.items():
        assert f"]({sub}/{name})" in md, f"relative link to {sub}/{name}"
    assert "| `exp1_cases` | `IV_stagnant` |" in md and TMP not in md, "one row, no absolute path"
    assert ".venv/bin/rerun" in md, "how to open a recording"


CHECKS = [check_poses_match_truth, check_arm_and_hull_geometry, check_fallback_without_scene,
          check_section_through_loaders, check_section_without_runs, check_recordings_section]


def main():
    return checklist.run(CHECKS, TMP, make_runs, errors=(AssertionError, KeyError))


if __name__ == "__main__":
    sys.exit(main())
