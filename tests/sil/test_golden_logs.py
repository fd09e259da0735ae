# SPDX-License-Identifier: Apache-2.0
"""The paper scenarios' logs are byte-identical to the recorded ones: a refactoring that must not
change behaviour (issue 14) is checked against the SHA-256 of every paper scenario's run.lcmlog,
recorded per controller precision in tests/sil/golden/paper_logs.sha256.

The barycenter-reference scenarios (cases II, III, VII, VIII) also run with
trajectory.theta_final_deg = "printed" (the paper's printed 10 kg column, docs/MODEL.md C26),
recorded as NAME@printed: those records are the logs from before the column's correction, so the
correction is shown to change nothing else.

A change that is meant to alter the logs (a new message field, different physics) updates the
record deliberately, and says so in its commit:
    test_golden_logs.py UVMS_EXE SOURCE_DIR PRECISION --update

Usage: test_golden_logs.py UVMS_EXE SOURCE_DIR PRECISION [--update]
PRECISION: double or float (the build's controller precision: the logs differ between them).
"""
import glob
import hashlib
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

UVMS, SRC, PRECISION = sys.argv[1], sys.argv[2], sys.argv[3]
UPDATE = "--update" in sys.argv[4:]
RECORD = os.path.join(SRC, "tests", "sil", "golden", "paper_logs.sha256")
TMP = scratch_dir("uvms-golden-")  # removed at exit (tests/support/scratch.py)
# Every message carries the run's session (sil/msg/session.h), drawn at random unless fixed: the
# recorded logs are those of this session.
SESSION = "601de4105e551011"
# The barycenter-reference cases, whose final pose is the payload's column.
PRINTED_CASES = ("II", "III", "VII", "VIII")
PRINTED = ["--set", 'trajectory.theta_final_deg="printed"']


def read_record():
    rec = {}
    if os.path.exists(RECORD):
        with open(RECORD) as f:
            for line in f:
                if line.strip() and not line.startswith("#"):
                    prec, name, digest = line.split()
                    rec[(prec, name)] = digest
    return rec


def write_record(rec):
    with open(RECORD, "w") as f:
        f.write("# SHA-256 of run.lcmlog of every sil/scenarios/paper/*.toml (memq, --session "
                f"{SESSION}),\n# per controller precision; written by tests/sil/test_golden_logs.py "
                "--update\n")
        for (prec, name), digest in sorted(rec.items()):
            f.write(f"{prec} {name} {digest}\n")


def main():
    if PRECISION not in ("double", "float"):
        print(f"FAIL: precision {PRECISION!r} (expected double or float)")
        return 2
    rec = read_record()
    scenarios = sorted(glob.glob(os.path.join(SRC, "sil", "scenarios", "paper", "*.toml")))
    if len(scenarios) != 16:
        print(f"FAIL: {len(scenarios)} paper scenarios, expected 16")
        return 1
    failures = 0
    runs = []
    for path in scenarios:
        name = os.path.basename(path)[:-5]
        runs.append((path, name, []))
        if name.split("_")[1] in PRINTED_CASES:
            runs.append((path, name + "@printed", PRINTED))
    for path, name, extra in runs:
        out = os.path.join(TMP, name)
        p = subprocess.run([UVMS, "run", path, "--out", out, "--transport", "memq",
                            "--session", SESSION] + extra,
                           capture_output=True, text=True, timeout=600)
        if p.returncode != 0:
            print(f"FAIL: {name}: exit {p.returncode}: {p.stderr.strip()}")
            failures += 1
            continue
        with open(os.path.join(out, "run.lcmlog"), "rb") as f:
            digest = hashlib.sha256(f.read()).hexdigest()
        want = rec.get((PRECISION, name))
        if UPDATE:
            rec[(PRECISION, name)] = digest
            print(f"recorded {PRECISION} {name} {digest}")
        elif want is None:
            print(f"FAIL: {name}: no recorded {PRECISION} log hash (run with --update)")
            failures += 1
        elif want != digest:
            print(f"FAIL: {name}: log differs from the recorded one ({digest} != {want})")
            failures += 1
        else:
            print(f"ok   {name}")
    if UPDATE:
        write_record(rec)
    print(f"{len(runs) - failures} passed, {failures} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
