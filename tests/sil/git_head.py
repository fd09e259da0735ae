# SPDX-License-Identifier: Apache-2.0
"""The git commit a build of SOURCE_DIR records (sil/provenance.hpp), for end-to-end tests."""
import os
import subprocess


def head_commit(src):
    """HEAD of src's own checkout, or None outside one (or without git)."""
    try:
        top = subprocess.run(["git", "-C", src, "rev-parse", "--show-toplevel"],
                             capture_output=True, text=True)
        if top.returncode != 0 or os.path.realpath(top.stdout.strip()) != os.path.realpath(src):
            return None
        return subprocess.run(["git", "-C", src, "rev-parse", "HEAD"], capture_output=True,
                              text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return None
