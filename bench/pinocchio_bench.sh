#!/usr/bin/env bash
# bench/pinocchio_bench.sh: the whole double-precision controller tick against one
# Pinocchio floating-base RNEA (free-flyer + 7 revolute joints: the firmware's paper arm on its
# vehicle), side by side in one process on this machine.
#
#   bench/pinocchio_bench.sh                       set up, build, run, print two table rows
#   RUNS=100 HOST_BUILD=build/host bench/pinocchio_bench.sh
#
# Setup: `tools/bootstrap --bench`, the opt-in benchmark venv build/venv-bench with
# tools/requirements-bench.txt (Pinocchio's PyPI wheel `pin` 4.1.0 and its pinned cmeel
# dependencies: 94 MB to download, 480 MB installed); Pinocchio's and Boost's headers come from
# its site-packages/cmeel.prefix/include, Eigen from Debian's libeigen3-dev.
# Build (not part of the CMake project, so CI does not pay for it): the firmware library of a
# host build (HOST_BUILD, default build/host, configured with the host preset if missing; only
# the target uvms_firmware is built), and bench/bench_vs_pinocchio.cpp compiled with g++
# -O3 -DNDEBUG against pin's headers (one translation unit, about a minute; recompiled only when
# it or pin changes), into HOST_BUILD/pinocchio_bench/.
# Run: `bench_vs_pinocchio time RUNS` (RUNS runs of the 2000-tick case VII sequence, default
# 100): first a model check (Pinocchio's joint torques equal the firmware's Newton–Euler in
# vacuum, or the run fails), then batches of 100 calls of each of four in turn (the tick, the
# RNEA, and the firmware's Newton–Euler `uvms_arm_rnea` alone in vacuum and in the paper
# configuration's fluid), median ns per call of each and their ratios to the RNEA. Then
# valgrind callgrind counts the instructions per call of each (2000 calls each; exact and
# load-independent).
# Prints the program's lines, then one Markdown row of each of two tables:
# | date | commit | Pinocchio | tick ns | RNEA ns | ratio | tick instr. | RNEA instr. | ratio |
# | date | commit | NE vacuum ns | ÷ RNEA | NE fluid ns | ÷ RNEA | NE vacuum instr. | ÷ RNEA |
#   NE fluid instr. | ÷ RNEA |

# SPDX-License-Identifier: Apache-2.0
# Strict mode; --help prints the comment block above and nothing else; else cd to ROOT.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"

RUNS="${RUNS:-100}"
HOST_BUILD="${HOST_BUILD:-build/host}"
OUT="${HOST_BUILD}/pinocchio_bench"
log() { echo "pinocchio_bench: $*" >&2; }

# ---- setup and build -------------------------------------------------------------------------
tools/bootstrap --bench >&2
PY=build/venv-bench/bin/python
PREFIX="$("${PY}" -c 'import cmeel; print(cmeel.__path__[0] + ".prefix")' 2>/dev/null ||
          true)"
if [[ ! -f "${PREFIX}/include/pinocchio/config.hpp" ]]; then
  # cmeel's layout: <site-packages>/cmeel.prefix next to the cmeel package.
  PREFIX="$("${PY}" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')/cmeel.prefix"
fi
[[ -f "${PREFIX}/include/pinocchio/config.hpp" ]] ||
  { log "Pinocchio headers not found under ${PREFIX}/include"; exit 1; }
PIN_VERSION="$(sed -n 's/^# *define PINOCCHIO_VERSION "\(.*\)"/\1/p' "${PREFIX}/include/pinocchio/config.hpp")"

[[ -f "${HOST_BUILD}/CMakeCache.txt" ]] || cmake --preset host -B "${HOST_BUILD}" >&2
cmake --build "${HOST_BUILD}" -j 2 --target uvms_firmware >&2
LIB="${HOST_BUILD}/firmware/libuvms_firmware.a"
mkdir -p "${OUT}"

# Pinocchio's interface definitions for its headers (lib/cmake/pinocchio: pinocchio_headers);
# no PINOCCHIO_ENABLE_TEMPLATE_INSTANTIATION, so rnea is compiled here with these flags.
CXXFLAGS=(-std=c++17 -O3 -DNDEBUG -Wall -Wextra
  -DBOOST_MPL_LIMIT_LIST_SIZE=30 -DBOOST_MPL_LIMIT_VECTOR_SIZE=30
  -DBOOST_MPL_CFG_NO_PREPROCESSED_HEADERS -DBOOST_FUSION_INVOKE_MAX_ARITY=12
  -isystem "${PREFIX}/include" -isystem /usr/include/eigen3
  -I firmware/include -I "${HOST_BUILD}/firmware/include" -I tests/support)
OBJ="${OUT}/bench_vs_pinocchio.o"
flags_now="$(printf '%s\n' "${CXXFLAGS[@]}" "${PIN_VERSION}" | sha256sum | cut -d' ' -f1)"
flags_then="$(cat "${OBJ}.flags" 2>/dev/null || true)"
if [[ ! -f "${OBJ}" || bench/bench_vs_pinocchio.cpp -nt "${OBJ}" ||
      "${HOST_BUILD}/firmware/include/uvms/config.h" -nt "${OBJ}" ||
      -n "$(find firmware/include -newer "${OBJ}" -name '*.h' | head -1)" ||
      "${flags_now}" != "${flags_then}" ]]; then
  log "compiling bench_vs_pinocchio.cpp against pin ${PIN_VERSION}'s headers (about a minute)"
  g++ "${CXXFLAGS[@]}" -c bench/bench_vs_pinocchio.cpp -o "${OBJ}"
  echo "${flags_now}" >"${OBJ}.flags"
fi
gcc -std=c11 -O3 -DNDEBUG -I firmware/include -I "${HOST_BUILD}/firmware/include" \
  -c tests/support/sensor_sequence.c -o "${OUT}/sensor_sequence.o"
EXE="${OUT}/bench_vs_pinocchio"
g++ -O3 "${OBJ}" "${OUT}/sensor_sequence.o" "${LIB}" -lm -o "${EXE}"

# ---- run -------------------------------------------------------------------------------------
line="$("${EXE}" time "${RUNS}")"
echo "${line}"
val() { grep -o "\b$1=[^ ]*" <<<"${line}" | cut -d= -f2; }
ctrl_ns="$(val ctrl_median_ns)" rnea_ns="$(val rnea_median_ns)" ratio="$(val ratio_of_medians)"
nev_ns="$(val ne_vacuum_median_ns)" nev_ratio="$(val ne_vacuum_ratio)"
new_ns="$(val ne_water_median_ns)" new_ratio="$(val ne_water_ratio)"

# Instructions per call: callgrind, collection on only inside the measured function.
count() {  # count SIDE FUNCTION -> instructions per call (2000 calls)
  local cg="${OUT}/callgrind.$1"
  valgrind --tool=callgrind --toggle-collect="$2" --callgrind-out-file="${cg}.out" \
    "${EXE}" count "$1" 1 >/dev/null 2>"${cg}.log"
  local ir
  ir="$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "${cg}.log")"
  [[ -n "${ir}" ]] || { log "callgrind gave no count for $1 (${cg}.log)"; exit 1; }
  echo $(( (ir + 1000) / 2000 ))
}
ctrl_ir="$(count ctrl uvms_ctrl_step)"
rnea_ir="$(count rnea bench_rnea_call)"
nev_ir="$(count ne-vacuum bench_ne_call)"
new_ir="$(count ne-water bench_ne_call)"
echo "callgrind: instructions per call: uvms_ctrl_step ${ctrl_ir}, bench_rnea_call ${rnea_ir}," \
     "bench_ne_call (uvms_arm_rnea) in vacuum ${nev_ir}, in the paper's fluid ${new_ir}"

commit="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
dirty="$(git status --porcelain -- firmware bench 2>/dev/null | wc -l || true)"
[[ "${dirty}" -gt 0 ]] && commit+=" + ${dirty} uncommitted files in firmware/, bench/"
echo
echo "| date | commit | Pinocchio | tick, median ns | RNEA, median ns | tick / RNEA | tick, instructions | RNEA, instructions | tick / RNEA |"
echo "|---|---|---|---:|---:|---:|---:|---:|---:|"
awk -v d="$(date -u +%Y-%m-%d)" -v c="${commit}" -v p="${PIN_VERSION}" -v cn="${ctrl_ns}" \
    -v rn="${rnea_ns}" -v r="${ratio}" -v ci="${ctrl_ir}" -v ri="${rnea_ir}" 'BEGIN {
  printf "| %s | %s | pin %s | %.0f | %.0f | %.2f | %d | %d | %.2f |\n", d, c, p, cn, rn, r, ci, ri, ci / ri }'
echo
echo "| date | commit | Newton–Euler in vacuum, median ns | ÷ RNEA | in the fluid, median ns | ÷ RNEA | in vacuum, instructions | ÷ RNEA | in the fluid, instructions | ÷ RNEA |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
awk -v d="$(date -u +%Y-%m-%d)" -v c="${commit}" -v vn="${nev_ns}" -v vr="${nev_ratio}" \
    -v wn="${new_ns}" -v wr="${new_ratio}" -v ri="${rnea_ir}" -v vi="${nev_ir}" \
    -v wi="${new_ir}" 'BEGIN {
  printf "| %s | %s | %.0f | %.2f | %.0f | %.2f | %d | %.2f | %d | %.2f |\n", d, c, vn, vr,
         wn, wr, vi, vi / ri, wi, wi / ri }'
