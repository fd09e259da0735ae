# SPDX-License-Identifier: Apache-2.0
"""`uvms campaign` end to end (issue 6): a 2 x 2 sweep of short runs expands, runs, resumes
after a real interruption without redoing finished runs, and yields the expected results rows;
a finished campaign extended by a seed and then by a sweep value runs only the new runs (ids
are stable, no directory is duplicated); [replicates] runs every unsteady run once per seed and
stagnant runs once; the paper campaigns have the documented run counts; plan.json and
results.json carry the provenance; bad campaign files fail before any run starts; a device or a
directory given as the campaign or its base is refused at once. Campaign integrity (issue 18):
a DIR of another campaign (another identity) is refused and --force-new re-runs it; a second
campaign on a DIR in use is refused with exit 4 and a crashed one leaves no stale lock; failed
runs are kept unless --retry-failed; progress reaches a pipe as it happens; --max-runs, an
overflowing product and a key on two axes are refused; an unwritable DIR is an error (exit 3).

Usage: test_campaign_e2e.py UVMS_EXE SOURCE_DIR CASE
       (CASE: resume | extend | replicates | paper_counts | provenance | bad_files |
              devices_and_directories_refused_promptly | identity_mismatch_refused |
              concurrent_campaign_refused | retry_failed | progress_through_a_pipe |
              run_limits | unwritable_out_is_an_error | interrupted_force_new |
              force_new_in_one_shard | base_pinned | foreign_summary_not_counted | logs_policy |
              run_names | run_files_synced | failed_sync_found | jobs_at_a_time)
       run_files_synced and failed_sync_found need UVMS_FSYNC_PROBE, the path of the
       tests/support/fsync_probe.c library (ctest sets it).
"""
import csv
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from campaign_testkit import (executed, fail, mark_summaries, plan_ids, redone,  # noqa: E402
                              wait_for, write_file)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

UVMS, SRC, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
BASE = os.path.join(SRC, "sil", "scenarios", "paper", "case_IV_stagnant.toml")
TMP = scratch_dir("uvms-campaign-")  # removed at exit (tests/support/scratch.py)


def write(name, text):
    return write_file(TMP, name, text)


TINY = f"""name = "tiny"
base = "{BASE}"
[set]
"run.duration_s" = 1.5
"trajectory.duration_s" = 1.5
"link.realtime_factor" = 4.0   # each run takes >= 0.37 s of wall time: room to interrupt
[[sweep]]
"control.case" = ["IV", "VII"]
[[sweep]]
"payload.mass_kg" = [0.0, 5.0]
"""


def case_resume():
    camp = write("tiny.toml", TINY)
    out = os.path.join(TMP, "out")
    runs = os.path.join(out, "runs")
    p = subprocess.Popen([UVMS, "campaign", camp, "--out", out, "-j", "1"],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    deadline = time.time() + 60
    done = []
    while time.time() < deadline and not done:
        if os.path.isdir(runs):
            done = [r for r in sorted(os.listdir(runs))
                    if os.path.exists(os.path.join(runs, r, "summary.json"))]
        time.sleep(0.02)
    p.send_signal(signal.SIGKILL)  # a hard interruption: no clean-up code runs
    p.wait()
    print(p.stdout.read())
    if not done:
        fail("no run finished before the interruption")
    time.sleep(0.5)  # the killed campaign's child got SIGTERM via PDEATHSIG
    # The run the kill interrupted writes a summary with failure "interrupted" (issue 15): it is
    # not finished, and the resumed campaign runs it again.
    finished = [r for r in sorted(os.listdir(runs))
                if os.path.exists(os.path.join(runs, r, "summary.json"))
                and json.load(open(os.path.join(runs, r, "summary.json")))["status"] == "finished"]
    if len(finished) >= 4:
        fail("the interruption came too late to test resuming")
    mtimes = {r: os.path.getmtime(os.path.join(runs, r, "summary.json")) for r in finished}
    print("finished before the interruption:", finished)

    p = subprocess.run([UVMS, "campaign", camp, "--out", out, "-j", "2"], capture_output=True,
                       text=True, timeout=120)
    print(p.stdout, p.stderr)
    if p.returncode != 0:
        fail(f"resumed campaign exited {p.returncode}")
    if f"4 runs ({len(finished)} already done)" not in p.stdout:
        fail("the resumed campaign did not report the finished runs as done")
    for r, t in mtimes.items():
        if os.path.getmtime(os.path.join(runs, r, "summary.json")) != t:
            fail(f"run {r} was redone")
    with open(os.path.join(out, "results.csv")) as f:
        rows = list(csv.DictReader(f))
    got = [(r["id"], r["control.case"], float(r["payload.mass_kg"]), r["status"]) for r in rows]
    # Ids: the axis labels (here the values) joined with "_", in Cartesian order.
    expected = [("IV_0.0", "IV", 0.0, "finished"), ("IV_5.0", "IV", 5.0, "finished"),
                ("VII_0.0", "VII", 0.0, "finished"), ("VII_5.0", "VII", 5.0, "finished")]
    if got != expected:
        fail(f"results.csv rows {got}, expected {expected}")
    with open(os.path.join(out, "results.json")) as f:
        res = json.load(f)
    if [r["ticks"] for r in res["runs"]] != [50] * 4:
        fail("results.json ticks are not 50 per run")
    # Each row carries its own run's summary, and the runs differ.
    for r in res["runs"]:
        with open(os.path.join(runs, r["id"], "summary.json")) as f:
            s = json.load(f)
        for k in ("thruster_energy_J", "mean_ee_error_m", "final_barycenter_m"):
            if r[k] != s[k]:
                fail(f"{r['id']}: results {k} = {r[k]} but its summary.json has {s[k]}")
    if len({r["thruster_energy_J"] for r in res["runs"]}) != 4:
        fail("the four runs have equal energies: the sweep did not reach the runs")
    print("resume ok; rows:", got)


def expect_error(name, text, needles):
    path = write(name, text)
    out = os.path.join(TMP, "out_" + name)
    p = subprocess.run([UVMS, "campaign", path, "--out", out], capture_output=True, text=True)
    print(name, "->", p.returncode, p.stderr.strip())
    if p.returncode != 1:
        fail(f"{name}: exit {p.returncode}, expected 1")
    for n in needles:
        if n not in p.stderr:
            fail(f"{name}: error does not mention {n!r}")
    if os.path.isdir(os.path.join(out, "runs")):
        fail(f"{name}: runs were started for an invalid campaign")


def case_bad_files():
    expect_error("unknown.toml", f'base = "{BASE}"\nsweeps = 3\n', ["unknown.toml:2", "sweeps"])
    expect_error("lengths.toml",
                 f'base = "{BASE}"\n[[sweep]]\n"control.case" = ["IV", "VII"]\n'
                 '"payload.mass_kg" = [1.0, 2.0, 3.0]\n',
                 ["lengths.toml:4", "payload.mass_kg", "vary together"])
    expect_error("badvalue.toml",
                 f'base = "{BASE}"\n[[sweep]]\n"payload.mass_kg" = [1.0, -2.0]\n',
                 ["run -2.0", "payload.mass_kg"])
    expect_error("nobase.toml", 'name = "x"\n', ["base"])
    expect_error("clash.toml",
                 f'base = "{BASE}"\n[[sweep]]\nlabels = ["a b", "a/b"]\n'
                 '"payload.mass_kg" = [1.0, 2.0]\n',
                 ["clash.toml", '"a_b"', "payload.mass_kg = 1.0", "payload.mass_kg = 2.0"])
    rep = f'base = "{BASE}"\n[replicates]\nkey = "run.seed"\n'  # [replicates] is line 2
    expect_error("rep_unknown.toml", rep + "values = [1]\nseed = 2\n",
                 ["rep_unknown.toml:5", "replicates.seed", "unknown key"])
    expect_error("rep_empty.toml", rep + "values = []\n",
                 ["rep_empty.toml:4", "replicates.values", "non-empty"])
    expect_error("rep_float.toml", rep + "values = [1, 2.5]\n",
                 ["rep_float.toml:4", "replicates.values", "integer"])
    expect_error("rep_dup.toml", rep + "values = [1, 2, 2]\n",
                 ["rep_dup.toml:4", "replicates.values", "more than once"])
    expect_error("rep_when.toml",
                 rep + 'values = [1]\nwhen = "environment.unsteady_flow.enabled"\n',
                 ["rep_when.toml", "replicates.when", "set neither", "case_IV_stagnant.toml"])


def case_devices_and_directories_refused_promptly():
    """`uvms campaign /dev/urandom` read without end, and a directory read as an empty file.
    Either one, as the campaign file or as its base scenario (read by the scenario check, or
    earlier for replicates.when), is refused at once: exit 1, naming the file and why."""
    for path, why in (("/dev/urandom", "not a regular file (a device"),
                      (TMP, "not a regular file (a directory")):
        bases = {"base": f'base = "{path}"\n',
                 "base_for_when": f'base = "{path}"\n[replicates]\nkey = "run.seed"\n'
                                  'values = [1]\nwhen = "environment.unsteady_flow.enabled"\n'}
        for kind in ("campaign", *bases):
            camp = path if kind == "campaign" else write(kind + ".toml", bases[kind])
            out = os.path.join(TMP, "out_refused")
            t0 = time.monotonic()
            p = subprocess.run([UVMS, "campaign", camp, "--out", out], capture_output=True,
                               text=True, timeout=30)
            took = time.monotonic() - t0
            print(kind, path, "->", p.returncode, f"{took:.2f} s", p.stderr.strip())
            if p.returncode != 1 or f"{path}: {why}" not in p.stderr:
                fail(f"{kind} {path}: exit {p.returncode}, expected 1 and {path}: {why}")
            if took > 5:
                fail(f"{kind} {path}: refused only after {took:.1f} s")
            if os.path.isdir(os.path.join(out, "runs")):
                fail(f"{kind} {path}: runs were started")


def run_campaign(path, out, *extra):
    p = subprocess.run([UVMS, "campaign", path, "--out", out, "-j", "2", *extra],
                       capture_output=True, text=True, timeout=300)
    print(p.stdout, p.stderr)
    if p.returncode != 0:
        fail(f"campaign {path} exited {p.returncode}")
    return p.stdout


FLOW = f"""name = "flow"
base = "{BASE}"
[set]
"run.duration_s" = 0.6
[[sweep]]
"control.case" = CASES
[[sweep]]
labels = ["stagnant", "unsteady"]
"environment.unsteady_flow.enabled" = [false, true]
[replicates]
key = "run.seed"
values = SEEDS
when = "environment.unsteady_flow.enabled"
"""


def flow_campaign(cases, seeds):
    return FLOW.replace("CASES", json.dumps(cases)).replace("SEEDS", json.dumps(seeds))


def expected_flow_ids(cases, seeds):
    return [i for c in cases
            for i in [f"{c}_stagnant"] + [f"{c}_unsteady_s{s}" for s in seeds]]


def case_extend():
    """A finished campaign gets one more seed, then one more sweep value: only new runs run."""
    camp = os.path.join(TMP, "flow.toml")
    out = os.path.join(TMP, "extend")
    runs = os.path.join(out, "runs")
    before = None
    for cases, seeds in [(["IV"], [1, 2]), (["IV"], [1, 2, 3]), (["IV", "VII"], [1, 2, 3])]:
        write("flow.toml", flow_campaign(cases, seeds))
        stdout = run_campaign(camp, out)
        want = expected_flow_ids(cases, seeds)
        done = len(before) if before else 0
        if f"{len(want)} runs ({done} already done)" not in stdout:
            fail(f"{cases} x {seeds}: expected {len(want)} runs with {done} already done")
        if plan_ids(out) != want:
            fail(f"plan ids {plan_ids(out)}, expected {want}")
        if sorted(os.listdir(runs)) != sorted(want):
            fail(f"run directories {sorted(os.listdir(runs))}, expected exactly {sorted(want)}")
        if redone(runs, before or {}):
            fail(f"runs {redone(runs, before)} were redone when the campaign was extended")
        new_ids = sorted(set(want) - set(before or {}))
        if executed(stdout) != new_ids:
            fail(f"the campaign ran {executed(stdout)}, expected only the new runs {new_ids}")
        with open(os.path.join(out, "results.json")) as f:
            rows = json.load(f)["runs"]
        if [r["id"] for r in rows] != want or any(r["status"] != "finished" for r in rows):
            fail("results.json rows are not the finished runs in plan order")
        before = mark_summaries(runs)
    print("extend ok:", sorted(before))


def case_replicates():
    """Unsteady runs once per seed (the seed reaches the run), stagnant runs once."""
    camp = write("rep.toml", flow_campaign(["VII"], [1, 2, 3]))
    out = os.path.join(TMP, "rep")
    run_campaign(camp, out)
    with open(os.path.join(out, "results.json")) as f:
        res = json.load(f)
    rows = {r["id"]: r for r in res["runs"]}
    want = expected_flow_ids(["VII"], [1, 2, 3])
    if list(rows) != want:
        fail(f"rows {list(rows)}, expected {want}")
    if res["replicates"] != {"key": "run.seed", "values": [1, 2, 3],
                             "when": "environment.unsteady_flow.enabled"}:
        fail(f"results.json replicates {res['replicates']}")
    if "run.seed" not in res["swept_keys"]:
        fail("run.seed is not among results.json's swept_keys")
    if "run.seed" in rows["VII_stagnant"]:
        fail("the stagnant run was given a seed")
    with open(os.path.join(out, "plan.json")) as f:
        plan = {r["id"]: r for r in json.load(f)["runs"]}
    for seed in (1, 2, 3):
        rid = f"VII_unsteady_s{seed}"
        if rows[rid]["run.seed"] != seed or plan[rid]["replicate"] != seed:
            fail(f"{rid}: run.seed {rows[rid].get('run.seed')}, plan {plan[rid].get('replicate')}")
        if plan[rid]["overrides"][-1] != f"run.seed={seed}":
            fail(f"{rid}: overrides {plan[rid]['overrides']} do not end with run.seed={seed}")
        if not rows[rid]["provenance"]["scenario_sets"].endswith(f"run.seed={seed}"):
            fail(f"{rid}: the run's own --set list does not end with its seed")
    if "replicate" in plan["VII_stagnant"]:
        fail("plan.json marks the stagnant run as a replicate")
    errors = {rows[f"VII_unsteady_s{s}"]["mean_ee_error_m"] for s in (1, 2, 3)}
    if len(errors) != 3:
        fail(f"the three seeds gave {len(errors)} distinct mean EE errors: the seed did not act")
    with open(os.path.join(out, "results.csv")) as f:
        csv_rows = {r["id"]: r for r in csv.DictReader(f)}
    if (csv_rows["VII_stagnant"]["run.seed"] != ""
            or csv_rows["VII_unsteady_s2"]["run.seed"] != "2"):
        fail("results.csv's run.seed column is wrong")
    print("replicates ok")


def case_paper_counts():
    """--dry-run of the paper campaigns (and the studies beside them): the run counts their
    header comments state."""
    counts = {"exp1_cases": 8 + 8 * 20, "exp2_payload": 20 + 10 * 20, "exp3_tracking": 2 + 2 * 20,
              "exp4_fidelity": 16 + 16 * 20, "exp5_travel": 20, "exp6_duration": 18,
              "exp7_energy_split": 10, "exp8_analytic": 14, "studies/exp9_friction": 7 * 6}
    for name, n in counts.items():
        folder = "" if "/" in name else "paper"
        path = os.path.join(SRC, "sil", "campaigns", folder, name + ".toml")
        p = subprocess.run([UVMS, "campaign", path, "--dry-run"], capture_output=True, text=True,
                           timeout=300)
        if p.returncode != 0:
            fail(f"{name}: --dry-run exited {p.returncode}: {p.stderr}")
        lines = p.stdout.splitlines()
        ids = [ln.split()[0] for ln in lines[:-1]]
        if f": {n} runs" not in lines[-1] or len(ids) != n or len(set(ids)) != n:
            fail(f"{name}: expected {n} distinct runs, got {len(set(ids))}: {lines[-1]}")
        for ln in lines[:-1]:
            unsteady = "environment.unsteady_flow.enabled=true" in ln
            seeded = re.search(r"_s(\d+)\s", ln + " ")
            seed_set = seeded and f"run.seed={int(seeded.group(1))}" in ln
            if unsteady != bool(seeded) or (seeded and not seed_set):
                fail(f"{name}: unsteady runs and only they carry a seed: {ln}")
        print(name, n, "runs ok")


PROV_KEYS = ["version", "git_commit", "build_preset", "build_type", "controller_precision",
             "campaign_sha256", "campaign_sets", "scenario_sha256"]


def case_provenance():
    camp = write("prov.toml", f'base = "{BASE}"\n[[sweep]]\n"payload.mass_kg" = [0.0, 5.0]\n')
    out = os.path.join(TMP, "prov")
    extra = ["run.duration_s=0.3", "link.timeout_s=2"]
    run_campaign(camp, out, *[x for e in extra for x in ("--set", e)])
    sha = {p: hashlib.sha256(open(p, "rb").read()).hexdigest() for p in (camp, BASE)}
    with open(os.path.join(out, "plan.json")) as f:
        plan = json.load(f)
    with open(os.path.join(out, "results.json")) as f:
        res = json.load(f)
    for name, doc in (("plan.json", plan), ("results.json", res)):
        prov = doc.get("provenance")
        if not isinstance(prov, dict) or list(prov) != PROV_KEYS:
            fail(f"{name} provenance keys {list(prov or {})}, expected {PROV_KEYS}")
        if prov["campaign_sha256"] != sha[camp] or prov["scenario_sha256"] != sha[BASE]:
            fail(f"{name}: hashes differ from hashlib's")
        if prov["campaign_sets"] != "\n".join(extra):
            fail(f"{name}: campaign_sets {prov['campaign_sets']!r}")
    overrides = {r["id"]: r["overrides"] for r in plan["runs"]}
    for row in res["runs"]:
        rp = row["provenance"]
        sets = "\n".join(overrides[row["id"]])
        if rp["scenario_sha256"] != sha[BASE] or rp["scenario_sets"] != sets:
            fail(f"{row['id']}: the run's provenance does not match its base and overrides")
        if rp["git_commit"] != res["provenance"]["git_commit"]:
            fail(f"{row['id']}: the run was built from another commit than the campaign")
    print("provenance ok:", json.dumps(res["provenance"], indent=1))


# ---------------------------------------------------------------------------------------------
# Campaign integrity (issue 18)

SHORT = ["--set", "run.duration_s=0.3"]  # the smallest runs: a few ticks each


def two_runs(name, base=BASE):
    return write(name, f'name = "two"\nbase = "{base}"\n[[sweep]]\n'
                       '"payload.mass_kg" = [0.0, 5.0]\n')


def campaign(path, out, *extra, timeout=300):
    p = subprocess.run([UVMS, "campaign", path, "--out", out, "-j", "2", *extra],
                       capture_output=True, text=True, timeout=timeout)
    print(" ".join(["campaign", os.path.basename(path), *extra]), "->", p.returncode)
    print(p.stdout, p.stderr)
    return p


def identity(out, name="plan.json"):
    with open(os.path.join(out, name)) as f:
        return json.load(f).get("identity")


def case_identity_mismatch_refused():
    """The identity (hash of the campaign bytes, base bytes, --sets, version) is in plan.json
    and results.json; a DIR of another identity (an edited base, another --set, runs without
    an identity) is refused with exit 1, naming both identities and what the old plan's
    provenance says differs, and nothing is touched; --force-new runs every run again under
    the new identity. A campaign file edited alone (how a campaign is extended) is the same
    campaign: accepted, with a note, its unchanged runs kept."""
    base = os.path.join(TMP, "base.toml")
    shutil.copyfile(BASE, base)
    camp = two_runs("ident.toml", base)
    out = os.path.join(TMP, "ident")
    runs = os.path.join(out, "runs")
    p = campaign(camp, out, *SHORT)
    if p.returncode != 0:
        fail(f"first campaign exited {p.returncode}")
    first = identity(out)
    if not re.fullmatch(r"[0-9a-f]{64}", first or "") or identity(out, "results.json") != first:
        fail(f"identities {first} / {identity(out, 'results.json')}: not one SHA-256 in hex")
    stamps = mark_summaries(runs)
    plan_bytes = open(os.path.join(out, "plan.json"), "rb").read()

    def refused(what, *extra, old=first, differs=()):
        """Returns the identity the refused campaign names as its own."""
        p = campaign(camp, out, *extra)
        if p.returncode != 1:
            fail(f"{what}: exit {p.returncode}, expected 1 (another campaign in DIR)")
        for n in ("holds another campaign", "--force-new", "another --out", "not recorded",
                  "base scenario file's bytes", "nothing was changed", old, *differs):
            if n not in p.stderr:
                fail(f"{what}: the refusal does not say {n!r}")
        m = re.search(r"this campaign's identity is ([0-9a-f]{64})", p.stderr)
        if not m or m.group(1) == first:
            fail(f"{what}: the refusal does not name a new identity")
        if open(os.path.join(out, "plan.json"), "rb").read() != plan_bytes:
            fail(f"{what}: plan.json was changed by a refused campaign")
        if redone(runs, stamps) or executed(p.stdout):
            fail(f"{what}: runs were redone by a refused campaign")
        return m.group(1)

    refused("another --set", *SHORT, "--set", "link.timeout_s=2",
            differs=["these differ: the --set overrides (campaign_sets"])
    # The campaign file alone edited: accepted as the same campaign, its runs kept.
    with open(camp, "a") as f:
        f.write("# a comment: other bytes, the same runs\n")
    p = campaign(camp, out, *SHORT)
    if p.returncode != 0 or "the campaign file changed since" not in p.stdout:
        fail("a campaign file edited alone was not accepted with a note")
    if "2 runs (2 already done)" not in p.stdout or redone(runs, stamps):
        fail("the runs of an edited campaign file were redone")
    if identity(out) in (None, first) or identity(out, "results.json") != identity(out):
        fail("plan.json / results.json do not carry the edited campaign's identity")
    two_runs("ident.toml", base)  # back to the first campaign file
    if campaign(camp, out, *SHORT).returncode != 0 or identity(out) != first:
        fail("the restored campaign is not the first campaign again")
    plan_bytes = open(os.path.join(out, "plan.json"), "rb").read()
    with open(base, "a") as f:
        f.write("# edited after the first campaign\n")
    edited = refused("edited base", *SHORT,
                     differs=["these differ: the base scenario file's bytes (scenario_sha256"])
    p = campaign(camp, out, *SHORT, "--force-new")
    if p.returncode != 0:
        fail(f"--force-new exited {p.returncode}")
    if f"held campaign {first}" not in p.stdout or "every run (2) is run again" not in p.stdout:
        fail("--force-new does not say that it replaces the campaign and runs every run again")
    if executed(p.stdout) != ["0.0", "5.0"] or sorted(redone(runs, stamps)) != ["0.0", "5.0"]:
        fail("--force-new did not run every run again")
    if identity(out) != edited or identity(out, "results.json") != edited:
        fail("plan.json / results.json do not carry the refused campaign's identity after "
             "--force-new")
    p = campaign(camp, out, *SHORT)  # the same campaign again: resumed, nothing to do
    if p.returncode != 0 or "2 runs (2 already done)" not in p.stdout:
        fail("the campaign of DIR's identity was not resumed")
    # Runs but no identity in plan.json: a campaign of another kind (an older uvms).
    with open(os.path.join(out, "plan.json")) as f:
        plan = json.load(f)
    del plan["identity"]
    with open(os.path.join(out, "plan.json"), "w") as f:
        json.dump(plan, f)
    plan_bytes = open(os.path.join(out, "plan.json"), "rb").read()
    stamps = mark_summaries(runs)
    refused("no identity", *SHORT, old="no identity")
    print("identity ok:", first, "->", edited)


def _rows(out):
    with open(os.path.join(out, "results.json")) as f:
        return json.load(f)


def _wait_generation(out, gen, proc):
    """Waits until DIR/plan.json has generation `gen` while `proc` runs."""
    deadline = time.monotonic() + 60
    while True:
        try:
            with open(os.path.join(out, "plan.json")) as f:
                if json.load(f).get("generation") == gen:
                    return
        except (OSError, ValueError):
            pass
        if proc.poll() is not None or time.monotonic() > deadline:
            fail(f"plan.json never reached generation {gen} (exit {proc.poll()})")
        time.sleep(0.01)


def case_interrupted_force_new():
    """An interrupted --force-new leaves no table of the old campaign beside the new plan:
    results.json and results.csv go before the new plan.json is written; the resumed campaign
    writes the new generation's table, every row of the new plan."""
    camp = slow_campaign("fnew.toml", 4)
    out = os.path.join(TMP, "fnew")
    if campaign(camp, out, "--set", "link.realtime_factor=0").returncode != 0:
        fail("the first campaign failed")
    old = _rows(out)
    p = subprocess.Popen([UVMS, "campaign", camp, "--out", out, "-j", "1", "--force-new"],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    _wait_generation(out, 1, p)
    p.send_signal(signal.SIGKILL)
    p.wait()
    for name in ("results.json", "results.csv"):
        if os.path.exists(os.path.join(out, name)):
            fail(f"an interrupted --force-new left the old {name} beside the new plan.json")
    p = campaign(camp, out)
    new = _rows(out)
    if p.returncode != 0 or new["generation"] != 1 or new["identity"] == old["identity"]:
        fail(f"the resumed campaign did not write the new generation's table ({p.returncode}, "
             f"generation {new.get('generation')})")
    sess = {r["id"]: r["session"] for r in old["runs"]}
    if any(r["session"] == sess[r["id"]] for r in new["runs"]):
        fail("a run of the old generation is in the new table")
    print("interrupted --force-new ok")


def case_force_new_in_one_shard():
    """--force-new in one shard starts a new generation: the other shards' runs of the old
    campaign stop counting; --merge refuses, naming them; once their shard has run again, the
    merged table holds only runs of the new base."""
    base = os.path.join(TMP, "shard_base.toml")
    shutil.copyfile(BASE, base)
    camp = two_runs("shardfn.toml", base)
    out = os.path.join(TMP, "shardfn")
    for i in (1, 2):
        if campaign(camp, out, *SHORT, "--shard", f"{i}/2").returncode != 0:
            fail(f"shard {i}/2 failed")
    if campaign(camp, out, *SHORT, "--merge").returncode != 0:
        fail("the first merge failed")
    with open(base, "a") as f:
        f.write("# the base edited\n")
    if campaign(camp, out, *SHORT, "--shard", "1/2", "--force-new").returncode != 0:
        fail("--force-new in shard 1/2 failed")
    p = campaign(camp, out, *SHORT, "--merge")
    if p.returncode != 3 or "5.0" not in p.stderr or "another run" not in p.stderr:
        fail(f"the merge kept shard 2's run of the old campaign (exit {p.returncode})")
    if os.path.exists(os.path.join(out, "results.json")):
        fail("the old table stayed beside the new plan")
    if campaign(camp, out, *SHORT, "--shard", "2/2").returncode != 0:
        fail("shard 2/2 again failed")
    if campaign(camp, out, *SHORT, "--merge").returncode != 0:
        fail("the merge of the new generation failed")
    want = hashlib.sha256(open(base, "rb").read()).hexdigest()
    shas = {r["provenance"]["scenario_sha256"] for r in _rows(out)["runs"]}
    if shas != {want}:
        fail(f"the merged rows come from bases {shas}, the plan's is {want}")
    print("--force-new in one shard ok")


def case_base_pinned():
    """Runs read the base scenario's bytes as the campaign read them before its first run (a
    copy in DIR/inputs), never the live file: a base edited mid-campaign changes no row; uvms
    run refuses a scenario whose bytes are not --scenario-sha256's."""
    base = os.path.join(TMP, "pinned_base.toml")
    shutil.copyfile(BASE, base)
    original = open(base, "rb").read()
    camp = write("pinned.toml", open(slow_campaign("x.toml", 4)).read().replace(BASE, base))
    out = os.path.join(TMP, "pinned")
    p = subprocess.Popen([UVMS, "campaign", camp, "--out", out, "-j", "1"],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wait_for(os.path.join(out, "runs", "0.0", "summary.json"), p)
    with open(base, "a") as f:
        f.write('[payload]\nmass_kg = 3.0\n')
    p.wait(timeout=120)
    print(p.stdout.read())
    want = hashlib.sha256(original).hexdigest()
    rows = _rows(out)["runs"]
    shas = {r["provenance"]["scenario_sha256"] for r in rows}
    if p.returncode != 0 or shas != {want}:
        fail(f"the runs read other bases than the pinned one: {shas} (exit {p.returncode})")
    with open(os.path.join(out, "plan.json")) as f:
        pinned = os.path.join(out, json.load(f)["inputs"]["base"]["path"])
    if open(pinned, "rb").read() != original:
        fail("DIR/inputs does not hold the base's bytes as first read")
    q = subprocess.run([UVMS, "run", base, "--transport", "memq", "--no-log", "--out",
                        os.path.join(TMP, "pinned_run"), "--scenario-sha256", want],
                       capture_output=True, text=True)
    if q.returncode != 1 or want not in q.stderr or "nothing was run" not in q.stderr:
        fail(f"uvms run ran a scenario whose bytes are not --scenario-sha256's ({q.returncode}: "
             f"{q.stderr.strip()})")
    print("base pinned ok")


def _torn_file_runs_again(camp, out, run_id, name):
    """Cuts run `run_id`'s file `name` to half, then to nothing, then fills it with NUL bytes,
    as a system crash can leave a file written without an fsync; each time the campaign must
    run that run again, and only it."""
    path = os.path.join(out, "runs", run_id, name)
    for damage in ("cut to 50 %", "cut to 0 %", "filled with NUL bytes"):
        with open(path, "rb") as f:
            text = f.read()
        with open(path, "wb") as f:
            f.write(text[:len(text) // 2] if "50" in damage else
                    b"" if "0 %" in damage else bytes(len(text)))
        p = campaign(camp, out, *SHORT)
        if p.returncode != 0 or executed(p.stdout) != [run_id]:
            fail(f"a run whose {name} was {damage} was not run again ({executed(p.stdout)})")


def case_foreign_summary_not_counted():
    """A run counts only when its summary's session, scenario hash, overrides and version are
    the plan's: a summary copied from another run, or from an older uvms campaign's DIR, is
    redone, and a DIR written before pinned inputs is refused with what to do."""
    camp = two_runs("foreign.toml")
    out = os.path.join(TMP, "foreign")
    if campaign(camp, out, *SHORT).returncode != 0:
        fail("the campaign failed")
    runs = os.path.join(out, "runs")
    shutil.copyfile(os.path.join(runs, "0.0", "summary.json"),
                    os.path.join(runs, "5.0", "summary.json"))
    p = campaign(camp, out, *SHORT)
    if p.returncode != 0 or executed(p.stdout) != ["5.0"]:
        fail(f"a summary of another run was counted as done ({executed(p.stdout)})")
    # overrides.json is written in place, not atomically (campaign_exec.cpp PrepareRunDir), which
    # is safe because one torn by a crash (cut short, or left empty) beside an intact summary
    # makes its run run again: that premise is what this checks.
    _torn_file_runs_again(camp, out, "0.0", "overrides.json")
    with open(os.path.join(out, "plan.json")) as f:
        plan = json.load(f)
    del plan["format"]
    with open(os.path.join(out, "plan.json"), "w") as f:
        json.dump(plan, f)
    p = campaign(camp, out, *SHORT)
    if p.returncode != 1 or "older uvms campaign" not in p.stderr or "--force-new" not in p.stderr:
        fail("a DIR of an older uvms campaign was not refused with what to do")
    if campaign(camp, out, *SHORT, "--force-new").returncode != 0:
        fail("--force-new on an older DIR failed")
    print("foreign summaries ok")


def _probed(args, log, **fail):
    """Runs args with tests/support/fsync_probe.c preloaded (UVMS_FSYNC_PROBE, set by ctest),
    recording into `log`, with the probe's injected failures `fail` (e.g.
    UVMS_FSYNC_PROBE_FAIL_SYNCFS="1"); returns the process and the recorded (call, path) pairs."""
    preload = " ".join(filter(None, [os.environ["UVMS_FSYNC_PROBE"], os.environ.get("LD_PRELOAD")]))
    env = dict(os.environ, LD_PRELOAD=preload, UVMS_FSYNC_PROBE_LOG=log, **fail)
    # An ASan build's runtime must otherwise come first among the loaded libraries.
    env["ASAN_OPTIONS"] = ":".join(filter(None, [os.environ.get("ASAN_OPTIONS"),
                                                 "verify_asan_link_order=0"]))
    p = subprocess.run(args, capture_output=True, text=True, timeout=300, env=env)
    print(" ".join(os.path.basename(a) for a in args[:2]), "->", p.returncode, p.stderr.strip())
    calls = []
    if os.path.exists(log):
        with open(log) as f:
            calls = [tuple(line.rstrip("\n").split(" ", 1)) for line in f]
    return p, calls


def _summary_fsyncs(calls, under):
    """The fsyncs of summary.json's temporaries under directory `under`."""
    under = os.path.realpath(under) + os.sep  # the probe records resolved paths
    return [c for c in calls if c[0] == "fsync" and c[1].startswith(under)
            and os.path.basename(c[1]).startswith("summary.json.tmp.")]


def case_run_files_synced():
    """What is made durable, recorded by an LD_PRELOAD probe: `uvms run` fsyncs its summary
    before renaming it into place (memq and udpm), and with --no-summary-fsync does not (the
    summary is still written whole); a campaign's runs write theirs without an fsync, each
    still fsyncs its log, and the campaign calls syncfs on DIR/runs once after its runs, before
    its results. A summary a crash left torn or empty is no summary: its run runs again (the
    premise of the unsynced summaries). (This machine: Linux 5.8 or later, not FUSE.)"""
    for transport in ("memq", "udpm"):
        for flag in ((), ("--no-summary-fsync",)):
            out = os.path.join(TMP, f"synced_{transport}_{len(flag)}")
            p, calls = _probed([UVMS, "run", BASE, "--transport", transport, "--no-log", "--out",
                                out, "--set", "run.duration_s=0.3", *flag],
                               os.path.join(TMP, f"probe_{transport}_{len(flag)}.log"))
            with open(os.path.join(out, "summary.json")) as f:
                status = json.load(f)["status"]
            synced = _summary_fsyncs(calls, out)
            if p.returncode != 0 or status != "finished" or len(synced) != (0 if flag else 1):
                fail(f"uvms run --transport {transport} {' '.join(flag)}: exit {p.returncode}, "
                     f"status {status}, {len(synced)} fsync(s) of the summary: {calls}")
    camp = two_runs("synced.toml")
    out = os.path.join(TMP, "synced_campaign")
    p, calls = _probed([UVMS, "campaign", camp, "--out", out, "-j", "2", *SHORT],
                       os.path.join(TMP, "probe_campaign.log"))
    syncfs = [i for i, c in enumerate(calls) if c[0] == "syncfs"]
    results = [i for i, c in enumerate(calls)
               if os.path.basename(c[1]).startswith("results.csv.tmp.")]
    logs = [c for c in calls if c[0] == "fsync" and c[1].endswith(os.sep + "run.lcmlog")]
    if (p.returncode != 0 or _summary_fsyncs(calls, out) or len(syncfs) != 1
            or calls[syncfs[0]][1] != os.path.realpath(os.path.join(out, "runs"))
            or not results or results[0] < syncfs[0] or len(logs) != 2):
        fail(f"the campaign's runs and DIR were not synced as designed (exit {p.returncode}): "
             f"{calls}")
    _torn_file_runs_again(camp, out, "5.0", "summary.json")
    print("run files synced ok")


def case_failed_sync_found():
    """When the campaign's syncfs reports a write-back error (injected by the fsync probe), each
    summary of the campaign is fsync'd alone: an error in none of them (another file's) is a
    note and the results are written; a summary whose fsync fails is removed, the campaign
    stops without results (exit 3) naming how many, and the next campaign runs that run again,
    and only it. --merge syncs the same way before it writes results."""
    camp = two_runs("failsync.toml")
    out = os.path.join(TMP, "failsync")
    args = [UVMS, "campaign", camp, "--out", out, "-j", "2", *SHORT]
    p, calls = _probed(args, os.path.join(TMP, "failsync_1.log"), UVMS_FSYNC_PROBE_FAIL_SYNCFS="1")
    if (p.returncode != 0 or "reported a write-back error" not in p.stdout
            or len(_summary_fsyncs(calls, "/")) != 0
            or len([c for c in calls if c[0] == "fsync" and c[1].endswith("summary.json")]) != 2
            or not os.path.exists(os.path.join(out, "results.csv"))):
        fail(f"a syncfs error in no summary: exit {p.returncode}, {p.stdout} {p.stderr} {calls}")
    p, calls = _probed(args + ["--force-new"], os.path.join(TMP, "failsync_2.log"),
                       UVMS_FSYNC_PROBE_FAIL_SYNCFS="1",
                       UVMS_FSYNC_PROBE_FAIL_FSYNC=os.path.join("5.0", "summary.json"))
    if (p.returncode != 3 or "1 of 2 runs' summaries could not be written to disk" not in p.stderr
            or "results not written" not in p.stderr
            or os.path.exists(os.path.join(out, "runs", "5.0", "summary.json"))
            or not os.path.exists(os.path.join(out, "runs", "0.0", "summary.json"))
            or os.path.exists(os.path.join(out, "results.csv"))):
        fail(f"a summary's failed write: exit {p.returncode}, {p.stdout} {p.stderr}")
    q = campaign(camp, out, *SHORT)
    if q.returncode != 0 or executed(q.stdout) != ["5.0"]:
        fail(f"the run whose summary was lost was not run again ({executed(q.stdout)})")
    m, _ = _probed([UVMS, "campaign", camp, "--out", out, "--merge", *SHORT],
                   os.path.join(TMP, "failsync_3.log"), UVMS_FSYNC_PROBE_FAIL_SYNCFS="1",
                   UVMS_FSYNC_PROBE_FAIL_FSYNC=os.path.join("0.0", "summary.json"))
    if (m.returncode != 3 or "--merge: 1 of 2 runs' summaries" not in m.stderr
            or os.path.exists(os.path.join(out, "runs", "0.0", "summary.json"))):
        fail(f"--merge with a summary's failed write: exit {m.returncode}, {m.stderr}")
    print("failed sync found ok")


def slow_campaign(name, n):
    """n runs of >= 0.37 s wall time each (1.5 s simulated at 4x real time)."""
    masses = ", ".join(f"{m}.0" for m in range(n))
    return write(name, f'name = "slow"\nbase = "{BASE}"\n[set]\n"run.duration_s" = 1.5\n'
                       '"trajectory.duration_s" = 1.5\n"link.realtime_factor" = 4.0\n'
                       f'[[sweep]]\n"payload.mass_kg" = [{masses}]\n')


def _most_at_once(out, slack_s=0.05):
    """The largest number of a campaign's runs that ran at the same time, from each summary's
    end (its file's modification time) and wall_time_s; overlaps under slack_s are not
    counted."""
    spans = []
    for d in os.listdir(os.path.join(out, "runs")):
        path = os.path.join(out, "runs", d, "summary.json")
        with open(path) as f:
            wall_s = json.load(f)["wall_time_s"]
        end_ns = os.stat(path).st_mtime_ns
        if end_ns % 1_000_000_000 == 0:
            print(f"SKIP: {path} has a whole-second time stamp (a coarse file system)")
            sys.exit(0)
        spans.append((end_ns * 1e-9 - wall_s + slack_s, end_ns * 1e-9))
    return max(sum(1 for s, e in spans if s < t <= e) for _, t in spans)


def case_jobs_at_a_time():
    """-j N runs N runs at a time, never more and not fewer: four runs of at least 0.37 s each
    run one at a time with -j 1, two at a time with -j 2."""
    camp = slow_campaign("jobs.toml", 4)
    for jobs in (1, 2):
        out = os.path.join(TMP, f"jobs_{jobs}")
        p = subprocess.run([UVMS, "campaign", camp, "--out", out, "-j", str(jobs)],
                           capture_output=True, text=True, timeout=120)
        most = _most_at_once(out) if p.returncode == 0 else None
        print(f"-j {jobs}: exit {p.returncode}, at most {most} at once")
        if most != jobs:
            fail(f"-j {jobs} ran up to {most} runs at once (exit {p.returncode}): {p.stderr}")
    print("jobs at a time ok")


def case_concurrent_campaign_refused():
    """While a campaign runs in DIR a second one is refused at once (exit 4, naming the lock
    and the first one's pid) and changes nothing; --dry-run takes no lock; the first finishes;
    the lock is gone with the process, also after a SIGKILL."""
    camp = slow_campaign("slow.toml", 3)
    out = os.path.join(TMP, "locked")
    args = [UVMS, "campaign", camp, "--out", out, "-j", "1"]
    first = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wait_for(os.path.join(out, "plan.json"), first)
    plan_stat = os.stat(os.path.join(out, "plan.json"))
    t0 = time.monotonic()
    second = subprocess.run(args, capture_output=True, text=True, timeout=30)
    took = time.monotonic() - t0
    print("second ->", second.returncode, f"{took:.2f} s", second.stdout, second.stderr)
    if second.returncode != 4:
        fail(f"a second campaign on a DIR in use exited {second.returncode}, expected 4")
    if first.poll() is not None:
        fail("the first campaign ended before the second was refused: nothing was tested")
    for n in ("in use by another campaign", f"(process {first.pid} on ", ".campaign.lock",
              "another --out"):
        if n not in second.stderr:
            fail(f"the refusal does not say {n!r}")
    if took > 5:
        fail(f"the second campaign was refused only after {took:.1f} s")
    if second.stdout or os.stat(os.path.join(out, "plan.json")) != plan_stat:
        fail("the refused campaign started or wrote something")
    dry = subprocess.run(args + ["--dry-run"], capture_output=True, text=True, timeout=30)
    if dry.returncode != 0:
        fail(f"--dry-run on a DIR in use exited {dry.returncode}: {dry.stderr}")
    stdout, stderr = first.communicate(timeout=120)
    print(stdout, stderr)
    if first.returncode != 0 or len(executed(stdout)) != 3:
        fail(f"the first campaign exited {first.returncode} or did not run its 3 runs")
    p = campaign(camp, out)
    if p.returncode != 0 or "3 runs (3 already done)" not in p.stdout:
        fail("after the first campaign ended, DIR is still locked")
    # A crash: the kernel drops the lock with the process, no stale lock is left behind.
    crashed = subprocess.Popen(args + ["--force-new"], stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
    wait_for(os.path.join(out, "runs", "0.0", "run.out"), crashed)
    crashed.kill()
    crashed.wait()
    time.sleep(0.5)  # its run got SIGTERM (PDEATHSIG) and writes an interrupted summary
    p = campaign(camp, out)
    if p.returncode != 0:
        fail(f"after a SIGKILLed campaign the next one exited {p.returncode}: stale lock?")
    print("lock ok")


def case_retry_failed():
    """A failed run (here: its summary.json made a failed one, as a diverged run writes it) is
    kept on resume, its row failed and exit 3; --retry-failed runs it, and only it, again."""
    camp = two_runs("retry.toml")
    out = os.path.join(TMP, "retry")
    runs = os.path.join(out, "runs")
    if campaign(camp, out, *SHORT).returncode != 0:
        fail("first campaign failed")
    path = os.path.join(runs, "5.0", "summary.json")
    with open(path) as f:
        s = json.load(f)
    s.update(status="failed", failure="diverged", reason="test: a run that failed")
    with open(path, "w") as f:
        json.dump(s, f)
    stamps = mark_summaries(runs)
    p = campaign(camp, out, *SHORT)
    if p.returncode != 3:
        fail(f"a campaign with a kept failed run exited {p.returncode}, expected 3")
    if executed(p.stdout) or redone(runs, stamps):
        fail(f"the resumed campaign ran {executed(p.stdout)} without --retry-failed")
    if "1 of the done runs failed and is kept" not in p.stdout or "--retry-failed" not in p.stdout:
        fail("the kept failed run is not reported")
    with open(os.path.join(out, "results.json")) as f:
        rows = {r["id"]: r for r in json.load(f)["runs"]}
    if rows["5.0"]["status"] != "failed" or rows["5.0"]["reason"] != "test: a run that failed":
        fail("the kept failed run's row is not its failed summary")
    p = campaign(camp, out, *SHORT, "--retry-failed")
    if p.returncode != 0:
        fail(f"--retry-failed exited {p.returncode}")
    if executed(p.stdout) != ["5.0"] or redone(runs, stamps) != ["5.0"]:
        fail(f"--retry-failed ran {executed(p.stdout)}, expected only the failed run 5.0")
    with open(path) as f:
        if json.load(f)["status"] != "finished":
            fail("the retried run did not finish")
    print("retry ok")


def logged(out):
    """The ids of the runs of DIR that have a run.lcmlog."""
    runs = os.path.join(out, "runs")
    return sorted(r for r in os.listdir(runs) if os.path.exists(os.path.join(runs, r, "run.lcmlog")))


def case_logs_policy():
    """--logs: failed keeps only a failed run's log; IDs (a pattern) keep those and the failed;
    none writes none (--no-logs the same); a resume without --logs keeps the done runs as they
    are; a later --logs naming a run kept without its log runs it again, and its log is what
    --logs all writes; a pattern that names no run, an
    empty id and two different policies are refused before anything is written."""
    camp = write("logs.toml", 'name = "logs"\nbase = "' + BASE + '"\n[[sweep]]\n'
                 '"payload.mass_kg" = [0.0, 2.0, 5.0]\n[[sweep]]\n'
                 '"verdict.max_ee_error_m" = [1.0, 1e-9]\nlabels = ["ok", "strict"]\n')
    out = os.path.join(TMP, "logs_failed")
    p = campaign(camp, out, *SHORT, "--logs", "failed")
    strict = sorted(i for i in plan_ids(out) if i.endswith("strict"))
    if p.returncode != 3 or logged(out) != strict or "logs failed" not in p.stdout:
        fail(f"--logs failed: exit {p.returncode}, logs of {logged(out)}; expected 3, {strict}")
    out = os.path.join(TMP, "logs_ids")
    p = campaign(camp, out, *SHORT, "--logs", "0.0_*")
    want = sorted(set(strict) | {"0.0_ok"})
    if p.returncode != 3 or logged(out) != want:
        fail(f"--logs 0.0_*: logs of {logged(out)}, expected {want}")
    for flag in (["--logs", "none"], ["--no-logs"]):
        out = os.path.join(TMP, "logs_none" + flag[-1])
        campaign(camp, out, *SHORT, *flag)
        if logged(out):
            fail(f"{' '.join(flag)}: logs of {logged(out)}")
    # Resumed without --logs, the done runs are kept as they are (no log is made).
    p = campaign(camp, out, *SHORT)
    if executed(p.stdout) or logged(out):
        fail(f"a resume without --logs ran {executed(p.stdout)}, logs of {logged(out)}")
    # The log of a run kept without one: asked for later, the run runs again and writes it,
    # byte for byte the log of the same run in a campaign that kept every log.
    p = campaign(camp, out, *SHORT, "--logs", "2.0_ok")
    if executed(p.stdout) != ["2.0_ok"] or logged(out) != ["2.0_ok"]:
        fail(f"--logs 2.0_ok after --no-logs ran {executed(p.stdout)}, logs of {logged(out)}")
    full = os.path.join(TMP, "logs_all")
    campaign(camp, full, *SHORT)
    if logged(full) != sorted(plan_ids(full)):
        fail(f"--logs all (the default): logs of {logged(full)}")
    with open(os.path.join(out, "runs", "2.0_ok", "run.lcmlog"), "rb") as a, \
         open(os.path.join(full, "runs", "2.0_ok", "run.lcmlog"), "rb") as b:
        if a.read() != b.read():
            fail("the log written later differs from the one the full campaign kept")
    for args, needle in ((["--logs", "9.0_*"], "9.0_* names no run of logs"),
                         (["--logs", "a,,b"], "an empty run id"),
                         (["--logs", "failed", "--no-logs"], "--logs given twice")):
        bad = os.path.join(TMP, "logs_bad")
        p = campaign(camp, bad, *SHORT, *args)
        if p.returncode not in (1, 2) or needle not in p.stderr or os.path.exists(bad):
            fail(f"{' '.join(args)}: exit {p.returncode}, stderr {p.stderr!r}; expected "
                 f"{needle!r} and nothing written")
    print("logs policy ok")


def case_run_names():
    """A campaign names each run <campaign>/<run id> in its summary.json (not the base
    scenario's name); `uvms run --name` sets it, and without it the scenario's name stays."""
    camp = two_runs("names.toml")
    out = os.path.join(TMP, "names")
    if campaign(camp, out, *SHORT).returncode != 0:
        fail("the campaign failed")
    names = {}
    for rid in plan_ids(out):
        with open(os.path.join(out, "runs", rid, "summary.json")) as f:
            names[rid] = json.load(f)["name"]
    if names != {rid: f"two/{rid}" for rid in names}:
        fail(f"summary names {names}, expected two/<run id>")
    for k, (extra, want) in enumerate(((["--name", "my run"], "my run"),
                                       (["--name", "my run", "--transport", "udpm"], "my run"),
                                       (["--transport", "memq"], "case_IV_stagnant"))):
        d = os.path.join(TMP, f"named{k}")
        p = subprocess.run([UVMS, "run", BASE, "--out", d, "--set", "run.duration_s=0.3",
                            *(extra if "--transport" in extra else extra + ["--transport", "memq"])],
                           capture_output=True, text=True, timeout=60)
        with open(os.path.join(d, "summary.json")) as f:
            got = json.load(f)["name"]
        if p.returncode != 0 or got != want or f"uvms run: {want}:" not in p.stdout:
            fail(f"uvms run {' '.join(extra)}: exit {p.returncode}, name {got!r}, expected "
                 f"{want!r} ({p.stdout.strip()[:120]})")
    print("run names ok")


def case_progress_through_a_pipe():
    """With stdout a pipe, the header and each progress line arrive as they happen, not when
    the campaign ends: both are read before the last run has even been written."""
    camp = slow_campaign("pipe.toml", 3)
    out = os.path.join(TMP, "pipe")
    last = os.path.join(out, "runs", "2.0", "summary.json")
    p = subprocess.Popen([UVMS, "campaign", camp, "--out", out, "-j", "1"],
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1)
    header = p.stdout.readline()
    header_early = not os.path.exists(last)
    progress = p.stdout.readline()
    progress_early = not os.path.exists(last) and p.poll() is None
    rest = p.stdout.read()
    p.wait()
    print(header, progress, rest)
    if p.returncode != 0:
        fail(f"campaign exited {p.returncode}")
    if not header.startswith("uvms campaign: slow: 3 runs"):
        fail(f"first line {header!r} is not the header")
    if not re.match(r"\[1/3\] elapsed .* finished$", progress.strip()):
        fail(f"second line {progress!r} is not the first progress line")
    if not (header_early and progress_early):
        fail("the header or the first progress line reached the pipe only at the end")
    print("progress ok")


def case_run_limits():
    """--max-runs (usage errors exit 2), a product past size_t, a key on two axes: exit 1,
    refused before any run, promptly."""
    camp = write("limit.toml", TINY)  # 2 x 2 runs
    for n in ("0", "-1", "x", "", "3.5", "99999999999999999999999"):
        p = subprocess.run([UVMS, "campaign", camp, "--dry-run", "--max-runs", n],
                           capture_output=True, text=True, timeout=30)
        if p.returncode != 2 or "--max-runs" not in p.stderr:
            fail(f"--max-runs {n!r}: exit {p.returncode}, expected 2 naming --max-runs")
    out = os.path.join(TMP, "out_limit")
    p = subprocess.run([UVMS, "campaign", camp, "--out", out, "--max-runs", "3"],
                       capture_output=True, text=True, timeout=30)
    print(p.returncode, p.stderr)
    if p.returncode != 1 or "4 runs" not in p.stderr or "--max-runs" not in p.stderr:
        fail(f"4 runs over --max-runs 3: exit {p.returncode}, expected 1 naming 4 runs")
    if os.path.exists(out):
        fail("a campaign over --max-runs wrote its --out")
    p = subprocess.run([UVMS, "campaign", camp, "--dry-run", "--max-runs", "4"],
                       capture_output=True, text=True, timeout=30)
    if p.returncode != 0 or ": 4 runs" not in p.stdout:
        fail("4 runs within --max-runs 4 refused")
    # Five axes of 10000 values: 10^20 runs, more than a 64-bit size_t counts.
    values = "[" + ", ".join(str(i) for i in range(10000)) + "]"
    axes = "".join(f'[[sweep]]\n"payload.k{a}" = {values}\n' for a in range(5))
    huge = write("huge.toml", f'base = "{BASE}"\n' + axes)
    t0 = time.monotonic()
    p = subprocess.run([UVMS, "campaign", huge, "--out", out], capture_output=True, text=True,
                       timeout=60)
    took = time.monotonic() - t0
    print("huge ->", p.returncode, f"{took:.2f} s", p.stderr[:300])
    if p.returncode != 1 or "overflow" not in p.stderr or took > 10:
        fail(f"an overflowing campaign: exit {p.returncode} after {took:.1f} s, expected 1 "
             "saying overflow at once")
    dup = write("dup.toml", f'base = "{BASE}"\n[[sweep]]\n"payload.mass_kg" = [0.0, 1.0]\n'
                            '[[sweep]]\n"payload.mass_kg" = [2.0, 3.0]\n')
    p = subprocess.run([UVMS, "campaign", dup, "--out", out], capture_output=True, text=True,
                       timeout=30)
    print("dup ->", p.returncode, p.stderr)
    if (p.returncode != 1 or "payload.mass_kg" not in p.stderr
            or "two [[sweep]] axes" not in p.stderr):
        fail(f"a key on two axes: exit {p.returncode}, expected 1 naming the key and the axes")
    if os.path.exists(out):
        fail("a refused campaign wrote its --out")
    print("limits ok")


def case_unwritable_out_is_an_error():
    """A run directory that cannot be created stops the campaign with exit 3 naming the path
    and the cause (no run silently skipped, no results); so does a read-only --out."""
    camp = two_runs("unwritable.toml")
    out = os.path.join(TMP, "blocked")
    os.makedirs(os.path.join(out, "runs"))
    with open(os.path.join(out, "runs", "0.0"), "w") as f:
        f.write("a file where run 0.0's directory goes\n")
    p = campaign(camp, out, *SHORT)
    blocked = os.path.join(out, "runs", "0.0")
    if p.returncode != 3:
        fail(f"a run directory that cannot be created: exit {p.returncode}, expected 3")
    for n in (f"cannot create the run directory {blocked}: ", "the campaign stopped"):
        if n not in p.stderr:
            fail(f"the error does not say {n!r}")
    if os.path.exists(os.path.join(out, "results.csv")):
        fail("results were written for a campaign that stopped")
    # A read-only --out: root writes through 0555 directories, so as root a read-only tmpfs.
    ro = os.path.join(TMP, "ro")
    os.makedirs(ro)
    mounted = False
    if os.geteuid() == 0:
        m = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=1m,ro", "tmpfs", ro],
                           capture_output=True, text=True)
        if m.returncode != 0:
            print("SKIP read-only --out: cannot mount a tmpfs:", m.stderr.strip())
            return
        mounted, cause = True, "Read-only file system"
    else:
        os.chmod(ro, 0o555)
        cause = "Permission denied"
    try:
        for what, out in (("a new --out", os.path.join(ro, "new")), ("the --out itself", ro)):
            p = campaign(camp, out, *SHORT)
            if p.returncode != 3 or cause not in p.stderr or out not in p.stderr:
                fail(f"{what} on a read-only directory: exit {p.returncode}, expected 3 naming "
                     f"{out} and {cause!r}")
    finally:
        if mounted:
            subprocess.run(["umount", ro], check=True)
    print("unwritable ok")


globals()["case_" + CASE]()
print("PASS", CASE)
