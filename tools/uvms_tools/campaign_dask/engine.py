# SPDX-License-Identifier: Apache-2.0
"""campaign_dask.engine: the runs of a plan as dask.distributed tasks, with progress.

One task per run of state "todo" (client.submit, pure=False, key "uvms-run-<id>-<token>": the
token, fresh per invocation, keeps two campaigns on one shared scheduler from sharing a key,
since dask treats equal keys as the same computation). The scheduler orders and places them;
this module writes no scheduler of its own. It keeps a bounded number of tasks in flight
(in_flight_limit: a few per worker thread, so every worker always has its next task queued)
and submits the next run of the plan as each one completes, so the client's memory (one
future and its bookkeeping per submitted task) does not grow with the campaign; dask
prioritises tasks in submission order, and runs are submitted in plan order.

Lost runs. A worker that dies while running a task: on a LocalCluster the scheduler itself
runs the task again elsewhere up to `distributed.scheduler.allowed-failures` = --max-retries
times (on a remote scheduler, its own setting). A run is lost on one attempt when its future
ends without a result (KilledWorker once that budget is spent, CancelledError or
CommClosedError when the scheduler or the connection went away, the task raised), or when the
worker returns it as "lost" (worker.py: uvms run ended with neither 0 nor 3 and without a
summary.json, the binary missing on that node or killed by a signal; or the worker's scratch
space failed). The client then submits the run again under a new key, at most --max-retries
times; after that the run is lost: it has no result, it is named, and the campaign exits 3. So
a broken node costs retries, not FAILED results: it does not drain the queue into the results.
A run whose `uvms run` exits 0 or 3 (or any status with a summary.json) is a result, written
and reported (finished / FAILED) like `uvms campaign` does, never retried: a failure is a
result of the run's inputs.

Results are written as they arrive (outdir.write_run_files, or by the worker itself under
--shared-fs), so an interrupted campaign keeps every finished run and resumes like
`uvms campaign`. A write into DIR that fails stops the campaign: no further result is
accepted, the remaining tasks are cancelled, exit 3 naming the path.
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

from uvms_tools.campaign_dask import outdir, worker

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
    plain function again. The function's bytes (with worker.py's code, some 18 kB) are made
    once, not once per task."""

    def __init__(self, fn):
        self.fn = fn
        self.pickled = cloudpickle.dumps(fn)

    def __call__(self, *args):
        return self.fn(*args)

    def __reduce__(self):
        return cloudpickle.loads, (self.pickled,)


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


# What must be the same on the client, the scheduler and every worker: the task (a function
# pickled by value with cloudpickle, its result) crosses all three, and dask's own protocol does.
# Python: major.minor (the bytecode of a by-value function is that of one minor version).
SAME_VERSIONS = ("python", "dask", "distributed", "cloudpickle")


def check_versions(client):
    """Raises ValueError naming every mismatch of SAME_VERSIONS between this client, the
    scheduler and the workers of `client`. client.get_versions(check=True) of distributed
    2026.8 only warns about a mismatch (and about every other package too): the comparison is
    made here, on the packages this tool depends on."""
    versions = client.get_versions(check=False)

    def picked(info):
        packages = (info or {}).get("packages") or {}
        out = {k: str(packages.get(k, "MISSING")) for k in SAME_VERSIONS}
        out["python"] = ".".join(out["python"].split(".")[:2])
        return out

    nodes = {"this client": picked(versions.get("client")),
             "the scheduler": picked(versions.get("scheduler"))}
    for addr, info in sorted((versions.get("workers") or {}).items()):
        nodes[f"worker {addr}"] = picked(info)
    mine = nodes["this client"]
    bad = [f"{where}: {k} {v[k]}" for where, v in nodes.items() for k in SAME_VERSIONS
           if v[k] != mine[k]]
    if bad:
        want = ", ".join(f"{k} {mine[k]}" for k in SAME_VERSIONS)
        raise ValueError(f"version mismatch with this client ({want}): {'; '.join(bad[:6])}"
                         f"{'; ...' if len(bad) > 6 else ''}. The scheduler and the workers need "
                         "the same Python minor version and the dask, distributed and "
                         "cloudpickle of tools/requirements.txt")


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
    """MM:SS as `uvms campaign` prints it (Clock in sil/cli/campaign_cmd.cpp)."""
    t = int(seconds + 0.5)
    return f"{t // 60:02d}:{t % 60:02d}"


class Outcome:
    """What happened to the runs to do: ids by result."""

    def __init__(self):
        self.finished, self.failed, self.lost = [], [], []
        self.error = None  # the first write failure: the campaign stopped


# Tasks in flight at most: IN_FLIGHT_PER_THREAD per worker thread of the cluster when the
# campaign starts, and never fewer than MIN_IN_FLIGHT (a cluster still growing gets work for
# the workers about to join). A worker then always has its next tasks queued at the scheduler,
# while the client holds a future for a few hundred runs, not for the whole campaign.
MIN_IN_FLIGHT, IN_FLIGHT_PER_THREAD = 64, 8


def in_flight_limit(client):
    """The bound on tasks in flight for the cluster of `client` (its total worker threads)."""
    try:
        threads = sum(client.nthreads().values())
    except Exception:  # noqa: BLE001  (no answer: the floor is enough to make progress)
        threads = 0
    return max(MIN_IN_FLIGHT, IN_FLIGHT_PER_THREAD * threads)


def run_tasks(client, plan, shared, max_retries, verbose, out=sys.stdout, limit=None):
    """Runs the plan's "todo" runs as tasks; returns an Outcome. `shared` is None (results come
    back to this client) or (DIR, token) (workers write under DIR/.work/<token>). `limit`: the
    bound on tasks in flight (None: in_flight_limit(client))."""
    runs = plan["runs"]
    todo = [r for r in runs if r["state"] == "todo"]
    total, skipped = len(runs), len(runs) - len(todo)
    token = uuid.uuid4().hex[:8]
    limit = limit or in_flight_limit(client)
    outcome = Outcome()
    t0 = time.monotonic()
    live = {}  # future key -> (future, run, resubmissions so far): tasks without an answer
    queue = iter(todo)  # runs not submitted yet, in plan order
    pending = distributed.as_completed()

    def submit(run, attempt):
        key = f"uvms-run-{run['id']}-{token}" + (f"-retry{attempt}" if attempt else "")
        fut = client.submit(EXECUTE_RUN, plan["uvms"], run["argv"], run["overrides_json"],
                            run["id"], shared, plan["inputs"]["base"],
                            run.get("keep_log", True), key=key, pure=False)
        live[fut.key] = (fut, run, attempt)
        pending.add(fut)

    def top_up():
        """Submits the next runs of the plan until `limit` tasks are in flight."""
        while len(live) < limit:
            run = next(queue, None)
            if run is None:
                return
            submit(run, 0)

    def progress(run_id, word):
        done = len(outcome.finished) + len(outcome.failed) + len(outcome.lost)
        elapsed_s = time.monotonic() - t0
        eta = clock(elapsed_s / done * (len(todo) - done)) if done else "--:--"
        print(f"[{skipped + done}/{total}] elapsed {clock(elapsed_s)}, ETA {eta}  "
              f"{run_id} {word}", file=out, flush=True)

    def lost(run, attempt, why):
        """This attempt of `run` has no result: submitted again within --max-retries, else the
        run is lost."""
        if attempt < max_retries:
            outdir.note(f"run {run['id']} lost ({why:.300}); submitted again "
                        f"({attempt + 1} of at most {max_retries})")
            try:
                submit(run, attempt + 1)
                return
            except Exception as e:  # noqa: BLE001  (the client itself is gone)
                why = f"cannot submit it again: {type(e).__name__}: {e}"
        outdir.note(f"run {run['id']} lost ({why:.300}) after {attempt} resubmissions: "
                    "no result")
        outcome.lost.append(run["id"])
        progress(run["id"], "LOST")

    try:
        top_up()
        for fut in pending:
            _, run, attempt = live.pop(fut.key)
            res = why = None
            try:
                res = fut.result()
            except LOST as e:
                why = f"{type(e).__name__}: {str(e).split('. ')[0]}".strip().rstrip(":")
            except Exception as e:  # noqa: BLE001  (the task raised: worth another worker)
                why = f"the task raised {type(e).__name__}: {e}"
            finally:
                fut.release()  # the worker may drop the run's bytes now
            if res is not None and verbose:
                outdir.note(f"run {run['id']} ran on {res['host']} (worker pid {res['pid']}), "
                            f"uvms run exit {res['rc']}")
            if res is not None and (res.get("lost") or res.get("dropped")):
                why, res = res.get("lost") or res.get("dropped"), None
            if res is None:
                lost(run, attempt, why)
                top_up()
                continue
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
            top_up()
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
