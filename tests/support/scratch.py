# SPDX-License-Identifier: Apache-2.0
"""A test's scratch directory under the system's temporary directory, removed when the test's
process exits (passed or failed), so that a test run leaves nothing behind.

Set UVMS_KEEP_TEST_SCRATCH=1 to keep it for a look; the path is then printed at exit.
"""
import atexit
import os
import shutil
import tempfile

KEEP_ENV = "UVMS_KEEP_TEST_SCRATCH"


def scratch_dir(prefix):
    """A new directory named prefix + random suffix, removed at exit unless KEEP_ENV is set."""
    path = tempfile.mkdtemp(prefix=prefix)
    atexit.register(_finish, path)
    return path


def _finish(path):
    if os.environ.get(KEEP_ENV) == "1":
        print(f"scratch kept ({KEEP_ENV}=1): {path}")
    else:
        shutil.rmtree(path, ignore_errors=True)
