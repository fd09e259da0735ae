#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""analytic: the simplified analytic model of SPEC §9 item 8 ([87–89]): the drag / reaction
ratio per payload and its payload and travel limits.

The command line of tools/uvms_tools/models/analytic.py (see --help).

Interpreter: see tools/uvms_tools/env.py (re-executes with REPO/.venv/bin/python when
needed).
"""
import os
import sys

if os.path.dirname(os.path.abspath(__file__)) not in sys.path:
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from uvms_tools.env import run_tool  # noqa: E402

if __name__ == "__main__":
    run_tool(__file__, "uvms_tools.models.analytic:main")
