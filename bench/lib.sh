# SPDX-License-Identifier: Apache-2.0
# bench/lib.sh: sourced by the benchmark scripts of bench/ (not run by itself), as
#   source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"
# It sets bash's strict mode (set -euo pipefail) and calls bench_start with the script's
# arguments: with -h or --help, it prints the calling script's leading comment block and exits 0;
# otherwise it changes to the repository root and sets ROOT to it. caller_path PATH gives a path
# the caller wrote relative to the directory it was run from, made absolute (an empty argument or
# an option, "-...", unchanged). need_executables NAME FILE... exits 2, naming NAME and the
# first FILE that is not an executable.
set -euo pipefail
CALLER_DIR="${PWD}"
caller_path() {
  [[ -z "$1" || "$1" == -* ]] && echo "$1" || (cd "${CALLER_DIR}" && realpath -m -- "$1")
}
need_executables() {
  local name="$1" f
  shift
  for f in "$@"; do
    [[ -x "${f}" ]] || { echo "${name}: not an executable: ${f}" >&2; exit 2; }
  done
}
bench_start() {
  case "${1:-}" in
    -h|--help)
      awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0"
      exit 0 ;;
  esac
  ROOT="$(cd "$(dirname "${BASH_SOURCE[1]}")/.." && pwd)"
  cd "${ROOT}"
}
bench_start "$@"
