# SPDX-License-Identifier: Apache-2.0
"""cli: `tools/report.py CAMPAIGNS_ROOT [--out DIR] [--uvms PATH | --schema FILE]`."""
import argparse
import os
import sys
import time

from uvms_tools.log import runlog
from uvms_tools.env import UVMS_REL, add_version_option, default_jobs, default_uvms

from . import document, html
from .context import Report
from .load import regen, schema as schema_mod
from .load.runs import TableError



def parse_args(argv):
    ap = argparse.ArgumentParser(
        description="Write report.md, report.html (self-contained) and figures/*.png from the "
                    "paper campaigns (docs/MODEL.md "
                    "§9) under CAMPAIGNS_ROOT. Every default of a setting the runs do not "
                    "override comes from the configuration schema of the build "
                    "(`uvms scenario schema`).")
    add_version_option(ap, "report")
    ap.add_argument("root", metavar="CAMPAIGNS_ROOT",
                    help="directory holding the campaign outputs (e.g. out/paper)")
    ap.add_argument("--out", help="output directory (default: CAMPAIGNS_ROOT)")
    ap.add_argument("--uvms", metavar="PATH",
                    help=f"the uvms binary whose `scenario schema` gives the configuration "
                         f"schema, and which makes again a run log the report reads that its "
                         f"campaign did not keep (uvms campaign --logs; $UVMS_JOBS at a time, "
                         f"unset: one per core; default: $UVMS, else {UVMS_REL} in the "
                         f"repository)")
    ap.add_argument("--schema", metavar="FILE",
                    help="read the schema from FILE (saved output of `uvms scenario schema`) "
                         "instead of running --uvms")
    a = ap.parse_args(argv)
    a.uvms = a.uvms or default_uvms()
    try:
        a.jobs = default_jobs()
    except ValueError as e:
        ap.error(str(e))
    return a


def main(argv=None):
    a = parse_args(argv)
    if not os.path.isdir(a.root):
        print(f"report: error: {a.root}: not a directory", file=sys.stderr)
        return 1
    out = a.out or a.root
    regen.set_uvms(a.uvms)
    regen.set_jobs(a.jobs)
    t0 = time.time()
    try:
        schema = (schema_mod.from_file(a.schema) if a.schema
                  else schema_mod.from_binary(a.uvms))
        os.makedirs(out, exist_ok=True)
        rep = Report(a.root, out, schema)
        if not rep.exps:
            print(f"report: warning: no campaign results.json under {a.root}", file=sys.stderr)
        path = document.build(rep)
    except (runlog.LogError, schema_mod.SchemaError, html.HtmlError, TableError) as e:
        print(f"report: error: {e}", file=sys.stderr)
        return 1
    finally:
        regen.stop_ahead()
    print(f"report: wrote {path}, report.html and {len(rep.figs.written)} figures in "
          f"{os.path.join(out, 'figures')} ({time.time() - t0:.1f} s)")
    return 0
