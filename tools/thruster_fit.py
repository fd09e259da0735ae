#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""thruster_fit: fit SPEC §5's propeller and motor model to a published bollard datasheet
(the "t200" motor set of sil/scenario/motor_sets.cpp).

The command line of tools/uvms_tools/models/thruster_fit.py (see --help).
"""
from uvms_tools.env import run_tool  # tools/ is sys.path[0]; run_tool re-executes in the venv

if __name__ == "__main__":
    run_tool(__file__, "uvms_tools.models.thruster_fit:main")
