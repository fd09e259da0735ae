# SPDX-License-Identifier: Apache-2.0
"""tools/campaign-dask end to end (issue 18), one engine checked against the other: a
campaign's runs as dask.distributed tasks leave the same DIR as `uvms campaign` (and as its
shards plus --merge, when the binary has them), file by file apart from the wall clock
(campaign_compare.py), whether the client or the workers (--shared-fs) write the runs; a worker
SIGKILLed mid-run is replaced, its run ends with it and every run is in the results exactly
once; with --max-retries 0 that run is lost instead (exit 3, named, no results) and alone runs
on resume; an interrupted campaign-dask (SIGINT, SIGTERM) keeps its finished runs, leaves no
process behind, and either engine resumes it without redoing them; the DIR lock is shared with
`uvms campaign` and its shards (exit 4 each way); --help, usage errors (exit 2) and a campaign
uvms refuses (exit 1, no DIR left behind); a --no-logs campaign over a logged one leaves no old
run.lcmlog, as `uvms campaign` does; one run's outcomes on a worker (a harness error without a
summary is lost, not a result; a --shared-fs result of a campaign whose client is gone is
dropped) and the client's resubmission of lost attempts, within --max-retries, with a bounded
number of tasks in flight.

Usage: test_campaign_dask.py UVMS_EXE SOURCE_DIR CASE
       (CASE: same_as_campaign | killed_worker | lost_run | resume | busy | help |
              no_logs_clears_old_logs | run_outcomes | resubmission)
"""
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import psutil

from campaign_compare import differences  # this directory, on sys.path as the script's
from campaign_testkit import (executed, fail, mark_summaries, plan_ids, redone, wait_for,
                              write_file)

UVMS, SRC, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
# With this (the venv's) interpreter, whatever UVMS_NO_REEXEC says (tools/uvms_tools/env.py).
TOOL_CMD = [sys.executable, os.path.join(SRC, "tools", "campaign-dask")]
BASE = os.path.join(SRC, "sil", "scenarios", "paper", "case_IV_stagnant.toml")
TMP = tempfile.mkdtemp(prefix="uvms-campaign-dask-")
# A plan's pinned base scenario (inputs.base) for the worker tests, whose fake uvms reads none.
PINNED = {"path": "inputs/0000/base.toml", "sha256": "0" * 64, "text": "# none\n"}


def write(name, text):
    return write_file(TMP, name, text)


def campaign_file(name, masses, cases=("IV", "VII"), realtime_factor=None):
    """cases x masses runs of 1.5 s simulated; at `realtime_factor` x real time a run takes
    1.5 / realtime_factor s of wall time (None: as fast as it goes, ~10 ms)."""
    rtf = f'"link.realtime_factor" = {realtime_factor}\n' if realtime_factor else ""
    return write(name, f'name = "{name[:-5]}"\nbase = "{BASE}"\n[set]\n'
                       '"run.duration_s" = 1.5\n"trajectory.duration_s" = 1.5\n' + rtf +
                 f'[[sweep]]\n"control.case" = {json.dumps(list(cases))}\n'
                 f'[[sweep]]\n"payload.mass_kg" = {json.dumps([float(m) for m in masses])}\n')


def uvms_campaign(camp, out, *extra, timeout=120):
    p = subprocess.run([UVMS, "campaign", camp, "--out", out, "-j", "2", *extra],
                       capture_output=True, text=True, timeout=timeout)
    print("uvms campaign", *extra, "->", p.returncode, "\n", p.stdout, p.stderr)
    return p


def runs_dir(out):
    return os.path.join(out, "runs")


def dask_args(camp, out, *extra):
    return [*TOOL_CMD, camp, "--out", out, "--uvms", UVMS, "--local-workers", "2", *extra]


def dask_campaign(camp, out, *extra, timeout=120):
    t0 = time.monotonic()
    p = subprocess.run(dask_args(camp, out, *extra), capture_output=True, text=True,
                       timeout=timeout)
    print(f"campaign-dask {' '.join(extra)} -> {p.returncode} in {time.monotonic() - t0:.1f} s"
          f"\n{p.stdout}{p.stderr}")
    return p


def read(path, mode="rb"):
    with open(path, mode) as f:
        return f.read()


def same(reference, other, what):
    """`other` holds the campaign of `reference` apart from the wall clock
    (campaign_compare.py: every result file, byte for byte but for the wall-clock fields)."""
    diffs = differences(reference, other)
    if diffs:
        more = f" (and {len(diffs) - 1} more)" if len(diffs) > 1 else ""
        fail(f"{what} differs from uvms campaign: {diffs[0]}{more}")
    print(f"{what}: the same as uvms campaign apart from the wall clock")


def has_shards():
    p = subprocess.run([UVMS, "campaign", "--help"], capture_output=True, text=True, timeout=30)
    return "--shard" in p.stdout and "--merge" in p.stdout


def case_same_as_campaign():
    """2 cases x 2 payload masses by uvms campaign -j 2, by campaign-dask (files returned to
    the client, and written by the workers with --shared-fs), and by two shards + --merge."""
    camp = campaign_file("same.toml", [0, 5])
    ref = os.path.join(TMP, "campaign")
    if uvms_campaign(camp, ref).returncode != 0:
        fail("uvms campaign exited non-zero")
    for name, extra in (("dask", ()), ("dask_shared_fs", ("--shared-fs",))):
        out = os.path.join(TMP, name)
        p = dask_campaign(camp, out, *extra)
        if p.returncode != 0:
            fail(f"campaign-dask {' '.join(extra)} exited {p.returncode}")
        if executed(p.stdout) != sorted(plan_ids(ref)):
            fail(f"campaign-dask ran {executed(p.stdout)}, expected every run once")
        if not p.stdout.startswith("campaign-dask: same: 4 runs (0 already done)"):
            fail(f"first line {p.stdout.splitlines()[0]!r}")
        if not p.stdout.rstrip().endswith(f"4/4 runs finished; {out}/results.csv"):
            fail("the last line is not the merge's")
        if os.path.exists(os.path.join(out, ".work")):
            fail("--shared-fs left its work directory DIR/.work behind")
        same(ref, out, "campaign-dask " + " ".join(extra))
    if not has_shards():
        print("SKIP shards: this uvms has no --shard/--merge")
        return
    out = os.path.join(TMP, "shards")
    for shard in ("1/2", "2/2"):
        if uvms_campaign(camp, out, "--shard", shard).returncode != 0:
            fail(f"shard {shard} exited non-zero")
    if uvms_campaign(camp, out, "--merge").returncode != 0:
        fail("--merge exited non-zero")
    same(ref, out, "shards + --merge")


# 3 cases x 4 payload masses (masses with a SPEC §8 joint-angle column: every case accepts them).
TWELVE_CASES, TWELVE_MASSES = ("IV", "VII", "I"), [0, 1, 2, 5]


def ended(proc, timeout):
    """Whether `proc` ends within `timeout` s. An orphan's zombie counts as ended: its
    reaper (pid 1 here) may take its time."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            if proc.status() == psutil.STATUS_ZOMBIE:
                return True
        except psutil.NoSuchProcess:
            return True
        time.sleep(0.01)
    return False


def descendants(pid):
    try:
        return psutil.Process(pid).children(recursive=True)
    except psutil.NoSuchProcess:
        return []


def runs_with_summary(out):
    runs = os.path.join(out, "runs")
    if not os.path.isdir(runs):
        return []
    return sorted(r for r in os.listdir(runs)
                  if os.path.exists(os.path.join(runs, r, "summary.json")))


def case_killed_worker():
    """12 runs of ~0.5 s wall time on 2 workers; once 2 runs are written, the worker process
    running a `uvms run` is SIGKILLed. How it is found: the `uvms` processes are children of
    the dask worker processes (worker.py starts them), which descend from the tool (LocalCluster
    spawns them), so the parent of a descendant named "uvms" is a worker with a run in flight,
    whatever dask names its processes. The killed worker's run must end with it (PDEATHSIG),
    the campaign must exit 0 with every run once, and equal uvms campaign's results."""
    camp = campaign_file("killed.toml", TWELVE_MASSES, TWELVE_CASES, realtime_factor=3.0)
    out = os.path.join(TMP, "killed")
    t0 = time.monotonic()
    p = subprocess.Popen(dask_args(camp, out), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
    victim = kill_a_busy_worker(p, out, t0)
    stdout, stderr = p.communicate(timeout=120)
    print(f"campaign-dask -> {p.returncode} in {time.monotonic() - t0:.1f} s\n{stdout}{stderr}")
    if p.returncode != 0:
        fail(f"campaign-dask exited {p.returncode} after a worker was killed")
    # The killed worker's private run directory (worker.py: uvms-dask-run-<host>-<pid>-*) is
    # removed by a later task or by the client at the end; none is left.
    left = [n for n in os.listdir(tempfile.gettempdir())
            if n.startswith("uvms-dask-run-") and f"-{victim}-" in n]
    if left:
        fail(f"the killed worker's run directories are left in {tempfile.gettempdir()}: {left}")
    ids = plan_ids(out)
    if len(ids) != 12 or sorted(os.listdir(os.path.join(out, "runs"))) != sorted(ids):
        fail(f"runs/ holds {sorted(os.listdir(os.path.join(out, 'runs')))}, expected {ids}")
    with open(os.path.join(out, "results.json")) as f:
        rows = [r["id"] for r in json.load(f)["runs"]]
    if rows != ids:
        fail(f"results.json rows {rows}, expected each of {ids} once")
    if executed(stdout) != sorted(ids):
        fail(f"progress reports {executed(stdout)}, expected each run once")
    ref = os.path.join(TMP, "killed_ref")
    if uvms_campaign(camp, ref).returncode != 0:
        fail("uvms campaign exited non-zero")
    same(ref, out, "campaign-dask with a killed worker")


def kill_a_busy_worker(p, out, t0):
    """Once 2 runs are written, SIGKILLs the worker of campaign-dask `p` that runs a uvms run;
    checks that run ends with it. Returns the worker's pid."""
    victim = orphan = None
    while victim is None and time.monotonic() - t0 < 60 and p.poll() is None:
        if len(runs_with_summary(out)) >= 2:
            for proc in descendants(p.pid):
                try:
                    if proc.name() == "uvms" and proc.parent().pid != p.pid:
                        victim, orphan = proc.parent(), proc
                        break
                except psutil.NoSuchProcess:
                    continue
        time.sleep(0.01)
    if victim is None:
        p.kill()
        fail(f"no worker with a run in flight found (campaign exit {p.poll()})")
    print(f"SIGKILL worker {victim.pid} ({' '.join(victim.cmdline())[:120]}) while it runs "
          f"uvms {orphan.pid}; {len(runs_with_summary(out))} runs written")
    victim.send_signal(signal.SIGKILL)
    if not ended(orphan, 5):
        fail(f"the killed worker's uvms run {orphan.pid} still runs 5 s later (no PDEATHSIG?)")
    return victim.pid


def case_lost_run():
    """--max-retries 0: the run of a killed worker is lost at once (LocalCluster
    allowed-failures 0, no resubmission): exit 3 naming it, no results written, every other run
    written; the same command then runs only that run and completes."""
    camp = campaign_file("lost.toml", TWELVE_MASSES, TWELVE_CASES, realtime_factor=3.0)
    out = os.path.join(TMP, "lost")
    t0 = time.monotonic()
    p = subprocess.Popen(dask_args(camp, out, "--max-retries", "0"), stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    kill_a_busy_worker(p, out, t0)
    stdout, stderr = p.communicate(timeout=120)
    print(f"campaign-dask -> {p.returncode} in {time.monotonic() - t0:.1f} s\n{stdout}{stderr}")
    lost = re.findall(r"^\[\d+/12\] .*  (\S+) LOST$", stdout, re.M)
    if p.returncode != 3 or len(lost) != 1 or "1 run lost" not in stderr or lost[0] not in stderr:
        fail(f"exit {p.returncode}, lost {lost}: expected 3 and one lost run named")
    if os.path.exists(os.path.join(out, "results.json")):
        fail("results were written with a run lost")
    written = runs_with_summary(out)
    if sorted(written + lost) != sorted(plan_ids(out)):
        fail(f"runs written {written} + lost {lost} are not the plan's runs once each")
    stamps = mark_summaries(runs_dir(out))
    p = dask_campaign(camp, out)
    if p.returncode != 0 or executed(p.stdout) != lost or redone(runs_dir(out), stamps):
        fail(f"the resumed campaign exited {p.returncode}, ran {executed(p.stdout)}, expected "
             f"only {lost}")
    print("lost run ok:", lost[0])


def interrupt(camp, out, sig, before):
    """Starts campaign-dask, sends `sig` once 2 more runs than `before` are written; checks
    it ends by that signal, leaves no run process and no results behind. Returns the ids
    with a summary.json, stamped."""
    t0 = time.monotonic()
    scratch = tempfile.mkdtemp(prefix="scratch-", dir=TMP)  # the workers' /tmp, watched
    p = subprocess.Popen(dask_args(camp, out), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True, env=dict(os.environ, TMPDIR=scratch))
    seen = set()
    while time.monotonic() - t0 < 60 and p.poll() is None:
        seen.update(descendants(p.pid))
        if len(runs_with_summary(out)) >= len(before) + 2:
            break
        time.sleep(0.01)
    p.send_signal(sig)
    stdout, stderr = p.communicate(timeout=60)
    print(f"campaign-dask, {signal.Signals(sig).name} -> {p.returncode} after "
          f"{time.monotonic() - t0:.1f} s\n{stdout}{stderr}")
    if p.returncode != -sig:
        fail(f"an interrupted campaign-dask exited {p.returncode}, expected death by {sig}")
    alive = [q.pid for q in seen if not ended(q, 3)]
    if alive:
        fail(f"processes of the interrupted campaign still run: {alive}")
    left = [n for n in os.listdir(scratch) if n.startswith("uvms-dask-run-")]
    if left:
        fail(f"the interrupted campaign left its runs' scratch directories in /tmp: {left}")
    done = runs_with_summary(out)
    if len(done) < len(before) + 2 or len(done) >= 12:
        fail(f"{len(done)} runs written: the interruption came too early or too late")
    new = sorted(set(done) - set(before))
    if executed(stdout) != new:
        fail(f"progress reported {executed(stdout)}, but runs/ has {new} newly written")
    for r in done:
        s = json.loads(read(os.path.join(out, "runs", r, "summary.json")))
        if s["status"] != "finished":
            fail(f"run {r}: a summary.json of status {s['status']} ({s.get('failure')}) left")
    if os.path.exists(os.path.join(out, "results.json")):
        fail("an interrupted campaign wrote results")
    return done


def case_resume():
    """12 runs of ~0.37 s: campaign-dask interrupted by SIGINT, resumed by campaign-dask and
    interrupted by SIGTERM, finished by uvms campaign; no run is redone at any step."""
    camp = campaign_file("resume.toml", TWELVE_MASSES, TWELVE_CASES, realtime_factor=4.0)
    out = os.path.join(TMP, "resume")
    first = interrupt(camp, out, signal.SIGINT, [])
    stamps = mark_summaries(runs_dir(out))
    second = interrupt(camp, out, signal.SIGTERM, first)
    if redone(runs_dir(out), stamps):
        fail(f"campaign-dask redid the finished runs {redone(runs_dir(out), stamps)}")
    stamps = mark_summaries(runs_dir(out))
    p = uvms_campaign(camp, out)
    if p.returncode != 0 or f"12 runs ({len(second)} already done)" not in p.stdout:
        fail(f"uvms campaign after campaign-dask: exit {p.returncode}, expected 0 with "
             f"{len(second)} runs already done")
    rest = sorted(set(plan_ids(out)) - set(second))
    if redone(runs_dir(out), stamps) or executed(p.stdout) != rest:
        fail(f"uvms campaign ran {executed(p.stdout)}; redone: {redone(runs_dir(out), stamps)}")
    # And the other way round: a finished DIR resumed by campaign-dask runs nothing.
    stamps = mark_summaries(runs_dir(out))
    p = dask_campaign(camp, out)
    if p.returncode != 0 or "12 runs (12 already done)" not in p.stdout or \
            redone(runs_dir(out), stamps):
        fail("campaign-dask on a finished DIR did not keep every run")
    print("resume ok:", len(first), "then", len(second), "runs before the interruptions")


def case_busy():
    """campaign-dask on a DIR in use by uvms campaign: exit 4 at once, naming the holder;
    uvms campaign on a DIR in use by campaign-dask: exit 4; campaign-dask beside a running
    shard: exit 4."""
    camp = campaign_file("busy.toml", [0, 1], cases=("IV",), realtime_factor=1.0)
    out = os.path.join(TMP, "busy")
    first = subprocess.Popen([UVMS, "campaign", camp, "--out", out, "-j", "1"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wait_for(os.path.join(out, "plan.json"), first, timeout_s=30)
    t0 = time.monotonic()
    p = subprocess.run(dask_args(camp, out), capture_output=True, text=True, timeout=30)
    took = time.monotonic() - t0
    print(f"campaign-dask -> {p.returncode} in {took:.2f} s\n{p.stdout}{p.stderr}")
    if first.poll() is not None:
        fail("uvms campaign ended before campaign-dask was refused: nothing was tested")
    if p.returncode != 4:
        fail(f"campaign-dask on a DIR in use exited {p.returncode}, expected 4")
    for n in ("in use by another campaign", f"(process {first.pid} on ", ".campaign.lock"):
        if n not in p.stderr:
            fail(f"the refusal does not say {n!r}")
    if p.stdout or took > 5:
        fail(f"the refused campaign-dask printed progress or took {took:.1f} s")
    first.communicate(timeout=60)
    # The other way round: campaign-dask holds DIR (through its plan and its runs).
    out = os.path.join(TMP, "busy_dask")
    d = subprocess.Popen(dask_args(camp, out), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
    wait_for(os.path.join(out, "plan.json"), d, timeout_s=30)
    p = uvms_campaign(camp, out, timeout=30)
    if d.poll() is not None:
        fail("campaign-dask ended before uvms campaign was refused: nothing was tested")
    if p.returncode != 4 or f"(process {d.pid} on " not in p.stderr:
        fail(f"uvms campaign on a DIR held by campaign-dask exited {p.returncode}, expected 4 "
             f"naming process {d.pid}")
    stdout, stderr = d.communicate(timeout=60)
    if d.returncode != 0:
        fail(f"campaign-dask exited {d.returncode}: {stdout}{stderr}")
    # A shard holds DIR's lock shared: campaign-dask (exclusive) is refused while it runs.
    out = os.path.join(TMP, "busy_shard")
    shard = subprocess.Popen([UVMS, "campaign", camp, "--out", out, "-j", "1", "--shard", "1/1"],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wait_for(os.path.join(out, "plan.json"), shard, timeout_s=30)
    p = subprocess.run(dask_args(camp, out), capture_output=True, text=True, timeout=30)
    print(f"campaign-dask beside a shard -> {p.returncode}\n{p.stdout}{p.stderr}")
    if shard.poll() is not None:
        fail("the shard ended before campaign-dask was refused: nothing was tested")
    if p.returncode != 4 or "in use by another campaign" not in p.stderr:
        fail(f"campaign-dask beside a running shard exited {p.returncode}, expected 4")
    shard.communicate(timeout=60)
    print("busy ok")


def case_help():
    """--help prints the usage and does nothing else; usage errors exit 2 naming the problem,
    before anything is written."""
    out = os.path.join(TMP, "help")
    p = subprocess.run([*TOOL_CMD, "--help"], capture_output=True, text=True, timeout=30)
    if p.returncode != 0 or not p.stdout.startswith("usage: tools/campaign-dask"):
        fail(f"--help: exit {p.returncode}, stdout {p.stdout[:200]!r}")
    for n in ("-j N, --jobs N, --local-workers N", "--scheduler", "--shared-fs", "--logs",
              "--no-logs", "--max-retries", "--uvms",
              "Exit status"):
        if n not in p.stdout:
            fail(f"--help does not mention {n}")
    camp = campaign_file("help.toml", [0])
    common = [camp, "--out", out, "--uvms", UVMS]
    bad = [("an unknown option", common + ["--local-workers", "1", "--bogus"], "--bogus"),
           ("both kinds of workers", common + ["--local-workers", "1", "--scheduler",
                                               "tcp://127.0.0.1:1"], "not allowed with"),
           ("zero workers", common + ["--local-workers", "0"], "--local-workers: needs a count"),
           ("a bad retry count", common + ["--local-workers", "1", "--max-retries", "x"],
            "--max-retries: needs a count"),
           ("no campaign", ["--out", out, "--uvms", UVMS, "--local-workers", "1"],
            "CAMPAIGN.toml"),
           ("no uvms", [camp, "--out", out, "--uvms", os.path.join(TMP, "none"),
                        "--local-workers", "1"], "not an executable file")]
    for what, args, needle in bad:
        p = subprocess.run([*TOOL_CMD, *args], capture_output=True, text=True, timeout=30)
        print(what, "->", p.returncode, p.stderr.strip())
        if p.returncode != 2 or needle not in p.stderr:
            fail(f"{what}: exit {p.returncode}, expected 2 saying {needle!r}")
        if os.path.exists(out):
            fail(f"{what}: a usage error wrote {out}")
    # A campaign uvms refuses: its exit status (1) and message, and no DIR left behind.
    bad_camp = write("bad.toml", f'base = "{BASE}"\nsweeps = 3\n')
    p = subprocess.run([*TOOL_CMD, bad_camp, "--out", out, "--uvms", UVMS, "--local-workers", "1"],
                       capture_output=True, text=True, timeout=30)
    print("a bad campaign ->", p.returncode, p.stderr.strip())
    if p.returncode != 1 or "bad.toml:2" not in p.stderr or os.path.exists(out):
        fail(f"a bad campaign: exit {p.returncode}, expected 1 naming bad.toml:2, no {out}")
    print("help ok")


def run_files(out):
    """{run id: sorted file names} of DIR/runs."""
    return {r: sorted(os.listdir(os.path.join(runs_dir(out), r)))
            for r in sorted(os.listdir(runs_dir(out)))}


def case_no_logs_clears_old_logs():
    """A logged campaign by uvms campaign, then campaign-dask --force-new --no-logs over it
    (files returned to the client, and written by the workers with --shared-fs): no old
    run.lcmlog is left beside the new summaries, and DIR equals uvms campaign --force-new
    --no-logs over the same logged campaign (whose `uvms run --no-log` removes the log)."""
    camp = campaign_file("nolog.toml", [0, 5])
    ref = os.path.join(TMP, "nolog_ref")
    for extra in ((), ("--force-new", "--no-logs")):
        if uvms_campaign(camp, ref, *extra).returncode != 0:
            fail(f"uvms campaign {' '.join(extra)} exited non-zero")
    if any("run.lcmlog" in names for names in run_files(ref).values()):
        fail("uvms campaign --force-new --no-logs left a run.lcmlog: nothing to compare with")
    for name, extra in (("nolog_dask", ()), ("nolog_dask_shared_fs", ("--shared-fs",))):
        out = os.path.join(TMP, name)
        if uvms_campaign(camp, out).returncode != 0:
            fail("the logged uvms campaign exited non-zero")
        logged = [r for r, names in run_files(out).items() if "run.lcmlog" in names]
        if sorted(logged) != sorted(plan_ids(out)):
            fail(f"the logged campaign left run.lcmlog only in {logged}")
        p = dask_campaign(camp, out, "--force-new", "--no-logs", *extra)
        if p.returncode != 0 or executed(p.stdout) != sorted(plan_ids(out)):
            fail(f"campaign-dask --force-new --no-logs {' '.join(extra)} exited {p.returncode}, "
                 f"ran {executed(p.stdout)}: expected 0, every run once")
        stale = [r for r, names in run_files(out).items() if "run.lcmlog" in names]
        if stale:
            fail(f"campaign-dask --no-logs {' '.join(extra)} left the old run.lcmlog of {stale}")
        same(ref, out, "campaign-dask --force-new --no-logs " + " ".join(extra))


def case_logs_policy():
    """--logs ID by campaign-dask (files returned, and written by the workers with --shared-fs)
    leaves DIR as uvms campaign --logs ID does: only that run keeps its run.lcmlog."""
    camp = campaign_file("logs.toml", [0, 5])
    ref = os.path.join(TMP, "logs_ref")
    if uvms_campaign(camp, ref, "--logs", "VII_0.0").returncode != 0:
        fail("uvms campaign --logs VII_0.0 exited non-zero")
    for name, extra in (("logs_dask", ()), ("logs_dask_shared_fs", ("--shared-fs",))):
        out = os.path.join(TMP, name)
        p = dask_campaign(camp, out, "--logs", "VII_0.0", *extra)
        kept = [r for r, names in run_files(out).items() if "run.lcmlog" in names]
        if p.returncode != 0 or kept != ["VII_0.0"]:
            fail(f"campaign-dask --logs VII_0.0 {' '.join(extra)}: exit {p.returncode}, logs of "
                 f"{kept}; expected 0, ['VII_0.0']")
        same(ref, out, "campaign-dask --logs VII_0.0 " + " ".join(extra))


def fake_uvms(name, body):
    """An executable shell script standing in for `uvms` (the worker runs it as `uvms run
    ...` in the run directory)."""
    path = write(name, "#!/bin/sh\n" + body)
    os.chmod(path, 0o755)
    return path


def case_run_outcomes():
    """worker.execute_run (one task's body, called here directly) with stand-ins for uvms: a
    run that ends with neither 0 nor 3 and without a summary.json (127: the binary cannot
    start; killed by a signal) is lost, not a result, and returns no files; exit 3 without a
    summary, or any status with one, is a result; a scratch space that cannot be created is
    lost; under --shared-fs a result is published (the old files the run did not produce
    removed) while DIR's lock is held, and dropped, DIR untouched, once it is not."""
    sys.path.insert(0, os.path.join(SRC, "tools"))
    from uvms_tools.campaign_dask import outdir, worker
    summary = 'echo \'{"status": "failed"}\' > summary.json\n'
    cases = [("missing binary", None, "lost"),
             ("killed", "kill -KILL $$\n", "lost"),
             ("exit 2, no summary", "exit 2\n", "lost"),
             ("exit 3, no summary", "exit 3\n", 3),
             ("exit 2 with a summary", summary + "exit 2\n", 2),
             ("exit 0", summary.replace("failed", "finished") + "exit 0\n", 0)]
    for i, (what, body, want) in enumerate(cases):
        uvms = os.path.join(TMP, "no-such-uvms") if body is None else \
            fake_uvms(f"uvms{i}", "echo harness says why\n" + body)
        res = worker.execute_run(uvms, ["run", "--out", "."], "{}", f"r{i}", None, PINNED)
        print(what, "->", {k: v for k, v in res.items() if k != "files"},
              sorted(res["files"] or {}))
        if want == "lost":
            if not res["lost"] or res["files"] is not None or res["error"]:
                fail(f"{what}: expected a lost attempt without files, got {res}")
            if body is not None and "harness says why" not in res["lost"]:
                fail(f"{what}: the reason does not quote run.out: {res['lost']!r}")
        elif res["lost"] or res["error"] or res["rc"] != want or res["files"] is None:
            fail(f"{what}: expected a result of exit {want}, got {res}")
    # A full /tmp: mkdtemp fails. The worker's scratch space, not DIR: lost, retried.
    saved = worker.tempfile.mkdtemp
    worker.tempfile.mkdtemp = lambda **kw: (_ for _ in ()).throw(OSError(28, "No space left"))
    try:
        res = worker.execute_run(fake_uvms("uvms_ok", "exit 0\n"), [], "{}", "r", None, PINNED)
    finally:
        worker.tempfile.mkdtemp = saved
    if not res["lost"] or "No space left" not in res["lost"] or res["error"]:
        fail(f"a failing mkdtemp: expected a lost attempt, got {res}")
    # --shared-fs: an old run.lcmlog of a logged run, then a --no-log run's publish.
    out = os.path.join(TMP, "publish")
    run_dir = os.path.join(out, "runs", "r")
    os.makedirs(os.path.join(out, ".work", "tok"))
    os.makedirs(run_dir)
    for name in ("run.lcmlog", "summary.json"):
        with open(os.path.join(run_dir, name), "w") as f:
            f.write("old\n")
    uvms = fake_uvms("uvms_nolog", summary.replace("failed", "finished") + "exit 0\n")
    lock = outdir.OutDirLock(out)  # the client's exclusive lock: held, so the worker publishes
    res = worker.execute_run(uvms, [], "{}", "r", (out, "tok"), PINNED)
    names = sorted(os.listdir(run_dir))
    print("published ->", res, names)
    if res["error"] or res["lost"] or res["dropped"] or \
            names != ["overrides.json", "run.out", "summary.json"]:
        fail(f"a --shared-fs publish under the lock left {names} ({res})")
    os.close(lock.fd)  # the client is gone: its lock with it
    os.unlink(os.path.join(run_dir, "summary.json"))
    res = worker.execute_run(uvms, [], "{}", "r", (out, "tok"), PINNED)
    print("client gone ->", res, sorted(os.listdir(run_dir)))
    if not res["dropped"] or ".campaign.lock" not in res["dropped"] or \
            os.path.exists(os.path.join(run_dir, "summary.json")):
        fail(f"a --shared-fs result after the client released DIR was not dropped: {res}")
    if os.listdir(os.path.join(out, ".work", "tok")):
        fail("the dropped run's scratch directory was left behind")
    print("run outcomes ok")


# case_resubmission's fake task reads and writes this through sys.modules["__main__"] (the
# cluster is in this process; a function of __main__ is pickled by value, its globals copied).
FAKE = {}


def fake_run(uvms, argv, overrides_json, run_id, shared, base, keep_log=True):
    """A stand-in for worker.execute_run: plays the next outcome of FAKE["script"][run_id]."""
    import types
    import distributed
    st = sys.modules["__main__"].FAKE
    with st["lock"]:
        attempt = st["attempts"].setdefault(run_id, 0)
        st["attempts"][run_id] += 1
        outcome = st["script"][run_id][min(attempt, len(st["script"][run_id]) - 1)]
        st["returned"] += 1
    res = {"id": run_id, "rc": None, "host": "fake", "pid": os.getpid(), "files": {},
           "lost": None, "error": None, "dropped": None}
    if outcome == "killed":
        raise distributed.KilledWorker(run_id, types.SimpleNamespace(address="tcp://fake:1"), 1)
    if outcome == "raises":
        raise RuntimeError("a bug in the task")
    if outcome == "lost":
        res["lost"] = "uvms run ended (exit 127) without a summary.json on fake"
    else:
        res["rc"] = outcome
    return res


def case_resubmission():
    """engine.run_tasks, the client side, against an in-process cluster with a fake task
    (fake_run) scripted per run: an attempt lost by KilledWorker (what the scheduler reports
    once its allowed-failures are spent), by an exception of the task or by a "lost" result
    (a harness error on the worker) is submitted again under a new key, at most --max-retries
    times, then the run is lost; a FAILED result (exit 3) is never retried. And the tasks are
    submitted in plan order with at most `limit` in flight (a run is first submitted only
    after enough earlier tasks have returned)."""
    sys.path.insert(0, os.path.join(SRC, "tools"))
    import io
    import threading
    import distributed
    from uvms_tools.campaign_dask import engine
    max_retries, limit = 1, 3
    script = {"finished": [0], "killed_once": ["killed", 0], "raises_once": ["raises", 0],
              "lost_once": ["lost", 0], "lost_always": ["lost"], "killed_always": ["killed"],
              "failed": [3, 0]}
    script.update({f"more{i}": [0] for i in range(6)})
    FAKE.update(lock=threading.Lock(), attempts={}, returned=0, script=script, firsts=[])
    plan = {"out": TMP, "uvms": "/nonexistent/uvms", "inputs": {"base": PINNED},
            "runs": [{"id": r, "argv": [], "overrides_json": "{}", "state": "todo"}
                     for r in script]}
    engine.EXECUTE_RUN = fake_run
    engine.quiet_logs()  # the in-process workers log the tasks' exceptions

    class Recorder:  # the client as run_tasks uses it, recording each first submission
        def __init__(self, client):
            self.client = client

        def submit(self, fn, *args, key, **kw):
            if "-retry" not in key:
                FAKE["firsts"].append((args[3], FAKE["returned"]))
            return self.client.submit(fn, *args, key=key, **kw)

        def __getattr__(self, name):
            return getattr(self.client, name)

    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False,
                                  dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        engine.check_versions(client)  # a LocalCluster passes the check of --scheduler
        progress = io.StringIO()
        outcome = engine.run_tasks(Recorder(client), plan, None, max_retries, False,
                                   out=progress, limit=limit)
    print(progress.getvalue(), "attempts:", FAKE["attempts"], "firsts:", FAKE["firsts"])
    want_lost = ["killed_always", "lost_always"]
    if sorted(outcome.lost) != want_lost or outcome.failed != ["failed"] or outcome.error or \
            len(outcome.finished) != len(script) - 3:
        fail(f"finished {outcome.finished}, failed {outcome.failed}, lost {outcome.lost}: "
             f"expected lost {want_lost}, failed ['failed'], the rest finished")
    # Scripted attempts, or 1 + max_retries for a run lost every time; a FAILED result once.
    want = {r: 1 + max_retries if r.endswith("_always") else len(s) for r, s in script.items()}
    want["failed"] = 1
    if FAKE["attempts"] != want:
        fail(f"attempts per run {FAKE['attempts']}, expected {want}")
    order = [r for r, _ in FAKE["firsts"]]
    if order != list(script):
        fail(f"first submissions in the order {order}, expected the plan's {list(script)}")
    early = [(r, n) for k, (r, n) in enumerate(FAKE["firsts"]) if n < k - limit + 1]
    if early:
        fail(f"submitted with more than {limit} tasks in flight: (run, tasks returned) {early}")
    print("resubmission ok")


globals()["case_" + CASE]()
shutil.rmtree(TMP, ignore_errors=True)  # kept for inspection when a case fails
print("PASS", CASE)
