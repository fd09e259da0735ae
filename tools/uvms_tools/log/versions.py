# SPDX-License-Identifier: Apache-2.0
"""versions: the message versions of lcmtypes/fingerprints.tsv.

Each uvms message type has numbered versions, each known by the fingerprint LCM computes from
its fields. The last version of a type is the one this build reads; a log message carrying an
older listed fingerprint is refused with both versions named (`older_version_problem`), never
decoded with the wrong layout."""
import os

from ..env import REPO_ROOT

TABLE = os.path.join(REPO_ROOT, "lcmtypes", "fingerprints.tsv")


def load(path=TABLE):
    """{type name: [(version, fingerprint bytes), ...]} in the file's order."""
    versions = {}
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            if not line.strip() or line.startswith("#"):
                continue
            parts = line.split()
            if len(parts) != 3 or not parts[1].isdigit() or not parts[2].startswith("0x"):
                raise ValueError(f"{path}:{n}: expected 'type version 0xFINGERPRINT'")
            versions.setdefault(parts[0], []).append((int(parts[1]),
                                                      bytes.fromhex(parts[2][2:])))
    return versions


def current(versions, type_name):
    """(version, fingerprint) this build reads, or None for an unlisted type."""
    listed = versions.get(type_name)
    return listed[-1] if listed else None


def older_version_problem(versions, type_name, fingerprint):
    """The refusal for a message of `type_name` carrying an older listed fingerprint, or None."""
    listed = versions.get(type_name, [])
    for version, fp in listed[:-1]:
        if fp == fingerprint:
            now, now_fp = listed[-1]
            return (f"a uvms.{type_name} message of version {version} (fingerprint "
                    f"0x{fp.hex()}); this build reads version {now} (0x{now_fp.hex()}): the log "
                    "was written by an older build. Read it with the build that wrote it (its "
                    "summary.json names the version), or re-run the scenario")
    return None
