# SPDX-License-Identifier: Apache-2.0
"""campaign_dask.outdir: the client's side of DIR (the contract of cli.py).

  * `OutDirLock`: DIR/.campaign.lock, flock(LOCK_EX|LOCK_NB), our pid written into it, held
    until the process ends (the kernel drops it however the process ends: no stale lock);
  * `uvms_campaign`: `uvms campaign ... --plan-only` / `--merge` with that lock handed over
    (UVMS_CAMPAIGN_LOCK_FD + pass_fds), so uvms does not lock DIR a second time;
  * `write_run_files`: a run's files returned by a worker, written into DIR/runs/<id>/ as
    `uvms campaign` leaves them: the old summary.json removed first, then the old files the
    run did not produce, each file written to NAME.tmp, fsync'd and renamed, summary.json last
    (its presence means a complete run).

Every write is checked; a failure raises `OutputError` whose message names the path and the
cause (the command line prints it and exits 3, never a traceback). Standard library only.
"""
import errno
import fcntl
import json
import os
import socket
import subprocess
import sys

from uvms_tools.campaign_dask.worker import RUN_FILES

EXIT_OK, EXIT_BAD_CAMPAIGN, EXIT_USAGE, EXIT_FAILED, EXIT_BUSY = 0, 1, 2, 3, 4


class CampaignStop(Exception):
    """The campaign cannot go on (exit 3); the message says why."""


class OutputError(CampaignStop):
    """A file or directory under DIR that could not be written; the message names it."""


class Busy(Exception):
    """DIR is locked by another campaign; the message says by which process."""


class OutDirLock:
    """The exclusive lock of one --out DIR, as `uvms campaign` takes it (CampaignLock in
    sil/campaign/campaign_lock.cpp). The descriptor is close-on-exec (Python's default): only the uvms
    children it is handed to (pass_fds) get it, never a dask worker."""

    def __init__(self, out_dir):
        self.path = os.path.join(out_dir, ".campaign.lock")
        self.fd = -1
        try:
            self.fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as e:
            raise OutputError(f"cannot create the lock file {self.path}: {e.strerror}") from None
        try:
            fcntl.flock(self.fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as e:
            if e.errno not in (errno.EWOULDBLOCK, errno.EAGAIN):
                raise OutputError(f"cannot lock {self.path}: {e.strerror}") from None
            holder = os.pread(self.fd, 299, 0).decode(errors="replace").strip()
            holder = f" (process {holder})" if holder else ""  # a shard's shared lock: none
            raise Busy(f"{out_dir} is in use by another campaign (or shards of one){holder}: "
                       f"it holds the lock {self.path}. One campaign at a time per --out: wait "
                       "until it ends, or give another --out") from None
        try:
            os.ftruncate(self.fd, 0)
            # "<pid> on <host>", as uvms writes it: a pid alone means little across machines.
            pid = f"{os.getpid()} on {socket.gethostname()}\n".encode()
            if os.pwrite(self.fd, pid, 0) != len(pid):
                raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))
        except OSError as e:
            raise OutputError(f"cannot write {self.path}: {e.strerror}") from None


def remove_if_only_lock(out_dir):
    """A DIR this process created for a campaign that uvms then refused (bad campaign file,
    usage): removed again when it holds nothing but our lock file, so a refused campaign leaves
    nothing behind, as `uvms campaign` (which checks before it creates DIR) does. Best effort;
    the lock file goes while we hold it, so a campaign that opened it meanwhile (within this
    refusal's few milliseconds) is still refused by our lock."""
    try:
        if os.listdir(out_dir) == [".campaign.lock"]:
            os.unlink(os.path.join(out_dir, ".campaign.lock"))
            os.rmdir(out_dir)
    except OSError:
        pass


def uvms_campaign(uvms, lock, args, capture):
    """`uvms campaign ARGS` with the lock handed over; stderr passes through. Returns
    (exit status, stdout text if `capture` else None)."""
    env = dict(os.environ, UVMS_CAMPAIGN_LOCK_FD=str(lock.fd))
    p = subprocess.run([uvms, "campaign", *args], env=env, pass_fds=(lock.fd,),
                       stdin=subprocess.DEVNULL, stderr=None,
                       stdout=subprocess.PIPE if capture else None, text=True)
    return p.returncode, p.stdout


def read_plan(text):
    """The plan `--plan-only` prints (JSON Lines: a head object whose "runs" counts the run
    lines that follow, then one object per run), as the head with "runs" the list of runs;
    ValueError when it is not one (a truncated output included)."""
    lines = text.splitlines()
    plan = json.loads(lines[0]) if lines else None
    if not isinstance(plan, dict) or not isinstance(plan.get("runs"), int):
        raise ValueError("not a plan head line with a run count")
    base = (plan.get("inputs") or {}).get("base") if isinstance(plan.get("inputs"), dict) else None
    if not (isinstance(base, dict) and all(isinstance(base.get(k), str)
                                           for k in ("path", "sha256", "text"))):
        raise ValueError("a plan head without its pinned base scenario (inputs.base: path, "
                         "sha256, text)")
    if plan["runs"] != len(lines) - 1:
        raise ValueError(f"the head announces {plan['runs']} runs, {len(lines) - 1} follow")
    plan["runs"] = [json.loads(line) for line in lines[1:]]
    for r in plan["runs"]:
        if not (isinstance(r, dict) and isinstance(r.get("id"), str)
                and isinstance(r.get("argv"), list) and isinstance(r.get("overrides_json"), str)
                and r.get("state") in ("todo", "done", "failed")):
            raise ValueError(f"a run without id, argv, overrides_json or state: {r!r:.200}")
    return plan


def _write_atomic(path, data):
    """`path` holds `data` or is unchanged: NAME.tmp written, fsync'd, renamed (as
    WriteTextFileAtomic in sil/run/summary_writer.cpp)."""
    tmp = path + ".tmp"
    try:
        fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    except OSError as e:
        raise OutputError(f"cannot create {tmp}: {e.strerror}") from None
    try:
        try:
            view = memoryview(data)
            while view:
                view = view[os.write(fd, view):]
            os.fsync(fd)
        finally:
            os.close(fd)
        os.replace(tmp, path)
    except OSError as e:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise OutputError(f"cannot write {path}: {e.strerror}") from None


def write_run_files(out_dir, run_id, files):
    """A run's files (name -> bytes) into DIR/runs/<id>/, summary.json last, leaving the
    directory as `uvms campaign` does: the old summary.json removed first, then every old file
    of RUN_FILES the run did not produce (run.lcmlog under --no-logs: `uvms run --no-log`
    removes it there), then the run's files."""
    run_dir = os.path.join(out_dir, "runs", run_id)
    try:
        os.makedirs(run_dir, exist_ok=True)
    except OSError as e:
        raise OutputError(f"cannot create the run directory {run_dir}: {e.strerror}") from None
    stale = ["summary.json"] + [n for n in RUN_FILES if n not in files and n != "summary.json"]
    for name in stale:
        path = os.path.join(run_dir, name)
        try:
            os.unlink(path)
        except FileNotFoundError:
            pass
        except OSError as e:
            raise OutputError(f"cannot remove the old {path}: {e.strerror}") from None
    for name in RUN_FILES:
        if name in files:
            _write_atomic(os.path.join(run_dir, name), files[name])


def note(msg):
    print(f"campaign-dask: {msg}", file=sys.stderr, flush=True)
