# SPDX-License-Identifier: Apache-2.0
"""What the campaign tests share (test_campaign_e2e.py, test_campaign_shards_e2e.py,
test_campaign_dask.py): the failure report and waiting for a running campaign to reach a
point. Standard library only."""
import os
import sys
import time


def fail(msg):
    """The test's verdict: prints FAIL and the reason, exits 1."""
    print("FAIL:", msg)
    sys.exit(1)


def wait_for(path, proc, timeout_s=60.0):
    """Waits until `path` exists while `proc` (a Popen) runs; fails when `proc` ends first or
    after timeout_s seconds."""
    deadline = time.monotonic() + timeout_s
    while not os.path.exists(path):
        if proc.poll() is not None or time.monotonic() > deadline:
            fail(f"{path} did not appear (the campaign's exit status: {proc.poll()})")
        time.sleep(0.01)
