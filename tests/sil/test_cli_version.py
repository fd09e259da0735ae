# SPDX-License-Identifier: Apache-2.0
"""--version and --help of every command-line program (sil/msg/cli_version.h).

usage: test_cli_version.py SOURCE_DIR PROGRAM_PATH...

For each program (a path, or "PATH SUBCOMMAND" for a subcommand of uvms; the Python tools in
tools/ print their name without ".py"): `--version` exits 0 and prints exactly one line "<name> <version> (git
<commit>)" on stdout and nothing on stderr, the version being the top-level CMakeLists.txt's
project VERSION and the commit `git rev-parse HEAD` (optionally -dirty) inside the checkout,
"unknown" outside one; `--help` exits 0 and prints the usage, not the version line.
"""
import os
import re
import subprocess
import sys
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import git_head  # noqa: E402  (tests/sil/git_head.py)

SRC = sys.argv[1]
PROGRAMS = sys.argv[2:]


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def project_version():
    v = git_head.project_version(SRC)
    if v is None:
        fail("no project(... VERSION ...) in the top-level CMakeLists.txt")
    return v


def head_commit():
    return git_head.head_commit(SRC)


def run(args, arg):
    return subprocess.run(args + [arg], capture_output=True, text=True, timeout=60)


if not PROGRAMS:
    fail("no programs given")
version = project_version()
head = head_commit()
commits = {"unknown"} if head is None else {head, head + "-dirty"}
for program in PROGRAMS:
    # A Python tool (tools/uvmslog.py, ...) prints its name without ".py"; "uvms SUB" runs
    # `uvms SUB --version`, which prints the uvms line.
    args = program.split(" ")
    name = os.path.basename(args[0])
    name = name[:-3] if name.endswith(".py") else name
    r = run(args, "--version")
    if r.returncode != 0 or r.stderr:
        fail(f"{name} --version: exit {r.returncode}, stderr {r.stderr!r}")
    m = re.fullmatch(r"(\S+) (\S+) \(git (\S+)\)\n", r.stdout)
    if not m:
        fail(f"{name} --version printed {r.stdout!r}")
    if m.group(1) != name or m.group(2) != version or m.group(3) not in commits:
        fail(f"{name} --version printed {r.stdout!r}; expected {name} {version} (git one of "
             f"{sorted(commits)})")
    h = run(args, "--help")
    if h.returncode != 0 or "usage:" not in h.stdout or f"{name} {version} (git" in h.stdout:
        fail(f"{name} --help: exit {h.returncode}, stdout {h.stdout!r}")
    print(f"ok: {r.stdout.strip()}; --help prints the usage")
