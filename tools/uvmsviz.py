#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""uvmsviz: a UVMS run log as a Rerun recording, a 3D replay with its time series.

    tools/uvmsviz.py RUN_DIR_OR_LOG [--out FILE.rrd] [--every K] [--name NAME]

Reads RUN_DIR/run.lcmlog (or the given log) and writes a .rrd file (default: the log's name
with .rrd, beside it: RUN_DIR/run.rrd) on the simulated-time timeline `sim_time`: vehicle and
hull, arm links (forward kinematics of the truth state), payload, thrust and flow arrows,
obstacles, contacts, EE and barycenter paths, and time series (thrusts, motor voltages and
currents, joints, EE and attitude errors, energies, clearance).
Open it with `.venv/bin/rerun FILE.rrd`.

The package tools/uvms_tools/viz/ holds the parts: kinematics.py (forward kinematics,
docs/MODEL.md §2), scene.py (what the log gives to draw), rerun_export.py (the recording; its
entity paths in one table), cli.py (this command line).

The generated LCM types are found as tools/uvmslog.py describes.
"""
from uvms_tools.env import run_tool  # tools/ is sys.path[0]; run_tool re-executes in the venv

if __name__ == "__main__":
    run_tool(__file__, "uvms_tools.viz.cli:main")
