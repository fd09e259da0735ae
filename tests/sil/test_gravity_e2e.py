# SPDX-License-Identifier: Apache-2.0
"""Station keeping at Earth and Europa gravity (docs/MODEL.md §6.3, §7.5) through `uvms run`:
cases IV (vehicle reference) and VII (barycenter reference) of sil/scenarios/gravity/ (K_PN =
100 N·m/rad, feedforward led by the thrusters' ramp lag), the paper's 60 s maneuver, stagnant,
with the 10 kg payload and with none (the vehicle trimmed for the payload it carries), each
beside the same run at g = 0 and the same run without the lead.

Usage: test_gravity_e2e.py UVMS_EXE SOURCE_DIR CASE
CASE: holds_station (every run finishes; with 10 kg at Earth the mean EE error is at most
      1.0 mm and the attitude error at most 0.2°, at Europa the mean EE error at most 0.3 mm;
      the same runs without the lead finish, are printed beside them, and with a payload have
      both a larger mean EE error and a larger attitude error) |
      paper_gain (with the paper's K_PN = 10 N·m/rad at Earth, 10 kg: at most 1° with the lead,
      more than 1° without it)
"""
import json
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

UVMS, SRC, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
GRAVITY = os.path.join(SRC, "sil", "scenarios", "gravity")
TMP = scratch_dir("uvms-gravity-")  # removed at exit (tests/support/scratch.py)
# Targets with the lead, 10 kg, trimmed, stagnant, 60 s, K_PN = 100: (max attitude error [rad],
# mean EE error [m]) by gravity. The runs without a payload are held to the same bounds.
TARGETS = {"earth": (math.radians(0.2), 1.0e-3), "europa": (math.radians(0.2), 0.3e-3)}
PAPER_GAIN_MAX_ATTITUDE_RAD = math.radians(1.0)
NO_LEAD = "control.feedforward_lead=false"


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
                rn, n = run(name + "_nolead", scenario, *load, NO_LEAD)
                # The same maneuver at g = 0 (no trim needed), for comparison.
                _, z = run(name + "_g0", scenario, *load, 'environment.gravity_m_s2="paper"',
                           "environment.trim=false")
                rows.append((name, s, n, z))
                max_att, max_ee = TARGETS[gravity]
                if rc != 0 or s["status"] != "finished":
                    bad.append(f"{name}: exit {rc}, {s['status']} {s.get('reason', '')}")
                elif rn != 0 or n["status"] != "finished":
                    bad.append(f"{name} without the lead: exit {rn}, {n['status']} "
                               f"{n.get('reason', '')}")
                elif s["max_attitude_error_rad"] > max_att:
                    bad.append(f"{name}: attitude error {math.degrees(s['max_attitude_error_rad']):.3f}° "
                               f"> {math.degrees(max_att):.1f}°")
                elif s["mean_ee_error_m"] > max_ee:
                    bad.append(f"{name}: mean EE error {s['mean_ee_error_m'] * 1e3:.3f} mm > "
                               f"{max_ee * 1e3:.1f} mm")
                elif payload > 0 and not (s["mean_ee_error_m"] < n["mean_ee_error_m"] and
                                          s["max_attitude_error_rad"] < n["max_attitude_error_rad"]):
                    bad.append(f"{name}: the lead did not lower both errors (ε "
                               f"{s['mean_ee_error_m'] * 1e3:.3f} vs {n['mean_ee_error_m'] * 1e3:.3f} mm, "
                               f"attitude {s['max_attitude_error_rad']:.5f} vs "
                               f"{n['max_attitude_error_rad']:.5f} rad)")
    print(f"{'run':18s} {'att [deg]':>9s} {'no lead':>8s} {'EE [mm]':>8s} {'no lead':>8s} "
          f"{'EE g=0':>8s} {'E [kJ]':>9s} {'no lead':>8s}")
    for name, s, n, z in rows:
        if s["status"] == "finished" and n["status"] == "finished":
            print(f"{name:18s} {math.degrees(s['max_attitude_error_rad']):9.3f} "
                  f"{math.degrees(n['max_attitude_error_rad']):8.3f} "
                  f"{s['mean_ee_error_m'] * 1e3:8.3f} {n['mean_ee_error_m'] * 1e3:8.3f} "
                  f"{z['mean_ee_error_m'] * 1e3:8.3f} {s['thruster_energy_J'] / 1e3:9.2f} "
                  f"{n['thruster_energy_J'] / 1e3:8.2f}")
    if bad:
        fail("; ".join(bad))


def case_paper_gain():
    scenario = os.path.join(GRAVITY, "case_VII_earth.toml")
    rc, s = run("paper_gain", scenario, "control.kpn_Nm_rad=10")
    rn, n = run("paper_gain_nolead", scenario, "control.kpn_Nm_rad=10", NO_LEAD)
    print(f"K_PN = 10 N·m/rad at Earth, 10 kg: max attitude error "
          f"{math.degrees(s['max_attitude_error_rad']):.2f}° with the lead, "
          f"{math.degrees(n['max_attitude_error_rad']):.2f}° without")
    if rc != 0 or s["max_attitude_error_rad"] > PAPER_GAIN_MAX_ATTITUDE_RAD:
        fail("with the lead the paper's attitude gain should hold within 1°")
    if rn != 0 or n["max_attitude_error_rad"] <= PAPER_GAIN_MAX_ATTITUDE_RAD:
        fail("without the lead the paper's attitude gain was expected to tilt beyond 1°")


globals()["case_" + CASE]()
print("ok:", CASE)
