# SPDX-License-Identifier: Apache-2.0
"""logs: views of a decoded run log (tools/uvmslog.py)."""
import numpy as np


def per_tick(log):
    """Telemetry (tick ≥ 0) and truth rows at the same ticks."""
    tm = log["UVMS_TELEMETRY"]
    tm = tm.select(tm["tick"] >= 0)
    tr = log["UVMS_TRUTH"]
    ticks = np.intersect1d(tm["tick"], tr["tick"])
    return tm.at_ticks(ticks), tr.at_ticks(ticks)


def has(log, *channels):
    """The log exists and holds every channel."""
    return log is not None and all(c in log for c in channels)


def scalar(cfg, field):
    """A scalar field of the logged configuration message (stored as a one-row array)."""
    return float(cfg[field][0])


def thruster_value(cfg, field, j=0):
    """Thruster j's entry of a per-thruster field of the logged configuration (propeller,
    motor and loop parameters, thrust limits: one value per thruster)."""
    return float(np.ravel(cfg[field][0])[j])
