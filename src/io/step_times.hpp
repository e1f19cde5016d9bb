// SPDX-License-Identifier: MIT
// Where a run's time went, printed at its end as LAMMPS prints its "MPI task
// timing breakdown": the steps' phases (sim/step_clock.hpp) and the rest of
// the loop ("other": output, analysis, checkpoints), each with its share of
// the wall time and, on several ranks, the least, mean and most of a rank.
// A phase much longer on one rank than on another is work out of balance;
// a long `exchange` is waiting for the other ranks.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

#include "io/json.hpp"
#include "tumble/sim/step_clock.hpp"

namespace tumble::io {

struct PhaseSpread {
    double least = 0.0, mean = 0.0, most = 0.0;  // s, over the ranks
};

struct StepTimesSpread {
    std::array<PhaseSpread, step_phase_count> phases;  // by StepPhase
    PhaseSpread other;                                 // the wall time less the phases
    double wall_seconds = 0.0;                         // of the loop, the ranks' mean
    std::int64_t steps = 0;
    int ranks = 1, threads = 1;
};

// This process's `times` within the loop's `wall_seconds` (the wall-clock
// time of the loop that took the steps) and, for a simulation `shared`
// among the ranks (Simulation::shared()), their spread over the ranks:
// then every rank calls it (MPI reductions) and gets the result.
StepTimesSpread step_times_spread(const StepTimes& times, double wall_seconds, int threads, bool shared);

// As text, headed "time by phase of WHAT", a line per phase (the phases
// no step spent time in left out), and as JSON: {"wall_seconds", "steps", "ranks", "threads", "phases":
// {name: {"seconds", "share", "least", "most"}}}, "seconds" the ranks' mean.
std::string step_times_text(const StepTimesSpread& spread, std::string_view what);
Json step_times_json(const StepTimesSpread& spread);

}  // namespace tumble::io
