# SPDX-License-Identifier: Apache-2.0
"""uvms_tools: the project's Python tools, one package (tools/pyproject.toml).

    env.py          the repository, the venv the command scripts re-execute in, the version
    log/            run logs read and checked (records.py), as numpy arrays (runlog.py)
    models/         the analytic model of SPEC §9 item 8, the thruster datasheet fit
    viz/            a run log as a Rerun 3D recording (tools/uvmsviz.py)
    dashboard/      one PNG page per run (tools/uvmslog.py --dashboard)
    report/         the campaign report of SPEC §9 (tools/report.py)
    campaign_dask/  a campaign's runs as dask.distributed tasks (tools/campaign-dask)

The command scripts in tools/ (tools/uvmslog.py, tools/report.py, ...) and the console scripts
of tools/pyproject.toml call into these; a subpackage's cli.py is its command line.
"""
