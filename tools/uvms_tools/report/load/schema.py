# SPDX-License-Identifier: Apache-2.0
"""schema: the configuration schema of the build, the JSON printed by
`uvms scenario schema`:

    {"schema_version": 1,
     "keys": [{"key": "thrusters.drive", "type": "...", "unit": "-", "default": <JSON value>,
               "range": "...", "firmware": ..., "lcm": ..., "plant": ..., "doc": "..."}, ...]}

The report takes every default and unit of a scenario key from here (never from
docs/SCENARIOS.md or the sources); the values the runs used come from their logged overrides,
summary.json and the logged controller configuration. A key whose "default" is null has no
single default (e.g. one derived from another key). Standard library only.
"""
import json
import os
import subprocess

SCHEMA_VERSION = 1
SUBCOMMAND = ("scenario", "schema")


class SchemaError(Exception):
    """The schema could not be obtained or is malformed; the message says why and what to do."""


class Schema:
    """The parsed schema: `entry(key)` is the key's row (dict), `default(key)` its default
    (None when it has none or the key is unknown), `defaults()` every non-null default."""

    def __init__(self, data, source=""):
        self.source = source   # for messages
        self.origin = ("text", source)  # ("binary" | "file" | "text", path): where it came from
        if not isinstance(data, dict):
            raise SchemaError(f"{source}: the schema is not a JSON object")
        ver = data.get("schema_version")
        if ver != SCHEMA_VERSION:
            raise SchemaError(f"{source}: schema_version {ver!r}, this report reads version "
                              f"{SCHEMA_VERSION}")
        rows = data.get("keys")
        if not isinstance(rows, list) or not rows:
            raise SchemaError(f"{source}: the schema has no \"keys\" list")
        self.rows = {}
        for i, row in enumerate(rows):
            if not isinstance(row, dict) or not isinstance(row.get("key"), str) \
                    or "default" not in row:
                raise SchemaError(f"{source}: keys[{i}] lacks \"key\" or \"default\"")
            self.rows[row["key"]] = row
        self.version = ver

    def __contains__(self, key):
        return key in self.rows

    def __len__(self):
        return len(self.rows)

    def entry(self, key):
        return self.rows.get(key)

    def default(self, key):
        row = self.rows.get(key)
        return None if row is None else row.get("default")

    def unit(self, key):
        row = self.rows.get(key)
        return None if row is None else row.get("unit")

    def defaults(self):
        """{key: default} of every key with a non-null default."""
        return {k: r["default"] for k, r in self.rows.items() if r["default"] is not None}

    def require_defaults(self, keys):
        """Raise SchemaError naming the keys of `keys` that have no default."""
        lacking = [k for k in keys if self.default(k) is None]
        if lacking:
            raise SchemaError(f"{self.source}: no default for {', '.join(lacking)} (the report "
                              f"selects runs by these keys)")


def parse(text, source="schema"):
    """Schema from JSON text."""
    try:
        data = json.loads(text)
    except json.JSONDecodeError as e:
        raise SchemaError(f"{source}: not JSON ({e})") from None
    return Schema(data, source)


def from_file(path):
    """Schema from a saved copy of `uvms scenario schema`'s output."""
    try:
        with open(path) as fh:
            text = fh.read()
    except OSError as e:
        raise SchemaError(f"cannot read the schema file {path}: {e.strerror}") from None
    sch = parse(text, path)
    sch.origin = ("file", path)
    return sch


def from_binary(uvms, timeout_s=120):
    """Schema printed by `UVMS scenario schema`."""
    cmd = f"{uvms} {' '.join(SUBCOMMAND)}"
    hint = ("the report reads every configuration default from the build's schema: build the "
            "host preset (cmake --build --preset host), or pass --uvms PATH (a uvms binary with "
            "`scenario schema`) or --schema FILE (its saved output)")
    if not os.path.isfile(uvms):
        raise SchemaError(f"cannot obtain the configuration schema: {uvms} does not exist; {hint}")
    try:
        p = subprocess.run([uvms, *SUBCOMMAND], capture_output=True, text=True,
                           timeout=timeout_s)
    except (OSError, subprocess.TimeoutExpired) as e:
        raise SchemaError(f"cannot obtain the configuration schema: `{cmd}`: {e}; {hint}") \
            from None
    if p.returncode != 0:
        err = (p.stderr.strip().splitlines() or ["no message"])[0]
        raise SchemaError(f"cannot obtain the configuration schema: `{cmd}` exited with "
                          f"{p.returncode} ({err}); {hint}")
    sch = parse(p.stdout, f"`{cmd}`")
    sch.origin = ("binary", uvms)
    return sch
