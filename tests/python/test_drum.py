# SPDX-License-Identifier: MIT
"""The drum protocol from Python: the callback at every sample, the
settings as tumble drum's options, the drum as a scenario to step."""

import os

import numpy as np
import pytest

import tumble
from conftest import TINY_DRUM


def test_callback_sees_every_sample(tiny_drum):
    directory, samples = tiny_drum
    series = tumble.io.Run(directory).drum_series
    # N = 0, 10 per revolution for 0.4 revolutions, and the final state if it
    # falls between two samples: one call per row of drum_series.csv.
    assert 5 <= len(samples) == len(series)
    np.testing.assert_array_equal([s.revolutions for s in samples], series["revolutions"])
    assert samples[0].revolutions == 0.0 and samples[-1].revolutions == pytest.approx(0.4, abs=0.01)
    for s, (_, row) in zip(samples, series.iterrows()):
        assert [c.mean_z for c in s.components] == [row["mean_z_left"], row["mean_z_right"]]
        assert s.time == row["time"]
    steps = [s.step for s in samples]
    assert steps == sorted(steps) and len(set(steps)) == len(steps)


def test_sample_particles_are_sensible(tiny_drum):
    _, samples = tiny_drum
    for s in samples:
        p = s.particles
        free = p["motions"] < 0
        assert free.sum() == 6 and sorted(p["ids"]) == list(range(len(p["ids"])))
        assert p["positions"].shape == (len(p["ids"]), 3)
        assert np.all(np.hypot(p["positions"][free, 0], p["positions"][free, 1]) < 0.015)  # inside the drum
        left, right = s.components
        assert left.grains + right.grains == 6
        # <z> of each half is the mean of its grains' z.
        z = p["positions"][free, 2]
        tags = p["tags"][free]
        assert left.mean_z == pytest.approx(z[tags == 0].mean(), abs=1e-12)
    # Copies: the first sample's arrays still hold the settled bed.
    assert not np.array_equal(samples[0].particles["velocities"], samples[-1].particles["velocities"])


def test_settings_are_the_command_lines():
    s = tumble.drum_settings(mode="self", grains=458, rpm=30, length=0.2, seed=4, shear="coulomb")
    assert (s.mode, s.grains, s.length, s.seed, s.shear) == ("self", 458, 0.2, 4, "coulomb")
    assert s.omega == pytest.approx(30 * 2 * np.pi / 60)
    assert tumble.drum_settings({"rotation": {"rpm": 30}}, omega=2.0).omega == 2.0  # an option replaces the file's
    with pytest.raises(tumble.Error, match="mode"):
        tumble.drum_settings(mode="three")
    with pytest.raises(TypeError, match="unknown setting"):
        tumble.drum_settings(speed=3)


def test_contact_model_settings_are_the_command_lines():
    default = tumble.drum_settings()
    assert (default.shear, default.friction_normal, default.tangential_stiffness) == ("paper", "net", "paper")
    s = tumble.drum_settings(shear="spring", friction_normal="jkr", tangential_stiffness="mindlin")
    assert (s.shear, s.friction_normal, s.tangential_stiffness) == ("spring", "jkr", "mindlin")
    with pytest.raises(tumble.Error, match="model.tangential_stiffness"):
        tumble.drum_settings(tangential_stiffness="hertz")


def test_arrangement_settings_are_the_command_lines():
    s = tumble.drum_settings(length=0.24, arrangement="bands", bands=3, band_widths=[0.25, 0.5, 0.25], ends="large",
                             small_volume_fraction=0.4, cap_friction=0.6)
    assert (s.arrangement, s.bands, s.band_widths, s.ends) == ("bands", 3, [0.25, 0.5, 0.25], "large")
    assert (s.small_volume_fraction, s.cap_friction) == (0.4, 0.6)
    assert s.band_edges == pytest.approx([-0.12, -0.06, 0.06, 0.12])
    b = tumble.drum_settings(arrangement="boundaries", boundaries=(-0.02, 0.03))
    assert b.boundaries == [-0.02, 0.03] and b.band_edges == pytest.approx([-0.06, -0.02, 0.03, 0.06])
    default = tumble.drum_settings()
    assert (default.arrangement, default.small_volume_fraction, default.cap_friction) == ("halves", None, None)
    with pytest.raises(tumble.Error, match="bands"):
        tumble.drum_settings(arrangement="bands", bands=1)
    with pytest.raises(tumble.Error, match="cap_friction"):
        tumble.drum_settings(periodic_axis=True, cap_friction=0.5)
    assert tumble.drum_settings(revolutions=150, until_band_change=10).until_band_change == 10
    assert tumble.drum_settings(skin=0.001).skin == 0.001  # tumble drum --skin, [neighbor] skin
    assert tumble.drum_settings().skin == 0.0
    assert tumble.drum_settings(surface_energy=0.0).surface_energy == 0.0  # --surface-energy, [model] surface_energy
    assert tumble.drum_settings().surface_energy == 0.2  # the paper's W
    with pytest.raises(tumble.Error, match="surface_energy"):
        tumble.drum_settings(surface_energy=-1.0)
    assert default.until_band_change == 0
    with pytest.raises(tumble.Error, match="until_band_change"):
        tumble.drum_settings(revolutions=12, until_band_change=12)
    # The drum built from them: three bands, small grains in the middle one,
    # by default an even fill (1/4, 1/2, 1/4 of the length: equal volumes).
    assert tumble.drum_settings(length=0.24, arrangement="bands", bands=3).band_edges == pytest.approx(
        [-0.12, -0.06, 0.06, 0.12])
    scenario = tumble.drum_scenario(length=0.24, grains=400, arrangement="bands", bands=3, ends="large")
    sim = tumble.Simulation(scenario)
    free = sim.motions < 0
    z, materials = sim.positions[free, 2], sim.materials[free]
    assert np.all(materials[np.abs(z) < 0.06] == 1) and np.all(materials[np.abs(z) > 0.06] == 0)


def test_drum_as_a_scenario_to_step():
    settings = {k: v for k, v in TINY_DRUM.items()}
    sim = tumble.Simulation(tumble.drum_scenario(**settings))
    sim.run(steps=2000)
    sim.set_motion(0, angular_velocity=settings["omega"])
    wall = sim.motions >= 0
    sim.run(steps=200)
    speed = np.linalg.norm(sim.velocities[wall], axis=1)
    radius = np.hypot(sim.positions[wall, 0], sim.positions[wall, 1])
    np.testing.assert_allclose(speed, settings["omega"] * radius, rtol=1e-9, atol=1e-12)


def test_an_exception_in_the_callback_ends_the_run(tmp_path):
    def fail(sample):
        if sample.revolutions > 0.1:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        tumble.run_drum(out=tmp_path / "run", on_sample=fail, **TINY_DRUM)
    assert not (tmp_path / "run" / "summary.json").exists()


def test_the_wall_spheres_forces_are_the_grains_load_on_any_thread_count():
    # Between calls every sphere's force is complete, the wall's too: the
    # load of the grains on each wall sphere. 2 threads sum it in another
    # order than 1 (round-off, which the flow amplifies: 5e-11 of the
    # largest after 1,550 steps (0.04 s), grown to 5 % some 500 steps
    # later as the bed settles); a thread's part left out is a tenth of the
    # largest or more.
    forces = {}
    for threads in (1, 2):
        sim = tumble.Simulation(tumble.drum_scenario(length=0.03, fill=0.3), threads=threads)
        sim.set_motion(0, angular_velocity=5.0)
        sim.run(steps=1550)
        wall = (sim.motions >= 0)[sim.by_id]
        forces[threads] = sim.forces[sim.by_id][wall]
    scale = np.abs(forces[1]).max()
    assert np.count_nonzero(np.linalg.norm(forces[1], axis=1) > 1e-3 * scale) > 30  # grains rest on the wall (49)
    np.testing.assert_allclose(forces[2], forces[1], rtol=0, atol=1e-6 * scale)


def _glass_tables():
    """Cohesionless glass-like beads of 3 and 2 mm and a steel wall, as the
    drum file's [[material]] and [[pair]] tables."""
    def material(name, radius, rho=2500.0):
        return {"name": name, "E": 1.0e7, "G": 4.0e6, "nu": 0.22, "xi": 50.0, "eta": 50.0, "rho": rho,
                "radius": radius}
    names = ["glass-3mm", "glass-2mm", "steel"]
    pairs = [{"materials": [a, b], "mu": 0.4 if "steel" in (a, b) else 0.3, "W": 0.0}
             for i, a in enumerate(names) for b in names[i:]]
    return [material("glass-3mm", 3.0e-3), material("glass-2mm", 2.0e-3), material("steel", 3.0e-3, 7800.0)], pairs


def test_walls_and_materials_are_the_drum_files():
    assert tumble.drum_settings().walls == "particles"
    assert tumble.drum_settings(walls="smooth").walls == "smooth"  # --walls, [drum] walls
    with pytest.raises(tumble.Error, match="drum.walls"):
        tumble.drum_settings(walls="glass")
    # A mantle from an STL file ([drum] mesh, --mesh): the walls become "mesh";
    # a missing file is refused naming the key.
    lifters = os.path.join(os.environ["TUMBLE_SOURCE_DIR"], "examples", "meshes", "drum_lifters.stl")
    assert tumble.drum_settings(mesh=lifters, mesh_scale=1e-3).walls == "mesh"
    with pytest.raises(tumble.Error, match="drum.mesh: .*no such file"):
        tumble.drum_settings(mesh=lifters + ".missing")
    assert tumble.drum_settings().materials == {"paper": True, "large": "material-1", "small": "material-2",
                                               "wall": "wall", "cap": "wall"}
    materials, pairs = _glass_tables()
    roles = {"large": "glass-3mm", "small": "glass-2mm", "wall": "steel"}
    s = tumble.drum_settings(material=materials, pair=pairs, materials=roles, walls="smooth")
    assert s.materials == {"paper": False, "large": "glass-3mm", "small": "glass-2mm", "wall": "steel",
                           "cap": "steel"}
    assert s.surface_energy == 0.0  # every pair's W
    # A dict laid out as the file goes through the same reader.
    d = tumble.drum_settings({"material": materials, "pair": pairs, "materials": roles, "drum": {"walls": "smooth"}})
    assert (d.walls, d.materials["large"]) == ("smooth", "glass-3mm")
    with pytest.raises(tumble.Error, match=r"materials\.small: unknown material \"glass-2m\""):
        tumble.drum_settings(material=materials, pair=pairs, materials={**roles, "small": "glass-2m"})
    with pytest.raises(tumble.Error, match=r"materials: missing"):
        tumble.drum_settings(material=materials, pair=pairs)
    with pytest.raises(tumble.Error, match=r"pair: missing \[\[pair\]\]"):
        tumble.drum_settings(material=materials, pair=pairs[:-1], materials=roles)
    # The smooth drum of them: no wall spheres, the grains of their radii.
    sim = tumble.Simulation(tumble.drum_scenario(material=materials, pair=pairs, materials=roles, walls="smooth",
                                                 grains=200))
    assert np.all(sim.motions < 0) and len(sim.ids) == 200
    assert set(np.round(sim.radii, 6)) == {0.003, 0.002}
