#!/usr/bin/env bash
# bench/sil_ab.sh: two builds of `uvms` on the same SIL run, interleaved: for a change of the
# link or the nodes, the wall time of one run before and after on the same machine in the same
# minutes (this VM's speed drifts by up to ~1.7x within minutes, so runs of one build and then
# of the other would mix the change with the drift).
#
#   bench/sil_ab.sh OLD_UVMS NEW_UVMS [PAIRS] [TRANSPORT]
#
# OLD_UVMS, NEW_UVMS: `uvms` programs, each beside its uvms-plant and uvms-controller (for an
# earlier commit, build it in a worktree). Each pair runs the 60 s paper case VII stagnant
# scenario (bench/sil_bench.sh's) once with each program over TRANSPORT (udpm, the default, or
# memq), with one fixed session, in the order old, new, new, old, ... so that neither side
# always runs first; PAIRS pairs (default 15). A run that does not finish stops the script
# (exit 1). Prints per side the median wall time (summary.json wall_time_s) and real-time
# factor with their range, and the median and quartiles of the new/old wall ratio of each pair.

# SPDX-License-Identifier: Apache-2.0
# Strict mode; --help prints the comment block above and nothing else; else cd to ROOT.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
OLD="$(caller_path "${1:-}")" NEW="$(caller_path "${2:-}")"

[[ $# -ge 2 ]] || { echo "usage: bench/sil_ab.sh OLD_UVMS NEW_UVMS [PAIRS] [TRANSPORT]" >&2; exit 2; }
PAIRS="${3:-15}" TRANSPORT="${4:-udpm}"
[[ "${PAIRS}" =~ ^[1-9][0-9]*$ ]] || { echo "sil_ab: PAIRS must be a positive integer" >&2; exit 2; }
[[ "${TRANSPORT}" == udpm || "${TRANSPORT}" == memq ]] ||
  { echo "sil_ab: TRANSPORT must be udpm or memq" >&2; exit 2; }
need_executables sil_ab "${OLD}" "${NEW}"
scenario=sil/scenarios/paper/case_VII_stagnant.toml
tmp=$(mktemp -d)
trap 'rm -rf "${tmp}"' EXIT

for ((p = 1; p <= PAIRS; ++p)); do
  order="old new"; (( p % 2 == 0 )) && order="new old"
  for side in ${order}; do
    exe="${OLD}"; [[ "${side}" == new ]] && exe="${NEW}"
    out="${tmp}/${side}${p}"
    "${exe}" run "${scenario}" --out "${out}" --transport "${TRANSPORT}" \
      --session 601de4105e551011 > "${out}.txt" 2>&1 ||
      { echo "sil_ab: the ${side} run of pair ${p} failed:" >&2; cat "${out}.txt" >&2; exit 1; }
  done
done
.venv/bin/python - "${tmp}" "${PAIRS}" "${TRANSPORT}" <<'PY'
import json, statistics, sys
tmp, pairs, transport = sys.argv[1], int(sys.argv[2]), sys.argv[3]
wall = {s: [json.load(open(f"{tmp}/{s}{p}/summary.json"))["wall_time_s"] for p in range(1, pairs + 1)]
        for s in ("old", "new")}
sim = json.load(open(f"{tmp}/old1/summary.json"))["duration_s"]
for s, w in wall.items():
    m = statistics.median(w)
    print(f"{s}: {transport} wall median {m:.3f} s ({min(w):.3f}-{max(w):.3f}): {sim / m:.0f}x real time "
          f"({sim / max(w):.0f}-{sim / min(w):.0f}x)")
r = sorted(n / o for n, o in zip(wall["new"], wall["old"]))
q = statistics.quantiles(r, n=4) if len(r) > 1 else [r[0]] * 3
print(f"new/old wall of each pair: median {statistics.median(r):.3f} (quartiles {q[0]:.3f}-{q[2]:.3f}, "
      f"range {r[0]:.3f}-{r[-1]:.3f}), {pairs} pairs")
PY
