# SPDX-License-Identifier: Apache-2.0
"""regen: a run's log that its campaign did not keep (uvms campaign --logs failed|none|IDs),
made again when the report reads it.

A campaign run is deterministic: its session is derived from its inputs and the pinned base
scenario's bytes are checked by SHA-256, so `uvms run` with the arguments plan.json records for
it (runs[].argv) writes the log the run had, byte for byte (docs/CAMPAIGNS.md "Which runs keep
a log"). The run is made again in a scratch directory beside the run's own (so the argv's
../../inputs/ path resolves the same); its summary.json must equal the kept one in every field
but the wall clock and the git commit, else the log is not used: this binary is not the one
that ran the campaign, and the report says so instead of reading another run's numbers. The log
then joins the run's directory, where it stays: what a report read is on disk beside it.

Each run is one `uvms run` subprocess; a loop over many runs' logs has them made ahead,
$UVMS_JOBS at a time (regenerate_ahead, Experiment.prefetch_logs).
"""
import json
import os
import shutil
import subprocess
from concurrent.futures import ThreadPoolExecutor

from uvms_tools.env import default_jobs, default_uvms

# summary.json fields a run made again may change: the wall clock, the run's name (a campaign of
# an older uvms named its runs after the base scenario) and the commit of a build whose code is
# the same (every number the run computes is compared).
VOLATILE = ("wall_time_s", "real_time_factor", "plant_wall_s", "name")
VOLATILE_PROVENANCE = ("git_commit",)


_UVMS = []  # the binary set_uvms() chose (tools/report.py --uvms)
_JOBS = []  # how many runs regenerate_ahead makes at a time (set_jobs)
_POOL = []  # regenerate_ahead's ThreadPoolExecutor, made on first use


def set_uvms(path):
    """The uvms binary that makes logs again (tools/report.py --uvms), as an absolute path: the
    run is started in its scratch directory, where a relative path would name another file."""
    _UVMS[:] = [os.path.abspath(path)]


def uvms_binary():
    """The uvms that makes a log again: set_uvms's (tools/report.py always sets it), else $UVMS,
    else build/host/sil/uvms of this repository."""
    return os.path.abspath((_UVMS[0] if _UVMS else None) or default_uvms())


def set_jobs(n):
    """How many runs regenerate_ahead makes at a time (tools/report.py: env.default_jobs, as
    tools/main); without it, env.default_jobs() when first needed. Runs already handed to the
    pool still run; the next regenerate_ahead makes a pool of n."""
    _JOBS[:] = [n]
    while _POOL:
        _POOL.pop().shutdown(wait=False)


def stop_ahead():
    """Cancels the regenerate_ahead runs not started yet and waits for the others (the report
    ends: an error, or interrupted)."""
    while _POOL:
        _POOL.pop().shutdown(cancel_futures=True)


def regenerate_ahead(exp_dir, run_id, argv):
    """regenerate() in a background thread, at most set_jobs() runs at a time: a
    concurrent.futures.Future of its outcome."""
    if not _POOL:
        _POOL.append(ThreadPoolExecutor(max_workers=_JOBS[0] if _JOBS else default_jobs(),
                                        thread_name_prefix="regen"))
    return _POOL[0].submit(regenerate, exp_dir, run_id, argv)


class BuildMismatch(str):
    """Why a log was not made again, when the cause holds for every run of the campaign (no
    uvms, or another build): the report stops trying for that campaign."""


def _comparable(summary):
    s = {k: v for k, v in summary.items() if k not in VOLATILE}
    s["provenance"] = {k: v for k, v in (summary.get("provenance") or {}).items()
                       if k not in VOLATILE_PROVENANCE}
    return s


def _differing(a, b):
    ca, cb = _comparable(a), _comparable(b)
    return sorted(k for k in set(ca) | set(cb) if ca.get(k) != cb.get(k))


def regenerate(exp_dir, run_id, argv, timeout_s=600):
    """Makes run `run_id`'s log again into exp_dir/runs/<id>/run.lcmlog. Returns None when the
    log is there, or why it is not (no argv in plan.json, no uvms, the run failed, or its
    summary differs from the kept one: the fields named)."""
    run_dir = os.path.join(exp_dir, "runs", run_id)
    if not argv:
        return "plan.json records no uvms run arguments for it (a campaign of an older uvms)"
    uvms = uvms_binary()
    if not (os.path.isfile(uvms) and os.access(uvms, os.X_OK)):
        return BuildMismatch(f"no uvms to run it with ({uvms}: build it with cmake --build "
                             "--preset host, or give tools/report.py --uvms PATH)")
    try:
        with open(os.path.join(run_dir, "summary.json")) as f:
            kept = json.load(f)
    except (OSError, json.JSONDecodeError) as e:
        return f"its summary.json cannot be read ({e})"
    scratch = os.path.join(exp_dir, "runs", f".log-again-{run_id}")
    shutil.rmtree(scratch, ignore_errors=True)
    try:
        os.makedirs(scratch)
        p = subprocess.run([uvms, *argv], cwd=scratch, capture_output=True, text=True,
                           timeout=timeout_s, stdin=subprocess.DEVNULL)
        if p.returncode != 0:
            said = (p.stderr.strip() or p.stdout.strip()).splitlines()[-1:] or [""]
            return f"{uvms} run exited {p.returncode}: {said[0]}"
        with open(os.path.join(scratch, "summary.json")) as f:
            again = json.load(f)
        diff = _differing(kept, again)
        if diff:
            return BuildMismatch(
                f"made again, its summary differs from the kept one in {', '.join(diff[:6])}"
                f"{' ...' if len(diff) > 6 else ''}: {uvms} is not the build that ran the "
                "campaign (run the campaign again, or keep its logs: --logs all)")
        os.replace(os.path.join(scratch, "run.lcmlog"), os.path.join(run_dir, "run.lcmlog"))
        return None
    except (OSError, subprocess.SubprocessError, json.JSONDecodeError) as e:
        return f"making it again failed: {e}"
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
