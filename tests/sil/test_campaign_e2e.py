# SPDX-License-Identifier: Apache-2.0
"""`uvms campaign` end to end (issue 6): a 2 x 2 sweep of short runs expands, runs, resumes
after a real interruption without redoing finished runs, and yields the expected results rows;
a finished campaign extended by a seed and then by a sweep value runs only the new runs (ids
are stable, no directory is duplicated); [replicates] runs every unsteady run once per seed and
stagnant runs once; the paper campaigns have the documented run counts; plan.json and
results.json carry the provenance; bad campaign files fail before any run starts; a device or a
directory given as the campaign or its base is refused at once.

Usage: test_campaign_e2e.py UVMS_EXE SOURCE_DIR CASE
       (CASE: resume | extend | replicates | paper_counts | provenance | bad_files |
              devices_and_directories_refused_promptly)
"""
import csv
import hashlib
import json
import os
import re
import signal
import subprocess
import sys
import tempfile
import time

UVMS, SRC, CASE = sys.argv[1], sys.argv[2], sys.argv[3]
BASE = os.path.join(SRC, "sil", "scenarios", "paper", "case_IV_stagnant.toml")
TMP = tempfile.mkdtemp(prefix="uvms-campaign-")


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def write(name, text):
    path = os.path.join(TMP, name)
    with open(path, "w") as f:
        f.write(text)
    return path


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


def mark_summaries(runs):
    """Adds a marker key to every run's summary.json (a redone run loses it); returns
    {run id: (inode, mtime_ns) of the marked file}."""
    out = {}
    for r in os.listdir(runs):
        path = os.path.join(runs, r, "summary.json")
        with open(path) as f:
            s = json.load(f)
        s.setdefault("test_marker", r)
        with open(path, "w") as f:
            json.dump(s, f)
        st = os.stat(path)
        out[r] = (st.st_ino, st.st_mtime_ns)
    return out


def not_redone(runs, stamps):
    """The runs of `stamps` whose summary.json was rewritten since mark_summaries."""
    redone = []
    for r, stamp in stamps.items():
        path = os.path.join(runs, r, "summary.json")
        with open(path) as f:
            marker = json.load(f).get("test_marker")
        st = os.stat(path)
        if marker != r or (st.st_ino, st.st_mtime_ns) != stamp:
            redone.append(r)
    return redone


def executed(stdout):
    """Run ids the campaign's (non-tty) progress lines report as run."""
    return sorted(m.group(1) for m in re.finditer(r"^\[\d+/\d+\] .*  (\S+) (?:finished|FAILED)$",
                                                   stdout, re.M))


def plan_ids(out):
    with open(os.path.join(out, "plan.json")) as f:
        return [r["id"] for r in json.load(f)["runs"]]


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
        if not_redone(runs, before or {}):
            fail(f"runs {not_redone(runs, before)} were redone when the campaign was extended")
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
    """--dry-run of the paper campaigns: the run counts their header comments state."""
    counts = {"exp1_cases": 8 + 8 * 20, "exp2_payload": 20 + 10 * 20, "exp3_tracking": 2 + 2 * 20,
              "exp4_fidelity": 16 + 16 * 20, "exp5_travel": 20, "exp6_duration": 18,
              "exp7_energy_split": 10, "exp8_analytic": 14}
    for name, n in counts.items():
        path = os.path.join(SRC, "sil", "campaigns", "paper", name + ".toml")
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


globals()["case_" + CASE]()
print("PASS", CASE)
