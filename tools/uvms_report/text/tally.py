# SPDX-License-Identifier: Apache-2.0
"""tally: the scorecard's count of verdicts. Substantive verdicts are tallied (and shown in
bold unless reproduced); comparisons of the classes below are shown in their rows but kept out
of the tally, and the tally line names them and why."""
from ..analyses import stats

MAGNITUDE_ONLY = "magnitude only"        # E_p beside the paper's joules: a different quantity
TRIVIAL = "trivial"                      # case I: no control, no thrust, zero energy
TRANSCRIPTION = "transcription check"    # [89]'s arithmetic: tests the transcription
EXCLUDED_LABEL = {MAGNITUDE_ONLY: "E_p comparisons, magnitude only",
                  TRIVIAL: "trivial case-I zeros",
                  TRANSCRIPTION: "arithmetic checks of [89]"}
EXCLUDED_WHY = {
    MAGNITUDE_ONLY: "the propulsive energy is a different quantity from the paper's energy, "
                    "see *Energies*: its factor to the paper's joules is shown, without a "
                    "verdict",
    TRIVIAL: "case I's energy and energy ratio in both tables: no control, no thrust, zero "
             "in the paper and in ours by construction",
    TRANSCRIPTION: "the payload and travel limits recomputed from [89]'s formula test the "
                   "transcription, not the physics",
}


class Tally:
    def __init__(self):
        self.counts = {}     # tallied (substantive) verdicts
        self.excluded = {}   # class -> number of comparisons kept out of the tally

    def v(self, verdict):
        """A substantive verdict: tallied, and shown in bold unless reproduced."""
        self.counts[verdict] = self.counts.get(verdict, 0) + 1
        return verdict if verdict == stats.REPRODUCED else f"**{verdict}**"

    def x(self, cls, shown):
        """A comparison kept out of the tally (class `cls`, see EXCLUDED_WHY): shown as
        `shown` in its row, counted only in self.excluded."""
        self.excluded[cls] = self.excluded.get(cls, 0) + 1
        return shown

    def tally_line(self):
        """The tally over the substantive verdicts, with what is excluded and why."""
        total = sum(self.counts.values())
        summ = ", ".join(f"{self.counts.get(k, 0)} {k}" for k in
                         (stats.REPRODUCED, stats.SAME_DIRECTION, stats.DIFFERS,
                          stats.NOT_MEASURED) if self.counts.get(k))
        excl = [f"{n} {EXCLUDED_LABEL[cls]} ({EXCLUDED_WHY[cls]})"
                for cls, n in self.excluded.items() if n]
        return (f"**Tally over {total} substantive verdicts:** {summ or 'none'}."
                + (" Not tallied: " + "; ".join(excl) + "." if excl else ""))
