# SPDX-License-Identifier: MIT
"""The Python functions refuse what the command line refuses, with its
check and its words, naming the key or the argument: a tumble.Error, never
a crash, and a state that goes wrong raises at the step that made it."""

import os
import re
import subprocess
import sys
import time
import tomllib

import pytest

import tumble
from conftest import TINY_DRUM
from test_simulation import SCENARIO


def python(code):
    """Runs `code` in a new interpreter that finds these tests' modules (a
    crash there fails this test rather than ending the whole pytest run)."""
    path = os.pathsep.join([os.path.dirname(__file__), os.environ.get("PYTHONPATH", "")])
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120,
                          env={**os.environ, "PYTHONPATH": path})


@pytest.mark.parametrize("build", [
    "d = tomllib.loads(SCENARIO); d['simulation']['itself'] = d; tumble.Scenario.from_dict(d)",
    "loop = []; loop.append(loop); tumble.Scenario.from_dict({**tomllib.loads(SCENARIO), 'domain': {'lo': loop}})",
    "deep = inner = {}\nfor _ in range(100000): inner['a'] = {}; inner = inner['a']\n"
    "tumble.Scenario.from_dict({**tomllib.loads(SCENARIO), 'simulation': deep})",
    "d = {'fill': {}}; d['fill']['itself'] = d; tumble.drum_settings(d)",
])
def test_a_dict_that_holds_itself_or_nests_too_deep_raises(build):
    code = ("import tomllib, tumble\nfrom test_simulation import SCENARIO\ntry:\n    " +
            build.replace("\n", "\n    ") + "\nexcept tumble.Error as e:\n    print(e)\n")
    r = python(code)
    assert r.returncode == 0, r.stderr[-2000:]
    assert "<dict>: " in r.stdout and "nested more than 32 deep (a dict or list that holds itself?)" in r.stdout, \
        r.stdout + r.stderr[-2000:]


def test_an_integer_beyond_64_bits_is_refused_naming_its_key():
    d = tomllib.loads(SCENARIO)
    d["particles"][0]["count"] = 2**70
    with pytest.raises(tumble.Error, match=r"<dict>: particles\[0\]\.count: '1180591620717411303424' is not "
                                           r"representable in 64 bits"):
        tumble.Scenario.from_dict(d)


def test_thread_counts_and_the_memory_limit_are_checked_as_on_the_command_line(tmp_path, tumble_binary):
    scenario = tumble.Scenario.from_toml(SCENARIO)
    with pytest.raises(tumble.Error, match=r"^threads: must be a whole number >= 0 \(0: every core\), got -1$"):
        tumble.Simulation(scenario, threads=-1)
    out = tmp_path / "drum"
    with pytest.raises(tumble.Error, match=r"^threads: must be a whole number >= 0 \(0: every core\), got -2$"):
        tumble.run_drum(out=out, threads=-2, **TINY_DRUM)
    for value in ("nan", "inf", "-1"):
        with pytest.raises(tumble.Error, match=rf"^max_memory_gib: must be a finite number > 0, got {value}"):
            tumble.run_drum(out=out, max_memory_gib=float(value), **TINY_DRUM)
        cli = subprocess.run([tumble_binary, "drum", "--max-memory", value, "--out", str(out)], capture_output=True,
                             text=True)
        assert f"--max-memory: must be a finite number > 0, got {value}" in cli.stderr
    cli = subprocess.run([tumble_binary, "drum", "--threads", "-1", "--out", str(out)], capture_output=True, text=True)
    assert "--threads: must be a whole number >= 0 (0: every core), got -1" in cli.stderr
    assert not out.exists()


def test_a_lattice_too_large_for_the_memory_is_refused_before_it_is_built():
    """10^7 spheres, 18.3 GiB at 1.96 kB each, against a limit of 1 GiB: refused
    from the lattice's counts before any sphere is made (building them took
    gigabytes and half a minute), in tumble run's words."""
    d = tomllib.loads(SCENARIO)
    d["domain"] = {"lo": [0.0, 0.0, 0.0], "hi": [1.0, 1.0, 10.0]}
    d["particles"] = [{"kind": "lattice", "material": "material-1", "origin": [0.005, 0.005, 0.005],
                       "counts": [100, 100, 1000], "spacing": 0.008}]
    started = time.monotonic()
    with pytest.raises(tumble.Error, match=r"^<dict>: the run would need about 18\.3 GiB of memory for 10000000 "
                                           r"spheres \(particles\[0\]\.counts\), 3\.41 neighbour pairs each, more "
                                           r"than the limit of 1 GiB \(max_memory_gib; default half the machine's "
                                           r"memory\)$"):
        tumble.Scenario.from_dict(d, max_memory_gib=1)
    assert time.monotonic() - started < 5, "the spheres were made before the refusal"
    for value in ("nan", "-1"):
        with pytest.raises(tumble.Error, match=rf"^max_memory_gib: must be a finite number > 0, got {value}"):
            tumble.Scenario.from_dict(d, max_memory_gib=float(value))


def test_more_steps_than_any_run_can_take_are_refused():
    sim = tumble.Simulation(tumble.Scenario.from_toml(SCENARIO))
    for call in (lambda: sim.advance(2**62), lambda: sim.run(steps=2**62)):
        with pytest.raises(tumble.Error, match=r"steps: 4611686018427387904 steps, more than any run can take "
                                               r"\(at most 1e\+12\)"):
            call()
    assert sim.step_count == 0


def test_a_motion_that_is_not_finite_is_refused():
    sim = tumble.Simulation(tumble.drum_scenario(**TINY_DRUM))
    for arguments in ((float("nan"),), (1.0, (0.0, float("inf"), 0.0)), (1.0, (0.0, 0.0, 0.0), (0.0, 0.0, 0.0))):
        with pytest.raises(tumble.Error, match=r"^set_motion: motion 0: (values must be finite|axis direction is zero)"):
            sim.set_motion(0, *arguments)
    # As a scenario's motions when it is read: a drum turned so fast that its
    # wall would move faster than the health check allows is refused (the
    # tiny drum's wall spheres reach 2.1 cm from the axis: at 1e4 rad/s 210
    # m/s, against 100 x its 0.858 m/s reference impact speed).
    with pytest.raises(tumble.Error, match=r"^set_motion: motion 0: its spheres and walls would move at up to 210 m/s "
                                           r".* faster than the 85.8 m/s"):
        sim.set_motion(0, 1.0e4)
    sim.set_motion(0, 5.0)  # the paper's speed is fine
    sim.step()
    sim.step()
    assert all(abs(x) < 1.0 for x in sim.positions.ravel())


def test_a_state_that_blows_up_raises_at_the_step_that_made_it():
    # A step of about 5 times the safe one: the grains fly apart after a
    # hundred steps or so, past the first of the checks every 100 steps.
    d = tomllib.loads(SCENARIO)
    d["time_step"] = {"dt": 6e-4, "allow_unsafe": True}
    scenario = tumble.Scenario.from_dict(d)
    sim = tumble.Simulation(scenario)
    with pytest.raises(tumble.Error, match=r"^the simulation blew up at step (\d+) ") as raised:
        sim.advance(100000)
    step = int(re.match(r"the simulation blew up at step (\d+)", str(raised.value)).group(1))
    assert 100 < step < 100000 and sim.step_count == step
    one_by_one = tumble.Simulation(scenario)
    for _ in range(step - 1):
        one_by_one.step()
    with pytest.raises(tumble.Error, match=rf"^the simulation blew up at step {step} "):
        one_by_one.step()
    again = tumble.Simulation(scenario)
    with pytest.raises(tumble.Error, match=rf"^the simulation blew up at step {step} "):
        again.run(steps=100000, check_every=7)
