# SPDX-License-Identifier: Apache-2.0
"""summary.json's provenance from `uvms run` (sil/run/provenance.hpp), end to end: every key in
order; scenario_sha256 equals Python's hashlib.sha256 of the file's bytes; scenario_sets is the
--set overrides joined with newlines; git_commit is `git rev-parse HEAD` (optionally -dirty)
inside the checkout, "unknown" outside one; version is the top-level CMakeLists.txt's project
VERSION; build_preset and build_type are this build tree's.

Usage: test_provenance_e2e.py UVMS_EXE SOURCE_DIR TRANSPORT BUILD_PRESET BUILD_TYPE
"""
import hashlib
import json
import os
import subprocess
import sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import git_head  # noqa: E402  (tests/sil/git_head.py)

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

UVMS, SRC, TRANSPORT, PRESET, BUILD_TYPE = sys.argv[1:6]
KEYS = ["version", "git_commit", "build_preset", "build_type", "controller_precision",
        "scenario_sha256", "scenario_sets"]


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def expected_commit():
    return git_head.head_commit(SRC)


def project_version():
    v = git_head.project_version(SRC)
    if v is None:
        fail("no project(... VERSION ...) in the top-level CMakeLists.txt")
    return v


tmp = scratch_dir("uvms-provenance-")  # removed at exit (tests/support/scratch.py)
# A scenario whose bytes include a non-ASCII comment and CRLF line ends: hashed as read.
scenario = os.path.join(tmp, "prov.toml")
with open(scenario, "wb") as f:
    f.write("# provenance test: θ, ρ\r\n[control]\r\ncase = \"VII\"\r\n".encode())
sets = ["run.duration_s=0.3", "payload.mass_kg=5"]
out = os.path.join(tmp, "run")
cmd = [UVMS, "run", scenario, "--out", out, "--transport", TRANSPORT]
for s in sets:
    cmd += ["--set", s]
p = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
print(p.stdout, p.stderr)
if p.returncode not in (0, 3):
    fail(f"uvms run exited {p.returncode}")
with open(os.path.join(out, "summary.json")) as f:
    prov = json.load(f).get("provenance")
print("provenance:", json.dumps(prov, indent=1))
if not isinstance(prov, dict):
    fail("summary.json has no provenance object")
if list(prov) != KEYS:
    fail(f"provenance keys {list(prov)}, expected {KEYS}")
with open(scenario, "rb") as f:
    want_sha = hashlib.sha256(f.read()).hexdigest()
if prov["scenario_sha256"] != want_sha:
    fail(f"scenario_sha256 {prov['scenario_sha256']}, hashlib says {want_sha}")
if prov["scenario_sets"] != "\n".join(sets):
    fail(f"scenario_sets {prov['scenario_sets']!r}, expected {chr(10).join(sets)!r}")
if prov["version"] != project_version():
    fail(f"version {prov['version']}, CMakeLists.txt says {project_version()}")
if prov["build_preset"] != (PRESET or "custom"):
    fail(f"build_preset {prov['build_preset']}, this build tree's is {PRESET!r}")
if prov["build_type"] != (BUILD_TYPE or "none"):
    fail(f"build_type {prov['build_type']}, this build tree's is {BUILD_TYPE!r}")
if prov["controller_precision"] not in ("double", "float"):
    fail(f"controller_precision {prov['controller_precision']!r}")
head = expected_commit()
commit = prov["git_commit"]
if head is None:
    if commit != "unknown":
        fail(f"git_commit {commit} outside a git checkout, expected unknown")
elif commit not in (head, head + "-dirty"):
    fail(f"git_commit {commit}, but HEAD is {head} (built from another commit? rebuild)")
print("PASS", TRANSPORT)
