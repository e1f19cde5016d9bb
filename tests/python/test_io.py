# SPDX-License-Identifier: MIT
"""Run directories read into numpy and pandas, and the analysis of
src/tumble/analysis called on what was read."""

import math
import shutil

import numpy as np
import pytest

import tumble


def test_drum_run_directory(tiny_drum):
    directory, samples = tiny_drum
    run = tumble.io.Run(directory)
    assert run.info["mode"] == "self" and [c["name"] for c in run.components] == ["left", "right"]
    assert list(run.drum_series.columns[:2]) == ["revolutions", "time"]
    assert set(run.profiles.columns) >= {"revolutions", "component", "bin", "z", "concentration"}
    assert len(run.time_series) >= len(samples)
    assert run.summary["components"][0]["grains"] + run.summary["components"][1]["grains"] == 6
    # The snapshots: 000000 at N = 0, then 10 per revolution.
    assert len(run.snapshot_files) == 5
    last = run.snapshot(-1)
    assert list(last["id"]) == sorted(last["id"]) and last.attrs["step"] == samples[-1].step
    arrays = tumble.io.snapshot_arrays(last)
    order = np.argsort(samples[-1].particles["ids"])
    np.testing.assert_array_equal(arrays["positions"], samples[-1].particles["positions"][order])


def test_band_files_of_a_run(tiny_drum):
    directory, _ = tiny_drum
    run = tumble.io.Run(directory)
    # A drum 3 cm long: 8 band bins of about 4 mm (docs/BAND-ANALYSIS.md).
    assert run.info["band_bins"] == 8
    N, phi = run.band_profile()
    assert phi.shape == (len(N), 8) and N[0] == 0.0 and len(N) >= 2
    _, grains = run.band_profile("grains")
    assert np.all(grains.sum(axis=1) == 6)
    assert len(run.bands) == len(N) and "dominant_wavelength" in run.bands.columns
    assert run.band_summary["species"] == "right" and run.band_summary["samples"] == len(N)
    assert run.summary["bands"]["bins"] == 8
    _, core = run.band_profile("bed_core_fraction")
    assert core.shape == phi.shape
    assert run.band_summary["radial_core"]["reference"] == "bed centroid"
    # Six shells per particle snapshot, holding every grain between them (exact: counts).
    shells = run.radial_shells
    assert list(shells.columns) == ["revolutions", "shell", "radius", "grains", "small_fraction"]
    per_snapshot = shells.groupby("revolutions")
    assert (per_snapshot.size() == 6).all() and (per_snapshot["grains"].sum() == 6).all()
    # The halves' boundary at z = 0: its blur is not measured in a drum 3 cm long (the windows keep 2 cm from
    # the caps), and no band_edges.csv is written.
    edges = run.band_summary["edges"]
    assert edges["method"] == "Boltzmann-Matano" and edges["boundaries"] == [] and not edges["determined"]
    assert [level["u"] for level in edges["levels"]] == [0.25, 0.5, 0.75] and edges["note"]
    with pytest.raises(FileNotFoundError):
        run.band_edges
    with pytest.raises(KeyError, match="bed_periphery_fraction"):
        run.band_profile("wall_fraction")  # the axis-referenced rows of an older tumble


def test_band_thresholds_of_analyze_drum(tiny_drum, tmp_path):
    directory, _ = tiny_drum
    copy = tmp_path / "run"
    shutil.copytree(directory, copy)
    tumble.analyze_drum(str(copy), band_z_enter=3.0, band_min_width=3)
    thresholds = tumble.io.Run(copy).band_summary["thresholds"]
    assert thresholds["z_enter"] == 3.0 and thresholds["min_width_bins"] == 3 and thresholds["z_leave"] == 2.0
    with pytest.raises(tumble.Error, match="band_z_leave must lie in 0 .. band_z_enter"):
        tumble.analyze_drum(str(copy), band_z_leave=5.0)


def test_tracks_hogg_and_msd_of_a_run(tiny_drum):
    directory, _ = tiny_drum
    run = tumble.io.Run(directory)
    revolutions, z = run.tracks(1)
    assert z.shape == (5, 3) and revolutions[0] == 0.0
    N, mean_z = run.mean_z(1)
    assert mean_z[0] == pytest.approx(z[0].mean(), abs=1e-12)
    fit = run.fit_hogg(1, first_revolution=0.0)
    assert fit["points"] == len(N) and not fit["determined"]  # too few samples: the fit says so
    msd = run.msd(1, first_revolution=0.0, block=0.2)
    assert set(msd) >= {"D", "interval", "lag", "msd", "determined", "note"} and not msd["determined"]
    assert msd["D"] is None and msd["block"] == 0.2  # not determined: None, as summary.json's null


def _same(a, b):
    """Equal, NaN (Python) and None (JSON null) alike where a number is undefined."""
    undefined = (lambda v: v is None or (isinstance(v, float) and math.isnan(v)))
    return (undefined(a) and undefined(b)) or a == b


def test_msd_of_a_run_is_the_summarys_D(short_drum, tmp_path):
    # One estimator, one answer: Run.msd(k) is summary.json's "msd" and
    # summary.txt's headline D, number for number (the same function, lags
    # and blocks), also after the run is analysed again with another start-up.
    copy = tmp_path / "run"
    shutil.copytree(short_drum, copy)
    for first in (None, 0.0):
        if first is not None:
            tumble.analyze_drum(str(copy), first_revolution=first)
        run = tumble.io.Run(copy)
        text = (copy / "summary.txt").read_text()
        headline = text.split("\n  shear model")[0]
        for k, component in enumerate(run.components):
            msd, kept = run.msd(k), run.summary["components"][k]["msd"]
            for key in ("D", "D_best_estimate", "D_lo", "D_hi", "determined", "note", "fit_lag_lo", "fit_lag_hi",
                        "blocks", "block", "first_revolution"):
                assert _same(msd[key], kept[key]), (first, k, key, msd[key], kept[key])
            assert _same(msd["interval"][0], kept["D_lo"]) and _same(msd["interval"][1], kept["D_hi"])
            name = component["name"]
            if msd["determined"]:
                assert f"    {name}: D = {msd['D']:.3e} m^2/rev, 95 % interval [" in headline
            else:
                assert msd["D"] is None and kept["D"] is None
                assert f"    {name}: D not determined: {msd['note']}" in headline
                if msd["D_best_estimate"] is not None:
                    assert f"(best estimate {msd['D_best_estimate']:.3e} m^2/rev)" in headline
        # With the start-up left in, the rotation holds a block: a D to compare, not only two Nones.
        if first == 0.0:
            assert all(run.msd(k)["D_best_estimate"] is not None or run.msd(k)["determined"] for k in range(2))


def test_hogg_fit_refuses_a_start_other_than_halves(tiny_drum, tmp_path):
    # Hogg's <z>(N) is that of two halves between caps; a band start's <z> mirrored by start_side would give a
    # D with no meaning (summary.json says "not applicable"), so the Python fit refuses as the C++ one does.
    directory, _ = tiny_drum
    copy = tmp_path / "run"
    shutil.copytree(directory, copy)
    info = (copy / "drum_run.toml").read_text()
    assert "arrangement = 'halves'" in info
    (copy / "drum_run.toml").write_text(info.replace("arrangement = 'halves'", "arrangement = 'bands'"))
    with pytest.raises(ValueError, match=r"not applicable to a start other than halves \(bands\)"):
        tumble.io.Run(copy).fit_hogg(1)
    (copy / "drum_run.toml").write_text(info.replace("periodic_axis = false", "periodic_axis = true"))
    with pytest.raises(ValueError, match="not applicable on a periodic axis"):
        tumble.io.Run(copy).fit_hogg(1)


def test_hogg_fit_finds_a_known_D():
    L, D = 0.12, 1.5e-5
    N = np.linspace(0.0, 30.0, 121)
    z = tumble.hogg_mean_position(D, N, L)
    assert z[0] == pytest.approx(L / 4)
    fit = tumble.fit_hogg(N, z, L)
    assert fit["determined"] and fit["D"] == pytest.approx(D, rel=1e-6)
    assert fit["amplitude"] == pytest.approx(L / 4, rel=1e-6)
    assert tumble.hogg_concentration(0.03, D, 0.0, L) == 1.0


def test_msd_finds_the_D_of_random_walkers():
    rng = np.random.default_rng(1)
    D, frames, grains, h = 2e-5, 161, 400, 0.125  # m^2/rev, frames 1/8 revolution apart
    steps = rng.normal(0.0, np.sqrt(2 * D * h), size=(frames - 1, grains))
    z = np.vstack([np.zeros(grains), np.cumsum(steps, axis=0)])
    estimate = tumble.axial_msd(np.arange(frames) * h, z)
    assert estimate["determined"]
    assert estimate["interval"][0] < D < estimate["interval"][1]
    assert estimate["D"] == pytest.approx(D, rel=0.1)
