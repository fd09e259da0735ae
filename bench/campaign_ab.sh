#!/usr/bin/env bash
# bench/campaign_ab.sh: two builds of `uvms` on the same campaign, interleaved: for a change of
# the harness or the truth model, a campaign's wall and CPU time before and after on the same
# machine in the same minutes (runs of one build, then of the other, mix the change with the
# machine's drift, on this VM up to 30 %).
#
#   bench/campaign_ab.sh OLD_UVMS NEW_UVMS [ROUNDS] [SEEDS]
#
# OLD_UVMS, NEW_UVMS: `uvms` programs (for an earlier commit, build it in a worktree). The
# campaign is bench/campaign_scale.py's (case VII in unsteady flow, 10 s runs, 4 payloads x 4
# flow amplitudes x SEEDS seeds, default 25: 400 runs), run with `-j 2 --no-logs` into a fresh
# directory under OUT (default build/campaign-ab) by each program in turn, ROUNDS times
# (default 5). Prints every run's wall, user and system time, then per side the medians and the
# median of the new/old ratios of each round.

# SPDX-License-Identifier: Apache-2.0
# Strict mode; --help prints the comment block above and nothing else; else cd to ROOT.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
OLD="$(caller_path "${1:-}")" NEW="$(caller_path "${2:-}")"

[[ $# -ge 2 ]] || { echo "usage: bench/campaign_ab.sh OLD_UVMS NEW_UVMS [ROUNDS] [SEEDS]" >&2; exit 2; }
ROUNDS="${3:-5}" SEEDS="${4:-25}"
for exe in "${OLD}" "${NEW}"; do
  [[ -x "${exe}" ]] || { echo "campaign_ab: not an executable: ${exe}" >&2; exit 2; }
done
OUT="$(realpath -m "${OUT:-build/campaign-ab}")"
mkdir -p "${OUT}"
.venv/bin/python -c "import sys; sys.path.insert(0, 'bench'); import campaign_scale as c; \
open(sys.argv[1], 'w').write(c.campaign_text(int(sys.argv[2]), 10))" "${OUT}/ab.toml" "${SEEDS}"

declare -A wall cpu
ratios=""
for ((r = 1; r <= ROUNDS; ++r)); do
  for side in old new; do
    exe="${OLD}"; [[ "${side}" == new ]] && exe="${NEW}"
    rm -rf "${OUT}/${side}"
    /usr/bin/time -f '%e %U %S' -o "${OUT}/${side}.time" "${exe}" campaign "${OUT}/ab.toml" \
      --out "${OUT}/${side}" -j 2 --no-logs > "${OUT}/${side}.log" 2>&1
    t="$(tail -1 "${OUT}/${side}.time")"
    grep -q "runs finished in" "${OUT}/${side}.log" || { echo "campaign_ab: ${side} failed: ${OUT}/${side}.log" >&2; exit 1; }
    read -r w u s <<<"${t}"
    c="$(awk -v u="${u}" -v s="${s}" 'BEGIN { printf "%.2f", u + s }')"
    echo "round ${r} ${side}: wall ${w} s, user ${u} s, system ${s} s"
    wall[${side}]+="${w} " cpu[${side}]+="${c} "
    [[ "${side}" == old ]] && old_w="${w}" || ratios+="$(awk -v a="${w}" -v b="${old_w}" 'BEGIN { printf "%.4f", a / b }') "
  done
done
median() { tr ' ' '\n' <<<"$1" | grep . | sort -g | awk '{a[NR]=$1} END {
  print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
for side in old new; do
  echo "${side}: median over ${ROUNDS} rounds: wall $(median "${wall[${side}]}") s, CPU (user + system) $(median "${cpu[${side}]}") s"
done
echo "new/old wall, median of the rounds: $(median "${ratios}") (range $(tr ' ' '\n' <<<"${ratios}" | grep . | sort -g | head -1)-$(tr ' ' '\n' <<<"${ratios}" | grep . | sort -g | tail -1))"
