# SPDX-License-Identifier: Apache-2.0
"""page (the dashboard): one PNG page per run, to see at a glance what a run did.

    tools/uvmslog.py RUN_DIR --dashboard [--out FILE.png]     RUN_DIR/dashboard.png
    tools/uvmslog.py CAMPAIGN_DIR --dashboard [-j N]          every runs/*/dashboard.png

The page (write_dashboard) has, against simulated time: the vehicle's displacement from its
initial position and its attitude error; the EE error (docs/MODEL.md §10); the contact
monitor's smallest clearance; the energies (the thrusters' on one panel, the manipulator's and
the ideal propulsive energy on another: each on its own scale); the wrench on the vehicle,
desired, deliverable by the commanded thrusts and produced (all inertial axes, moments about
the vehicle CoM); per thruster the thrust, motor voltage and current; the joint angles against
their references. A header names the run, its status (a failed run: the failure and its
reason), the controller's Table X switches, the duration and the key numbers: summary.json's,
and recomputed from the log where the summary has none (a failed run's metrics are null,
docs/FAULTS.md). A failed run gets its page like any other.

Sources (lcmtypes/*.lcm): truth_t (UVMS_TRUTH, the plant) and telemetry_t (UVMS_TELEMETRY, the
controller; tick -1, the configuration acknowledgement, left out). Frames: telemetry
force_des_N / moment_des_Nm (F_P0, N_P0) and force_deliverable_N / moment_deliverable_Nm
(R0 H P) are inertial; truth thrust_force_N / thrust_moment_Nm are the sums of R0 u_j T_j and
(R0 a_j) x (R0 u_j T_j) over the thrusters (plant/src/plant.cpp), inertial too: like is
plotted with like. Thrusters T1..Tn and joints J1..JN (the configured counts) are numbered from 1 and named by
runlog.component_labels; each thruster keeps its colour on every panel.

The data-prep functions (vehicle_displacement, attitude_error, ee_error_mm, wrench_series,
thruster_series, joint_series, energy_series, clearance_series) are pure: Log in, the arrays
plotted out.
"""
import json
import os
import textwrap

import numpy as np

from uvms_tools.log import runlog

DASHBOARD_NAME = "dashboard.png"
FIGSIZE_IN = (16, 23)  # portrait page, 1600 x 2300 px at DPI: readable at 100 % on a laptop
GRID = (6, 2)  # panel rows, columns (draw_panels)
DPI = 100
HEADER_WIDTH_CHARS = 190  # header lines wrap here (11 pt on FIGSIZE_IN)
CHANNELS = ("UVMS_TRUTH", "UVMS_TELEMETRY", "UVMS_CONFIG", "UVMS_STATUS", "UVMS_SCENE")
# (UVMS_SCENE: the contact clearance; logs of older builds have none)
XYZ_COLORS = ("tab:red", "tab:green", "tab:blue")  # components x, y, z
THRUSTER_CMAP = "tab10"  # thruster j gets colour j - 1: the same on every panel
JOINT_CMAP = "Dark2"
# Display units for small quantities: (factor from SI, name); the largest that shows >= 0.1.
SCALES = {"m": ((1.0, "m"), (1e3, "mm"), (1e6, "µm")),
          "rad": ((1.0, "rad"), (1e3, "mrad"), (1e6, "µrad"))}


# ----------------------------------------------------------------------------------------------
# Data preparation: Log -> the arrays plotted (SI units)


def telemetry_of_ticks(log):
    """UVMS_TELEMETRY without the configuration acknowledgement (tick -1)."""
    tm = log["UVMS_TELEMETRY"]
    return tm.select(tm["tick"] >= 0)


def vehicle_displacement(log):
    """(t_s, r0 - r0(first sample) (n, 3) [m]) from truth position_m."""
    tr = log["UVMS_TRUTH"]
    return tr["t_s"], tr["position_m"] - tr["position_m"][0]


def attitude_error(log):
    """(t_s, phi (n, 3) [rad], |phi| (n,) [rad]): telemetry attitude_error_rad, the rotation
    vector of E = R0d R0^T (SPEC [44])."""
    tm = telemetry_of_ticks(log)
    phi = tm["attitude_error_rad"]
    return tm["t_s"], phi, np.linalg.norm(phi, axis=1)


def ee_error_mm(log):
    """(t_s, SPEC §10 EE error [mm]) per tick (runlog.ee_error)."""
    _, t_s, eps_m = runlog.ee_error(log)
    return t_s, eps_m * 1e3


def wrench_series(log):
    """{"force": {...}, "moment": {...}}, each {source: (t_s, (n, 3))}, inertial axes:
    desired (telemetry *_des), deliverable (telemetry *_deliverable: what the commanded
    thrusts produce) and produced (truth thrust_force_N / thrust_moment_Nm)."""
    tm, tr = telemetry_of_ticks(log), log["UVMS_TRUTH"]
    out = {}
    for kind, des, dlv, prod in (("force", "force_des_N", "force_deliverable_N", "thrust_force_N"),
                                 ("moment", "moment_des_Nm", "moment_deliverable_Nm",
                                  "thrust_moment_Nm")):
        out[kind] = {"desired": (tm["t_s"], tm[des]), "deliverable": (tm["t_s"], tm[dlv]),
                     "produced": (tr["t_s"], tr[prod])}
    return out


def configured_count(log, field, slots):
    """The logged controller configuration's count `field` (num_thrusters, num_joints), within
    1..slots; `slots` (every column of the message) when the log has no configuration."""
    cfg = log.get("UVMS_CONFIG")
    if cfg is None or not cfg.count:
        return slots
    return min(max(int(cfg[field][0]), 1), slots)


def thruster_series(log):
    """Per thruster (columns T1..Tn, n configured): {name: (t_s, (samples, n))} of the
    telemetry's thrust_des_N and current_des_A and the truth's thrust_N, motor_voltage_V,
    motor_current_A."""
    tm, tr = telemetry_of_ticks(log), log["UVMS_TRUTH"]
    n = configured_count(log, "num_thrusters", tr["thrust_N"].shape[1])
    out = {f: (tm["t_s"], tm[f][:, :n]) for f in ("thrust_des_N", "current_des_A")}
    out.update({f: (tr["t_s"], tr[f][:, :n])
                for f in ("thrust_N", "motor_voltage_V", "motor_current_A")})
    return out


def joint_series(log):
    """{"joint_position_rad": truth (t_s, (samples, N)), "joint_ref_rad": telemetry (t_s,
    (samples, N))}, N the configured joint count."""
    tm, tr = telemetry_of_ticks(log), log["UVMS_TRUTH"]
    n = configured_count(log, "num_joints", tr["joint_position_rad"].shape[1])
    return {"joint_position_rad": (tr["t_s"], tr["joint_position_rad"][:, :n]),
            "joint_ref_rad": (tm["t_s"], tm["joint_ref_rad"][:, :n])}


ENERGY_FIELDS = ("thruster_energy_J", "thruster_energy_signed_J", "manipulator_energy_J",
                 "propulsive_energy_J")


def energy_series(log):
    """(t_s, {field: (n,) [J]}) of the truth's cumulative energies (SPEC §5)."""
    tr = log["UVMS_TRUTH"]
    return tr["t_s"], {f: tr[f] for f in ENERGY_FIELDS}


def clearance_series(log):
    """(t_s, min_clearance_m [m], closest_pair) of the truth samples where the contact monitor
    gave a finite distance (inf: monitor off); empty arrays when it never did."""
    tr = log["UVMS_TRUTH"]
    c = tr["min_clearance_m"]
    ok = np.isfinite(c)
    return tr["t_s"][ok], c[ok], tr["closest_pair"][ok]


def contact_clearance_m(log):
    """The configured clearance (UVMS_SCENE clearance_m, below it a run fails) or None (no
    scene in the log, or the monitor off)."""
    sc = log.get("UVMS_SCENE")
    if sc is None or not sc.count or not int(sc["contact_enabled"][-1]):
        return None
    return float(sc["clearance_m"][-1])


def display_scale(values, si_unit):
    """(factor, unit name) showing `values` (SI) in the largest unit of SCALES[si_unit] in which
    the largest magnitude is >= 0.1 (mm for 0.7e-3 m), else the smallest."""
    peak = float(np.nanmax(np.abs(values))) if np.size(values) else 0.0
    choices = SCALES[si_unit]
    for factor, name in choices:
        if peak * factor >= 0.1:
            return factor, name
    return choices[0] if peak == 0.0 else choices[-1]


# ----------------------------------------------------------------------------------------------
# Header: what the run was and how it went


def read_json(path):
    """The JSON at `path`, or None when it is missing or unreadable."""
    try:
        with open(path) as fh:
            return json.load(fh)
    except (OSError, ValueError):
        return None


def run_status(log, summary):
    """'finished' / 'failed (FAILURE): REASON' from summary.json, else from the log's last
    UVMS_STATUS."""
    if summary is not None:
        failure, why = summary.get("failure") or "", summary.get("reason") or ""
        return (str(summary.get("status", "?")) + (f" ({failure})" if failure else "")
                + (f": {why}" if why else ""))
    st = log.get("UVMS_STATUS")
    if st is None or not st.count:
        return "no status in the log"
    runlog.lcm_types()
    from uvms.run_status_t import run_status_t as rs
    names = {rs.RUNNING: "running", rs.FINISHED: "finished", rs.FAILED: "failed"}
    state = names.get(int(st["state"][-1]), f"state {int(st['state'][-1])}")
    return state + (f": {st['reason'][-1]}" if st["reason"][-1] else "")


def controller_switches(log):
    """The Table X switches (SPEC §9) of the logged controller configuration, as text."""
    cfg = log.get("UVMS_CONFIG")
    if cfg is None or not cfg.count:
        return "no controller configuration in the log"
    on = {0: "off", 1: "on"}
    ref = {0: "vehicle", 1: "barycenter"}.get(int(cfg["position_reference"][0]), "?")
    return (f"reference {ref}, attitude control {on.get(int(cfg['attitude_control'][0]))}, "
            f"position feedforward {on.get(int(cfg['position_feedforward'][0]))}, "
            f"feedback {on.get(int(cfg['position_feedback'][0]))}")


KEY_FIELDS = ("mean_ee_error_m", "max_ee_error_m") + ENERGY_FIELDS


def numbers_from_log(log):
    """The KEY_FIELDS recomputed from the log: EE error over the ticks (runlog.ee_error, as
    the plant's summary), energies at the last truth sample."""
    _, _, eps = runlog.ee_error(log)
    tr = log["UVMS_TRUTH"]
    out = {f: float(tr[f][-1]) for f in ENERGY_FIELDS}
    if len(eps):
        out.update(mean_ee_error_m=float(eps.mean()), max_ee_error_m=float(eps.max()))
    return out


def key_numbers(log, summary):
    """Mean/max EE error and energies: summary.json's; where it has none (no summary.json, or
    null: a failed run) recomputed from the log; "n/a" where neither has a value."""
    s = {f: (summary or {}).get(f) for f in KEY_FIELDS}
    missing = [f for f in KEY_FIELDS if s[f] is None]
    if missing:
        logged = numbers_from_log(log)
        s.update({f: logged.get(f) for f in missing})
    if summary is None:
        src = "from the log (no summary.json)"
    elif len(missing) == len(KEY_FIELDS):
        src = "from the log (summary.json has null)"
    else:
        src = "summary.json" + (f"; from the log: {', '.join(missing)}" if missing else "")

    def num(f, scale=1.0, unit="J"):
        return "n/a" if s[f] is None else f"{s[f] * scale:.4g} {unit}"
    return (f"mean EE error {num('mean_ee_error_m', 1e3, 'mm')}, max "
            f"{num('max_ee_error_m', 1e3, 'mm')}; thruster energy {num('thruster_energy_J')} "
            f"(signed {num('thruster_energy_signed_J')}), manipulator "
            f"{num('manipulator_energy_J')}, propulsive {num('propulsive_energy_J')}  [{src}]")


def case_of(overrides):
    """The Table X case an override sets (control.case="VII" -> 'VII'), else ''."""
    for o in overrides or ():
        key, _, value = o.partition("=")
        if key.strip() == "control.case":
            return value.strip().strip('"')
    return ""


def header_lines(log, summary, overrides, title):
    """The page's header: run and status; case, scenario and overrides; the controller's
    switches and the duration; the key numbers."""
    tr = log["UVMS_TRUTH"]
    case = case_of(overrides)
    name = (summary or {}).get("name", "")
    scenario = os.path.splitext(os.path.basename((summary or {}).get("scenario", "")))[0]
    base = "base scenario" if overrides else "scenario"
    what = [f"case {case}" if case else "",
            f"run {name}" if name and name != scenario else "",
            f"{base} {scenario}" if scenario else "",
            "overrides: " + ", ".join(overrides) if overrides else ""]
    duration = f"{tr['t_s'][-1] - tr['t_s'][0]:.4g} s simulated ({int(tr['tick'][-1])} ticks)"
    return [f"{title}: {run_status(log, summary)}",
            "  ·  ".join(x for x in what if x) or "no summary.json or overrides.json",
            f"controller: {controller_switches(log)}  ·  {duration}",
            key_numbers(log, summary)]


# ----------------------------------------------------------------------------------------------
# Panels (matplotlib axes in, nothing out). Legends sit to the right of their panel, so that
# they never hide data.


def palette(cmap_name, n):
    import matplotlib
    cmap = matplotlib.colormaps[cmap_name]
    return [cmap(i % cmap.N) for i in range(n)]


def side_legend(ax, entries=None):
    """Legend right of the panel: of (label, line properties) proxies, or of the plotted lines."""
    from matplotlib.lines import Line2D
    kw = {"fontsize": 8, "loc": "upper left", "bbox_to_anchor": (1.01, 1.0), "borderaxespad": 0}
    if entries is None:
        ax.legend(**kw)
        return
    ax.legend([Line2D([], [], **props) for _, props in entries], [lab for lab, _ in entries],
              **kw)


def finish(ax, title, ylabel):
    ax.set_title(title, fontsize=10)
    ax.set_ylabel(ylabel, fontsize=9)
    ax.set_xlabel("simulated time t [s]", fontsize=9)
    ax.grid(alpha=0.3)


def panel_vehicle_position(ax, log):
    t, d = vehicle_displacement(log)
    k, unit = display_scale(d, "m")
    for i, lab in enumerate(runlog.component_labels("UVMS_TRUTH", "position_m", (3,))):
        ax.plot(t, d[:, i] * k, color=XYZ_COLORS[i], lw=1.2, label=lab)
    side_legend(ax)
    finish(ax, "Vehicle position r0 − r0(0), inertial (truth position_m)",
           f"displacement [{unit}]")


def panel_attitude_error(ax, log):
    t, phi, norm = attitude_error(log)
    k, unit = display_scale(norm, "rad")
    for i, lab in enumerate(runlog.component_labels("UVMS_TELEMETRY", "attitude_error_rad",
                                                     (3,))):
        ax.plot(t, phi[:, i] * k, color=XYZ_COLORS[i], lw=1.0, label=lab)
    ax.plot(t, norm * k, color="black", lw=1.6, label="norm")
    side_legend(ax)
    finish(ax, "Attitude error φe, rotation vector of R0d R0ᵀ (telemetry attitude_error_rad)",
           f"attitude error [{unit}]")


def panel_ee_error(ax, log):
    t, eps = ee_error_mm(log)
    ax.plot(t, eps, color="black", lw=1.4, label="ε")
    ax.axhline(eps.mean(), color="tab:red", lw=1.0, ls="--", label=f"mean\n{eps.mean():.4g} mm")
    side_legend(ax)
    finish(ax, "EE error ε (docs/MODEL.md §10: station-keeping error of the EE)\n"
               "|truth ee_position_m − telemetry ee_estimate_m|", "EE error [mm]")


ENERGY_STYLES = {"thruster_energy_J": ("tab:red", "-"),
                 "thruster_energy_signed_J": ("black", ":"),
                 "manipulator_energy_J": ("tab:purple", "-"),
                 "propulsive_energy_J": ("tab:cyan", "-")}
# Two panels, one scale each: the thrusters' electrical energies are ~1e3 x the others.
ENERGY_PANELS = ((("thruster_energy_J", "thruster_energy_signed_J"),
                  "Thruster electrical energy, cumulative (truth; docs/MODEL.md §5)",
                  "thruster energy [J]"),
                 (("manipulator_energy_J", "propulsive_energy_J"),
                  "Manipulator and ideal propulsive energy, cumulative (truth; docs/MODEL.md §5)",
                  "manipulator, propulsive energy [J]"))


def panel_energy(ax, log, fields, title, ylabel):
    t, e = energy_series(log)
    for f in fields:
        color, ls = ENERGY_STYLES[f]
        ax.plot(t, e[f], color=color, ls=ls, lw=1.5)
    side_legend(ax, [(f"{f}\nfinal {e[f][-1]:.4g} J", {"color": ENERGY_STYLES[f][0],
                                                       "ls": ENERGY_STYLES[f][1]})
                     for f in fields])
    finish(ax, title, ylabel)


def panel_clearance(ax, log):
    t, c, pair = clearance_series(log)
    limit = contact_clearance_m(log)
    title = "Smallest clearance (contact monitor; docs/MODEL.md §5), truth min_clearance_m"
    if not len(c):
        ax.text(0.5, 0.5, "contact monitor off: no finite min_clearance_m in the log",
                ha="center", va="center", transform=ax.transAxes, fontsize=10)
        finish(ax, title, "smallest clearance [m]")
        return
    i = int(np.argmin(c))
    ax.plot(t, c, color="black", lw=1.4, label=f"min_clearance_m\nsmallest {c[i]:.4g} m\n"
                                                 f"({pair[i]}, t = {t[i]:.4g} s)")
    if limit is not None:
        ax.axhline(limit, color="tab:red", lw=1.0, ls="--",
                   label=f"clearance {limit:.4g} m\n(closer ends the run)")
    side_legend(ax)
    finish(ax, title, "smallest clearance [m]")


WRENCH_STYLES = (("desired", "-", 2.4, 0.4), ("deliverable", "--", 1.2, 1.0),
                 ("produced", ":", 1.8, 1.0))
WRENCH_FIELDS = {"force": ("force_des_N", "force_deliverable_N", "thrust_force_N", "N",
                           "Thrust force on the vehicle"),
                 "moment": ("moment_des_Nm", "moment_deliverable_Nm", "thrust_moment_Nm", "N·m",
                            "Thrust moment about the vehicle CoM")}


def panel_wrench(ax, log, kind):
    series = wrench_series(log)[kind]
    des, dlv, prod, unit, what = WRENCH_FIELDS[kind]
    for src, ls, lw, alpha in WRENCH_STYLES:
        t, v = series[src]
        for i in range(3):
            ax.plot(t, v[:, i], color=XYZ_COLORS[i], ls=ls, lw=lw, alpha=alpha)
    labels = runlog.component_labels("UVMS_TRUTH", prod, (3,))
    names = {"desired": f"desired\n{des}", "deliverable": f"deliverable\n{dlv}",
             "produced": f"produced\ntruth {prod}"}
    side_legend(ax, [(lab, {"color": c}) for lab, c in zip(labels, XYZ_COLORS)]
                + [(names[s], {"color": "black", "ls": ls, "lw": lw, "alpha": a})
                   for s, ls, lw, a in WRENCH_STYLES])
    finish(ax, f"{what}, inertial axes\ndesired (telemetry) vs deliverable by the commanded "
               "thrusts (telemetry) vs produced (truth)", f"{kind} [{unit}]")


def panel_per_thruster(ax, log, truth_field, tel_field, title, ylabel):
    """Truth `truth_field` solid, telemetry `tel_field` (or None) dashed; a colour per thruster."""
    s = thruster_series(log)
    t, v = s[truth_field]
    labels = series_labels(log, truth_field, v.shape[1])
    colors = palette(THRUSTER_CMAP, len(labels))
    for j in range(len(labels)):
        ax.plot(t, v[:, j], color=colors[j], lw=1.2)
        if tel_field:
            ax.plot(s[tel_field][0], s[tel_field][1][:, j], color=colors[j], lw=1.2, ls="--")
    entries = [(lab, {"color": c, "lw": 2.5}) for lab, c in zip(labels, colors)]
    if tel_field:
        entries += [("truth", {"color": "black"}), ("telemetry", {"color": "black", "ls": "--"})]
    side_legend(ax, entries)
    sources = f"truth {truth_field}" + (f" (solid) vs telemetry {tel_field} (dashed)"
                                        if tel_field else "")
    finish(ax, f"{title}\n{sources}", ylabel)


def series_labels(log, field, n):
    """The first n component names of the truth's `field` (thrust_N: T1..; joint_position_rad:
    J1..), named from the message's full width: a sliced width would name the axis by its
    length instead (runlog.component_labels)."""
    return runlog.component_labels("UVMS_TRUTH", field, log["UVMS_TRUTH"][field].shape[1:])[:n]


def panel_joints(ax, log):
    s = joint_series(log)
    t, q = s["joint_position_rad"]
    t_ref, q_ref = s["joint_ref_rad"]
    labels = series_labels(log, "joint_position_rad", q.shape[1])
    colors = palette(JOINT_CMAP, len(labels))
    for i in range(len(labels)):
        ax.plot(t, q[:, i], color=colors[i], lw=2.0)
        ax.plot(t_ref, q_ref[:, i], color="black", lw=0.8, ls="--")
    entries = [(lab, {"color": c, "lw": 2.5}) for lab, c in zip(labels, colors)]
    entries += [("truth", {"color": "gray", "lw": 2.0}),
                ("reference", {"color": "black", "ls": "--", "lw": 0.8})]
    side_legend(ax, entries)
    finish(ax, "Joint angles θ vs reference θref\ntruth joint_position_rad (solid) vs telemetry "
               "joint_ref_rad (dashed)", "joint angle [rad]")


# ----------------------------------------------------------------------------------------------
# The page


def draw_panels(axes, log):
    """The twelve panels on a GRID of axes."""
    panel_vehicle_position(axes[0, 0], log)
    panel_attitude_error(axes[0, 1], log)
    panel_ee_error(axes[1, 0], log)
    panel_clearance(axes[1, 1], log)
    for ax, (fields, title, ylabel) in zip(axes[2], ENERGY_PANELS):
        panel_energy(ax, log, fields, title, ylabel)
    panel_wrench(axes[3, 0], log, "force")
    panel_wrench(axes[3, 1], log, "moment")
    panel_per_thruster(axes[4, 0], log, "thrust_N", "thrust_des_N",
                       "Thrust per thruster along u_j: produced vs desired (allocated P_j)",
                       "thrust [N]")
    panel_per_thruster(axes[4, 1], log, "motor_voltage_V", None,
                       "Motor terminal voltage per thruster (truth)", "voltage [V]")
    panel_per_thruster(axes[5, 0], log, "motor_current_A", "current_des_A",
                       "Motor current per thruster: actual vs desired", "current [A]")
    panel_joints(axes[5, 1], log)
    for ax in axes.flat:  # a run that failed on its first tick: single samples as dots
        for line in ax.get_lines():
            if len(line.get_xdata()) == 1:
                line.set_marker("o")


def check_drawable(log):
    """LogError unless the log has truth and telemetry of at least one tick."""
    for ch in ("UVMS_TRUTH", "UVMS_TELEMETRY"):
        if ch not in log and log.undecodable(ch):
            raise log.undecodable(ch)
        if ch not in log or not log[ch].count:
            raise runlog.LogError(f"{log.path}: no {ch} messages: nothing to draw")
    if not len(runlog.ee_error(log)[0]):
        raise runlog.LogError(f"{log.path}: no tick with both truth and telemetry (the run "
                               "ended before its first tick): nothing to draw")


def write_dashboard(log, summary, out_path, title, overrides=None):
    """Write the dashboard page of `log` (runlog.Log with CHANNELS) to out_path (PNG).
    summary: the run's summary.json (dict) or None; overrides: its overrides.json list or None;
    title: the run's name for the header."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    check_drawable(log)
    fig, axes = plt.subplots(*GRID, figsize=FIGSIZE_IN, layout="constrained", sharex=True)
    try:
        draw_panels(axes, log)
        for ax in axes.flat:
            ax.tick_params(labelbottom=True)
        lines = [w for line in header_lines(log, summary, overrides, title)
                 for w in textwrap.wrap(line, HEADER_WIDTH_CHARS, subsequent_indent="    ")]
        fig.suptitle("\n".join(lines), fontsize=11, x=0.01, horizontalalignment="left")
        fig.savefig(out_path, dpi=DPI, format="png")
    finally:
        plt.close(fig)


# ----------------------------------------------------------------------------------------------
# Runs and campaigns (tools/uvmslog.py RUN... --dashboard)


def targets_of(path):
    """The run directories or log files a --dashboard path stands for: a log file, a run
    directory, or a campaign directory (every runs/*/ that keeps its log: a note on stderr
    counts the others, which a campaign's --logs policy left without one). Raises LogError for
    anything else, and for a campaign none of whose runs keeps a log."""
    import sys
    if os.path.isfile(path) or os.path.isfile(os.path.join(path, runlog.RUN_LOG_NAME)):
        return [path]
    runs = os.path.join(path, "runs")
    if os.path.isdir(runs):
        dirs = [os.path.join(runs, d) for d in sorted(os.listdir(runs))
                if not d.startswith(".") and os.path.isdir(os.path.join(runs, d))]
        logged = [d for d in dirs if os.path.isfile(os.path.join(d, runlog.RUN_LOG_NAME))]
        if dirs and not logged:
            raise runlog.LogError(f"{path}: none of its {len(dirs)} runs keeps a "
                                  f"{runlog.RUN_LOG_NAME} (uvms campaign --logs); make the logs "
                                  "of the runs to draw with uvms campaign FILE --out DIR --logs "
                                  "ID[,ID...]")
        if len(logged) < len(dirs):
            print(f"uvmslog: note: {len(dirs) - len(logged)} of the {len(dirs)} runs of {path} "
                  f"keep no {runlog.RUN_LOG_NAME} (uvms campaign --logs): no page for them",
                  file=sys.stderr)
        return logged
    if os.path.isdir(path):
        raise runlog.LogError(f"{path}: neither a run directory ({runlog.RUN_LOG_NAME}) nor "
                               "a campaign directory (runs/*/)")
    raise runlog.LogError(f"{path}: no such log file or directory")


def default_out(log_file):
    """RUN_DIR/dashboard.png beside RUN_DIR/run.lcmlog; LOG.dashboard.png beside another log."""
    d, name = os.path.split(os.path.abspath(log_file))
    if name == runlog.RUN_LOG_NAME:
        return os.path.join(d, DASHBOARD_NAME)
    return os.path.join(d, os.path.splitext(name)[0] + "." + DASHBOARD_NAME)


def dashboard_of(target, out=None, title=None, until_damage=False):
    """Draw one run's page; returns (its path, a note or None). Raises LogError (no log,
    damaged, unreadable, no data). until_damage: draw what precedes the log's first damage
    (the note says where it is)."""
    log_file = runlog.log_path(target)
    run_dir = os.path.dirname(os.path.abspath(log_file))
    log = runlog.load(log_file, CHANNELS, until_damage)
    out = out or default_out(log_file)
    write_dashboard(log, read_json(os.path.join(run_dir, "summary.json")), out,
                    title or os.path.basename(run_dir.rstrip(os.sep)),
                    read_json(os.path.join(run_dir, "overrides.json")))
    return out, runlog.damage_note(log.reading)


def _task(args):
    """One run for a worker: (ok, line to print). Every error is caught here, in the worker:
    one bad run gives one line, the other runs still get their pages."""
    target, out, title, until_damage = args
    try:
        path, note = dashboard_of(target, out, title, until_damage)
        return True, f"wrote {path}" + (f" (note: {note})" if note else "")
    except (runlog.LogError, OSError) as e:
        return False, f"uvmslog: error: {e}"
    except ValueError as e:  # data this page cannot show: reported, the other runs go on
        return False, f"uvmslog: error: {target}: {e}"
    except Exception as e:  # noqa: BLE001 (a bug: still one line, never a lost batch)
        return False, (f"uvmslog: error: {target}: no page, internal error "
                       f"{type(e).__name__}: {e}")


def run_dashboards(paths, out=None, jobs=1, title=None, until_damage=False):
    """--dashboard on every path (run, log or campaign): one line per run, then a total.
    Returns the exit status: 0, or 1 when some run has no page (a damaged log among them,
    unless until_damage: then its page shows what precedes the damage)."""
    import sys
    try:
        targets = [t for p in paths for t in targets_of(p)]
        if out and len(targets) != 1:
            raise runlog.LogError(f"--out names one file, but {len(targets)} runs were given "
                                   f"(without --out each run gets RUN_DIR/{DASHBOARD_NAME})")
        if out:
            runlog.check_png_out(out)  # PNG only: no FILE -> FILE.png, no .pdf
    except runlog.LogError as e:
        print(f"uvmslog: error: {e}", file=sys.stderr)
        return 1
    tasks = [(t, out, title if len(targets) == 1 else None, until_damage) for t in targets]
    failed = 0
    for ok, line in _results(tasks, jobs):
        print(line, file=sys.stdout if ok else sys.stderr, flush=True)
        failed += not ok
    if len(targets) > 1:
        print(f"{len(targets) - failed} of {len(targets)} dashboards written"
              + (f", {failed} failed" if failed else ""))
    return 1 if failed else 0


def _results(tasks, jobs):
    """(ok, line) of every task, in order; `jobs` processes at a time."""
    if jobs <= 1 or len(tasks) <= 1:
        yield from map(_task, tasks)
        return
    import multiprocessing
    with multiprocessing.Pool(min(jobs, len(tasks))) as pool:
        yield from pool.imap(_task, tasks)
