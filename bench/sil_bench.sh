#!/usr/bin/env bash
# bench/sil_bench.sh [N] [--update] [uvms run options, e.g. --set section.key=value ...]: wall
# time and real-time factor of the 60 s paper case VII scenario (0.03 s ticks, 2000 lockstep
# round trips) over udpm (two processes) and memq (one process), N runs each (default 7), one
# fixed session. The runs alternate udpm, memq, udpm, ... so that both transports see the same
# machine: these VMs' speed drifts by up to ~1.7x within minutes (neighbours), so the udpm/memq
# ratio is steadier than either time. Prints median and best per transport, the truth model's
# share (summary.json plant_wall_s), the link's cost per tick (udpm median − memq median), the
# CPU steal over the measurement and the machine (CPU model and clock), and checks that the
# udpm and memq logs are byte-identical. Then bench_lcm_roundtrip (bench/lcm_roundtrip.c)
# measures the link with nothing to compute: the round trip of one tick's messages with each
# direction on its own port (as `uvms run`'s private link) and with one URL both ways (as
# `uvms run --url`).
# --update adds the measurement as a row of the table in docs/BENCHMARKS.md (between
# <!-- sil-bench:begin --> and <!-- sil-bench:end -->). Target: >= 300x real time over udpm
# (median). Needs a built host preset (cmake --workflow --preset host); UVMS_BUILD picks
# another build directory.

# SPDX-License-Identifier: Apache-2.0
set -euo pipefail
# --help: the comment block above, and nothing else.
case "${1:-}" in
  -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
esac
cd "$(dirname "${BASH_SOURCE[0]}")/.."
n=7
update=0
while [[ $# -gt 0 ]]; do  # N and --update, in either order, before the uvms run options
  if [[ $1 =~ ^[1-9][0-9]*$ ]]; then n=$1; shift
  elif [[ $1 == --update ]]; then update=1; shift
  else break; fi
done
uvms=${UVMS_BUILD:-build/host}/sil/uvms
scenario=sil/scenarios/paper/case_VII_stagnant.toml
# One session for every run (the messages carry it; drawn at random otherwise): the udpm and memq
# logs can then be compared byte for byte.
session=601de4105e551011
tmp=$(mktemp -d)
trap 'rm -rf "${tmp}"' EXIT
steal() { awk '/^cpu /{print $9 + 0; exit}' /proc/stat; }
echo "uvms run ${scenario} $*: ${n} runs per transport, alternating; load average $(cut -d' ' -f1-3 /proc/loadavg)"
steal0=$(steal)
t0=$(date +%s.%N)
for i in $(seq "${n}"); do
  for transport in udpm memq; do
    out="${tmp}/${transport}${i}"
    "${uvms}" run "${scenario}" --out "${out}" --transport "${transport}" --session "${session}" "$@" >"${out}.txt" 2>&1 ||
      { echo "sil_bench: run ${i} over ${transport} failed:" >&2; cat "${out}.txt" >&2; exit 1; }
  done
done
t1=$(date +%s.%N)
steal1=$(steal)
# The link with nothing to compute, at the default spin budget (link.spin_us = 2000 µs; a
# --set of it is not passed on).
roundtrip=$("${UVMS_BUILD:-build/host}/bench/bench_lcm_roundtrip" 2000 2000) ||
  { echo "sil_bench: bench_lcm_roundtrip failed (above: the round without an answer)" >&2; exit 1; }
echo "${roundtrip}" >&2
rt_median() { sed -n "s/^LCM udpm round trip, $1.*: median \([0-9.]*\) us.*/\1/p" <<<"${roundtrip}"; }
row=$(.venv/bin/python - "${tmp}" "${n}" "${t0}" "${t1}" "$((steal1 - steal0))" "$(getconf CLK_TCK)" "$(getconf _NPROCESSORS_ONLN)" "$(git rev-parse --short HEAD)$(git diff --quiet HEAD -- . 2>/dev/null || echo -dirty)" "$*" "$(rt_median split)" "$(rt_median shared)" <<'PY'
import datetime, json, statistics, sys
sys.path.insert(0, "bench")
from doc_block import machine
tmp, n = sys.argv[1], int(sys.argv[2])
elapsed = float(sys.argv[4]) - float(sys.argv[3])
steal, hz, cpus = int(sys.argv[5]), int(sys.argv[6]), int(sys.argv[7])
commit, extra = sys.argv[8], sys.argv[9]
rt_split, rt_shared = float(sys.argv[10]), float(sys.argv[11])
runs = {t: [json.load(open(f"{tmp}/{t}{i}/summary.json")) for i in range(1, n + 1)] for t in ("udpm", "memq")}
for t, s in runs.items():
    assert all(x["status"] == "finished" and x["missed_ticks"] == 0 for x in s), t
sim, ticks = runs["memq"][0]["duration_s"], runs["memq"][0]["ticks"]
med, plant = {}, {}
for t, s in runs.items():
    walls = sorted(x["wall_time_s"] for x in s)
    med[t] = statistics.median(walls)
    plant[t] = statistics.median(x["plant_wall_s"] for x in s)
    print(f"{t}: wall median {med[t]:.3f} s (best {walls[0]:.3f}, worst {walls[-1]:.3f}) for {sim:.0f} s "
          f"simulated: {sim / med[t]:.0f}x real time (best {sim / walls[0]:.0f}x); {med[t] / ticks * 1e6:.0f} us "
          f"per tick, of which the plant {plant[t] / ticks * 1e6:.0f} us ({s[0]['integrator_rhs_evals'] / ticks:.1f} RHS/tick)",
          file=sys.stderr)
ratios = [u["wall_time_s"] / m["wall_time_s"] for u, m in zip(runs["udpm"], runs["memq"])]
link_us = (med['udpm'] - med['memq']) / ticks * 1e6
steal_pc = 100.0 * steal / hz / (elapsed * cpus)
print(f"udpm/memq wall ratio of neighbouring runs: median {statistics.median(ratios):.2f}; "
      f"link cost over memq {link_us:.0f} us per tick", file=sys.stderr)
print(f"CPU steal during the measurement: {steal_pc:.1f} % of {cpus} CPUs", file=sys.stderr)
udpm_w = sorted(x["wall_time_s"] for x in runs["udpm"])
memq_w = sorted(x["wall_time_s"] for x in runs["memq"])
print(f"| {datetime.date.today().isoformat()} | {commit} | {n}{' (' + extra + ')' if extra else ''} "
      f"| **{sim / med['udpm']:.0f}×** ({sim / udpm_w[-1]:.0f}–{sim / udpm_w[0]:.0f}×) "
      f"| {sim / med['memq']:.0f}× ({sim / memq_w[-1]:.0f}–{sim / memq_w[0]:.0f}×) "
      f"| {link_us:.0f} µs | {rt_split:.0f} / {rt_shared:.0f} µs "
      f"| {plant['memq'] / ticks * 1e6:.1f} µs | {steal_pc:.1f} % | {machine()} |")
PY
)
echo "${row}"
if cmp -s "${tmp}/udpm1/run.lcmlog" "${tmp}/memq1/run.lcmlog"; then
  echo "udpm and memq logs: byte-identical"
else
  echo "sil_bench: udpm and memq logs DIFFER (a harness defect)" >&2
  exit 1
fi
if ((update)); then
  .venv/bin/python - docs/BENCHMARKS.md "${row}" <<'PY'
import sys
doc, row = sys.argv[1], sys.argv[2]
BEGIN, END = "<!-- sil-bench:begin -->", "<!-- sil-bench:end -->"
text = open(doc).read()
i, j = text.find(BEGIN), text.find(END)
if i < 0 or j < i:
    sys.exit(f"sil_bench: {doc} has no {BEGIN} ... {END} block")
block = text[i + len(BEGIN):j].rstrip("\n")
open(doc, "w").write(text[:i + len(BEGIN)] + block + "\n" + row + "\n" + text[j:])
print(f"sil_bench: row added to {doc}")
PY
fi
