# SPDX-License-Identifier: Apache-2.0
"""`uvms vehicle import-urdf` (tools/uvms_tools/vehicle/urdf.py, docs/MODEL.md §2 "General
links") against Pinocchio on the same URDF.

The fixture (tests/tools/data/four_joint_arm.urdf) has joint origins with rpy, axes along z, y,
x and a skew direction, turned inertial frames (off-diagonal tensors), a fixed link inside the
chain, a fixed tool frame at the tip and a plate fixed to the root. The import's links go to
the firmware through `uvms model --config` (its Newton–Euler recursion, double build), vehicle
at rest and level at the origin, no link volume (so no buoyancy, drag or added mass: the arm in
vacuum) and no payload; Pinocchio builds its fixed-base model from the URDF itself
(pin.buildModelFromUrdf). At 50 random states (q within the limits, q̇, q̈) under gravity:
  - the joint torques agree to 1e-9 relative (of the largest |τ| of the state);
  - the EE (the tip link's origin) agrees with Pinocchio's frame placement to 1e-12 m.
Then the errors, each naming the element: a moving link without <inertial>, a prismatic, a
floating joint, a <mimic> joint on the chain, eight movable joints, a branching tree without
--tip, a bad number, a side file's unknown link; the hydrodynamics from --hydro, the exit
statuses, --help, and `uvms vehicle` through the uvms binary. Last, the imported arm flown in a
SIL run: the viewer's kinematics of the logged scene reproduce the plant's EE.

Usage: test_urdf_import.py UVMS_EXE SOURCE_DIR
"""
import json
import os
import re
import subprocess
import sys
import tomllib

import numpy as np
import pinocchio as pin

UVMS, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tools"))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checklist  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

TMP = scratch_dir("uvms-urdf-")
FIXTURE = os.path.join(SRC, "tests", "tools", "data", "four_joint_arm.urdf")
TOOL = os.path.join(SRC, "tools", "uvms_vehicle.py")
G = [0.0, 0.0, -9.81]
REL_TOL = 1e-9
TALLY = checklist.Tally()
check = TALLY.check


def vehicle(*args, expect=0):
    p = subprocess.run([sys.executable, TOOL] + list(args), capture_output=True, text=True,
                       env=dict(os.environ, UVMS_NO_REEXEC="1"))
    if p.returncode != expect:
        check(False, f"uvms vehicle {' '.join(args)}: exit {p.returncode}, expected {expect} "
                     f"({p.stderr.strip()[-300:]})")
    return p


def imported(*extra):
    p = vehicle("import-urdf", FIXTURE, *extra)
    return tomllib.loads(p.stdout)


def model_config(desc):
    """`uvms model --config` of an imported description, every link without volume."""
    links = []
    for L in desc["arm"]["link"]:
        links.append({k: L[k] for k in ("alpha_rad", "a_m", "d_m", "placement_m",
                                         "placement_rotvec_rad", "mass_kg", "com_m",
                                         "inertia_kg_m2", "inertia_products_kg_m2")}
                     | {"diameter_m": 0.0})
    cfg = {"vehicle": {"base_offset_m": desc["vehicle"]["arm_base_m"],
                       "base_rotvec_rad": desc["vehicle"]["arm_base_rotvec_rad"]},
           "links": links}
    path = os.path.join(TMP, "model.json")
    with open(path, "w") as f:
        json.dump(cfg, f)
    return path


def firmware(cfg, q, qd, qdd):
    zero3 = [0.0, 0.0, 0.0]
    state = {"vehicle": {"position_m": zero3, "quaternion_wxyz": [1.0, 0.0, 0.0, 0.0],
                         "velocity_m_s": zero3, "angular_velocity_rad_s": zero3,
                         "acceleration_m_s2": zero3, "angular_acceleration_rad_s2": zero3},
             "joints": {"position_rad": list(q), "velocity_rad_s": list(qd),
                        "acceleration_rad_s2": list(qdd)},
             "density_kg_m3": 1000.0, "flow_m_s": zero3, "gravity_m_s2": G,
             "payload_kg": 0.0, "angle_of_attack": True}
    p = subprocess.run([UVMS, "model", "--config", cfg], input=json.dumps(state),
                       capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"uvms model: exit {p.returncode}: {p.stderr.strip()}")
    return json.loads(p.stdout)


def check_against_pinocchio():
    desc = imported()
    cfg = model_config(desc)
    model = pin.buildModelFromUrdf(FIXTURE)
    model.gravity.linear = np.array(G)
    data = model.createData()
    tool = model.getFrameId("tool")
    check(model.nq == 4 and len(desc["arm"]["link"]) == 4, f"4 joints on both sides "
          f"(Pinocchio nq = {model.nq}, imported {len(desc['arm']['link'])})")
    lo, hi = model.lowerPositionLimit, model.upperPositionLimit
    rng = np.random.default_rng(20261205)
    worst_tau, worst_ee = 0.0, 0.0
    for _ in range(50):
        q = rng.uniform(lo, hi)
        qd, qdd = rng.uniform(-1.0, 1.0, 4), rng.uniform(-2.0, 2.0, 4)
        tau_pin = pin.rnea(model, data, q, qd, qdd)
        pin.framesForwardKinematics(model, data, q)
        out = firmware(cfg, q, qd, qdd)
        tau = np.array(out["joint_torque_Nm"])
        worst_tau = max(worst_tau, np.abs(tau - tau_pin).max() / np.abs(tau_pin).max())
        worst_ee = max(worst_ee, np.abs(np.array(out["ee_position_m"]) -
                                        data.oMf[tool].translation).max())
    print(f"import-urdf vs Pinocchio: worst joint-torque difference {worst_tau:.2e} (relative), "
          f"worst EE difference {worst_ee:.2e} m over 50 states")
    check(worst_tau <= REL_TOL, f"joint torques = pin.rnea to {REL_TOL:g} relative "
          f"(worst {worst_tau:.2e})")
    check(worst_ee <= 1e-12, f"EE = Pinocchio's tool frame to 1e-12 m (worst {worst_ee:.2e} m)")
    limits = [(L.get("joint_min_rad"), L.get("joint_max_rad")) for L in desc["arm"]["link"]]
    check(limits == [(-3.0, 3.0), (-2.0, 2.0), (-2.5, 2.5), (-3.0, 3.0)],
          f"joint limits from <limit> ({limits})")


def edited(pattern, repl, name, count=1):
    """The fixture with one regex edit, written to TMP/name."""
    with open(FIXTURE) as f:
        text = f.read()
    new, n = re.subn(pattern, repl, text, count=count, flags=re.S)
    assert n == count, pattern
    path = os.path.join(TMP, name)
    with open(path, "w") as f:
        f.write(new)
    return path


def error_of(path, *extra):
    p = vehicle("import-urdf", path, *extra, expect=1)
    return p.stderr.strip()


def check_errors():
    cases = [
        (edited(r'<link name="fore">\s*<inertial>.*?</inertial>', '<link name="fore">',
                "no_inertia.urdf"),
         "link 'fore' (moved by joint 'elbow') has no <inertial>"),
        (edited(r'name="elbow" type="revolute"', 'name="elbow" type="prismatic"', "prismatic.urdf"),
         "joint 'elbow': type 'prismatic': the firmware runs revolute joints only"),
        (edited(r'name="shoulder" type="revolute"', 'name="shoulder" type="floating"',
                "floating.urdf"),
         "joint 'shoulder': type 'floating'"),
        (edited(r'(<joint name="wrist" type="revolute">)', r'\1<mimic joint="elbow"/>', "mimic.urdf"),
         "joint 'wrist': a <mimic> joint"),
        (edited(r'xyz="0.02 0 0.08" rpy="0.1 0 -0.2"', 'xyz="0.02 0 zero" rpy="0.1 0 -0.2"',
                "bad_number.urdf"),
         "joint 'shoulder' <origin>: xyz='0.02 0 zero' is not 3 numbers"),
    ]
    # Eight movable joints: four more after the wrist.
    extra = "".join(
        f'<link name="x{k}"><inertial><mass value="0.1"/><inertia ixx="1e-5" ixy="0" ixz="0" '
        f'iyy="1e-5" iyz="0" izz="1e-5"/></inertial></link><joint name="j{k}" type="revolute">'
        f'<parent link="{"tool" if k == 0 else f"x{k - 1}"}"/><child link="x{k}"/>'
        f'<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        for k in range(4))
    cases.append((edited(r"</robot>", extra + "</robot>", "eight.urdf"),
                  "8 movable joints between 'base_link' and 'x3' (expected 1..7"))
    # A gripper's two fingers: the tree branches at the wrist.
    fingers = "".join(
        f'<link name="finger{k}"><inertial><mass value="0.05"/><inertia ixx="1e-6" ixy="0" '
        f'ixz="0" iyy="1e-6" iyz="0" izz="1e-6"/></inertial></link><joint name="f{k}" '
        f'type="revolute"><parent link="wrist"/><child link="finger{k}"/><axis xyz="1 0 0"/>'
        f'<limit lower="0" upper="0.5" effort="1" velocity="1"/></joint>' for k in range(2))
    branch = edited(r"</robot>", fingers + "</robot>", "branch.urdf")
    cases.append((branch, "the tree branches (3 leaf links: finger0, finger1, tool); name the "
                          "arm's tip with --tip LINK"))
    for path, want in cases:
        got = error_of(path)
        check(want in got, f"{os.path.basename(path)}: {want!r} in the error ({got[-200:]!r})")
    # --tip picks the arm out of the branching tree; the fingers (and a camera fixed to the
    # upper arm, off the path) are carried rigidly: Pinocchio with the fingers at rest agrees.
    camera = ('<link name="camera"><inertial><origin xyz="0.01 0.02 0"/><mass value="0.4"/>'
              '<inertia ixx="2e-4" ixy="0" ixz="0" iyy="3e-4" iyz="0" izz="1e-4"/></inertial>'
              '</link><joint name="camera_fix" type="fixed"><parent link="upper"/>'
              '<child link="camera"/><origin xyz="0.1 0.05 0.03" rpy="0 0.4 0"/></joint>')
    branch_cam = edited(r"</robot>", fingers + camera + "</robot>", "branch_camera.urdf")
    p = vehicle("import-urdf", branch_cam, "--tip", "tool")
    check(p.stdout.count("[[arm.link]]") == 4 and "held rigid" in p.stdout,
          "--tip tool: the 4-joint arm of the branching tree, the fingers held rigid (said)")
    desc = tomllib.loads(p.stdout)
    model = pin.buildModelFromUrdf(branch_cam)
    model.gravity.linear = np.array(G)
    data = model.createData()
    rng = np.random.default_rng(7)
    worst = 0.0
    for _ in range(10):
        q = np.zeros(model.nq)
        q[:4] = rng.uniform(-1.0, 1.0, 4)
        qd, qdd = np.zeros(model.nv), np.zeros(model.nv)
        qd[:4], qdd[:4] = rng.uniform(-1.0, 1.0, 4), rng.uniform(-2.0, 2.0, 4)
        tau_pin = pin.rnea(model, data, q, qd, qdd)[:4]
        tau = np.array(firmware(model_config(desc), q[:4], qd[:4], qdd[:4])["joint_torque_Nm"])
        worst = max(worst, np.abs(tau - tau_pin).max() / np.abs(tau_pin).max())
    check(model.nq == 6 and worst <= REL_TOL, f"off-path masses (fingers at rest, a fixed "
          f"camera) carried: torques = pin.rnea to {REL_TOL:g} (worst {worst:.2e})")
    hydro = os.path.join(TMP, "hydro.toml")
    with open(hydro, "w") as f:
        # An added mass isotropic in each block: diagonal in any axes, so frame 2 gets it as is.
        f.write("[upper]\ndiameter_m = 0.05\ndrag_coeff = 1.1\n"
                "added_mass_kg = [0.1, 0.1, 0.1, 1e-4, 1e-4, 1e-4]\n")
    desc = imported("--hydro", hydro)
    L2 = desc["arm"]["link"][1]
    got_ma = L2.get("added_mass_kg", [])
    check(L2["diameter_m"] == 0.05 and L2["drag_coeff"] == 1.1 and len(got_ma) == 6
          and max(abs(a - b) for a, b in zip(got_ma, [0.1] * 3 + [1e-4] * 3)) <= 1e-15
          and "added_mass_kg" not in desc["arm"]["link"][0]
          and desc["arm"]["link"][0]["diameter_m"] == 0.06,
          "hydrodynamics: link 2 from --hydro (with its own added mass), link 1 from its "
          "collision cylinder (radius 0.03 m)")
    with open(hydro, "w") as f:
        f.write("[upper]\nadded_mass_kg = [0.1, -0.2]\n")
    got = error_of(FIXTURE, "--hydro", hydro)
    check("added_mass_kg" in got and "6 numbers >= 0" in got,
          f"a side file's bad added_mass_kg is named ({got!r})")
    # The fixture's upper link is turned against frame 2 (rpy origin, skew axis): a diagonal
    # that is not isotropic would not be diagonal in frame 2, and is refused, naming it.
    with open(hydro, "w") as f:
        f.write("[upper]\ndiameter_m = 0.05\nadded_mass_kg = [0.1, 0.3, 0.0, 1e-4, 2e-4, 0.0]\n")
    got = error_of(FIXTURE, "--hydro", hydro)
    check("[upper] added_mass_kg" in got and "not diagonal there" in got,
          f"an added mass that frame 2 cannot hold diagonal is refused ({got!r})")
    with open(hydro, "w") as f:
        f.write("[uper]\ndiameter_m = 0.05\n")
    got = error_of(FIXTURE, "--hydro", hydro)
    check("no <link> named uper" in got, f"a side file's unknown link is named ({got!r})")


def check_cli():
    p = vehicle("--help")
    check(p.returncode == 0 and "import-urdf" in p.stdout and "Exit status" in p.stdout,
          "uvms vehicle --help: the subcommand and the exit statuses")
    p = vehicle("import-urdf", expect=2)
    check("usage: uvms vehicle import-urdf" in p.stderr, "no URDF: usage error, exit 2")
    p = vehicle("import-urdf", os.path.join(TMP, "missing.urdf"), expect=1)
    check("No such file" in p.stderr, "a missing file: exit 1, said")
    p = subprocess.run([UVMS, "vehicle", "--help"], capture_output=True, text=True)
    check(p.returncode == 0 and "import-urdf" in p.stdout,
          f"`uvms vehicle --help` through the uvms binary (exit {p.returncode})")
    p = subprocess.run([UVMS, "vehicle", "import-urdf", FIXTURE], capture_output=True, text=True)
    check(p.returncode == 0 and p.stdout.count("[[arm.link]]") == 4,
          f"`uvms vehicle import-urdf` through the uvms binary (exit {p.returncode})")


def check_sil_run():
    """The imported arm flown end to end: mounted where the paper's arm is, in a scenario of
    its own (case IV, 1.5 s), `uvms run` finishes, and the viewer's kinematics of the logged
    scene (general links and mount) reproduce the plant's truth EE at every tick."""
    from uvms_tools.log import runlog
    from uvms_tools.viz.kinematics import arm_frames, geometry_from_log
    arm = vehicle("import-urdf", FIXTURE, "--mount-xyz", "0.914", "0", "0.152").stdout
    text = ('[run]\nduration_s = 1.5\n[control]\ncase = "IV"\n' + arm +
            '\n[trajectory]\nduration_s = 1.5\ntheta_start_deg = [0.0, 30.0, -40.0, 10.0]\n'
            'theta_final_deg = [20.0, 10.0, 30.0, 60.0]\n')
    path, out = os.path.join(TMP, "urdf_arm.toml"), os.path.join(TMP, "urdf_run")
    with open(path, "w") as f:
        f.write(text)
    p = subprocess.run([UVMS, "run", path, "--out", out, "--transport", "memq"],
                       capture_output=True, text=True)
    check(p.returncode == 0, f"uvms run of the imported arm (exit {p.returncode}: "
                             f"{p.stderr.strip()[-300:]})")
    if p.returncode != 0:
        return
    log = runlog.load(os.path.join(out, "run.lcmlog"))
    tr = log["UVMS_TRUTH"]
    geom = geometry_from_log(log)
    fr = arm_frames(geom, tr["position_m"], tr["quaternion_wxyz"], tr["joint_position_rad"])
    err = np.abs(fr["origins_m"][:, -1] - tr["ee_position_m"]).max()
    moved = np.ptp(tr["joint_position_rad"][:, :4], axis=0).max()
    check(geom.num_joints == 4 and np.abs(geom.placement_rotvec_rad).max() > 0.1 and moved > 0.05
          and err < 1e-9, f"the logged scene's general links: viewer FK = plant EE at {tr.count} "
          f"ticks (max {err:.2e} m; joints moved {moved:.2f} rad)")


def steps():
    check_against_pinocchio()
    check_sil_run()
    check_errors()
    check_cli()


if __name__ == "__main__":
    sys.exit(TALLY.run(steps, TMP))
