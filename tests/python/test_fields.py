# SPDX-License-Identifier: MIT
"""Coarse-grained fields from Python (docs/FIELDS.md): tumble.coarse_grain
of arrays, tumble.fields of a run directory, and the refusal of bad
settings naming them."""

import math
import subprocess

import numpy as np
import pandas as pd
import pytest

import tumble
from conftest import TINY_DRUM


def lattice(n, a):
    """The sites of an n^3 simple cubic lattice of spacing a, N x 3."""
    k = np.arange(n) * a
    return np.stack(np.meshgrid(k, k, k, indexing="ij"), -1).reshape(-1, 3)


def test_a_lattice_from_arrays_has_its_solid_fraction():
    a = 1e-3
    x = lattice(12, a)
    n = len(x)
    f = tumble.coarse_grain(x, np.zeros((n, 3)), np.full(n, 1e-6), np.full(n, a / 2), lo=[4 * a] * 3,
                            hi=[7 * a] * 3, cell=a, kernel="lucy", width=a)
    assert f["solid_fraction"].shape == (3, 3, 3)
    assert f["velocity"].shape == (3, 3, 3, 3)
    assert f["stress"].shape == (3, 3, 3, 3, 3)
    assert np.allclose(f["x"], [4.5e-3, 5.5e-3, 6.5e-3])
    assert f["samples"] == 1
    np.testing.assert_allclose(f["solid_fraction"], np.pi / 6, rtol=3e-3)  # tests/unit/test_coarse_grain.cpp


def test_a_contact_from_arrays_carries_its_force_times_its_branch():
    x = np.array([[0.0, 0.0, 0.0], [0.0, 0.0, -1e-3]])
    contacts = dict(i=np.array([0]), j=np.array([1]), force=np.array([[0.0, 0.0, 2.0]]),
                    branch=np.array([[0.0, 0.0, 1e-3]]))
    f = tumble.coarse_grain(x, np.zeros((2, 3)), np.full(2, 1e-6), np.full(2, 5e-4), contacts,
                            lo=[-2e-3, -2e-3, -2.6e-3], hi=[2e-3, 2e-3, 1.6e-3], cell=1e-4, width=5e-4, kernel="lucy")
    cell = 1e-4 ** 3
    total = f["contact_stress"].sum(axis=(0, 1, 2)) * cell
    np.testing.assert_allclose(total[2, 2], 2e-3, rtol=1e-3)
    assert abs(total[0, 0]) < 1e-12 and abs(total[0, 2]) < 1e-12
    assert f["pressure"].max() > 0.0  # compression is positive


def test_bad_settings_and_arrays_are_refused_naming_them(tmp_path):
    x = lattice(2, 1e-3)
    v, m, R = np.zeros((8, 3)), np.ones(8), np.full(8, 5e-4)
    with pytest.raises(tumble.Error, match="^width: "):
        tumble.coarse_grain(x, v, m, R, width=0.0)
    with pytest.raises(tumble.Error, match="^hi: must be above lo"):
        tumble.coarse_grain(x, v, m, R, lo=[0, 0, 0], hi=[1, 0, 1])
    with pytest.raises(tumble.Error, match="^average: "):
        tumble.coarse_grain(x, v, m, R, average="zz")
    with pytest.raises(tumble.Error, match="^kernel: "):
        tumble.coarse_grain(x, v, m, R, kernel="box")
    with pytest.raises(tumble.Error, match="^positions: "):
        tumble.coarse_grain(np.zeros((8, 2)), v, m, R)
    with pytest.raises(tumble.Error, match="^radii: "):
        tumble.coarse_grain(x, v, m, np.ones(7))
    with pytest.raises(tumble.Error, match="max_memory_gib"):
        tumble.coarse_grain(x, v, m, R, lo=[0, 0, 0], hi=[1, 1, 1], cell=1e-3, width=1e-3, max_memory_gib=1)
    with pytest.raises(tumble.Error, match="grain 0 has a position"):
        tumble.coarse_grain(x, v, -m, R, lo=[0, 0, 0], hi=[1, 1, 1], width=0.5)
    with pytest.raises(tumble.Error, match="names a grain beyond"):
        tumble.coarse_grain(x, v, m, R, dict(i=[0], j=[9], force=[[0, 0, 1]], branch=[[0, 0, 1e-3]]))
    with pytest.raises(tumble.Error, match="^run directory: no such directory"):
        tumble.fields(tmp_path / "missing")
    with pytest.raises(tumble.Error, match="^samples: "):
        tumble.fields(tmp_path, samples=0)


def test_fields_of_a_run_directory(tiny_drum):
    directory, _ = tiny_drum
    f = tumble.fields(directory, average="z", samples=2, every=0.005, kernel="lucy")
    assert f["samples"] == 2
    assert len(f["times"]) == 2 and f["times"][1] - f["times"][0] == pytest.approx(0.005, rel=0.01)
    assert f["density"].shape[0] == 1  # z averaged
    assert np.isfinite(f["stress"]).all() and f["solid_fraction"].max() > 0.1
    assert str(f["checkpoint"]).endswith(".tck")


def test_the_command_line_writes_what_python_computes(tiny_drum, tumble_binary, tmp_path):
    """tumble fields: fields.csv (pandas) and fields.vti (VTK's own reader)
    hold what tumble.fields returns for the same settings."""
    directory, _ = tiny_drum
    out = tmp_path / "fields"
    settings = ["--average", "z", "--cell", "0.002", "--samples", "2", "--every", "0.005"]
    done = subprocess.run([tumble_binary, "fields", str(directory), "-q", "-o", str(out)] + settings,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    f = tumble.fields(directory, average="z", cell=0.002, samples=2, every=0.005)
    table = pd.read_csv(out / "fields.csv", float_precision="round_trip")
    assert len(table) == f["density"].size and (table["samples"] == 2).all()
    np.testing.assert_array_equal(table["density"].to_numpy(), f["density"].ravel())
    np.testing.assert_array_equal(table["stress_xz"].to_numpy(), f["stress"][..., 0, 2].ravel())
    np.testing.assert_array_equal(table["velocity_y"].to_numpy(), f["velocity"][..., 1].ravel())
    vtk = pytest.importorskip("vtkmodules.vtkIOXML")
    from vtkmodules.util.numpy_support import vtk_to_numpy
    reader = vtk.vtkXMLImageDataReader()
    reader.SetFileName(str(out / "fields.vti"))
    reader.Update()
    image = reader.GetOutput()
    assert image.GetDimensions() == tuple(f["density"].shape[::-1])
    assert image.GetOrigin() == pytest.approx((f["x"][0], f["y"][0], f["z"][0]))
    points = image.GetPointData()
    np.testing.assert_array_equal(vtk_to_numpy(points.GetArray("pressure")), f["pressure"].ravel())
    np.testing.assert_array_equal(vtk_to_numpy(points.GetArray("contact_stress")), f["contact_stress"].reshape(-1, 9))


def test_the_fields_of_a_simulation_stepped_in_python():
    """sim.grain_state() hands tumble.coarse_grain a state's grains and
    contacts, the walls' too: the contact stress of 40 grains in a walled
    box, integrated over the box, is the sum of f (x) b over the contacts."""
    from test_simulation import SCENARIO
    sim = tumble.Simulation(tumble.Scenario.from_toml(SCENARIO))
    sim.run(duration=0.1)
    sim.set_contact_recording(True)
    sim.step()
    state = sim.grain_state()
    contacts = state["contacts"]
    assert state["positions"].shape == (40, 3) and len(contacts["i"]) > 0
    assert (contacts["j"] == -1).any()  # the box's walls
    w = 0.0018
    L = 0.052  # the box (5 cm) and the wall contacts' points on its faces, averaged over x and y
    f = tumble.coarse_grain(**state, lo=[-L / 2, -L / 2, -3.5 * w], hi=[L / 2, L / 2, 0.05 + 3.5 * w],
                            cell=w / 4, average="xy", width=w, kernel="lucy")
    dz = f["z"][1] - f["z"][0]
    integral = f["contact_stress"].sum(axis=(0, 1, 2)) * dz * L * L
    expected = np.einsum("ka,kb->ab", contacts["force"], contacts["branch"])
    np.testing.assert_allclose(integral, expected, rtol=1e-3, atol=1e-3 * np.abs(expected).max())


@pytest.fixture(scope="module")
def flowing_drum(tmp_path_factory):
    """The paper's drum with 600 grains of one kind, turned one revolution
    at 5 rad/s: a bed deep enough for a flowing layer over a turning bed."""
    return tumble.run_drum(out=tmp_path_factory.mktemp("drum") / "flowing", mode="self", grains=600, revolutions=1.0,
                           snapshots=0)


def test_the_drum_frame_finds_the_flowing_layer(flowing_drum, tumble_binary, tmp_path):
    """tumble.fields(frame="drum"): the free surface, the depth profile below
    it and its numbers; the command line writes the same (profile.csv,
    drum_frame.json)."""
    settings = dict(samples=3, every=0.01, kernel="lucy", cell=0.001)
    d = tumble.fields(flowing_drum, frame="drum", **settings)
    s, p = d["surface"], d["profile"]
    assert p["velocity"].shape == (1, len(p["d"]), 1, 3)
    u = p["velocity"][0, :, 0, 0]
    phi = p["solid_fraction"][0, :, 0]
    # The surface lies where the profile's solid fraction is half the bed's:
    # phi(d = 0), interpolated, is the level the surface was fitted to (on
    # the cross-section rather than the middle part's profile: within 20 %).
    assert np.interp(0.0, p["d"], phi) == pytest.approx(s["surface_solid_fraction"], rel=0.2)
    # The layer flows downhill at the surface and the bed below goes uphill
    # with the drum, but no faster than the drum turning rigidly, whose
    # velocity along the surface is omega n . r = omega (level - d): at the
    # deepest node where phi > 0.3, measured 0.47 of it (the paper's grains,
    # mu = 0.1, slip over each other and the wall all through this shallow
    # bed).
    assert s["surface_velocity_m_per_s"] > 0.0 and u[-1] < 0.0
    deep = np.nonzero(phi > 0.3)[0][-1]
    rigid = 5.0 * (s["surface_level_m"] - p["d"][deep])
    assert 0.2 < u[deep] / rigid < 1.0
    # The thickness is where u turns, a few grains deep; u is 0 there.
    assert 1.0 < s["layer_thickness_diameters"] < 5.0
    assert abs(np.interp(s["layer_thickness_m"], p["d"], u)) < 0.01 * s["surface_velocity_m_per_s"]
    # The angle: between 15 and 45 degrees for these grains (mu = 0.1
    # between them, a rough wall).
    assert 15.0 < s["angle_of_repose_deg"] < 45.0

    # Resolved along the axis too (frame_cells): the same nodes along d, 4
    # along z; the bed of one kind is uniform along the axis but for the
    # caps, so the mean of its axial nodes' density inside the layer is the
    # profile's, within 10 % (each node's value is the kernel's mean over
    # 3w about it, a sample of the axis rather than its average).
    r = tumble.fields(flowing_drum, frame="drum", frame_cells=(1, 4), **settings)
    resolved = r["frame"]
    assert resolved["density"].shape == (4, len(p["d"]), 1)
    np.testing.assert_array_equal(resolved["d"], p["d"])
    np.testing.assert_array_equal(r["profile"]["density"], p["density"])
    half = np.interp(s["layer_thickness_m"] / 2, p["d"], p["density"][0, :, 0])
    axial = [np.interp(s["layer_thickness_m"] / 2, p["d"], resolved["density"][k, :, 0]) for k in range(4)]
    assert np.mean(axial) == pytest.approx(half, rel=0.1)

    out = tmp_path / "fields"
    done = subprocess.run([tumble_binary, "fields", str(flowing_drum), "-q", "-o", str(out), "--frame", "drum",
                           "--samples", "3", "--every", "0.01", "--kernel", "lucy", "--cell", "0.001", "--format",
                           "csv", "--frame-cells", "1,4"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    table = pd.read_csv(out / "profile.csv", float_precision="round_trip")
    np.testing.assert_array_equal(table["d"].to_numpy(), p["d"])
    np.testing.assert_array_equal(table["velocity_s"].to_numpy(), u)
    np.testing.assert_array_equal(table["stress_sd"].to_numpy(), p["stress"][0, :, 0, 0, 1])
    frame = pd.read_csv(out / "frame.csv", float_precision="round_trip")
    np.testing.assert_array_equal(frame["velocity_s"].to_numpy(), resolved["velocity"][..., 0].ravel())
    import json
    assert json.loads((out / "drum_frame.json").read_text()) == s


def test_the_drum_frame_during_a_run_is_that_of_the_same_states_afterwards(tmp_path, tumble_binary):
    """tumble.run_drum(fields={"frame": "drum"}) averages the cross-section
    during the run and carries the depth profile from it at the end;
    tumble fields --frame drum takes the same states again from a checkpoint
    and coarse-grains them in the surface's coordinates (docs/FIELDS.md,
    "During a run")."""
    drum = dict(mode="self", grains=600, revolutions=1.0, snapshots=0)  # the flowing drum of the tests above
    # The grid on both sides: the drum's inside (radius 4 cm, 12 cm long)
    # and 3 widths (the mean radius, 3 mm) beyond it across the axis, so
    # that the cross-section holds every grain's kernel whole, as the drum
    # frame's default grid during a run does.
    grid = {"lo": [-0.05, -0.05, -0.06], "hi": [0.05, 0.05, 0.06], "kernel": "gaussian", "cell": 0.001}
    fields = {"frame": "drum", "from": 1.0, "every": 0.01, "samples": 20, "span": 0.5, "format": "csv", **grid}
    during = tumble.run_drum(out=tmp_path / "during", fields=fields, **drum) / "flowing_layer"
    dt = tumble.io.Run(during.parent).info["dt"]
    # The first state is the step that ends at or after 1 s: stop one before it.
    stopped = tumble.run_drum(out=tmp_path / "stopped", stop_at_step=math.ceil(1.0 / dt - 1e-9) - 1, **drum)
    after = tmp_path / "after"
    done = subprocess.run([tumble_binary, "fields", str(stopped), "-q", "-o", str(after), "--frame", "drum",
                           "--samples", "20", "--every", "0.01", "--kernel", "gaussian", "--cell", "0.001",
                           "--lo", "-0.05,-0.05,-0.06", "--hi", "0.05,0.05,0.06", "--span", "0.5", "--format", "csv"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    # The same states: the cross-sections are the same bytes, so the surface
    # found on them is the same (tolerance none).
    assert (during / "fields.csv").read_bytes() == (after / "fields.csv").read_bytes()
    import json
    a, b = (json.loads((d / "drum_frame.json").read_text()) for d in (during, after))
    for key in ("angle_of_repose_deg", "surface_level_m", "surface_solid_fraction"):
        assert a[key] == b[key], key
    # The profiles: the same depth nodes; the carried one is the 2-D kernel's
    # mean along s, bilinear between the cross-section's nodes, the other the
    # 1-D kernel of the grains in the frame. Measured: phi within 0.015 (at
    # the bed's bottom, where the chord shrinks fastest: the 2-D kernel is
    # cut at 3w on a disc, the 1-D one on a segment), the thickness within
    # 1.2 %, the surface velocity within 0.02 %. Tolerances about twice
    # those.
    p, q = (pd.read_csv(d / "profile.csv") for d in (during, after))
    np.testing.assert_array_equal(p["d"], q["d"])
    bed = q["solid_fraction"] > 0.05
    print(f"[measured] phi {np.abs(p['solid_fraction'] - q['solid_fraction'])[bed].max():.3g}, "
          f"u {np.abs(p['velocity_s'] - q['velocity_s'])[bed].max():.3g} m/s at worst; thickness "
          f"{a['layer_thickness_m']:.6g} against {b['layer_thickness_m']:.6g} m, surface velocity "
          f"{a['surface_velocity_m_per_s']:.6g} against {b['surface_velocity_m_per_s']:.6g} m/s")
    assert np.abs(p["solid_fraction"] - q["solid_fraction"])[bed].max() < 0.03
    assert a["layer_thickness_m"] == pytest.approx(b["layer_thickness_m"], rel=0.025)
    assert a["surface_velocity_m_per_s"] == pytest.approx(b["surface_velocity_m_per_s"], rel=0.005)

    # Stopped between its states and resumed, the run writes the same files,
    # byte for byte: its checkpoint keeps the sums and how far the grains
    # reach from the axis (the profile's depth).
    halfway = tumble.run_drum(out=tmp_path / "halfway", fields=fields,
                              stop_at_step=math.ceil(1.0 / dt - 1e-9) + 5 * math.ceil(0.01 / dt - 1e-9) + 2, **drum)
    assert not (halfway / "flowing_layer").exists()
    done = subprocess.run([tumble_binary, "resume", "-q", str(halfway)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    for name in ("fields.csv", "profile.csv", "drum_frame.json"):
        assert (halfway / "flowing_layer" / name).read_bytes() == (during / name).read_bytes(), name


def test_the_flowing_layer_against_the_kernel_width(flowing_drum):
    """The drum frame's numbers at widths d/8 to d (docs/FIELDS.md, "Width":
    the table there is what this prints, pytest -s), 20 samples 10 ms apart,
    Lucy's kernel, cells of w/2 (at most 1 mm). Between w = d/4 and d/2 the
    numbers agree (the plateau); below, the solid fraction resolves the
    grains; above, the kernel's reach (3w) is the bed's depth."""
    d = 0.0072  # m, the grains' diameter
    rows = {}
    for ratio in (0.125, 0.25, 0.5, 1.0):
        w = ratio * d
        f = tumble.fields(flowing_drum, frame="drum", samples=20, every=0.01, kernel="lucy", width=w,
                          cell=min(w / 2, 0.001))
        s, p = f["surface"], f["profile"]
        h = s["layer_thickness_m"]
        mid = {k: float(np.interp(h / 2, p["d"], p[k][0, :, 0])) for k in
               ("solid_fraction", "shear_rate", "friction", "inertial_number")}
        rows[ratio] = dict(s, **mid)
        print(f"| {ratio:g} | {s['angle_of_repose_deg']:.1f} | {s['bed_solid_fraction']:.3f} | "
              f"{s['surface_velocity_m_per_s']:.3f} | {h * 1e3:.1f} | {mid['solid_fraction']:.3f} | "
              f"{mid['shear_rate']:.2f} | {mid['friction']:.3f} | {mid['inertial_number']:.3f} |")
    quarter, half = rows[0.25], rows[0.5]
    # The plateau, w = d/4 and d/2 (measured: 19.4 and 20.1 degrees, 13.1
    # and 14.0 mm, phi 0.555 and 0.575, mu 0.345 and 0.311, I 0.242 and
    # 0.217): tolerances 2 degrees, 10 %, 5 %, 15 %, 25 % (the kernel's mean
    # over a layer a few grains deep, whose gradients it smooths more as it
    # widens; I is a ratio of three fields).
    assert quarter["angle_of_repose_deg"] == pytest.approx(half["angle_of_repose_deg"], abs=2.0)
    assert quarter["layer_thickness_m"] == pytest.approx(half["layer_thickness_m"], rel=0.1)
    assert quarter["solid_fraction"] == pytest.approx(half["solid_fraction"], rel=0.05)
    assert quarter["friction"] == pytest.approx(half["friction"], rel=0.15)
    assert quarter["inertial_number"] == pytest.approx(half["inertial_number"], rel=0.25)
    # At w = d/8 the time-averaged solid fraction still shows the grains:
    # the bed's phi_ref is above 1 (measured 1.06), and the surface at
    # phi_ref / 2 is no longer the bed's.
    assert rows[0.125]["bed_solid_fraction"] > 0.9
    # At w = d (3w = 22 mm, the bed's depth) the bed's phi is smeared over
    # its edges: phi_ref falls below 0.5 (measured 0.431).
    assert rows[1.0]["bed_solid_fraction"] < 0.5


def test_the_drum_frame_refuses_bad_settings(tiny_drum, tmp_path):
    directory, _ = tiny_drum
    with pytest.raises(tumble.Error, match="^frame: lab or drum"):
        tumble.fields(directory, frame="rotating")
    with pytest.raises(tumble.Error, match=r"^span: .* \(0, 1\], got 0"):
        tumble.fields(directory, frame="drum", span=0.0)
    with pytest.raises(tumble.Error, match="^average: the drum frame's cross-section is averaged along z"):
        tumble.fields(directory, frame="drum", average="x")
    with pytest.raises(tumble.Error, match="^frame: drum takes the directory of a tumble drum run"):
        tumble.fields(tmp_path, frame="drum")
    with pytest.raises(tumble.Error, match="^frame_cells: the cells along s and z, whole numbers >= 1, got 2.5"):
        tumble.fields(directory, frame="drum", frame_cells=(2.5, 1))
    with pytest.raises(tumble.Error, match="^frame_cells: .* for the drum frame"):
        tumble.fields(directory, frame_cells=(1, 4))


def test_fields_during_a_drum_run_refuse_bad_settings_before_any_work(tmp_path):
    """tumble.run_drum(fields=...) checks its settings before the run starts,
    naming the key, as tumble drum --fields does (tests/data/bad/cli)."""
    out = tmp_path / "run"
    with pytest.raises(tumble.Error, match="^fields: every: the time between the states must be a finite number > 0 s"):
        tumble.run_drum(out=out, fields={"every": 0.0}, **TINY_DRUM)
    with pytest.raises(tumble.Error, match="^fields: lo: three numbers X,Y,Z"):
        tumble.run_drum(out=out, fields={"lo": [0.0, 0.0]}, **TINY_DRUM)
    with pytest.raises(tumble.Error, match="^fields: colour: no such key"):
        tumble.run_drum(out=out, fields={"colour": "red"}, **TINY_DRUM)
    with pytest.raises(tumble.Error, match="^fields: frame: lab or drum"):
        tumble.run_drum(out=out, fields={"frame": "disc"}, **TINY_DRUM)
    with pytest.raises(tumble.Error, match="^fields: span: the middle part of the free surface"):
        tumble.run_drum(out=out, fields={"frame": "drum", "span": 2}, **TINY_DRUM)
    assert not out.exists()


def test_fields_during_a_drum_run_are_written_at_its_end(tmp_path):
    """tumble.run_drum(fields=...) writes DIR/fields/fields.csv with the states
    asked for (tests/unit/test_run_fields.cpp checks that they are those of
    tumble fields, bit for bit)."""
    d = tumble.run_drum(out=tmp_path / "run", fields={"from": 0.2, "every": 0.005, "samples": 3, "average": "z",
                                                      "cell": 1e-3, "format": "csv"}, **TINY_DRUM)
    f = pd.read_csv(d / "fields" / "fields.csv")
    assert (f["samples"] == 3).all()  # exact: a count
    assert not (d / "fields" / "fields.vti").exists()
    assert f["solid_fraction"].max() > 0.05  # the grains are on the grid (0.2 measured: 6 grains averaged along z)


def test_fields_during_a_drum_run_go_on_after_a_resume(tmp_path, tumble_binary):
    """A drum run stopped between its states keeps the fields' sums in its
    checkpoint: resumed, it writes the fields of the run that was not
    stopped, byte for byte (the same states summed in the same order)."""
    fields = {"from": 0.2, "every": 0.005, "samples": 3, "average": "z", "cell": 1e-3, "format": "csv"}
    whole = tumble.run_drum(out=tmp_path / "whole", fields=fields, **TINY_DRUM)
    dt = tumble.io.Run(whole).info["dt"]
    # The first state is the step that ends at 0.2 s, the next ones 0.005 s
    # apart: stop two steps after the second, resume for the third.
    stop = round(0.2 / dt) + round(0.005 / dt) + 2
    stopped = tumble.run_drum(out=tmp_path / "stopped", fields=fields, stop_at_step=stop, **TINY_DRUM)
    assert not (stopped / "fields").exists()
    done = subprocess.run([tumble_binary, "resume", "-q", str(stopped)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert (stopped / "fields" / "fields.csv").read_bytes() == (whole / "fields" / "fields.csv").read_bytes()
