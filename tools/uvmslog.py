#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""uvmslog: a UVMS run log (LCM event log of `uvms run`): list its channels, plot or export
fields, or draw a dashboard page per run.

The command line of tools/uvms_tools/uvmslog.py (see --help): the listing, --plot and --csv
are tools/uvms_tools/log/runlog.py, --dashboard is tools/uvms_tools/dashboard/page.py.
"""
from uvms_tools.env import run_tool  # tools/ is sys.path[0]; run_tool re-executes in the venv

if __name__ == "__main__":
    run_tool(__file__, "uvms_tools.uvmslog:main")
