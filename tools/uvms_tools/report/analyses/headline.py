# SPDX-License-Identifier: Apache-2.0
"""headline: the barycenter-vs-vehicle comparisons of every campaign, counted as evidence.

A comparison is a dict (made by context.Report.add_comparison): exp (campaign name), label and
sub (display only), row (the override values that define its row in the per-experiment table),
cond (the override values shared by both sides), unsteady (from the runs' override values),
pair ("VII/IV"), paired (stats.Paired), verdict, config (the vehicle run's effective settings
without case and seed), seeds, energies (per seed: (seed, E_num, E_den))."""
import json
from collections import Counter

from . import stats


def _norm_value(v):
    if isinstance(v, bool) or v is None or isinstance(v, str):
        return v
    if isinstance(v, (int, float)):
        return float(f"{float(v):.12g}")
    if isinstance(v, (list, tuple)):
        return [_norm_value(x) for x in v]
    if isinstance(v, dict):
        return {k: _norm_value(x) for k, x in v.items()}
    return str(v)


def normalize_config(cfg, keys=(), defaults=None):
    """A configuration (dotted key → value) as a canonical JSON string: every key of `keys`
    (the union over the configurations being compared) filled with its default (`defaults`,
    the schema's) where unset, numbers to 12 significant digits."""
    dflt = defaults or {}
    full = dict(cfg)
    for k in keys:
        if k not in full and k in dflt:
            full[k] = dflt[k]
    return json.dumps({k: _norm_value(v) for k, v in full.items()}, sort_keys=True)


def cmp_name(c):
    """A headline comparison's short name: 'exp2, (C) unsteady, density error, 10 kg'."""
    return c["label"] + (f", {c['sub']}" if c.get("sub") else "")


def _union_find(n, same):
    """Groups of 0..n−1 under the relation same(i, j) (j < i), in order of first element."""
    parent = list(range(n))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i in range(n):
        for j in range(i):
            if same(i, j):
                parent[root(i)] = root(j)
    groups = {}
    for i in range(n):  # in order: each group's first entry is its earliest
        groups.setdefault(root(i), []).append(i)
    return list(groups.values())


def dedupe_comparisons(comps, defaults=None):
    """Group headline comparisons that are the same evidence: the same pair of cases over the
    same seeds and either the same effective configuration (normalize_config, defaults filled
    over the union of keys) or bit-identical per-seed energies. Returns (groups, notes):
    groups in order of first appearance, each a list whose first entry stands for the group;
    notes name any inconsistency (same configuration, different energies: the runs are not
    reproducible; different configuration, identical energies: a setting that changed
    nothing)."""
    keys = set()
    for c in comps:
        keys |= set(c.get("config") or {})
    ident = [(c["pair"], tuple(c.get("seeds") or ()),
              normalize_config(c.get("config") or {}, keys, defaults)) for c in comps]
    notes = []

    def same(i, j):
        same_cfg = bool(comps[i].get("config")) and ident[i] == ident[j]
        ei, ej = comps[i].get("energies"), comps[j].get("energies")
        same_e = bool(ei) and ei == ej and comps[i]["pair"] == comps[j]["pair"]
        if same_cfg and ei and ej and ei != ej:
            notes.append(f"{cmp_name(comps[i])} and {cmp_name(comps[j])} have the same "
                         f"configuration but different energies (runs not reproducible?)")
        if same_e and not same_cfg:
            notes.append(f"{cmp_name(comps[i])} and {cmp_name(comps[j])} differ in their "
                         f"settings but have bit-identical energies: counted once")
        return same_cfg or same_e

    groups = _union_find(len(comps), same)
    return [[comps[i] for i in g] for g in groups], notes


def answer(n_cheaper, n):
    """The headline's one-word answer for k cheaper verdicts of n configurations."""
    k = n_cheaper
    return "yes" if k == n else "mostly" if k > n / 2 else "no" if k == 0 else "rarely"


def verdict_counts(comps):
    return Counter(c["verdict"] for c in comps)


def verdict_text(verd):
    """'3× cheaper, 1× no significant difference' in a fixed order."""
    return ", ".join(f"{verd[v]}× {v}" for v in (stats.CHEAPER, stats.NO_DIFF, stats.DEARER)
                     if verd.get(v))


def row_groups(comps):
    """{(exp, pair, row values): [comparisons]} in order of first appearance: the rows of the
    per-experiment table, grouped by the override values that define each row."""
    out = {}
    for c in comps:
        key = (c["exp"], c["pair"], json.dumps(c.get("row") or {}, sort_keys=True))
        out.setdefault(key, []).append(c)
    return out


def small_savings(comps, limit):
    """The cheaper comparisons whose mean ratio is above 1 − limit."""
    return [c for c in comps if c["verdict"] == stats.CHEAPER
            and c["paired"].dist.mean > 1 - limit]
