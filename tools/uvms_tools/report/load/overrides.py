# SPDX-License-Identifier: Apache-2.0
"""overrides: a run's settings are its overrides ('section.key=VALUE', TOML values, from
plan.json or the run's overrides.json), its results row and summary.json; a key the run does
not set takes the schema's default. Runs are selected by these values, never by run ids or
labels."""
import json
import tomllib

from ..keys import KEY_SEED
from ..num import isnum


def parse_override(text):
    """'section.key=VALUE' (TOML value) -> (key, value); (None, None) if unparsable."""
    key, sep, val = str(text).partition("=")
    if not sep:
        return None, None
    try:
        return key.strip(), tomllib.loads("v = " + val.strip())["v"]
    except tomllib.TOMLDecodeError:
        return key.strip(), val.strip()


def apply_overrides(texts):
    """{key: value} of a run's override texts, applied in order (the last value of a key
    wins)."""
    applied = {}
    for text in texts or []:
        k, v = parse_override(text)
        if k is not None:
            applied[k] = v
    return applied


def same_value(a, b):
    """Equal settings: bools only equal bools, numbers compared to 1e-9."""
    if isinstance(a, bool) or isinstance(b, bool):
        return a is b or (isinstance(a, bool) and isinstance(b, bool) and a == b)
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return abs(float(a) - float(b)) < 1e-9
    return a == b


def run_value(run, key, defaults):
    """A run's value of a scenario key: its own (override or results row), else the
    schema's default (`defaults`: {key: default})."""
    return run[key] if key in run else defaults.get(key)


def seed_of(run):
    s = run.get(KEY_SEED)
    return int(s) if isnum(s) else None


def matches(run, cond, defaults):
    """The run has every value of `cond` ({key: value})."""
    return all(same_value(run_value(run, k, defaults), v) for k, v in cond.items())


def differing_keys(a, b, defaults):
    """Override keys whose values differ between two runs."""
    keys = set(a.get("_overrides", [])) | set(b.get("_overrides", []))
    return sorted(k for k in keys
                  if not same_value(run_value(a, k, defaults), run_value(b, k, defaults)))


def finished(run):
    return run is not None and run.get("status") == "finished"


def condition_key(run, skip=(KEY_SEED,)):
    """The run's overrides without `skip`, as a hashable key: runs that differ only in
    run.seed share it (one condition)."""
    return tuple(sorted((k, json.dumps(run[k], sort_keys=True))
                        for k in run.get("_overrides", []) if k not in skip))
