# SPDX-License-Identifier: Apache-2.0
"""lcm_schema: the LCM message definitions (lcmtypes/*.lcm) read as data, and a JSON Schema of
each, for the MCAP export (log/mcap_export.py). The schemas are made from the .lcm files, the
same definitions lcm-gen makes the decoders from, never written per field.

Only what lcmtypes/ uses is read: `package`, `struct`, `const` lines (skipped), members of a
primitive type with fixed or variable array dimensions, `//` and `/* */` comments (a member's
trailing comment becomes its schema description). Anything else is an LcmSchemaError naming
the file and line.

JSON mapping (the exporter writes values this way, the schemas say so):
  int8_t, int16_t, int32_t, byte   integer
  int64_t                          string of the decimal value: JSON numbers are IEEE doubles
                                   in most readers (Foxglove's too), exact only to 2^53, and a
                                   session id is a random 64-bit value
  float, double                    number; a non-finite value (JSON has none) as the string
                                   "NaN", "Infinity" or "-Infinity"
  boolean                          boolean
  string                           string
  byte[N] (one dimension)          string: NUL-padded UTF-8 text, up to its first NUL
  T[N]..., T[member]...            arrays (N items; a member's value items)
"""
import os
import re

from uvms_tools.env import REPO_ROOT

INTEGER = {"int8_t", "int16_t", "int32_t", "byte"}
REAL = {"float", "double"}
PRIMITIVE = INTEGER | REAL | {"int64_t", "boolean", "string"}
MEMBER = re.compile(r"^(\w+)\s+(\w+)\s*((?:\[\s*\w+\s*\]\s*)*);$")
DIM = re.compile(r"\[\s*(\w+)\s*\]")


class LcmSchemaError(Exception):
    """A .lcm file this reader does not understand, or no lcmtypes directory."""


class Member:
    """One member: its LCM type, name, dimensions (ints, or the name of the member holding the
    length) and trailing comment."""

    def __init__(self, type_name, name, dims, comment):
        self.type, self.name, self.dims, self.comment = type_name, name, dims, comment

    def is_text(self):
        """byte[N]: NUL-padded text (the convention of lcmtypes/: run_status_t.reason)."""
        return self.type == "byte" and len(self.dims) == 1


def lcmtypes_dir():
    """$UVMS_LCMTYPES_DIR, else lcmtypes/ of this repository."""
    d = os.environ.get("UVMS_LCMTYPES_DIR") or os.path.join(REPO_ROOT, "lcmtypes")
    if not os.path.isdir(d):
        raise LcmSchemaError(f"no LCM type definitions: {d} is not a directory (set "
                             "UVMS_LCMTYPES_DIR to the lcmtypes/ the log was written with)")
    return d


def _strip_block_comments(text):
    return re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)


def parse(path):
    """{struct name: [Member]} of one .lcm file (package `uvms` assumed by the caller)."""
    with open(path) as f:
        lines = _strip_block_comments(f.read()).splitlines()
    structs, current = {}, None
    for no, raw in enumerate(lines, 1):
        code, _, comment = raw.partition("//")
        code = code.strip()
        where = f"{path}:{no}"
        if not code:
            # A comment line right under a member continues its description.
            if current is not None and current and comment.strip() and raw.startswith(" " * 8):
                current[-1].comment = (current[-1].comment + " " + comment.strip()).strip()
            continue
        if code.startswith("package ") or code == "{" or code.startswith("const "):
            continue
        m = re.match(r"^struct\s+(\w+)\s*(\{)?$", code)
        if m:
            current = structs.setdefault(m.group(1), [])
            continue
        if code in ("}", "};"):
            current = None
            continue
        m = MEMBER.match(code)
        if m is None or current is None:
            raise LcmSchemaError(f"{where}: not a member this reader knows: {code!r}")
        type_name, name, dims = m.group(1), m.group(2), DIM.findall(m.group(3))
        if type_name not in PRIMITIVE:
            raise LcmSchemaError(f"{where}: member {name} has type {type_name}: only primitive "
                                 "types are supported")
        current.append(Member(type_name, name, [int(d) if d.isdigit() else d for d in dims],
                              comment.strip()))
    return structs


def definitions():
    """{type name: [Member]} of every lcmtypes/*.lcm."""
    d = lcmtypes_dir()
    out = {}
    for name in sorted(os.listdir(d)):
        if name.endswith(".lcm"):
            out.update(parse(os.path.join(d, name)))
    if not out:
        raise LcmSchemaError(f"no struct in {d}/*.lcm")
    return out


def _leaf(m):
    if m.is_text():
        return {"type": "string", "description": "NUL-padded UTF-8 text, up to its first NUL"}
    if m.type in INTEGER:
        return {"type": "integer"}
    if m.type == "int64_t":
        return {"type": "string", "pattern": "^-?[0-9]+$",
                "description": "int64 as a decimal string (exact; JSON numbers are not)"}
    if m.type in REAL:
        return {"type": ["number", "string"], "pattern": "^(NaN|-?Infinity)$",
                "description": "a number; non-finite as NaN, Infinity or -Infinity"}
    return {"type": "boolean" if m.type == "boolean" else "string"}


def member_schema(m):
    """The JSON Schema of one member: its leaf wrapped in one array per dimension."""
    s = _leaf(m)
    dims = m.dims[:-1] if m.is_text() else m.dims
    for d in reversed(dims):
        s = {"type": "array", "items": s}
        if isinstance(d, int):
            s["minItems"] = s["maxItems"] = d
    if m.comment:
        s = dict(s, description=m.comment + (f" ({s['description']})" if "description" in s
                                               else ""))
    return s


def json_schema(type_name, members):
    """The JSON Schema (draft 2020-12) of one LCM type, as a dict."""
    return {"$schema": "https://json-schema.org/draft/2020-12/schema",
            "title": f"uvms.{type_name}", "type": "object",
            "properties": {m.name: member_schema(m) for m in members},
            "required": [m.name for m in members], "additionalProperties": False}
