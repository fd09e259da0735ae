# SPDX-License-Identifier: Apache-2.0
"""The cluster templates (tools/cluster/, docs/CAMPAIGNS.md): rendered by tools/cluster/render,
each is checked for its structure and then run here, shard by shard, exactly as the scheduler
would run it (the Slurm script with SLURM_ARRAY_TASK_ID = 1..N; the Indexed Job's container
command through `sh -c` with JOB_COMPLETION_INDEX = 0..N-1 after Kubernetes' own $(VAR)
expansion, the volume's mount path mapped to a temporary directory), the shards at the same time
on one campaign directory, then the merge. The merged results are checked against a plain
`uvms campaign` of the same campaign: every run exactly once, in plan order, run by the shard
that round-robin assigns it (plan index k by shard k % N + 1), with the same summaries (all but
the wall-clock fields) and byte-identical logs.

  slurm: the script passes `bash -n`, its #SBATCH header asks for the array 1-N, the cores and
         the time rendered; --help prints the header; --submit submits the shards and then the
         merge with --dependency=afterany (a stand-in sbatch records both calls); a task id
         outside 1..N is refused; paths with spaces and a --set value with quotes survive.
  k8s:   two batch/v1 Jobs parse (yaml.safe_load_all): the shards' Indexed Job (completions N,
         1 <= parallelism <= N, restartPolicy Never, per-index retries, no retry of exit 1-3,
         the command deriving --shard from JOB_COMPLETION_INDEX, requests = limits = -j cores)
         and the merge Job (suspended, --merge, the same claim, mount, campaign, --out and --set);
         every volume mount names a volume of the ReadWriteMany claim and --out lies under it;
         rendering without --image, or with --out outside the mount, is refused. The campaign
         is summary-only (--no-logs): no run keeps a log, as in the plain campaign. Each pod's
         command runs as PID 1 of its own PID namespace, as in a container (unshare(1), when
         this machine allows it: root or user namespaces; otherwise a note says so).

  k8s_paths: rendered with "$" in the mount, --out and --campaign: after Kubernetes' expansion
         of the env values, OUT and CAMPAIGN name the given directories under the volume's
         mountPath (which it does not expand) in both Jobs.

Usage: test_cluster_templates.py UVMS_EXE SOURCE_DIR CASE   (CASE: slurm | k8s | k8s_paths)
"""
import json
import os
import re
import shlex
import shutil
import stat
import subprocess
import sys
import tempfile
import time

UVMS, SRC, CASE = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), sys.argv[3]
RENDER = os.path.join(SRC, "tools", "cluster", "render")
BASE = os.path.join(SRC, "sil", "scenarios", "paper", "case_IV_stagnant.toml")
TMP = tempfile.mkdtemp(prefix="uvms-cluster-")
SHARDS = 3  # 4 runs over 3 shards: one shard gets two runs, the others one
# A --set given to every shard and the merge (the campaign's identity includes it): quotes and a
# space-free value that the sweep overrides, so the results are those of the campaign file.
SETS = ['control.case="IV"']
# The wall-clock fields of a summary: the only ones that differ between two runs of the same run.
WALL_CLOCK_FIELDS = {"wall_time_s", "real_time_factor", "plant_wall_s"}

# 4 runs of 1.5 s simulated (tests/sil/test_campaign_e2e.py's TINY).
TINY = f"""name = "tiny"
base = "{BASE}"
[set]
"run.duration_s" = 1.5
"trajectory.duration_s" = 1.5
"link.realtime_factor" = 4.0
[[sweep]]
"control.case" = ["IV", "VII"]
[[sweep]]
"payload.mass_kg" = [0.0, 5.0]
"""


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    return path


def render(template, *args, expect=0):
    p = subprocess.run([sys.executable, RENDER, os.path.join(SRC, "tools", "cluster", template),
                        *args], capture_output=True, text=True, timeout=30)
    if p.returncode != expect:
        fail(f"render {template} {shlex.join(args)}: exit {p.returncode}, expected {expect}: "
             f"{p.stderr.strip()}")
    if expect == 0 and "{{" in p.stdout:
        fail(f"render {template}: placeholders left: "
             f"{sorted(set(re.findall(r'{{[A-Z_]+}}', p.stdout)))}")
    return p.stdout if expect == 0 else p.stderr


def run_shards(commands):
    """Start every shard at once (they share the campaign directory), wait for all."""
    t0 = time.monotonic()
    procs = [subprocess.Popen(argv, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              text=True, stdin=subprocess.DEVNULL) for argv, env in commands]
    outs = [p.communicate(timeout=240)[0] for p in procs]
    print(f"{len(procs)} shards at once: {time.monotonic() - t0:.1f} s")
    for i, (p, out) in enumerate(zip(procs, outs), 1):
        print(f"--- shard {i}/{len(procs)}: exit {p.returncode}\n{out}")
        if p.returncode != 0:
            fail(f"shard {i}/{len(procs)} exited {p.returncode}, expected 0 (every run finished)")
    return outs


def plain_campaign(camp, *extra):
    out = os.path.join(TMP, "plain")
    sets = [w for s in SETS for w in ("--set", s)]
    p = subprocess.run([UVMS, "campaign", camp, "--out", out, "-j", "1", *sets, *extra],
                       capture_output=True, text=True, timeout=240, stdin=subprocess.DEVNULL)
    if p.returncode != 0:
        fail(f"plain uvms campaign: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return out


def load(path):
    with open(path) as f:
        return json.load(f)


def check_against_plain(sharded, plain, shard_outputs, logs):
    """The merged campaign in `sharded` equals the plain one in `plain` (module docstring)."""
    plan = [r["id"] for r in load(os.path.join(sharded, "plan.json"))["runs"]]
    if [r["id"] for r in load(os.path.join(plain, "plan.json"))["runs"]] != plan:
        fail("the sharded and the plain campaign have different plans")
    if len(plan) != 4 or len(set(plan)) != 4:
        fail(f"plan {plan}: expected 4 distinct runs")
    # Each run was run by its round-robin shard only (the progress line names it).
    for k, rid in enumerate(plan):
        by = [i + 1 for i, out in enumerate(shard_outputs)
              if re.search(rf"(^|\s){re.escape(rid)} finished", out, re.M)]
        if by != [k % SHARDS + 1]:
            fail(f"run {rid} (plan index {k}) reported finished by shard(s) {by}, "
                 f"expected shard {k % SHARDS + 1} of {SHARDS} only")
    got, want = load(os.path.join(sharded, "results.json")), load(os.path.join(plain, "results.json"))
    ids = [r["id"] for r in got["runs"]]
    if ids != plan:
        fail(f"merged results.json ids {ids}, expected every run once in plan order {plan}")
    if [r["status"] for r in got["runs"]] != [r["status"] for r in want["runs"]] or \
       any(r["status"] != "finished" for r in got["runs"]):
        fail("statuses differ from the plain campaign's (or a run did not finish): "
             f"{[(r['id'], r['status']) for r in got['runs']]}")
    for g, w in zip(got["runs"], want["runs"]):
        diff = sorted(k for k in set(g) | set(w)
                      if k not in WALL_CLOCK_FIELDS and g.get(k) != w.get(k))
        if diff:
            fail(f"run {g['id']}: merged row differs from the plain campaign's in {diff}")
    head = {k: v for k, v in got.items() if k != "runs"}
    if head != {k: v for k, v in want.items() if k != "runs"}:
        fail("results.json's identity, provenance or header differs from the plain campaign's")
    with open(os.path.join(sharded, "results.csv")) as f:
        rows = f.read().splitlines()[1:]
    if len(rows) != len(plan):
        fail(f"results.csv has {len(rows)} rows, expected {len(plan)}")
    for rid in plan:
        a, b = (os.path.join(d, "runs", rid, "run.lcmlog") for d in (sharded, plain))
        if not logs:
            if os.path.exists(a) or os.path.exists(b):
                fail(f"run {rid} kept a log in a --no-logs campaign")
            continue
        with open(a, "rb") as fa, open(b, "rb") as fb:
            if fa.read() != fb.read():
                fail(f"run {rid}: run.lcmlog differs between the sharded and the plain campaign")
    print(f"ok: {len(plan)} runs, each once, by its round-robin shard; rows and "
          f"{'logs' if logs else 'the absence of logs'} as in the plain campaign")


def check_no_results_yet(out):
    for name in ("results.json", "results.csv"):
        if os.path.exists(os.path.join(out, name)):
            fail(f"a shard wrote {name}; only the merge may")
    if not os.path.exists(os.path.join(out, "plan.json")):
        fail("the shards wrote no plan.json")


def merge(argv, env):
    p = subprocess.run(argv, env=env, capture_output=True, text=True, timeout=120,
                       stdin=subprocess.DEVNULL)
    print(f"--- merge: exit {p.returncode}\n{p.stdout}{p.stderr}")
    if p.returncode != 0 or "4/4 runs finished" not in p.stdout:
        fail(f"merge: exit {p.returncode}, expected 0 and '4/4 runs finished' on stdout")


# ----------------------------------------------------------------------------------------------
def sbatch_header(script):
    """The #SBATCH directives sbatch reads: those before the first command line."""
    directives = []
    for line in script.splitlines()[1:]:
        if line.startswith("#SBATCH"):
            directives.append(line.split(None, 1)[1].strip())
        elif line.strip() and not line.startswith("#"):
            break
    return dict(d.lstrip("-").split("=", 1) for d in directives)


def case_slurm():
    camp = write(os.path.join(TMP, "camp dir", "tiny.toml"), TINY)
    out = os.path.join(TMP, "shared fs", "out")
    script = os.path.join(TMP, "tiny.sbatch")
    render("slurm-campaign.sbatch", "--shards", str(SHARDS), "--cpus", "1", "--time", "00:10:00",
           "--campaign", camp, "--out", out, "--uvms", UVMS, "--name", "tiny",
           *[w for s in SETS for w in ("--set", s)], "-o", script)
    if not os.stat(script).st_mode & stat.S_IXUSR:
        fail("render -o did not make the script executable")
    text = open(script).read()
    if "{{" in text:
        fail(f"render -o left placeholders: {sorted(set(re.findall(r'{{[A-Z_]+}}', text)))}")
    p = subprocess.run(["bash", "-n", script], capture_output=True, text=True)
    if p.returncode != 0:
        fail(f"bash -n: {p.stderr.strip()}")
    header = sbatch_header(text)
    want = {"array": f"1-{SHARDS}", "cpus-per-task": "1", "time": "00:10:00", "job-name": "tiny"}
    for k, v in want.items():
        if header.get(k) != v:
            fail(f"#SBATCH --{k}={header.get(k)!r}, expected {v!r} (header {header})")
    print(f"ok: bash -n; #SBATCH {header}")

    p = subprocess.run([script, "--help"], capture_output=True, text=True, timeout=10)
    if p.returncode != 0 or "job array" not in p.stdout or p.stderr or "set -euo" in p.stdout:
        fail(f"--help: exit {p.returncode}, stderr {p.stderr!r}")

    # --submit with a stand-in sbatch that records its arguments and answers job ids.
    fake = os.path.join(TMP, "bin")
    calls = os.path.join(TMP, "sbatch-calls")
    write(os.path.join(fake, "sbatch"),
          '#!/bin/sh\nprintf "%s\\n" "$*" >> "$SBATCH_CALLS"\n'
          'n=$(wc -l < "$SBATCH_CALLS"); echo "$((4240 + n));testcluster"\n')
    os.chmod(os.path.join(fake, "sbatch"), 0o755)
    env = dict(os.environ, PATH=fake + os.pathsep + os.environ["PATH"], SBATCH_CALLS=calls)
    p = subprocess.run([script, "--submit"], env=env, capture_output=True, text=True, timeout=10)
    submitted = open(calls).read().splitlines() if os.path.exists(calls) else []
    print(f"--submit: exit {p.returncode}: {p.stdout.strip()}; sbatch calls: {submitted}")
    if p.returncode != 0 or len(submitted) != 2:
        fail(f"--submit: exit {p.returncode}, {len(submitted)} sbatch calls, expected 0 and 2")
    if submitted[0] != f"--parsable {script}":
        fail(f"--submit: first sbatch call {submitted[0]!r}, expected the script alone")
    second = submitted[1].split()
    if "--dependency=afterany:4241" not in second or second[-2:] != [script, "--merge"] or \
       "--array=1" not in second:
        fail(f"--submit: merge call {submitted[1]!r}, expected --dependency=afterany:4241 "
             "(the shards' job id without ';cluster'), --array=1 and the script with --merge")
    if os.path.exists(out):
        fail("--submit (a stand-in sbatch) ran something")

    base_env = {k: v for k, v in os.environ.items() if not k.startswith("SLURM_")}
    for bad in ("", "0", str(SHARDS + 1), "x"):
        env = dict(base_env, SLURM_ARRAY_TASK_ID=bad) if bad else base_env
        p = subprocess.run([script], env=env, capture_output=True, text=True, timeout=10)
        if p.returncode != 2 or "SLURM_ARRAY_TASK_ID" not in p.stderr:
            fail(f"SLURM_ARRAY_TASK_ID={bad!r}: exit {p.returncode}, expected 2 naming it")
    if os.path.exists(out):
        fail("a refused array task wrote the campaign directory")

    outs = run_shards([([script], dict(base_env, SLURM_ARRAY_TASK_ID=str(i),
                                       SLURM_ARRAY_JOB_ID="4241", SLURM_CPUS_PER_TASK="1"))
                       for i in range(1, SHARDS + 1)])
    check_no_results_yet(out)
    merge([script, "--merge"], dict(base_env, SLURM_ARRAY_TASK_ID="1", SLURM_CPUS_PER_TASK="1"))
    check_against_plain(out, plain_campaign(camp), outs, logs=True)


# ----------------------------------------------------------------------------------------------
def k8s_expand(s, env):
    """Kubernetes' expansion of command and args: $(NAME) of a defined variable -> its value,
    $$ -> $, anything else (an undefined $(NAME), "$((...))", "$X") left as it is."""
    out, i = [], 0
    while i < len(s):
        if s[i] == "$" and i + 1 < len(s):
            if s[i + 1] == "$":
                out.append("$")
                i += 2
                continue
            if s[i + 1] == "(":
                j = s.find(")", i + 2)
                if j < 0:
                    out.append(s[i:])
                    break
                name = s[i + 2:j]
                out.append(env[name] if name in env else s[i:j + 1])
                i = j + 1
                continue
        out.append(s[i])
        i += 1
    return "".join(out)


def k8s_env(container):
    """A container's env values as Kubernetes expands them: in order, each against the ones
    before it (k8s_expand)."""
    env = {}
    for e in container.get("env", []):
        env[e["name"]] = k8s_expand(e["value"], env)
    return env


def pod_command(container, index, mounts, uvms):
    """argv and environment of a container as its pod would run it, here."""
    env = {}
    for name, v in k8s_env(container).items():
        for mount_path, local in mounts.items():
            if v == mount_path or v.startswith(mount_path.rstrip("/") + "/"):
                v = local + v[len(mount_path.rstrip("/")):]
        env[name] = v
    env["UVMS"] = uvms  # the binary as the image would hold it
    if index is not None:
        env["JOB_COMPLETION_INDEX"] = str(index)  # set by Kubernetes in an Indexed Job's pods
    argv = [k8s_expand(w, env) for w in container["command"] + container.get("args", [])]
    for w, orig in zip(argv, container["command"] + container.get("args", [])):
        if w != orig:
            fail(f"Kubernetes would expand {orig!r} to {w!r}: the script must not use $(NAME)")
    base = {k: v for k, v in os.environ.items() if k not in env}
    return argv, dict(base, **env)


def pid_namespace_prefix():
    """A command prefix that runs a command as PID 1 of a new PID namespace, as a container's
    command is run (every shard pod has pid 1: per-process names built from the pid collide on
    the shared volume), or [] when this machine cannot (neither root nor user namespaces)."""
    for prefix in (["unshare", "--pid", "--fork", "--kill-child"],
                   ["unshare", "--user", "--map-root-user", "--pid", "--fork", "--kill-child"]):
        try:
            p = subprocess.run(prefix + ["sh", "-c", 'test "$$" = 1'], capture_output=True,
                               timeout=10)
        except (OSError, subprocess.TimeoutExpired):
            continue
        if p.returncode == 0:
            return prefix
    return []


def case_k8s():
    mount, out_in_pod = "/data", "/data/campaigns/tiny out"
    common = ["--shards", str(SHARDS), "--cpus", "1", "--claim", "uvms-test", "--mount", mount,
              "--campaign", "/data/camp/tiny.toml", "--uvms", "/opt/uvms/bin/uvms",
              "--name", "tiny", "--no-logs", *[w for s in SETS for w in ("--set", s)]]
    err = render("k8s-campaign-job.yaml", *common, "--out", out_in_pod, expect=1)
    if "--image" not in err:
        fail(f"render without --image: {err.strip()!r}, expected it to name --image")
    err = render("k8s-campaign-job.yaml", *common, "--image", "x", "--out", "/elsewhere/o", expect=1)
    if "--mount" not in err:
        fail(f"render with --out outside --mount: {err.strip()!r}, expected a refusal")
    text = render("k8s-campaign-job.yaml", *common, "--image", "registry.example/uvms:test",
                  "--out", out_in_pod)
    import yaml  # the venv's (tools/requirements.txt)
    docs = [d for d in yaml.safe_load_all(text) if d is not None]
    if len(docs) != 2 or any(d.get("apiVersion") != "batch/v1" or d.get("kind") != "Job"
                             for d in docs):
        fail(f"expected two batch/v1 Jobs, got {[(d.get('apiVersion'), d.get('kind')) for d in docs]}")
    shards, merge_job = docs
    spec = shards["spec"]
    if spec.get("completionMode") != "Indexed" or spec.get("completions") != SHARDS or \
       not 1 <= spec.get("parallelism", 0) <= SHARDS:
        fail(f"shards Job: completionMode {spec.get('completionMode')}, completions "
             f"{spec.get('completions')}, parallelism {spec.get('parallelism')}; expected "
             f"Indexed, {SHARDS}, 1..{SHARDS}")
    if spec.get("backoffLimitPerIndex") is None:
        fail("shards Job: no backoffLimitPerIndex (an evicted shard should be retried alone)")
    rules = spec.get("podFailurePolicy", {}).get("rules", [])
    if not any(r["action"] == "FailIndex" and 3 in r.get("onExitCodes", {}).get("values", [])
               for r in rules):
        fail("shards Job: exit 3 (a run failed: a result) is retried; expected FailIndex")
    name = shards["metadata"]["name"]
    if merge_job["metadata"]["name"] != f"{name}-merge" or merge_job["spec"].get("suspend") is not True:
        fail("the merge Job must be NAME-merge and created suspended")
    for job in docs:
        pod = job["spec"]["template"]["spec"]
        if pod.get("restartPolicy") != "Never":
            fail(f"{job['metadata']['name']}: restartPolicy {pod.get('restartPolicy')}, expected "
                 "Never (a podFailurePolicy needs it)")
        claims = {v["name"]: v["persistentVolumeClaim"]["claimName"]
                  for v in pod["volumes"] if "persistentVolumeClaim" in v}
        (container,) = pod["containers"]
        mounts = {m["mountPath"]: m["name"] for m in container["volumeMounts"]}
        if set(mounts.values()) - set(claims) or set(claims.values()) != {"uvms-test"}:
            fail(f"{job['metadata']['name']}: mounts {mounts} vs claims {claims}")
        env = {e["name"]: e["value"] for e in container["env"]}
        if env.get("OUT") != out_in_pod or env.get("CAMPAIGN") != "/data/camp/tiny.toml" or \
           not any(env["OUT"].startswith(m.rstrip("/") + "/") for m in mounts):
            fail(f"{job['metadata']['name']}: OUT {env.get('OUT')!r} not on the mounted claim")
        if container["command"][:2] != ["sh", "-c"]:
            fail(f"{job['metadata']['name']}: command {container['command'][:2]}, expected sh -c")
    shard_c = shards["spec"]["template"]["spec"]["containers"][0]
    merge_c = merge_job["spec"]["template"]["spec"]["containers"][0]
    if "JOB_COMPLETION_INDEX" not in shard_c["command"][2] or "--shard" not in shard_c["command"][2]:
        fail("the shard command does not derive --shard from JOB_COMPLETION_INDEX")
    if "--merge" not in merge_c["command"][2]:
        fail("the merge Job's command has no --merge")
    sets = [w for s in SETS for w in ("--set", s)]
    if merge_c.get("args") != sets or shard_c.get("args") != ["--no-logs"] + sets:
        fail(f"args: shards {shard_c.get('args')}, merge {merge_c.get('args')}: expected the "
             f"same --set for both (the campaign's identity) and --no-logs for the shards")
    res = shard_c["resources"]
    jobs = {e["name"]: e["value"] for e in shard_c["env"]}["JOBS"]
    if res["requests"] != res["limits"] or str(res["requests"]["cpu"]) != jobs:
        fail(f"resources {res} with -j {jobs}: expected requests = limits, cpu = -j (a run per core)")
    print(f"ok: 2 Jobs; Indexed {SHARDS}/{spec['parallelism']}; claim and mount consistent; "
          f"merge suspended")

    local = os.path.join(TMP, "volume")
    camp = write(os.path.join(local, "camp", "tiny.toml"), TINY)
    out = os.path.join(local, "campaigns", "tiny out")
    pidns = pid_namespace_prefix()
    print("each pod's command runs as PID 1 of its own PID namespace" if pidns else
          "note: no PID namespaces here (neither root nor user namespaces): the pods' commands "
          "run as ordinary processes")
    pods = [pod_command(shard_c, i, {mount: local}, UVMS) for i in range(SHARDS)]
    outs = run_shards([(pidns + argv, env) for argv, env in pods])
    check_no_results_yet(out)
    argv, env = pod_command(merge_c, None, {mount: local}, UVMS)
    merge(pidns + argv, env)
    check_against_plain(out, plain_campaign(camp, "--no-logs"), outs, logs=False)


def case_k8s_paths():
    """Paths with "$" in them ("$x", "$(HOME)" and "$$" as text): the volume's mountPath, which
    Kubernetes takes as written, and OUT and CAMPAIGN, env values it expands ("$$" -> "$"), name
    the directories given, OUT and CAMPAIGN below the mount, in both Jobs; a --set value keeps
    its "$(B)". A template that uses the mount elsewhere than in a mountPath is refused."""
    import yaml  # the venv's (tools/requirements.txt)
    mount = "/data/$x $(HOME)"
    out, campaign = mount + "/out $$ d", mount + "/camp/tiny.toml"
    sets = ['run.name="a$(B)"']
    text = render("k8s-campaign-job.yaml", "--shards", "2", "--image", "registry.example/uvms:test",
                  "--mount", mount, "--out", out, "--campaign", campaign, "--name", "paths",
                  *[w for s in sets for w in ("--set", s)])
    docs = [d for d in yaml.safe_load_all(text) if d is not None]
    if len(docs) != 2:
        fail(f"expected two Jobs, got {len(docs)}")
    for job in docs:
        name = job["metadata"]["name"]
        (container,) = job["spec"]["template"]["spec"]["containers"]
        (mount_path,) = [m["mountPath"] for m in container["volumeMounts"]]
        env = k8s_env(container)
        print(f"{name}: mountPath {mount_path!r}, OUT {env['OUT']!r}, CAMPAIGN {env['CAMPAIGN']!r}")
        if mount_path != mount:
            fail(f"{name}: the volume is mounted at {mount_path!r}, expected {mount!r}")
        if env["OUT"] != out or env["CAMPAIGN"] != campaign:
            fail(f"{name}: OUT {env['OUT']!r}, CAMPAIGN {env['CAMPAIGN']!r} after Kubernetes' "
                 f"expansion; expected {out!r}, {campaign!r}")
        if not (env["OUT"].startswith(mount_path + "/") and env["CAMPAIGN"].startswith(mount_path + "/")):
            fail(f"{name}: OUT and CAMPAIGN are not below the mountPath {mount_path!r}: the shards "
                 "would write outside their volume")
        args = [k8s_expand(w, env) for w in container.get("args", [])]
        if args != [w for s in sets for w in ("--set", s)]:
            fail(f"{name}: args {args} after Kubernetes' expansion, expected the --set as given")
    bad = write(os.path.join(TMP, "bad.yaml"), "env:\n  - {name: ROOT, value: {{MOUNT}}}\n")
    err = render(bad, "--shards", "1", "--campaign", "/data/c.toml", "--out", "/data/o", expect=1)
    if "mountPath" not in err:
        fail(f"a template using the mount in an env value: {err.strip()!r}, expected a refusal")
    print("ok: mountPath, OUT and CAMPAIGN agree after expansion; the mount only in a mountPath")


def main():
    t0 = time.monotonic()
    {"slurm": case_slurm, "k8s": case_k8s, "k8s_paths": case_k8s_paths}.get(
        CASE, lambda: fail(f"unknown case {CASE!r}"))()
    print(f"PASS {CASE} ({time.monotonic() - t0:.1f} s)")
    shutil.rmtree(TMP, ignore_errors=True)  # kept after a FAIL, for a look


if __name__ == "__main__":
    main()
