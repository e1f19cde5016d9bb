# SPDX-License-Identifier: MIT
"""The README's two commands, with cmake, ctest and the program stood in by
scripts that note how they were called: the main job (scripts/run.sh)
builds the tumble program only and says how long the first build takes;
the test command (scripts/test.sh) then builds everything else and says so."""

import os
import pathlib
import shutil
import stat
import subprocess

import pytest

SOURCE = pathlib.Path(os.environ.get("TUMBLE_SOURCE_DIR", pathlib.Path(__file__).parents[2]))

# cmake --build makes what a real build would leave: build/tumble for any
# build, build/tests/unit_tests for a build of everything.
FAKE_CMAKE = """#!/bin/sh
echo "cmake $*" >> "$CALLS"
case " $* " in
  *" --build "*" --target "*) mkdir -p build; printf '#!/bin/sh\\necho "tumble $*" >> "$CALLS"\\n' > build/tumble;
                              chmod +x build/tumble ;;
  *" --build "*) mkdir -p build/tests; cp "$0" build/tumble; : > build/tests/unit_tests; chmod +x build/tests/unit_tests ;;
  *) mkdir -p build; : > build/CMakeCache.txt ;;
esac
"""
FAKE_CTEST = """#!/bin/sh
echo "ctest $*" >> "$CALLS"
"""


@pytest.fixture
def tree(tmp_path):
    """A copy of the scripts in an empty tree, cmake and ctest stood in for."""
    shutil.copytree(SOURCE / "scripts", tmp_path / "tree" / "scripts")
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    for name, text in (("cmake", FAKE_CMAKE), ("ctest", FAKE_CTEST)):
        (bin_dir / name).write_text(text)
        (bin_dir / name).chmod((bin_dir / name).stat().st_mode | stat.S_IXUSR)
    env = dict(os.environ, PATH=f"{bin_dir}:{os.environ['PATH']}", CALLS=str(tmp_path / "calls"))
    return tmp_path / "tree", env, tmp_path / "calls"


def run(tree, env, script):
    done = subprocess.run(["bash", str(tree / "scripts" / script)], cwd=tree, env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stderr


def test_run_builds_the_program_only_then_test_builds_the_rest(tree):
    root, env, calls = tree
    said = run(root, env, "run.sh")
    builds = [line for line in calls.read_text().splitlines() if "--build" in line]
    assert builds == [builds[0]] and "--target tumble" in builds[0], builds
    # One line per long phase, with an estimate measured on 2 cores.
    assert "tumble: building tumble in build/ (the first time: about " in said and "minutes on 2" in said, said
    assert "tumble drum --force" in calls.read_text()
    calls.write_text("")
    said = run(root, env, "test.sh")
    builds = [line for line in calls.read_text().splitlines() if "--build" in line]
    assert len(builds) == 1 and "--target" not in builds[0], builds
    assert "building the Python module and the tests in build/ (the first time: about " in said, said
    assert "ctest" in calls.read_text()
    # Built: no estimate again.
    calls.write_text("")
    assert "the first time" not in run(root, env, "run.sh")
