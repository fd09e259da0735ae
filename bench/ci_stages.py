#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""bench/ci_stages.py: the stage times of a `.ci/run` log as a row of docs/BENCHMARKS.md.

    bench/ci_stages.py LOG --commit SHA             print the row
    bench/ci_stages.py LOG --commit SHA --update    add it to the table in docs/BENCHMARKS.md
                                                    (between <!-- ci-stages:begin --> and
                                                    <!-- ci-stages:end -->; a row of the same
                                                    commit is replaced)

LOG is the output of `time CI=true bash .ci/run` on a fresh clone: tools/test prints "===
tools/test: stage times (N s in all) ===" and one line per stage (bootstrap; configure, build
and test of each host preset), .ci/run "=== .ci/run: done in N s (tools/test N s, cortex-m4f N
s) ===". A log without them (a failed run, an older .ci/run) is an error (exit 1) naming what
is missing. The date is today's (UTC) unless --date is given.
"""
import argparse
import datetime
import os
import re
import sys

DOC = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "docs",
                   "BENCHMARKS.md")
BEGIN, END = "<!-- ci-stages:begin -->", "<!-- ci-stages:end -->"
PRESETS = ("host", "host-float", "host-asan", "host-fuzz")
HEADER = ("| date | commit | bootstrap | " + " | ".join(f"{p}: build / test" for p in PRESETS)
          + " | cortex-m4f | total |")


class StageError(ValueError):
    """A log without the stage lines."""


def parse(text):
    """{"bootstrap": s, "<preset>": (configure, build, test), "cortex-m4f": s, "total": s}."""
    out = {}
    m = re.search(r"^  bootstrap (\d+) s$", text, re.M)
    if m:
        out["bootstrap"] = int(m.group(1))
    for p in PRESETS:
        m = re.search(rf"^  {re.escape(p)}: configure (\d+) s, build (\d+) s, test (\d+) s$",
                      text, re.M)
        if m:
            out[p] = tuple(int(x) for x in m.groups())
    m = re.search(r"=== \.ci/run: done in (\d+) s \(tools/test (\d+) s, cortex-m4f (\d+) s\) ===",
                  text)
    if m:
        out["total"], out["cortex-m4f"] = int(m.group(1)), int(m.group(3))
    missing = [k for k in ("bootstrap", *PRESETS, "cortex-m4f", "total") if k not in out]
    if missing:
        raise StageError(f"no stage time of {', '.join(missing)} in the log (a failed run, or a "
                         ".ci/run that prints no stage times)")
    return out


def row(stages, commit, date):
    def mmss(s):
        return f"{s} s ({s // 60} min {s % 60:02d} s)"
    cells = [date, commit[:7], f"{stages['bootstrap']} s"]
    cells += [f"{stages[p][0] + stages[p][1]} / {stages[p][2]} s" for p in PRESETS]
    cells += [f"{stages['cortex-m4f']} s", f"**{mmss(stages['total'])}**"]
    return "| " + " | ".join(cells) + " |"


def update(doc_text, new_row, commit):
    """doc_text with new_row in the table between the markers (a row of `commit` replaced)."""
    if BEGIN not in doc_text or END not in doc_text:
        raise StageError(f"no {BEGIN} ... {END} in {DOC}")
    head, rest = doc_text.split(BEGIN, 1)
    body, tail = rest.split(END, 1)
    rows = [ln for ln in body.strip().splitlines()[2:] if ln.startswith("|")]
    rows = [r for r in rows if f"| {commit[:7]} |" not in r] + [new_row]
    table = [HEADER, "|" + "---|" * (len(PRESETS) + 5)] + rows
    return head + BEGIN + "\n" + "\n".join(table) + "\n" + END + tail


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("log", help="the output of `time CI=true bash .ci/run`")
    ap.add_argument("--commit", required=True, help="the commit the CI run checked out")
    ap.add_argument("--date", default=datetime.datetime.now(datetime.timezone.utc)
                    .strftime("%Y-%m-%d"))
    ap.add_argument("--update", action="store_true", help="write the row into the doc")
    a = ap.parse_args(argv)
    try:
        with open(a.log, errors="replace") as f:
            stages = parse(f.read())
        r = row(stages, a.commit, a.date)
        if not a.update:
            print(r)
            return 0
        with open(DOC) as f:
            text = f.read()
        with open(DOC, "w") as f:
            f.write(update(text, r, a.commit))
        print(f"ci_stages: {os.path.relpath(DOC)}: {r}")
    except (OSError, StageError) as e:
        print(f"ci_stages: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
