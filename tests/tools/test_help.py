# SPDX-License-Identifier: Apache-2.0
"""--help on every command prints help and does nothing else: exit 0 within a few seconds
(none of them bootstraps, builds, runs a campaign or a benchmark), help text on stdout, nothing
on stderr, and the repository's tracked and untracked files unchanged. tools/main without the
free space it needs stops before deleting or writing anything.

Usage: test_help.py SOURCE_DIR SIL_DIR BENCH_DIR
"""
import os
import subprocess
import sys

SRC, SIL, BENCH = sys.argv[1], sys.argv[2], sys.argv[3]
SCRIPTS = ["tools/main", "tools/test", "tools/bootstrap", ".ci/run", "bench/host_bench.sh",
           "bench/m4f_bench.sh", "bench/sil_bench.sh", "bench/footprint_table.py",
           "bench/pinocchio_bench.sh", "bench/pinocchio_ab.sh", "bench/paper_metrics_diff.py",
           "bench/campaign_scale.py", "bench/ci_stages.py", "bench/campaign_ab.sh", "bench/doc_block.py",
           "bench/sil_ab.sh",
           "tools/report.py",
           "tools/uvmslog.py", "tools/analytic.py", "tools/thruster_fit.py", "tools/cluster/render",
           "tools/campaign-dask", "tools/uvmsviz.py", "tools/lcm-spy"]
PROGRAMS = ["uvms", "uvms-plant", "uvms-controller", "uvms-controller-pil"]
BENCH_PROGRAMS = ["bench_ctrl_host", "bench_plant", "bench_lcm_roundtrip"]


def repo_state():
    p = subprocess.run(["git", "-C", SRC, "status", "--porcelain", "--untracked-files=all"],
                       capture_output=True, text=True)
    return p.stdout if p.returncode == 0 else None


def main():
    before = repo_state()
    failures = []
    # Python tools with this (the venv's) interpreter, as UVMS_NO_REEXEC tells them to expect.
    commands = [([sys.executable] if s.endswith(".py") else []) + [os.path.join(SRC, s)]
                for s in SCRIPTS] + [[os.path.join(SIL, p)] for p in PROGRAMS] + \
               [[os.path.join(BENCH, p)] for p in BENCH_PROGRAMS]
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
    # One -j convention: N at a time, by default all cores (uvms campaign, campaign-dask with
    # --local-workers as its alias, uvmslog --dashboard).
    for cmd, needles in (([os.path.join(SIL, "uvms"), "campaign", "--help"],
                          ["-j N", "default: all cores"]),
                         ([sys.executable, os.path.join(SRC, "tools", "campaign-dask"), "--help"],
                          ["-j N, --jobs N, --local-workers N", "all cores"]),
                         ([sys.executable, os.path.join(SRC, "tools", "uvmslog.py"), "--help"],
                          ["-j N, --jobs N", "all cores"])):
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=20, cwd=SRC)
        flat = " ".join(p.stdout.split())
        missing = [n for n in needles if n not in flat]
        name = " ".join(os.path.basename(c) for c in cmd[:3])
        if missing:
            failures.append(f"{name}: no {missing} (one -j convention)")
        else:
            print(f"ok   {name}: -j, all cores")
    # tools/main's free-space check runs before anything is deleted or written: with an
    # impossible requirement it stops at once with a clear error (exit 1).
    # It writes about 1 GiB (the logs of the runs the report reads), 12 GiB with --keep-logs.
    env = dict(os.environ, UVMS_MAIN_MIN_FREE_GIB="100000000")
    for extra, writes in (([], "writes about 1 GiB"), (["--keep-logs"], "writes about 12 GiB")):
        p = subprocess.run([os.path.join(SRC, "tools/main"), *extra], capture_output=True,
                           text=True, timeout=20, cwd=SRC, env=env)
        if p.returncode != 1 or "needs 100000000 GiB" not in p.stderr or \
                "Nothing was deleted" not in p.stderr or writes not in p.stderr:
            failures.append(f"tools/main {' '.join(extra)} with too little space: exit "
                            f"{p.returncode}, {p.stderr.strip()[:200]!r}")
        else:
            print(f"ok   tools/main {' '.join(extra)} stops before writing: "
                  f"{p.stderr.strip()[:100]}")
    p = subprocess.run([os.path.join(SRC, "tools/main"), "--bogus"], capture_output=True,
                       text=True, timeout=20, cwd=SRC)
    if p.returncode != 2 or "unknown option --bogus" not in p.stderr:
        failures.append(f"tools/main --bogus: exit {p.returncode}, {p.stderr.strip()[:200]!r}")
    if before is not None and repo_state() != before:
        failures.append("--help changed files in the repository")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
