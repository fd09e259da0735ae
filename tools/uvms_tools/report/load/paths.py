# SPDX-License-Identifier: Apache-2.0
"""paths: paths as the report shows them, without machine-specific prefixes."""
import os
import re

from uvms_tools.env import REPO_ROOT


def disp_path(p, root=None):
    """A path for the report without machine-specific prefixes: relative to the repository,
    to `root` (the campaigns root), or from its 'sil/' component; else its basename."""
    if not p:
        return ""
    p = str(p)
    if not os.path.isabs(p):
        return p
    for base, prefix in ((REPO_ROOT, ""), (root, "")):
        if base and (p == base or p.startswith(base.rstrip("/") + "/")):
            return prefix + (os.path.relpath(p, base) if p != base else ".")
    m = re.search(r"(?:^|/)((?:sil|tools|tests|docs|firmware|plant)/.*)$", p)
    if m:
        return m.group(1)
    return os.path.basename(p)
