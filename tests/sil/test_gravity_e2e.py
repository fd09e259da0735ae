# SPDX-License-Identifier: Apache-2.0
"""Station keeping at Earth and Europa gravity (issue 16 item 2; docs/MODEL.md §6.3) through
`uvms run`: cases IV (vehicle reference) and VII (barycenter reference) of
sil/scenarios/gravity/, the paper's 60 s maneuver, with the 10 kg payload and with none (the
vehicle trimmed for the payload it carries), each beside the same run at g = 0.

Usage: test_gravity_e2e.py UVMS_EXE SOURCE_DIR CASE
CASE: holds_station (every run finishes within 1° of attitude error; its mean EE error stays
      within a few mm, printed beside the g = 0 run's) | paper_gain_tilts (with the paper's
      K_PN = 10 N·m/rad the Earth 10 kg run tilts by more than 1°: why the scenarios raise it)
"""
import json
import math
import os
import subprocess
import sys
import tempfile

UVMS, SRC, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
GRAVITY = os.path.join(SRC, "sil", "scenarios", "gravity")
TMP = tempfile.mkdtemp(prefix="uvms-gravity-")
MAX_ATTITUDE_RAD = math.radians(1.0)  # the bound
# Mean EE error bound [m]: the paper's own EE errors under unsteady flow are tens of mm; at
# Earth gravity with 10 kg the attitude error (≤ 1°) over the ~1 m reach gives a few mm.
MAX_MEAN_EE_ERROR_M = 0.010


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def run(name, scenario, *sets):
    out = os.path.join(TMP, name)
    args = [UVMS, "run", scenario, "--out", out, "--transport", "memq"]
    for s in sets:
        args += ["--set", s]
    p = subprocess.run(args, capture_output=True, text=True, timeout=300)
    print(p.stdout.strip(), p.stderr.strip())
    with open(os.path.join(out, "summary.json")) as f:
        return p.returncode, json.load(f)


def case_holds_station():
    rows, bad = [], []
    for case in ("IV", "VII"):
        for gravity in ("earth", "europa"):
            for payload in (10.0, 0.0):
                scenario = os.path.join(GRAVITY, f"case_{case}_{gravity}.toml")
                load = (f"payload.mass_kg={payload}", f"environment.trim_payload_kg={payload}")
                name = f"{case}_{gravity}_{payload:g}kg"
                rc, s = run(name, scenario, *load)
                # The same maneuver at g = 0 (no trim needed), for comparison.
                _, z = run(name + "_g0", scenario, *load, 'environment.gravity_m_s2="paper"',
                           "environment.trim=false")
                rows.append((name, s, z))
                if rc != 0 or s["status"] != "finished":
                    bad.append(f"{name}: exit {rc}, {s['status']} {s.get('reason', '')}")
                elif s["max_attitude_error_rad"] > MAX_ATTITUDE_RAD:
                    bad.append(f"{name}: attitude error {s['max_attitude_error_rad']:.4f} rad > 1°")
                elif s["mean_ee_error_m"] > MAX_MEAN_EE_ERROR_M:
                    bad.append(f"{name}: mean EE error {s['mean_ee_error_m'] * 1e3:.2f} mm")
    print(f"{'run':18s} {'att [deg]':>9s} {'EE [mm]':>8s} {'EE g=0':>8s} {'E [kJ]':>9s} {'E g=0':>8s}")
    for name, s, z in rows:
        if s["status"] == "finished":
            print(f"{name:18s} {math.degrees(s['max_attitude_error_rad']):9.3f} "
                  f"{s['mean_ee_error_m'] * 1e3:8.3f} {z['mean_ee_error_m'] * 1e3:8.3f} "
                  f"{s['thruster_energy_J'] / 1e3:9.2f} {z['thruster_energy_J'] / 1e3:8.3f}")
    if bad:
        fail("; ".join(bad))


def case_paper_gain_tilts():
    scenario = os.path.join(GRAVITY, "case_VII_earth.toml")
    rc, s = run("paper_gain", scenario, "control.kpn_Nm_rad=10")
    print(f"K_PN = 10 N·m/rad at Earth, 10 kg: max attitude error "
          f"{math.degrees(s['max_attitude_error_rad']):.2f}°")
    if rc != 0 or s["max_attitude_error_rad"] <= MAX_ATTITUDE_RAD:
        fail("with the paper's attitude gain the run was expected to tilt beyond 1° and finish")


globals()["case_" + CASE]()
print("ok:", CASE)
