#!/usr/bin/env bash
# tools/bench/sil_bench.sh [N]: wall time and real-time factor of the 60 s paper case VII
# scenario (0.03 s ticks, 2000 lockstep round trips) over udpm (two processes) and memq (one
# process), N runs each (default 5), median and best. Target (issue 5): >= 200x real time
# over udpm. Needs a built host preset (cmake --workflow --preset host).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
n=${1:-5}
uvms=${UVMS_BUILD:-build/host}/sil/uvms
scenario=sil/scenarios/paper/case_VII_stagnant.toml
tmp=$(mktemp -d)
trap 'rm -rf "${tmp}"' EXIT
echo "uvms run ${scenario}: ${n} runs per transport; load average $(cut -d' ' -f1-3 /proc/loadavg)"
for transport in udpm memq; do
  for i in $(seq "${n}"); do
    "${uvms}" run "${scenario}" --out "${tmp}/${transport}${i}" --transport "${transport}" >/dev/null 2>&1
  done
  .venv/bin/python - "${tmp}" "${transport}" "${n}" <<'PY'
import json, statistics, sys
tmp, transport, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
s = [json.load(open(f"{tmp}/{transport}{i}/summary.json")) for i in range(1, n + 1)]
walls = sorted(x["wall_time_s"] for x in s)
sim = s[0]["duration_s"]
assert all(x["status"] == "finished" and x["missed_ticks"] == 0 for x in s)
med = statistics.median(walls)
print(f"{transport}: wall median {med:.3f} s (best {walls[0]:.3f}, worst {walls[-1]:.3f}) for "
      f"{sim:.0f} s simulated: {sim / med:.0f}x real time (best {sim / walls[0]:.0f}x); "
      f"{med / s[0]['ticks'] * 1e6:.0f} us per tick; plant {s[0]['integrator_rhs_evals'] / s[0]['ticks']:.1f} RHS/tick")
PY
done
cmp -s "${tmp}/udpm1/run.lcmlog" "${tmp}/memq1/run.lcmlog" && echo "udpm and memq logs: byte-identical"
