# SPDX-License-Identifier: Apache-2.0
"""checklist: the check loop that tests/tools/test_*.py share. Each check is a function that
raises AssertionError (or one of `errors`) when what it checks does not hold; `run` prints
"ok"/"FAIL" per check and then the plain closing line "N passed, M failed", removes the test's
scratch directory whatever happens, and returns the exit status (1 if any check failed)."""
import shutil
import time


def run(checks, tmp, setup=None, errors=(AssertionError,)):
    """Run `setup()` (if given), then every check in order; `tmp` is removed at the end."""
    t0 = time.time()
    failed = 0
    try:
        if setup is not None:
            setup()
        for check in checks:
            try:
                check()
                print(f"ok   {check.__name__}", flush=True)
            except errors as e:
                failed += 1
                print(f"FAIL {check.__name__}: {e}", flush=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"{len(checks) - failed} passed, {failed} failed ({time.time() - t0:.1f} s)")
    return 1 if failed else 0


class Tally:
    """The other style the tools' tests use: many `check(cond, msg)` calls (ok/FAIL per line)
    inside a few steps; `run(steps, tmp)` runs them, removes `tmp` whatever happens, prints
    "N passed, M failed" and returns the exit status."""

    def __init__(self):
        self.passed, self.failures = [], []

    def check(self, cond, msg):
        print(("ok   " if cond else "FAIL ") + msg, flush=True)
        (self.passed if cond else self.failures).append(msg)

    def run(self, steps, tmp):
        try:
            steps()
        finally:
            shutil.rmtree(tmp, ignore_errors=True)
        print(f"{len(self.passed)} passed, {len(self.failures)} failed")
        return 1 if self.failures else 0
