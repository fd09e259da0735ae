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
# directory under OUT (OUT/ab-SIDE-ROUND; default build/campaign-ab; a relative OUT is the
# caller's) by each program in turn, ROUNDS times (default 5), in the order old, new, new, old,
# old, new, ... so that neither side always runs first. The campaign directories, an earlier
# measurement's too, are deleted only at the end, and kept when a campaign fails: on ext4
# without a journal, files created right after others were deleted cost more
# (docs/CAMPAIGNS.md). A campaign that does not finish every run stops the script
# (exit 1, naming its log). Prints every run's wall, user and system time, then per side the
# medians and the median of the new/old ratios of each round.

# SPDX-License-Identifier: Apache-2.0
# Strict mode; --help prints the comment block above and nothing else; else cd to ROOT.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
OLD="$(caller_path "${1:-}")" NEW="$(caller_path "${2:-}")"

[[ $# -ge 2 ]] || { echo "usage: bench/campaign_ab.sh OLD_UVMS NEW_UVMS [ROUNDS] [SEEDS]" >&2; exit 2; }
ROUNDS="${3:-5}" SEEDS="${4:-25}"
need_executables campaign_ab "${OLD}" "${NEW}"
OUT="$(caller_path "${OUT:-${ROOT}/build/campaign-ab}")"
mkdir -p "${OUT}"
# An earlier measurement's directories (a campaign resumes into an existing one) set aside.
mkdir -p "${OUT}/stale.$$"
mv "${OUT}"/ab-* "${OUT}"/old "${OUT}"/new "${OUT}/stale.$$/" 2>/dev/null || true
finished=0
trap '(( finished )) && rm -rf "${OUT:?}"/ab-old-* "${OUT:?}"/ab-new-* "${OUT:?}"/stale.*' EXIT
.venv/bin/python -c "import sys; sys.path.insert(0, 'bench'); import campaign_scale as c; \
open(sys.argv[1], 'w').write(c.campaign_text(int(sys.argv[2]), 10))" "${OUT}/ab.toml" "${SEEDS}"
RUNS=$((16 * SEEDS))

# Campaign $2 of side $1 into the fresh OUT/ab-$1-$2; sets W, U, S (wall, user, system seconds).
campaign() {
  local exe="${OLD}"; [[ "$1" == new ]] && exe="${NEW}"
  local TIMEFORMAT='%R %U %S' t
  if ! t="$( { time "${exe}" campaign "${OUT}/ab.toml" --out "${OUT}/ab-$1-$2" -j 2 --no-logs \
                > "${OUT}/$1.log" 2>&1; } 2>&1 )" ||
     ! grep -q "${RUNS}/${RUNS} runs finished in" "${OUT}/$1.log"; then
    echo "campaign_ab: the $1 campaign did not finish every run: ${OUT}/$1.log, ${OUT}/ab-$1-$2" >&2
    exit 1
  fi
  read -r W U S <<<"${t}"
}

declare -A wall cpu old_wall
ratios=""
for ((r = 1; r <= ROUNDS; ++r)); do
  order="old new"; (( r % 2 == 0 )) && order="new old"
  for side in ${order}; do
    campaign "${side}" "${r}"
    echo "round ${r} ${side}: wall ${W} s, user ${U} s, system ${S} s"
    wall[${side}]+="${W} " cpu[${side}]+="$(awk -v u="${U}" -v s="${S}" 'BEGIN { printf "%.2f", u + s }') "
    [[ "${side}" == old ]] && old_wall[${r}]="${W}" || new_w="${W}"
  done
  ratios+="$(awk -v a="${new_w}" -v b="${old_wall[${r}]}" 'BEGIN { printf "%.4f", a / b }') "
done
median() { tr ' ' '\n' <<<"$1" | grep . | sort -g | awk '{a[NR]=$1} END {
  print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
for side in old new; do
  echo "${side}: median over ${ROUNDS} rounds: wall $(median "${wall[${side}]}") s, CPU (user + system) $(median "${cpu[${side}]}") s"
done
echo "new/old wall, median of the rounds: $(median "${ratios}") (range $(tr ' ' '\n' <<<"${ratios}" | grep . | sort -g | head -1)-$(tr ' ' '\n' <<<"${ratios}" | grep . | sort -g | tail -1))"
finished=1
