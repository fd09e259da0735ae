# SPDX-License-Identifier: Apache-2.0
"""campaign_dask: the modules of tools/campaign-dask (a campaign's runs as dask tasks).

In the order data flows: outdir.py (the DIR lock, the plan and the merge by `uvms campaign`,
the client's writes of a run's files), worker.py (one run on a dask worker: standard library
only, shipped to the workers by value), engine.py (the cluster, one task per run, retries of
lost tasks, progress). The command line is tools/campaign-dask.
"""
