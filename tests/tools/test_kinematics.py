# SPDX-License-Identifier: Apache-2.0
"""tools/uvms_tools/viz/kinematics.py (numpy forward kinematics, docs/MODEL.md §2, SPEC [3]) against
three independent references:
  (a) the plant's logged truth: on a fresh 1.5 s run, FK of the truth position, quaternion and
      joint angles gives the truth ee_position_m (computed by the C++ plant with Eigen) at
      every tick;
  (b) `uvms model` (the firmware library): ee_position_m and base_point_m at random states, for
      the run's arm and for it made general (random link placements, a turned mount);
  (c) closed forms: one link with a = 1, all else zero, theta = pi/2 -> EE = base + (0, 1, 0);
      the mount turned, a general link's placement.
And the geometry's source: geometry_from_log takes the log's UVMS_SCENE fields when there is
one, else UVMS_CONFIG's (compared with the raw message fields), else GeometryError; the
viewer's scene (uvms_tools.viz.scene.read_scene) gets the same geometry.

Usage: test_kinematics.py UVMS_EXE SOURCE_DIR
"""
import dataclasses
import json
import os
import subprocess
import sys

import numpy as np

UVMS, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tools"))
from uvms_tools.log import runlog  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checklist  # noqa: E402
from uvms_tools.viz.kinematics import (ArmGeometry, GeometryError, arm_frames,  # noqa: E402
                                  geometry_from_log, quat_to_rot)
from uvms_tools.viz.scene import read_scene  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

TMP = scratch_dir("uvms-kinematics-")  # removed at exit (tests/support/scratch.py)
SCENARIO = "sil/scenarios/paper/case_VII_stagnant.toml"
# Same formulas in double on both sides, different operation order: rounding only (the arm
# spans ~1 m, a few hundred ulps at most).
TOL_TRUTH_M = 1e-9
TOL_MODEL_M = 1e-12
TOL_CLOSED_M = 1e-15
SEED = 19
N_STATES = 3

TALLY = checklist.Tally()
check = TALLY.check


def fresh_log():
    out = os.path.join(TMP, "run")
    p = subprocess.run([UVMS, "run", SCENARIO, "--set", "run.duration_s=1.5",
                        "--set", "trajectory.duration_s=1.5", "--out", out],
                       cwd=SRC, capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"uvms run failed ({p.returncode}): {p.stderr.strip()[-300:]}")
    return runlog.load(os.path.join(out, "run.lcmlog"))


def check_truth(log):
    """(a) FK of every truth sample reproduces the plant's ee_position_m."""
    tr = log["UVMS_TRUTH"]
    geom = geometry_from_log(log)
    fr = arm_frames(geom, tr["position_m"], tr["quaternion_wxyz"], tr["joint_position_rad"])
    err = np.linalg.norm(fr["origins_m"][:, -1] - tr["ee_position_m"], axis=1)
    check(fr["origins_m"].shape == (tr.count, geom.num_joints + 1, 3)
          and fr["rot"].shape == (tr.count, geom.num_joints + 1, 3, 3)
          and fr["payload_m"].shape == (tr.count, 3), "arm_frames shapes (n, N+1, 3), "
          "(n, N+1, 3, 3), (n, 3)")
    moved = np.ptp(tr["joint_position_rad"], axis=0).max()
    check(moved > 1e-3, f"the arm moves during the run (max joint range {moved:.3g} rad)")
    check(err.max() < TOL_TRUTH_M, f"FK vs truth ee_position_m at {tr.count} ticks: max "
          f"{err.max():.3g} m < {TOL_TRUTH_M:g} m")
    rot = quat_to_rot(tr["quaternion_wxyz"])
    orth = np.abs(rot @ rot.transpose(0, 2, 1) - np.eye(3)).max()
    check(orth < 1e-14 and np.allclose(np.linalg.det(rot), 1.0), "quat_to_rot is a rotation")


def same_as_message(geom, channel):
    """geom holds message 0's DH parameters and offsets of a UVMS_SCENE/UVMS_CONFIG channel."""
    n = int(channel["num_joints"][0])
    pairs = [(geom.alpha_rad, channel["link_alpha_rad"][0][:n]),
             (geom.a_m, channel["link_a_m"][0][:n]), (geom.d_m, channel["link_d_m"][0][:n]),
             (geom.diameter_m, channel["link_diameter_m"][0][:n]),
             (geom.base_offset_m, channel["base_offset_m"][0]),
             (geom.payload_offset_m, channel["payload_offset_m"][0])]
    return geom.num_joints == n and all(np.array_equal(g, np.asarray(m, dtype=float))
                                        for g, m in pairs)


def without(log, channel):
    """A copy of a runlog.Log without one channel (as a log written without it)."""
    out = runlog.Log(log.path)
    out.update({k: v for k, v in log.items() if k != channel})
    return out


def with_marked_scene(log):
    """A copy of the log whose UVMS_SCENE link lengths a_i are 1 m longer: a scene geometry
    that differs from UVMS_CONFIG's whatever the run."""
    out = without(log, "UVMS_SCENE")
    sc = log["UVMS_SCENE"]
    marked = runlog.Channel(sc.name, sc.type_name)
    marked.update(sc)
    marked["link_a_m"] = np.asarray(sc["link_a_m"], dtype=float) + 1.0
    out["UVMS_SCENE"] = marked
    return out


def check_source(log):
    """UVMS_SCENE first, else UVMS_CONFIG, else GeometryError; read_scene agrees."""
    check("UVMS_SCENE" in log, "the run's log has a UVMS_SCENE message")
    marked = with_marked_scene(log)
    geom, scene = geometry_from_log(marked), read_scene(marked)
    check(same_as_message(geom, marked["UVMS_SCENE"])
          and not same_as_message(geom, log["UVMS_CONFIG"]) and scene.source == "UVMS_SCENE"
          and same_as_message(scene.geometry, marked["UVMS_SCENE"]),
          "geometry_from_log and read_scene: the UVMS_SCENE message's geometry (a scene "
          "that differs from UVMS_CONFIG)")
    old = without(log, "UVMS_SCENE")
    scene = read_scene(old)
    check(same_as_message(geometry_from_log(old), log["UVMS_CONFIG"])
          and scene.source == "UVMS_CONFIG" and same_as_message(scene.geometry,
                                                                log["UVMS_CONFIG"]),
          "without UVMS_SCENE: geometry_from_log and read_scene take UVMS_CONFIG's")
    try:
        geometry_from_log(without(old, "UVMS_CONFIG"))
        raised = False
    except GeometryError:
        raised = True
    check(raised, "without UVMS_SCENE and UVMS_CONFIG: GeometryError")


def model_config(geom, path):
    """`uvms model --config` file with a geometry (the log's: the same links as the run),
    general placements and the mount's rotation included."""
    zeros = np.zeros((geom.num_joints, 3))
    place_t = zeros if geom.placement_m is None else geom.placement_m
    place_r = zeros if geom.placement_rotvec_rad is None else geom.placement_rotvec_rad
    base_r = np.zeros(3) if geom.base_rotvec_rad is None else geom.base_rotvec_rad
    cfg = {"vehicle": {"base_offset_m": geom.base_offset_m.tolist(),
                       "base_rotvec_rad": np.asarray(base_r).tolist()},
           "payload_offset_m": geom.payload_offset_m.tolist(),
           "links": [{"alpha_rad": float(al), "a_m": float(a), "d_m": float(d),
                      "placement_m": np.asarray(t).tolist(),
                      "placement_rotvec_rad": np.asarray(r).tolist()}
                     for al, a, d, t, r in zip(geom.alpha_rad, geom.a_m, geom.d_m, place_t,
                                               place_r)]}
    with open(path, "w") as fh:
        json.dump(cfg, fh)


def model_input(rng, n_joints):
    q = rng.normal(size=4)
    zero3 = [0.0, 0.0, 0.0]
    return {"vehicle": {"position_m": rng.uniform(-5, 5, 3).tolist(),
                        "quaternion_wxyz": (q * rng.uniform(0.5, 2.0)).tolist(),
                        "velocity_m_s": zero3, "angular_velocity_rad_s": zero3,
                        "acceleration_m_s2": zero3, "angular_acceleration_rad_s2": zero3},
            "joints": {"position_rad": rng.uniform(-np.pi, np.pi, n_joints).tolist(),
                       "velocity_rad_s": [0.0] * n_joints,
                       "acceleration_rad_s2": [0.0] * n_joints},
            "density_kg_m3": 1025.0, "flow_m_s": zero3, "gravity_m_s2": [0.0, 0.0, -9.81],
            "payload_kg": 0.0, "angle_of_attack": True}


def general(geom, rng):
    """The geometry with a random fixed placement after every link's DH transform and a
    turned mount (docs/MODEL.md §2 "General links")."""
    n = geom.num_joints
    return dataclasses.replace(geom, placement_m=rng.uniform(-0.1, 0.1, (n, 3)),
                               placement_rotvec_rad=rng.uniform(-1.5, 1.5, (n, 3)),
                               base_rotvec_rad=rng.uniform(-1.5, 1.5, 3))


def check_model(log, make_general=False):
    """(b) ee_position_m and base_point_m against `uvms model` at random states (with
    make_general: the log's arm made general, the same placements given to both)."""
    geom = geometry_from_log(log)
    if make_general:
        geom = general(geom, np.random.default_rng(SEED + 1))
    cfg = os.path.join(TMP, "model.json")
    model_config(geom, cfg)
    rng = np.random.default_rng(SEED)
    for k in range(N_STATES):
        inp = model_input(rng, geom.num_joints)
        p = subprocess.run([UVMS, "model", "--config", cfg], input=json.dumps(inp),
                           capture_output=True, text=True)
        if p.returncode != 0:
            check(False, f"uvms model state {k}: exit {p.returncode}: {p.stderr.strip()}")
            continue
        out = json.loads(p.stdout)
        v, j = inp["vehicle"], inp["joints"]
        fr = arm_frames(geom, [v["position_m"]], [v["quaternion_wxyz"]], [j["position_rad"]])
        e_ee = np.abs(fr["origins_m"][0, -1] - out["ee_position_m"]).max()
        e_base = np.abs(fr["origins_m"][0, 0] - out["base_point_m"]).max()
        check(e_ee < TOL_MODEL_M and e_base < TOL_MODEL_M, f"state {k}"
              f"{' (general links, turned mount)' if make_general else ''}: vs uvms model: EE "
              f"{e_ee:.3g} m, base point {e_base:.3g} m < {TOL_MODEL_M:g} m")


def check_closed_form():
    """(c) one link a = 1 m, theta = pi/2: EE = base + (0, 1, 0); payload offset along x_1."""
    geom = ArmGeometry(alpha_rad=np.zeros(1), a_m=np.ones(1), d_m=np.zeros(1),
                       diameter_m=np.zeros(1), base_offset_m=np.array([0.5, 0.0, 0.0]),
                       payload_offset_m=np.array([0.25, 0.0, 0.0]), num_joints=1)
    r0 = np.array([[1.0, 2.0, 3.0]])
    fr = arm_frames(geom, r0, [[1.0, 0.0, 0.0, 0.0]], [[np.pi / 2]])
    base = r0[0] + [0.5, 0.0, 0.0]
    check(np.abs(fr["origins_m"][0, 0] - base).max() < TOL_CLOSED_M, "base = r0 + s0")
    check(np.abs(fr["origins_m"][0, 1] - (base + [0, 1, 0])).max() < TOL_CLOSED_M,
          f"EE = base + (0, 1, 0) ({fr['origins_m'][0, 1] - base})")
    check(np.abs(fr["payload_m"][0] - (base + [0, 1.25, 0])).max() < TOL_CLOSED_M,
          "payload = EE + R_1 (0.25, 0, 0) = base + (0, 1.25, 0)")
    # Vehicle turned by pi/2 about z (q = (cos pi/4, 0, 0, sin pi/4)): s0 turns to +y.
    c = np.cos(np.pi / 4)
    fr = arm_frames(geom, r0, [[c, 0.0, 0.0, c]], [[0.0]])
    check(np.abs(fr["origins_m"][0, 0] - (r0[0] + [0, 0.5, 0])).max() < 1e-15,
          "vehicle yawed by pi/2: base = r0 + (0, 0.5, 0)")
    # The mount turned by pi/2 about y (rotvec (0, pi/2, 0)): the base's x axis is the
    # vehicle's -z, so at theta = 0 the link points down: EE = base + (0, 0, -1).
    mounted = dataclasses.replace(geom, base_rotvec_rad=np.array([0.0, np.pi / 2, 0.0]))
    fr = arm_frames(mounted, r0, [[1.0, 0.0, 0.0, 0.0]], [[0.0]])
    check(np.abs(fr["origins_m"][0, 1] - (base + [0, 0, -1])).max() < 1e-15,
          f"mount turned about y by pi/2: EE = base + (0, 0, -1) ({fr['origins_m'][0, 1] - base})")
    # A general link: DH a = 1, then t = (0, 0.5, 0) and rho = (0, 0, pi/2): at theta = 0 the
    # origin is base + (1, 0.5, 0) and the frame is turned by pi/2 about z.
    placed = dataclasses.replace(geom, placement_m=np.array([[0.0, 0.5, 0.0]]),
                                 placement_rotvec_rad=np.array([[0.0, 0.0, np.pi / 2]]))
    fr = arm_frames(placed, r0, [[1.0, 0.0, 0.0, 0.0]], [[0.0]])
    check(np.abs(fr["origins_m"][0, 1] - (base + [1, 0.5, 0])).max() < 1e-15
          and np.abs(fr["rot"][0, 1] - [[0, -1, 0], [1, 0, 0], [0, 0, 1]]).max() < 1e-15,
          "general link: origin base + (1, 0.5, 0), frame turned by pi/2 about z")


def steps():
    log = fresh_log()
    check_truth(log)
    check_source(log)
    check_model(log)
    check_model(log, make_general=True)
    check_closed_form()


def main():
    return TALLY.run(steps, TMP)


if __name__ == "__main__":
    sys.exit(main())
