# SPDX-License-Identifier: Apache-2.0
"""--help on every command prints help and does nothing else: exit 0 within a few seconds
(none of them bootstraps, builds, runs a campaign or a benchmark), help text on stdout, nothing
on stderr, and the repository's tracked and untracked files unchanged. tools/main without the
free space it needs stops before deleting or writing anything.

Usage: test_help.py SOURCE_DIR SIL_DIR
"""
import os
import subprocess
import sys

SRC, SIL = sys.argv[1], sys.argv[2]
SCRIPTS = ["tools/main", "tools/test", "tools/bootstrap", ".ci/run", "bench/host_bench.sh",
           "bench/m4f_bench.sh", "bench/sil_bench.sh", "bench/footprint_table.py",
           "bench/pinocchio_bench.sh", "bench/campaign_scale.py", "tools/report.py",
           "tools/uvmslog.py", "tools/analytic.py", "tools/thruster_fit.py", "tools/cluster/render",
           "tools/campaign-dask", "tools/uvmsviz.py", "tools/lcm-spy"]
PROGRAMS = ["uvms", "uvms-plant", "uvms-controller", "uvms-controller-pil"]


def repo_state():
    p = subprocess.run(["git", "-C", SRC, "status", "--porcelain", "--untracked-files=all"],
                       capture_output=True, text=True)
    return p.stdout if p.returncode == 0 else None


def main():
    before = repo_state()
    failures = []
    # Python tools with this (the venv's) interpreter, as UVMS_NO_REEXEC tells them to expect.
    commands = [([sys.executable] if s.endswith(".py") else []) + [os.path.join(SRC, s)]
                for s in SCRIPTS] + [[os.path.join(SIL, p)] for p in PROGRAMS]
    for cmd in commands:
        try:
            p = subprocess.run(cmd + ["--help"], capture_output=True, text=True, timeout=20,
                               cwd=SRC)
        except subprocess.TimeoutExpired:
            failures.append(f"{cmd[-1]} --help still running after 20 s (it does work)")
            continue
        name = os.path.relpath(cmd[-1], SRC)
        if p.returncode != 0 or not p.stdout.strip() or p.stderr.strip():
            failures.append(f"{name} --help: exit {p.returncode}, stdout {len(p.stdout)} chars, "
                            f"stderr {p.stderr.strip()[:120]!r}")
        else:
            print(f"ok   {name}: {p.stdout.strip().splitlines()[0][:90]}")
    # tools/main's free-space check runs before anything is deleted or written: with an
    # impossible requirement it stops at once with a clear error (exit 1).
    env = dict(os.environ, UVMS_MAIN_MIN_FREE_GIB="100000000")
    p = subprocess.run([os.path.join(SRC, "tools/main")], capture_output=True, text=True,
                       timeout=20, cwd=SRC, env=env)
    if p.returncode != 1 or "needs 100000000 GiB" not in p.stderr or "Nothing was deleted" not in p.stderr:
        failures.append(f"tools/main with too little space: exit {p.returncode}, {p.stderr.strip()[:200]!r}")
    else:
        print(f"ok   tools/main stops before writing: {p.stderr.strip()[:100]}")
    if before is not None and repo_state() != before:
        failures.append("--help changed files in the repository")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
