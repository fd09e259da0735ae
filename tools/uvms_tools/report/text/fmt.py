# SPDX-License-Identifier: Apache-2.0
"""fmt: number, statistic and table formatting for the report's Markdown. Standard library
and numpy only."""
import math
import re

from ..num import div, isnum  # noqa: F401 (re-exported)


def f(x, nd=1, unit=""):
    """Fixed-point number or 'n/a'."""
    if not isnum(x):
        return "n/a"
    return f"{float(x):.{nd}f}" + (f" {unit}" if unit else "")


def g(x, sig=3, unit=""):
    """Significant-digit number or 'n/a'."""
    if not isnum(x):
        return "n/a"
    return f"{float(x):.{sig}g}" + (f" {unit}" if unit else "")


def mm(x, nd=2):
    return f(None if not isnum(x) else 1e3 * float(x), nd)


def cell(c):
    """A table cell: '|' inside it (|x|, ∫Σ|T|) escaped so that it does not split the cell."""
    return str(c).replace("\\|", "|").replace("|", "\\|")


def table(header, rows):
    out = ["| " + " | ".join(cell(h) for h in header) + " |",
           "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(cell(c) for c in r) + " |" for r in rows]
    return out + [""]


def fmt_range(vals, nd=3):
    v = [x for x in vals if isnum(x)]
    if not v:
        return "n/a"
    return f(min(v), nd) if len(v) == 1 or min(v) == max(v) else f"{f(min(v), nd)}–{f(max(v), nd)}"


def _num(x, nd, sig):
    return g(x, sig) if sig else f(x, nd)


def failed_suffix(d):
    """' (k failed)' when k runs (or seed pairs) of the sample gave no value, else ''."""
    k = getattr(d, "n_failed", 0) or 0
    return f" ({k} failed)" if k > 0 else ""


def fmt_n(d):
    """The sample size 'n', with ' (k failed)' when runs of the condition gave no value."""
    if d is None:
        return "0"
    return f"{d.n}{failed_suffix(d)}"


def fmt_dist(d, nd=3, scale=1.0, sig=None, n=False, unit=""):
    """'mean ± h' (h = half-width of the 95 % CI) for a seeded sample, 'mean' for a single run,
    'n/a' when empty; `unit` (e.g. ' %') follows the number. n=True appends ' (n = k)' for
    samples of more than one. ' (k failed)' is appended whenever runs of the condition gave no
    value (stats.Dist.n_failed)."""
    if d is None:
        return "n/a"
    if d.n == 0:
        return "n/a" + failed_suffix(d)
    if d.n == 1:
        return _num(d.mean * scale, nd, sig) + unit + failed_suffix(d)
    s = f"{_num(d.mean * scale, nd, sig)} ± {_num(d.half_width * abs(scale), nd, sig)}{unit}"
    return s + (f" (n = {d.n})" if n else "") + failed_suffix(d)


def fmt_ci(d, nd=3, scale=1.0, sig=None):
    """'[lo, hi]' of the 95 % CI, or '—' without one."""
    if d is None or not d.has_ci:
        return "—"
    lo, hi = sorted((d.lo * scale, d.hi * scale))
    return f"[{_num(lo, nd, sig)}, {_num(hi, nd, sig)}]"


def fmt_minmax(d, nd=3, scale=1.0, sig=None):
    if d is None or d.n == 0:
        return "n/a"
    lo, hi = sorted((d.min * scale, d.max * scale))
    return _num(lo, nd, sig) if d.n == 1 else f"{_num(lo, nd, sig)}–{_num(hi, nd, sig)}"


def fmt_factor(ours, paper):
    """'×k' of ours over the paper's value, '—' when the paper's is 0 or either is missing."""
    r = div(ours, paper)
    if not isnum(r):
        return "—"
    return f"×{g(r, 3)}" if r < 1000 else f"×{r:.3g}".replace("e+0", "e").replace("e+", "e")


def fmt_setting(v):
    """A configuration value as the scenario files write it (TOML): true/false, "text",
    numbers in their shortest form (1e-8, 0.01, 1025), arrays in brackets."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return '"' + v.replace("\\", "\\\\").replace('"', '\\"') + '"'
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if v.is_integer() and abs(v) < 1e15:
            return str(int(v))
        return re.sub(r"e([-+])0*(\d)", lambda m: "e" + m.group(1).replace("+", "") + m.group(2),
                      repr(v))
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(fmt_setting(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{k} = {fmt_setting(x)}" for k, x in v.items()) + "}"
    return str(v)


def f_dash(x, nd=3):
    """Fixed-point number, '—' when missing or not finite."""
    return f"{float(x):.{nd}f}" if x is not None and math.isfinite(float(x)) else "—"


def g_dash(x, sig=3):
    """Significant-digit number, '—' when missing or not finite."""
    return f"{float(x):.{sig}g}" if x is not None and math.isfinite(float(x)) else "—"


def fmt_interval(est, nd=3):
    """An inference.Estimate as "est [lo, hi]", "est (deterministic)" without an interval, or
    "n/a" for None."""
    if est is None:
        return "n/a"
    if est.deterministic or not est.has_ci:
        return f"{f(est.estimate, nd)} (deterministic)"
    return f"{f(est.estimate, nd)} [{f(est.lo, nd)}, {f(est.hi, nd)}]"
