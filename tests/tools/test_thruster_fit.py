# SPDX-License-Identifier: Apache-2.0
"""The "t200" motor set against its datasheet (docs/MODEL.md §5 "The T200 set").

1. tools/thruster_fit.py, run on the cited data (tests/tools/data/t200_16V_bollard.csv),
   gives the values of the "t200" set in sil/scenario/motor_sets.cpp (read from that file, the ONE
   table) to their printed 4 significant digits.
2. The set, evaluated with SPEC §5's laws (the same formulas as plant/src/propulsion.cpp),
   reproduces the datasheet within the residuals stated in docs/MODEL.md: RMS relative error
   of thrust vs RPM ≤ 12.5 %, of electrical power vs RPM ≤ 4 %, of electrical power vs thrust
   ≤ 23 %; at full throttle the terminal voltage is the 16 V bus within 3 %.
3. The plant and the controller use the same values: a 3 s closed-loop run of case IV with
   thrusters.motor = "t200" at the datasheet's ρ = 1000 kg/m³ logs, every tick and thruster,
   the thrust of the set's law at the logged speed (relative 1e-9), a terminal voltage
   V = Rm·I + Lm·İ + km·ω with |Lm·İ| small, and a controller configuration carrying the
   set's Rm, Lm, km, b.

Usage: test_thruster_fit.py UVMS_BINARY SOURCE_DIR
"""
import csv
import io
import math
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

UVMS, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tools"))
from uvms_tools.models import thruster_fit  # noqa: E402

DATA = os.path.join(SRC, "tests", "tools", "data", "t200_16V_bollard.csv")
RHO_TEST = 1000.0
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def set_from_table():
    """The "t200" set's values, read from sil/scenario/motor_sets.cpp (T200Set())."""
    text = open(os.path.join(SRC, "sil", "scenario", "motor_sets.cpp"), encoding="utf-8").read()
    body = text[text.index("PropulsionParams T200Set()"):]
    body = body[:body.index("return p;")]
    vals = {k: float(v) for k, v in re.findall(r"p\.(\w+)\s*=\s*([-+0-9.eE]+);", body)}
    check(len(vals) == 10, f"T200Set() sets the 10 keys (got {sorted(vals)})")
    check('{"t200",' in text and "T200Set}" in text.replace("\n", "").replace(" ", ""),
          'the table lists "t200" with T200Set')
    return vals


def main():
    p = set_from_table()
    data = thruster_fit.load(DATA)
    check(data["pwm_us"].size == 186, f"186 datasheet points with RPM > 0 (got {data['pwm_us'].size})")

    # 1. The script reproduces the table.
    fit = thruster_fit.fit(data, RHO_TEST, 0.076, 16.0, 0.1, 5.0, 2.0e-5, 5.0e-5)
    for k, v in fit["params"].items():
        ok = (v == p[k] == 0.0) or abs(v - p[k]) <= 5e-4 * abs(v)
        check(ok, f"fit {k} = {v:.6g} matches the table's {p[k]:.6g}")

    # 2. The set against the data (SPEC §5 at v_a = 0, steady state).
    T, w, P = data["thrust_N"], data["omega"], data["power_W"]
    D = p["diameter_m"]
    kt = RHO_TEST * D**4 / (4 * math.pi**2)
    kq = RHO_TEST * D**5 / (4 * math.pi**2)
    T_model = kt * (p["ct2"] * w * np.abs(w))
    sT = np.abs(T) >= 0.1 * thruster_fit.G0
    e_T = float(np.sqrt(np.mean(((T_model[sT] - T[sT]) / T[sT]) ** 2)))
    check(e_T <= 0.125, f"thrust vs RPM: RMS relative error {e_T:.4f} <= 0.125 ({sT.sum()} points)")
    check(bool(np.all(np.sign(T_model) == np.sign(T))), "positive thrust at negative ω (CT2 < 0)")

    def power_at(om):
        current = (p["viscous_friction_Nm_s"] * om + kq * p["cq2"] * om * np.abs(om)) / p["torque_constant_Nm_A"]
        voltage = p["resistance_ohm"] * current + p["torque_constant_Nm_A"] * om
        return current, voltage, voltage * current

    sP = P >= 5.0
    I_w, V_w, P_w = power_at(w)
    e_Pw = float(np.sqrt(np.mean(((P_w[sP] - P[sP]) / P[sP]) ** 2)))
    check(e_Pw <= 0.04, f"power vs RPM: RMS relative error {e_Pw:.4f} <= 0.04 ({sP.sum()} points)")
    w_T = -np.sign(T) * np.sqrt(np.abs(T) / abs(kt * p["ct2"]))
    _, _, P_T = power_at(w_T)
    e_PT = float(np.sqrt(np.mean(((P_T[sP] - P[sP]) / P[sP]) ** 2)))
    check(e_PT <= 0.23, f"power vs thrust: RMS relative error {e_PT:.4f} <= 0.23")
    check(bool(np.all(P_w > 0)), "the water and the bearings load the shaft: V·I > 0 at every point")
    ends = [int(np.argmin(data["pwm_us"])), int(np.argmax(data["pwm_us"]))]
    for i in ends:
        check(abs(abs(V_w[i]) - 16.0) <= 0.03 * 16.0,
              f"full throttle (PWM {data['pwm_us'][i]:.0f}): terminal voltage {abs(V_w[i]):.2f} V ≈ 16 V bus")

    # 3. The plant and the controller, closed loop.
    with tempfile.TemporaryDirectory() as out:
        run = subprocess.run(
            [UVMS, "run", os.path.join(SRC, "sil", "scenarios", "paper", "case_IV_stagnant.toml"),
             "--out", out, "--transport", "memq", "--set", 'thrusters.motor="t200"',
             "--set", "run.duration_s=3", "--set", f"environment.density_kg_m3={RHO_TEST}"],
            capture_output=True, text=True, timeout=120)
        check(run.returncode == 0 and "finished" in run.stdout,
              f"case IV with t200 runs closed loop ({run.stdout.strip()[:160]} {run.stderr.strip()[:300]})")
        if run.returncode != 0:
            return
        rows = export(out, "UVMS_TRUTH")
        cfg = export(out, "UVMS_CONFIG")[0]
    om = np.array([[float(r[f"motor_speed_rad_s.T{j}"]) for j in range(1, 9)] for r in rows])
    cur = np.array([[float(r[f"motor_current_A.T{j}"]) for j in range(1, 9)] for r in rows])
    volt = np.array([[float(r[f"motor_voltage_V.T{j}"]) for j in range(1, 9)] for r in rows])
    thr = np.array([[float(r[f"thrust_N.T{j}"]) for j in range(1, 9)] for r in rows])
    check(float(np.abs(thr).max()) > 1e-3, f"the thrusters work (max |T| {np.abs(thr).max():.3g} N)")
    law = kt * p["ct2"] * om * np.abs(om)
    err = float(np.max(np.abs(thr - law) / np.maximum(np.abs(law), 1e-12)))
    check(err <= 1e-9, f"plant thrust = the set's law at the logged speed (max relative error {err:.2e})")
    resid = volt - p["resistance_ohm"] * cur - p["torque_constant_Nm_A"] * om  # = Lm·İ
    check(float(np.abs(resid).max()) <= 0.01,
          f"V = Rm·I + Lm·İ + km·ω with |Lm·İ| <= 10 mV (max {np.abs(resid).max():.2e} V)")
    for field, key in [("motor_resistance_ohm", "resistance_ohm"), ("motor_inductance_H", "inductance_H"),
                       ("motor_torque_constant_Nm_A", "torque_constant_Nm_A"),
                       ("motor_viscous_friction_Nm_s", "viscous_friction_Nm_s")]:
        got = [float(cfg[f"{field}.T{j}"]) for j in range(1, 9)]  # one set per thruster
        check(all(abs(x - p[key]) <= 1e-6 * abs(p[key]) for x in got),
              f"controller config {field} = {got[0]:.6g} on all 8 thrusters (set {p[key]:.6g})")


def export(run_dir, channel):
    env = dict(os.environ, UVMS_NO_REEXEC="1")
    r = subprocess.run([sys.executable, os.path.join(SRC, "tools", "uvmslog.py"), run_dir, "--csv", channel,
                        "--out", "-"], capture_output=True, text=True, timeout=120, env=env)
    if r.returncode != 0:
        raise SystemExit(f"uvmslog --csv {channel} failed: {r.stderr}")
    return list(csv.DictReader(io.StringIO(r.stdout)))


if __name__ == "__main__":
    main()
    if failures:
        print(f"{len(failures)} check(s) failed")
        sys.exit(1)
    print("all checks passed")
