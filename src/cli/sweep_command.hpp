// SPDX-License-Identifier: MIT
// tumble sweep: the drum experiment over rotation speeds, modes and seeds
// (docs/SWEEP.md). Each point is a child `tumble drum` in its own directory.
#pragma once

#include <string>

#include "experiments/progress.hpp"

namespace tumble::cli {

struct SweepOptions {
    std::string sweep_file;         // the sweep TOML file (examples/sweep_*.toml)
    std::string output_directory;   // empty: the file's [output] directory
    unsigned jobs = 0;              // points at once (per MPI rank); 0: the cores / ranks on this node
    bool list = false;              // print the points and their state, run nothing
    bool quiet = false;             // print nothing but errors and failed points
    double progress_every = experiments::default_progress_every;  // s between progress lines in a log; 0: none
    double wait_timeout = 7 * 24 * 3600.0;  // s: how long MPI rank 0 waits for the other ranks' points
    std::string tumble_binary;      // empty: this executable (/proc/self/exe); for tests
};
int sweep_command(const SweepOptions& options);

}  // namespace tumble::cli
