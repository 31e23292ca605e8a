"""Whether a joint vector fits joint limits, written independently of the core's fit_limits: the
closed forms' within_limits mask is checked against it."""

import math


def turns_fit(row, lo, hi, prismatic=None):
    """Whether whole turns (revolute joints only) bring every joint of ``row`` within [lo, hi]:
    for each joint the least shift to at least ``lo``, then compared with ``hi``. (The core allows
    1e-12 of rounding at a limit: a row it marks outside must not fit here.)"""
    prismatic = prismatic or [False] * len(row)
    for v, low, high, slides in zip(row, lo, hi, prismatic):
        if low <= v <= high:
            continue
        if slides or not math.isfinite(low):
            return False
        if not v + 2 * math.pi * math.ceil((low - v) / (2 * math.pi)) <= high:
            return False
    return True
