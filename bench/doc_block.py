#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""bench/doc_block.py: the generated blocks of docs/BENCHMARKS.md (imported by the bench scripts).

A generated block is the text between a begin marker and an end marker (HTML comments); a
script's --update replaces it with its new output (publish). machine() names the machine a
measurement ran on.

As a command, for the shell bench scripts: `bench/doc_block.py NAME < TEXT` writes TEXT between
<!-- NAME:begin --> and <!-- NAME:end --> in docs/BENCHMARKS.md.
"""
import argparse
import os
import sys

DOC = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "docs", "BENCHMARKS.md")


def replace_block(begin, end, text, doc=DOC):
    """Replaces what lies between `begin` and `end` in `doc` with `text` (SystemExit when the
    markers are missing or out of order)."""
    with open(doc) as f:
        s = f.read()
    i, j = s.find(begin), s.find(end)
    if i < 0 or j < i:
        raise SystemExit(f"{doc} has no {begin} ... {end} block")
    with open(doc, "w") as f:
        f.write(s[:i + len(begin)] + "\n" + text + "\n" + s[j:])


def publish(begin, end, text, update):
    """A bench script's table: printed; with `update` (its --update), also written between
    `begin` and `end` in docs/BENCHMARKS.md (replace_block)."""
    print(text)
    if update:
        replace_block(begin, end, text)
        print(f"docs/BENCHMARKS.md: {begin} ... {end} updated")


def machine():
    """The machine a measurement ran on, for a block's header: the CPU's model name and clock
    (from /proc/cpuinfo; "under a hypervisor" when it says so), the CPU count and the memory,
    e.g. "AMD EPYC at 2596 MHz, under a hypervisor; 2 CPUs, 24 GiB". Absolute times move with
    the machine: a figure without it cannot be compared with a later one."""
    model, mhz, virtual = "CPU model unknown", None, False
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                key, _, value = line.partition(":")
                key, value = key.strip(), value.strip()
                if key == "model name" and model == "CPU model unknown":
                    model = value
                elif key == "cpu MHz" and mhz is None:
                    mhz = float(value)
                elif key == "flags" and "hypervisor" in value.split():
                    virtual = True
    except OSError:
        pass
    clock = f" at {mhz:.0f} MHz" if mhz else ""
    gib = os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE") / 2**30
    return (f"{model}{clock}{', under a hypervisor' if virtual else ''}; "
            f"{os.cpu_count()} CPUs, {gib:.0f} GiB")


def main():
    ap = argparse.ArgumentParser(
        description="Writes standard input between <!-- NAME:begin --> and <!-- NAME:end --> in "
                    "docs/BENCHMARKS.md (the shell bench scripts' --update).")
    ap.add_argument("name", help="the block's name")
    args = ap.parse_args()
    replace_block(f"<!-- {args.name}:begin -->", f"<!-- {args.name}:end -->", sys.stdin.read())
    print(f"docs/BENCHMARKS.md: block {args.name} updated", file=sys.stderr)


if __name__ == "__main__":
    main()
