#!/usr/bin/env bash
# bench/sil_bench.sh [N] [uvms run options, e.g. --set section.key=value ...]: wall time and real-time factor
# of the 60 s paper case VII scenario (0.03 s ticks, 2000 lockstep round trips) over udpm (two
# processes) and memq (one process), N runs each (default 7). The runs alternate udpm, memq,
# udpm, ... so that both transports see the same machine: these VMs' speed drifts by up to
# ~1.7x within minutes (neighbours), so the udpm/memq ratio is steadier than either time.
# Prints median and best per transport, the link's cost per tick, and the CPU steal over the
# measurement. Target: >= 200x real time over udpm. Needs a built host preset
# (cmake --workflow --preset host); UVMS_BUILD picks another build directory.

# SPDX-License-Identifier: Apache-2.0
set -euo pipefail
# --help: the comment block above, and nothing else.
case "${1:-}" in
  -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
esac
cd "$(dirname "${BASH_SOURCE[0]}")/.."
if [[ ${1:-} =~ ^[1-9][0-9]*$ ]]; then n=$1; shift; else n=7; fi
uvms=${UVMS_BUILD:-build/host}/sil/uvms
scenario=sil/scenarios/paper/case_VII_stagnant.toml
tmp=$(mktemp -d)
trap 'rm -rf "${tmp}"' EXIT
steal() { awk '/^cpu /{print $9 + 0; exit}' /proc/stat; }
echo "uvms run ${scenario} $*: ${n} runs per transport, alternating; load average $(cut -d' ' -f1-3 /proc/loadavg)"
steal0=$(steal)
t0=$(date +%s.%N)
for i in $(seq "${n}"); do
  for transport in udpm memq; do
    out="${tmp}/${transport}${i}"
    "${uvms}" run "${scenario}" --out "${out}" --transport "${transport}" "$@" >"${out}.txt" 2>&1 ||
      { echo "sil_bench: run ${i} over ${transport} failed:" >&2; cat "${out}.txt" >&2; exit 1; }
  done
done
t1=$(date +%s.%N)
steal1=$(steal)
.venv/bin/python - "${tmp}" "${n}" "${t0}" "${t1}" "$((steal1 - steal0))" "$(getconf CLK_TCK)" "$(getconf _NPROCESSORS_ONLN)" <<'PY'
import json, statistics, sys
tmp, n = sys.argv[1], int(sys.argv[2])
elapsed = float(sys.argv[4]) - float(sys.argv[3])
steal, hz, cpus = int(sys.argv[5]), int(sys.argv[6]), int(sys.argv[7])
runs = {t: [json.load(open(f"{tmp}/{t}{i}/summary.json")) for i in range(1, n + 1)] for t in ("udpm", "memq")}
for t, s in runs.items():
    assert all(x["status"] == "finished" and x["missed_ticks"] == 0 for x in s), t
sim, ticks = runs["memq"][0]["duration_s"], runs["memq"][0]["ticks"]
med = {}
for t, s in runs.items():
    walls = sorted(x["wall_time_s"] for x in s)
    med[t] = statistics.median(walls)
    print(f"{t}: wall median {med[t]:.3f} s (best {walls[0]:.3f}, worst {walls[-1]:.3f}) for {sim:.0f} s "
          f"simulated: {sim / med[t]:.0f}x real time (best {sim / walls[0]:.0f}x); {med[t] / ticks * 1e6:.0f} us "
          f"per tick; plant {s[0]['integrator_rhs_evals'] / ticks:.1f} RHS/tick")
ratios = [u["wall_time_s"] / m["wall_time_s"] for u, m in zip(runs["udpm"], runs["memq"])]
print(f"udpm/memq wall ratio of neighbouring runs: median {statistics.median(ratios):.2f}; "
      f"link cost over memq {(med['udpm'] - med['memq']) / ticks * 1e6:.0f} us per tick")
print(f"CPU steal during the measurement: {100.0 * steal / hz / (elapsed * cpus):.1f} % of {cpus} CPUs")
PY
if cmp -s "${tmp}/udpm1/run.lcmlog" "${tmp}/memq1/run.lcmlog"; then
  echo "udpm and memq logs: byte-identical"
else
  echo "sil_bench: udpm and memq logs DIFFER (a harness defect)" >&2
  exit 1
fi
