#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""uvms_vehicle: `uvms vehicle` (describe your own vehicle: import-urdf). The command line of
tools/uvms_tools/vehicle/cli.py; `uvms vehicle ...` runs this script."""
from uvms_tools.env import run_tool  # tools/ is sys.path[0]; run_tool re-executes in the venv

if __name__ == "__main__":
    run_tool(__file__, "uvms_tools.vehicle.cli:main")
