#!/usr/bin/env bash
# bench/host_bench.sh: host figures of one controller tick.
#   - wall time per uvms_ctrl_step [ns]: median/p90/p99 of every step of 20 runs of the 60 s
#     sensor sequence (2000 ticks), Release build, double (host) and float (host-float);
#   - x86-64 instructions per step: callgrind with --toggle-collect=uvms_ctrl_step over one run
#     (2000 steps), total Ir / 2000 (repeatable, unlike time).
# Usage: bench/host_bench.sh   (builds the host and host-float presets if needed)

# SPDX-License-Identifier: Apache-2.0
set -euo pipefail
# --help: the comment block above, and nothing else.
case "${1:-}" in
  -h|--help) awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"; exit 0 ;;
esac
cd "$(dirname "${BASH_SOURCE[0]}")/.."
for preset in host host-float; do
  [[ -f build/${preset}/build.ninja ]] || cmake --preset "${preset}" >/dev/null
  cmake --build --preset "${preset}" --target bench_ctrl_host >/dev/null
done
echo "| build | case | median ns/step | p90 | p99 | x86 instructions/step (callgrind) |"
echo "|---|---|---:|---:|---:|---:|"
for preset in host host-float; do
  exe=build/${preset}/bench/bench_ctrl_host
  for c in 4 7; do
    line=$("${exe}" time "${c}" 20)
    med=$(sed -E 's/.*median ([0-9]+).*/\1/' <<<"${line}")
    p90=$(sed -E 's/.*p90 ([0-9]+).*/\1/' <<<"${line}")
    p99=$(sed -E 's/.*p99 ([0-9]+).*/\1/' <<<"${line}")
    out=$(mktemp)
    valgrind --tool=callgrind --toggle-collect=uvms_ctrl_step --callgrind-out-file="${out}" \
      "${exe}" count "${c}" 1 >/dev/null 2>"${out}.log"
    ir=$(grep -E "Collected :" "${out}.log" | sed -E 's/.*Collected : ([0-9]+).*/\1/')
    rm -f "${out}" "${out}.log"
    printf '| %s | %s | %s | %s | %s | %d |\n' "${preset}" "${c}" "${med}" "${p90}" "${p99}" $((ir / 2000))
  done
done
