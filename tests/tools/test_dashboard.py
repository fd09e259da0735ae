# SPDX-License-Identifier: Apache-2.0
"""tools/uvmslog.py --dashboard (tools/uvms_tools/dashboard/page.py) on a fresh 1.5 s run and
on a tiny campaign of two 1 s runs.

The data the page plots is checked through the dashboard's pure data-prep functions against
independent quantities: the plant's summary.json (final vehicle displacement, max attitude error,
max vehicle excursion, mean EE error, final energies, all summed or taken by the C++ plant node)
and the produced thrust force and moment recomputed here from the truth's quaternion and
per-thruster thrusts and the plant's thruster geometry (UVMS_SCENE, else UVMS_CONFIG):
F = sum_j R0 u_j T_j, N = sum_j (R0 a_j) x (R0 u_j T_j) (plant/src/plant.cpp, SPEC §5).
The page itself: a PNG of the configured pixel size that is not blank; one per campaign run;
one-line errors for a directory without a log. --out: FILE.PNG is written as that very file, in
PNG; a name without .png, a .pdf, a directory or a file in a missing directory is a one-line
error that writes nothing.
Failed runs (summary.json metrics null, docs/FAULTS.md): one that fails the EE-error verdict
(--limit max_ee_error_m=1e-6) and one that fails on contact at its first tick (clearance 0.06 m
> the hull-link4 distance): each gets a page; its header carries the summary's status, failure
and reason, and the key numbers come from the log: the max EE error against the value the
plant's verdict prints in the reason, the smallest clearance against the distance the contact
monitor prints. A batch -j 2 of [good, broken, failed, failed] draws the good and the failed
runs; the broken one (a summary.json that breaks the page) gives one error line, exit 1. The
page's panels: one y-axis each (no twin axes), thruster energies apart from the manipulator
and propulsive ones, units in every y label, no "SPEC" in any text on the page.

Usage: test_dashboard.py UVMS_EXE SOURCE_DIR
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

import numpy as np

UVMS, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tools"))
from uvms_tools.log import runlog  # noqa: E402
from uvms_tools.dashboard import page as dash  # noqa: E402

PY = sys.executable
TOOL = os.path.join(SRC, "tools", "uvmslog.py")
TMP = tempfile.mkdtemp(prefix="uvms-dashboard-")
# Same doubles, same operations as the plant up to summation order: a few ulps.
REL_TOL = 1e-12
# Recomputing R0 from the logged quaternion (rounded to double, normalised) and summing 8
# thrusters in another order: far below 1e-9 of the largest component.
WRENCH_REL_TOL = 1e-9
# A blank page has grey std 0; one of empty axes with titles and grids about 29; a page with
# data about 37. Data lines are coloured, axes and text are not: pages with data have 1.5-2 %
# coloured pixels (RGB max - min > 60), a page of empty axes none.
MIN_PIXEL_STD = 20.0
MIN_COLOURED_FRACTION = 0.005
COLOURED_CHROMA = 60
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

failures = []


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


def rel_close(a, b, tol=REL_TOL):
    return abs(a - b) <= tol * max(abs(b), 1e-300)


def uvms_run(out_dir, duration_s, extra=(), want_rc=0):
    cmd = [UVMS, "run", os.path.join(SRC, "sil/scenarios/paper/case_VII_stagnant.toml"),
           "--out", out_dir, "--set", f"run.duration_s={duration_s}", "--set",
           f"trajectory.duration_s={duration_s}", "--transport", "memq", *extra]
    p = subprocess.run(cmd, capture_output=True, text=True)
    check(p.returncode == want_rc,
          f"uvms run {' '.join(extra)} exits {want_rc} ({p.returncode}: {p.stderr.strip()[-300:]})")


def png_stats(path):
    """(width, height), the grey-level std and the fraction of coloured pixels of a PNG
    (Pillow, independent of matplotlib)."""
    from PIL import Image
    with Image.open(path) as im:
        im.verify()
    with Image.open(path) as im:
        rgb = np.asarray(im.convert("RGB"))  # uint8: max - min >= 0 cannot wrap
        grey_std = float(np.asarray(im.convert("L")).std())
    coloured = float(((rgb.max(axis=2) - rgb.min(axis=2)) > COLOURED_CHROMA).mean())
    return im.size, grey_std, coloured


def quat_to_matrix(q):
    """R(q) for q = (w, x, y, z), normalised (vehicle -> inertial)."""
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def produced_wrench(log):
    """(F, N) per truth sample recomputed from quaternion, thrust_N and thruster geometry."""
    geo = log.get("UVMS_SCENE") or log["UVMS_CONFIG"]
    a, u = geo["thruster_position_m"][-1], geo["thruster_direction"][-1]
    tr = log["UVMS_TRUTH"]
    force, moment = [], []
    for q, thrust in zip(tr["quaternion_wxyz"], tr["thrust_N"]):
        r = quat_to_matrix(q)
        f_j = (r @ u.T).T * thrust[:, None]
        force.append(f_j.sum(axis=0))
        moment.append(np.cross((r @ a.T).T, f_j).sum(axis=0))
    return np.array(force), np.array(moment)


def check_data_prep(log, summary):
    """Vehicle motion, EE error and energies against the plant's summary."""
    tr = log["UVMS_TRUTH"]
    t, d = dash.vehicle_displacement(log)
    final = np.subtract(summary["final_vehicle_position_m"], summary["initial_vehicle_position_m"])
    check((t == tr["t_s"]).all() and (d[0] == 0).all()
          and all(rel_close(x, y) for x, y in zip(d[-1], final)),
          f"vehicle displacement: final {d[-1].tolist()} == summary final − initial")
    check(rel_close(np.linalg.norm(d, axis=1).max(), summary["max_vehicle_excursion_m"]),
          "vehicle displacement: max norm == summary max_vehicle_excursion_m")
    t, phi, norm = dash.attitude_error(log)
    check(len(t) == summary["ticks"] and rel_close(norm.max(), summary["max_attitude_error_rad"]),
          f"attitude error: one per tick, max {norm.max()!r} == summary "
          f"{summary['max_attitude_error_rad']!r}")
    t, eps_mm = dash.ee_error_mm(log)
    check(len(t) == summary["ticks"]
          and rel_close(eps_mm.mean() * 1e-3, summary["mean_ee_error_m"]),
          "EE error [mm]: mean × 1e-3 == summary mean_ee_error_m")
    t, energies = dash.energy_series(log)
    check(all(rel_close(v[-1], summary[f]) for f, v in energies.items())
          and set(energies) == {"thruster_energy_J", "thruster_energy_signed_J",
                                "manipulator_energy_J", "propulsive_energy_J"},
          "energies: the four truth energies, final values == summary")


def check_wrench_and_series(log, summary):
    """The produced wrench recomputed here; the other series are the logged fields."""
    tr, tm = log["UVMS_TRUTH"], log["UVMS_TELEMETRY"]
    w = dash.wrench_series(log)
    force, moment = produced_wrench(log)
    for kind, ref in (("force", force), ("moment", moment)):
        got = w[kind]["produced"][1]
        scale = max(np.abs(ref).max(), 1e-12)
        diff = np.abs(got - ref).max() if got.shape == ref.shape else np.inf
        check(diff <= WRENCH_REL_TOL * scale,
              f"produced {kind} == Σ over thrusters recomputed from truth (inertial): shape "
              f"{got.shape} == {ref.shape}, max diff {diff:.3g} of {scale:.3g}")
    sel = tm["tick"] >= 0
    check((w["force"]["desired"][1] == tm["force_des_N"][sel]).all()
          and (w["moment"]["deliverable"][1] == tm["moment_deliverable_Nm"][sel]).all()
          and len(w["force"]["desired"][0]) == summary["ticks"],
          "desired / deliverable: telemetry force_des_N, moment_deliverable_Nm without tick -1")
    s = dash.thruster_series(log)
    check((s["thrust_N"][1] == tr["thrust_N"]).all()
          and (s["thrust_des_N"][1] == tm["thrust_des_N"][sel]).all()
          and (s["current_des_A"][1] == tm["current_des_A"][sel]).all()
          and (s["motor_current_A"][1] == tr["motor_current_A"]).all()
          and (s["motor_voltage_V"][1] == tr["motor_voltage_V"]).all()
          and s["thrust_N"][1].shape[1] == 8, "per-thruster series: truth and telemetry, 8 each")
    j = dash.joint_series(log)
    check((j["joint_position_rad"][1] == tr["joint_position_rad"]).all()
          and (j["joint_ref_rad"][1] == tm["joint_ref_rad"][sel]).all(),
          "joint series: truth joint_position_rad, telemetry joint_ref_rad")


def check_series_of_another_vehicle():
    """A run of the shipped two-link arm: the joint series holds its 2 joints (the logged
    configuration's num_joints), not the message's 7 slots; the thrusters stay 8."""
    run = os.path.join(TMP, "planar_arm")
    p = subprocess.run([UVMS, "run", os.path.join(SRC, "sil", "scenarios", "vehicles",
                                                  "planar_arm_VII_stagnant.toml"),
                        "--out", run, "--transport", "memq", "--set", "run.duration_s=0.3"],
                       capture_output=True, text=True)
    check(p.returncode == 0, f"two-link arm run ({p.stderr.strip()[-200:]})")
    log = runlog.load(run, dash.CHANNELS)
    j, s = dash.joint_series(log), dash.thruster_series(log)
    check(j["joint_position_rad"][1].shape[1] == 2 and j["joint_ref_rad"][1].shape[1] == 2
          and s["thrust_N"][1].shape[1] == 8,
          f"two-link arm: joint series of {j['joint_position_rad'][1].shape[1]} joints (2), "
          f"{s['thrust_N'][1].shape[1]} thrusters (8)")
    labels = (dash.series_labels(log, "joint_position_rad", 2),
              dash.series_labels(log, "thrust_N", 6))
    check(labels == (["J1", "J2"], ["T1", "T2", "T3", "T4", "T5", "T6"]),
          f"labels of 2 joints and 6 thrusters named from the messages' widths: {labels}")


def check_helpers(log, summary):
    check(dash.display_scale(np.array([0.7e-3]), "m") == (1e3, "mm")
          and dash.display_scale(np.array([5e-5]), "m") == (1e6, "µm")
          and dash.display_scale(np.array([-0.2]), "m") == (1.0, "m")
          and dash.display_scale(np.zeros(3), "rad") == (1.0, "rad"),
          "display_scale: 0.7e-3 m in mm, 5e-5 m in µm, 0.2 m in m, zeros in SI")
    head = dash.header_lines(log, summary, ['control.case="VII"', "run.seed=3"], "RUNNAME")
    mean_mm = f"{summary['mean_ee_error_m'] * 1e3:.4g} mm"
    check(head[0] == "RUNNAME: finished" and "case VII" in head[1] and "run.seed=3" in head[1]
          and "reference barycenter" in head[2] and mean_mm in head[3],
          f"header: name, status, case, overrides, switches, mean EE error ({mean_mm})")
    # A campaign run: summary.json names the run (<campaign>/<id>), the base scenario its file.
    named = dict(summary, name="exp1_cases/VII_stagnant",
                 scenario="../../inputs/0123/case_I_stagnant.toml")
    head = dash.header_lines(log, named, ['control.case="VII"'], "R")
    check("case VII" in head[1] and "run exp1_cases/VII_stagnant" in head[1]
          and "base scenario case_I_stagnant" in head[1],
          f"header of a campaign run: its case, its own name, its base scenario ({head[1]})")
    from_log = dash.key_numbers(log, None)
    energy = f"thruster energy {summary['thruster_energy_J']:.4g} J"
    check(mean_mm in from_log and energy in from_log and "no summary.json" in from_log,
          f"without summary.json the numbers come from the log and agree ({from_log})")


def check_page(path, what):
    size, std, coloured = png_stats(path)
    want = (round(dash.FIGSIZE_IN[0] * dash.DPI), round(dash.FIGSIZE_IN[1] * dash.DPI))
    check(size == want and std > MIN_PIXEL_STD and coloured > MIN_COLOURED_FRACTION,
          f"{what}: valid PNG {size} == {want}, grey std {std:.1f} > {MIN_PIXEL_STD}, "
          f"coloured {coloured:.2%} > {MIN_COLOURED_FRACTION:.1%}")


def check_campaign():
    toml = os.path.join(TMP, "tiny.toml")
    base = os.path.join(SRC, "sil/scenarios/paper/case_VII_stagnant.toml")
    with open(toml, "w") as fh:
        fh.write(f'name = "tiny"\nbase = "{base}"\n[set]\n"run.duration_s" = 1.0\n'
                 '"trajectory.duration_s" = 1.0\n[[sweep]]\n"payload.mass_kg" = [0.0, 1.0]\n')
    camp = os.path.join(TMP, "camp")
    p = subprocess.run([UVMS, "campaign", toml, "--out", camp, "-j", "2"], capture_output=True,
                       text=True)
    runs = sorted(os.listdir(os.path.join(camp, "runs"))) if p.returncode == 0 else []
    check(len(runs) == 2, f"tiny campaign: 2 runs ({p.returncode}: {p.stderr.strip()[-200:]})")
    nolog = os.path.join(camp, "runs", "nolog")  # a run whose campaign kept no log (--logs)
    os.makedirs(nolog)
    os.makedirs(os.path.join(camp, "runs", ".log-again-x"))  # a report's scratch: not a run
    p = subprocess.run([PY, TOOL, camp, "--dashboard", "-j", "2"], capture_output=True, text=True)
    pages = [os.path.join(camp, "runs", r, "dashboard.png") for r in runs]
    err = p.stderr.strip().splitlines()
    check(all(os.path.isfile(x) for x in pages) and p.stdout.count("wrote ") == 2
          and "2 of 2 dashboards written" in p.stdout,
          f"campaign --dashboard -j 2: one page per run with a log ({p.stdout.strip()[-200:]})")
    check(p.returncode == 0 and len(err) == 1 and "1 of the 3 runs" in err[0]
          and "keep no run.lcmlog" in err[0],
          f"a run without a log (uvms campaign --logs): counted in one note, no page ({err})")
    empty = os.path.join(TMP, "camp_nolog")
    os.makedirs(os.path.join(empty, "runs", "a"))
    p = subprocess.run([PY, TOOL, empty, "--dashboard"], capture_output=True, text=True)
    check(p.returncode == 1 and "none of its 1 runs keeps a run.lcmlog" in p.stderr,
          f"a campaign none of whose runs keeps a log: an error ({p.stderr.strip()[:120]})")
    if pages and os.path.isfile(pages[0]):
        check_page(pages[0], "campaign run page")


def check_out_names(run):
    """--out: PNG only, under exactly the name given."""
    upper = os.path.join(TMP, "page.PNG")
    p = subprocess.run([PY, TOOL, run, "--dashboard", "--out", upper], capture_output=True,
                       text=True)
    magic = b""
    if os.path.isfile(upper):
        with open(upper, "rb") as fh:
            magic = fh.read(len(PNG_MAGIC))
    check(p.returncode == 0 and p.stdout.strip() == f"wrote {upper}" and magic == PNG_MAGIC
          and not os.path.exists(upper + ".png"), f"--out page.PNG: a PNG named so ({p.stderr})")
    missing = os.path.join(TMP, "no_such_dir")
    p = subprocess.run([PY, TOOL, run, "--dashboard", "--out", os.path.join(missing, "p.png")],
                       capture_output=True, text=True)
    check(p.returncode == 1 and p.stderr.startswith("uvmslog: error: --out")
          and len(p.stderr.strip().splitlines()) == 1 and f"no directory {missing}" in p.stderr
          and "Errno" not in p.stderr and not os.path.exists(missing),
          f"--out in a missing directory: one line naming it ({p.stderr.strip()})")
    for name in ("page", "page.pdf", ""):
        target = os.path.join(TMP, name) if name else TMP
        before = set(os.listdir(TMP))
        p = subprocess.run([PY, TOOL, run, "--dashboard", "--out", target], capture_output=True,
                           text=True)
        check(p.returncode == 1 and p.stderr.startswith("uvmslog: error: --out")
              and len(p.stderr.strip().splitlines()) == 1 and set(os.listdir(TMP)) == before,
              f"--out {name or 'DIR'}: a one-line error, nothing written ({p.stderr.strip()})")


def failed_run(name, extra, failure):
    """A run that fails (uvms run exit 3) as `failure`; (run dir, its summary or {})."""
    run = os.path.join(TMP, name)
    uvms_run(run, 1.5, extra, want_rc=3)
    summary = dash.read_json(os.path.join(run, "summary.json")) or {}
    check(summary.get("status") == "failed" and summary.get("failure") == failure
          and summary.get("mean_ee_error_m", 0) is None
          and summary.get("thruster_energy_J", 0) is None,
          f"{name}: summary status failed ({failure}), metrics null ({summary.get('reason')})")
    return run, summary


def number_in(text, pattern):
    """The float `pattern`'s group 1 matches in `text`, or None."""
    m = re.search(pattern, text)
    return float(m.group(1)) if m else None


def check_failed_diverged():
    """EE-error verdict failure: page, header from summary.json, numbers from the log."""
    run, summary = failed_run("failed_ee", ["--limit", "max_ee_error_m=0.000001"], "diverged")
    reason = summary.get("reason", "")
    log = runlog.load(run, dash.CHANNELS)
    head = dash.header_lines(log, summary, None, "F")
    check(head[0] == f"F: failed (diverged): {reason}",
          f"failed run header: status, failure and reason of summary.json ({head[0]})")
    # The verdict prints the max EE error with 6 significant digits ("%g"); the header 4.
    plant_max_m = number_in(reason, r"max_ee_error_m ([0-9.eE+-]+) exceeds")
    page_max_mm = number_in(head[3], r"max ([0-9.eE+-]+) mm")
    check(plant_max_m is not None and page_max_mm is not None
          and abs(page_max_mm * 1e-3 - plant_max_m) <= 1e-3 * plant_max_m
          and "from the log (summary.json has null)" in head[3] and "n/a" not in head[3],
          f"failed run key numbers from the log: max EE error {page_max_mm} mm == the "
          f"verdict's {plant_max_m} m ({head[3]})")
    return run


def check_batch(good, failed_ee, failed_contact):
    """A batch -j 2 of [good run, a run whose summary.json breaks the page, the two failed
    runs]: every run but the broken one gets its page, the broken one one error line, exit 1."""
    bad = os.path.join(TMP, "bad_summary")
    os.makedirs(bad)
    shutil.copy(os.path.join(failed_ee, runlog.RUN_LOG_NAME), bad)
    with open(os.path.join(bad, "summary.json"), "w") as fh:
        json.dump({"status": "finished", "mean_ee_error_m": "not a number"}, fh)
    pages = [os.path.join(r, "dashboard.png") for r in (good, failed_ee, failed_contact)]
    for x in pages:
        if os.path.exists(x):
            os.remove(x)
    p = subprocess.run([PY, TOOL, good, bad, failed_ee, failed_contact, "--dashboard", "-j",
                        "2"], capture_output=True, text=True)
    err = p.stderr.strip().splitlines()
    check(all(os.path.isfile(x) for x in pages) and p.stdout.count("wrote ") == 3
          and "3 of 4 dashboards written, 1 failed" in p.stdout,
          f"batch [good, broken, failed, failed at tick 1] -j 2: a page for the good and the "
          f"failed runs ({p.stdout.strip()[-300:]})")
    check(p.returncode == 1 and len(err) == 1 and err[0].startswith("uvmslog: error:")
          and bad in err[0] and "Traceback" not in p.stderr,
          f"the run whose summary breaks the page: one line, the others drawn, exit 1 ({err})")
    if os.path.isfile(pages[1]):
        check_page(pages[1], "failed run page")


def check_failed_contact():
    """Contact failure at the first tick: clearance panel data vs the monitor's reason."""
    run, summary = failed_run("failed_contact", ["--set", "contact.clearance_m=0.06"], "contact")
    log = runlog.load(run, dash.CHANNELS)
    t, c, pair = dash.clearance_series(log)
    m = re.search(r"contact: (\w+) and (\w+) at distance ([0-9.]+) m \(clearance ([0-9.]+) m\)",
                  summary.get("reason", ""))
    check(m is not None and len(c) == log["UVMS_TRUTH"].count
          and abs(c.min() - float(m.group(3))) <= 1e-6 and pair[0] == f"{m[1]}|{m[2]}"
          and dash.contact_clearance_m(log) == 0.06 == float(m.group(4)),
          f"clearance series: smallest {c.min() if len(c) else None} m, pair "
          f"{pair[0] if len(pair) else None}, clearance {dash.contact_clearance_m(log)} == the "
          f"monitor's reason ({summary.get('reason')})")
    return run


def check_panels(log):
    """One y-axis per panel; energies split by scale; units in y labels; no SPEC on the page."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(*dash.GRID, figsize=dash.FIGSIZE_IN, layout="constrained")
    try:
        dash.draw_panels(axes, log)
        n_axes = len(fig.axes)
        where = {}
        for k, ax in enumerate(axes.flat):
            for line in ax.get_lines():
                for f in dash.ENERGY_FIELDS:
                    if np.array_equal(line.get_ydata(), log["UVMS_TRUTH"][f]):
                        where.setdefault(f, set()).add(k)
        texts = [t.get_text() for ax in axes.flat for t in ax.findobj(
            matplotlib.text.Text)]
        ylabels = [ax.get_ylabel() for ax in axes.flat]
    finally:
        plt.close(fig)
    thr = where.get("thruster_energy_J", set()) | where.get("thruster_energy_signed_J", set())
    small = where.get("manipulator_energy_J", set()) | where.get("propulsive_energy_J", set())
    check(n_axes == axes.size and len(thr) == 1 and len(small) == 1 and not thr & small,
          f"panels: {n_axes} axes for {axes.size} panels (no twin axes); thruster energies on "
          f"panel {thr}, manipulator and propulsive on {small}")
    check(all(re.search(r"\[[^\]]+\]", y) for y in ylabels),
          f"every panel's y label has a unit ({ylabels})")
    check(not any("SPEC" in t for t in texts) and any("docs/MODEL.md §10" in t for t in texts),
          "page text cites docs/MODEL.md (§10 on the EE error), never SPEC")


def main():
    try:
        checks()
    finally:
        shutil.rmtree(TMP, ignore_errors=True)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


def checks():
    run = os.path.join(TMP, "run")
    uvms_run(run, 1.5)
    summary = json.load(open(os.path.join(run, "summary.json")))
    log = runlog.load(run, dash.CHANNELS + ("UVMS_SCENE",))
    check_data_prep(log, summary)
    check_wrench_and_series(log, summary)
    check_helpers(log, summary)
    check_series_of_another_vehicle()
    p = subprocess.run([PY, TOOL, run, "--dashboard"], capture_output=True, text=True)
    page = os.path.join(run, "dashboard.png")
    check(p.returncode == 0 and p.stdout.strip() == f"wrote {page}" and p.stderr == "",
          f"RUN --dashboard writes RUN/dashboard.png ({p.stderr.strip()[-200:]})")
    if os.path.isfile(page):
        check_page(page, "run page")
    other = os.path.join(TMP, "other.png")
    check_campaign()
    p = subprocess.run([PY, TOOL, run, run, "--dashboard", "--out", other], capture_output=True,
                       text=True)
    check(p.returncode == 1 and len(p.stderr.strip().splitlines()) == 1 and "--out" in p.stderr,
          f"--out with two runs: a one-line error ({p.stderr.strip()})")
    check_out_names(run)
    check_panels(log)
    check_batch(run, check_failed_diverged(), check_failed_contact())
    for bad, why in ((os.path.join(TMP, "empty"), "neither a run directory"),
                     (os.path.join(TMP, "missing"), "no such")):
        os.makedirs(os.path.join(TMP, "empty"), exist_ok=True)
        p = subprocess.run([PY, TOOL, bad, "--dashboard"], capture_output=True, text=True)
        check(p.returncode == 1 and len(p.stderr.strip().splitlines()) == 1
              and p.stderr.startswith("uvmslog: error:") and why in p.stderr,
              f"--dashboard {os.path.basename(bad)}: {p.stderr.strip()}")


if __name__ == "__main__":
    sys.exit(main())
