#!/usr/bin/env bash
# bench/pinocchio_ab.sh: two builds of the tick against Pinocchio's RNEA, interleaved: for a
# change of the firmware, the tick's time before and after on the same machine in the same
# minutes (a sequence of runs of one build, then of the other, mixes the change with the
# machine's drift, which on a VM is as large as a few per cent).
#
#   bench/pinocchio_ab.sh OLD_EXE NEW_EXE [ROUNDS] [RUNS]
#
# OLD_EXE, NEW_EXE (relative to the current directory): bench_vs_pinocchio programs, each made by bench/pinocchio_bench.sh from its
# build (HOST_BUILD=DIR bench/pinocchio_bench.sh writes DIR/pinocchio_bench/bench_vs_pinocchio;
# for an earlier commit, run that commit's script in a worktree with its own HOST_BUILD).
# ROUNDS (default 4) rounds of `EXE time RUNS` (default 30), OLD then NEW in each round. Prints
# every run's line (tick and RNEA median ns, their ratio), then per side the median over the
# rounds of the tick's ns and of the tick/RNEA ratio.
# BLOCK=NAME (environment): also writes those lines, after a line naming the command and
# LABEL (environment, e.g. "old: 0.9.0 at 86d8edc; new: this change"), into docs/BENCHMARKS.md
# between <!-- NAME:begin --> and <!-- NAME:end --> (bench/doc_block.py NAME).

# SPDX-License-Identifier: Apache-2.0
# Strict mode; --help prints the comment block above and nothing else; else cd to ROOT.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
OLD="$(caller_path "${1:-}")" NEW="$(caller_path "${2:-}")"

[[ $# -ge 2 ]] || { echo "usage: bench/pinocchio_ab.sh OLD_EXE NEW_EXE [ROUNDS] [RUNS]" >&2; exit 2; }
ROUNDS="${3:-4}" RUNS="${4:-30}"
need_executables pinocchio_ab "${OLD}" "${NEW}"

val() { grep -o "\b$1=[^ ]*" <<<"$2" | cut -d= -f2; }
declare -A ns ratio
lines=()
say() { echo "$*"; lines+=("$*"); }
for ((r = 1; r <= ROUNDS; ++r)); do
  for side in old new; do
    exe="${OLD}"; [[ "${side}" == new ]] && exe="${NEW}"
    line="$("${exe}" time "${RUNS}")"
    t="$(val ctrl_median_ns "${line}")" q="$(val rnea_median_ns "${line}")"
    k="$(val ratio_of_medians "${line}")"
    say "round ${r} ${side}: tick ${t} ns, RNEA ${q} ns, tick/RNEA ${k}"
    ns[${side}]+="${t} " ratio[${side}]+="${k} "
  done
done
median() { tr ' ' '\n' <<<"$1" | grep . | sort -g | awk '{a[NR]=$1} END {
  print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2 }'; }
for side in old new; do
  say "${side}: tick median ${ROUNDS} rounds $(median "${ns[${side}]}") ns," \
      "tick/RNEA $(median "${ratio[${side}]}")"
done
if [[ -n "${BLOCK:-}" ]]; then
  { echo "\`bench/pinocchio_ab.sh $*\`${LABEL:+ (${LABEL})}:"; echo; echo '```'
    printf '%s\n' "${lines[@]}"; echo '```'; } | .venv/bin/python bench/doc_block.py "${BLOCK}"
fi
