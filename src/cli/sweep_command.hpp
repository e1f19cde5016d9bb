// SPDX-License-Identifier: MIT
// tumble sweep: the drum experiment over rotation speeds, modes and seeds
// (docs/SWEEP.md; the library: experiments/sweep.hpp). Each point is a
// child `tumble drum` in its own directory.
#pragma once

#include "experiments/sweep.hpp"

namespace tumble::cli {

// The library's options (tumble_binary: set to this executable), and --list.
struct SweepOptions : experiments::SweepRunOptions {
    bool list = false;  // print the points and their state, run nothing
};
int sweep_command(const SweepOptions& options);

}  // namespace tumble::cli
