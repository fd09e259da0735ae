# SPDX-License-Identifier: Apache-2.0
"""choices_runs: the modeling-choice rows about the thrusters and the controller (logged
configuration) and about the campaigns (the runs' overrides, the schema's defaults)."""
from ..analyses import motor
from ..load.logs import thruster_value
from .checks import joint_tracking, max_voltage, sign_check
from .fmt import f, g
from .settings import default_text, overridden_text


def _drive_row(rep, cfg):
    ms = rep.motor or motor.motor_step(cfg)
    d = rep.drive()
    return ["thruster drive (motor power stage)", f"{rep.drive_text()} "
            "(summary.json). Current drive: the power stage makes the motor current "
            "follow the controller's integrated current command and V = Rm·I + "
            "Lm·İ + km·ω [53] is evaluated for the energy — the paper's reading "
            f"(\"power supply response time negligible\"); speed-step 63 % time "
            f"{f(ms['tau_current_s'], 3)} s with KA = "
            f"{g(thruster_value(cfg, 'speed_gain_1_s'), 3)}, KB = {g(thruster_value(cfg, 'current_gain_1_s'), 3)} "
            f"1/s. Voltage drive: the controller's V is held over the tick; "
            f"{f(ms['tau_voltage_s'], 3)} s to 63 % — an alternative study of a slow "
            "drive, not the paper's"
            + ("" if d in ("current", "voltage") else
               "; these runs predate the setting (voltage drive)"), "§5, §7.4"]


def thruster_rows(rep, cfg, e1):
    durs = sorted({float(r.get("duration_s") or 0) for r in e1.runs})
    return [
        _drive_row(rep, cfg),
        ["thruster sign convention", f"CT2 = {g(thruster_value(cfg, 'ct2'), 3)} < 0: positive "
         "thrust needs negative shaft speed; positive voltage drives positive "
         "current" + sign_check(rep), "§7.4, §3.4"],
        ["motor voltage limit", f"|V| ≤ {g(thruster_value(cfg, 'voltage_limit_V'), 3)} V (logged "
         "config): effectively unlimited — the paper sets none, and with k_m = "
         f"{g(thruster_value(cfg, 'motor_torque_constant_Nm_A'), 3)} V·s/rad a few newtons of thrust "
         f"need kilovolts; largest |V| commanded in experiments 1 and 3 (one seed per "
         f"condition): {f(max_voltage(rep), 1)} V", "§7.4"],
        ["joint servo gains", f"K_q = {g(cfg['joint_kq_1_s2'][0], 4)} 1/s², K_qd = "
         f"{g(cfg['joint_kqd_1_s'][0], 4)} 1/s (logged config)" + joint_tracking(rep), "§8"],
        ["controller period / run length", f"{g(cfg['tick_s'][0], 3)} s tick, "
         f"trajectory t_F = {g(cfg['traj_duration_s'][0], 4)} s (logged config); "
         f"run length in {e1.name}: {', '.join(g(x, 4) for x in durs)} s; "
         "experiment 6 sweeps both", "§3.5"]]


def _integrator_row(rep):
    keys = ("integrator.method", "integrator.rel_tol", "integrator.abs_tol")
    integ = ", ".join(f"{k.split('.')[-1]} = {default_text(rep.schema, k)}" for k in keys)
    return ["CVODE", f"{integ} (documented defaults" + overridden_text(rep.exps, *keys)
            + "); the integrator stops at every tick boundary", "§5"]


def _travel_text(e5):
    return (f"start pose θ = {e5.common_value('trajectory.theta_start_deg')} deg (the sampling "
            f"pose), direction {e5.common_value('trajectory.cartesian.direction')}: from the "
            "stowed pose θI a +x line is unreachable after about 2 cm (campaign file "
            "exp5_travel.toml, README findings)")


def _analytic_like_text(e8b):
    return ("the line of experiment 8 with arm.mass_scale = "
            f"{e8b.common_value('arm.mass_scale')}, arm.hydrodynamics = "
            f"{str(e8b.common_value('arm.hydrodynamics')).lower()} (massless, dragless arm "
            "without volume or added mass, in plant and controller model): payload only, "
            "compared by integrated thrust force")


def _analytic_text(e8):
    c = e8.common_value
    return (f"the analytic model's maneuver: straight EE line ({c('trajectory.mode')}), r_Δ = "
            f"{c('trajectory.cartesian.distance_m')} m along "
            f"{c('trajectory.cartesian.direction')}, from the sampling pose; no unsteady flow, "
            "no density error; payload swept")


# Rows about single experiments: (campaign name, row label, text of its runs, SPEC sections);
# a row is written when the campaign has runs.
_EXPERIMENT_ROWS = (
    ("exp5_travel", "travel experiment (5)", _travel_text, "§8, §9 item 5"),
    ("exp8b_analytic_like", "analytic model, like for like (8b)", _analytic_like_text,
     "§9 item 8"),
    ("exp8_analytic", "analytic experiment (8)", _analytic_text, "§9 item 8"),
    ("exp6_duration", "duration experiment (6)",
     lambda _: "run.duration_s swept together with trajectory.duration_s: every run ends with "
               "its trajectory", "§9 item 6"),
)


def _experiment_rows(rep):
    rows = []
    for name, label, text, spec in _EXPERIMENT_ROWS:
        e = rep.exp(name)
        if e is not None and e.runs:
            rows.append([label, text(e), spec])
    return rows


def campaign_rows(rep):
    return [_integrator_row(rep)] + _experiment_rows(rep) + [
        ["EE estimate / error", "vehicle-reference cases: [3] at the reference pose; "
         "barycenter cases: initial barycenter + virtual manipulator [4]; sampled every "
         "tick (telemetry ee_estimate_m vs truth ee_position_m)", "§10"]]
