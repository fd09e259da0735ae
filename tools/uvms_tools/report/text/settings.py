# SPDX-License-Identifier: Apache-2.0
"""settings: where the report's text gets a setting's default (the configuration schema) and
where the paper campaigns set it (the runs' logged overrides, the base scenarios)."""
from ..load.paths import disp_path
from .fmt import fmt_setting


def default_text(schema, key):
    """A key's default as the scenario files write it, from the schema."""
    v = schema.default(key)
    return fmt_setting(v) if v is not None else f"no single default (see `{key}` in the schema)"


def where_set(exps, keys):
    """Where any of `keys` is set: by the runs of a campaign (their logged overrides, which
    hold the campaign's [set], sweeps and replicates) or in a campaign's base scenario."""
    where = []
    for e in exps.values():
        for k in sorted(keys):
            vals = {fmt_setting(r[k]) for r in e.runs if k in r.get("_overrides", [])}
            if len(vals) == 1:
                where.append(f"{e.name}: {k} = {vals.pop()}")
            elif vals:
                where.append(f"{e.name}: {k} in {len(vals)} values")
        base = e.base_keys()
        for k in keys:
            if k in base:
                where.append(f"{disp_path(e.base_path)}: {k} = {fmt_setting(base[k])}")
    return sorted(set(where))


def overridden_text(exps, *keys):
    """'; overridden: …' or '; not overridden by any paper campaign or base scenario'."""
    o = where_set(exps, set(keys))
    if o:
        return "; overridden: " + "; ".join(o)
    return "; not overridden by any paper campaign or base scenario"


def coeff_rows(table):
    """(distance [diameters], drag factor, added-mass factor) of a coefficient table (the
    schema's environment.coeff_table: a list of objects)."""
    out = []
    for row in table or []:
        try:
            out.append(tuple(float(row[k]) for k in ("distance_diameters", "drag_factor",
                                                      "added_mass_factor")))
        except (KeyError, TypeError, ValueError):
            return []  # not the schema's format: shown as missing rather than guessed
    return out
