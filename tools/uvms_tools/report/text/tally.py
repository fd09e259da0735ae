# SPDX-License-Identifier: Apache-2.0
"""tally: the classes of scorecard rows that are shown but kept out of the tally
(scorecard/rows.py Row.excluded), with what the tally line calls them and why."""
TRIVIAL = "trivial"                      # case I: no control, no thrust, zero energy
TRANSCRIPTION = "transcription check"    # [89]'s arithmetic: tests the transcription
EXCLUDED_LABEL = {TRIVIAL: "trivial case-I zeros",
                  TRANSCRIPTION: "arithmetic checks of [89]"}
EXCLUDED_WHY = {
    TRIVIAL: "case I's energy and energy ratio in both tables: no control, no thrust, zero "
             "in the paper and in ours by construction",
    TRANSCRIPTION: "the payload and travel limits recomputed from [89]'s formula test the "
                   "transcription, not the physics",
}
