// SPDX-License-Identifier: MIT
// The analysis of src/tumble/analysis for Python: the Hogg solution and its
// fits (hogg.hpp), the grains' axial MSD and its D (axial_msd.hpp), the
// grain tracks of a drum run directory, and coarse-grained fields of grains
// given as arrays or of a run directory (coarse_grain.hpp,
// experiments/fields.hpp).
#include <cmath>
#include <limits>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "experiments/fields.hpp"
#include "io/drum_output.hpp"
#include "io/fields_output.hpp"
#include "tumble/analysis/axial_msd.hpp"
#include "tumble/analysis/hogg.hpp"

namespace tumble::python {

namespace fs = std::filesystem;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The rows of an N x 3 array (columns == 3) or the entries of an N array
// (columns == 0), N == rows unless rows is none; tumble::Error naming `name`.
Array checked(const py::object& object, const char* name, std::size_t columns,
              std::optional<std::size_t> rows = std::nullopt) {
    const Array a = Array::ensure(object);
    if (!a) throw Error(std::string(name) + ": not an array of numbers");
    const bool shape = columns == 0 ? a.ndim() == 1 : a.ndim() == 2 && static_cast<std::size_t>(a.shape(1)) == columns;
    const auto n = static_cast<std::size_t>(a.ndim() > 0 ? a.shape(0) : 0);
    if (!shape || (rows && n != *rows))
        throw Error(std::string(name) + ": an array of " + (rows ? std::to_string(*rows) : std::string("N")) +
                    (columns == 0 ? "" : " x 3") + " numbers, got " + std::to_string(a.ndim()) +
                    " dimensions of " + std::to_string(n) + " rows");
    return a;
}

std::span<const Vec3> rows_of(const Array& a) {
    return {reinterpret_cast<const Vec3*>(a.data()), static_cast<std::size_t>(a.shape(0))};
}

experiments::FieldSettings field_settings(std::optional<std::array<double, 3>> lo, std::optional<std::array<double, 3>> hi,
                                          std::optional<double> cell, std::optional<std::array<double, 3>> cells,
                                          const std::string& average, const std::string& kernel,
                                          std::optional<double> width, double max_memory_gib) {
    experiments::FieldSettings s;
    if (lo) s.lo = Vec3{(*lo)[0], (*lo)[1], (*lo)[2]};
    if (hi) s.hi = Vec3{(*hi)[0], (*hi)[1], (*hi)[2]};
    s.cell = cell;
    s.cells = cells;
    s.average = average;
    if (kernel != "gaussian" && kernel != "lucy") throw Error("kernel: gaussian or lucy, got \"" + kernel + "\"");
    s.kernel = kernel == "lucy" ? analysis::CgKernel::lucy : analysis::CgKernel::gaussian;
    s.width = width;
    s.max_memory_gib = max_memory_gib;
    return s;
}

// The fields as numpy arrays shaped by the grid, (nz, ny, nx) for a scalar,
// then 3 for a vector, 3 x 3 for a tensor; the nodes' coordinates along
// each axis under the axes' names (x, y, z; s, d, z in the drum's frame).
py::dict fields_dict(const analysis::Fields& f, const std::string& axes = "xyz") {
    py::dict d;
    const analysis::CgGrid& g = f.grid;
    for (int k = 0; k < 3; ++k) {
        std::vector<double> at(g.cells[static_cast<std::size_t>(k)]);
        for (std::size_t a = 0; a < at.size(); ++a)
            at[a] = g.lo[k] + (static_cast<double>(a) + 0.5) * g.spacing(k);
        d[py::str(std::string(1, axes[static_cast<std::size_t>(k)]))] =
            py::array_t<double>(static_cast<py::ssize_t>(at.size()), at.data());
    }
    const std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(g.cells[2]), static_cast<py::ssize_t>(g.cells[1]),
                                         static_cast<py::ssize_t>(g.cells[0])};
    for (const io::FieldColumn& c : io::field_columns(f)) {
        std::vector<py::ssize_t> s = shape;
        if (c.components.size() == 3) s.push_back(3);
        if (c.components.size() == 9) s.insert(s.end(), {3, 3});
        py::array_t<double> a(s);
        std::copy(c.values.begin(), c.values.end(), a.mutable_data());
        d[c.name.c_str()] = a;
    }
    d["samples"] = f.samples;
    return d;
}

}  // namespace

void bind_analysis(py::module_& m) {
    m.def("hogg_mean_position", py::vectorize(&analysis::hogg_mean_position), py::arg("D"), py::arg("N"), py::arg("L"),
          "<z>(N) of the component that started at z > 0, m (Hogg et al.; D in m^2/rev, L in m)");
    m.def("hogg_concentration", py::vectorize(&analysis::hogg_concentration), py::arg("z"), py::arg("D"), py::arg("N"),
          py::arg("L"), "C(z, N) of the component that started at z > 0");

    m.def(
        "fit_hogg",
        [](const std::vector<double>& N, const std::vector<double>& z, double L, double first_revolution, bool drift,
           std::optional<double> fixed_D) {
            const analysis::HoggFit f = analysis::fit_hogg(N, z, L, {first_revolution, drift, fixed_D.value_or(-1.0)});
            return py::dict(py::arg("D") = f.D, py::arg("D_stderr") = f.D_stderr, py::arg("amplitude") = f.amplitude,
                            py::arg("amplitude_stderr") = f.amplitude_stderr, py::arg("drift") = f.drift,
                            py::arg("drift_stderr") = f.drift_stderr, py::arg("points") = f.points,
                            py::arg("residual_rms") = f.residual_rms,
                            py::arg("correlation_samples") = f.correlation_samples,
                            py::arg("determined") = f.determined, py::arg("note") = f.note);
        },
        py::arg("N"), py::arg("z"), py::arg("L"), py::arg("first_revolution") = 1.0, py::arg("drift") = false,
        py::arg("fixed_D") = py::none(),
        "The Hogg fit with the amplitude free (analysis/hogg.hpp, fit_hogg): <z>(N) of the component that started "
        "at z > 0 (mirror the other), N in revolutions, z and L in m; D in m^2/rev");

    m.def(
        "axial_msd",
        [](const std::vector<double>& revolutions, const std::vector<std::vector<double>>& z, double block,
           double fit_from, double half_length, double cap_margin) {
            const analysis::MsdOptions o{block, fit_from, half_length, cap_margin};
            const analysis::MsdEstimate e =
                analysis::estimate_axial_diffusion({analysis::axial_msd_blocks({revolutions, z}, o)}, o);
            return py::dict(py::arg("D") = e.D, py::arg("interval") = std::array<double, 2>{e.interval.lo, e.interval.hi},
                            py::arg("lag") = e.lag, py::arg("msd") = e.msd, py::arg("fit_lo") = e.fit_lo,
                            py::arg("fit_hi") = e.fit_hi, py::arg("blocks") = e.blocks,
                            py::arg("determined") = e.determined, py::arg("note") = e.note);
        },
        py::arg("revolutions"), py::arg("z"), py::arg("block") = 2.0, py::arg("fit_from") = 1.0,
        py::arg("half_length") = std::numeric_limits<double>::infinity(), py::arg("cap_margin") = 3.0,
        "D from the grains' axial MSD (analysis/axial_msd.hpp): revolutions of equally spaced frames, z[frame][grain] "
        "in m (continuous in time), caps at +-half_length; D in m^2/rev with its 95 % bootstrap interval");

    m.def(
        "drum_msd",
        [](const fs::path& directory, std::size_t component, double first_revolution, std::optional<double> block) {
            const io::DrumRunInfo info = io::read_drum_run_info(directory / "drum_run.toml");
            const std::vector<analysis::GrainFrame> frames = io::read_rotation_frames(directory, info);
            io::AnalyzeOptions options;
            options.first_revolution = first_revolution;
            const double used = block.value_or(io::drum_msd_block(frames, info, options));
            const analysis::MsdEstimate e = io::drum_msd(frames, info, component, options, block.value_or(0.0));
            // A D as summary.json has it: None where it is null there.
            const auto value = [](const io::Json& j) {
                return j.is_null() ? py::object(py::none()) : py::cast(j.get<double>());
            };
            return py::dict(py::arg("D") = value(io::determined_value(e.D, e.determined)),
                            py::arg("D_best_estimate") = value(io::best_estimate(e.D, e.determined)),
                            py::arg("D_lo") = e.interval.lo, py::arg("D_hi") = e.interval.hi,
                            py::arg("interval") = std::array<double, 2>{e.interval.lo, e.interval.hi},
                            py::arg("determined") = e.determined, py::arg("note") = e.note,
                            py::arg("fit_lag_lo") = e.fit_lo, py::arg("fit_lag_hi") = e.fit_hi,
                            py::arg("blocks") = e.blocks, py::arg("block") = used,
                            py::arg("first_revolution") = first_revolution, py::arg("lag") = e.lag,
                            py::arg("msd") = e.msd);
        },
        py::arg("directory"), py::arg("component"), py::arg("first_revolution") = 1.0, py::arg("block") = py::none(),
        "D of a drum run's component from its grains' axial MSD, by the estimator and lag window of its "
        "summary.json's \"msd\" and summary.txt's headline D (io/drum_output.hpp, drum_msd); block: revolutions "
        "per block (None: the run's own, as the summary's)");

    m.def(
        "hogg_not_applicable",
        [](const fs::path& directory) {
            return io::hogg_not_applicable(io::read_drum_run_info(directory / "drum_run.toml"));
        },
        py::arg("directory"),
        "Why the Hogg solution does not describe <z> of a drum run (its start, its axis), or '' if it does");

    m.def(
        "drum_tracks",
        [](const fs::path& directory, int component) {
            const io::DrumRunInfo info = io::read_drum_run_info(directory / "drum_run.toml");
            const analysis::AxialTracks t = analysis::axial_tracks(io::read_rotation_frames(directory, info), component,
                                                                   info.periodic_axis ? info.inner_length : 0.0);
            return py::make_tuple(t.revolutions, t.z);
        },
        py::arg("directory"), py::arg("component"),
        "The axial positions of a drum run's grains of one component (tag) in its snapshots from N = 0: "
        "(revolutions, z[frame][grain]) in id order, unwrapped on a periodic axis");

    m.def(
        "coarse_grain",
        [](const py::object& positions, const py::object& velocities, const py::object& masses,
           const py::object& radii, const std::optional<py::dict>& contacts, std::optional<std::array<double, 3>> lo,
           std::optional<std::array<double, 3>> hi, std::optional<double> cell,
           std::optional<std::array<double, 3>> cells, const std::string& average, const std::string& kernel,
           std::optional<double> width, double max_memory_gib) {
            const experiments::FieldSettings s =
                field_settings(lo, hi, cell, cells, average, kernel, width, max_memory_gib);
            if (const std::string problem = experiments::field_settings_problem(s); !problem.empty()) throw Error(problem);
            const Array x = checked(positions, "positions", 3);
            const std::size_t n = static_cast<std::size_t>(x.shape(0));
            const Array v = checked(velocities, "velocities", 3, n), mass = checked(masses, "masses", 0, n),
                        R = checked(radii, "radii", 0, n);
            const analysis::CgGrains grains{rows_of(x), rows_of(v), {mass.data(), n}, {R.data(), n}};
            std::vector<analysis::CgContact> list;
            if (contacts) {
                using Ints = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>;
                const Ints i = Ints::ensure((*contacts)["i"]), j = Ints::ensure((*contacts)["j"]);
                if (!i || !j || i.ndim() != 1 || j.ndim() != 1 || j.shape(0) != i.shape(0))
                    throw Error("contacts: \"i\" and \"j\" must be integer arrays of one length");
                const std::size_t c = static_cast<std::size_t>(i.shape(0));
                const Array f = checked((*contacts)["force"], "contacts[\"force\"]", 3, c);
                const Array b = checked((*contacts)["branch"], "contacts[\"branch\"]", 3, c);
                for (std::size_t k = 0; k < c; ++k) {
                    const std::int64_t ik = i.data()[k], jk = j.data()[k];
                    if (ik < 0 || static_cast<std::size_t>(ik) >= n || jk >= static_cast<std::int64_t>(n))
                        throw Error("contacts: contact " + std::to_string(k) + " names a grain beyond the " +
                                    std::to_string(n) + " given");
                    list.push_back({static_cast<std::size_t>(ik),
                                    jk < 0 ? analysis::CgContact::wall : static_cast<std::size_t>(jk),
                                    rows_of(f)[k], rows_of(b)[k]});
                }
            }
            const analysis::CgSettings settings = experiments::grid_settings(s, grains, "max_memory_gib");
            analysis::Fields f;
            {
                py::gil_scoped_release released;
                f = analysis::coarse_grain(settings, grains, list);
            }
            return fields_dict(f);
        },
        py::arg("positions"), py::arg("velocities"), py::arg("masses"), py::arg("radii"),
        py::arg("contacts") = py::none(), py::kw_only(), py::arg("lo") = py::none(), py::arg("hi") = py::none(),
        py::arg("cell") = py::none(), py::arg("cells") = py::none(), py::arg("average") = "",
        py::arg("kernel") = "gaussian", py::arg("width") = py::none(), py::arg("max_memory_gib") = 0.0,
        "Coarse-grained fields of grains (docs/FIELDS.md): positions and velocities N x 3 (m, m/s), masses and "
        "radii N (kg, m); contacts a dict of arrays i, j (the other grain, -1 for a wall), force (on i, N) and "
        "branch (from j's centre or the wall's contact point to i's centre, m). The grid: lo, hi (m; default the "
        "grains' extent), cell (m; default the width) or cells (per axis), average (the averaged axes, e.g. 'z'); "
        "kernel 'gaussian' or 'lucy' of width w (m; default the mean radius). A dict of numpy arrays: x, y, z (the "
        "nodes), each field shaped (nz, ny, nx[, 3[, 3]]), samples");

    m.def(
        "fields",
        [](const fs::path& directory, int samples, double every, const std::optional<fs::path>& checkpoint,
           std::optional<std::array<double, 3>> lo, std::optional<std::array<double, 3>> hi, std::optional<double> cell,
           std::optional<std::array<double, 3>> cells, const std::string& average, const std::string& kernel,
           std::optional<double> width, double max_memory_gib, const std::string& frame, double span,
           std::array<double, 2> frame_cells) {
            experiments::RunFieldsOptions o;
            o.run_directory = directory;
            o.checkpoint = checkpoint.value_or(fs::path());
            o.samples = samples;
            o.every = every;
            o.settings = field_settings(lo, hi, cell, cells, average, kernel, width, max_memory_gib);
            o.memory_option = "max_memory_gib";
            o.frame = frame;
            o.span = span;
            o.frame_cells = frame_cells;
            experiments::RunFields run;
            {
                py::gil_scoped_release released;
                run = experiments::run_fields(o, [](const std::string&) {});
            }
            py::dict d = fields_dict(run.fields);
            d["times"] = run.times;
            d["checkpoint"] = run.checkpoint;
            if (run.drum) {
                d["profile"] = fields_dict(run.drum->profile, "sdz");
                if (run.drum->resolved) d["frame"] = fields_dict(*run.drum->resolved, "sdz");
                d["surface"] = py::module_::import("json").attr("loads")(
                    io::json_line(io::drum_frame_json(run.drum->surface, run.drum->layer, span)));
            }
            return d;
        },
        py::arg("directory"), py::kw_only(), py::arg("samples") = 1, py::arg("every") = 0.01,
        py::arg("checkpoint") = py::none(), py::arg("lo") = py::none(), py::arg("hi") = py::none(),
        py::arg("cell") = py::none(), py::arg("cells") = py::none(), py::arg("average") = "",
        py::arg("kernel") = "gaussian", py::arg("width") = py::none(), py::arg("max_memory_gib") = 0.0,
        py::arg("frame") = "lab", py::arg("span") = 0.5, py::arg("frame_cells") = std::array<double, 2>{1.0, 1.0},
        "Coarse-grained fields of a run directory, as tumble fields computes them (docs/FIELDS.md): `samples` "
        "states `every` s apart, continued in memory from the run's newest checkpoint (or `checkpoint`), every "
        "contact force exact. The grid and kernel as coarse_grain's; the dict of coarse_grain, with times (s) and "
        "checkpoint. frame='drum' (a drum run): the cross-section averaged along z, and besides 'profile' (the "
        "depth profile below the free surface, in the drum's coordinates s, d, z; averaged over the middle `span` "
        "of the surface) and 'surface' (drum_frame.json's numbers); frame_cells=(NS, NZ) adds 'frame', the same "
        "resolved along s and z too");
}

}  // namespace tumble::python
