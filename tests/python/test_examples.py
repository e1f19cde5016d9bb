# SPDX-License-Identifier: MIT
"""The examples of examples/python run as written, and the meshes of the
examples are what examples/meshes/make_meshes.py writes."""

import os
import subprocess
import sys

from conftest import SOURCE

EXAMPLES = SOURCE / "examples" / "python"


def run(script, *arguments, cwd):
    done = subprocess.run([sys.executable, str(EXAMPLES / script), *arguments], cwd=cwd, env=os.environ,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_scenario_steps(tmp_path):
    out = run("scenario_steps.py", cwd=tmp_path)
    assert "stopped after" in out and "contacts" in out


def test_drum_callback_then_read_run(tmp_path):
    out = run("drum_callback.py", "drum", cwd=tmp_path)
    assert "N = 0.000" in out and (tmp_path / "drum" / "summary.json").is_file()
    out = run("read_run.py", "drum", cwd=tmp_path)
    assert "Hogg D" in out and "MSD D" in out


def test_example_meshes_are_what_make_meshes_writes(tmp_path):
    meshes = SOURCE / "examples" / "meshes"
    done = subprocess.run([sys.executable, str(meshes / "make_meshes.py"), "--out", str(tmp_path)], capture_output=True,
                          text=True)
    assert done.returncode == 0, done.stderr
    for name in ("chute.stl", "v_blender.stl"):
        assert (tmp_path / name).read_bytes() == (meshes / name).read_bytes(), name
