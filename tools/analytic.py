#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""analytic: the simplified analytic model of SPEC §9 item 8 ([87–89]): the drag / reaction
ratio per payload and its payload and travel limits.

The command line of tools/uvms_tools/models/analytic.py (see --help).
"""
from uvms_tools.env import run_tool  # tools/ is sys.path[0]; run_tool re-executes in the venv

if __name__ == "__main__":
    run_tool(__file__, "uvms_tools.models.analytic:main")
