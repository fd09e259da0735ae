# SPDX-License-Identifier: Apache-2.0
"""Two campaign output directories compared as the engines promise (docs/CAMPAIGNS.md "How a
run is executed"): every file byte for byte, apart from the wall-clock fields.

The wall-clock fields are summary.json's `wall_time_s`, `real_time_factor` and `plant_wall_s`
(also in the rows of results.json; the first two are columns of results.csv) and the wall time
and real-time factor in the first line of run.out ("... 0.006465 s wall (232.0x real time, memq)"). Their values are masked in the text
and everything else is compared byte for byte: plan.json, overrides.json, run.lcmlog, the rest
of summary.json, run.out and results.json as text (key order and number formatting included),
results.csv field by field with those two columns left out.
Lock files and the files of an engine's own bookkeeping are not results and are not compared.
Standard library only; used by test_campaign_shards_e2e.py and test_campaign_dask.py.
"""
import csv
import io
import os
import re

WALL_CLOCK_KEYS = ("wall_time_s", "real_time_factor", "plant_wall_s")
_RUN_OUT_WALL = re.compile(r"[0-9.e+-]+ s wall \([0-9.]+x real time")


def _read(path):
    with open(path, "rb") as f:
        return f.read()


_JSON_WALL = re.compile(rb'("(?:' + b"|".join(k.encode() for k in WALL_CLOCK_KEYS) +
                       rb')": )[^,\n}]*')


def _json_without_wall_clock(data):
    """JSON text with the values of the wall-clock keys replaced by a mark (the text stays as
    it is otherwise: a difference in key order or number formatting still shows)."""
    return _JSON_WALL.sub(rb"\1<wall clock>", data)


def _csv_without_wall_clock(data):
    rows = list(csv.reader(io.StringIO(data.decode())))
    if not rows:
        return rows
    keep = [i for i, k in enumerate(rows[0]) if k not in WALL_CLOCK_KEYS]
    return [[r[i] for i in keep if i < len(r)] for r in rows]


def _run_out_without_wall_clock(data):
    return _RUN_OUT_WALL.sub("<wall> s wall (<rtf>x real time", data.decode(errors="replace"))


def _files(root):
    """Result files of a campaign DIR, relative paths (no lock files, no hidden work dirs)."""
    found = set()
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = [d for d in dirnames if not d.startswith(".")]
        for name in filenames:
            if not name.startswith("."):
                found.add(os.path.relpath(os.path.join(dirpath, name), root))
    return found


def _same(rel, a, b):
    name = os.path.basename(rel)
    if name.endswith(".json"):
        return _json_without_wall_clock(a) == _json_without_wall_clock(b)
    if name == "results.csv":
        return _csv_without_wall_clock(a) == _csv_without_wall_clock(b)
    if name == "run.out":
        return _run_out_without_wall_clock(a) == _run_out_without_wall_clock(b)
    return a == b


def differences(dir_a, dir_b):
    """The differences between two campaign DIRs, as sentences (empty: the same campaign)."""
    files_a, files_b = _files(dir_a), _files(dir_b)
    diffs = [f"{rel}: only in {d}" for rel, d in
             [(r, dir_a) for r in sorted(files_a - files_b)] +
             [(r, dir_b) for r in sorted(files_b - files_a)]]
    for rel in sorted(files_a & files_b):
        a, b = _read(os.path.join(dir_a, rel)), _read(os.path.join(dir_b, rel))
        if not _same(rel, a, b):
            diffs.append(f"{rel}: differs beyond the wall-clock fields")
    return diffs
