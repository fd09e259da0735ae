# SPDX-License-Identifier: Apache-2.0
"""The report's logs made again (tools/uvms_tools/report/load/regen.py): a campaign that kept no
log (uvms campaign --logs none), read by the report's Experiment:
  - a log asked for is made again from plan.json, byte for byte the log a campaign that kept
    every log holds, and stays beside its run (logs_read says "made again");
  - a run whose kept summary.json differs from the one made again (as when another build ran
    the campaign) gets no log: logs_read names the differing field, nothing is left on disk;
  - without a uvms to run, logs_read says so;
  - a kept log is read as it is ("kept");
  - logs made ahead, several at a time (Experiment.prefetch_logs), then read: the same logs_read
    (in the order read), warnings and logs on disk as read one by one, also when a differing
    summary stops the campaign's regeneration while later runs' logs are being made;
  - tools/report.py's --uvms defaults to $UVMS, else the repository's build (as every tool's).

Usage: test_report_regen.py UVMS_EXE SOURCE_DIR
"""
import contextlib
import io
import json
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time

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
                '"payload.mass_kg" = [0.0, 2.0, 5.0, 10.0, 20.0]\n')
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


def another_builds_summary(out, rid):
    """Run rid's kept summary.json as another build would have written it: its mean EE error
    ×1.5, which the run made again does not match."""
    path = os.path.join(out, "runs", rid, "summary.json")
    with open(path) as f:
        s = json.load(f)
    s["mean_ee_error_m"] *= 1.5
    with open(path, "w") as f:
        json.dump(s, f)


def read_in_order(pristine, full, order, ahead, differ=(), kept=(), unfinished=(), hold=()):
    """Reads the logs of `order` (run ids) in a copy of campaign `pristine`, after
    prefetch_logs(order) when `ahead`: runs in `differ` have a kept summary the run made again
    does not match, runs in `kept` the log of campaign `full`, runs in `unfinished` did not
    finish; the runs in `hold` are made in the background only once the campaign's regeneration
    stopped. Returns (logs_read items in order, warnings, {id: log bytes or None}, ids made in
    a background thread)."""
    out = os.path.join(TMP, f"order-{'ahead' if ahead else 'serial'}")
    shutil.rmtree(out, ignore_errors=True)
    shutil.copytree(pristine, out)
    for rid in differ:
        another_builds_summary(out, rid)
    for rid in kept:
        shutil.copy(log_path(full, rid), log_path(out, rid))
    e = experiment(out)
    runs = {r["id"]: r for r in e.runs}
    for rid in unfinished:
        runs[rid]["status"] = "failed"
    made_in = []
    real = regen.regenerate

    def noted(exp_dir, run_id, argv):
        if threading.current_thread() is not threading.main_thread():
            made_in.append(run_id)
            deadline = time.monotonic() + 20  # a prefetch that never stops fails, not hangs
            while run_id in hold and e._regen_stopped is None and time.monotonic() < deadline:
                time.sleep(0.01)
        return real(exp_dir, run_id, argv)
    regen.regenerate = noted  # regenerate_ahead's; the one-by-one path's is runs.regenerate
    err = io.StringIO()
    try:
        with contextlib.redirect_stderr(err):
            if ahead:
                e.prefetch_logs([runs[rid] for rid in order])
            for rid in order:
                e.log(runs[rid], ["UVMS_TRUTH"])
    finally:
        regen.regenerate = real
    logs = {}
    for rid in runs:
        p = log_path(out, rid)
        logs[rid] = open(p, "rb").read() if os.path.exists(p) else None
    left = [d for d in os.listdir(os.path.join(out, "runs")) if d.startswith(".")]
    return list(e.logs_read.items()), err.getvalue(), logs, sorted(made_in) + left


def check_ahead_as_serial(pristine, full):
    """prefetch_logs then reading, against reading one by one. Five at a time, every run made
    ahead starts at once (the differing summary of 5.0 stops the campaign's regeneration once
    the later runs' logs are made: they are removed); one at a time, the later runs wait until
    it stopped (the one started is removed, the others are not made; which one, a race)."""
    differ = ("a differing summary stops the rest", ["0.0", "5.0", "10.0", "2.0", "20.0"])
    cases = [(5, "kept, unfinished and made again", ["10.0", "2.0", "20.0", "0.0", "5.0"],
              dict(kept=["2.0"], unfinished=["20.0"]), ["0.0", "10.0", "5.0"]),
             (5, *differ, dict(differ=["5.0"]), ["0.0", "10.0", "2.0", "20.0", "5.0"]),
             (1, *differ, dict(differ=["5.0"], hold=["10.0", "2.0", "20.0"]), None)]
    for jobs, what, order, setup, made_ahead in cases:
        regen.set_jobs(jobs)
        what = f"{jobs} at a time, {what}"
        s_read, s_err, s_logs, s_bg = read_in_order(pristine, full, order, False, **setup)
        a_read, a_err, a_logs, a_bg = read_in_order(pristine, full, order, True, **setup)
        check(a_read == s_read and a_err == s_err,
              f"made ahead, {what}: logs_read and warnings as one by one ({a_read})")
        check(a_logs == s_logs, f"made ahead, {what}: the logs on disk as one by one "
              f"({sorted(k for k, v in a_logs.items() if v)})")
        check(s_bg == [] and a_bg == (made_ahead or a_bg) and {"0.0", "5.0"} <= set(a_bg),
              f"made ahead, {what}: {a_bg} made in the background")


def main():
    os.chdir(SRC)  # --uvms given relative to where the report runs, not the run's directory
    regen.set_uvms(os.path.relpath(UVMS, SRC))
    full = campaign(os.path.join(TMP, "all"))
    bare = campaign(os.path.join(TMP, "none"), "--logs", "none")
    pristine = os.path.join(TMP, "pristine")
    shutil.copytree(bare, pristine)
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
        another_builds_summary(bare, rid)
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
    check_ahead_as_serial(pristine, full)
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
