# SPDX-License-Identifier: MIT
"""The sweep of `tumble sweep` from Python: a tiny sweep run, then found
finished by a second call, and its table read with tumble.io."""

import pathlib

import pytest

import tumble

# Two points of 20 grains turned 0.1 revolutions (as the sweep test of
# tests/unit/test_sweep.cpp that resumes a point): a few seconds each.
TINY_SWEEP = """[sweep]
omega = [5.0]
modes = ["self"]
seeds = [1, 2]
revolutions = 0.1
grains_self = 20
grains_two_component = 20
snapshots_per_revolution = 0
"""


@pytest.fixture(scope="module")
def sweep_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("sweep") / "tiny.toml"
    path.write_text(TINY_SWEEP)
    return path


def test_run_sweep_then_all_points_finished(sweep_file, tumble_binary):
    out = sweep_file.parent / "out"
    names = ["self_omega5.000_seed1", "self_omega5.000_seed2"]
    assert [(p["name"], p["state"]) for p in tumble.sweep_points(sweep_file, out=out)] == [
        (name, "pending") for name in names]

    result = tumble.run_sweep(sweep_file, out=out, jobs=2, tumble_binary=tumble_binary)
    assert result == dict(directory=out, points=2, with_results=2, failed=0, exit_code=0)
    table = tumble.io.read_csv(out / "sweep.csv")
    assert list(table["seed"]) == [1, 2] and list(table["status"]) == ["finished"] * 2
    assert (table["omega"] == 5.0).all() and (table["grains"] == 20).all()
    points = tumble.sweep_points(sweep_file, out=out)
    assert [(p["name"], p["mode"], p["omega"], p["seed"], p["state"]) for p in points] == [
        (name, "self", 5.0, seed, "finished") for name, seed in zip(names, [1, 2])]

    # Found finished: nothing runs again (the points' logs are untouched).
    logs = {p["name"]: (p["directory"] / "log.txt").stat().st_mtime_ns for p in points}
    again = tumble.run_sweep(sweep_file, out=out)  # the program that find_tumble_binary finds
    assert again == result
    assert {p["name"]: (p["directory"] / "log.txt").stat().st_mtime_ns for p in points} == logs
    assert len(tumble.io.read_csv(out / "sweep_summary.csv")) == 1


def test_bad_sweep_file_is_refused_before_any_point(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(TINY_SWEEP.replace("omega = [5.0]", "omega = [-5.0]"))
    with pytest.raises(tumble.Error, match=r"sweep\.omega\[0\]: must be > 0"):
        tumble.run_sweep(path, out=tmp_path / "out", tumble_binary="/nonexistent")
    assert not (tmp_path / "out").exists()


def test_build_tree_module_runs_the_build_tree_program(monkeypatch, tumble_binary):
    monkeypatch.delenv("TUMBLE_BINARY", raising=False)
    assert tumble.find_tumble_binary() == pathlib.Path(tumble_binary).resolve()


def test_missing_tumble_binary_is_named(monkeypatch):
    monkeypatch.setenv("TUMBLE_BINARY", "/nonexistent/tumble")
    with pytest.raises(FileNotFoundError, match="TUMBLE_BINARY: /nonexistent/tumble"):
        tumble.find_tumble_binary()
