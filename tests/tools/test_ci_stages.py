# SPDX-License-Identifier: Apache-2.0
"""bench/ci_stages.py: a .ci/run log's stage lines become one row of docs/BENCHMARKS.md's CI
table (numbers taken as printed; build = configure + build); a log without them is refused,
naming what is missing; --update replaces the row of the same commit and keeps the others.

Usage: test_ci_stages.py SOURCE_DIR
"""
import os
import sys

SRC = sys.argv[1]
sys.path.insert(0, os.path.join(SRC, "bench"))
import ci_stages  # noqa: E402

LOG = """...
=== tools/test: stage times (911 s in all) ===
  bootstrap 32 s
  host: configure 1 s, build 134 s, test 156 s
  host-float: configure 1 s, build 129 s, test 40 s
  host-asan: configure 1 s, build 241 s, test 70 s
  host-fuzz: configure 1 s, build 53 s, test 53 s
=== .ci/run: cross build, workflow preset cortex-m4f ===
=== .ci/run: done in 913 s (tools/test 911 s, cortex-m4f 2 s) ===
"""
failures = []


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


stages = ci_stages.parse(LOG)
r = ci_stages.row(stages, "1e1853f0000", "2026-12-05")
check(r == "| 2026-12-05 | 1e1853f | 32 s | 135 / 156 s | 130 / 40 s | 242 / 70 s | 54 / 53 s "
          "| 2 s | **913 s (15 min 13 s)** |", f"the row of a log: {r}")
try:
    ci_stages.parse(LOG.replace("  host-asan: configure 1 s, build 241 s, test 70 s\n", "")
                    .replace("done in 913 s", "done"))
    check(False, "a log without stage lines is refused")
except ci_stages.StageError as e:
    check("host-asan" in str(e) and "total" in str(e), f"a log without them is refused: {e}")
doc = f"before\n{ci_stages.BEGIN}\n{ci_stages.HEADER}\n|---|\n| old | 0000000 | x |\n" \
      f"| old | 1e1853f | stale |\n{ci_stages.END}\nafter\n"
new = ci_stages.update(doc, r, "1e1853f")
check(new.count("1e1853f") == 1 and "stale" not in new and "| old | 0000000 | x |" in new
      and new.startswith("before\n") and new.endswith(f"{ci_stages.END}\nafter\n"),
      "--update replaces the row of the same commit, keeps the others and the text around")
print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
