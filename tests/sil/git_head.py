# SPDX-License-Identifier: Apache-2.0
"""The git commit and the project version a build of SOURCE_DIR records (sil/run/provenance.hpp),
for end-to-end tests."""
import os
import re
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


def project_version(src):
    """The VERSION of project(...) in src's top-level CMakeLists.txt, or None without one."""
    with open(os.path.join(src, "CMakeLists.txt")) as f:
        m = re.search(r"project\(\s*\w+\s+VERSION\s+([0-9][0-9.]*)", f.read())
    return m.group(1) if m else None
