#!/usr/bin/env bash
# bench/m4f_bench.sh: instructions per controller tick (uvms_ctrl_step) on an emulated
# Cortex-M4F, and the static RAM/flash of an image holding one controller.
#
#   bench/m4f_bench.sh            cases IV and VII, 2000 ticks of 0.03 s (60 s) each
#   CASES="1 4 7" TICKS=500 bench/m4f_bench.sh
#
# How: firmware/target/bench_m4f.c (float firmware, built by the cortex-m4f preset) calls
# uvms_bench_mark_begin(), uvms_ctrl_step(), uvms_bench_mark_end() once per tick; QEMU 7.2
# (mps2-an386, -icount shift=0, deterministic) runs it with bench/qemu_icount_plugin.c
# (built by the host preset), which counts the guest instructions between the two marker
# addresses (taken from the ELF with arm-none-eabi-nm) exactly, and attributes them to the
# ELF's symbols. QEMU counts instructions, not cycles (no pipeline, FPU or flash wait states).
# Cross-check: the same run with measure=0 (sensors generated, controller not called); the
# difference of the plugin's instruction totals per tick must equal the per-interval mean up
# to the few instructions of the marker calls and bookkeeping outside the interval.
# Prints Markdown; raw per-tick counts and per-symbol counts stay in build/cortex-m4f/bench/,
# and the figures also go to build/cortex-m4f/bench/m4f_bench.json (machine-readable: read by
# bench/footprint_table.py, which writes the table in docs/BENCHMARKS.md).
#
# Environment (defaults in brackets; relative paths are relative to the repository root):
#   M4F_BUILD=DIR   cortex-m4f build tree [build/cortex-m4f]; configured with the cortex-m4f
#                   preset (cmake --preset cortex-m4f -B DIR) if it does not exist yet
#   HOST_BUILD=DIR  host build tree that builds the QEMU plugin [build/host]; configured with
#                   the host preset if missing. HOST_BUILD=none: no host build, the plugin is
#                   compiled with cc into BENCH_OUT (if missing or older than its source)
#   BENCH_OUT=DIR   raw data and the JSON file [M4F_BUILD/bench]
#   NO_BUILD=1      do not run cmake: use the images in M4F_BUILD as they are (ctest)

# SPDX-License-Identifier: Apache-2.0
# Strict mode; --help prints the comment block above and nothing else; else cd to ROOT.
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh" "$@"

CASES="${CASES:-4 7}"
TICKS="${TICKS:-2000}"
M4F_BUILD="${M4F_BUILD:-build/cortex-m4f}"
HOST_BUILD="${HOST_BUILD:-build/host}"
NO_BUILD="${NO_BUILD:-0}"
ELF="${M4F_BUILD}/firmware/target/uvms_bench_m4f.elf"
MAP="${M4F_BUILD}/firmware/target/uvms_bench_m4f.map"
LIB="${M4F_BUILD}/firmware/libuvms_firmware.a"
OUT="${BENCH_OUT:-${M4F_BUILD}/bench}"
JSON="${OUT}/m4f_bench.json"
if [[ "${HOST_BUILD}" == none ]]; then
  PLUGIN="${OUT}/libqemu_icount_plugin.so"
else
  PLUGIN="${HOST_BUILD}/bench/libqemu_icount_plugin.so"
fi

log() { echo "$*" >&2; }
roman() { local r=(0 I II III IV V VI VII VIII); echo "${r[$1]}"; }

# ---- build (configure only when the build tree does not exist yet) -------------------------
mkdir -p "${OUT}"
rm -f "${JSON}"  # written again at the end of a complete run only
if [[ "${NO_BUILD}" != 1 ]]; then
  [[ -f "${M4F_BUILD}/CMakeCache.txt" ]] || cmake --preset cortex-m4f -B "${M4F_BUILD}" >&2
  cmake --build "${M4F_BUILD}" -j 2 >&2
  if [[ "${HOST_BUILD}" != none ]]; then
    [[ -f "${HOST_BUILD}/CMakeCache.txt" ]] || cmake --preset host -B "${HOST_BUILD}" >&2
    cmake --build "${HOST_BUILD}" -j 2 --target qemu_icount_plugin >&2
  fi
fi
# HOST_BUILD=none: the plugin is one C file without dependencies (no glib; qemu_plugin_api.h).
if [[ "${HOST_BUILD}" == none && ( ! -f "${PLUGIN}" || bench/qemu_icount_plugin.c -nt "${PLUGIN}" ) ]]; then
  cc -std=c11 -O2 -Wall -Wextra -fPIC -shared -fvisibility=hidden -Ibench \
    -o "${PLUGIN}" bench/qemu_icount_plugin.c >&2
fi
for f in "${ELF}" "${MAP}" "${LIB}" "${PLUGIN}"; do
  [[ -f "${f}" ]] || { log "m4f_bench: ${f} missing after the build"; exit 1; }
done

sym_addr() { arm-none-eabi-nm "${ELF}" | awk -v s="$1" '$3 == s { print "0x" $1 }'; }
BEGIN_ADDR="$(sym_addr uvms_bench_mark_begin)"
END_ADDR="$(sym_addr uvms_bench_mark_end)"
SPAN_ADDR="$(sym_addr uvms_bench_mark_span)"
[[ -n "${BEGIN_ADDR}" && -n "${END_ADDR}" && -n "${SPAN_ADDR}" ]] ||
  { log "m4f_bench: marker symbols not found in ${ELF}"; exit 1; }

# run_qemu TAG APPEND [extra plugin args]: runs the image, leaves TAG.stdout and TAG.log
# (the plugin's summary line) in ${OUT}; fails if the image does not exit 0.
run_qemu() {
  local tag="$1" append="$2" extra="${3:-}" rc=0
  qemu-system-arm -M mps2-an386 -nographic -monitor none -serial none \
    -semihosting-config enable=on,target=native -icount shift=0 \
    -d plugin -D "${OUT}/${tag}.log" \
    -plugin "${PLUGIN},begin=${BEGIN_ADDR},end=${END_ADDR},span=${SPAN_ADDR}${extra}" \
    -kernel "${ELF}" -append "${append}" >"${OUT}/${tag}.stdout" || rc=$?
  if [[ ${rc} -ne 0 ]]; then
    log "m4f_bench: ${tag}: image exited ${rc}"; cat "${OUT}/${tag}.stdout" >&2; exit 1
  fi
}
# field FILE KEY: value of KEY=... on the plugin's "icount:" summary line or the image's line.
field() { grep -ho "\b$2=[^ ]*" "$1" | tail -1 | cut -d= -f2; }

# ---- per-case runs ---------------------------------------------------------------------------
:
for c in ${CASES}; do
  run_qemu "case${c}" "case=${c} ticks=${TICKS} measure=1" \
    ",out=${OUT}/case${c}.counts,syms=${OUT}/case${c}.syms"
  run_qemu "case${c}_nomeasure" "case=${c} ticks=${TICKS} measure=0"
  n="$(field "${OUT}/case${c}.log" intervals)"
  [[ "${n}" == "${TICKS}" && "$(field "${OUT}/case${c}.log" unmatched)" == 0 ]] ||
    { log "m4f_bench: case ${c}: ${n} intervals for ${TICKS} ticks"; exit 1; }
  [[ "$(field "${OUT}/case${c}.stdout" not_ok)" == 0 ]] ||
    { log "m4f_bench: case ${c}: a step returned an error"; exit 1; }
done

# Call overhead inside each interval, from the disassembly of the tick loop: the instructions
# strictly between `bl uvms_bench_mark_begin` and `bl uvms_bench_mark_end` (argument set-up,
# the call to the step, storing its status), the call to the end marker, one marker's bx lr.
overhead="$(arm-none-eabi-objdump -d --no-show-raw-insn "${ELF}" | awk '
  done { next }                      # read to the end: an early exit would SIGPIPE objdump
  /bl[ \t].*<uvms_bench_mark_begin>/ { on = 1; n = 0; next }
  on && /bl[ \t].*<uvms_bench_mark_end>/ { print n + 2; done = 1; next }
  on && /^ +[0-9a-f]+:/ { ++n }')"
commit="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
dirty="$(git status --porcelain -- firmware 2>/dev/null | wc -l)"
echo "## uvms_ctrl_step on Cortex-M4F (QEMU 7.2 mps2-an386, float firmware, -O3)"
echo
echo "Commit ${commit}; firmware/ files with uncommitted changes: ${dirty}. ${TICKS} ticks of"
echo "0.03 s per case, paper configuration (uvms_ctrl_config_paper), telemetry filled."
echo "Instructions executed per call, exact (TCG plugin, -icount shift=0); each count includes"
echo "${overhead} instructions of call overhead (argument set-up, the call, the status store, the call"
echo "to the end marker, one marker's bx lr; from the disassembly). Target: <= 10,000."
echo
echo "| case | ticks | median | max | min | mean | stack peak [B] |"
echo "|---|---:|---:|---:|---:|---:|---:|"
for c in ${CASES}; do
  L="${OUT}/case${c}.log"
  printf '| %s | %s | %s | %s | %s | %s | %s |\n' "$(roman "$c")" "$(field "$L" intervals)" \
    "$(field "$L" median)" "$(field "$L" max)" "$(field "$L" min)" "$(field "$L" mean)" \
    "$(field "${OUT}/case${c}.stdout" stack_peak_below_caller)"
done
echo
echo "Stack peak: bytes below the benchmark loop's frame ever written during the run (step and"
sensor_stack="$(field "${OUT}/case${CASES%% *}_nomeasure.stdout" stack_peak_below_caller)"
[[ "${sensor_stack}" == 64 ]] && sensor_stack="<= 64"  # 64 B under the frame are not painted
echo "sensor generation; sensor generation alone: ${sensor_stack} B)."

# ---- sizes -----------------------------------------------------------------------------------
read -r text data bss _ < <(arm-none-eabi-size -B "${ELF}" | awk 'NR == 2')
ctrl_size=$(( 16#$(arm-none-eabi-nm -S "${ELF}" | awk '$4 == "uvms_bench_ctrl" { print $2 }') ))
lib_text="$(arm-none-eabi-size -t "${LIB}" | awk '/\(TOTALS\)/ { print $1 }')"
echo
echo "## Static memory of the benchmark image (one controller instance)"
echo
echo "| | bytes |"
echo "|---|---:|"
echo "| RAM: .data + .bss | $(( data + bss )) (${data} + ${bss}) |"
echo "| flash: .text (incl. .rodata, vectors) + .data | $(( text + data )) (${text} + ${data}) |"
echo "| sizeof(uvms_ctrl_t) (nm -S uvms_bench_ctrl; target <= 4096) | ${ctrl_size} |"
echo "| firmware library .text, all objects (arm-none-eabi-size -t) | ${lib_text} |"
echo
echo "By origin (input sections in ${MAP#"${M4F_BUILD}"/}):"
echo
# Input-section lines of the map: " .sec ADDR SIZE FILE", or " .sec" then "ADDR SIZE FILE".
# One tab-separated line per origin: name, .text, .rodata, .data, .bss.
origins="$(awk '
  /^Linker script and memory map/ { inmap = 1; next }
  !inmap { next }
  /^ [.A-Z*]/ && NF == 1 { pending = $1; next }
  /^ [.A-Z]/ && NF >= 4 && $2 ~ /^0x/ && $3 ~ /^0x/ { add($1, $3, $4); pending = ""; next }
  /^  +0x/ && NF == 3 && $2 ~ /^0x/ && pending != "" { add(pending, $2, $3); pending = ""; next }
  { pending = "" }
  function hex(s,   v, i) {   # "0x1a0" -> 416 (mawk has no strtonum)
    s = tolower(substr(s, 3)); v = 0
    for (i = 1; i <= length(s); ++i) v = 16 * v + index("0123456789abcdef", substr(s, i, 1)) - 1
    return v
  }
  function add(sec, size, file,   cls, org) {
    if (sec ~ /^\.(text|isr_vector)/) cls = "text"
    else if (sec ~ /^\.(rodata|ARM\.exidx|ARM\.extab|init_array|fini_array|preinit_array)/) cls = "rodata"
    else if (sec ~ /^\.data/) cls = "data"
    else if (sec ~ /^(\.bss|COMMON)/) cls = "bss"
    else return
    if (file ~ /libuvms_firmware\.a/) org = "firmware library (libuvms_firmware.a)"
    else if (file ~ /bench_m4f|startup_m4f/) org = "benchmark harness + startup"
    else if (file ~ /libm\.a/) org = "libm (sinf, cosf, atan2f, ...)"
    else org = "newlib-nano, semihosting, libgcc"
    sz[org, cls] += hex(size)
  }
  END {
    n = split("firmware library (libuvms_firmware.a)|libm (sinf, cosf, atan2f, ...)|newlib-nano, semihosting, libgcc|benchmark harness + startup", order, "|")
    for (i = 1; i <= n; ++i) {
      o = order[i]
      printf "%s\t%d\t%d\t%d\t%d\n", o, sz[o, "text"], sz[o, "rodata"], sz[o, "data"], sz[o, "bss"]
    }
  }' "${MAP}")"
echo "| origin | .text | .rodata | .data | .bss | flash | RAM |"
echo "|---|---:|---:|---:|---:|---:|---:|"
while IFS=$'\t' read -r o t r d b; do
  printf '| %s | %d | %d | %d | %d | %d | %d |\n' "$o" "$t" "$r" "$d" "$b" $((t + r + d)) $((d + b))
done <<<"${origins}"
echo
echo "(Alignment fill between input sections is not attributed; the harness's .bss holds the"
echo "controller instance and the sensor/command/telemetry records.)"

# ---- cross-check -------------------------------------------------------------------------------
echo
echo "## Cross-check of the per-interval counts"
echo
echo "Instruction totals of the same image with the controller called (measure=1) and not"
echo "called (measure=0, sensors still generated), divided by the ticks, vs. the plugin's mean"
echo "per interval. Tick loop: counted between the uvms_bench_mark_span calls around the loop."
echo "Whole run: from reset to exit, which also holds the differing summary printf."
echo
echo "| case | tick loop: Δ/ticks | whole run: Δ/ticks | interval mean | loop Δ/ticks − mean | insn vs block total (measure=1) |"
echo "|---|---:|---:|---:|---:|---|"
for c in ${CASES}; do
  L1="${OUT}/case${c}.log" L0="${OUT}/case${c}_nomeasure.log"
  awk -v c="$(roman "$c")" -v n="${TICKS}" -v m="$(field "$L1" mean)" \
      -v s1="$(field "$L1" span)" -v s0="$(field "$L0" span)" \
      -v t1="$(field "$L1" total)" -v t0="$(field "$L0" total)" -v tb1="$(field "$L1" tb_total)" \
      'BEGIN {
    ds = (s1 - s0) / n; dt = (t1 - t0) / n
    printf "| %s | %.3f | %.3f | %.3f | %+.3f | %d vs %d (%+d) |\n", c, ds, dt, m, ds - m, t1, tb1, tb1 - t1 }'
done
echo
echo "Loop Δ − mean: instructions per tick outside the interval that run only when the controller"
echo "is called (the call to the begin marker, the end marker's return, the status and flag"
echo "bookkeeping, minus the skipped branch). The block-level total counts a translation block's"
echo "instructions on entry; it exceeds the per-instruction total only by blocks left part-way"
echo "(semihosting BKPT calls)."

# ---- hot spots ---------------------------------------------------------------------------------
echo
echo "## Where the instructions go (self counts per symbol, per step; top 15 by the sum over cases)"
echo
hdr="| symbol |"; sep="|---|"
for c in ${CASES}; do hdr+=" $(roman "$c") |"; sep+="---:|"; done
echo "${hdr}"; echo "${sep}"
files=(); for c in ${CASES}; do files+=("${OUT}/case${c}.syms"); done
awk -v n="${TICKS}" -v k="${#files[@]}" '
  FNR == 1 { f++ }
  { cnt[$2, f] = $1; tot[$2] += $1; tsum[f] += $1 }
  END {
    m = 0
    for (s in tot) names[++m] = s
    for (i = 1; i <= m; ++i)            # selection sort of the top 15 by total
      for (j = i + 1; j <= m; ++j)
        if (tot[names[j]] > tot[names[i]]) { t = names[i]; names[i] = names[j]; names[j] = t }
    for (i = 1; i <= m && i <= 15; ++i) {
      line = "| " names[i] " |"
      for (g = 1; g <= k; ++g)
        line = line sprintf(" %.0f (%.1f %%) |", cnt[names[i], g] / n, 100 * cnt[names[i], g] / tsum[g])
      print line
    }
  }' "${files[@]}"
echo
echo "Raw data: ${OUT}/case<N>.counts (per tick), case<N>.syms (per symbol, whole run)."

# ---- machine-readable results (bench/footprint_table.py reads them) ----------------------------
# Numbers only as the tools printed them; no commit or date (the figures depend on the sources
# and the tools, and the table built from them must not change when nothing else did).
{
  q() { local s="${1//\\/\\\\}"; printf '"%s"' "${s//\"/\\\"}"; }  # JSON string
  echo "{"
  echo "  \"ticks\": ${TICKS},"
  echo "  \"call_overhead_instructions\": ${overhead},"
  echo "  \"toolchain\": {\"cc\": $(q "$(arm-none-eabi-gcc --version | head -1)"), \"qemu\": $(q "$(qemu-system-arm --version | head -1)")},"
  echo "  \"cases\": ["
  sep=""
  for c in ${CASES}; do
    L="${OUT}/case${c}.log" S="${OUT}/case${c}.stdout"
    stack="$(field "$S" stack_peak_below_caller)"  # "N" or "N(paint_exhausted)": N is a lower bound
    exhausted=false; [[ "${stack}" == *paint_exhausted* ]] && exhausted=true
    printf '%s    {"case": %s, "name": "%s", "intervals": %s, "median": %s, "max": %s, "min": %s, "mean": %s, "stack_peak_bytes": %s, "stack_paint_exhausted": %s, "sizeof_ctrl": %s}' \
      "${sep}" "${c}" "$(roman "$c")" "$(field "$L" intervals)" "$(field "$L" median)" \
      "$(field "$L" max)" "$(field "$L" min)" "$(field "$L" mean)" \
      "${stack%%[!0-9]*}" "${exhausted}" "$(field "$S" sizeof_ctrl)"
    sep=$',\n'
  done
  printf '\n  ],\n'
  echo "  \"image\": {\"text\": ${text}, \"data\": ${data}, \"bss\": ${bss}, \"ram\": $((data + bss)), \"flash\": $((text + data)), \"ctrl_instance_bytes\": ${ctrl_size}},"
  echo "  \"library_text_all_objects\": ${lib_text},"
  echo "  \"by_origin\": ["
  sep=""
  while IFS=$'\t' read -r o t r d b; do
    printf '%s    {"origin": %s, "text": %d, "rodata": %d, "data": %d, "bss": %d, "flash": %d, "ram": %d}' \
      "${sep}" "$(q "$o")" "$t" "$r" "$d" "$b" $((t + r + d)) $((d + b))
    sep=$',\n'
  done <<<"${origins}"
  printf '\n  ]\n}\n'
} >"${JSON}.tmp"
mv "${JSON}.tmp" "${JSON}"
echo "Machine-readable: ${JSON}."
