# SPDX-License-Identifier: Apache-2.0
"""poses: the paper's Fig. 7 in the report (experiment 1): what is drawn, and the final
vehicle displacement, EE and barycenter positions of the runs drawn, from their truth logs."""
import sys

import numpy as np

from uvms_tools.log import runlog
from uvms_tools.viz.kinematics import GeometryError

from ..figures import poses as fig_poses
from ..keys import BARY, COND_EXP1_KEYS, COND_EXP1_TEXT, KEY_CASE, VEH
from ..load.overrides import seed_of
from .common import img
from .fmt import f, mm, table

NAME = "exp1_cases"
CONDS = ["stagnant", "unsteady"]
CHANNELS = ["UVMS_SCENE", "UVMS_CONFIG", "UVMS_TRUTH", "UVMS_TELEMETRY", "UVMS_STATUS"]


def _poses(e, cond_name, case):
    """(run, stowed, final, notes) of the lowest-seed run of (case, condition), or None when
    the run or its log is missing or unreadable (a reason on stderr)."""
    run = e.one(dict(COND_EXP1_KEYS[cond_name], **{KEY_CASE: case}))
    lg = e.log(run, CHANNELS) if run else None
    if lg is None:
        return None
    try:
        return (run, *fig_poses.run_poses(lg))
    except (runlog.LogError, GeometryError) as err:
        print(f"report: Fig. 7: {run['id']}: {err}", file=sys.stderr)
        return None


def _row_title(cond_name, seed):
    return COND_EXP1_TEXT[cond_name] + ("" if seed is None else f", seed {seed} (one run)")


def _mm(x_m):
    """[m] -> '12.3' [mm], without a '-0.0'."""
    s = mm(x_m, 1)
    return "0.0" if s == "-0.0" else s


def _numbers(cond_name, case, run, stowed, final):
    disp = final["vehicle_m"] - stowed["vehicle_m"]
    bary = final["barycenter_m"] - stowed["barycenter_m"]
    return [COND_EXP1_TEXT[cond_name], f"{case} (`{run['id']}`)", f(final["t_s"], 1),
            ", ".join(_mm(v) for v in disp), _mm(np.linalg.norm(disp)),
            ", ".join(f(v, 4) for v in final["ee_m"]), _mm(np.linalg.norm(bary))]


def _collect(e):
    """Figure rows, table rows and scene notes of the conditions whose IV and VII runs exist."""
    rows, cells, notes = [], [], set()
    for k in CONDS:
        got = {c: _poses(e, k, c) for c in (VEH, BARY)}
        if any(v is None for v in got.values()):
            continue
        run_v, stowed = got[VEH][0], got[VEH][1]
        rows.append((_row_title(k, seed_of(run_v)), stowed,
                     [(c, got[c][2]) for c in (VEH, BARY)]))
        for c in (VEH, BARY):
            run, st, fin, nts = got[c]
            cells.append(_numbers(k, c, run, st, fin))
            notes.update(nts)
    return rows, cells, sorted(notes)


def section(rep):
    """### Fig. 7 in experiment 1's section; a sentence when the runs are missing."""
    e = rep.exp(NAME)
    if e is None:
        return []  # experiment 1's section says it is missing
    md = ["### Fig. 7: stowed and final poses", ""]
    rows, cells, notes = _collect(e)
    if not rows:
        return md + ["*The runs of cases IV and VII of `exp1_cases` (or their logs) were not "
                     "found: Fig. 7 is not drawn.*", ""]
    img(md, fig_poses.draw(rep.figs, rows),
        "The stowed (initial) pose, dashed grey, and the final poses under vehicle (IV, blue) "
        "and barycenter (VII, red) stabilization, each with the vehicle where it ended up; "
        "one row per condition (unsteady: one seed, a picture, not a statistic).")
    md += ["Drawn from each run's own truth log: vehicle CoM position, attitude and joint "
           "angles of the first and last `UVMS_TRUTH` samples through the forward kinematics "
           "of docs/MODEL.md §2 (`tools/uvms_tools/viz/kinematics.py`): the arm as the line "
           "through the DH frame origins p_0 (arm base) … p_7 (end-effector, star), the barycenter "
           "(cross) as the plant logged it, the vehicle as its hull box (from `UVMS_SCENE`) "
           "or, in logs without it, its body axes from the CoM. The stowed pose is the "
           "IV run's first sample. Equal scaling on all axes.", ""]
    if notes:
        print("report: Fig. 7: " + "; ".join(notes), file=sys.stderr)
        md += [f"*Geometry:* {n}." for n in notes] + [""]
    md += table(["condition", "case (run)", "t [s]", "vehicle displacement x, y, z [mm]",
                 "|displacement| [mm]", "final EE x, y, z [m]", "barycenter moved [mm]"], cells)
    return md
