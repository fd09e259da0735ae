# SPDX-License-Identifier: Apache-2.0
"""tomlfiles: the input files a campaign names (plan.json "campaign", "base"): the base
scenario's keys (its settings under every run's overrides) and the campaign file's leading
comment (quoted as its description)."""
import tomllib


def flatten_toml(d, prefix=""):
    """{dotted key: value} of nested TOML tables."""
    out = {}
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(flatten_toml(v, key + "."))
        else:
            out[key] = v
    return out


def toml_keys(path):
    """Flattened keys of a scenario file (or {} if unreadable)."""
    try:
        with open(path, "rb") as fh:
            return flatten_toml(tomllib.load(fh))
    except (OSError, tomllib.TOMLDecodeError):
        return {}


def header_comment(path):
    """The leading comment block of a TOML file, as one paragraph."""
    lines = []
    try:
        with open(path) as fh:
            for line in fh:
                if not line.startswith("#"):
                    break
                lines.append(line[1:].strip())
    except OSError:
        return ""
    return " ".join(lines)
