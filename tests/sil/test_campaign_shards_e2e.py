# SPDX-License-Identifier: Apache-2.0
"""`uvms campaign --shard I/N`, `--merge`, `--plan-only` and `--no-logs` end to end (issue 18).

Cases:
  shards_match_campaign  a 5-run campaign as a whole and as shards 1/3, 2/3, 3/3 (two of them at
                         the same time on one DIR) then --merge: the same files apart from the
                         wall-clock fields (logs byte for byte); the shards cover the plan
                         round-robin; a merge with a shard missing is refused (exit 3, naming
                         the runs) and writes no results.
  shard_locks            while shards run, a whole campaign and a merge on their DIR are refused
                         (exit 4), the same shard twice and a shard of another N are refused
                         (exit 4), another shard is not; --dry-run --shard lists the shard's
                         runs; bad --shard values and option clashes are usage errors (exit 2).
  plan_only              --plan-only prints JSON Lines (a head, a line per run) and nothing else
                         on stdout, writes
                         plan.json and no run; its states follow DIR (todo, done, failed, and
                         todo again with --retry-failed); a run executed by hand as its entry
                         says gives the campaign's files; the lock hand-over through
                         UVMS_CAMPAIGN_LOCK_FD works, and a descriptor of another file or a held
                         lock is refused.
  no_logs                --no-logs: no run.lcmlog anywhere, the same results; a logged run redone
                         without logs loses its old log.

Usage: test_campaign_shards_e2e.py UVMS_EXE SOURCE_DIR CASE
"""
import fcntl
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from campaign_compare import differences  # noqa: E402
from campaign_testkit import fail, plan_ids, wait_for  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

UVMS, SRC, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
BASE = os.path.join(os.path.abspath(SRC), "sil", "scenarios", "paper", "case_IV_stagnant.toml")
TMP = scratch_dir("uvms-shards-")  # removed at exit (tests/support/scratch.py)


def write_campaign(name, masses, realtime_factor=None):
    """A sweep over payload masses of 1.5 s runs (at `realtime_factor` x real time if given)."""
    pace = f'"link.realtime_factor" = {realtime_factor}\n' if realtime_factor else ""
    path = os.path.join(TMP, name)
    with open(path, "w") as f:
        f.write(f'name = "shards"\nbase = "{BASE}"\n[set]\n"run.duration_s" = 1.5\n'
                f'"trajectory.duration_s" = 1.5\n{pace}[[sweep]]\n"payload.mass_kg" = '
                f'[{", ".join(f"{m:.1f}" for m in masses)}]\n')
    return path


def uvms(*args, env=None, pass_fds=(), timeout=300):
    p = subprocess.run([UVMS, "campaign", *args], capture_output=True, text=True, timeout=timeout,
                       env=env, pass_fds=pass_fds)
    print(" ".join(["uvms campaign", *[os.path.basename(a) for a in args]]), "->", p.returncode)
    print(p.stdout, p.stderr)
    return p


def expect(p, code, what, needles=()):
    if p.returncode != code:
        fail(f"{what}: exit {p.returncode}, expected {code}")
    for n in needles:
        if n not in p.stdout + p.stderr:
            fail(f"{what}: the output does not say {n!r}")


def run_ids_with_results(out):
    runs = os.path.join(out, "runs")
    return sorted(r for r in os.listdir(runs)
                  if os.path.exists(os.path.join(runs, r, "summary.json")))


def case_shards_match_campaign():
    camp = write_campaign("five.toml", range(5))
    whole, sharded = os.path.join(TMP, "whole"), os.path.join(TMP, "sharded")
    expect(uvms(camp, "--out", whole, "-j", "2"), 0, "the whole campaign")
    ids = plan_ids(whole)
    # Shards 1/3 and 2/3 side by side on one DIR (the shared lock), 3/3 later.
    procs = [subprocess.Popen([UVMS, "campaign", camp, "--out", sharded, "--shard", f"{i}/3",
                               "-j", "1"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True) for i in (1, 2)]
    for i, p in enumerate(procs, 1):
        out, _ = p.communicate(timeout=300)
        print(f"shard {i}/3 ->", p.returncode, out)
        if p.returncode != 0 or f"shard {i}/3" not in out:
            fail(f"shard {i}/3 exited {p.returncode}")
    got = run_ids_with_results(sharded)
    want = sorted(ids[k] for k in range(5) if k % 3 in (0, 1))
    if got != want:
        fail(f"shards 1/3 and 2/3 ran {got}, expected the round-robin share {want}")
    missing = [ids[k] for k in range(5) if k % 3 == 2]
    early = uvms(camp, "--out", sharded, "--merge")
    expect(early, 3, "a merge with shard 3/3 missing", [f"{len(missing)} of 5 runs have no result",
                                                        *missing])
    if os.path.exists(os.path.join(sharded, "results.csv")):
        fail("a refused merge wrote results.csv")
    expect(uvms(camp, "--out", sharded, "--shard", "3/3"), 0, "shard 3/3")
    merged = uvms(camp, "--out", sharded, "--merge")
    expect(merged, 0, "the merge", ["5/5 runs finished"])
    if "builds" in merged.stdout:
        fail("a merge of runs of one build notes several builds")
    diffs = differences(whole, sharded)
    if diffs:
        fail("shards + merge differ from the whole campaign: " + "; ".join(diffs[:5]))
    # Runs of another build (a shard run with another binary): the merge says so.
    path = os.path.join(sharded, "runs", ids[4], "summary.json")
    with open(path) as f:
        s = json.load(f)
    s["provenance"]["git_commit"], s["provenance"]["controller_precision"] = "0" * 40, "float"
    with open(path, "w") as f:
        json.dump(s, f)
    mixed = uvms(camp, "--out", sharded, "--merge")
    expect(mixed, 0, "a merge of runs of two builds", ["the runs come from 2 builds",
                                                        "0" * 40 + " float"])
    print("shards + merge == campaign over", len(ids), "runs")


def case_shard_locks():
    camp = write_campaign("slow.toml", range(4), realtime_factor=4.0)  # >= 0.37 s per run
    out = os.path.join(TMP, "locked")
    first = subprocess.Popen([UVMS, "campaign", camp, "--out", out, "--shard", "1/2", "-j", "1"],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wait_for(os.path.join(out, "plan.json"), first)
    expect(uvms(camp, "--out", out), 4, "a whole campaign while a shard runs",
           ["in use by another campaign", ".campaign.lock"])
    expect(uvms(camp, "--out", out, "--merge"), 4, "a merge while a shard runs")
    expect(uvms(camp, "--out", out, "--shard", "1/2"), 4, "the same shard twice",
           ["shard 1/2", ".shard-1-of-2.lock"])
    expect(uvms(camp, "--out", out, "--shard", "1/4"), 4, "a shard of another N beside 1/2",
           ["has shard 1/2 running", "the same N"])
    # The campaign file edited while shard 1/2 runs: shard 2/2 of the edited campaign (another
    # identity, accepted alone as an extension) would write into the same run directories.
    with open(camp) as f:
        original = f.read()
    with open(camp, "w") as f:
        f.write(original.replace("[0.0, 1.0, 2.0, 3.0]", "[0.0, 1.0, 2.0, 3.0, 4.0]"))
    expect(uvms(camp, "--out", out, "--shard", "2/2"), 4, "a shard of an edited campaign",
           ["has shard 1/2 of another campaign running", "the same campaign"])
    with open(camp, "w") as f:
        f.write(original)
    if first.poll() is not None:
        fail("shard 1/2 ended before the refusals were checked: nothing was tested")
    expect(uvms(camp, "--out", out, "--shard", "2/2", "-j", "1"), 0, "shard 2/2 beside 1/2")
    first.communicate(timeout=300)
    if first.returncode != 0:
        fail(f"shard 1/2 exited {first.returncode}")
    expect(uvms(camp, "--out", out, "--merge"), 0, "the merge after both shards")
    dry = uvms(camp, "--shard", "2/3", "--dry-run")
    if dry.returncode != 0 or dry.stdout.splitlines()[:-1] != ["1.0  payload.mass_kg=1.0"] or \
            "1 run of shard 2/3 (4 in the plan)" not in dry.stdout:
        fail("--dry-run --shard 2/3 does not list the shard's one run")
    for bad in ("0/2", "3/2", "1/0", "1", "1/2x", "-1/2", "a/b", "1/100001", "1/ 2", "1/+2",
                " 1/2", "1/2/3"):
        expect(uvms(camp, "--out", out, "--shard", bad), 2, f"--shard {bad}", ["--shard needs I/N"])
    for clash in (["--merge", "--shard", "1/2"], ["--merge", "--plan-only"],
                  ["--dry-run", "--plan-only"], ["--merge", "--retry-failed"]):
        expect(uvms(camp, "--out", out, *clash), 2, " ".join(clash))
    print("shard locks ok")


def plan_only(camp, out, *extra, env=None, pass_fds=()):
    p = uvms(camp, "--out", out, "--plan-only", *extra, env=env, pass_fds=pass_fds)
    if p.returncode != 0:
        return p, None
    lines = p.stdout.splitlines()
    plan = json.loads(lines[0])
    if plan["runs"] != len(lines) - 1:
        fail(f"--plan-only's head line announces {plan['runs']} runs, {len(lines) - 1} follow")
    plan["runs"] = [json.loads(line) for line in lines[1:]]
    return p, plan


def run_by_hand(plan, entry):
    """Executes one run as its plan entry says (docs/CAMPAIGNS.md "How a run is executed")."""
    d = os.path.join(plan["out"], entry["dir"])
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "overrides.json"), "w") as f:
        f.write(entry["overrides_json"])
    with open(os.path.join(d, "run.out"), "wb") as log:
        return subprocess.run([plan["uvms"], *entry["argv"]], cwd=d, stdout=log,
                              stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                              timeout=120).returncode


def case_plan_only():
    camp = write_campaign("three.toml", range(3))
    ref, out = os.path.join(TMP, "ref"), os.path.join(TMP, "planned")
    expect(uvms(camp, "--out", ref, "-j", "2"), 0, "the reference campaign")
    _, plan = plan_only(camp, out)
    if plan is None:
        fail("--plan-only failed on a new DIR")
    if [r["state"] for r in plan["runs"]] != ["todo"] * 3 or plan["total"] != 3:
        fail(f"a new DIR's plan is not 3 runs to do: {plan}")
    if plan_ids(out) != [r["id"] for r in plan["runs"]] or os.listdir(os.path.join(out, "runs")):
        fail("--plan-only did not write plan.json with the plan's runs, or started a run")
    for entry in plan["runs"]:
        if run_by_hand(plan, entry) != 0:
            fail(f"run {entry['id']} executed from its plan entry failed")
    expect(uvms(camp, "--out", out, "--merge"), 0, "the merge of runs executed by hand")
    diffs = differences(ref, out)
    if diffs:
        fail("runs executed from the plan differ from the campaign's: " + "; ".join(diffs[:5]))
    # States follow DIR: a failed run is "failed" (kept) unless --retry-failed.
    summary = os.path.join(out, plan["runs"][1]["dir"], "summary.json")
    with open(summary) as f:
        s = json.load(f)
    s["status"], s["failure"] = "failed", "diverged"
    with open(summary, "w") as f:
        json.dump(s, f)
    states = [r["state"] for r in plan_only(camp, out)[1]["runs"]]
    retry = [r["state"] for r in plan_only(camp, out, "--retry-failed")[1]["runs"]]
    if states != ["done", "failed", "done"] or retry != ["done", "todo", "done"]:
        fail(f"states {states} and with --retry-failed {retry}")
    shard = plan_only(camp, out, "--shard", "2/2")[1]
    if [r["id"] for r in shard["runs"]] != [plan["runs"][1]["id"]] or shard["shard"] != {
            "index": 2, "count": 2}:
        fail(f"--plan-only --shard 2/2 lists {shard['runs']}")
    # The lock hand-over: a held lock is refused (exit 4) unless its descriptor is handed over.
    fd = os.open(os.path.join(out, ".campaign.lock"), os.O_RDWR | os.O_CREAT, 0o644)
    fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
    expect(plan_only(camp, out)[0], 4, "--plan-only on a DIR locked by another process")
    env = dict(os.environ, UVMS_CAMPAIGN_LOCK_FD=str(fd))
    p, handed = plan_only(camp, out, env=env, pass_fds=(fd,))
    if handed is None:
        fail(f"--plan-only with the lock handed over exited {p.returncode}")
    expect(uvms(camp, "--out", out, "--merge", env=env, pass_fds=(fd,)), 3,
           "a merge under the handed-over lock (one run failed)", ["2/3 runs finished"])
    other = os.open(camp, os.O_RDONLY)
    bad_env = dict(os.environ, UVMS_CAMPAIGN_LOCK_FD=str(other))
    expect(plan_only(camp, out, env=bad_env, pass_fds=(other,))[0], 2,
           "UVMS_CAMPAIGN_LOCK_FD naming another file")
    os.close(fd)
    os.close(other)
    print("plan-only ok")


def case_no_logs():
    camp = write_campaign("nolog.toml", range(2))
    logged, bare = os.path.join(TMP, "logged"), os.path.join(TMP, "bare")
    expect(uvms(camp, "--out", logged, "-j", "2"), 0, "the campaign with logs")
    expect(uvms(camp, "--out", bare, "-j", "2", "--no-logs"), 0, "the campaign with --no-logs")
    logs = [os.path.join(dp, f) for dp, _, fs in os.walk(bare) for f in fs if f.endswith(".lcmlog")]
    if logs:
        fail(f"--no-logs left logs: {logs}")
    # Only the logs, and run.out's line naming them, may differ.
    diffs = [d for d in differences(logged, bare)
             if not (d.startswith("runs/") and d.endswith(f"run.lcmlog: only in {logged}"))
             and not d.endswith("run.out: differs beyond the wall-clock fields")]
    if diffs:
        fail("--no-logs changed more than the logs: " + "; ".join(diffs[:5]))
    for r in os.listdir(os.path.join(bare, "runs")):
        with open(os.path.join(bare, "runs", r, "run.out")) as f:
            text = f.read()
        if not text.rstrip().endswith("./summary.json") or "lcmlog" in text:
            fail(f"run {r}'s run.out under --no-logs names a log or no summary: {text!r}")
    # A logged run redone without logs loses its old log (it would pass for the new run's).
    expect(uvms(camp, "--out", logged, "--force-new", "--no-logs"), 0, "--force-new --no-logs")
    left = [dp for dp, _, fs in os.walk(logged) if "run.lcmlog" in fs]
    if left:
        fail(f"runs redone with --no-logs kept their old logs: {left}")
    # uvms run --no-log over udpm (two processes: the plant process is told too).
    udpm = os.path.join(TMP, "udpm")
    p = subprocess.run([UVMS, "run", BASE, "--out", udpm, "--transport", "udpm", "--no-log",
                        "--set", "run.duration_s=0.6"], capture_output=True, text=True,
                       timeout=120)
    print("uvms run --transport udpm --no-log ->", p.returncode, p.stdout, p.stderr)
    if p.returncode != 0 or os.listdir(udpm) != ["summary.json"]:
        fail(f"uvms run --transport udpm --no-log: exit {p.returncode}, files {os.listdir(udpm)}")
    print("no-logs ok")


globals()["case_" + CASE]()
print("PASS", CASE)
