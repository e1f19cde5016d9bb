# SPDX-License-Identifier: MIT
"""tools/plot_drum.py at the level of its figures: the colours of the species
are those of tools/palette.txt (which tumble render is built with), every log
axis carries at least two tick labels, legends sit beside the data, and a
sweep's undetermined D values are drawn apart from the determined ones.
Run by ctest (tests/CMakeLists.txt) or: python3 tests/python/test_plot_drum.py"""

import os
import sys
import tempfile
import unittest

try:
    import numpy as np
    import matplotlib  # noqa: F401
except ImportError as missing:
    print(f"skipped: {missing}")
    sys.exit(77)

TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools")
sys.path.insert(0, TOOLS)
import plot_drum  # noqa: E402


class Capture(plot_drum.Writer):
    """A writer that keeps the figures instead of saving them."""

    def __init__(self):
        super().__init__("unused")
        self.figures = {}

    def save(self, fig, name):
        fig.canvas.draw()
        self.figures[name] = fig


def labelled_ticks(axis):
    lo, hi = sorted(axis.get_view_interval())
    formatter = axis.get_major_formatter()
    locs = [t for t in axis.get_majorticklocs() if lo <= t <= hi]
    return [formatter(t) for t in locs if formatter(t)]


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def tiny_run(directory, energies):
    """A run directory with the files fig_energy and fig_depth read."""
    write(os.path.join(directory, "drum_run.toml"),
          'mode = "two-component"\nomega = 5.0\nfroude = 0.1\n'
          '[[component]]\nname = "material-1"\nstart_side = -1.0\n'
          '[[component]]\nname = "material-2"\nstart_side = 1.0\n')
    rows = ["revolutions,kinetic_per_grain_material-1,kinetic_per_grain_material-2,"
            "kinetic_energy_material-1,kinetic_energy_material-2"]
    for k, (e1, e2) in enumerate(energies):
        rows.append(f"{k * 0.5},{e1},{e2},{e1 * 229},{e2 * 771}")
    write(os.path.join(directory, "drum_series.csv"), "\n".join(rows) + "\n")
    write(os.path.join(directory, "depth_mobility.csv"),
          "layer,depth_lo,depth_hi,msd_per_rev_material-1,share_material-1,occupancy_material-1,"
          "msd_per_rev_material-2,share_material-2,occupancy_material-2\n"
          "0,0,1,3.1e-5,0.6,0.3,3.4e-5,0.55,0.35\n"
          "1,1,2,2.2e-5,0.3,0.3,2.6e-5,0.3,0.3\n"
          "2,2,3,1.9e-5,0.1,0.4,2.0e-5,0.15,0.35\n")
    return plot_drum.Run(directory)


class Figures(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        plot_drum.plt.close("all")
        self.tmp.cleanup()

    def test_species_colours_are_the_palette_shared_with_the_movie(self):
        with open(os.path.join(TOOLS, "palette.txt")) as f:
            palette = ["#" + line.split()[0] for line in f if line.strip() and not line.startswith("#")]
        self.assertGreaterEqual(len(palette), 2)
        self.assertEqual(plot_drum.COLOURS, palette)
        # fig_energy draws component k in palette colour k.
        run = tiny_run(self.dir, [(2.0e-7, 1.0e-7), (2.5e-7, 1.2e-7), (3.0e-7, 1.1e-7)])
        w = Capture()
        plot_drum.fig_energy(run, w)
        top = w.figures["fig_energy"].axes[0]
        colours = [plot_drum.matplotlib.colors.to_hex(line.get_color()) for line in top.get_lines()]
        self.assertEqual(colours[:2], palette[:2])

    def test_log_axes_carry_two_labels_even_over_a_narrow_range(self):
        # Energies within a fraction of a decade: one power of ten at most.
        run = tiny_run(self.dir, [(2.1e-7, 1.0e-7), (2.6e-7, 1.2e-7), (3.0e-7, 1.1e-7), (2.4e-7, 1.3e-7)])
        w = Capture()
        plot_drum.fig_energy(run, w)
        plot_drum.fig_depth(run, w)
        top, bottom = w.figures["fig_energy"].axes[:2]
        left = w.figures["fig_depth"].axes[0]
        for name, axis in (("energy per grain", top.yaxis), ("energy ratio", bottom.yaxis),
                           ("depth <dz^2>", left.xaxis)):
            self.assertEqual(axis.get_scale(), "log", name)
            self.assertGreaterEqual(len(labelled_ticks(axis)), 2, f"{name}: {labelled_ticks(axis)}")

    def test_legends_beside_the_data(self):
        run = tiny_run(self.dir, [(2.0e-7, 1.0e-7), (2.5e-7, 1.2e-7), (3.0e-7, 1.1e-7)])
        w = Capture()
        plot_drum.fig_energy(run, w)
        fig = w.figures["fig_energy"]
        renderer = fig.canvas.get_renderer()
        for ax in fig.axes[:2]:
            legend = ax.get_legend().get_window_extent(renderer)
            self.assertGreaterEqual(legend.x0, ax.get_window_extent(renderer).x1)

    def test_kymograph_in_the_species_colours_with_the_merges(self):
        run = tiny_run(self.dir, [(2.0e-7, 1.0e-7), (2.5e-7, 1.2e-7)])
        bins, header = 4, "revolutions,quantity,bin_0,bin_1,bin_2,bin_3"
        rows = [header]
        # The first sample from a tumble before the radial core about the
        # bed's centre (core and wall from the axis): not in the core's map.
        for n, phi, core, outer in ((0.0, "1,0,1,0", "core_fraction", "wall_fraction"),
                                    (0.25, "1,1,1,0", "bed_core_fraction", "bed_periphery_fraction")):
            rows += [f"{n},small_fraction,{phi}", f"{n},grains,5,5,5,5", f"{n},small_grains,5,0,5,0",
                     f"{n},{core},{phi}", f"{n},{outer},0,0,1,0"]
        write(os.path.join(self.dir, "band_profile.csv"), "\n".join(rows) + "\n")
        write(os.path.join(self.dir, "bands.csv"),
              "revolutions,bands,rich_bands,mean,contrast,band_contrast,dominant_wavelength,dominant_share,"
              "core_fraction,periphery_fraction,core_excess,left_end_rich,left_end_fraction,right_end_rich,"
              "right_end_fraction\n"
              "0,4,2,0.5,0.5,1,0.06,0.9,0.5,0.5,0,1,1,0,0\n"
              "0.25,2,1,0.75,0.37,1,0.12,0.8,0.75,0.75,0,1,1,0,0\n")
        write(os.path.join(self.dir, "bands.json"),
              '{"species": "material-2", "other": "material-1", "events": '
              '[{"revolutions": 0.25, "kind": "merge", "z": -0.015}], "radial_core": {"blocks": '
              '[{"from": 0, "to": 1, "revolutions": 1, "core_excess": 0.1, "core_excess_lo": null, '
              '"core_excess_hi": null}]}}')
        write(os.path.join(self.dir, "band_edges.csv"),
              "boundary,z_start,revolutions,matano,D_u25,D_u50,D_u75\n"
              "0,-0.02,15,-0.02,1e-5,2e-5,3e-5\n0,-0.02,25,-0.02,1.1e-5,2.1e-5,nan\n"
              "1,0.02,15,0.02,1e-5,2e-5,3e-5\n1,0.02,25,0.02,1.2e-5,1.9e-5,2.9e-5\n")
        w = Capture()
        plot_drum.fig_bands(run, w)
        blur = w.figures["fig_bands"].axes[8]  # D of the boundaries: 3 compositions x 2 boundaries
        self.assertEqual(len(blur.get_lines()), 6)
        self.assertEqual(blur.get_yscale(), "log")
        self.assertEqual(len(blur.get_lines()[4].get_xdata()), 1)  # u = 0.75 of boundary 0 (by level, then boundary): one finite D
        kymo = w.figures["fig_bands"].axes[0]
        mesh = kymo.collections[0]
        self.assertEqual(mesh.get_array().size, 2 * bins)
        colour = plot_drum.matplotlib.colors.to_hex
        self.assertEqual(colour(mesh.cmap(1.0)), plot_drum.COLOURS[1])
        self.assertEqual(colour(mesh.cmap(0.0)), plot_drum.COLOURS[0])
        merges = [line for line in kymo.get_lines() if line.get_marker() == "x"]
        self.assertEqual(len(merges), 1)
        core = w.figures["fig_bands"].axes[1].collections[0].get_array()
        self.assertEqual(core.size, bins)  # the one sample measured about the bed's centre
        self.assertEqual(list(core), [1, 1, 0, 0])
        self.assertEqual(w.figures["fig_bands"].axes[2].get_xscale(), "log")  # the band count

    def test_sweep_draws_undetermined_d_apart(self):
        table = os.path.join(self.dir, "sweep.csv")
        write(table, "mode,omega,froude,seed,D_left,D_stderr_left,determined_left,"
                     "D_right,D_stderr_right,determined_right,status\n"
                     "self,2,0.0163,1,1.0e-5,2e-6,true,1.2e-5,2e-6,true,finished\n"
                     "self,2,0.0163,2,1.1e-5,2e-6,true,0.9e-5,2e-6,true,finished\n"
                     "self,5,0.102,1,2.0e-5,3e-6,true,2.4e-5,3e-6,true,finished\n"
                     "self,5,0.102,2,9.0e-5,8e-5,false,2.2e-5,3e-6,true,finished\n")

        class Args:
            out = None

        Args.table = table
        saved = plot_drum.Writer
        plot_drum.Writer = lambda outdir: Capture()
        try:
            w = plot_drum.do_sweep(Args)
        finally:
            plot_drum.Writer = saved
        ax = w.figures["fig3_self_D_vs_omega"].axes[0]
        labels = [t.get_text() for t in ax.get_legend().get_texts()]
        self.assertTrue(any("left" in t and "not determined" in t for t in labels), labels)
        self.assertFalse(any("right" in t and "not determined" in t for t in labels), labels)
        # The open marker sits at the undetermined value; the mean at omega = 5 leaves it out.
        open_markers = [line for line in ax.get_lines() if line.get_markerfacecolor() == "none"]
        self.assertEqual(len(open_markers), 1)
        self.assertAlmostEqual(float(open_markers[0].get_ydata()[0]), 9.0e-5)
        means = [c for c in ax.containers if "started left" in c.get_label()]
        self.assertEqual(len(means), 1)
        np.testing.assert_allclose(means[0].lines[0].get_ydata(), [1.05e-5, 2.0e-5])


    def test_flowing_layer_draws_the_surface_it_was_given(self):
        run = tiny_run(self.dir, [(2.0e-7, 1.0e-7), (2.5e-7, 1.2e-7)])
        w = Capture()
        plot_drum.fig_flowing_layer(run, w)  # no fields yet: skipped with a note
        self.assertEqual(w.skipped, ["fig_flowing_layer"])
        fields = os.path.join(self.dir, "flowing_layer")
        os.makedirs(fields)
        surface = dict(angle_of_repose_deg=30.0, surface_level_m=-0.01, surface_half_length_m=0.03, span=0.5,
                       bed_solid_fraction=0.6, surface_solid_fraction=0.3, surface_velocity_m_per_s=0.1,
                       layer_thickness_m=0.004, layer_thickness_diameters=2.0, mean_diameter_m=0.002,
                       fit_columns=20, fit_iterations=3)
        write(os.path.join(fields, "drum_frame.json"), plot_drum.json.dumps(surface))
        rows = ["x,y,z,solid_fraction,velocity_x,velocity_y"]
        for y in (-0.02, -0.01, 0.0):
            for x in (-0.02, 0.0, 0.02):
                rows.append(f"{x},{y},0,{0.6 if y < -0.005 else 0.0},0.1,0.0")
        write(os.path.join(fields, "fields.csv"), "\n".join(rows) + "\n")
        rows = ["s,d,z,solid_fraction,velocity_s,shear_rate,pressure,friction,inertial_number"]
        for d in (-0.002, 0.0, 0.002, 0.004, 0.006):
            rows.append(f"0,{d},0,{0.0 if d < 0 else 0.6},{0.1 - 25 * d},25,{1000 * max(d, 0)},0.5,0.2")
        write(os.path.join(fields, "profile.csv"), "\n".join(rows) + "\n")
        plot_drum.fig_flowing_layer(run, w)
        cut = w.figures["fig_flowing_layer"].axes[0]
        # The surface's solid line (the part averaged): its points lie on
        # n . r = level, n = (-sin a, cos a), and it spans half the chord.
        line = [ln for ln in cut.get_lines() if ln.get_linestyle() == "-"][0]
        x, y = np.asarray(line.get_xdata()) * 1e-3, np.asarray(line.get_ydata()) * 1e-3
        a = np.radians(30.0)
        np.testing.assert_allclose(-np.sin(a) * x + np.cos(a) * y, -0.01, atol=1e-12)
        self.assertAlmostEqual(float(np.hypot(x[1] - x[0], y[1] - y[0])), 0.03, places=12)
        # Six profiles against depth, the surface's velocity panel first.
        self.assertEqual(len(w.figures["fig_flowing_layer"].axes), 1 + 1 + 6)  # the cut, its colour bar, 6 panels


if __name__ == "__main__":
    unittest.main()
