#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""bench/campaign_scale.py: a 10,000-run Monte Carlo campaign on this machine, through
`uvms campaign -j 2` and through `tools/campaign-dask --local-workers 2`, measured.

    bench/campaign_scale.py              measure, print the table (markdown) and the JSON
    bench/campaign_scale.py --update     measure, and write the table into
                                               docs/BENCHMARKS.md between the markers
                                               <!-- campaign-scale:begin --> and
                                               <!-- campaign-scale:end -->
    bench/campaign_scale.py --seeds 25   a smaller campaign (4 x 4 x 25 = 400 runs)
    bench/campaign_scale.py --from-json OUT/campaign_scale.json [--update]
                                               the table again from an earlier run's figures

The campaign (written to OUT/mc_scale.toml): case VII in unsteady flow (the paper's
sil/scenarios/paper/case_VII_unsteady.toml), every run shortened to --duration-s of simulated
time (default 10 s, 334 ticks), swept over 4 payload masses x 4 flow amplitudes, each
replicated over --seeds seeds (default 625): 10,000 runs. Both engines run it with --no-logs
(summaries only) into OUT/campaign and OUT/dask; then the two directories are compared as the
engines promise (tests/sil/campaign_compare.py: identical apart from the wall-clock fields).
A further 96 runs with logs (4 x 4 x 6 seeds) give the disk per run with logs and their gzip
ratio.

Measured, per engine: wall time, runs per minute, simulated seconds per wall second, the peak
memory of the whole process tree (sum of RSS, sampled every 0.2 s with psutil) and of its
largest process, the disk per run, and the CPU time of the engine's main process per run.
From these, by arithmetic: runs per hour on N such machines under Dask, and the limits (the
client's CPU per run, the result bytes through one 1 Gbit/s link, the disk). For Dask, the scheduler's overhead per task: 2,000 empty
tasks on the same LocalCluster, submitted at once and gathered (wall time / task), and the
engine's overhead per run against `uvms campaign` (the difference of their wall times / runs).

Last, the same `uvms campaign` again right after deleting the first one's output
(OUT/campaign, its 40,000 files and directories), as `rm -rf out && uvms campaign ... --out out`
does: on ext4 without a journal the kernel avoids reusing an inode freed in the last minute (six
while its inode table block is not yet written back), and each new file or directory checks the
recently freed ones one by one, reading each one's deletion time. So the first
measurements run on a fresh OUT: an OUT left by an earlier measurement is renamed aside first
and deleted only after the last measurement.

Environment: UVMS=PATH (default build/host/sil/uvms); OUT=DIR (default build/campaign-scale;
replaced). Takes about 8 minutes at the defaults on 2 cores; keep the machine quiet.
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.path.insert(0, os.path.join(ROOT, "tests", "sil"))
from doc_block import machine, publish  # noqa: E402 (bench/, the script's directory)

PAYLOADS_KG = [0.0, 1.0, 5.0, 10.0]
AMPLITUDES_M_S = [0.01, 0.02, 0.05, 0.1]
BEGIN, END = "<!-- campaign-scale:begin -->", "<!-- campaign-scale:end -->"


def campaign_text(seeds, duration_s, name="mc_scale"):
    base = os.path.join(ROOT, "sil", "scenarios", "paper", "case_VII_unsteady.toml")
    return (f'name = "{name}"\n'
            'description = "scale benchmark: seeds x payload x flow amplitude (bench/)"\n'
            f'base = "{base}"\n[set]\n"run.duration_s" = {duration_s}\n'
            f'"trajectory.duration_s" = {duration_s}\n'
            '"environment.unsteady_flow.enabled" = true\n'
            f'[[sweep]]\n"payload.mass_kg" = {json.dumps(PAYLOADS_KG)}\n'
            f'[[sweep]]\n"environment.unsteady_flow.amplitude_m_s" = {json.dumps(AMPLITUDES_M_S)}\n'
            f'[replicates]\nkey = "run.seed"\nfirst = 1\ncount = {seeds}\n')


def tree_rss(proc):
    """(sum of RSS, largest RSS) in bytes over `proc` and its descendants."""
    import psutil
    try:
        procs = [proc] + proc.children(recursive=True)
    except psutil.Error:
        return 0, 0
    sizes = []
    for p in procs:
        try:
            sizes.append(p.memory_info().rss)
        except psutil.Error:
            pass
    return sum(sizes), max(sizes, default=0)


def run_measured(argv, log_path):
    """Runs argv with its output into log_path; returns (exit, wall s, peak tree RSS, peak
    largest-process RSS, CPU s of the main process), sampled every 0.2 s. The main process is
    the engine's centre: `uvms campaign` itself, or the Dask client with its LocalCluster's
    scheduler (which runs in the client's process)."""
    import psutil
    peak = [0, 0, 0.0]
    with open(log_path, "w") as log:
        t0 = time.monotonic()
        p = subprocess.Popen(argv, stdout=log, stderr=subprocess.STDOUT)
        ps = psutil.Process(p.pid)
        done = threading.Event()

        def sample():
            while not done.is_set():
                total, largest = tree_rss(ps)
                peak[0], peak[1] = max(peak[0], total), max(peak[1], largest)
                try:
                    cpu = ps.cpu_times()
                    peak[2] = max(peak[2], cpu.user + cpu.system)
                except psutil.Error:
                    pass
                done.wait(0.2)
        t = threading.Thread(target=sample, daemon=True)
        t.start()
        rc = p.wait()
        wall = time.monotonic() - t0
        done.set()
        t.join()
    return rc, wall, peak[0], peak[1], peak[2]


def disk_bytes(path):
    """(allocated bytes, apparent bytes) under path."""
    alloc = apparent = 0
    for dp, _, files in os.walk(path):
        for f in files:
            st = os.lstat(os.path.join(dp, f))
            alloc += st.st_blocks * 512
            apparent += st.st_size
    return alloc, apparent


def simulated_s(out):
    with open(os.path.join(out, "results.json")) as f:
        rows = json.load(f)["runs"]
    return sum(r.get("duration_s") or 0.0 for r in rows), len(rows), sum(
        r.get("status") == "finished" for r in rows)


def measure_engine(name, argv, out, work):
    rc, wall, rss_tree, rss_max, main_cpu = run_measured(argv, os.path.join(work, f"{name}.log"))
    if rc != 0:
        sys.exit(f"campaign_scale: {name} exited {rc}; see {work}/{name}.log")
    sim, runs, finished = simulated_s(out)
    alloc, apparent = disk_bytes(os.path.join(out, "runs"))
    return {"engine": name, "wall_s": wall, "runs": runs, "finished": finished,
            "simulated_s": sim, "runs_per_min": runs / wall * 60.0, "sim_s_per_wall_s": sim / wall,
            "peak_rss_tree_MiB": rss_tree / 2**20, "peak_rss_largest_MiB": rss_max / 2**20,
            "disk_per_run_KiB": alloc / runs / 1024, "apparent_per_run_KiB": apparent / runs / 1024,
            "main_cpu_ms_per_run": main_cpu / runs * 1e3}


def dask_task_overhead(n_tasks=2000, workers=2):
    """Wall seconds per empty task on a LocalCluster like the engine's (submit all, gather)."""
    import dask
    from distributed import Client, LocalCluster
    dask.config.set({"logging.distributed": "error"})
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        client.gather(client.map(int, range(workers * 4), pure=False))  # warm the workers
        t0 = time.monotonic()
        futures = client.map(int, range(n_tasks), pure=False)
        client.gather(futures)
        return (time.monotonic() - t0) / n_tasks


def logged_sample(uvms, work, duration_s, runs=100):
    """Disk per run with logs, from `runs` runs of the same campaign; the log's gzip ratio."""
    import gzip
    seeds = max(1, runs // (len(PAYLOADS_KG) * len(AMPLITUDES_M_S)))
    camp = os.path.join(work, "mc_logged.toml")
    with open(camp, "w") as f:
        f.write(campaign_text(seeds, duration_s, "mc_logged"))
    out = os.path.join(work, "logged")
    subprocess.run([uvms, "campaign", camp, "--out", out, "-j", "2"], check=True,
                   stdout=subprocess.DEVNULL)
    alloc, _ = disk_bytes(os.path.join(out, "runs"))
    n = len(os.listdir(os.path.join(out, "runs")))
    log = os.path.join(out, "runs", sorted(os.listdir(os.path.join(out, "runs")))[0], "run.lcmlog")
    with open(log, "rb") as f:
        raw = f.read()
    return {"runs": n, "disk_per_run_KiB": alloc / n / 1024, "log_KiB": len(raw) / 1024,
            "gzip_ratio": len(raw) / len(gzip.compress(raw, 6))}


def table(res):
    c, d = res["campaign"], res["dask"]
    lines = [
        f"Measured by `bench/campaign_scale.py` on {res['machine']}: {c['runs']:,} runs of "
        f"{res['duration_s']:g} s simulated each "
        f"(case VII, unsteady flow; 4 payloads x 4 flow amplitudes x {res['seeds']} seeds), "
        "`--no-logs`.",
        "",
        "| engine | wall | runs/min | simulated s per wall s | peak memory, all processes "
        "(largest one) | disk per run |",
        "|---|---|---|---|---|---|",
    ]
    for name, r in (("`uvms campaign -j 2`", c), ("`tools/campaign-dask --local-workers 2`", d)):
        lines.append(f"| {name} | {r['wall_s']:.0f} s | {r['runs_per_min']:,.0f} | "
                     f"{r['sim_s_per_wall_s']:.0f} | {r['peak_rss_tree_MiB']:.0f} MiB "
                     f"({r['peak_rss_largest_MiB']:.0f} MiB) | {r['disk_per_run_KiB']:.1f} KiB |")
    lg = res["logged"]
    ad = res.get("campaign_after_delete")  # absent from the figures of older runs
    lines += [
        "",
    ] + ([
        f"- `uvms campaign -j 2` again, right after deleting the first one's output "
        f"({c['runs'] * 4:,} files and directories): {ad['wall_s']:.0f} s "
        f"({ad['wall_s'] / c['wall_s']:.2f}x the fresh directory's time; one run each, the "
        f"fresh one first, minutes apart), on {res.get('file_system', 'this file system')}."
        + ((" Without a journal, ext4 avoids reusing an inode freed in the last minute (six "
            "while its inode table block is dirty), checking each such inode when it creates a "
            "file (docs/CAMPAIGNS.md, \"Writing into a directory just emptied\")."
            if ad['wall_s'] / c['wall_s'] >= 1.03 else
            " No cost of the deletion measurable here (under 3 %); the mechanism that can "
            "cost a campaign after a deletion on ext4 without a journal is in docs/CAMPAIGNS.md, "
            "\"Writing into a directory just emptied\".")
           if res.get("file_system") == "ext4 without a journal" else ""),
    ] if ad else []) + [
        f"- Finished runs: {c['finished']:,}/{c['runs']:,} (`uvms campaign`), "
        f"{d['finished']:,}/{d['runs']:,} (Dask). The two directories compared file by file "
        f"(tests/sil/campaign_compare.py): {res['differences']} difference(s) apart from the "
        "wall-clock fields.",
        f"- With logs ({lg['runs']} runs of the same campaign): {lg['disk_per_run_KiB']:.0f} KiB "
        f"per run on disk, of which the log is {lg['log_KiB']:.0f} KiB; gzip -6 shrinks a log "
        f"{lg['gzip_ratio']:.1f}x. 10,000 logged runs: "
        f"{lg['disk_per_run_KiB'] * 10000 / 2**20:.1f} GiB.",
        f"- Dask scheduler overhead: {res['dask_empty_task_ms']:.2f} ms per empty task "
        f"(2,000 tasks, LocalCluster of 2 workers); the engine as a whole: "
        f"{res['dask_overhead_per_run_ms']:.1f} ms per run more than `uvms campaign` "
        "(planning, the task, the worker's process start, returning and writing the files).",
        "",
    ] + estimate(res)
    return "\n".join(lines)


def estimate(res):
    """Runs per hour on N machines of this kind under Dask, by arithmetic from the figures
    measured above, and what limits it."""
    d, lg = res["dask"], res["logged"]
    per_machine_h = d["runs_per_min"] * 60.0
    centre_ms = d["main_cpu_ms_per_run"]          # client + scheduler CPU per run
    centre_h = 3600e3 / centre_ms
    sched_h = 3600e3 / res["dask_empty_task_ms"]  # the scheduler alone, empty tasks
    link_Bps = 1e9 / 8                             # one 1 Gbit/s link into the client
    bytes_bare = d["apparent_per_run_KiB"] * 1024
    bytes_logged = bytes_bare + lg["log_KiB"] * 1024
    link_bare_h, link_logged_h = 3600 * link_Bps / bytes_bare, 3600 * link_Bps / bytes_logged
    rows = []
    for n in (1, 10, 100, 1000):
        rows.append(f"| {n:,} | {n * per_machine_h:,.0f} | "
                    f"{min(n * per_machine_h, centre_h, link_bare_h):,.0f} |")
    n_centre = centre_h / per_machine_h
    return [
        f"Estimate for N machines of this kind under Dask (arithmetic from the figures above; "
        f"each machine a worker per core, as here: {per_machine_h:,.0f} runs/h):",
        "",
        "| machines | N x one machine, runs/h | capped by the client (summaries only), runs/h |",
        "|---|---|---|",
    ] + rows + [
        "",
        f"- The client: its process (which here also hosts the LocalCluster's scheduler) spent "
        f"{centre_ms:.1f} ms of CPU per run (planning, submitting, the scheduler's share, "
        f"receiving the files and writing them with fsync); one core of it caps the campaign "
        f"near {centre_h:,.0f} runs/h, reached at about {n_centre:,.0f} machines. (Here the "
        "client shares the 2 cores with the workers, so one machine's rate above is a floor for "
        "a machine that only runs workers.) The scheduler alone handled an empty task "
        f"in {res['dask_empty_task_ms']:.2f} ms ({sched_h:,.0f} tasks/h). Past that, "
        "`--shared-fs` takes the file writing off the client; runs longer than "
        f"{res['duration_s']:g} s raise the machine count the client can feed in proportion.",
        f"- Result transfer: {bytes_bare / 1024:.1f} KiB per run summary-only, "
        f"{bytes_logged / 2**20:.2f} MiB with its log; one 1 Gbit/s link into the client "
        f"carries {link_bare_h:,.0f} runs/h summary-only, {link_logged_h:,.0f} runs/h with logs.",
        f"- Disk at DIR: {d['disk_per_run_KiB']:.0f} KiB per run summary-only (4 inodes), "
        f"{lg['disk_per_run_KiB']:.0f} KiB with logs: a million runs need "
        f"{d['disk_per_run_KiB'] * 1e6 / 2**20:.0f} GiB, or {lg['disk_per_run_KiB'] * 1e6 / 2**20:,.0f} "
        "GiB with logs.",
    ]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog="\n\n".join(__doc__.split("\n\n")[1:]))
    ap.add_argument("--seeds", type=int, default=625, help="seeds per configuration [625]")
    ap.add_argument("--duration-s", type=float, default=10.0, help="simulated s per run [10]")
    ap.add_argument("--update", action="store_true", help="write the table into BENCHMARKS.md")
    ap.add_argument("--from-json", metavar="F", help="no measurement: the figures of an earlier "
                    "run (its OUT/campaign_scale.json)")
    args = ap.parse_args()
    if args.from_json:
        with open(args.from_json) as f:
            res = json.load(f)
        return report(res, args.update)
    uvms = os.path.abspath(os.environ.get("UVMS", os.path.join(ROOT, "build/host/sil/uvms")))
    work = os.path.abspath(os.environ.get("OUT", os.path.join(ROOT, "build/campaign-scale")))
    aside = set_aside(work)
    try:
        res = measure(uvms, work, args)
    finally:
        for d in aside:
            shutil.rmtree(d, ignore_errors=True)
    return report(res, args.update)


def set_aside(work):
    """Renames an earlier OUT (and any left aside by an interrupted measurement) out of the way
    so that the measurements write into a fresh OUT; returns the directories to delete after
    them. A rename frees no inode (docstring: deleting first would slow the campaigns)."""
    parent, base = os.path.split(work)
    os.makedirs(parent, exist_ok=True)
    aside = [os.path.join(parent, n) for n in os.listdir(parent) if n.startswith(base + ".old-")]
    if os.path.exists(work):
        dest = f"{work}.old-{os.getpid()}"
        os.rename(work, dest)
        aside.append(dest)
    return aside


def file_system(path):
    """The file system under path, as the table names it: its type, and for ext4 whether it
    has a journal (the kernel lists a journaled ext4 device in /proc/fs/jbd2)."""
    try:  # --nofsroot: a bind mount's SOURCE without its [/subdirectory]
        lines = subprocess.run(["findmnt", "--nofsroot", "-no", "FSTYPE,SOURCE", "-T", path],
                               capture_output=True, text=True, check=False).stdout.splitlines()
    except OSError:
        lines = []
    out = lines[-1].split() if lines else []  # stacked mounts: the last line is the visible one
    if len(out) != 2:
        return "a file system findmnt did not name"
    fstype, dev = out
    if fstype != "ext4":
        return fstype
    try:
        journals = os.listdir("/proc/fs/jbd2")
    except OSError:
        return "ext4"
    name = os.path.basename(os.path.realpath(dev))
    return "ext4 with a journal" if any(j.startswith(name + "-") for j in journals) else \
        "ext4 without a journal"


def measure(uvms, work, args):
    """Every measurement into the fresh directory `work`; returns the figures."""
    os.makedirs(work)
    camp = os.path.join(work, "mc_scale.toml")
    with open(camp, "w") as f:
        f.write(campaign_text(args.seeds, args.duration_s))
    res = {"seeds": args.seeds, "duration_s": args.duration_s,
           "machine": machine(), "file_system": file_system(work)}
    res["campaign"] = measure_engine(
        "campaign", [uvms, "campaign", camp, "--out", os.path.join(work, "campaign"), "-j", "2",
                     "--no-logs"], os.path.join(work, "campaign"), work)
    res["dask"] = measure_engine(
        "dask", [sys.executable, os.path.join(ROOT, "tools", "campaign-dask"), camp, "--out",
                 os.path.join(work, "dask"), "--local-workers", "2", "--no-logs", "--uvms", uvms],
        os.path.join(work, "dask"), work)
    from campaign_compare import differences
    diffs = differences(os.path.join(work, "campaign"), os.path.join(work, "dask"))
    res["differences"] = len(diffs)
    res["first_differences"] = diffs[:5]
    res["dask_empty_task_ms"] = dask_task_overhead() * 1e3
    res["dask_overhead_per_run_ms"] = (res["dask"]["wall_s"] - res["campaign"]["wall_s"]) / \
        res["campaign"]["runs"] * 1e3
    res["logged"] = logged_sample(uvms, work, args.duration_s)
    # Last: `uvms campaign` again right after its first output is deleted (the docstring).
    shutil.rmtree(os.path.join(work, "campaign"))
    res["campaign_after_delete"] = measure_engine(
        "campaign_after_delete", [uvms, "campaign", camp, "--out", os.path.join(work, "campaign"),
                                  "-j", "2", "--no-logs"], os.path.join(work, "campaign"), work)
    with open(os.path.join(work, "campaign_scale.json"), "w") as f:
        json.dump(res, f, indent=2)
    return res


def report(res, update):
    """Prints the figures and the table; writes the table into BENCHMARKS.md with `update`.
    Returns the exit status: 1 when the engines' directories differed."""
    text = table(res)
    print(json.dumps(res, indent=2))
    publish(BEGIN, END, text, update)
    return 0 if res["differences"] == 0 else 1


if __name__ == "__main__":
    from uvms_tools.env import reexec_in_venv
    reexec_in_venv(__file__)
    sys.exit(main())
