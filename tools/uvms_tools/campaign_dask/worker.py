# SPDX-License-Identifier: Apache-2.0
"""campaign_dask.worker: one run of a campaign, executed on a dask worker.

`execute_run` is the body of every task. It runs the plan's `uvms run` exactly as the
contract of cli.py (and `uvms campaign`) does: in a directory of its own holding overrides.json (the
plan's exact bytes), with cwd there, stdin /dev/null and stdout + stderr into run.out. The argv
comes verbatim from the plan (`--out .`, a fixed `--session`), so the run's files do not depend
on where the directory is.

Where the files go:
  * default: the directory is a private temp dir on the worker; the files come back to the
    client as bytes (the client writes them into DIR/runs/<id>/, outdir.write_run_files);
  * shared filesystem: the directory is DIR/.work/<campaign token>/<uuid> (same filesystem as
    DIR/runs, so a rename is atomic); the files are renamed into DIR/runs/<id>/, summary.json
    last, so a summary.json there always belongs to a complete run.
Either way DIR/runs/<id>/ then holds exactly the files this run produced, as `uvms campaign`
leaves it (its `uvms run --no-log` removes an old run.lcmlog): an old file of a name in
RUN_FILES that this run did not produce is removed before summary.json is published.

What the client gets back (the "result"): a run whose `uvms run` exited 0 or 3, or left a
summary.json whatever its status, is a result (finished or failed). A run that exited with
another status and left no summary.json (127: the binary cannot be started on this node; killed
by a signal) says nothing about its inputs, only about this worker: it comes back "lost" with
the reason, as does a failure of this worker's own scratch space (a full /tmp, a scratch file
that cannot be read), and the client submits it again (--max-retries). Only a failure to write
into DIR itself (the --shared-fs publish) is "error": the campaign stops.

A worker that dies (SIGKILL, lost node) must not leave its `uvms run` writing files: the child
gets PR_SET_PDEATHSIG(SIGTERM) (uvms run then writes an "interrupted" summary into its private
directory, never into runs/). The signal follows the thread that started the child; that thread
blocks in wait() until the child ends, so it outlives the child unless the process dies. The
child also gets a session of its own, so a Ctrl-C at the terminal reaches the campaign's client
(which stops the cluster) and not every run directly.

This module is shipped to the workers by value (engine.py: cloudpickle.register_pickle_by_value)
so a remote worker needs the uvms binary at the plan's absolute path, but neither the base
scenario (its pinned bytes come with each task) nor a copy of tools/. Standard library only.
"""
import contextlib
import ctypes
import fcntl
import os
import shutil
import signal
import socket
import subprocess
import tempfile
import uuid

# The files of a run directory, in the order they are published: summary.json last (its
# presence means a complete run; `uvms campaign` and --merge read it as "the run is done").
RUN_FILES = ("overrides.json", "run.out", "run.lcmlog", "summary.json")

_PR_SET_PDEATHSIG = 1  # <linux/prctl.h>
_TEMP_PREFIX = "uvms-dask-run-"  # + host + "-" + worker pid + "-": private run directories


def _pdeathsig_preexec():
    """A preexec_fn giving the child SIGTERM when the thread that started it dies. prctl is
    looked up before the fork, so the child only makes one foreign call (no allocation)."""
    prctl = ctypes.CDLL(None, use_errno=True).prctl
    prctl.argtypes = [ctypes.c_int, ctypes.c_ulong, ctypes.c_ulong, ctypes.c_ulong,
                      ctypes.c_ulong]
    prctl.restype = ctypes.c_int
    parent = os.getpid()

    def preexec():
        prctl(_PR_SET_PDEATHSIG, int(signal.SIGTERM), 0, 0, 0)
        if os.getppid() != parent:  # the worker died before prctl took effect
            os._exit(127)
    return preexec


def _temp_prefix():
    """This process's private run directories: the host name too, so that containers sharing
    a /tmp (and not their pid numbers) never take each other's for stale."""
    host = "".join(c if c.isalnum() else "_" for c in socket.gethostname())
    return f"{_TEMP_PREFIX}{host}-"


def remove_stale_temp_dirs():
    """Private run directories of dead workers of this host (a worker killed mid-run cannot
    remove its own): removed when their pid is gone. Best effort."""
    root, prefix = tempfile.gettempdir(), _temp_prefix()
    try:
        names = [n for n in os.listdir(root) if n.startswith(prefix)]
    except OSError:
        return
    for name in names:
        pid = name[len(prefix):].split("-", 1)[0]
        if not pid.isdigit() or os.path.exists(f"/proc/{pid}"):
            continue
        shutil.rmtree(os.path.join(root, name), ignore_errors=True)


def _run_uvms(uvms, argv, overrides_json, work):
    """`uvms <argv>` in `work` (which gets overrides.json and run.out); returns its exit status
    (negative: killed by that signal; 127: it could not be started, run.out says why)."""
    with open(os.path.join(work, "overrides.json"), "wb") as f:
        f.write(overrides_json.encode("utf-8"))
    with open(os.path.join(work, "run.out"), "wb") as log:
        try:
            child = subprocess.Popen([uvms, *argv], cwd=work, stdin=subprocess.DEVNULL,
                                     stdout=log, stderr=subprocess.STDOUT,
                                     start_new_session=True, preexec_fn=_pdeathsig_preexec())
        except OSError as e:  # as `uvms campaign` does: the cause into run.out, no summary
            log.write(f"campaign-dask: cannot execute {uvms}: {e.strerror}\n".encode())
            return 127
        try:
            return child.wait()
        except BaseException:  # the task was interrupted: never leave the run behind
            child.terminate()
            child.wait()
            raise


def _fsync_file(path):
    fd = os.open(path, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)


def _client_gone(out_dir):
    """Whether the campaign's client no longer holds DIR's exclusive lock (--shared-fs, just
    before publishing). A client interrupted while its tasks run on a remote cluster cancels
    their futures, but a task already running finishes on its worker: its result must not land
    in a DIR the client has released (another campaign, or `uvms campaign --force-new`, may own
    DIR by now). flock(LOCK_SH | LOCK_NB) on DIR/.campaign.lock: EWOULDBLOCK means an exclusive
    holder (the client) is still there; success means nobody holds it exclusively any more, and
    the shared lock just taken is released at once.

    The window that remains: the client may release DIR between this check and the renames
    that follow (a few milliseconds), and those files then land in a DIR without its owner.
    They are a complete run of this campaign's plan (its overrides.json, summary.json last),
    so a resume of the same campaign keeps it as done, as it keeps any finished run. Only if
    another campaign (--force-new) took DIR within that same instant and wrote a run of the
    same id can this late run overwrite it. A lock held across the renames would close the
    window, but a shared lock conflicts with the client's exclusive one by design, so this
    worker cannot hold one while the client runs.

    A filesystem whose flock fails (ENOLCK: locks not supported on this mount) cannot tell:
    the run is published, as it was before this check existed."""
    try:
        fd = os.open(os.path.join(out_dir, ".campaign.lock"), os.O_RDONLY)
    except FileNotFoundError:
        return True  # the lock file is gone: so is the campaign that held it
    except OSError:
        return False
    try:
        fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
    except OSError:
        # EWOULDBLOCK: the client still holds it exclusively. Any other errno (ENOLCK: this
        # mount has no flock) cannot tell: publish, as before this check existed.
        return False
    else:
        fcntl.flock(fd, fcntl.LOCK_UN)
        return True
    finally:
        os.close(fd)


def _publish(work, run_dir, out_dir, token_dir):
    """Renames the run's files from `work` into `run_dir`, summary.json last, and removes the
    old files of `run_dir` this run did not produce. Returns (error, dropped): error None or
    the message of the first failure (naming the path); dropped None or why the result was
    not published (its campaign has ended)."""
    # The campaign that started this task has ended (its client removed the token directory,
    # or no longer holds DIR's lock): a later campaign may own DIR now, so this late result
    # is dropped.
    if not os.path.isdir(token_dir):
        return None, f"{token_dir} is gone: the campaign of this run has ended; result dropped"
    if _client_gone(out_dir):
        return None, (f"{os.path.join(out_dir, '.campaign.lock')} is no longer held: the "
                      "campaign of this run has ended; result dropped")
    step = f"cannot create the run directory {run_dir}"
    try:
        os.makedirs(run_dir, exist_ok=True)
        summary = os.path.join(run_dir, "summary.json")
        step = f"cannot remove the old {summary}"
        try:
            os.unlink(summary)
        except FileNotFoundError:
            pass
        produced = [n for n in RUN_FILES if os.path.exists(os.path.join(work, n))]
        for name in RUN_FILES:
            if name not in produced:
                stale = os.path.join(run_dir, name)
                step = f"cannot remove the old {stale}"
                try:
                    os.unlink(stale)
                except FileNotFoundError:
                    pass
        for name in produced:
            src = os.path.join(work, name)
            step = f"cannot move {src} to {os.path.join(run_dir, name)}"
            _fsync_file(src)
            os.replace(src, os.path.join(run_dir, name))
    except OSError as e:
        return f"{step}: {e.strerror or e}", None
    return None, None


def _last_line(path):
    """The last non-empty line of a small text file (run.out), for a message; "" if none."""
    try:
        with open(path, "rb") as f:
            f.seek(0, os.SEEK_END)
            f.seek(max(0, f.tell() - 4096))
            lines = [ln for ln in f.read().decode(errors="replace").splitlines() if ln.strip()]
    except OSError:
        return ""
    return lines[-1].strip()[:200] if lines else ""


def _pinned_run_dir(top, base):
    """Lays `top` out as a campaign's DIR is, for the run's argv (which reads the pinned base
    scenario at ../../<inputs.base path>, relative to the run's directory): the plan's pinned
    bytes (inputs.base "text") at top/<inputs.base path>, and the run's directory top/runs/run,
    which is returned. So a worker that does not see DIR, or sees another copy of the base, runs
    the plan's bytes (uvms run --scenario-sha256 checks them), and the run's summary names the
    same path whichever engine runs it."""
    rel = os.path.normpath(base["path"])
    if os.path.isabs(rel) or rel.startswith(".."):
        raise OSError(0, f"the plan's inputs.base path {base['path']!r} is not inside DIR")
    local = os.path.join(top, rel)
    os.makedirs(os.path.dirname(local), exist_ok=True)
    with open(local, "wb") as f:
        f.write(base["text"].encode("utf-8"))
    run_dir = os.path.join(top, "runs", "run")
    os.makedirs(run_dir)
    return run_dir


def execute_run(uvms, argv, overrides_json, run_id, shared, base, keep_log=True):
    """One run of the plan. `shared` is None (return the files) or (DIR, campaign token) (write
    them under DIR, which this worker sees at the same path as the client). `base`: the plan's
    pinned base scenario (inputs.base: path relative to DIR, sha256, text), which the run reads
    from beside its own directory (_pinned_run_dir).

    Returns {"id", "rc": uvms run's exit status, "host", "pid", "files": {name: bytes} or None,
    "lost": None or why this worker has no result (a harness error without a summary.json, its
    scratch space failed): the client runs it again, "error": None or a message naming a path
    under DIR that could not be written (the campaign stops), "dropped": None or why a
    --shared-fs result was not published (the campaign has ended)}. `keep_log` False (the plan's
    keep_log under --logs failed or IDs): a run that finished (exit 0) loses its run.lcmlog
    here, as `uvms campaign` removes it (a failed run keeps it). A failure is a returned
    result, not an exception: the client tells it from a lost task by that."""
    result = {"id": run_id, "rc": None, "host": socket.gethostname(), "pid": os.getpid(),
              "files": None, "lost": None, "error": None, "dropped": None}
    if shared is None:
        remove_stale_temp_dirs()
        try:
            work = tempfile.mkdtemp(prefix=f"{_temp_prefix()}{os.getpid()}-")
        except OSError as e:
            result["lost"] = f"cannot create a run directory in {tempfile.gettempdir()} on " \
                             f"{result['host']}: {e.strerror}"
            return result
    else:
        out_dir, token = shared
        token_dir = os.path.join(out_dir, ".work", token)
        work = os.path.join(token_dir, uuid.uuid4().hex)
        try:
            os.mkdir(work)
        except OSError as e:  # DIR not mounted on this node, say: this worker's problem
            result["lost"] = f"cannot create the run directory {work} on {result['host']}: " \
                             f"{e.strerror}"
            return result
    top = work
    try:
        try:
            try:
                work = _pinned_run_dir(top, base)
            except OSError as e:
                result["lost"] = f"cannot lay out the run directory in {top} on " \
                                 f"{result['host']}: {e.strerror}"
                return result
            result["rc"] = rc = _run_uvms(uvms, argv, overrides_json, work)
            if rc not in (0, 3) and not os.path.exists(os.path.join(work, "summary.json")):
                why = f"killed by signal {-rc}" if rc < 0 else f"exit {rc}"
                said = _last_line(os.path.join(work, "run.out"))
                result["lost"] = f"uvms run ended ({why}) without a summary.json on " \
                                 f"{result['host']}" + (f": {said}" if said else "")
                return result
            if rc == 0 and not keep_log:
                with contextlib.suppress(FileNotFoundError):
                    os.unlink(os.path.join(work, "run.lcmlog"))
            if shared is None:
                files = {}
                for name in RUN_FILES:
                    path = os.path.join(work, name)
                    if os.path.exists(path):
                        with open(path, "rb") as f:
                            files[name] = f.read()
                result["files"] = files
        except OSError as e:
            result["lost"] = f"run directory {work} on {result['host']}: {e.strerror or e}"
            return result
        if shared is not None:
            result["error"], result["dropped"] = _publish(
                work, os.path.join(out_dir, "runs", run_id), out_dir, token_dir)
        return result
    finally:
        shutil.rmtree(top, ignore_errors=True)
