# SPDX-License-Identifier: Apache-2.0
"""scene: everything a run log gives to draw the run, read in one place.

Why: the viewer (rerun_export.py) and the report need the same facts (geometry, hull,
obstacles, thrusters, per-tick truth and telemetry, the end of the run) and must agree on where
each comes from. Sources, in order of preference:
  - UVMS_SCENE (scene_t, lcmtypes/scene_t.lcm): the plant's true geometry, hull box, thrusters
    and contact monitor (obstacles, clearance); one message at the start of the run;
  - UVMS_CONFIG (controller_config_t): the controller's arm and thruster geometry, for logs
    written before scene_t. Then there is no hull and no obstacle, which `Scene.notes` says.
Per-tick series: UVMS_TRUTH (ticks 0..n, the last one after the final tick), UVMS_TELEMETRY
(ticks 0..n-1; the configuration acknowledgement, tick -1, is dropped), UVMS_STATUS (start
and end of the run). Frames (docs/MODEL.md §2): vehicle frame for the hull and thrusters,
inertial for the obstacles and every truth vector.
"""
from dataclasses import dataclass, field

import numpy as np

from uvms_tools.log import runlog

from .kinematics import CONFIG_CHANNEL, SCENE_CHANNEL, ArmGeometry, geometry_channel

TRUTH_CHANNEL = "UVMS_TRUTH"
TELEMETRY_CHANNEL = "UVMS_TELEMETRY"
STATUS_CHANNEL = "UVMS_STATUS"
# The contact monitor's clearance when the log does not say (scenario default, SPEC §5) [m].
DEFAULT_CLEARANCE_M = 0.0


@dataclass(frozen=True)
class Obstacle:
    """A vertical cylinder of the contact monitor (inertial frame) [m]."""
    name: str
    base_center_m: np.ndarray  # (3,) center of the bottom disc
    height_m: float
    radius_m: float


@dataclass(frozen=True)
class Thrusters:
    """Thruster j in row j-1 (j = 1..n), vehicle frame: position a_j [m], unit direction u_j."""
    position_m: np.ndarray   # (n, 3)
    direction: np.ndarray    # (n, 3)
    source: str              # channel they come from


@dataclass(frozen=True)
class RunEnd:
    """The end-of-run record (run_status_t, lcmtypes/run_status_t.lcm)."""
    state: str     # RUNNING, FINISHED or FAILED (the type's constant names)
    code: int      # run_status_t code (OK, CONTACT, ...)
    reason: str
    tick: int
    utime_us: int  # simulated time of the record [µs]
    failed: bool
    contact: bool  # ended by the contact monitor

    def text(self):
        """'FAILED at tick 35 (code 3): reason' (one line)."""
        return (f"{self.state} at tick {self.tick} (code {self.code})"
                + (f": {self.reason}" if self.reason else ""))


@dataclass
class Scene:
    """What to draw. truth/telemetry are uvmslog Channels (first axis = message)."""
    source: str                   # UVMS_SCENE or UVMS_CONFIG
    geometry: ArmGeometry
    thrusters: Thrusters
    hull_size_m: np.ndarray | None    # (3,) box edges along the vehicle axes, None without scene
    hull_center_m: np.ndarray | None  # (3,) box center from the CoM, vehicle frame
    obstacles: list
    contact_enabled: bool | None  # None: unknown (no scene)
    clearance_m: float
    truth: runlog.Channel
    telemetry: runlog.Channel
    end: RunEnd | None
    notes: list = field(default_factory=list)  # one-line remarks for stderr


def _first(channel, name, width=None):
    """Message 0's value of a field as a float array (the first `width` rows if given)."""
    value = np.asarray(list(np.atleast_1d(channel[name][0])), dtype=float)
    return value if width is None else value[:width]


def thrusters_of(channel):
    """Thrusters from a UVMS_SCENE or UVMS_CONFIG channel (message 0, first num_thrusters)."""
    n = int(channel["num_thrusters"][0])
    pos = np.asarray(channel["thruster_position_m"][0], dtype=float).reshape(-1, 3)[:n]
    direction = np.asarray(channel["thruster_direction"][0], dtype=float).reshape(-1, 3)[:n]
    return Thrusters(pos, direction, channel.name)


def obstacles_of(scene):
    """Obstacles of a UVMS_SCENE channel (message 0), in the message's order."""
    n = int(scene["num_obstacles"][0])
    if n == 0:
        return []
    names = [str(s) for s in np.atleast_1d(scene["obstacle_name"][0])]
    centers = np.asarray(list(scene["obstacle_base_center_m"][0]), dtype=float).reshape(-1, 3)
    heights = _first(scene, "obstacle_height_m")
    radii = _first(scene, "obstacle_radius_m")
    return [Obstacle(names[k], centers[k], float(heights[k]), float(radii[k]))
            for k in range(n)]


def run_end(log):
    """The last UVMS_STATUS record, or None when the log has none."""
    st = log.get(STATUS_CHANNEL)
    if st is None or st.count == 0:
        return None
    runlog.lcm_types()  # puts the generated package on sys.path
    from uvms.run_status_t import run_status_t  # noqa: WPS433 (generated at build time)
    state, code = int(st["state"][-1]), int(st["code"][-1])
    names = {run_status_t.RUNNING: "RUNNING", run_status_t.FINISHED: "FINISHED",
             run_status_t.FAILED: "FAILED"}
    return RunEnd(names.get(state, f"state {state}"), code, str(st["reason"][-1]),
                  int(st["tick"][-1]), int(st["utime"][-1]),
                  failed=state == run_status_t.FAILED, contact=code == run_status_t.CONTACT)


def require(log, name):
    """The channel `name` with at least one message, else runlog.LogError."""
    ch = log.get(name)
    if ch is None and log.undecodable(name):
        raise log.undecodable(name)
    if ch is None or ch.count == 0:
        raise runlog.LogError(f"{log.path}: no {name} messages (has: "
                               f"{', '.join(sorted(log)) or 'none'})")
    return ch


def _geometry_part(log):
    """(source, ArmGeometry, Thrusters, hull size, hull center, obstacles, contact, clearance,
    notes) from the channel kinematics.geometry_channel chooses (UVMS_SCENE, else
    UVMS_CONFIG)."""
    channel = geometry_channel(log)
    geom, thrusters = ArmGeometry.from_channel(channel), thrusters_of(channel)
    if channel.name == SCENE_CHANNEL:
        return (SCENE_CHANNEL, geom, thrusters, _first(channel, "hull_size_m"),
                _first(channel, "hull_center_m"), obstacles_of(channel),
                bool(channel["contact_enabled"][0]), float(channel["clearance_m"][0]), [])
    note = (f"no {SCENE_CHANNEL} in the log (written before scene_t): arm and thrusters from "
            f"{CONFIG_CHANNEL} (the controller's model); no hull and no obstacles drawn")
    return (CONFIG_CHANNEL, geom, thrusters, None, None, [], None, DEFAULT_CLEARANCE_M, [note])


def read_scene(log):
    """Scene of a runlog.Log; runlog.LogError when truth or telemetry is missing,
    kinematics.GeometryError when the geometry is (no UVMS_SCENE nor UVMS_CONFIG)."""
    truth = require(log, TRUTH_CHANNEL)
    telemetry = require(log, TELEMETRY_CHANNEL)
    telemetry = telemetry.select(telemetry["tick"] >= 0)
    (source, geom, thr, hull_size, hull_center, obstacles, contact, clearance,
     notes) = _geometry_part(log)
    return Scene(source=source, geometry=geom, thrusters=thr, hull_size_m=hull_size,
                 hull_center_m=hull_center, obstacles=obstacles, contact_enabled=contact,
                 clearance_m=clearance, truth=truth, telemetry=telemetry, end=run_end(log),
                 notes=notes)


def subsample(scene, every):
    """The scene with every `every`-th truth sample (0, K, 2K, ...; ceil(n/K) of n) and the
    telemetry of those ticks only."""
    if every <= 1:
        return scene
    truth = scene.truth.select(np.arange(0, scene.truth.count, every))
    telemetry = scene.telemetry.select(np.isin(scene.telemetry["tick"], truth["tick"]))
    return Scene(**{**scene.__dict__, "truth": truth, "telemetry": telemetry})
