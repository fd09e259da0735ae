# SPDX-License-Identifier: Apache-2.0
"""env: where the package runs: the repository, the project's venv, the version, how many runs
at a time.

The command scripts in tools/ (tools/uvmslog.py, tools/report.py, tools/campaign-dask, ...) have
the shebang `#!/usr/bin/env python3` so that they start anywhere; numpy, matplotlib and lcm live
in REPO/.venv (pinned in tools/requirements.txt, created by tools/bootstrap). Each script's
whole body is `run_tool(__file__, "uvms_tools.<module>:<function>")`: when the running
interpreter is not the venv's, it re-executes the script with REPO/.venv/bin/python first
(once; UVMS_NO_REEXEC=1 disables it). The bottom layer of the package: standard library only,
imports nothing of uvms_tools.
"""
import os
import re
import sys

# tools/uvms_tools/env.py: three levels below the repository.
REPO_ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
VENV_DIR = os.path.join(REPO_ROOT, ".venv")
# The uvms binary of this repository's host build (relative to REPO_ROOT), and the one a tool
# runs when not told which: $UVMS, else that one.
UVMS_REL = os.path.join("build", "host", "sil", "uvms")


def default_uvms():
    """$UVMS, else build/host/sil/uvms of this repository (UVMS_REL)."""
    return os.environ.get("UVMS") or os.path.join(REPO_ROOT, UVMS_REL)


def default_jobs():
    """How many runs a tool runs at a time, as tools/main: $UVMS_JOBS, else one per core this
    process may run on (`nproc`). Raises ValueError when $UVMS_JOBS is not a positive integer
    written as `uvms campaign -j` reads one (ASCII digits, an optional leading +)."""
    v = os.environ.get("UVMS_JOBS", "")
    if not v:
        return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") \
            else os.cpu_count() or 1
    n = int(v) if re.fullmatch(r"\+?[0-9]+", v) else 0
    if n < 1:
        raise ValueError(f"UVMS_JOBS={v!r}: not a positive integer")
    return n


def reexec_in_venv(script):
    """Re-execute `script` (with the same arguments) under REPO/.venv/bin/python if needed."""
    venv_python = os.path.join(VENV_DIR, "bin", "python")
    if os.environ.get("UVMS_NO_REEXEC") or not os.path.exists(venv_python):
        return
    if os.path.realpath(sys.prefix) == os.path.realpath(VENV_DIR):
        return
    os.environ["UVMS_NO_REEXEC"] = "1"  # never loop
    os.execv(venv_python, [venv_python, os.path.abspath(script)] + sys.argv[1:])


def run_tool(script, target, **kwargs):
    """A thin command script's whole body (tools/report.py, tools/uvmslog.py, tools/uvmsviz.py,
    tools/analytic.py, tools/thruster_fit.py, tools/campaign-dask): re-execute under the venv
    if needed, then exit with the status of `target` ("uvms_tools.module:function", called
    with kwargs)."""
    import importlib
    reexec_in_venv(script)
    module, func = target.split(":")
    sys.exit(getattr(importlib.import_module(module), func)(**kwargs))


def project_version():
    """The project's version, from its one source: `project(uvms VERSION x.y.z ...)` in the
    top-level CMakeLists.txt (tools/pyproject.toml reads it as VERSION when it builds). Outside
    a checkout (the package installed from a wheel), the installed package's own metadata."""
    import re
    path = os.path.join(REPO_ROOT, "CMakeLists.txt")
    if not os.path.exists(path):
        from importlib import metadata
        return metadata.version("uvms-tools")
    with open(path, encoding="utf-8") as fh:
        m = re.search(r"project\(\s*uvms\s+VERSION\s+([0-9][0-9.]*)", fh.read())
    if m is None:
        raise RuntimeError(f"no project(uvms VERSION ...) in {path}")
    return m.group(1)


VERSION = project_version()


def version_line(program):
    """What `--version` prints, as every program of the project does (sil/msg/cli_version.h):
    "<program> <version> (git <commit>)", the commit `git rev-parse HEAD` of the checkout with
    "-dirty" when tracked files differ from it, "unknown" outside a checkout."""
    import subprocess
    commit = "unknown"
    try:
        head = subprocess.run(["git", "-C", REPO_ROOT, "rev-parse", "HEAD"], capture_output=True,
                              text=True, timeout=10)
        if head.returncode == 0 and head.stdout.strip():
            commit = head.stdout.strip()
            dirty = subprocess.run(["git", "-C", REPO_ROOT, "status", "--porcelain",
                                    "--untracked-files=no"], capture_output=True, text=True,
                                   timeout=10)
            if dirty.returncode == 0 and dirty.stdout.strip():
                commit += "-dirty"
    except (OSError, subprocess.SubprocessError):
        pass
    return f"{program} {VERSION} (git {commit})"


def add_version_option(parser, program):
    """`--version` on an argparse parser: prints version_line(program) and exits 0 (computed
    only when asked: git runs only then)."""
    import argparse

    class _Version(argparse.Action):
        def __call__(self, p, namespace, values, option_string=None):
            print(version_line(program))
            p.exit(0)

    parser.add_argument("--version", nargs=0, action=_Version,
                        help="print the version and the commit, and exit")
