# SPDX-License-Identifier: Apache-2.0
"""bench/doc_block.py: the generated blocks of docs/BENCHMARKS.md (imported by the bench scripts).

A generated block is the text between a begin marker and an end marker (HTML comments); a
script's --update replaces it with its new output.
"""
import os

DOC = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "docs", "BENCHMARKS.md")


def replace_block(begin, end, text, doc=DOC):
    """Replaces what lies between `begin` and `end` in `doc` with `text` (SystemExit when the
    markers are missing or out of order)."""
    with open(doc) as f:
        s = f.read()
    i, j = s.find(begin), s.find(end)
    if i < 0 or j < i:
        raise SystemExit(f"{doc} has no {begin} ... {end} block")
    with open(doc, "w") as f:
        f.write(s[:i + len(begin)] + "\n" + text + "\n" + s[j:])
