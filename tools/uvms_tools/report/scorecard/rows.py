# SPDX-License-Identifier: Apache-2.0
"""rows: one scorecard row, its verdict rule and its JSON form.

A row's verdict is never typed in: make() computes it from the row's own data with
evaluate(), so that scorecard.json can be re-checked (tests mutate a number and see the verdict
flip). Rules (analyses/verdicts.py, analyses/stats.py):
  magnitude    an absolute quantity (mm, J) within a factor tol_factor, sign first;
  directional  a change (ref 0) or ratio (ref 1) the paper states, sign first, then within tol
               or the paper's value inside our CI;
  statement    a statement with a criterion evaluated elsewhere: holds True / False / "partly".
Rows that are shown but not tallied carry `excluded` (text.tally's classes)."""
import math
from dataclasses import dataclass, field

from ..analyses import stats, verdicts
from ..analyses.inference import Estimate
from ..num import isnum

READINGS = ("same task", "same motion")
BOTH = "both"   # the same runs in both readings (vehicle-reference cases, other experiments)


def estimate_of(x):
    """An inference.Estimate from a number (deterministic), a stats.Dist or an Estimate."""
    if x is None:
        return None
    if isinstance(x, Estimate):
        return x
    if isinstance(x, stats.Dist):
        if x.n == 0:
            return None
        det = x.deterministic
        lo, hi = (math.nan, math.nan) if det else x.ci
        return Estimate(float(x.mean), lo, hi, x.n, "mean, Student t", math.nan,
                        deterministic=det)
    return Estimate(float(x), math.nan, math.nan, 1, "one run", math.nan, deterministic=True)


def _json_num(v):
    return float(v) if isnum(v) else None


@dataclass
class Row:
    reference: str            # "Table XI", "Text", "Figs. 14–15", ...
    row: str                  # "case VII", "stagnant saving", ...
    quantity: str             # "mean EE error ε [mm]", "E_p/E_p(IV)", ...
    reading: str              # READINGS or BOTH
    paper: float              # the paper's printed value (None for a statement)
    ours: Estimate            # None: not measured
    rule: dict                # {"kind": ..., parameters}
    verdict: str = ""
    cause: str = "—"
    depends_on: list = field(default_factory=list)   # [{"parameter", "note"}]
    excluded: str = ""        # text.tally class, or "" (tallied)
    unit: str = ""
    ours_text: str = ""       # for statements: what was measured, in words
    p_holm: float = math.nan

    def to_json(self):
        o = self.ours
        ours = None if o is None else {
            "mean": _json_num(o.estimate), "lo": _json_num(o.lo), "hi": _json_num(o.hi),
            "n": int(o.n), "method": o.method, "p": _json_num(o.p),
            "deterministic": bool(o.deterministic)}
        return {"reference": self.reference, "row": self.row, "quantity": self.quantity,
                "reading": self.reading, "unit": self.unit, "paper": _json_num(self.paper),
                "ours": ours, "ours_text": self.ours_text, "rule": self.rule,
                "verdict": self.verdict, "tallied": not self.excluded,
                "excluded": self.excluded or None, "cause": self.cause,
                "depends_on": self.depends_on, "p_holm": _json_num(self.p_holm)}


def ours_from_json(o):
    """The Estimate of a row's JSON "ours" (None stays None)."""
    if o is None:
        return None
    nan = math.nan
    f = (lambda v: nan if v is None else float(v))
    return Estimate(f(o["mean"]), f(o["lo"]), f(o["hi"]), int(o["n"]), o["method"], f(o["p"]),
                    deterministic=bool(o["deterministic"]))


def evaluate(rule, paper, ours):
    """The verdict of a rule on the paper's value and ours (an Estimate or None)."""
    kind = rule["kind"]
    if kind == "statement":
        return stats.statement_verdict(rule.get("holds"))
    if ours is None or not isnum(ours.estimate):
        return stats.NOT_MEASURED
    if kind == "magnitude":
        return verdicts.magnitude_verdict(paper, ours, tol_factor=rule["tol_factor"])
    if kind == "directional":
        return verdicts.directional_verdict(paper, ours, tol=rule["tol"], ref=rule["ref"])
    raise ValueError(f"unknown rule kind {kind!r}")


def evaluate_json(obj):
    """Re-decide a row of scorecard.json from its own numbers."""
    return evaluate(obj["rule"], obj["paper"], ours_from_json(obj["ours"]))


def magnitude(tol_factor=stats.TOL_FACTOR):
    return {"kind": "magnitude", "tol_factor": tol_factor}


def directional(ref, tol=stats.TOL_RATIO):
    return {"kind": "directional", "ref": ref, "tol": tol}


def statement(holds, criterion):
    return {"kind": "statement", "holds": holds, "criterion": criterion}


def make(reference, row, quantity, reading, paper, ours, rule, cause="", **kw):
    """A Row whose verdict is evaluate()d from its data; cause "" → "—" when reproduced."""
    est = estimate_of(ours)
    r = Row(reference, row, quantity, reading, paper, est, rule, **kw)
    r.verdict = evaluate(rule, paper, est)
    r.cause = cause if cause and r.verdict != stats.REPRODUCED else "—"
    return r
