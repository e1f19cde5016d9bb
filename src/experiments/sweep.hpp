// SPDX-License-Identifier: MIT
// The sweep (docs/SWEEP.md) as a library: what `tumble sweep` and the
// Python module's run_sweep call. It runs `tumble drum` for every (mode,
// omega, seed) of a sweep file, each point a child process in its own
// directory, several at once; skips finished points and resumes interrupted
// ones; under an MPI launcher (mpirun, srun) rank 0 hands the points out to
// the ranks as they free up and gathers their results by MPI messages
// (core/mpi.hpp); writes sweep.csv and sweep_summary.csv. It prints the progress lines unless
// quiet, and draws no figures. The parts that need no process of their own
// (the file, the points, their state on disk, the tables) are io/sweep.hpp.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "experiments/progress.hpp"
#include "io/sweep.hpp"

namespace tumble::experiments {

struct SweepRunOptions {
    std::string sweep_file;                  // the sweep TOML file (examples/sweep_*.toml)
    std::string output_directory;            // empty: the file's [output] directory
    unsigned jobs = 0;                       // points at once per MPI rank; 0: the cores / ranks on this node
    bool quiet = false;                      // print nothing but errors and failed points
    double progress_every = default_progress_every;  // s between progress lines in a log; 0: none
    std::filesystem::path tumble_binary;     // the program each point runs (tumble drum, tumble resume)
};

// How a sweep ended. exit_code: 0 (every point has results), 1 (some have
// none), exit_stopped (SIGINT or SIGTERM: the running points wrote
// checkpoints; the next sweep resumes them). An MPI rank other than 0 ends
// with 0 (or exit_stopped) and writes no tables: rank 0 reports every
// rank's failures.
struct SweepOutcome {
    std::filesystem::path directory;
    std::size_t points = 0;        // of the whole sweep, all ranks
    std::size_t with_results = 0;  // rows of sweep.csv with numbers
    std::size_t failed = 0;        // points that failed in this run (rank 0: of every rank; else: of this rank)
    bool stopped = false;          // by a signal
    bool tables_written = false;   // sweep.csv and sweep_summary.csv (rank 0, unless stopped)
    int exit_code = 0;
};

// Runs the sweep of sweep_plan(). Throws tumble::Error for a bad sweep file
// or point (before any point runs) and for a sweep directory it cannot
// create or lock. SIGINT and SIGTERM stop it (install_stop_signals).
SweepOutcome run_sweep(const SweepRunOptions& options);

// The points of a sweep file in the sweep directory (output_directory;
// empty: the file's [output] directory), in plan order, each checked as
// tumble drum will check it (step counts, samples) with the time step the
// drum chooses for its mode; runs nothing (io::point_state tells each
// point's state). Throws tumble::Error naming the file and the point.
struct SweepPlan {
    std::filesystem::path directory;
    std::vector<io::SweepPoint> points;
};
SweepPlan sweep_plan(const std::string& sweep_file, const std::string& output_directory);

}  // namespace tumble::experiments
