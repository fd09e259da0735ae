# SPDX-License-Identifier: Apache-2.0
"""Analyses: pure functions on arrays and dicts (no files, no plotting), each tested on
synthetic data with known answers (tests/tools/test_report_analyses.py,
test_report_stats.py, test_report_inference.py)."""
