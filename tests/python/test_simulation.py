# SPDX-License-Identifier: MIT
"""A scenario built and stepped in Python gives the same numbers as
`tumble run` of the same file; the particle arrays are views without a copy."""

import subprocess
import tomllib

import numpy as np
import pytest

import tumble
from conftest import SOURCE

SCENARIO = """
[simulation]
duration = 0.02
seed = 5
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.025, -0.025, 0.0]
hi = [0.025, 0.025, 0.05]
walls = [true, true, true]
wall_material = "material-1"

[[material]]
name = "material-1"
E = 1.0e6
G = 0.3e6
nu = 0.25
xi = 500.0
eta = 500.0
rho = 1000.0
radius = 0.0036

[[pair]]
materials = ["material-1", "material-1"]
mu = 0.1
W = 0.2

[[particles]]
kind = "random_fill"
material = "material-1"
lo = [-0.02, -0.02, 0.005]
hi = [0.02, 0.02, 0.045]
count = 40
speed = 0.3

[output]
time_series_interval = 0.002
snapshot_interval = 0.02
"""


@pytest.fixture(scope="module")
def cli_run(tmp_path_factory, tumble_binary):
    """`tumble run` of SCENARIO: its directory and the scenario file."""
    directory = tmp_path_factory.mktemp("run")
    scenario = directory / "scenario.toml"
    scenario.write_text(SCENARIO)
    subprocess.run([tumble_binary, "run", str(scenario), "--out", str(directory / "out"), "-q"], check=True)
    return directory / "out", scenario


def test_stepping_in_python_matches_tumble_run_bitwise(cli_run):
    out, scenario_file = cli_run
    with open(scenario_file, "rb") as file:
        scenario = tumble.Scenario.from_dict(tomllib.load(file))
    sim = tumble.Simulation(scenario)
    run = tumble.io.Run(out)
    snapshot = run.snapshot(-1)
    sim.run(steps=snapshot.attrs["step"])
    assert snapshot.attrs["time"] == sim.time
    expected = tumble.io.snapshot_arrays(snapshot)
    order = sim.by_id
    np.testing.assert_array_equal(sim.ids[order], expected["ids"])
    for name in ("positions", "velocities", "angular_velocities", "radii"):
        np.testing.assert_array_equal(getattr(sim, name)[order], expected[name], err_msg=name)
    # On to the end of the run: its last row of time_series.csv.
    sim.run(steps=run.info["steps"] - sim.step_count)
    last = run.time_series.iloc[-1]
    observed = sim.observe()
    assert last["step"] == sim.step_count
    for column in ("kinetic_translational", "kinetic_rotational", "contact_energy", "contacts", "max_overlap_ratio"):
        assert last[column] == observed[column], column


def test_from_file_and_from_toml_agree(cli_run):
    _, scenario_file = cli_run
    a = tumble.Simulation(tumble.Scenario.from_file(scenario_file))
    b = tumble.Simulation(tumble.Scenario.from_toml(SCENARIO))
    a.advance(50)
    for _ in range(50):
        b.step()
    np.testing.assert_array_equal(a.positions, b.positions)


def test_bad_input_names_the_key():
    with pytest.raises(tumble.Error, match=r"<dict>: simulation.duration: .*must be > 0"):
        tumble.Scenario.from_dict({**tomllib.loads(SCENARIO), "simulation": {"duration": -1.0}})
    with pytest.raises(tumble.Error, match=r"domain.lo\[2\]"):
        d = tomllib.loads(SCENARIO)
        d["domain"]["lo"][2] = "low"
        tumble.Scenario.from_dict(d)


def test_arrays_are_views_of_the_store():
    sim = tumble.Simulation(tumble.Scenario.from_toml(SCENARIO))
    sim.advance(10)
    a, b = sim.positions, sim.positions
    assert a.__array_interface__["data"][0] == b.__array_interface__["data"][0]  # the same memory, not copies
    assert a.base is sim  # the view keeps the simulation alive
    assert a.shape == (40, 3) and a.strides == (24, 8) and not a.flags.writeable
    assert sim.radii.base is sim and sim.ids.dtype == np.int64 and sim.materials.dtype == np.int32


def test_a_view_follows_the_engine_while_the_store_stays():
    """Without re-sorts ([neighbor] sort_every = 0) the store never moves: a
    view taken once shows every later step."""
    scenario = tomllib.loads(SCENARIO)
    scenario["neighbor"] = {"sort_every": 0}
    sim = tumble.Simulation(tumble.Scenario.from_dict(scenario))
    view = sim.positions
    before = view.copy()
    sim.advance(200)
    assert not np.array_equal(view, before)
    np.testing.assert_array_equal(view, sim.positions)


def test_run_until_a_condition():
    sim = tumble.Simulation(tumble.Scenario.from_toml(SCENARIO))
    calls = []

    def until(s):
        calls.append(s.step_count)
        return s.step_count >= 300

    steps = sim.run(steps=10_000, until=until, check_every=100)
    assert steps == 300 and calls == [100, 200, 300]


def test_run_refuses_a_negative_count_or_time():
    # Each would otherwise do nothing without a word.
    sim = tumble.Simulation(tumble.Scenario.from_toml(SCENARIO))
    with pytest.raises(tumble.Error, match="run: steps: need a count >= 0, got -5"):
        sim.run(steps=-5)
    with pytest.raises(tumble.Error, match="run: duration: need a time >= 0 s, got -1"):
        sim.run(duration=-1.0)
    with pytest.raises(tumble.Error, match="run: duration: need a time >= 0 s, got nan"):
        sim.run(duration=float("nan"))
    with pytest.raises(tumble.Error, match="advance: steps: need a count >= 0, got -1"):
        sim.advance(-1)
    assert sim.run(steps=0) == 0 and sim.step_count == 0


def test_step_times_split_the_steps_by_phase():
    sim = tumble.Simulation(tumble.Scenario.from_toml(SCENARIO))
    sim.advance(300)
    times = sim.step_times
    assert set(times) == {"motion", "exchange", "neighbours", "forces", "steps"}
    assert times["steps"] == 300
    assert times["forces"] > 0 and times["motion"] > 0 and times["exchange"] == 0  # one process
    sim.reset_step_times()
    assert sim.step_times["steps"] == 0 and sim.step_times["forces"] == 0


def test_contacts_with_history():
    sim = tumble.Simulation(tumble.Scenario.from_toml(SCENARIO))
    sim.run(duration=0.15)  # the grains have fallen into a bed
    c = sim.contacts()
    n = len(c["id_i"])
    assert n > 20
    assert np.all(c["id_i"] < c["id_j"]) and np.all(c["overlap"] > 0)
    assert c["slip"].shape == (n, 3) and c["normal"].shape == (n, 3)
    np.testing.assert_allclose(np.linalg.norm(c["normal"], axis=1), 1.0)
    # The slip lies in the contact plane and some contact has one.
    np.testing.assert_allclose(np.sum(c["slip"] * c["normal"], axis=1), 0.0, atol=1e-12)
    assert np.abs(c["slip"]).max() > 0


def test_example_scenario_file_runs():
    sim = tumble.Simulation(tumble.scenario(SOURCE / "examples" / "two_spheres.toml"))
    sim.run(steps=20)
    assert sim.size == 2 and sim.material_names == ["material-1"]


def test_recorded_contact_forces_add_up_to_the_particle_forces():
    sim = tumble.Simulation(tumble.Scenario.from_toml(SCENARIO))
    sim.run(duration=0.15)
    sim.set_contact_recording(True)
    sim.step()
    r = sim.contact_records()
    assert np.any(r["id_j"] < 0) and np.all(r["id_i"] >= 0)  # flat-wall contacts too
    total = np.zeros((sim.size, 3))
    np.add.at(total, r["id_i"], r["force"])
    spheres = r["id_j"] >= 0
    np.add.at(total, r["id_j"][spheres], -r["force"][spheres])
    np.testing.assert_allclose(total, sim.forces[sim.by_id], rtol=1e-9, atol=1e-12)


def test_walls_from_a_dict_with_their_surfaces_and_loads():
    """A [[wall]] given in a dict: the grains fall onto a smooth floor inside a
    cylinder; walls() draws both and the floor carries the grains' weight."""
    scenario = tomllib.loads(SCENARIO)
    scenario["domain"] = {"lo": [-0.025, -0.025, 0.0], "hi": [0.025, 0.025, 0.05]}  # no box walls
    scenario["wall"] = [
        {"name": "floor", "shape": "plane", "material": "material-1", "point": [0.0, 0.0, 0.0]},
        {"name": "tube", "shape": "cylinder", "material": "material-1", "radius": 0.025, "point": [0.0, 0.0, 0.0],
         "length": 0.05},
    ]
    scenario["particles"][0].update(lo=[-0.017, -0.017, 0.005], hi=[0.017, 0.017, 0.045])
    sim = tumble.Simulation(tumble.Scenario.from_dict(scenario))
    sim.run(duration=0.4)  # fallen and come to rest
    floor, tube = sim.walls()
    assert floor["name"] == "floor" and tube["name"] == "tube"
    assert tube["vertices"].shape == (96, 3) and tube["triangles"].shape == (96, 3)
    np.testing.assert_allclose(np.hypot(tube["vertices"][:, 0], tube["vertices"][:, 1]), 0.025)
    assert floor["triangles"].shape == (2, 3)
    # At rest the floor carries the weight not held by the tube's friction.
    weight = 40 * 1000.0 * 4.0 / 3.0 * np.pi * 0.0036**3 * 9.81
    assert -floor["force"][2] + -tube["force"][2] == pytest.approx(weight, rel=0.02)
    assert -floor["force"][2] > 0.5 * weight
    with pytest.raises(tumble.Error, match=r"<dict>: wall\[1\]\.radius: must be > 0"):
        scenario["wall"][1]["radius"] = -1.0
        tumble.Scenario.from_dict(scenario)


def test_spheres_poured_in_from_a_dict():
    """An [[insert]] in a dict and no [[particles]]: the simulation starts
    empty and pours 40 grains, 10 at a time every 0.01 s (where the region is
    still crowded a batch places fewer and the next the rest); `inserted`
    counts them, the arrays grow, the ids run on, and a bad batch is refused
    at its key."""
    scenario = tomllib.loads(SCENARIO)
    del scenario["particles"]
    scenario["insert"] = [{"material": "material-1", "lo": [-0.02, -0.02, 0.03], "hi": [0.02, 0.02, 0.045],
                           "count": 40, "batch": 10, "every": 0.01}]
    sim = tumble.Simulation(tumble.Scenario.from_dict(scenario))
    assert sim.size == 0 and sim.inserted == [0]
    sim.step()
    assert sim.inserted == [10] and sim.size == 10
    sim.run(duration=0.2)
    assert sim.inserted == [40] and sim.size == 40
    assert sorted(sim.ids) == list(range(40))
    assert np.all(sim.positions[:, 2] < 0.045)
    scenario["insert"][0]["batch"] = 50
    with pytest.raises(tumble.Error, match=r"<dict>: insert\[0\]\.batch: must lie in \[1, 40\], got 50"):
        tumble.Scenario.from_dict(scenario)
