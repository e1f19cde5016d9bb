// SPDX-License-Identifier: MIT
// When a run writes its checkpoints (docs/CHECKPOINTS.md), the signals that
// make it stop cleanly, and the blow-up check: SIGINT or SIGTERM ask the run
// to write a checkpoint at the next step it can and exit with exit_stopped;
// a second SIGINT exits at once. Every 100 steps, and before each
// checkpoint (so at the end of every run), the run is checked
// (tumble/sim/health.hpp); an unphysical one stops with BlewUp, and its last
// checkpoint, written before, stays good.
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>

#include "io/checkpoint.hpp"
#include "tumble/core/error.hpp"
#include "tumble/sim/health.hpp"

namespace tumble::experiments {

// The exit codes of tumble besides 0 (done) and 1 (a sweep with points
// without results); README.md, "Exit codes".
inline constexpr int exit_bad_input = 2;  // bad input, an impossible setting or a command-line mistake (main.cpp)
inline constexpr int exit_unexpected = 3; // an unexpected error (a bug, or the system refused something)
inline constexpr int exit_stopped = 4;   // stopped early with a checkpoint: `tumble resume DIR` continues
inline constexpr int exit_blew_up = 5;   // the simulation became unphysical (see the diagnostic)

struct CheckpointPolicy {
    double every_minutes = 10.0;    // wall-clock minutes between checkpoints; 0: not by the clock
    std::int64_t every_steps = 0;   // steps between checkpoints (drums: from revolutions); 0: not by steps
    std::int64_t stop_at_step = 0;  // write a checkpoint and stop at this step of the simulation; 0: never
};

// The program as the user invoked it (argv[0]: build/tumble until it is
// installed, tumble once on the PATH), for the commands that messages
// suggest ("continue with: build/tumble resume DIR"); "tumble" until set.
void set_program_name(std::string name);
const std::string& program_name();

// The run became unphysical; what() is the diagnostic (main exits with exit_blew_up).
class BlewUp : public Error {
public:
    using Error::Error;
};

// Installs the SIGINT/SIGTERM handlers (once per process).
void install_stop_signals();
bool stop_signalled();
// Forgets a stop that was asked for (a process that goes on after the run:
// the Python module).
void clear_stop_signal();

// Steps between two blow-up checks (health_problem) of a run: the check
// costs about one force evaluation.
inline constexpr std::int64_t health_check_steps = 100;

class Checkpointer {
public:
    Checkpointer(std::filesystem::path run_directory, CheckpointPolicy policy, HealthLimits limits);

    enum class Due { no, yes, and_stop };
    // After some steps: checks the run's health every 100 steps (throws
    // BlewUp) and says whether a checkpoint is due. `steps_done` counts the
    // steps for every_steps (e.g. since rotation began).
    Due after_steps(const Simulation& sim, std::int64_t steps_done);
    // Checks the run's health (throws BlewUp, writing nothing), then writes
    // the checkpoint of `sim`: every checkpoint, the final one included,
    // holds a state that passed the check.
    void write(const Simulation& sim, const io::Checkpoint& checkpoint);
    // Prints why the run stops and how to go on; returns exit_stopped.
    int stopped(std::int64_t step) const;
    const CheckpointPolicy& policy() const { return policy_; }

private:
    std::filesystem::path directory_;
    Due due(std::int64_t step, std::int64_t steps_done) const;
    void check_health(const Simulation& sim);

    CheckpointPolicy policy_;
    HealthLimits limits_;
    std::int64_t checked_at_step_ = 0;
    std::filesystem::path last_written_;
    std::chrono::steady_clock::time_point last_;
};

// A checkpoint of the simulation now: its scenario, its state, and in the
// record its thread count (the order of the force sums depends on it).
io::Checkpoint checkpoint_of(const Simulation& sim);
// Whose checkpoint files a simulation writes: this rank's if it is shared
// among ranks.
io::CheckpointRank checkpoint_rank(const Simulation& sim);

// The simulation of a checkpoint, on the recorded thread count, in the
// recorded state: one rank's on any number of ranks (shared out among
// them), several ranks' on as many (tumble::Error otherwise); the run directory's output files are cut back to the
// lengths they had when the checkpoint was written.
Simulation restore_simulation(io::Checkpoint& checkpoint, const std::filesystem::path& run_directory);

// The policy kept in a checkpoint record, and read back from it.
void save_policy(io::CheckpointRecord& record, const CheckpointPolicy& policy);
CheckpointPolicy load_policy(const io::CheckpointRecord& record);

}  // namespace tumble::experiments
