# SPDX-License-Identifier: MIT
"""Shared fixtures of the Python tests (run by ctest: tests/CMakeLists.txt
sets PYTHONPATH to build/python and TUMBLE_BINARY, TUMBLE_BUILD_DIR,
TUMBLE_SOURCE_DIR, CMAKE_COMMAND)."""

import os
import pathlib

import pytest

import tumble

SOURCE = pathlib.Path(os.environ.get("TUMBLE_SOURCE_DIR", pathlib.Path(__file__).parents[2]))


@pytest.fixture(scope="session")
def tumble_binary():
    return os.environ.get("TUMBLE_BINARY", str(SOURCE / "build" / "tumble"))


# A drum small enough to run in seconds: 6 grains in a drum 3 cm long and
# across, turned 0.4 revolutions at 20 rad/s, 10 samples and 10 snapshots per
# revolution.
TINY_DRUM = dict(mode="self", grains=6, length=0.03, diameter=0.03, omega=20.0, revolutions=0.4, samples=10,
                 snapshots=10)


@pytest.fixture(scope="session")
def tiny_drum(tmp_path_factory):
    """A finished tiny drum run: (directory, the samples its callback saw)."""
    samples = []
    directory = tumble.run_drum(out=tmp_path_factory.mktemp("drum") / "run", on_sample=samples.append, **TINY_DRUM)
    return directory, samples


@pytest.fixture(scope="session")
def short_drum(tmp_path_factory):
    """A finished drum run of the tiny drum turned 2.5 revolutions: long
    enough for a block of the grains' MSD with the start-up left in."""
    return tumble.run_drum(out=tmp_path_factory.mktemp("drum") / "short", **dict(TINY_DRUM, revolutions=2.5))
