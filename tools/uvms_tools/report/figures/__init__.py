# SPDX-License-Identifier: Apache-2.0
"""Figures: matplotlib only. Each function draws one figure from prepared arrays and
distributions, saves it through figures.common.Figures and returns its path relative to the
report."""
