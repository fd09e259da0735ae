# SPDX-License-Identifier: Apache-2.0
"""scorecard: the reproduction scorecard at the top of the report — the paper's printed
numbers (analyses.paper) beside this project's, with a verdict per row (stats.RULE_TEXT):
Tables XI and XII and the text's savings (scorecard_cases), Table XIII and the analytic model
(scorecard_models), the statements of the text and figures (scorecard_statements)."""
from ..analyses import stats
from ..analyses.paper import PAPER
from .scorecard_cases import case_table, savings
from .scorecard_models import analytic_rows, table_xiii
from .scorecard_statements import statements
from .tally import Tally


class Scorecard(Tally):
    """Rows of the scorecard, built from a context.Report after its sections ran; keeps
    saving_results (the text's savings, for the headline)."""

    def __init__(self, rep):
        super().__init__()
        self.rep = rep
        self.saving_results = {}

    def build(self):
        md = ["## Reproduction scorecard", "",
              f"The paper's printed numbers ({PAPER}; constants cited by table, figure or text "
              "in tools/uvms_report/analyses/paper.py) beside this project's results from the "
              "runs below. "
              f"Drive: {self.rep.drive_text()} (docs/MODEL.md §5).", "", stats.RULE_TEXT, ""]
        body = (case_table(self, "XI") + case_table(self, "XII") + savings(self)
                + table_xiii(self) + statements(self) + analytic_rows(self))
        md += [self.tally_line() + " Absolute electrical energies (E_el) differ by design of "
               "the motor model (see *Energies* below); compare the ratio rows.", ""]
        return md + body
