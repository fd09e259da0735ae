# SPDX-License-Identifier: Apache-2.0
"""uvms_tools: the project's Python tools, one package (tools/pyproject.toml).

    env.py          the repository, the venv the command scripts re-execute in, the version,
                    how many runs at a time ($UVMS_JOBS)
    log/            run logs read and checked (records.py), as numpy arrays (runlog.py)
    models/         the analytic model of SPEC §9 item 8, the thruster datasheet fit
    campaign_dask/  a campaign's runs as dask.distributed tasks (tools/campaign-dask)
    vehicle/        your own vehicle: an arm from URDF (uvms vehicle, tools/uvms_vehicle.py)
    viz/            a run log as a Rerun 3D recording (tools/uvmsviz.py)
    dashboard/      one PNG page per run (tools/uvmslog.py --dashboard)
    report/         the campaign report of SPEC §9 (tools/report.py)
    uvmslog.py      the uvmslog command: log/'s listing, plots and CSV, dashboard/'s pages

Layers, bottom up. A module imports from its own subpackage and from lower layers only, never
from its own layer or above, and no import (function-level ones included) closes a cycle;
tests/tools/test_import_layers.py checks both:

    3  report, uvmslog.py
    2  viz, dashboard
    1  log, models, campaign_dask, vehicle
    0  env (standard library only)

The command scripts in tools/ (tools/uvmslog.py, tools/report.py, ...) and the console scripts
of tools/pyproject.toml only call into the package: a subpackage's cli.py is its command line,
uvmslog.py that of the one command spanning two subpackages.
"""
