# SPDX-License-Identifier: MIT
"""Reading a run directory of `tumble run` or `tumble drum` (docs/DRUM.md,
"Files of a run directory") into pandas data frames and numpy arrays.

    run = tumble.io.Run("drum-out")
    run.drum_series["mean_z_material_1"]      # a pandas Series
    run.snapshot(-1)                           # the last particle snapshot, by id
    run.msd(0)                                 # D of component 0 from its grains' axial MSD

Column names are read with '-' as '_' (mean_z_material-1 -> mean_z_material_1),
so that they are valid identifiers and the same whichever way a version of
tumble wrote them; comment lines (#) are skipped.
"""

import json
import pathlib
import re
import tomllib

import numpy as np

from tumble import _core


def read_csv(path):
    """A CSV file of a run as a pandas DataFrame (comments skipped, '-' in
    column names as '_'); numbers read back to the very doubles written."""
    import pandas

    frame = pandas.read_csv(path, comment="#", float_precision="round_trip")
    frame.columns = [name.strip().replace("-", "_") for name in frame.columns]
    return frame


def read_snapshot(path):
    """A particle snapshot (snapshots/NNNNNN.csv) as a DataFrame in global-id
    order, with its time (s) and step in frame.attrs: from its time and step
    columns, or from the first line "# time = T s, step = S" of snapshots
    written before it had them."""
    frame = read_csv(path)
    if {"time", "step"} <= set(frame.columns) and len(frame):
        frame.attrs["time"], frame.attrs["step"] = float(frame["time"].iloc[0]), int(frame["step"].iloc[0])
        return frame
    with open(path) as file:
        header = re.search(r"time\s*=\s*([^\s,]+).*?step\s*=\s*(\d+)", file.readline())
    if header:
        frame.attrs["time"], frame.attrs["step"] = float(header.group(1)), int(header.group(2))
    return frame


def snapshot_arrays(frame):
    """The numpy arrays of a snapshot frame, named as Simulation's: ids,
    positions, velocities, angular_velocities (N x 3), radii, tags."""
    return {
        "ids": frame["id"].to_numpy(),
        "positions": frame[["x", "y", "z"]].to_numpy(),
        "velocities": frame[["vx", "vy", "vz"]].to_numpy(),
        "angular_velocities": frame[["wx", "wy", "wz"]].to_numpy(),
        "radii": frame["radius"].to_numpy(),
        "tags": frame["tag"].to_numpy(),
    }


class Run:
    """A run directory. Each table is read when first asked for."""

    def __init__(self, directory):
        self.directory = pathlib.Path(directory)
        if not self.directory.is_dir():
            raise FileNotFoundError(f"{self.directory}: not a run directory")
        self._tables = {}

    def table(self, name):
        """Any CSV file of the run (e.g. 'depth_mobility.csv') as a DataFrame."""
        if name not in self._tables:
            self._tables[name] = read_csv(self.directory / name)
        return self._tables[name]

    @property
    def time_series(self):
        """time_series.csv: energies, contacts, largest overlap per sample."""
        return self.table("time_series.csv")

    @property
    def drum_series(self):
        """drum_series.csv: per sample N, time, angle of repose, and per component <z> and energies."""
        return self.table("drum_series.csv")

    @property
    def profiles(self):
        """profiles.csv: C(z, N) per sample, component and bin."""
        return self.table("profiles.csv")

    def band_profile(self, quantity="small_fraction"):
        """(N, values[sample, bin]) of band_profile.csv, numpy arrays: the
        quantity small_fraction (phi, the kymograph C(z, N)), grains,
        small_grains, bed_core_fraction or bed_periphery_fraction (phi in the
        inner and outer third about the bed's centre) per axial bin
        (docs/BAND-ANALYSIS.md); bin b is centred at z = -L/2 + (b + 1/2) L / bins.
        Samples written by an earlier tumble have core_fraction and
        wall_fraction instead, ranked from the drum axis: each quantity has
        the samples that hold it."""
        frame = self.table("band_profile.csv")
        rows = frame[frame["quantity"] == quantity]
        if rows.empty:
            present = ", ".join(sorted(set(frame["quantity"])))
            raise KeyError(f"band_profile.csv has no quantity {quantity!r} (it has {present})")
        columns = [c for c in frame.columns if c.startswith("bin_")]
        return rows["revolutions"].to_numpy(), rows[columns].to_numpy(dtype=float)

    @property
    def bands(self):
        """bands.csv: per band sample the band count, contrast, dominant wavelength, radial core (core and
        periphery about the bed's centre), end bands."""
        return self.table("bands.csv")

    @property
    def band_positions(self):
        """band_positions.csv: per band sample, one row per band (species, edges, composition)."""
        return self.table("band_positions.csv")

    @property
    def band_edges(self):
        """band_edges.csv: per boundary of the start and block of 10 revolutions, the Matano plane and the
        interdiffusion D at three compositions, D_u25, D_u50, D_u75 (docs/BAND-ANALYSIS.md, Boltzmann-Matano)."""
        return self.table("band_edges.csv")

    @property
    def radial_shells(self):
        """radial_shells.csv: per particle snapshot, the small grains' volume
        fraction in each of 6 shells of equal grain volume about the bed's
        centre (revolutions, shell from 0 innermost, radius, grains,
        small_fraction; docs/BAND-ANALYSIS.md, "Radial shells")."""
        return self.table("radial_shells.csv")

    @property
    def band_summary(self):
        """bands.json: the thresholds, the final bands, the events (merges), the radial core per block of N."""
        return json.loads((self.directory / "bands.json").read_text())

    @property
    def axial_msd_table(self):
        """axial_msd.csv: the grains' axial MSD against lag, per component."""
        return self.table("axial_msd.csv")

    @property
    def summary(self):
        """summary.json: the analysis (undefined numbers are None)."""
        return json.loads((self.directory / "summary.json").read_text())

    @property
    def info(self):
        """What was run: drum_run.toml of a drum run, run.json of tumble run."""
        drum = self.directory / "drum_run.toml"
        if drum.exists():
            with open(drum, "rb") as file:
                return tomllib.load(file)
        return json.loads((self.directory / "run.json").read_text())

    @property
    def components(self):
        """The drum's components (name, grains, mass, start_side), by tag."""
        return self.info["component"]

    @property
    def snapshot_files(self):
        """The particle snapshots, snapshots/NNNNNN.csv, in order."""
        return sorted((self.directory / "snapshots").glob("*.csv"))

    def snapshot(self, k=-1):
        """Particle snapshot k (negative counts from the last) as a DataFrame in id order."""
        return read_snapshot(self.snapshot_files[k])

    def mean_z(self, component):
        """(N, <z>) of a drum component, numpy arrays (revolutions, m)."""
        name = self.components[component]["name"].replace("-", "_")
        return self.drum_series["revolutions"].to_numpy(), self.drum_series[f"mean_z_{name}"].to_numpy()

    def fit_hogg(self, component, first_revolution=1.0, drift=False, fixed_D=None):
        """The Hogg fit with the amplitude free (tumble.fit_hogg) of a drum
        component's <z>(N), mirrored if it started at z < 0. Hogg's solution
        is that of two halves between end caps: for another start (bands,
        boundaries, mixed) or a periodic axis this raises ValueError, as
        summary.json's fit says "not applicable"."""
        why = _core.hogg_not_applicable(self.directory)
        if why:
            raise ValueError(f"{self.directory}: Hogg fit {why}")
        N, z = self.mean_z(component)
        side = self.components[component]["start_side"]
        return _core.fit_hogg(N, side * z, self.info["inner_length"], first_revolution=first_revolution,
                              drift=drift, fixed_D=fixed_D)

    def tracks(self, component):
        """(revolutions, z[frame, grain]) of a drum component's grains in the snapshots from N = 0."""
        revolutions, z = _core.drum_tracks(self.directory, component)
        return np.asarray(revolutions), np.asarray(z)

    def msd(self, component, first_revolution=None, block=None):
        """D of a drum component from its grains' axial MSD: the estimator,
        lag window and blocks of the run's summary (summary.json's "msd",
        summary.txt's headline D), so the same number with its 95 %
        interval. A dict: D (None when not determined), D_best_estimate
        (the value of one not determined), D_lo, D_hi and interval (its 95 %
        interval), determined, note, fit_lag_lo and fit_lag_hi (the lags
        fitted), blocks, block (revolutions per block), first_revolution,
        lag and msd (the pooled MSD against lag, revolutions and m^2).
        first_revolution: the start-up left out (None: the summary's, else
        1); block: revolutions per block (None: the run's own choice)."""
        if first_revolution is None:
            summary = self.directory / "summary.json"
            msd = {}
            if summary.exists():
                components = self.summary.get("components") or []
                if component < len(components):
                    msd = components[component].get("msd") or {}
            first_revolution = msd.get("first_revolution", 1.0)
        return _core.drum_msd(self.directory, component, first_revolution=first_revolution, block=block)
