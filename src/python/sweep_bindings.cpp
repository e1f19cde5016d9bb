// SPDX-License-Identifier: MIT
// The sweep (experiments/sweep.hpp) for Python: its points and their state,
// and the sweep itself, each point a child process of the tumble program.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "bindings.hpp"
#include "experiments/sweep.hpp"
#include "tumble/core/mpi.hpp"

namespace tumble::python {

namespace fs = std::filesystem;

namespace {
// Under an MPI launcher (mpirun python3 script.py) the ranks share the
// sweep's points as under tumble sweep: MPI is started at the first sweep
// (core/mpi.hpp; nothing without a launcher) and ends with the process.
void start_mpi_once() {
    static int argc = 0;
    static char** argv = nullptr;
    static const mpi::Session session(argc, argv);
}
}  // namespace

void bind_sweep(py::module_& m) {
    m.def(
        "sweep_points",
        [](const std::string& sweep_file, const std::string& out) {
            const experiments::SweepPlan plan = experiments::sweep_plan(sweep_file, out);
            py::list points;
            for (const io::SweepPoint& p : plan.points)
                points.append(py::dict(py::arg("name") = p.name, py::arg("mode") = p.mode,
                                       py::arg("omega") = p.omega, py::arg("seed") = p.seed,
                                       py::arg("directory") = p.directory,
                                       py::arg("state") = io::to_string(io::point_state(p.directory))));
            return points;
        },
        py::arg("sweep_file"), py::arg("out"),
        "The points of a sweep file in plan order, each a dict: name, mode, omega (rad/s), seed, directory, "
        "state (pending, unfinished, failed, finished); runs nothing");

    m.def(
        "run_sweep",
        [](const std::string& sweep_file, const std::string& out, unsigned jobs, bool quiet,
           const fs::path& tumble_binary) {
            start_mpi_once();
            const experiments::SweepRunOptions o{.sweep_file = sweep_file, .output_directory = out, .jobs = jobs,
                                                 .quiet = quiet, .tumble_binary = tumble_binary};
            const experiments::SweepOutcome outcome = run_stoppable(
                [&] { return experiments::run_sweep(o); },
                [&](const experiments::SweepOutcome& stopped) {
                    return "the sweep stopped; its running points wrote checkpoints; continue with the same call, "
                           "or: " + experiments::program_name() + " sweep " + sweep_file + " -o " + stopped.directory.string();
                });
            return py::dict(py::arg("directory") = outcome.directory, py::arg("points") = outcome.points,
                            py::arg("with_results") = outcome.with_results, py::arg("failed") = outcome.failed,
                            py::arg("exit_code") = outcome.exit_code);
        },
        py::arg("sweep_file"), py::arg("out"), py::arg("jobs"), py::arg("quiet"), py::arg("tumble_binary"),
        "The sweep of `tumble sweep` (docs/SWEEP.md), each point run by the program tumble_binary. Returns a dict: "
        "directory, points, with_results, failed, exit_code");
}

}  // namespace tumble::python
