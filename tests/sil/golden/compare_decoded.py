# SPDX-License-Identifier: Apache-2.0
"""compare_decoded.py: two run logs of the same runs, written before and after a change of the
message types, are the same but for the fields the change names.

For a change meant to alter the golden logs (tests/sil/test_golden_logs.py --update) that
adds or changes message fields: record the paper scenarios' logs with the old and the new build
(as test_golden_logs.py runs them), then run this. Every event pair must have the same channel
and timestamp; events with equal bytes pass; the others are decoded, the old one with the old
types (.lcm files of OLD_REV) and the new one with this tree's, and every field must be equal
except the ones --ignore names (TYPE.FIELD), the crc32 (it covers the changed bytes) and fields
only one version has that --ignore names. A field --widened names was a scalar and is now an
array (one value per thruster, say): every entry of the new one must equal the old scalar.

Usage: compare_decoded.py OLD_DIR NEW_DIR OLD_REV [--ignore TYPE.FIELD]... [--widened TYPE.FIELD]...
OLD_DIR, NEW_DIR: folders of run folders (NAME/run.lcmlog) with the same names.
OLD_REV: the git revision whose lcmtypes/*.lcm wrote OLD_DIR's logs.
Exit status 0 when every log matches, 1 otherwise; one line per log.
"""
import glob
import importlib.util
import os
import subprocess
import sys

import lcm

SRC = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..", ".."))
sys.path.insert(0, os.path.join(SRC, "tests", "support"))
from scratch import scratch_dir  # noqa: E402  (removed at exit)


def generate(lcm_files, tag):
    """Python classes of the given .lcm files, loaded under module names of their own."""
    out = scratch_dir(f"uvms-lcm-{tag}-")
    subprocess.run(["lcm-gen", "--python", "--ppath", out] + lcm_files, check=True)
    classes = {}
    for path in glob.glob(os.path.join(out, "uvms", "*_t.py")):
        name = os.path.basename(path)[:-3]
        spec = importlib.util.spec_from_file_location(f"{tag}_{name}", path)
        mod = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(mod)
        classes[name] = getattr(mod, name)
    return classes


def old_lcm_files(rev):
    out = scratch_dir("uvms-lcm-src-")
    names = subprocess.run(["git", "-C", SRC, "ls-tree", "--name-only", rev, "lcmtypes/"],
                           check=True, capture_output=True, text=True).stdout.split()
    files = []
    for n in names:
        if n.endswith(".lcm"):
            text = subprocess.run(["git", "-C", SRC, "show", f"{rev}:{n}"], check=True,
                                  capture_output=True, text=True).stdout
            path = os.path.join(out, os.path.basename(n))
            with open(path, "w") as f:
                f.write(text)
            files.append(path)
    return files


def by_fingerprint(classes):
    return {cls._get_packed_fingerprint(): cls for cls in classes.values()}


def fields(msg):
    return {k: getattr(msg, k) for k in msg.__slots__}


def compare_log(old_path, new_path, old_types, new_types, ignore, widened=frozenset()):
    a = list(lcm.EventLog(old_path, "r"))
    b = list(lcm.EventLog(new_path, "r"))
    if len(a) != len(b):
        return f"{len(a)} events before, {len(b)} after"
    decoded = 0
    for ea, eb in zip(a, b):
        if ea.channel != eb.channel or ea.timestamp != eb.timestamp:
            return f"event {ea.eventnum}: channel/timestamp {ea.channel}@{ea.timestamp} vs {eb.channel}@{eb.timestamp}"
        if ea.data == eb.data:
            continue
        ca, cb = old_types.get(ea.data[:8]), new_types.get(eb.data[:8])
        if ca is None or cb is None or ca.__name__ != cb.__name__:
            return f"event {ea.eventnum} ({ea.channel}): bytes differ and the types do not decode them"
        fa, fb = fields(ca.decode(ea.data)), fields(cb.decode(eb.data))
        t = ca.__name__
        for k in sorted(set(fa) | set(fb)):
            if k == "crc32" or f"{t}.{k}" in ignore:
                continue
            if k not in fa or k not in fb:
                return f"event {ea.eventnum} ({ea.channel}): field {t}.{k} in one version only"
            if f"{t}.{k}" in widened:
                if any(v != fa[k] for v in fb[k]):
                    return f"event {ea.eventnum} ({ea.channel}): {t}.{k} {fb[k]!r} is not {fa[k]!r} throughout"
                continue
            if fa[k] != fb[k]:
                return f"event {ea.eventnum} ({ea.channel}): {t}.{k} {fa[k]!r} != {fb[k]!r}"
        decoded += 1
    widened_text = f"; widened and equal: {', '.join(sorted(widened))}" if widened else ""
    return f"ok ({len(a)} events, {decoded} decoded and equal but for {', '.join(sorted(ignore))}{widened_text})"


def main(argv):
    if len(argv) < 4 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) > 1 and argv[1] in ("-h", "--help") else 2
    old_dir, new_dir, rev = argv[1], argv[2], argv[3]
    ignore = {argv[i + 1] for i in range(4, len(argv) - 1) if argv[i] == "--ignore"}
    widened = frozenset(argv[i + 1] for i in range(4, len(argv) - 1) if argv[i] == "--widened")
    old_types = by_fingerprint(generate(old_lcm_files(rev), "old"))
    new_types = by_fingerprint(generate(sorted(glob.glob(os.path.join(SRC, "lcmtypes", "*.lcm"))), "new"))
    bad = 0
    names = sorted(os.listdir(old_dir))
    if sorted(os.listdir(new_dir)) != names:
        print("FAIL: the two folders hold different runs")
        return 1
    for name in names:
        verdict = compare_log(os.path.join(old_dir, name, "run.lcmlog"),
                              os.path.join(new_dir, name, "run.lcmlog"), old_types, new_types, ignore,
                              widened)
        ok = verdict.startswith("ok")
        bad += not ok
        print(f"{'ok  ' if ok else 'FAIL'} {name}: {verdict}")
    print(f"{len(names) - bad} of {len(names)} logs equal but for {', '.join(sorted(ignore)) or 'nothing'}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
