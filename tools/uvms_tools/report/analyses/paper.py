# SPDX-License-Identifier: Apache-2.0
"""paper: the paper's printed numbers (cited constants), the criteria of the scorecard's
statement rows, and the rules that read a paper table or a trend over payloads.

Every PAPER_* constant below is transcribed from Lynch & Ellery, "Efficient Control of an
AUV-Manipulator System: An Application for the Exploration of Europa", IEEE J. Oceanic Eng.
39(3), 2014, DOI 10.1109/JOE.2013.2271390, and cited by table, figure or text. They are the
paper's results, set beside this project's; nothing here is tuned toward them and every "ours"
value comes from the runs (or from tools/analytic.py with the runs' logged parameters).
The verdict rule is stats.scorecard_verdict / stats.RULE_TEXT.
"""
from . import stats

PAPER = ("Lynch & Ellery, IEEE J. Oceanic Eng. 39(3), 2014, "
         "DOI 10.1109/JOE.2013.2271390")
PAPER_FULL = ("Lynch & Ellery, \"Efficient Control of an AUV-Manipulator System: An "
              "Application for the Exploration of Europa\", IEEE Journal of Oceanic Engineering "
              "39(3), 2014, DOI "
              "[10.1109/JOE.2013.2271390](https://doi.org/10.1109/JOE.2013.2271390)")

# Table XI: stagnant flow, no density error, 60 s, 10 kg payload.
# case: (mean EE error [mm], energy [J])
PAPER_TABLE_XI = {
    "I": (78.01, 0.0), "II": (24.35, 0.1807), "III": (1.85, 0.1930), "IV": (0.12, 0.3391),
    "V": (2.93, 0.3523), "VI": (1.51, 0.3326), "VII": (0.13, 0.1946), "VIII": (0.91, 0.1932),
}
# Table XII: unsteady flow and density error (1025 actual, 1000 kg/m³ modeled).
PAPER_TABLE_XII = {
    "I": (124.90, 0.0), "II": (79.03, 0.1839), "III": (95.90, 0.1933), "IV": (3.32, 0.6194),
    "V": (5.65, 0.6087), "VI": (108.92, 0.3259), "VII": (3.16, 0.3871), "VIII": (3.70, 0.3760),
}
# Text (with Table XI): barycenter cases "approximately 43.3 % less energy".
PAPER_SAVING_STAGNANT = 0.433
# Text (with Table XII): among the cases with feedback, barycenter stabilization "consumed on
# average 38.5 % less energy".
PAPER_SAVING_UNSTEADY = 0.385
# Table XIII: model fidelity, (unsteady flow, density error, angle of attack, variable CD & CM,
# vehicle energy [J], barycenter energy [J], ratio); added mass always on.
PAPER_TABLE_XIII = [
    (True, False, False, False, 0.5170, 0.3461, 0.6695),
    (True, True, False, False, 0.5223, 0.3503, 0.6707),
    (True, True, True, False, 0.5030, 0.3381, 0.6721),
    (True, True, True, True, 0.4569, 0.2807, 0.6144),
    (False, False, False, False, 0.3331, 0.1914, 0.5746),
    (False, True, False, False, 0.3365, 0.1936, 0.5752),
    (False, True, True, False, 0.3246, 0.1838, 0.5661),
    (False, True, True, True, 0.3187, 0.1866, 0.5854),
]
# Fig. 25 (travel 0.1–1 m, density error and variable coefficients, no flow): the energy ratio
# "remaining within approximately 53 %–59 %".
PAPER_FIG25_RATIO = (0.53, 0.59)
# Fig. 26 (duration 6–120 s): ratio depends on duration below ~30 s, negligibly above, and
# "remains below 100 %".
PAPER_FIG26_FLAT_FROM_S = 30.0
# Analytic model [87–89]: barycenter stabilization preferred for any payload below 144.3 kg at
# the arm's maximum travel 1.82 m, and for any travel below 0.994 m as η → 1.
PAPER_PAYLOAD_LIMIT_KG = 144.3
PAPER_PAYLOAD_LIMIT_TRAVEL_M = 1.82
PAPER_TRAVEL_LIMIT_M = 0.994

# Criteria of the statement rows (stated in the rows).
DENSITY_SMALL = 0.03     # "about 1 %": every |E_B/E_A − 1| at most 3 %
UNSTEADY_MARKED = 1.10   # "markedly": E_C/E_B above 1.10 (CI lower bound when seeded)
FLAT_SPREAD = 0.05       # "flat": max − min of the ratio at most 0.05
MANIP_EQUAL = 0.10       # "about equal": |E_man(VII)/E_man(IV) − 1| at most 10 %
THR_MARKED = 0.90        # "falls markedly": E_thr(VII)/E_thr(IV) at most 0.90
TRACK_SMALL = 0.10       # "small deviations": RMS|F_des − F_prod| / RMS|F_des| at most 10 %


def paper_saving(table, pairs):
    """1 − Σ E(barycenter) / Σ E(vehicle) over `pairs` of a paper table."""
    return 1.0 - sum(table[b][1] for _, b in pairs) / sum(table[v][1] for v, _ in pairs)


def payload_trend(series):
    """Trend of one series over payloads: series = [{seed: value}] in payload order.
    Steps and the overall change (last − first) are paired per seed (stats.paired_difference)
    and read by stats.direction: +1 / −1 only when the 95 % CI excludes 0 (one deterministic
    value: its sign), 0 = no significant change. Returns dict(diff, overall, rise, mono):
    rise = the last payload significantly higher than the first; mono = no step significantly
    down and, for a seeded series, rise (a deterministic series only needs no step down)."""
    steps = [stats.direction(stats.paired_difference(b, a))
             for a, b in zip(series, series[1:])]
    diff = stats.paired_difference(series[-1], series[0])
    overall = stats.direction(diff)
    seeded = any(len(s) > 1 for s in series)
    no_down = all(d is not None and d >= 0 for d in steps)
    rise = overall == 1
    return dict(diff=diff, overall=overall, rise=rise,
                mono=no_down and (rise if seeded else True))
