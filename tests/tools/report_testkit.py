# SPDX-License-Identifier: Apache-2.0
"""report_testkit: synthetic campaign outputs for the report's tests (the files tools/report.py
reads: plan.json, results.json, runs/<id>/summary.json)."""
import json
import os


# What ties a results.json to its plan.json (the report refuses a table of another campaign):
# the same identity and generation in both.
TABLE_ID = {"identity": "0" * 64, "generation": 0}


def write_campaign(d, name, runs, base=""):
    """A campaign output dir: runs = [(run id, overrides, results row fields)]."""
    os.makedirs(os.path.join(d, "runs"))
    plan, rows = [], []
    for rid, ovr, fields in runs:
        plan.append({"id": rid, "overrides": ovr})
        rows.append(dict({"id": rid, "status": "finished"}, **fields))
        os.makedirs(os.path.join(d, "runs", rid))
        with open(os.path.join(d, "runs", rid, "summary.json"), "w") as fh:
            json.dump({"drive": "current"}, fh)
    with open(os.path.join(d, "plan.json"), "w") as fh:
        json.dump(dict(TABLE_ID, name=name, base=base, runs=plan), fh)
    with open(os.path.join(d, "results.json"), "w") as fh:
        json.dump(dict(TABLE_ID, name=name, runs=rows), fh)
