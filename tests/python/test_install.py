# SPDX-License-Identifier: MIT
"""cmake --install: the installed tumble runs a drum and draws its figures
from another directory, and the installed module imports."""

import os
import pathlib
import subprocess
import sys

import pytest

from conftest import SOURCE


@pytest.fixture(scope="module")
def prefix(tmp_path_factory):
    prefix = tmp_path_factory.mktemp("prefix")
    build = os.environ.get("TUMBLE_BUILD_DIR", str(SOURCE / "build"))
    subprocess.run([os.environ.get("CMAKE_COMMAND", "cmake"), "--install", build, "--prefix", str(prefix)],
                   check=True, stdout=subprocess.DEVNULL)
    return prefix


def test_installed_files(prefix):
    assert (prefix / "bin" / "tumble").is_file()
    assert (prefix / "share" / "tumble" / "tools" / "plot_drum.py").is_file()
    assert (prefix / "share" / "tumble" / "examples" / "python" / "drum_callback.py").is_file()


def test_installed_drum_and_plot_from_elsewhere(prefix, tmp_path):
    tumble = str(prefix / "bin" / "tumble")
    subprocess.run([tumble, "drum", "-q", "--mode", "self", "--grains", "6", "--length", "0.03", "--diameter", "0.03",
                    "--omega", "20", "--revolutions", "0.4", "--no-plot", "--out", "run"], cwd=tmp_path, check=True)
    assert (tmp_path / "run" / "summary.json").is_file()
    subprocess.run([tumble, "plot", "run", "--out", "figures"], cwd=tmp_path, check=True, stdout=subprocess.DEVNULL)
    assert (tmp_path / "figures" / "fig_z.png").is_file()


def test_installed_plot_runs_the_installed_script(prefix, tmp_path):
    """Not the source tree's: an installed script that only leaves a mark."""
    script = prefix / "share" / "tumble" / "tools" / "plot_drum.py"
    original = script.read_text()
    try:
        script.write_text("import pathlib, sys\npathlib.Path('mark').write_text(' '.join(sys.argv[1:]))\n")
        # tumble plot refuses a directory that is not a drum run's before it starts the script.
        (tmp_path / "some-run").mkdir()
        (tmp_path / "some-run" / "drum_run.toml").write_text("")
        subprocess.run([str(prefix / "bin" / "tumble"), "plot", "some-run"], cwd=tmp_path, check=True)
        assert (tmp_path / "mark").read_text() == "run some-run"
    finally:
        script.write_text(original)


def installed_python(prefix, cwd, code):
    """What `code` prints with the installed module first on the path (and
    no TUMBLE_BINARY), and where that module is."""
    site = prefix / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "dist-packages"
    env = {name: value for name, value in os.environ.items() if name != "TUMBLE_BINARY"}
    printed = subprocess.run([sys.executable, "-c", code], cwd=cwd, env={**env, "PYTHONPATH": str(site)},
                             check=True, capture_output=True, text=True).stdout
    return printed.strip(), site


def test_installed_module_imports(prefix, tmp_path):
    found, site = installed_python(prefix, tmp_path, "import tumble; print(tumble.__file__)")
    assert pathlib.Path(found).is_relative_to(site)


def test_installed_module_runs_the_installed_program(prefix, tmp_path):
    """run_sweep's points: the tumble installed beside the module, not the build tree's."""
    found, _ = installed_python(prefix, tmp_path, "import tumble; print(tumble.find_tumble_binary())")
    assert pathlib.Path(found) == (prefix / "bin" / "tumble").resolve()
