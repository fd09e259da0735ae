# SPDX-License-Identifier: Apache-2.0
"""campaign_dask.engine: the runs of a plan as dask.distributed tasks, with progress.

One task per run of state "todo" (client.submit, pure=False, key "uvms-run-<id>-<token>": the
token, fresh per invocation, keeps two campaigns on one shared scheduler from sharing a key,
since dask treats equal keys as the same computation). The scheduler orders and places them;
this module writes no scheduler of its own: it submits every task at once (dask prioritises
them in submission order, that is plan order) and handles them as they complete.

Lost tasks. A worker that dies while running a task: on a LocalCluster the scheduler itself
runs the task again elsewhere up to `distributed.scheduler.allowed-failures` = --max-retries
times (on a remote scheduler, its own setting). When a future still ends lost (KilledWorker
once that budget is spent, CancelledError or CommClosedError when the scheduler or the
connection went away) the client submits the run again under a new key, at most --max-retries
times; after that the run is lost: it has no result, it is named, and the campaign exits 3.
A run whose `uvms run` exits 3 (or with any other status) is a result, written and reported
FAILED like `uvms campaign` does, never retried: a failure is a result of the run's inputs.

Results are written as they arrive (outdir.write_run_files, or by the worker itself under
--shared-fs), so an interrupted campaign keeps every finished run and resumes like
`uvms campaign`. A write that fails stops the campaign: no further result is accepted, the
remaining tasks are cancelled, exit 3 naming the path.
"""
import importlib.util
import logging
import os
import shutil
import sys
import time
import uuid

import cloudpickle
import dask
import distributed
from distributed.comm.core import CommClosedError

from campaign_dask import outdir, worker

# A future that ended without a result of its run (the run itself never said anything).
LOST = (distributed.KilledWorker, distributed.CancelledError, CommClosedError, TimeoutError)

QUIET_LOGGERS = ("distributed", "distributed.client", "distributed.gc", "distributed.nanny",
                 "distributed.scheduler", "distributed.worker", "distributed.core",
                 "tornado", "tornado.application", "asyncio", "bokeh")


class ByValue:
    """A function that reaches the scheduler and the workers by value, whichever pickler dask
    picks: distributed tries the standard pickle first, which would send a reference to
    campaign_dask.worker (not importable on a remote worker or scheduler) and ignores
    cloudpickle's by-value registry for a function nested in a task. Unpickled, it is the
    plain function again."""

    def __init__(self, fn):
        self.fn = fn

    def __call__(self, *args):
        return self.fn(*args)

    def __reduce__(self):
        return cloudpickle.loads, (cloudpickle.dumps(self.fn),)


# cloudpickle.dumps(execute_run) then carries the module's code too (standard library only).
cloudpickle.register_pickle_by_value(worker)
EXECUTE_RUN = ByValue(worker.execute_run)


# A worker preload (the text of a script; it runs in each local worker process as it starts,
# restarted ones too): a Ctrl-C at the terminal reaches the whole foreground process group,
# the local workers included. This client stops them (and their runs) itself; without this
# each worker would also die of it and print a KeyboardInterrupt traceback.
WORKER_IGNORES_SIGINT = """
import signal  # campaign-dask: the client handles Ctrl-C
signal.signal(signal.SIGINT, signal.SIG_IGN)
"""


def quiet_logs():
    """dask's own log lines (worker restarts, connection closed, ...) off: this tool reports
    what matters to a campaign (a lost run, a retry) itself. --verbose keeps them."""
    for name in QUIET_LOGGERS:
        logging.getLogger(name).setLevel(logging.CRITICAL)


def start_client(local_workers, scheduler, max_retries, verbose):
    """(client, cluster or None, description) for --local-workers N or --scheduler ADDRESS."""
    if scheduler:
        return distributed.Client(scheduler, timeout="20s"), None, f"scheduler {scheduler}"
    # worker-saturation 1.0: a 1-thread worker holds one task, not ceil(1.1) = 2. When a
    # worker dies the scheduler charges every task it held with a failure, so a queued task
    # would lose a retry for a death it had no part in.
    dask.config.set({"distributed.scheduler.allowed-failures": max_retries,
                     "distributed.scheduler.worker-saturation": 1.0})
    # ":0": any free port. (dashboard_address=None is not "no dashboard": it falls back to
    # the configured default, the fixed port 8787.)
    cluster = distributed.LocalCluster(
        n_workers=local_workers, processes=True, threads_per_worker=1,
        dashboard_address=":0", silence_logs=logging.INFO if verbose else logging.CRITICAL,
        preload=[WORKER_IGNORES_SIGINT])
    return distributed.Client(cluster), cluster, "a LocalCluster"


def dashboard_link(client):
    """The scheduler's dashboard URL, or None when it has none. A scheduler without bokeh (not
    in tools/requirements.txt) serves only a page asking to install it: no link then."""
    try:
        if "dashboard" not in client.scheduler_info().get("services", {}):
            return None
        if not client.run_on_scheduler(lambda: importlib.util.find_spec("bokeh") is not None):
            return None
        return client.dashboard_link
    except Exception:  # noqa: BLE001  (a link is a courtesy; no link is no error)
        return None


def clock(seconds):
    """MM:SS as `uvms campaign` prints it (Clock in sil/campaign_cli.cpp)."""
    t = int(seconds + 0.5)
    return f"{t // 60:02d}:{t % 60:02d}"


class Outcome:
    """What happened to the runs to do: ids by result."""

    def __init__(self):
        self.finished, self.failed, self.lost = [], [], []
        self.error = None  # the first write failure: the campaign stopped


def run_tasks(client, plan, shared, max_retries, verbose, out=sys.stdout):
    """Runs the plan's "todo" runs as tasks; returns an Outcome. `shared` is None (results come
    back to this client) or (DIR, token) (workers write under DIR/.work/<token>)."""
    runs = plan["runs"]
    todo = [r for r in runs if r["state"] == "todo"]
    total, skipped = len(runs), len(runs) - len(todo)
    token = uuid.uuid4().hex[:8]
    outcome = Outcome()
    t0 = time.monotonic()
    live = {}  # future key -> (future, run, resubmissions so far): tasks without an answer

    def submit(run, attempt):
        key = f"uvms-run-{run['id']}-{token}" + (f"-retry{attempt}" if attempt else "")
        fut = client.submit(EXECUTE_RUN, plan["uvms"], run["argv"], run["overrides_json"],
                            run["id"], shared, key=key, pure=False)
        live[fut.key] = (fut, run, attempt)
        return fut

    def progress(run_id, word):
        done = len(outcome.finished) + len(outcome.failed) + len(outcome.lost)
        el = time.monotonic() - t0
        eta = clock(el / done * (len(todo) - done)) if done else "--:--"
        print(f"[{skipped + done}/{total}] elapsed {clock(el)}, ETA {eta}  {run_id} {word}",
              file=out, flush=True)

    pending = distributed.as_completed([submit(r, 0) for r in todo])
    try:
        for fut in pending:
            _, run, attempt = live.pop(fut.key)
            try:
                res = fut.result()
            except LOST as e:
                why = f"{type(e).__name__}: {str(e).split('. ')[0]}".strip().rstrip(":")
                if attempt < max_retries:
                    outdir.note(f"run {run['id']} lost ({why:.300}); submitted again "
                                f"({attempt + 1} of at most {max_retries})")
                    try:
                        pending.add(submit(run, attempt + 1))
                        continue
                    except Exception as e2:  # noqa: BLE001  (the client itself is gone)
                        why = f"cannot submit it again: {type(e2).__name__}: {e2}"
                outdir.note(f"run {run['id']} lost ({why:.300}) after {attempt} "
                            "resubmissions: no result")
                outcome.lost.append(run["id"])
                progress(run["id"], "LOST")
                continue
            except Exception as e:  # the task itself raised: a bug, not a lost worker
                outdir.note(f"run {run['id']}: the task raised {type(e).__name__}: {e}")
                outcome.lost.append(run["id"])
                progress(run["id"], "LOST")
                continue
            finally:
                fut.release()  # the worker may drop the run's bytes now
            if verbose:
                outdir.note(f"run {run['id']} ran on {res['host']} (worker pid {res['pid']}), "
                            f"uvms run exit {res['rc']}")
            if res["error"] is None and shared is None:
                try:
                    outdir.write_run_files(plan["out"], run["id"], res["files"])
                except outdir.OutputError as e:
                    res["error"] = str(e)
            if res["error"] is not None:
                outcome.error = f"run {run['id']}: {res['error']}"
                break
            (outcome.finished if res["rc"] == 0 else outcome.failed).append(run["id"])
            progress(run["id"], "finished" if res["rc"] == 0 else "FAILED")
    finally:
        pending.clear()
        if live:  # stopped early (a write failure, an interrupt): nothing more is wanted
            client.cancel([f for f, _, _ in live.values()])
    return outcome


def make_work_dir(out_dir):
    """--shared-fs: DIR/.work/<token>, the parent of the workers' private run directories.
    Earlier campaigns' leftovers (a killed worker's) are removed first: we hold DIR's lock."""
    work = os.path.join(out_dir, ".work")
    shutil.rmtree(work, ignore_errors=True)
    token = uuid.uuid4().hex
    path = os.path.join(work, token)
    try:
        os.makedirs(path)
    except OSError as e:
        raise outdir.OutputError(f"cannot create {path}: {e.strerror}") from None
    return token
