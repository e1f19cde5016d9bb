// SPDX-License-Identifier: MIT
// The analysis of src/tumble/analysis for Python: the Hogg solution and its
// fits (hogg.hpp), the grains' axial MSD and its D (axial_msd.hpp), and the
// grain tracks of a drum run directory.
#include <cmath>
#include <limits>

#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "io/drum_output.hpp"
#include "tumble/analysis/axial_msd.hpp"
#include "tumble/analysis/hogg.hpp"

namespace tumble::python {

namespace fs = std::filesystem;

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
}

}  // namespace tumble::python
