# SPDX-License-Identifier: MIT
"""The estimator of the benchmarks' paired ratios (bench/peers/peerlib.py,
ratio_interval: the geometric mean of round-by-round ratios with a 95 % t
interval), checked against numbers worked out by hand and, on synthetic
rounds with a known true ratio, for its coverage."""

import math
import random
import sys

import pytest
from conftest import SOURCE

sys.path.insert(0, str(SOURCE / "bench" / "peers"))
import peerlib  # noqa: E402


def test_two_ratios_give_their_geometric_mean_and_the_t_interval_of_one_degree_of_freedom():
    # ln 2 and ln 8: mean ln 4, standard deviation ln 4 / sqrt 2, so the
    # half width is t(0.975, 1) = 12.706 times ln 4 / 2.
    mean, low, high = peerlib.ratio_interval([2.0, 8.0])
    half = 12.706 * math.log(4.0) / 2.0
    assert mean == pytest.approx(4.0, rel=1e-12)
    assert low == pytest.approx(4.0 * math.exp(-half), rel=1e-12)
    assert high == pytest.approx(4.0 * math.exp(half), rel=1e-12)


def test_one_ratio_has_no_interval():
    assert peerlib.ratio_interval([3.0]) == (pytest.approx(3.0, rel=1e-12), None, None)
    assert peerlib.fmt_interval([3.0]) == "3.000"


def test_the_interval_covers_a_known_ratio_95_times_in_100():
    # 4,000 synthetic sets of 5 rounds: each round's ratio is the true 3.0
    # times a host factor, log-normal with a 10 % spread (as noisy as this
    # project's hosts). A 95 % interval must hold 3.0 in 95 % of the sets;
    # the binomial spread of that count over 4,000 sets is 0.34 %, so 93.9
    # to 96.1 % (3.2 of them) is the band a correct interval falls in.
    rng = random.Random(27)
    sets, covered = 4000, 0
    for _ in range(sets):
        ratios = [3.0 * math.exp(rng.gauss(0.0, 0.1)) for _ in range(5)]
        _, low, high = peerlib.ratio_interval(ratios)
        covered += low <= 3.0 <= high
    assert 0.939 <= covered / sets <= 0.961
