"""`uvms campaign` end to end (issue 6): a 2 x 2 sweep of short runs expands, runs, resumes
after a real interruption without redoing finished runs, and yields the expected results rows;
bad campaign files fail before any run starts.

Usage: test_campaign_e2e.py UVMS_EXE SOURCE_DIR CASE   (CASE: resume | bad_files)
"""
import csv
import json
import os
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
    finished = [r for r in sorted(os.listdir(runs))
                if os.path.exists(os.path.join(runs, r, "summary.json"))]
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
    expected = [("000_IV_0.0", "IV", 0.0, "finished"), ("001_IV_5.0", "IV", 5.0, "finished"),
                ("002_VII_0.0", "VII", 0.0, "finished"), ("003_VII_5.0", "VII", 5.0, "finished")]
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
                 ["run 001", "payload.mass_kg"])
    expect_error("nobase.toml", 'name = "x"\n', ["base"])


globals()["case_" + CASE]()
print("PASS", CASE)
