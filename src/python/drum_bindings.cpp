// SPDX-License-Identifier: MIT
// The drum experiment (experiments/drum.hpp) for Python: its settings, the
// protocol with a callback at every sample, and the analysis of a run.
#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "experiments/drum.hpp"
#include "experiments/limits.hpp"
#include "io/drum_config.hpp"
#include "io/toml_reader.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace tumble::python {

namespace fs = std::filesystem;

namespace {

py::object namespace_of(py::dict fields) { return py::module_::import("types").attr("SimpleNamespace")(**fields); }

// What the callback receives at a sample: the measurement (drum_series.csv,
// profiles.csv) and copies of the particle arrays, in the store's order.
py::object sample_of(const experiments::DrumSample& s) {
    py::list components;
    for (const analysis::ComponentState& c : s.state.components)
        components.append(namespace_of(py::dict(
            py::arg("grains") = c.grains, py::arg("mass") = c.mass, py::arg("mean_z") = c.mean_z,
            py::arg("mean_z_stderr") = c.mean_z_stderr, py::arg("kinetic_energy") = c.kinetic_energy,
            py::arg("kinetic_per_grain") = c.kinetic_per_grain,
            py::arg("concentration") = array_of(c.concentration, py::handle()))));
    py::dict particles;
    for_each_particle_field([&](const char* name, auto field, const char*) {
        particles[name] = array_of(s.simulation.particles().*field, py::handle());
    });
    const Vec3& centre = s.state.bed_centre;
    return namespace_of(py::dict(py::arg("revolutions") = s.revolutions, py::arg("time") = s.simulation.time(),
                                 py::arg("step") = s.simulation.step_count(),
                                 py::arg("angle_of_repose") = s.state.angle_of_repose,
                                 py::arg("fill_fraction") = s.state.fill_fraction,
                                 py::arg("bed_centre") = std::array<double, 3>{centre.x, centre.y, centre.z},
                                 py::arg("components") = components, py::arg("particles") = particles));
}

}  // namespace

void bind_drum(py::module_& m) {
    py::class_<io::DrumSettings>(m, "DrumSettings", "Settings of the drum experiment (tumble.drum_settings)")
        .def_readonly("mode", &io::DrumSettings::mode,
                      "two-component (large and small grains) or self (one kind, tagged by the half it started in)")
        .def_property_readonly("grains", &io::DrumSettings::grain_count, "the number of grains it makes")
        .def_property_readonly("omega", &io::DrumSettings::omega, "rad/s")
        .def_readonly("revolutions", &io::DrumSettings::revolutions, "revolutions of the rotation")
        .def_readonly("until_band_change", &io::DrumSettings::until_band_change,
                      "end early once the band count has differed from the start's this many revolutions (0: off)")
        .def_readonly("seed", &io::DrumSettings::seed, "seed of the fill")
        .def_property_readonly("length", [](const io::DrumSettings& s) { return s.geometry.length; }, "m")
        .def_property_readonly("diameter", [](const io::DrumSettings& s) { return s.geometry.diameter; }, "m")
        .def_property_readonly("wall_radius", [](const io::DrumSettings& s) { return s.geometry.wall_radius; }, "m")
        .def_property_readonly("periodic_axis", [](const io::DrumSettings& s) { return s.geometry.periodic_axis; },
                               "no end caps: the axis is periodic, the length its period")
        .def_property_readonly("walls",
                               [](const io::DrumSettings& s) { return keyword_of(drum_wall_kinds, s.geometry.walls); },
                               "particles (a wall of spheres, the paper's) or smooth (a cylinder and two discs)")
        .def_property_readonly(
            "materials",
            [](const io::DrumSettings& s) {
                const DrumMaterials& m = s.materials;
                auto name = [&](std::int32_t k) -> py::object {
                    return k >= 0 ? py::object(py::str(m.materials.at(k).name)) : py::object(py::none());
                };
                return py::dict(py::arg("paper") = m.paper, py::arg("large") = name(m.large),
                                py::arg("small") = name(m.small), py::arg("wall") = name(m.wall),
                                py::arg("cap") = name(m.cap >= 0 ? m.cap : m.wall));
            },
            "the materials of the large and small grains, the wall and the caps (names), and whether they are "
            "the paper's")
        .def_property_readonly("cap_friction", [](const io::DrumSettings& s) { return s.fill.cap_friction; },
                               "mu between grains and end caps; None: the wall's")
        .def_property_readonly("arrangement",
                               [](const io::DrumSettings& s) { return keyword_of(arrangements, s.fill.arrangement); },
                               "the axial arrangement at the start: halves, mixed, bands or boundaries")
        .def_property_readonly("bands", [](const io::DrumSettings& s) { return s.fill.bands; },
                               "arrangement bands: the number of alternating bands")
        .def_property_readonly("band_widths", [](const io::DrumSettings& s) { return s.fill.band_widths; },
                               "arrangement bands: their widths as fractions of the length (empty: equal)")
        .def_property_readonly("boundaries", [](const io::DrumSettings& s) { return s.fill.boundaries; }, "m")
        .def_property_readonly("ends", [](const io::DrumSettings& s) { return keyword_of(species_names, s.fill.ends); },
                               "bands, boundaries: the species of the left end band, small or large")
        .def_property_readonly("small_volume_fraction",
                               [](const io::DrumSettings& s) { return s.fill.small_volume_fraction; },
                               "None: equal masses")
        .def_property_readonly("band_edges",
                               [](const io::DrumSettings& s) { return band_edges(s.geometry, s.fill); },
                               "z (m) of the start's band edges, -length/2 to length/2")
        .def_readonly("spin_up_time", &io::DrumSettings::spin_up_time, "s")
        .def_readonly("samples_per_revolution", &io::DrumSettings::samples_per_revolution,
                      "rows of drum_series.csv and profiles.csv per revolution")
        .def_readonly("profile_bins", &io::DrumSettings::profile_bins, "axial bins of the concentration profile C(z, N)")
        .def_readonly("snapshots_per_revolution", &io::DrumSettings::snapshots_per_revolution,
                      "particle snapshots per revolution (0: none)")
        .def_readonly("dt", &io::DrumSettings::dt, "s; 0: chosen from the materials")
        .def_readonly("skin", &io::DrumSettings::skin, "m, the neighbour list's; 0: 0.3 x the largest radius")
        .def_property_readonly("shear", [](const io::DrumSettings& s) { return keyword_of(shear_models, s.shear); },
                               "the shear model (docs/MODEL.md)")
        .def_property_readonly("friction_normal",
                               [](const io::DrumSettings& s) { return keyword_of(friction_normals, s.friction_normal); },
                               "the normal force that limits friction (docs/MODEL.md)")
        .def_property_readonly("tangential_stiffness", [](const io::DrumSettings& s) {
            return keyword_of(tangential_stiffnesses, s.tangential_stiffness);
        }, "the tangential stiffness: the paper's or Mindlin's (docs/MODEL.md)")
        .def_property_readonly("surface_energy", &io::DrumSettings::uniform_surface_energy,
                               "J/m^2, every pair's W (the attraction): the one given, else the one the materials' "
                               "pairs share (the paper's 0.2); None if their W differ; 0: cohesionless")
        .def_readonly("output", &io::DrumSettings::output, "the run directory");

    m.def("load_drum_settings", &io::load_drum_settings, py::arg("path"), "A drum settings file (TOML)");
    m.def(
        "drum_settings_from_dict",
        [](const py::dict& d, const fs::path& name) { return io::read_drum_settings(toml_from_dict(d, name), name); },
        py::arg("settings"), py::arg("name") = "<dict>", "Drum settings laid out as the file: {'fill': {...}, ...}");

    m.def(
        "run_drum",
        [](const io::DrumSettings& settings, const std::function<void(py::object)>& on_sample, int threads, bool force,
           bool quiet, double checkpoint_revolutions, double checkpoint_minutes, std::int64_t stop_at_step,
           bool allow_unsafe_dt, double max_memory_gib, const std::vector<std::string>& fields) {
            // As the command line checks --threads and --max-memory (0: the default).
            if (const std::string why = experiments::thread_count_problem(threads, std::to_string(threads));
                !why.empty())
                throw Error("threads: " + why);
            need_memory_limit(max_memory_gib);
            experiments::DrumRunOptions o;
            o.settings = settings;
            o.force = force;
            o.quiet = quiet;
            o.plot = false;
            o.threads = threads;
            o.checkpoint_revolutions = checkpoint_revolutions;
            o.checkpoints.every_minutes = checkpoint_minutes;
            o.checkpoints.stop_at_step = stop_at_step;
            o.allow_unsafe_dt = allow_unsafe_dt;
            o.max_memory_gib = max_memory_gib;
            o.fields = fields;
            if (on_sample)
                o.on_sample = [&on_sample](const experiments::DrumSample& s) {
                    py::gil_scoped_acquire python;
                    on_sample(sample_of(s));
                };
            const experiments::DrumOutcome outcome = run_stoppable(
                [&] { return experiments::run_drum(o); },
                [](const experiments::DrumOutcome& stopped) {
                    return "the drum run stopped with a checkpoint; continue with: " + experiments::program_name() + " resume " +
                           stopped.directory.string();
                });
            return py::make_tuple(outcome.exit_code, outcome.directory);
        },
        py::arg("settings"), py::arg("on_sample") = nullptr, py::arg("threads") = 1, py::arg("force") = false,
        py::arg("quiet") = true, py::arg("checkpoint_every_revolutions") = 1.0,
        py::arg("checkpoint_every_minutes") = 10.0, py::arg("stop_at_step") = 0, py::arg("allow_unsafe_dt") = false,
        py::arg("max_memory_gib") = 0.0, py::arg("fields") = std::vector<std::string>{},
        "The drum protocol (experiments/drum.hpp) into settings.output; on_sample(sample) after every sample; fields: KEY=VALUE items "
        "(experiments::parse_fields_during_run). Returns (exit code, directory)");

    const analysis::BandOptions band_defaults;
    m.def(
        "analyze_drum",
        [](const std::string& directory, double first_revolution, double band_z_enter, double band_z_leave,
           double band_min_contrast, double band_min_contrast_leave, int band_smoothing, int band_min_width) {
            io::AnalyzeOptions options{first_revolution,
                                       {band_smoothing, band_z_enter, band_z_leave, band_min_contrast,
                                        band_min_contrast_leave, band_min_width}};
            analysis::check_band_options(options.bands, [](const std::string& field) { return "band_" + field; });
            return experiments::analyze_drum(directory, options);
        },
        py::arg("directory"), py::arg("first_revolution") = 1.0, py::arg("band_z_enter") = band_defaults.z_enter,
        py::arg("band_z_leave") = band_defaults.z_leave, py::arg("band_min_contrast") = band_defaults.min_contrast,
        py::arg("band_min_contrast_leave") = band_defaults.min_contrast_leave,
        py::arg("band_smoothing") = band_defaults.smoothing, py::arg("band_min_width") = band_defaults.min_width,
        "Analyses a finished drum run again (summary.json, summary.txt), with the band thresholds of tumble analyze's "
        "--band-* options (docs/BAND-ANALYSIS.md); returns the summary text");
}

}  // namespace tumble::python
