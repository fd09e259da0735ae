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
uvms refuses (exit 1, no DIR left behind).

Usage: test_campaign_dask.py UVMS_EXE SOURCE_DIR CASE
       (CASE: same_as_campaign | killed_worker | lost_run | resume | busy | help)
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
from campaign_testkit import executed, fail, mark_summaries, plan_ids, redone, wait_for

UVMS, SRC, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
# With this (the venv's) interpreter, whatever UVMS_NO_REEXEC says (tools/toolenv.py).
TOOL_CMD = [sys.executable, os.path.join(SRC, "tools", "campaign-dask")]
BASE = os.path.join(SRC, "sil", "scenarios", "paper", "case_IV_stagnant.toml")
TMP = tempfile.mkdtemp(prefix="uvms-campaign-dask-")


def write(name, text):
    path = os.path.join(TMP, name)
    with open(path, "w") as f:
        f.write(text)
    return path


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
    p = subprocess.Popen(dask_args(camp, out), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         text=True)
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
    for n in ("--local-workers", "--scheduler", "--shared-fs", "--max-retries", "--uvms",
              "Exit status"):
        if n not in p.stdout:
            fail(f"--help does not mention {n}")
    camp = campaign_file("help.toml", [0])
    common = [camp, "--out", out, "--uvms", UVMS]
    bad = [("an unknown option", common + ["--local-workers", "1", "--bogus"], "--bogus"),
           ("no workers", common, "--local-workers"),
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


globals()["case_" + CASE]()
shutil.rmtree(TMP, ignore_errors=True)  # kept for inspection when a case fails
print("PASS", CASE)
