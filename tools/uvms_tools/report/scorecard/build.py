# SPDX-License-Identifier: Apache-2.0
"""build: the Scorecard of one report: its rows (cases, fidelity, claims), the multiplicity
adjustment, scorecard.json, and the tallies per reading."""
import json
import math
import os

from ..analyses import inference, stats
from . import cases, claims, fidelity, flow
from .rows import BOTH, READINGS

VERDICTS = (stats.REPRODUCED, stats.SAME_DIRECTION, stats.DIFFERS, stats.NOT_MEASURED)


class Scorecard:
    """rows: every scorecard row (rows.Row), after build()."""

    def __init__(self, rep):
        self.rep = rep
        self.rows = []
        self.sweep = None

    def build(self):
        rep = self.rep
        self.sweep = flow.load(rep)
        if self.sweep is not None:
            self.sweep.mechanism = flow.mechanism(rep, self.sweep)
        self.rows = (cases.case_rows(rep, "XI", self.sweep) + cases.case_rows(rep, "XII", self.sweep)
                     + cases.accuracy_rows(rep)
                     + cases.saving_rows(rep, self.sweep) + fidelity.table_rows(rep)
                     + fidelity.effect_rows(rep) + claims.statement_rows(rep)
                     + claims.analytic_rows(rep))
        self._holm()
        return self.rows

    def _holm(self):
        """Holm across the seed-dependent verdicts (rows whose estimate has a p-value)."""
        fam = [r for r in self.rows if r.ours is not None and not r.ours.deterministic
               and math.isfinite(r.ours.p) and not r.excluded]
        adj, _ = inference.holm([r.ours.p for r in fam])
        for r, p in zip(fam, adj):
            r.p_holm = p

    def tally(self, reading):
        """{verdict: count} over the tallied rows of one reading (rows of both readings, the
        same runs, count in each)."""
        out = {v: 0 for v in VERDICTS}
        for r in self.rows:
            if not r.excluded and r.reading in (reading, BOTH):
                out[r.verdict] = out.get(r.verdict, 0) + 1
        return out

    def reading_for(self, reference):
        """The reading that reproduces more of a reference's tallied rows (None on a tie),
        with {reading: (reproduced, total)}."""
        score = {}
        for rd in READINGS:
            rs = [r for r in self.rows if r.reference == reference and not r.excluded
                  and r.reading in (rd, BOTH)]
            score[rd] = (sum(r.verdict == stats.REPRODUCED for r in rs), len(rs))
        best = max(READINGS, key=lambda rd: score[rd][0])
        tie = len({score[rd][0] for rd in READINGS}) == 1
        return (None if tie else best), score

    def write_json(self, out_dir):
        path = os.path.join(out_dir, "scorecard.json")
        doc = {"paper": "Lynch & Ellery, IEEE J. Oceanic Eng. 39(3), 2014, "
                        "DOI 10.1109/JOE.2013.2271390",
               "energy": "propulsive energy E_p (docs/MODEL.md §5) for every energy verdict",
               "multiplicity": inference.MULTIPLICITY_POLICY,
               "tally": {rd: self.tally(rd) for rd in READINGS},
               "rows": [r.to_json() for r in self.rows]}
        with open(path, "w") as fh:
            json.dump(doc, fh, indent=1, ensure_ascii=False)
            fh.write("\n")
        return path
