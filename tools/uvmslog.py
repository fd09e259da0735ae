#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""uvmslog: a UVMS run log (LCM event log of `uvms run`): list its channels, plot or export
fields, or draw a dashboard page per run.

The command line of tools/uvms_tools/uvmslog.py (see --help): the listing, --plot and --csv
are tools/uvms_tools/log/runlog.py, --dashboard is tools/uvms_tools/dashboard/page.py.

Interpreter: see tools/uvms_tools/env.py (re-executes with REPO/.venv/bin/python when
needed).
"""
import os
import sys

if os.path.dirname(os.path.abspath(__file__)) not in sys.path:
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from uvms_tools.env import run_tool  # noqa: E402

if __name__ == "__main__":
    run_tool(__file__, "uvms_tools.uvmslog:main")
