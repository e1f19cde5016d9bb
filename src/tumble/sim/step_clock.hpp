// SPDX-License-Identifier: MIT
// Where a run's time goes: the wall-clock time of the time steps split by
// phase, as LAMMPS and LIGGGHTS print at the end of a run. The team's first
// thread reads the clock between the phases, so a phase's time includes
// the wait of its threads for the slowest of them (at the barrier that
// ends it); on several ranks a rank's wait for the others falls in
// `exchange`. Reading the clock changes nothing in the physics: the results
// are the same bitwise.
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tumble/core/parallel.hpp"

namespace tumble {

// The phases of a step (Simulation::step()):
//   motion:     the kicks and drift of the grains, the prescribed motion of
//               the wall spheres, the threads' force sums added up, the flat
//               walls' forces;
//   exchange:   on several ranks, the ghosts' motion from their owners and
//               the vote on a rebuild, with the wait for the other ranks;
//   neighbours: the Verlet list built anew (sort, cell search, histories;
//               on several ranks the rebalance, migration and ghosts too);
//   forces:     the contact forces, the pair loop.
enum class StepPhase { motion, exchange, neighbours, forces };
inline constexpr std::size_t step_phase_count = 4;
inline constexpr std::array<std::string_view, step_phase_count> step_phase_names{"motion", "exchange", "neighbours",
                                                                                 "forces"};

// Seconds spent in each phase (by StepPhase) over `steps` steps.
struct StepTimes {
    std::array<double, step_phase_count> seconds{};
    std::int64_t steps = 0;
};

// Laps of one step at a time, read by the team's first thread only (the
// other threads' calls do nothing). Between steps it stands still, so what
// a caller does between them (output, analysis) is not counted.
class StepClock {
public:
    void start(const Team& team) {
        if (!team.leader()) return;
        last_ = clock::now();
        running_ = true;
    }
    // The time since the last lap (or the start) to `phase`.
    void lap(const Team& team, StepPhase phase) {
        if (!team.leader() || !running_) return;
        const clock::time_point now = clock::now();
        times_.seconds[static_cast<std::size_t>(phase)] += std::chrono::duration<double>(now - last_).count();
        last_ = now;
    }
    // The last lap, and one step more.
    void stop(const Team& team, StepPhase phase) {
        if (!team.leader() || !running_) return;
        lap(team, phase);
        running_ = false;
        ++times_.steps;
    }
    const StepTimes& times() const { return times_; }
    void reset() { times_ = StepTimes{}; }

private:
    using clock = std::chrono::steady_clock;
    clock::time_point last_;
    bool running_ = false;
    StepTimes times_;
};

}  // namespace tumble
