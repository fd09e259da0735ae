# SPDX-License-Identifier: Apache-2.0
"""scorecard: the reproduction scorecard as data. Every comparison with a number the paper
prints is one Row (rows.py): reference, row, quantity, reading, the paper's value, ours (mean,
CI, n), the rule that decides its verdict, the verdict, and a cause that is a measured
attribution or a named hypothesis. The rows are written to OUT/scorecard.json, and the
markdown scorecard is rendered from them (render.py).
- cases.py: Tables XI and XII and the text's savings, in both readings of docs/MODEL.md §8;
- fidelity.py: Table XIII and the effects it prints (density error, variable coefficients);
- claims.py: the statements read from the text and figures, and the analytic limits;
- build.py: the Scorecard that runs them and writes scorecard.json."""
