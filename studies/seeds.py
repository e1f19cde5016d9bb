# SPDX-License-Identifier: MIT
"""Intervals over independent runs (seeds), shared by the studies' scripts.

A mean over n runs with its two-sided 95 % Student's t interval (n - 1
degrees of freedom): two runs give a spread, not an interval, and the
scripts say so where they print one."""

import math

# Student's t, two-sided 95 %, by degrees of freedom (1 to 15).
T95 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160, 2.145, 2.131]


def t95(dof):
    """Student's t quantile for a two-sided 95 % interval; above 15 degrees of freedom 1.96 + 2.4 / dof (within 0.5 %)."""
    return T95[dof - 1] if dof <= len(T95) else 1.960 + 2.4 / dof


def interval(values):
    """(mean, low, high) over the runs; low and high are nan for a single run."""
    n = len(values)
    m = sum(values) / n
    if n < 2:
        return m, float("nan"), float("nan")
    sd = math.sqrt(sum((v - m) ** 2 for v in values) / (n - 1))
    half = t95(n - 1) * sd / math.sqrt(n)
    return m, m - half, m + half
