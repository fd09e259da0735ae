"""report_fmt: number and table formatting shared by tools/report.py and its section modules.
Standard library and numpy only."""
import math

import numpy as np

import stats


def isnum(x):
    return x is not None and not isinstance(x, bool) and \
        isinstance(x, (int, float, np.floating, np.integer)) and math.isfinite(float(x))


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


def div(a, b):
    if not isnum(a) or not isnum(b) or float(b) == 0.0:
        return float("nan")
    return float(a) / float(b)


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


def fmt_k_of_n(paired):
    """'k of n' seeds with ratio < 1."""
    if paired is None or paired.n == 0:
        return "n/a"
    return f"{paired.n_below_1} of {paired.n}"


def dist_of(values):
    return stats.describe(values)


# Scenario keys and case names shared by the report modules (docs/SCENARIOS.md, SPEC §9).
CASES = ["I", "II", "III", "IV", "V", "VI", "VII", "VIII"]
VEH, BARY = "IV", "VII"  # vehicle and barycenter stabilization (SPEC §9 Table X)
# Cases that differ only in the position reference (same attitude, feedforward and feedback
# switches of Table X): (vehicle, barycenter).
MATCHED_PAIRS = [("VI", "III"), ("IV", "VII"), ("V", "VIII")]
FEEDBACK_PAIRS = [("IV", "VII"), ("V", "VIII")]
KEY_CASE = "control.case"
KEY_UNSTEADY = "environment.unsteady_flow.enabled"
KEY_DENSITY = "environment.density_error"
KEY_AOA = "environment.angle_of_attack"
KEY_VARC = "environment.variable_coefficients"
KEY_PAYLOAD = "payload.mass_kg"
KEY_DIST = "trajectory.cartesian.distance_m"
KEY_TRAJ_DUR = "trajectory.duration_s"
KEY_SEED = "run.seed"
# Values of keys a run does not override (docs/SCENARIOS.md defaults), for selecting runs.
KEY_DEFAULTS = {KEY_UNSTEADY: False, KEY_DENSITY: False, KEY_AOA: True, KEY_VARC: False,
                KEY_PAYLOAD: 10.0}
E_EL, E_P, E_MAN, ERR = ("thruster_energy_J", "propulsive_energy_J", "manipulator_energy_J",
                         "mean_ee_error_m")
