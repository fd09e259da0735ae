# SPDX-License-Identifier: Apache-2.0
"""num: the finite-number test and the safe division every module uses."""
import math

import numpy as np


def isnum(x):
    """A finite real number (not a bool)."""
    return x is not None and not isinstance(x, bool) and \
        isinstance(x, (int, float, np.floating, np.integer)) and math.isfinite(float(x))


def div(a, b):
    """a / b as a float; NaN when either is not a number or b is 0."""
    if not isnum(a) or not isnum(b) or float(b) == 0.0:
        return float("nan")
    return float(a) / float(b)
