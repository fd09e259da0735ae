#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""bench/footprint_table.py: the footprint and tick table of docs/BENCHMARKS.md, measured.

    bench/footprint_table.py            measure, compare with the table in the doc
                                              (exit 0 equal, 1 different: prints the diff)
    bench/footprint_table.py --update   measure, write the table into the doc
    bench/footprint_table.py --json F   use F (a bench/m4f_bench.sh result) instead
                                              of running the benchmark (with either mode)

What it measures: bench/m4f_bench.sh (cases IV and VII of the paper configuration,
2000 ticks of 0.03 s = 60 s each, QEMU 7.2 with the project's instruction-counting plugin;
exact) writes its figures to BENCH_OUT/m4f_bench.json, and this script turns them into the
table: sizeof(uvms_ctrl_t) in float (the Cortex-M4F benchmark image's instance) and in double
(the size probe firmware/probe/ctrl_size_probe.c compiled for the host), the stack peak, RAM and
flash of the benchmark image and the library's share, the library's .text, and instructions
per uvms_ctrl_step (median, max) with a time estimate at 168 MHz. Instruction counts and sizes
are exact and deterministic, so the comparison is exact: the text between the markers
<!-- footprint:begin --> and <!-- footprint:end --> must equal the generated text.

Environment (as for m4f_bench.sh; relative paths from the repository root):
  M4F_BUILD=DIR   cortex-m4f build tree [build/cortex-m4f]
  HOST_BUILD=DIR  host build tree [build/host]: the QEMU plugin and the double size probe;
                  none: no host build (the plugin and the probe are compiled here with cc)
  NO_BUILD=1      use the build trees as they are (no cmake --build)
  BENCH_OUT=DIR   raw data of this run [M4F_BUILD/footprint]
The ctest test docs.benchmarks_footprint_table_is_current (cortex-m4f build) runs the compare
mode with M4F_BUILD=<that build> HOST_BUILD=none NO_BUILD=1.
"""
import argparse
import difflib
import json
import os
import re
import shlex
import subprocess
import sys
import tempfile
import textwrap

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOC = os.path.join(ROOT, "docs", "BENCHMARKS.md")
BEGIN = "<!-- footprint:begin -->"
END = "<!-- footprint:end -->"
CLOCK_HZ = 168e6      # the Cortex-M4F clock the estimate is stated at (STM32F4's maximum)
TICK_S = 0.03         # controller period, SPEC §8 (0.03 s)
SELF = "bench/footprint_table.py"


class Failure(Exception):
    """A measurement could not be made (exit 2)."""


def run(cmd, **kw):
    p = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True, **kw)
    if p.returncode != 0:
        raise Failure(f"{' '.join(map(shlex.quote, cmd))} exited {p.returncode}:\n"
                      f"{p.stdout[-2000:]}{p.stderr[-2000:]}")
    return p.stdout


def symbol_size(nm, obj, symbol):
    """Size in bytes of `symbol` in `obj` from `nm -S` (as cmake/print_symbol_size.cmake)."""
    for line in run([nm, "-S", obj]).splitlines():
        f = line.split()
        if len(f) == 4 and f[3] == symbol:
            return int(f[1], 16)
    raise Failure(f"{symbol} not found in {obj}")


def host_ctrl_size(host_build, no_build, scratch):
    """sizeof(uvms_ctrl_t) in double: the host build's size probe object, or (HOST_BUILD=none)
    the same probe compiled here with cc against a config.h from the firmware's template."""
    if host_build != "none":
        if not no_build:
            if not os.path.isfile(os.path.join(ROOT, host_build, "CMakeCache.txt")):
                run(["cmake", "--preset", "host", "-B", host_build])
            run(["cmake", "--build", host_build, "-j", "2", "--target", "uvms_ctrl_size_probe"])
        obj = os.path.join(ROOT, host_build, "firmware", "CMakeFiles",
                           "uvms_ctrl_size_probe.dir", "probe", "ctrl_size_probe.c.o")
        if not os.path.isfile(obj):
            raise Failure(f"{obj} missing (build the host preset, or HOST_BUILD=none)")
        return symbol_size("nm", obj, "uvms_ctrl_size_probe_instance")
    inc = os.path.join(scratch, "include")
    script = os.path.join(scratch, "config_h.cmake")
    with open(script, "w") as f:  # the firmware's own template, precision double
        f.write("set(UVMS_CONFIG_REAL_FLOAT 0)\n"
                "foreach(v PROJECT_VERSION PROJECT_VERSION_MAJOR PROJECT_VERSION_MINOR "
                "PROJECT_VERSION_PATCH)\n  set(${v} 0)\nendforeach()\n"
                f'configure_file("{ROOT}/firmware/cmake/config.h.in" "{inc}/uvms/config.h" @ONLY)\n')
    run(["cmake", "-P", script])
    obj = os.path.join(scratch, "ctrl_size_probe.o")
    run(["cc", "-std=c11", "-O3", "-c", "-I", inc, "-I", os.path.join(ROOT, "firmware", "include"),
         os.path.join(ROOT, "firmware", "probe", "ctrl_size_probe.c"), "-o", obj])
    return symbol_size("nm", obj, "uvms_ctrl_size_probe_instance")


def measure(env, json_file):
    """Runs m4f_bench.sh (unless json_file) and the host probe: (m4f_bench.json, double size)."""
    out = env["BENCH_OUT"]
    os.makedirs(os.path.join(ROOT, out), exist_ok=True)
    if json_file is None:
        json_file = os.path.join(ROOT, out, "m4f_bench.json")
        with open(os.path.join(ROOT, out, "m4f_bench.md"), "w") as md, \
             open(os.path.join(ROOT, out, "m4f_bench.log"), "w") as log:
            p = subprocess.run([os.path.join(ROOT, "bench", "m4f_bench.sh")], cwd=ROOT,
                               env={**os.environ, **env}, stdout=md, stderr=log)
        if p.returncode != 0:
            with open(os.path.join(ROOT, out, "m4f_bench.log")) as log:
                tail = log.read()[-3000:]
            raise Failure(f"bench/m4f_bench.sh exited {p.returncode}:\n{tail}")
    with open(json_file) as f:
        m4f = json.load(f)
    with tempfile.TemporaryDirectory() as scratch:
        double_size = host_ctrl_size(env["HOST_BUILD"], env["NO_BUILD"] == "1",
                                                 scratch)
    return m4f, double_size


def num(x):
    """10666 -> '10,666'; 10666.5 -> '10,666.5' (a median of an even count)."""
    x = float(x)
    return f"{x:,.0f}" if x == int(x) else f"{x:,.1f}"


def estimate_us(insns):
    return f"{insns / CLOCK_HZ * 1e6:.1f} µs"


def para(text):
    """A prose paragraph wrapped like the rest of the doc (95 columns)."""
    return textwrap.fill(text, width=95, break_long_words=False, break_on_hyphens=False)


def table(m4f, double_size):
    """The generated Markdown (between the markers). No date or commit: it changes only when
    a figure does."""
    cases = {c["name"]: c for c in m4f["cases"]}
    names = [n for n in ("IV", "VII") if n in cases]
    if names != ["IV", "VII"]:
        raise Failure(f"the benchmark ran cases {sorted(cases)}; the table needs IV and VII")
    for n in names:
        c = cases[n]
        if c["intervals"] != m4f["ticks"] or c["stack_paint_exhausted"]:
            raise Failure(f"case {n}: {c['intervals']} intervals for {m4f['ticks']} ticks, "
                          f"stack paint exhausted: {c['stack_paint_exhausted']}")
        if c["sizeof_ctrl"] != m4f["image"]["ctrl_instance_bytes"]:
            raise Failure("the image's sizeof(uvms_ctrl_t) and its symbol size differ")
    img = m4f["image"]
    lib = next(o for o in m4f["by_origin"] if o["origin"].startswith("firmware library"))
    stack = max(cases[n]["stack_peak_bytes"] for n in names)
    ticks = m4f["ticks"]
    cc = re.sub(r"^arm-none-eabi-gcc \(([^)]*)\) ", "", m4f["toolchain"]["cc"]).split()[0]
    # QEMU's major.minor only: a distribution's point release (7.2.x) does not change what an
    # instruction is, and the table should not go stale with a security update.
    qemu = re.search(r"version (\d+\.\d+)", m4f["toolchain"]["qemu"]).group(1)
    tick_us = TICK_S * 1e6
    L = []
    L.append(para(f"Generated by `{SELF} --update` (do not edit by hand): "
             f"`bench/m4f_bench.sh`, cases IV and VII of the paper configuration "
             f"(`uvms_ctrl_config_paper`, pseudoinverse allocation, telemetry filled), "
             f"{ticks:,} ticks of {TICK_S} s ({ticks * TICK_S:g} s) each; float firmware, "
             f"arm-none-eabi-gcc {cc} -O3, QEMU {qemu} `mps2-an386` with `-icount shift=0` and "
             f"the project's instruction-counting plugin. The ctest test "
             f"`docs.benchmarks_footprint_table_is_current` (cortex-m4f build) fails when this "
             f"table differs from a fresh measurement."))
    L.append("")
    L.append("| figure | bytes | how |")
    L.append("|---|---:|---|")
    L.append(f"| `sizeof(uvms_ctrl_t)`, float (Cortex-M4F; target ≤ 4,096) | "
             f"{num(img['ctrl_instance_bytes'])} | `nm -S` of the benchmark image's instance |")
    L.append(f"| `sizeof(uvms_ctrl_t)`, double (host, x86-64) | {num(double_size)} | "
             f"`nm -S` of `firmware/probe/ctrl_size_probe.c` compiled for the host |")
    L.append(f"| stack peak while stepping, Cortex-M4F (step + sensor generation, "
             f"max of IV, VII) | {num(stack)} | painted stack, bytes below the tick loop's "
             f"frame |")
    L.append(f"| benchmark image RAM, `.data + .bss` (one controller, its I/O records, "
             f"newlib) | {num(img['ram'])} | `arm-none-eabi-size` |")
    L.append(f"| benchmark image flash, `.text + .data` | {num(img['flash'])} | "
             f"`arm-none-eabi-size` |")
    L.append(f"| of which the firmware library: flash / RAM | {num(lib['flash'])} / "
             f"{num(lib['ram'])} | link map, input sections from `libuvms_firmware.a` |")
    L.append(f"| firmware library `.text`, all objects | {num(m4f['library_text_all_objects'])}"
             f" | `arm-none-eabi-size -t libuvms_firmware.a` |")
    L.append("")
    L.append("| Cortex-M4F, per `uvms_ctrl_step` | case IV | case VII |")
    L.append("|---|---:|---:|")
    row = lambda label, f: L.append(f"| {label} | " + " | ".join(f(cases[n]) for n in names)
                                    + " |")
    row("instructions, median (target ≤ 10,000)", lambda c: num(c["median"]))
    row("instructions, max (target ≤ 10,500)", lambda c: num(c["max"]))
    row("**estimate**: time at 168 MHz, median", lambda c: estimate_us(c["median"]))
    row(f"**estimate**: time at 168 MHz, max (share of the {TICK_S * 1e3:g} ms tick)",
        lambda c: f"{estimate_us(c['max'])} ({c['max'] / CLOCK_HZ * 1e6 / tick_us * 100:.2f} %)")
    L.append("")
    L.append(para(f"Instruction counts are exact (every executed instruction between markers around "
             f"the call; each includes {m4f['call_overhead_instructions']} instructions of call "
             f"overhead). The times are an estimate, not a measurement: instructions ÷ 168 MHz, "
             f"that is one cycle per instruction and no wait states. That ignores multi-cycle "
             f"instructions (loads and stores take 2 cycles unless pipelined, taken branches "
             f"refill the pipeline, `VDIV`/`VSQRT` take 14), flash wait states and the "
             f"accelerator or cache that hides them (an STM32F4 at 168 MHz runs flash with 5 wait "
             f"states), and interrupts; the real time is longer."))
    return "\n".join(L) + "\n"


def doc_block(text):
    """(before, block, after) of the doc around the markers."""
    i, j = text.find(BEGIN), text.find(END)
    if i < 0 or j < i or text.count(BEGIN) != 1 or text.count(END) != 1:
        raise Failure(f"docs/BENCHMARKS.md needs exactly one {BEGIN} ... {END} pair")
    i += len(BEGIN)
    return text[:i], text[i:j], text[j:]


def main(argv):
    if "-h" in argv or "--help" in argv:
        print(__doc__.strip())
        return 0
    ap = argparse.ArgumentParser(add_help=False)
    ap.add_argument("--update", action="store_true")
    ap.add_argument("--json")
    args, unknown = ap.parse_known_args(argv)
    if unknown:
        print(f"footprint_table: unknown arguments {unknown} (see --help)", file=sys.stderr)
        return 2
    update = args.update
    json_file = os.path.abspath(args.json) if args.json else None
    def under_root(path):  # an absolute path inside the checkout, as a relative one
        rel = os.path.relpath(path, ROOT) if os.path.isabs(path) else path
        return path if rel.startswith("..") else rel

    env = {"M4F_BUILD": under_root(os.environ.get("M4F_BUILD", "build/cortex-m4f")),
           "HOST_BUILD": under_root(os.environ.get("HOST_BUILD", "build/host")),
           "NO_BUILD": os.environ.get("NO_BUILD", "0")}
    env["BENCH_OUT"] = os.environ.get("BENCH_OUT", os.path.join(env["M4F_BUILD"], "footprint"))
    # The command that reproduces this measurement and writes it (with a build first).
    prefix = " ".join(f"{k}={shlex.quote(env[k])}" for k in ("M4F_BUILD", "HOST_BUILD")
                      if env[k] != {"M4F_BUILD": "build/cortex-m4f", "HOST_BUILD": "build/host"}[k])
    regen = (prefix + " " if prefix else "") + f"{SELF} --update"
    try:
        m4f, double_size = measure(env, json_file)
        new = "\n" + table(m4f, double_size)
        with open(DOC, encoding="utf-8") as f:
            text = f.read()
        before, old, after = doc_block(text)
    except Failure as e:
        print(f"footprint_table: {e}", file=sys.stderr)
        return 2
    if update:
        if old != new:
            with open(DOC, "w", encoding="utf-8") as f:
                f.write(before + new + after)
            print("footprint_table: docs/BENCHMARKS.md updated")
        else:
            print("footprint_table: docs/BENCHMARKS.md already current")
        return 0
    if old == new:
        print("footprint_table: docs/BENCHMARKS.md's footprint table matches the measurement")
        return 0
    sys.stdout.writelines(difflib.unified_diff(
        old.splitlines(True), new.splitlines(True), "docs/BENCHMARKS.md (footprint table)",
        "fresh measurement"))
    print(f"\nFAIL: docs/BENCHMARKS.md's footprint table differs from a fresh measurement.\n"
          f"Regenerate it with:\n    {regen}\n(then review and commit docs/BENCHMARKS.md)")
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
