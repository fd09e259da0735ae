# SPDX-License-Identifier: Apache-2.0
"""causes: the scorecard's standard wording for the cause of a difference."""
CAUSE_ENERGY = "magnitude: friction-dominated motor (docs/MODEL.md §5; see Energies)"
CAUSE_FLOW = ("flow amplitude and harmonics not printed in the paper (docs/MODEL.md §6.1 "
              "defaults used)")
OPEN = "open"


def cause_text(parts):
    """The non-empty causes, each once, joined; '—' when there is none."""
    parts = [p for p in parts if p]
    return "; ".join(dict.fromkeys(parts)) if parts else "—"
