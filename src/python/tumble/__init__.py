# SPDX-License-Identifier: MIT
"""tumble: discrete-element simulation of visco-elastic spheres and the
rotating-drum experiment of Kohring's paper, from Python.

    import tumble
    sim = tumble.Simulation(tumble.Scenario.from_file("examples/demo.toml"))
    sim.run(steps=1000)
    x = sim.positions[sim.by_id]          # N x 3, in global-id order

The particle arrays of a Simulation are read-only numpy views of the
engine's memory (no copy). The engine re-sorts its particles in space, so
their order changes between steps: follow grains by `ids` (or index with
`by_id`), and read an array again after stepping instead of keeping a view.

The drum experiment: tumble.run_drum(...) (the protocol of `tumble drum`,
with a callback at every sample); its settings are tumble drum's options.
A sweep over speeds, modes and seeds: tumble.run_sweep(sweep_file) (that of
`tumble sweep`). Run directories: tumble.io.Run(directory). README.md,
section "Python".
"""

import copy
import os
import pathlib
import shutil
import tomllib

from tumble._core import (  # noqa: F401
    BlewUp,
    DrumSettings,
    Error,
    Scenario,
    Simulation,
    analyze_drum,
    axial_msd,
    coarse_grain,
    drum_tracks,
    fields,
    fit_hogg,
    hogg_concentration,
    hogg_mean_position,
)
from tumble._core import version as __version__  # noqa: F401
from tumble import _core, _paths

# tumble drum's options -> (table, key) of a drum settings file (docs/DRUM.md,
# examples/drum_*.toml).
DRUM_OPTIONS = {
    "length": ("drum", "length"),
    "diameter": ("drum", "diameter"),
    "wall_radius": ("drum", "wall_radius"),
    "periodic_axis": ("drum", "periodic_axis"),
    "walls": ("drum", "walls"),
    "mesh": ("drum", "mesh"),
    "mesh_scale": ("drum", "mesh_scale"),
    "cap_friction": ("drum", "cap_friction"),
    "mode": ("fill", "mode"),
    "arrangement": ("fill", "arrangement"),
    "bands": ("fill", "bands"),
    "band_widths": ("fill", "band_widths"),
    "boundaries": ("fill", "boundaries"),
    "ends": ("fill", "ends"),
    "small_volume_fraction": ("fill", "small_volume_fraction"),
    "grains": ("fill", "grains"),
    "fill": ("fill", "fill_fraction"),
    "seed": ("fill", "seed"),
    "omega": ("rotation", "omega"),
    "rpm": ("rotation", "rpm"),
    "froude": ("rotation", "froude"),
    "revolutions": ("rotation", "revolutions"),
    "until_band_change": ("rotation", "until_band_change"),
    "spin_up": ("rotation", "spin_up_time"),
    "samples": ("measure", "samples_per_revolution"),
    "bins": ("measure", "profile_bins"),
    "band_bins": ("measure", "band_bins"),
    "snapshots": ("measure", "snapshots_per_revolution"),
    "settle_speed": ("settle", "speed"),
    "settle_max_time": ("settle", "max_time"),
    "dt": ("time_step", "dt"),
    "skin": ("neighbor", "skin"),
    "shear": ("model", "shear"),
    "friction_normal": ("model", "friction_normal"),
    "tangential_stiffness": ("model", "tangential_stiffness"),
    "surface_energy": ("model", "surface_energy"),
    "out": ("output", "directory"),
}
# The drum's own materials: the file's top-level [[material]] and [[pair]]
# tables (lists of dicts, as in a scenario) and its [materials] table
# (a dict: large, small, wall, cap naming them; docs/DRUM.md, "Materials").
DRUM_TABLES = ("material", "pair", "materials")
# Options that replace each other, as on the command line.
_ALTERNATIVES = (("grains", "fill"), ("omega", "rpm", "froude"))


def scenario(source, base_dir=".", max_memory_gib=0.0):
    """A Scenario from a file (path) or a dict laid out as the file; one whose
    run is estimated to need more than max_memory_gib GiB (0: half the
    machine's memory) is refused before any sphere is made."""
    if isinstance(source, dict):
        return Scenario.from_dict(source, base_dir=base_dir, max_memory_gib=max_memory_gib)
    return Scenario.from_file(source, max_memory_gib=max_memory_gib)


def drum_settings(config=None, **options):
    """The drum's settings: tumble drum's defaults, then `config` (a drum
    settings file, or a dict laid out as one), then the options, named as
    tumble drum's (DRUM_OPTIONS: mode, grains, fill, omega, rpm, froude,
    revolutions, length, diameter, walls, seed, shear, out, ...), and the
    drum's own materials as the file's tables (DRUM_TABLES: material=[{...},
    ...], pair=[{...}, ...], materials={"large": ..., "small": ...,
    "wall": ...}), each replacing the config's. Checked as the command line
    checks them (tumble.Error)."""
    if isinstance(config, DrumSettings):
        if options:
            raise TypeError("drum_settings: options apply to a file or a dict, not to DrumSettings")
        return config
    if config is not None and not isinstance(config, dict) and not options:
        return _core.load_drum_settings(config)
    if isinstance(config, dict):
        table, name = copy.deepcopy(config), "<dict>"
    elif config is not None:
        with open(config, "rb") as file:
            table, name = tomllib.load(file), f"{os.fspath(config)} and the options"
    else:
        table, name = {}, "<options>"
    for option, value in options.items():
        if option in DRUM_TABLES:
            table[option] = copy.deepcopy(value)
            continue
        if option not in DRUM_OPTIONS:
            raise TypeError(f"drum_settings: unknown setting {option!r}; known: "
                            f"{', '.join([*DRUM_OPTIONS, *DRUM_TABLES])}")
        for group in _ALTERNATIVES:
            if option in group:
                for other in group:
                    section, key = DRUM_OPTIONS[other]
                    table.get(section, {}).pop(key, None)
        section, key = DRUM_OPTIONS[option]
        table.setdefault(section, {})[key] = value
    return _core.drum_settings_from_dict(table, name)


def drum_scenario(config=None, allow_unsafe_dt=False, **options):
    """The paper's drum of these settings as a Scenario, filled and at rest
    (the wall is motion 0: Simulation.set_motion(0, omega) turns it)."""
    return Scenario.drum(drum_settings(config, **options), allow_unsafe_dt=allow_unsafe_dt)


def run_drum(config=None, *, on_sample=None, threads=1, force=False, quiet=True, checkpoint_every_revolutions=1.0,
             checkpoint_every_minutes=10.0, stop_at_step=0, allow_unsafe_dt=False, max_memory_gib=0.0, fields=None,
             **options):
    """The drum experiment of `tumble drum` (docs/DRUM.md) into the settings'
    output directory (option `out`): settle, turn, sample, photograph,
    analyse; no figures (tumble plot DIR draws them).

    on_sample(sample) is called after every sample is written (N = 0, then
    `samples` per revolution, and the end), with sample.revolutions, .time,
    .step, .angle_of_repose, .fill_fraction, .bed_centre, .components (per
    tag: grains, mass, mean_z, mean_z_stderr, kinetic_energy,
    kinetic_per_grain, concentration) and .particles (copies of the particle
    arrays, in the store's order: follow grains by 'ids'). An exception it
    raises ends the run; the directory keeps its newest checkpoint (tumble
    resume DIR continues it). Ctrl-C writes a checkpoint, stops the run and
    raises KeyboardInterrupt.

    fields: a dict of the keys of `tumble drum --fields` (every, from,
    samples, lo, hi, cell, cells, average, kernel, width, format, frame,
    span; lo, hi and cells as sequences of three), e.g. {"every": 0.01,
    "from": 1.0, "average": "z"}: coarse-grained fields averaged during the
    run into DIR/fields; with "frame": "drum", the cross-section into
    DIR/flowing_layer with the drum frame's profile (profile.csv,
    drum_frame.json) found from it at the end (docs/FIELDS.md, "During a
    run"); bad ones raise tumble.Error before any work.

    Returns the run directory (pathlib.Path); read it with tumble.io.Run."""
    settings = drum_settings(config, **options)
    _, directory = _core.run_drum(settings, on_sample=on_sample, threads=threads, force=force, quiet=quiet,
                                  checkpoint_every_revolutions=checkpoint_every_revolutions,
                                  checkpoint_every_minutes=checkpoint_every_minutes, stop_at_step=stop_at_step,
                                  allow_unsafe_dt=allow_unsafe_dt, max_memory_gib=max_memory_gib,
                                  fields=_field_items(fields))
    return pathlib.Path(directory)


def _field_items(fields):
    """The KEY=VALUE items of a dict of fields' settings (sequences joined by commas)."""
    def text(value):
        if isinstance(value, (list, tuple)):
            return ",".join(repr(float(v)) for v in value)
        return repr(value) if isinstance(value, float) else str(value)
    return [f"{key}={text(value)}" for key, value in (fields or {}).items()]

def find_tumble_binary():
    """The tumble program that run_sweep's points run: $TUMBLE_BINARY if it is
    set; else this package's own if it exists (installed: the one installed
    beside it, PREFIX/bin/tumble; in build/python: the build tree's); else
    tumble on the PATH. FileNotFoundError naming what was tried if none."""
    if os.environ.get("TUMBLE_BINARY"):
        tried = {"TUMBLE_BINARY": os.environ["TUMBLE_BINARY"]}
    else:
        tried = {"this package's": pathlib.Path(__file__).parent / _paths.TUMBLE_PROGRAM,
                 "on the PATH": shutil.which("tumble")}
    for path in tried.values():
        if path and os.path.isfile(path) and os.access(path, os.X_OK):
            return pathlib.Path(path).resolve()
    raise FileNotFoundError("tumble: no tumble program for the sweep's points; tried "
                            + "; ".join(f"{where}: {os.fspath(path) if path else 'none'}"
                                        for where, path in tried.items())
                            + " (set TUMBLE_BINARY, or pass tumble_binary)")


def _name_the_program():
    """Messages that suggest a command (continue with: PROGRAM resume DIR)
    name this package's tumble program where there is one."""
    try:
        _core.set_program_name(os.fspath(find_tumble_binary()))
    except FileNotFoundError:
        pass


_name_the_program()


def sweep_points(sweep_file, out=None):
    """The points of a sweep file (docs/SWEEP.md) in plan order, each a dict:
    name, mode, omega (rad/s), seed, directory (under `out`, default the
    file's [output] directory) and state (pending, unfinished, failed,
    finished), as `tumble sweep --list`; runs nothing."""
    return _core.sweep_points(os.fspath(sweep_file), os.fspath(out or ""))


def run_sweep(sweep_file, out=None, jobs=0, quiet=True, tumble_binary=None):
    """The sweep of `tumble sweep` (docs/SWEEP.md): every point of the sweep
    file a `tumble drum` child process in out/points/NAME (out: default the
    file's [output] directory), `jobs` at once (0: the cores); finished
    points are skipped and interrupted ones resumed; then out/sweep.csv and
    out/sweep_summary.csv (tumble.io.read_csv reads them). No figures
    (python3 tools/plot_drum.py sweep out/sweep.csv draws them).

    tumble_binary: the program the points run (default: find_tumble_binary()).
    Ctrl-C stops the points with checkpoints (the next call resumes them) and
    raises KeyboardInterrupt.

    Returns a dict: directory, points, with_results (points with numbers in
    sweep.csv), failed (points that failed in this call; each leaves its
    log.txt), exit_code (that of tumble sweep: 0, or 1 if a point has no
    results)."""
    return _core.run_sweep(os.fspath(sweep_file), os.fspath(out or ""), jobs, quiet,
                           os.fspath(tumble_binary or find_tumble_binary()))


from tumble import io  # noqa: E402,F401  (tumble.io.Run: run directories)
