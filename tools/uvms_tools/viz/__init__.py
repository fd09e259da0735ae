# SPDX-License-Identifier: Apache-2.0
"""viz: 3D replay of a UVMS run log as a Rerun recording (tools/uvmsviz.py).

kinematics.py: forward kinematics of the arm from logged states (numpy, vectorized; also used
by the report); scene.py: everything a log gives to draw (geometry, hull, obstacles, thrusters,
per-tick truth); rerun_export.py: the recording (entity paths in one table); cli.py: the
command line.
"""
