# SPDX-License-Identifier: Apache-2.0
"""exp3_motor: the thruster speed loop's step response for both drives; the runs' drive
named."""
from ..analyses import motor
from ..figures import exp3 as fig3
from .common import img
from .fmt import f, g

_CURRENT_TEXT = ("With the current drive the power stage makes the current follow the "
                 "controller's integrated command, so the speed loop settles with KA and KB; "
                 "the voltage drive, whose held voltage excites the motor's lightly damped "
                 "electromechanical mode, is an alternative study of a slow drive, not the "
                 "paper's.")
_VOLTAGE_TEXT = ("With the voltage drive the held voltage drives ω close to V/k_m within each "
                 "tick and the current loop's correction acts only through the small L·İ* "
                 "term; the current drive (the paper's reading, docs/MODEL.md §5) settles with "
                 "KA and KB. These runs therefore study a slow drive, not the paper's.")


def _tau_txt(x):
    return f"{f(x, 3)} s"


def motor_section(rep, cfg):
    ms = motor.motor_step(cfg)
    rep.motor = ms
    drive = rep.drive()
    used = drive if drive in ("current", "voltage") else "voltage"  # unrecorded: old build
    res = ms["resolution_s"]
    path = fig3.motor_step(rep.figs, ms, used)
    tau_used = ms[f"tau_{used}_s"]
    other = "voltage" if used == "current" else "current"
    lp = motor.loop_damping(cfg)
    md = ["**Thruster response.** The loops of docs/MODEL.md §7.4 run once per controller "
          f"tick. The runs used the {rep.drive_text()} (docs/MODEL.md §5). For the logged "
          f"motor and loop parameters, a unit step of the desired shaft speed reaches 63 % "
          f"after {_tau_txt(tau_used)} with the {used} drive, against "
          f"{_tau_txt(ms['tau_continuous_s'])} for the same law in continuous time "
          f"(ω̈ + (KB + b/J)·ω̇ + KA·KB·ω = KA·KB·ω̂: ω_n = {g(lp['wn'], 3)} rad/s, ζ = "
          f"{g(lp['zeta'], 3)}: b/J = {g(lp['b_j'], 3)} 1/s adds to KB in the damping, since the "
          f"friction acts at once and its compensation in Î only through the lagging "
          f"current) and {_tau_txt(ms[f'tau_{other}_s'])} with the {other} drive. The "
          "drives are the exact discretisation of the motor equations [53–55] over the "
          "tick; all three responses are evaluated on a "
          f"{g(res * 1e3, 2)} ms grid and each 63 % time is the first crossing, linearly "
          "interpolated between grid points (a tick-grid reading would be quantised to "
          f"{g(ms['tick_s'], 3)} s). "
          + (_CURRENT_TEXT if used == "current" else _VOLTAGE_TEXT), ""]
    img(md, path,
        "Step response of one thruster's speed loop with the current and the voltage drive "
        "(loops evaluated every tick, the motor exactly between ticks) and the "
        "continuous-time law; 63 % times are first crossings interpolated on a "
        f"{g(res * 1e3, 2)} ms grid.")
    return md
