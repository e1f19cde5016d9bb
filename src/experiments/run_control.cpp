// SPDX-License-Identifier: MIT
#include "experiments/run_control.hpp"

#include "tumble/core/mpi.hpp"

#include <csignal>
#include <unistd.h>

#include <fmt/format.h>

#include "tumble/sim/simulation.hpp"

namespace tumble::experiments {

namespace {

volatile std::sig_atomic_t stop_flag = 0;

// Async-signal-safe: sets the flag, or on a second SIGINT leaves at once.
extern "C" void on_stop_signal(int signal) {
    if (stop_flag && signal == SIGINT) {
        static const char message[] = "\ntumble: second interrupt: exiting at once, without a checkpoint\n";
        [[maybe_unused]] const auto written = ::write(STDERR_FILENO, message, sizeof message - 1);
        ::_exit(130);
    }
    stop_flag = 1;
}

}  // namespace

void install_stop_signals() {
    struct sigaction action {};
    action.sa_handler = on_stop_signal;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

bool stop_signalled() { return stop_flag != 0; }

void clear_stop_signal() { stop_flag = 0; }

Checkpointer::Checkpointer(std::filesystem::path run_directory, CheckpointPolicy policy, HealthLimits limits)
    : directory_(std::move(run_directory)), policy_(policy), limits_(limits), last_(std::chrono::steady_clock::now()) {
    install_stop_signals();
}

Checkpointer::Due Checkpointer::after_steps(const Simulation& sim, std::int64_t steps_done) {
    if (sim.step_count() - checked_at_step_ >= health_check_steps) check_health(sim);
    const Due d = due(sim.step_count(), steps_done);
    // Shared among ranks: every rank writes its checkpoint, or none does (a
    // signal or the clock may reach one rank first).
    return sim.shared() ? static_cast<Due>(mpi::max(static_cast<double>(d))) : d;
}

void Checkpointer::check_health(const Simulation& sim) {
    checked_at_step_ = sim.step_count();
    const std::string problem = health_problem(sim, limits_);
    if (problem.empty()) return;
    std::vector<std::filesystem::path> kept = io::checkpoint_files(directory_, checkpoint_rank(sim));
    throw BlewUp("the simulation blew up at " + problem + ". " +
                 (kept.empty() ? std::string("No checkpoint was written before.")
                               : "The last good checkpoint is kept: " + kept.back().string() + ".") +
                 " Check the time step (docs/MODEL.md) and the input.");
}

Checkpointer::Due Checkpointer::due(std::int64_t step, std::int64_t steps_done) const {
    if (stop_signalled() || (policy_.stop_at_step > 0 && step >= policy_.stop_at_step)) return Due::and_stop;
    if (policy_.every_steps > 0 && steps_done > 0 && steps_done % policy_.every_steps == 0) return Due::yes;
    const double minutes = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count() / 60.0;
    return policy_.every_minutes > 0.0 && minutes >= policy_.every_minutes ? Due::yes : Due::no;
}

namespace {
std::string& program_name_storage() {
    static std::string name = "tumble";
    return name;
}
}  // namespace

void set_program_name(std::string name) {
    if (!name.empty()) program_name_storage() = std::move(name);
}

const std::string& program_name() { return program_name_storage(); }

void Checkpointer::write(const Simulation& sim, const io::Checkpoint& checkpoint) {
    check_health(sim);
    const io::CheckpointRank who = checkpoint_rank(sim);
    // Shared among ranks: one number for the files of all ranks (each rank
    // looks before any writes).
    long number = io::next_checkpoint_number(directory_);
    if (sim.shared()) number = static_cast<long>(mpi::max(static_cast<double>(number)));
    io::write_checkpoint(directory_, checkpoint, who, number);
    last_ = std::chrono::steady_clock::now();
}

int Checkpointer::stopped(std::int64_t step) const {
    if (mpi::rank() == 0)  // shared among ranks, every rank stops at the same step
        fmt::print(stderr, "tumble: {} at step {}; checkpoint written. Continue with: {} resume {}\n",
               stop_signalled() ? "stopped by a signal" : "stopped as asked (--stop-at-step)", step,
               program_name(), directory_.string());
    return exit_stopped;
}

io::Checkpoint checkpoint_of(const Simulation& sim) {
    io::Checkpoint c{{}, sim.scenario(), sim.capture()};
    c.record.set("threads", std::int64_t{sim.threads()});
    c.record.set("ranks", std::int64_t{checkpoint_rank(sim).ranks});
    // So that a rank's file renamed to another rank's name is told apart.
    c.record.set("rank", std::int64_t{checkpoint_rank(sim).rank});
    return c;
}

io::CheckpointRank checkpoint_rank(const Simulation& sim) {
    return sim.shared() ? io::CheckpointRank{mpi::rank(), mpi::size()} : io::CheckpointRank{};
}

Simulation restore_simulation(io::Checkpoint& checkpoint, const std::filesystem::path& run_directory) {
    const std::int64_t ranks = checkpoint.record.has("ranks") ? checkpoint.record.integer("ranks") : 1;
    if (ranks != mpi::size() && ranks != 1)
        throw Error(checkpoint.record.source + ": written by a run on " + std::to_string(ranks) +
                    " ranks; resume it on as many (mpirun -np " + std::to_string(ranks) + " " + program_name() +
                    " resume; a run on several ranks goes on only on as many, a run on one on any number)");
    Simulation sim(std::move(checkpoint.scenario), static_cast<int>(checkpoint.record.integer("threads")),
                   mpi::size() > 1 ? Ranks::world : Ranks::one);
    sim.restore(std::move(checkpoint.state));
    if (mpi::rank() == 0) io::truncate_to_recorded_lengths(checkpoint.record, run_directory);
    return sim;
}

void save_policy(io::CheckpointRecord& record, const CheckpointPolicy& policy) {
    record.set("checkpoint.every_minutes", policy.every_minutes);
    record.set("checkpoint.every_steps", policy.every_steps);
}

CheckpointPolicy load_policy(const io::CheckpointRecord& record) {
    CheckpointPolicy policy;
    policy.every_minutes = record.number("checkpoint.every_minutes");
    policy.every_steps = record.integer("checkpoint.every_steps");
    return policy;
}

}  // namespace tumble::experiments
