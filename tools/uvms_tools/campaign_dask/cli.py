# SPDX-License-Identifier: Apache-2.0
"""campaign-dask: a campaign's runs (`uvms campaign`) as dask.distributed tasks.

    tools/campaign-dask CAMPAIGN.toml --out DIR [--set K=V]... [--transport memq|udpm]
        [--max-runs N] [--retry-failed] [--force-new] [--logs all|failed|none|ID[,ID...]]
        [-j N | --scheduler ADDRESS] [--shared-fs] [--max-retries K]
        [--uvms PATH] [--verbose]

The same campaign as `uvms campaign` (docs/SCENARIOS.md "Campaigns"), with dask placing the
runs on workers, and the same DIR: byte-identical run logs, the same results.csv/results.json,
and either engine resumes what the other started. The division of labour follows one
contract (uvms owns every campaign rule, this tool only moves runs and bytes):

 1. lock DIR (DIR/.campaign.lock, exclusive; busy: exit 4) and hold it to the end;
 2. `uvms campaign ... --plan-only` with the lock handed over: identity check, --force-new,
    plan.json, and the plan as JSON (each run's argv, overrides.json bytes, state). It is
    never re-expanded here;
 3. every "todo" run is one dask task running `uvms run` on a worker (campaign_dask/worker.py)
    exactly as `uvms campaign` runs it; its files come back to this client, which writes them
    into DIR/runs/<id>/ (summary.json last), or with --shared-fs the worker writes them there
    itself (DIR must then be at the same path on every worker); either way runs/<id>/ ends
    up holding exactly the run's files, as `uvms campaign` leaves it; progress, one line per
    run;
 4. `uvms campaign ... --merge` (lock handed over) writes results.csv and results.json.

Exit status: 0 every run finished; 1 bad campaign, or DIR holds another campaign; 2 usage;
3 some run failed or was lost, or a file could not be written (the message names it); 4 DIR is
in use by another campaign. Interrupted (SIGINT/SIGTERM): finished runs are kept, the runs in
flight are abandoned (EPILOG says how, per kind of cluster), and the process ends by that
signal; run the same command again to resume.

Interpreter: see tools/uvms_tools/env.py (re-executes with REPO/.venv/bin/python when needed).
"""
import argparse
import os
import shutil
import signal
import sys

from uvms_tools.env import add_version_option, default_uvms  # noqa: E402
from uvms_tools.campaign_dask import outdir  # noqa: E402  (standard library only; dask loads later)

EPILOG = """\
Each run of state "todo" in the plan is one task; runs already done (and failed ones, unless
--retry-failed) are kept, as `uvms campaign` keeps them. A worker that dies mid-run is
replaced: the scheduler re-runs its task (LocalCluster: allowed-failures = --max-retries), and
a task that still ends lost is submitted again up to --max-retries times; after that the run
is lost (named; exit 3). So is a run whose uvms run ends with neither 0 nor 3 and without a
summary.json (the binary missing on a node, killed by a signal), or whose worker cannot use
its scratch space: such a run says nothing about its inputs and goes to another attempt. A
run that fails (uvms run exit 3, or a summary.json says so) is a result, never retried.
Needs the uvms binary, the campaign's base scenario and (with --shared-fs) DIR at the same
absolute paths on every worker, and (--scheduler) the same Python minor version and the
same dask, distributed and cloudpickle as this client (tools/requirements.txt; checked when
connecting, exit 3). Interrupted (Ctrl-C, SIGTERM): finished runs are kept and the same
command (or uvms campaign) resumes. With local workers (-j) the workers stop with this client and
the runs in flight with them. With --scheduler the client cancels its tasks: the queued ones
never start, but a run already running on a worker runs to its end there, and its result is
dropped: without --shared-fs it is never written into DIR; with --shared-fs the worker sees
that DIR's lock is no longer held and publishes nothing (a run whose publish began in the
instant before the client ended may still land: a complete run of this campaign, which a
resume keeps). docs/CAMPAIGNS.md has more.
Exit status: 0 every run finished; 1 bad campaign or DIR holds another campaign; 2 usage;
3 some run failed or was lost, or a write failed; 4 DIR is in use by another campaign."""


# The command's name in usage and error lines: tools/campaign-dask, or the uvms-campaign-dask
# entry point (run() sets it).
PROG = "tools/campaign-dask"


class Parser(argparse.ArgumentParser):
    def error(self, message):
        sys.stderr.write(f"campaign-dask: error: {message}\n(see {self.prog} --help)\n")
        sys.exit(2)


def count(lo):
    def parse(text):
        try:
            n = int(text, 10)
        except ValueError:
            n = None
        if n is None or n < lo or n > 256:
            raise argparse.ArgumentTypeError(f"needs a count {lo}..256, got {text!r}")
        return n
    return parse


def parse_args(argv):
    p = Parser(prog=PROG, epilog=EPILOG,
               formatter_class=argparse.RawDescriptionHelpFormatter,
               description="Runs a campaign (uvms campaign) as dask.distributed tasks into the "
                           "same DIR, with the same results.")
    add_version_option(p, "campaign-dask")
    p.add_argument("campaign", metavar="CAMPAIGN.toml")
    p.add_argument("--out", required=True, metavar="DIR", help="output directory, as for uvms "
                   "campaign (plan.json, runs/<id>/, results.csv, results.json)")
    p.add_argument("--set", action="append", default=[], metavar="K=V", dest="sets",
                   help="an override of every run, as uvms campaign --set (repeatable)")
    p.add_argument("--transport", metavar="memq|udpm", help="as uvms campaign --transport")
    p.add_argument("--max-runs", metavar="N", help="as uvms campaign --max-runs")
    p.add_argument("--retry-failed", action="store_true", help="run failed runs again")
    p.add_argument("--force-new", action="store_true",
                   help="start afresh in a DIR of another campaign (every run again)")
    logs = p.add_mutually_exclusive_group()
    logs.add_argument("--logs", metavar="all|failed|none|ID[,ID...]",
                      help="which runs keep their run.lcmlog, as uvms campaign --logs (default "
                           "all; failed: only failed runs; IDs: those runs and the failed)")
    logs.add_argument("--no-logs", dest="logs", action="store_const", const="none",
                      help="the same as --logs none")
    where = p.add_mutually_exclusive_group()
    where.add_argument("-j", "--jobs", "--local-workers", type=count(1), metavar="N",
                       dest="local_workers",
                       help="a LocalCluster of N worker processes (1 thread each) on this host "
                            "(default, without --scheduler: all cores, as uvms campaign -j; "
                            "--local-workers is the same)")
    where.add_argument("--scheduler", metavar="ADDRESS",
                       help="a running dask scheduler, e.g. tcp://10.0.0.5:8786")
    p.add_argument("--shared-fs", action="store_true",
                   help="workers write the runs' files under DIR themselves (DIR at the same "
                        "path on every worker) instead of returning them to this client")
    p.add_argument("--max-retries", type=count(0), default=3, metavar="K",
                   help="times a lost run is submitted again (default 3)")
    p.add_argument("--uvms", metavar="PATH",
                   help="the uvms binary (default: $UVMS, else build/host/sil/uvms of this "
                        "repository)")
    p.add_argument("--verbose", action="store_true",
                   help="dask's own log lines, and where each run ran")
    a = p.parse_args(argv)
    if a.scheduler is None and a.local_workers is None:
        a.local_workers = os.cpu_count() or 1
    a.uvms = a.uvms or default_uvms()
    if not (os.path.isfile(a.uvms) and os.access(a.uvms, os.X_OK)):
        p.error(f"--uvms {a.uvms}: not an executable file (build it with cmake --build --preset "
                "host, or give --uvms PATH or $UVMS)")
    if a.scheduler is not None and not a.scheduler.strip():
        p.error("--scheduler needs an address")
    return a


def campaign_args(a):
    """The arguments shared by --plan-only and --merge (the ones the identity and the plan
    depend on); --retry-failed, --force-new and --logs only plan."""
    args = [a.campaign, "--out", a.out]
    for s in a.sets:
        args += ["--set", s]
    if a.transport is not None:
        args += ["--transport", a.transport]
    if a.max_runs is not None:
        args += ["--max-runs", a.max_runs]
    return args


def note_kept_failed(plan):
    """The note `uvms campaign` prints (on stdout) about earlier failed runs it keeps; the
    plan's "failed" state says which (--plan-only prints no notes about the runs)."""
    kept = [r["id"] for r in plan["runs"] if r["state"] == "failed"]
    if kept:
        n = len(kept)
        print(f"campaign-dask: note: {n} of the done runs failed and "
              f"{'is kept as it is' if n == 1 else 'are kept as they are'} (--retry-failed runs "
              f"failed runs again): {', '.join(kept[:5])}{', ...' if n > 5 else ''}", flush=True)


class Interrupted(BaseException):
    """SIGTERM, raised in the main thread like KeyboardInterrupt is for SIGINT."""


def on_sigterm(signum, frame):
    raise Interrupted()


def plan_campaign(a, lock):
    """`uvms campaign ... --plan-only` under our lock: (exit status, plan or None)."""
    plan_flags = [f for f, on in (("--retry-failed", a.retry_failed),
                                  ("--force-new", a.force_new)) if on]
    if a.logs is not None:
        plan_flags += ["--logs", a.logs]
    rc, text = outdir.uvms_campaign(a.uvms, lock, campaign_args(a) + plan_flags +
                                    ["--plan-only"], capture=True)
    if rc != 0:
        return rc, None  # uvms said why on stderr; its statuses are ours
    try:
        return 0, outdir.read_plan(text)
    except ValueError as e:
        outdir.note(f"error: {a.uvms} campaign --plan-only printed no plan ({e}); is it a uvms "
                    "of this repository's version?")
        return outdir.EXIT_FAILED, None


def run_plan(a, plan):
    """The plan's runs to do as dask tasks; returns the engine's Outcome (None: nothing to do).
    Raises outdir.CampaignStop (a write failed, no cluster to run on), KeyboardInterrupt or
    Interrupted."""
    todo = sum(r["state"] == "todo" for r in plan["runs"])
    head = f"campaign-dask: {plan['name']}: {len(plan['runs'])} runs " \
           f"({len(plan['runs']) - todo} already done)"
    if not todo:
        print(f"{head}, nothing to run", flush=True)
        note_kept_failed(plan)
        return None
    transport = next((r["argv"][i + 1] for r in plan["runs"][:1]
                      for i, x in enumerate(r["argv"][:-1]) if x == "--transport"), "?")
    if not a.verbose:  # before dask is imported: the spawned workers inherit it too
        os.environ.setdefault("DASK_LOGGING__DISTRIBUTED", "critical")
    try:
        from uvms_tools.campaign_dask import engine, worker
    except ImportError as e:  # an interpreter without the venv's packages
        raise outdir.CampaignStop(f"{e}: dask.distributed is not importable by "
                                  f"{sys.executable} (tools/bootstrap installs it into .venv)") \
            from None
    if not a.verbose:
        engine.quiet_logs()
    work = os.path.join(plan["out"], ".work")
    shared = (plan["out"], engine.make_work_dir(plan["out"])) if a.shared_fs else None
    client = cluster = None
    try:
        try:
            client, cluster, where = engine.start_client(a.local_workers, a.scheduler,
                                                         a.max_retries, a.verbose)
        except (OSError, ValueError, RuntimeError) as e:  # unreachable, bad address, no spawn
            what = f"connect to the dask scheduler {a.scheduler}" if a.scheduler else \
                f"start a LocalCluster of {a.local_workers} workers"
            raise outdir.CampaignStop(f"cannot {what}: {type(e).__name__}: {e}; no run was "
                                      "started") from None
        if a.scheduler:  # a LocalCluster runs this very interpreter
            try:
                engine.check_versions(client)
            except (OSError, ValueError, RuntimeError) as e:
                raise outdir.CampaignStop(f"the dask cluster at {a.scheduler}: {e}; no run was "
                                          "started") from None
        n = len(client.nthreads())
        link = engine.dashboard_link(client)
        print(f"{head}, {todo} to run on {n} dask worker{'s' if n != 1 else ''} ({where}), "
              f"transport {transport}" + (f"; dashboard {link}" if link else ""), flush=True)
        note_kept_failed(plan)
        return engine.run_tasks(client, plan, shared, a.max_retries, a.verbose)
    finally:  # also when interrupted: the local workers end, and their runs with them (the
        # runs of a remote cluster finish there; their results are dropped: EPILOG)
        # The local workers and their runs, known before they are stopped: a run its worker
        # left behind (interrupted: PDEATHSIG) may still write into its scratch directory for a
        # moment, so the directories are removed once every one of them has ended.
        local = _descendants() if cluster is not None else []
        if client is not None:
            client.close(timeout=10)
        if cluster is not None:
            cluster.close(timeout=10)
            _wait_ended(local)
            # The workers were on this host, so this process can remove what they left.
            worker.remove_stale_temp_dirs()
        if shared:  # DIR/.work/<token>, and DIR/.work when nothing else is in it
            shutil.rmtree(os.path.join(work, shared[1]), ignore_errors=True)
            try:
                os.rmdir(work)
            except OSError:
                pass


def _descendants():
    """This process's descendants that end with the cluster (the local workers and their runs);
    [] if unknown. Not multiprocessing's resource tracker: it lives until this process exits,
    so waiting for it cost every campaign the full timeout of _wait_ended (10 s)."""
    import psutil  # here, not at the top: --help and usage errors load nothing heavy
    try:
        procs = psutil.Process().children(recursive=True)
    except psutil.Error:
        return []
    return [p for p in procs if not _is_resource_tracker(p)]


def _is_resource_tracker(proc):
    import psutil
    try:
        return any("multiprocessing.resource_tracker" in part for part in proc.cmdline())
    except psutil.Error:  # already gone: nothing to wait for either
        return True


def _wait_ended(procs, timeout_s=10.0):
    """Waits (up to timeout_s) until every process of `procs` has ended."""
    import psutil
    psutil.wait_procs(procs, timeout=timeout_s)


def report_stop(a, outcome):
    if outcome.error:
        outdir.note(f"error: {outcome.error}")
    if outcome.lost:
        n = len(outcome.lost)
        outdir.note(f"{n} run{'s' if n != 1 else ''} lost, without a result (why: above): "
                    f"{', '.join(outcome.lost[:5])}{', ...' if n > 5 else ''}")
    outdir.note("the campaign stopped: results not written (the same command runs the runs "
                "without a result)")


def main(argv):
    a = parse_args(argv)
    new_dir = not os.path.isdir(a.out)
    try:
        os.makedirs(a.out, exist_ok=True)
    except OSError as e:
        outdir.note(f"error: cannot create the output directory {a.out}: {e.strerror}")
        return outdir.EXIT_FAILED
    try:
        lock = outdir.OutDirLock(a.out)  # held until this process ends
    except outdir.Busy as e:
        outdir.note(f"error: {e}")
        return outdir.EXIT_BUSY
    except outdir.OutputError as e:
        outdir.note(f"error: {e}")
        return outdir.EXIT_FAILED
    rc, plan = plan_campaign(a, lock)
    if plan is None:
        if new_dir:
            outdir.remove_if_only_lock(a.out)
        return rc
    try:
        outcome = run_plan(a, plan)
    except outdir.CampaignStop as e:
        outdir.note(f"error: {e}")
        return outdir.EXIT_FAILED
    if outcome is not None and (outcome.error or outcome.lost):
        report_stop(a, outcome)
        return outdir.EXIT_FAILED
    rc, text = outdir.uvms_campaign(a.uvms, lock, campaign_args(a) + ["--merge"], capture=True)
    lines = (text or "").strip().splitlines()
    if lines:
        print(lines[-1], flush=True)
    return rc


def die_by(signum):
    """After an interruption: end by the signal itself, as a parent (a shell, a batch system)
    expects of an interrupted program."""
    sys.stdout.flush()
    print(f"campaign-dask: interrupted ({signal.Signals(signum).name}): the runs in flight are "
          "abandoned (with --scheduler they finish on their workers and their results are "
          "dropped); finished runs are kept (the same command resumes)", file=sys.stderr,
          flush=True)
    signal.signal(signum, signal.SIG_DFL)
    os.kill(os.getpid(), signum)
    sys.exit(128 + signum)


def run(argv=None, prog=None):
    """The command line (tools/campaign-dask, the uvms-campaign-dask entry point): main with
    SIGTERM and Ctrl-C turned into an orderly stop that ends by the signal. prog: the name in
    usage and error lines (default: how it was invoked)."""
    global PROG
    PROG = prog or os.path.basename(sys.argv[0])
    signal.signal(signal.SIGTERM, on_sigterm)
    try:
        return main(sys.argv[1:] if argv is None else argv)
    except KeyboardInterrupt:
        die_by(signal.SIGINT)
    except Interrupted:
        die_by(signal.SIGTERM)
    return outdir.EXIT_FAILED  # not reached: die_by ends the process
