# SPDX-License-Identifier: Apache-2.0
"""thruster_fit: fit SPEC §5's propeller and motor model to a published bollard datasheet.

Data: tests/tools/data/t200_16V_bollard.csv (Blue Robotics T200 at 16 V, its public
performance workbook of September 2019; the citation is in the file's header). Every row with a
measured shaft speed (RPM > 0; the sheet reports RPM below 300 as 0) is a data point.

Model (SPEC §5 at v_a = 0, steady state, the project's sign convention: CT2 < 0, so positive
thrust needs negative shaft speed ω; the datasheet's RPM is unsigned, ω = −sign(T)·2π·RPM/60):

  T = ρ·D⁴/(4π²)·CT2·ω·|ω|                  (thrust)
  Q = ρ·D⁵/(4π²)·CQ2·ω·|ω|                  (CQ2 > 0: the water loads the shaft, Q·ω > 0)
  km·I = b·ω + Q                             (J·ω̇ = km·I − b·ω − Q with ω̇ = 0)
  V = Rm·I + km·ω,  P_el = V·I = Rm·I² + (b·ω + Q)·ω

P_el is the motor's terminal power; the datasheet's power is the supply's V·I at the ESC input.
They are equal for a lossless ESC: the ESC's losses are lumped into Rm and b.

Fit, in three steps:
 1. CT2 from thrust against speed: least squares of the relative thrust error over the points
    with |T| ≥ --min-thrust-kgf (below, the sheet's 0.01 kgf rounding dominates).
 2. b, CQ2 and r = Rm/km² from electrical power against the measured speed (the motor's
    physics: at equal speed the power is nearly the same both ways, the thrust is not),
    least squares of the relative error over the points with P ≥ --min-power-W (below, the
    sheet's 0.05–0.1 A rounding dominates). Bounds b, CQ2, r ≥ 0.
 3. km from the bus voltage at full throttle (duty cycle 1: the motor sees the whole bus):
    there V = P/I_bus = --bus-V and I = I_bus, so km = (b·ω + Q)/I at the full-throttle
    speed; the mean over the two full-throttle rows (forward and reverse). Rm = r·km².
J and Lm are not identifiable from steady-state data; they are stated estimates
(--rotor-inertia, --inductance; docs/MODEL.md §5 "The T200 set"). CT1, CQ1 (the advance-speed
terms) are not identifiable from bollard data; the set gives 0.

Residuals: RMS relative error of thrust vs RPM, of power vs RPM and of power vs thrust (the
power the model needs at the speed that makes the measured thrust), over the fit ranges and
over all points, per direction. Prints the set as C++ for sil/scenario/motor_sets.cpp.

Usage: tools/thruster_fit.py [--data CSV] [--json OUT] [other options: --help]
"""
import argparse
import json
import math
import os

from uvms_tools.env import REPO_ROOT, add_version_option

DEFAULT_DATA = os.path.join(REPO_ROOT, "tests", "tools", "data", "t200_16V_bollard.csv")
G0 = 9.80665  # standard gravity [m/s²]: 1 kgf in N


def load(path):
    """The datasheet's rows with a measured speed: dict of numpy arrays (SI units, signed ω)."""
    import numpy as np
    rows = []
    with open(path, encoding="utf-8") as f:
        header = None
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            if header is None:
                header = line.split(",")
                continue
            rows.append([float(x) for x in line.split(",")])
    a = np.array(rows)
    col = {name: a[:, i] for i, name in enumerate(header)}
    keep = col["rpm"] > 0
    thrust_N = col["force_kgf"][keep] * G0
    speed = col["rpm"][keep] * 2.0 * math.pi / 60.0
    return {
        "pwm_us": col["pwm_us"][keep],
        "thrust_N": thrust_N,
        "omega": -np.sign(thrust_N) * speed,  # CT2 < 0: positive thrust, negative ω
        "power_W": col["power_W"][keep],
        "current_A": col["current_A"][keep],
        "voltage_V": col["voltage_V"][keep],
        "dropped": int((~keep).sum()),
    }


def thrust_N(ct2, rho, D, omega):
    """SPEC §5 thrust at v_a = 0 [N]."""
    import numpy as np
    return rho * D**4 / (4.0 * math.pi**2) * ct2 * omega * np.abs(omega)


def omega_for_thrust(ct2, rho, D, T):
    """The speed that makes thrust T at v_a = 0 (the controller's ω̂ of [57–63] with v_a = 0)."""
    import numpy as np
    c1 = ct2 * rho * D**4 / (4.0 * math.pi**2)  # < 0
    return -np.sign(T) * np.sqrt(np.abs(T) / abs(c1))


def steady_state(p, rho, omega):
    """Steady state at v_a = 0: (current I [A], terminal voltage V [V], power V·I [W])."""
    import numpy as np
    Q = rho * p["diameter_m"]**5 / (4.0 * math.pi**2) * p["cq2"] * omega * np.abs(omega)
    current = (p["viscous_friction_Nm_s"] * omega + Q) / p["torque_constant_Nm_A"]
    voltage = p["resistance_ohm"] * current + p["torque_constant_Nm_A"] * omega
    return current, voltage, voltage * current


def rms_rel(model, data):
    import numpy as np
    return float(np.sqrt(np.mean(((model - data) / data) ** 2)))


def fit(data, rho, D, bus_V, min_thrust_kgf, min_power_W, J, Lm):
    import numpy as np
    from scipy.optimize import least_squares

    T, w, P = data["thrust_N"], data["omega"], data["power_W"]
    sT = np.abs(T) >= min_thrust_kgf * G0
    # 1. CT2: minimise Σ(T_model/T − 1)², linear in CT2: closed form.
    x = rho * D**4 / (4.0 * math.pi**2) * w[sT] * np.abs(w[sT]) / T[sT]
    ct2 = float(np.sum(x) / np.sum(x * x))

    # 2. b, CQ2, r = Rm/km² from electrical power against the measured speed (the motor's
    #    physics; power at equal speed is nearly the same both ways, thrust is not).
    sP = P >= min_power_W
    kq = rho * D**5 / (4.0 * math.pi**2)

    def power(theta, om):
        b, cq2, r = theta
        torque = b * om + kq * cq2 * om * np.abs(om)  # km·I
        return r * torque**2 + torque * om

    res = least_squares(lambda th: power(th, w[sP]) / P[sP] - 1.0, x0=[1e-4, 0.05, 1e-3],
                        bounds=([0.0, 0.0, 0.0], [np.inf, np.inf, np.inf]),
                        x_scale=[1e-4, 0.05, 1e-3], xtol=1e-15, ftol=1e-15, gtol=1e-15)
    b, cq2, r = (float(v) for v in res.x)

    # 3. km from the bus voltage at full throttle (duty 1: V = bus, I = I_bus), both ends of
    #    the PWM range: bus = Rm·I + km·|ω| = r·km²·I + km·|ω|, the positive root.
    ends = [int(np.argmin(data["pwm_us"])), int(np.argmax(data["pwm_us"]))]
    kms = []
    for i in ends:
        I_bus, speed = P[i] / bus_V, abs(w[i])
        a_, b_, c_ = r * I_bus, speed, -bus_V
        kms.append(float((-b_ + math.sqrt(b_ * b_ - 4.0 * a_ * c_)) / (2.0 * a_)) if a_ > 0
                   else bus_V / speed)
    km = float(np.mean(kms))
    params = {
        "diameter_m": D, "ct1": 0.0, "ct2": ct2, "cq1": 0.0, "cq2": cq2,
        "resistance_ohm": r * km * km, "inductance_H": Lm, "torque_constant_Nm_A": km,
        "viscous_friction_Nm_s": b, "rotor_inertia_kg_m2": J,
    }

    # Residuals.
    T_model = thrust_N(ct2, rho, D, w)
    w_T = omega_for_thrust(ct2, rho, D, T)  # the speed the model needs for the measured thrust
    I_w, V_w, P_w = steady_state(params, rho, w)  # at the measured speed
    _, _, P_model = steady_state(params, rho, w_T)
    fwd, rev = T > 0, T < 0
    resid = {
        "thrust_vs_rpm_fit_range": rms_rel(T_model[sT], T[sT]),
        "thrust_vs_rpm_all": rms_rel(T_model, T),
        "thrust_vs_rpm_forward": rms_rel(T_model[sT & fwd], T[sT & fwd]),
        "thrust_vs_rpm_reverse": rms_rel(T_model[sT & rev], T[sT & rev]),
        "power_vs_rpm_fit_range": rms_rel(P_w[sP], P[sP]),
        "power_vs_rpm_forward": rms_rel(P_w[sP & fwd], P[sP & fwd]),
        "power_vs_rpm_reverse": rms_rel(P_w[sP & rev], P[sP & rev]),
        "current_vs_rpm_fit_range": rms_rel(np.abs(I_w[sP]) * np.abs(V_w[sP]) / bus_V,
                                            data["current_A"][sP]),
        "power_vs_thrust_fit_range": rms_rel(P_model[sP], P[sP]),
        "power_vs_thrust_all": rms_rel(P_model, P),
        "power_vs_thrust_forward": rms_rel(P_model[sP & fwd], P[sP & fwd]),
        "power_vs_thrust_reverse": rms_rel(P_model[sP & rev], P[sP & rev]),
    }
    full = {"km_each_end_Nm_A": kms,
            "terminal_V_at_full_throttle": [float(abs(V_w[i])) for i in ends],
            "motor_current_A_at_full_throttle": [float(abs(I_w[i])) for i in ends],
            "power_W_at_full_throttle_model": [float(P_model[i]) for i in ends],
            "power_W_at_full_throttle_data": [float(P[i]) for i in ends],
            "thrust_N_at_full_throttle_data": [float(T[i]) for i in ends]}
    n = {"points": int(len(T)), "dropped_zero_rpm": data["dropped"],
         "thrust_fit": int(sT.sum()), "power_fit": int(sP.sum()),
         "thrust_range_N": [float(T.min()), float(T.max())],
         "rpm_range": [float(np.abs(w).min() * 60 / (2 * math.pi)),
                       float(np.abs(w).max() * 60 / (2 * math.pi))],
         "power_range_W": [float(P.min()), float(P.max())]}
    return {"params": params, "residuals": resid, "full_throttle": full, "counts": n,
            "settings": {"rho_kg_m3": rho, "bus_V": bus_V, "min_thrust_kgf": min_thrust_kgf,
                         "min_power_W": min_power_W}}


def cxx(params):
    order = ["diameter_m", "ct1", "ct2", "cq1", "cq2", "resistance_ohm", "inductance_H",
             "torque_constant_Nm_A", "viscous_friction_Nm_s", "rotor_inertia_kg_m2"]
    return "\n".join(f"  p.{k} = {params[k]:.4g};" for k in order)


def main(argv=None):
    ap = argparse.ArgumentParser(
        description="Fit SPEC §5's propeller + motor model (CT2, CQ2, b, Rm, km) to a bollard "
                    "datasheet (thrust, RPM, supply power at one bus voltage); print the "
                    "parameters, the residuals and the set as C++ for sil/scenario/motor_sets.cpp.")
    add_version_option(ap, "thruster_fit")
    ap.add_argument("--data", default=DEFAULT_DATA, help="datasheet CSV (default: %(default)s)")
    ap.add_argument("--diameter", type=float, default=0.076,
                    help="propeller diameter D [m] (default: the T200's published 76 mm)")
    ap.add_argument("--rho", type=float, default=1000.0,
                    help="water density of the test [kg/m³] (default: fresh water, 1000)")
    ap.add_argument("--bus-V", type=float, default=16.0, help="bus voltage [V] (default: 16)")
    ap.add_argument("--min-thrust-kgf", type=float, default=0.1,
                    help="thrust fit uses |T| ≥ this [kgf] (default: %(default)s)")
    ap.add_argument("--min-power-W", type=float, default=5.0,
                    help="power fit uses P ≥ this [W] (default: %(default)s)")
    ap.add_argument("--rotor-inertia", type=float, default=2.0e-5,
                    help="J [kg·m²], a stated estimate (default: %(default)s)")
    ap.add_argument("--inductance", type=float, default=5.0e-5,
                    help="Lm [H], a stated estimate (default: %(default)s)")
    ap.add_argument("--json", help="also write the result as JSON to this file")
    args = ap.parse_args(argv)

    data = load(args.data)
    out = fit(data, args.rho, args.diameter, args.bus_V, args.min_thrust_kgf, args.min_power_W,
              args.rotor_inertia, args.inductance)
    print(json.dumps(out, indent=2))
    print("\n// sil/scenario/motor_sets.cpp\n" + cxx(out["params"]))
    if args.json:
        with open(args.json, "w", encoding="utf-8") as f:
            json.dump(out, f, indent=2)
    return 0
