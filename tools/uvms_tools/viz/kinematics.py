# SPDX-License-Identifier: Apache-2.0
"""kinematics: forward kinematics of the vehicle-manipulator, numpy, vectorized over samples.

Why here: the viewer (tools/uvmsviz.py) and the report draw the arm from logged states (truth
position, attitude and joint angles); they need the frames of every link, which the logs do not
carry. This is the firmware's forward kinematics (firmware/src/kinematics.c, uvms_arm_fk)
written again in numpy, so that it can be checked against the plant's logged EE position and
against `uvms model` (tests/tools/test_kinematics.py).

Frames and conventions (docs/MODEL.md §2; SPEC [1]–[3]):
    R0 = quat_to_rot(q)                  vehicle -> inertial, q = (w, x, y, z), normalised
    p_0 = r0 + R0 s0                     arm base point; frame B = DH frame 0 has the axes
                                         R0 Rot(rho_B) (R0's unless the mount turns them)
    A_i = R_{i-1} Rz(theta_i) Rx(alpha_i)                     (standard, distal DH)
    p_i = p_{i-1} + a_i x(A_i) + d_i z_{i-1} + A_i t_i        (= p_{i-1} + R_i l_i, [3])
    R_i = A_i Rot(rho_i)                 (t_i = rho_i = 0 for a standard DH link)
    EE = p_N;  payload point = p_N + R_N payload_offset
with x_i, z_i the first and third columns of R_i. Inertial coordinates, metres, radians.

    from uvms_tools.viz.kinematics import ArmGeometry, arm_frames, geometry_from_log, quat_to_rot
    geom = geometry_from_log(runlog.load("run.lcmlog"))
    fr = arm_frames(geom, truth["position_m"], truth["quaternion_wxyz"],
                    truth["joint_position_rad"])
    fr["origins_m"][:, -1]          # (n, 3) EE position [m]
"""
from dataclasses import dataclass

import numpy as np

SCENE_CHANNEL = "UVMS_SCENE"    # scene_t: the plant's true geometry (preferred)
CONFIG_CHANNEL = "UVMS_CONFIG"  # controller_config_t: the controller's geometry (fallback)


class GeometryError(ValueError):
    """The log carries no geometry (neither UVMS_SCENE nor UVMS_CONFIG) or a malformed one."""


@dataclass(frozen=True)
class ArmGeometry:
    """Arm geometry, link i in slot i-1 (arrays of length num_joints).

    alpha_rad, a_m, d_m: standard DH twist [rad], length [m], offset [m] (SPEC §3.1);
    diameter_m: link cylinder diameter d_L [m]; base_offset_m: s0, vehicle CoM -> arm base
    point, vehicle frame (3,) [m]; payload_offset_m: EE -> payload point, frame N (3,) [m];
    payload_kg: point payload [kg] (0 when the source has none); placement_m,
    placement_rotvec_rad (N, 3): a general link's fixed translation and rotation after its DH
    transform [m], [rad]; base_rotvec_rad (3,): the mount's rotation of the base axes [rad].
    """
    alpha_rad: np.ndarray
    a_m: np.ndarray
    d_m: np.ndarray
    diameter_m: np.ndarray
    base_offset_m: np.ndarray
    payload_offset_m: np.ndarray
    num_joints: int
    payload_kg: float = 0.0
    placement_m: np.ndarray = None
    placement_rotvec_rad: np.ndarray = None
    base_rotvec_rad: np.ndarray = None

    @classmethod
    def from_channel(cls, channel):
        """From message 0 of a UVMS_SCENE (scene_t, the plant's truth) or UVMS_CONFIG
        (controller_config_t, the controller's model) channel (runlog.Channel)."""
        name = channel.name
        try:
            n = int(channel["num_joints"][0])
            if not 1 <= n <= len(channel["link_alpha_rad"][0]):
                raise GeometryError(f"{name}: num_joints = {n} out of range")
            return cls(
                alpha_rad=np.array(channel["link_alpha_rad"][0][:n], dtype=float),
                a_m=np.array(channel["link_a_m"][0][:n], dtype=float),
                d_m=np.array(channel["link_d_m"][0][:n], dtype=float),
                diameter_m=np.array(channel["link_diameter_m"][0][:n], dtype=float),
                base_offset_m=np.array(channel["base_offset_m"][0], dtype=float),
                payload_offset_m=np.array(channel["payload_offset_m"][0], dtype=float),
                num_joints=n,
                payload_kg=float(channel["payload_kg"][0]) if "payload_kg" in channel else 0.0,
                placement_m=np.array(channel["link_placement_m"][0][:n], dtype=float),
                placement_rotvec_rad=np.array(channel["link_placement_rotvec_rad"][0][:n],
                                              dtype=float),
                base_rotvec_rad=np.array(channel["base_rotvec_rad"][0], dtype=float))
        except (KeyError, IndexError) as e:
            raise GeometryError(f"{name}: no arm geometry in the message ({e})") from e


def geometry_channel(log):
    """The channel a runlog.Log's geometry comes from: UVMS_SCENE when it has a message (the
    plant's truth), else UVMS_CONFIG (logs written before scene_t). The one place of this
    choice (uvms_tools.viz.scene.read_scene, hence the viewer and the report, uses it).
    GeometryError when neither has a message."""
    for name in (SCENE_CHANNEL, CONFIG_CHANNEL):
        channel = log.get(name)
        if channel is not None and channel.count:
            return channel
    raise GeometryError(f"no {SCENE_CHANNEL} or {CONFIG_CHANNEL} message: no arm geometry")


def geometry_from_log(log):
    """ArmGeometry of a runlog.Log, from geometry_channel(log)."""
    return ArmGeometry.from_channel(geometry_channel(log))


def quat_to_rot(q_wxyz):
    """Rotation matrices of unit quaternions, vehicle -> inertial (docs/MODEL.md §2).

    q_wxyz: (n, 4) scalar first, normalised here (norm must be > 0). Returns (n, 3, 3).
    """
    q = np.asarray(q_wxyz, dtype=float)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    rows = [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def rotvec_to_rot(rotvec_rad):
    """Rot(rho) of one rotation vector rho = axis * angle (3,) [rad] -> (3, 3) (Rodrigues);
    the identity for rho = 0."""
    rho = np.asarray(rotvec_rad, dtype=float)
    phi = float(np.linalg.norm(rho))
    if phi == 0.0:
        return np.eye(3)
    k = rho / phi
    K = np.array([[0.0, -k[2], k[1]], [k[2], 0.0, -k[0]], [-k[1], k[0], 0.0]])
    return np.eye(3) + np.sin(phi) * K + (1.0 - np.cos(phi)) * (K @ K)


def _zeros_if_none(x, shape):
    return np.zeros(shape) if x is None else np.asarray(x, dtype=float)


def dh_rotation(theta_rad, alpha_rad):
    """A_i = Rz(theta) Rx(alpha), the rotation part of a standard DH step: theta (n,),
    alpha scalar [rad] -> (n, 3, 3)."""
    ct, st = np.cos(theta_rad), np.sin(theta_rad)
    ca, sa = np.cos(alpha_rad), np.sin(alpha_rad)
    zero, one = np.zeros_like(ct), np.ones_like(ct)
    rows = [[ct, -st * ca, st * sa], [st, ct * ca, -ct * sa], [zero, sa * one, ca * one]]
    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)


def arm_frames(geom, r0_m, q_wxyz, theta_rad):
    """Frames of the arm at n samples (docs/MODEL.md §2, SPEC [3], firmware uvms_arm_fk).

    geom: ArmGeometry (N joints); r0_m (n, 3) vehicle CoM [m]; q_wxyz (n, 4) attitude
    vehicle -> inertial (normalised here); theta_rad (n, >= N) joint angles [rad] (the first
    N columns are used). Returns a dict:
        origins_m (n, N+1, 3): p_0 (base point r0 + R0 s0) .. p_N (EE), inertial [m]
        rot       (n, N+1, 3, 3): R_0 (frame B) .. R_N, frame i -> inertial
        payload_m (n, 3): payload point p_N + R_N payload_offset, inertial [m]
    """
    r0 = np.atleast_2d(np.asarray(r0_m, dtype=float))
    theta = np.atleast_2d(np.asarray(theta_rad, dtype=float))
    n_j = geom.num_joints
    if theta.shape[1] < n_j:
        raise GeometryError(f"{theta.shape[1]} joint angles for {n_j} joints")
    R0 = quat_to_rot(np.atleast_2d(q_wxyz))
    origins = [r0 + R0 @ geom.base_offset_m]
    rot = [R0 @ rotvec_to_rot(_zeros_if_none(geom.base_rotvec_rad, 3))]
    place_t = _zeros_if_none(geom.placement_m, (n_j, 3))
    place_r = _zeros_if_none(geom.placement_rotvec_rad, (n_j, 3))
    for i in range(n_j):
        r_prev = rot[-1]
        a_i = r_prev @ dh_rotation(theta[:, i], geom.alpha_rad[i])
        origins.append(origins[-1] + geom.a_m[i] * a_i[:, :, 0] + geom.d_m[i] * r_prev[:, :, 2]
                       + a_i @ place_t[i])
        rot.append(a_i @ rotvec_to_rot(place_r[i]))
    payload = origins[-1] + rot[-1] @ geom.payload_offset_m
    return {"origins_m": np.stack(origins, axis=1), "rot": np.stack(rot, axis=1),
            "payload_m": payload}
