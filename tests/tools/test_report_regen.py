# SPDX-License-Identifier: Apache-2.0
"""The report's logs made again (tools/uvms_tools/report/load/regen.py): a campaign that kept no
log (uvms campaign --logs none), read by the report's Experiment:
  - a log asked for is made again from plan.json, byte for byte the log a campaign that kept
    every log holds, and stays beside its run (logs_read says "made again");
  - a run whose kept summary.json differs from the one made again (as when another build ran
    the campaign) gets no log: logs_read names the differing field, nothing is left on disk;
  - without a uvms to run, logs_read says so;
  - a kept log is read as it is ("kept");
  - tools/report.py's --uvms defaults to $UVMS, else the repository's build (as every tool's).

Usage: test_report_regen.py UVMS_EXE SOURCE_DIR
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

UVMS, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tools"))
from uvms_tools.report.load import regen  # noqa: E402
from uvms_tools.report.load.runs import Experiment  # noqa: E402
from uvms_tools.report import cli as report_cli  # noqa: E402
from uvms_tools.env import REPO_ROOT, UVMS_REL  # noqa: E402

TMP = tempfile.mkdtemp(prefix="uvms-regen-")
BASE = os.path.join(SRC, "sil", "scenarios", "paper", "case_IV_stagnant.toml")
failures = []


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


def campaign(out, *extra):
    camp = os.path.join(TMP, "two.toml")
    with open(camp, "w") as f:
        f.write(f'name = "two"\nbase = "{BASE}"\n[[sweep]]\n'
                '"payload.mass_kg" = [0.0, 5.0, 10.0]\n')
    p = subprocess.run([UVMS, "campaign", camp, "--out", out, "-j", "2", "--set",
                        "run.duration_s=0.5", *extra], capture_output=True, text=True, timeout=120)
    if p.returncode != 0:
        print(p.stdout, p.stderr)
        sys.exit(f"FAIL uvms campaign {' '.join(extra)} exited {p.returncode}")
    return out


def experiment(out):
    with open(os.path.join(out, "results.json")) as f:
        return Experiment(out, json.load(f))


def log_path(out, rid):
    return os.path.join(out, "runs", rid, "run.lcmlog")


def main():
    os.chdir(SRC)  # --uvms given relative to where the report runs, not the run's directory
    regen.set_uvms(os.path.relpath(UVMS, SRC))
    full = campaign(os.path.join(TMP, "all"))
    bare = campaign(os.path.join(TMP, "none"), "--logs", "none")
    check(not os.path.exists(log_path(bare, "0.0")), "--logs none kept no log")
    e = experiment(bare)
    run = next(r for r in e.runs if r["id"] == "0.0")
    lg = e.log(run, ["UVMS_TRUTH"])
    check(lg is not None and len(lg["UVMS_TRUTH"]["tick"]) > 5 and
          e.logs_read == {"0.0": "made again"},
          f"the log is made again when read ({e.logs_read})")
    with open(log_path(bare, "0.0"), "rb") as a, open(log_path(full, "0.0"), "rb") as b:
        check(a.read() == b.read(), "byte for byte the log the full campaign kept")
    # Another build's numbers: the kept summaries say otherwise than the runs made again. The
    # first gets no log and names the field; the report then stops trying for the campaign.
    for rid in ("5.0", "10.0"):
        path = os.path.join(bare, "runs", rid, "summary.json")
        with open(path) as f:
            s = json.load(f)
        s["mean_ee_error_m"] *= 1.5
        with open(path, "w") as f:
            json.dump(s, f)
    e = experiment(bare)
    run = next(r for r in e.runs if r["id"] == "5.0")
    check(e.log(run) is None and "mean_ee_error_m" in e.logs_read["5.0"]
          and not os.path.exists(log_path(bare, "5.0"))
          and not [d for d in os.listdir(os.path.join(bare, "runs")) if d.startswith(".")],
          f"a differing summary gets no log, named ({e.logs_read['5.0'][:120]})")
    e.log(next(r for r in e.runs if r["id"] == "10.0"))
    check(e.logs_read["10.0"].startswith("not made again (as 5.0)")
          and not os.path.exists(log_path(bare, "10.0")),
          f"the next run is not simulated again for nothing ({e.logs_read['10.0'][:60]})")
    regen.set_uvms(os.path.join(TMP, "no-such-uvms"))
    e = experiment(bare)
    run = next(r for r in e.runs if r["id"] == "5.0")
    check(e.log(run) is None and "no uvms to run it with" in e.logs_read["5.0"],
          f"without a uvms: said ({e.logs_read['5.0'][:80]})")
    e = experiment(full)
    e.log(next(r for r in e.runs if r["id"] == "5.0"))
    check(e.logs_read == {"5.0": "kept"}, f"a kept log is read as it is ({e.logs_read})")
    saved = os.environ.pop("UVMS", None)
    try:
        check(report_cli.parse_args(["out"]).uvms == os.path.join(REPO_ROOT, UVMS_REL),
              "report --uvms: without $UVMS the repository's build")
        os.environ["UVMS"] = "/opt/elsewhere/uvms"
        check(report_cli.parse_args(["out"]).uvms == "/opt/elsewhere/uvms",
              "report --uvms: $UVMS when set")
        check(report_cli.parse_args(["out", "--uvms", "x/uvms"]).uvms == "x/uvms",
              "report --uvms: the option over $UVMS")
    finally:
        os.environ.pop("UVMS", None)
        if saved is not None:
            os.environ["UVMS"] = saved
    shutil.rmtree(TMP, ignore_errors=True)
    print(f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
