// SPDX-License-Identifier: MIT
// tumble run FILE: read a scenario, simulate it, write the output directory;
// checkpoints on the way, so that `tumble resume DIR` can continue it.
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "experiments/run_control.hpp"
#include "cli/commands.hpp"
#include "experiments/limits.hpp"
#include "experiments/progress.hpp"
#include "io/config.hpp"
#include "io/output.hpp"
#include "io/snapshots.hpp"
#include "io/step_times.hpp"
#include "tumble/core/mpi.hpp"
#include "tumble/sim/health.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::cli {

namespace fs = std::filesystem;

namespace {

// Steps between two samples at the given interval (s); 0 if never.
std::int64_t every(double interval, double dt) {
    return interval > 0.0 ? std::max<std::int64_t>(1, std::llround(std::min(interval / dt, max_steps))) : 0;
}

// What a run carries from one process to the next (kept in its checkpoints).
struct RunPlan {
    std::string scenario_file;
    std::uint64_t seed = 0;
    double duration = 0.0;  // s
    std::int64_t steps = 0, sample_every = 0, snapshot_every = 0;
    double wall_seconds = 0.0;  // spent by earlier processes
    bool quiet = false;
    ProgressStyle progress;     // of this process: not kept in checkpoints
};

void save_plan(io::CheckpointRecord& r, const RunPlan& plan) {
    r.set("command", std::string("run"));
    r.set("run.scenario_file", plan.scenario_file);
    r.set("run.seed", static_cast<std::int64_t>(plan.seed));
    r.set("run.duration", plan.duration);
    r.set("run.steps", plan.steps);
    r.set("run.sample_every", plan.sample_every);
    r.set("run.snapshot_every", plan.snapshot_every);
    r.set("run.wall_seconds", plan.wall_seconds);
}

RunPlan load_plan(const io::CheckpointRecord& r) {
    RunPlan plan;
    plan.scenario_file = r.text("run.scenario_file");
    plan.seed = static_cast<std::uint64_t>(r.integer("run.seed"));
    plan.duration = r.number("run.duration");
    plan.steps = r.integer("run.steps");
    plan.sample_every = r.integer("run.sample_every");
    plan.snapshot_every = r.integer("run.snapshot_every");
    plan.wall_seconds = r.number("run.wall_seconds");
    return plan;
}

// The run from wherever `sim` stands to the end. Shared among MPI ranks,
// every rank steps, measures (collectively) and writes its own checkpoint
// file; rank 0 alone writes the time series and run.json and talks.
class RunLoop {
public:
    // fields: taken during the run, kept in its checkpoints, written at its end.
    RunLoop(Simulation& sim, RunPlan plan, fs::path dir, CheckpointPolicy policy, bool continuing,
            const std::vector<double>& snapshot_times, FieldRecorder* fields = nullptr)
        : sim_(sim), plan_(std::move(plan)), dir_(std::move(dir)), fields_(fields),
          checkpoints_(dir_, policy, default_health_limits(sim.scenario())) {
        if (mpi::rank() == 0) series_.emplace(dir_ / "time_series.csv", sim.scenario(), continuing);
        if (plan_.snapshot_every) snapshots_.emplace(dir_, snapshot_times, !sim.scenario().walls.empty());
    }

    int run() {
        const bool talk = !plan_.quiet && mpi::rank() == 0;
        if (mpi::rank() != 0) plan_.progress = progress_style(true, 0.0);
        Progress progress("run", sim_.step_count(), plan_.steps, plan_.progress,
                          {.particles = sim_.scenario().free_count(), .seconds_per_step = sim_.dt()});
        while (sim_.step_count() < plan_.steps) {
            if (fields_) fields_->advance(sim_, 1);
            else sim_.step();
            sample();
            progress.update(sim_.step_count());
            const auto due = checkpoints_.after_steps(sim_, sim_.step_count());
            if (due == Checkpointer::Due::no) continue;
            checkpoint(false, progress.elapsed_seconds());
            if (due == Checkpointer::Due::and_stop) {
                progress.finish();
                return checkpoints_.stopped(sim_.step_count());
            }
        }
        progress.finish();
        const io::StepTimesSpread phases =
            io::step_times_spread(sim_.step_times(), progress.elapsed_seconds(), sim_.threads(), sim_.shared());
        // The run is finished only when its results are written: a checkpoint
        // of the final state first (a resume from it writes the results
        // again), then the results, then the checkpoint that says "finished".
        checkpoint(false, progress.elapsed_seconds());
        if (!plan_.sample_every || plan_.steps % plan_.sample_every != 0) write_series();  // the final state
        const double seconds = plan_.wall_seconds + progress.elapsed_seconds();
        if (mpi::rank() == 0)
            io::write_run_json(dir_ / "run.json", sim_,
                               {plan_.scenario_file, plan_.seed, plan_.duration, plan_.steps, seconds,
                                sim_.scenario().particles.size(), sim_.scenario().free_count(), phases});
        if (fields_) {
            const std::string written = fields_->write(dir_);
            if (talk) fmt::print("{}\n", written);
        }
        checkpoint(true, progress.elapsed_seconds());
        if (talk) {
            // Three digits for a short run (a tenth of a second rounds it to "0.0 s").
            fmt::print("done in {} s ({:.3g} particle updates/s); output in {}\n",
                       seconds < 100.0 ? fmt::format("{:#.3g}", seconds) : fmt::format("{:.0f}", seconds),
                       seconds > 0 ? static_cast<double>(sim_.scenario().free_count()) * plan_.steps / seconds : 0.0,
                       dir_.string());
            fmt::print("{}", io::step_times_text(phases, "the run (this process: since its start or resume)"));
        }
        return 0;
    }

    // The samples due at the current step (the first at step 0).
    void sample() {
        if (plan_.sample_every && sim_.step_count() % plan_.sample_every == 0) write_series();
        if (plan_.snapshot_every && sim_.step_count() % plan_.snapshot_every == 0) snapshots_->write(sim_);
    }

private:
    void write_series() {
        const Observables o = sim_.observe();  // collective
        if (series_) series_->write(o);
    }

    // seconds: spent by this process so far.
    void checkpoint(bool finished, double seconds) {
        io::Checkpoint c = checkpoint_of(sim_);
        RunPlan now = plan_;
        now.wall_seconds += seconds;
        save_plan(c.record, now);
        save_policy(c.record, checkpoints_.policy());
        c.record.set("finished", static_cast<std::int64_t>(finished));
        c.record.set("snapshot_times", snapshots_ ? snapshots_->times() : std::vector<double>{});
        if (fields_) fields_->save(c.record);
        if (mpi::rank() == 0) io::record_file_lengths(c.record, dir_, {"time_series.csv"});
        checkpoints_.write(sim_, c);
    }

    Simulation& sim_;
    RunPlan plan_;
    fs::path dir_;
    FieldRecorder* fields_;
    Checkpointer checkpoints_;
    std::optional<io::TimeSeriesWriter> series_;  // rank 0
    std::optional<io::SnapshotSeries> snapshots_;
};

}  // namespace

int run_command(const RunOptions& options) {
    // Everything is read and checked before anything is written, the memory
    // the run will need before the reader makes any sphere.
    const int threads = resolve_threads(options.threads);
    io::RunConfig config = io::load_run_config(
        options.scenario_file,
        scenario_memory_check(threads, memory_limit_bytes(options.max_memory_gib), "--max-memory GIB"));
    if (!options.output_directory.empty()) config.output.directory = options.output_directory;
    const bool shared = mpi::size() > 1;
    Simulation sim(std::move(config.scenario), threads, shared ? Ranks::world : Ranks::one);
    const double dt = sim.dt();
    check_time_step(sim.time_step_report(), options.scenario_file);
    RunPlan plan{options.scenario_file,
                 config.seed,
                 config.duration,
                 step_count(config.duration, dt, options.scenario_file + ": simulation.duration"),
                 every(config.output.time_series_interval, dt),
                 every(config.output.snapshot_interval, dt),
                 0.0,
                 options.quiet,
                 progress_style(options.quiet, options.progress_every)};
    check_stiffness(sim.scenario(), options.allow_soft, options.scenario_file);  // after what no run can do
    std::optional<FieldRecorder> fields;
    std::vector<std::string> field_items = config.fields;  // the command line's after the file's: they replace them
    field_items.insert(field_items.end(), options.fields.begin(), options.fields.end());
    if (!field_items.empty()) fields.emplace(field_items, sim, plan.steps, options.max_memory_gib, false);

    const auto& dir = config.output.directory;
    std::optional<io::RunLock> lock;  // rank 0's: the other ranks write only their checkpoints
    if (mpi::rank() == 0) lock.emplace(io::prepare_output_directory(dir, options.force));
    if (!options.quiet && mpi::rank() == 0) {
        const TimeStepReport& t = sim.time_step_report();
        std::int64_t poured = 0;  // still to come
        for (std::size_t q = 0; q < sim.inserted().size(); ++q) poured += sim.scenario().insertions[q].count - sim.inserted()[q];
        fmt::print("tumble run {}: {} particles ({} free{}), {} steps of {:.3g} s ({}; safe maximum {:.3g} s){}\n",
                   options.scenario_file, sim.scenario().particles.size(), sim.scenario().free_count(),
                   poured > 0 ? fmt::format("; {} more to be poured in", poured) : "", plan.steps, dt,
                   t.automatic ? "chosen automatically" : "given", t.maximum,
                   shared ? fmt::format(", shared among {} MPI ranks (slabs along {})", mpi::size(),
                                        "xyz"[sim.slabs()->axis()])
                          : "");
        if (fields) fmt::print("{}\n", fields->summary());
    }
    RunLoop loop(sim, plan, dir, options.checkpoints, false, {}, fields ? &*fields : nullptr);
    loop.sample();
    return loop.run();
}

int resume_run(io::Checkpoint checkpoint, const fs::path& dir, bool quiet, double progress_every) {
    RunPlan plan = load_plan(checkpoint.record);
    plan.quiet = quiet;
    plan.progress = progress_style(quiet, progress_every);
    if (plan.steps != step_count(plan.duration, checkpoint.state.dt, checkpoint.record.source + ": run.duration") ||
        plan.sample_every < 0 || plan.snapshot_every < 0 || plan.sample_every > max_steps ||
        plan.snapshot_every > max_steps)
        throw Error(checkpoint.record.source + ": record keys run.steps, run.sample_every or run.snapshot_every do not "
                                               "fit its duration and time step");
    Simulation sim = restore_simulation(checkpoint, dir);
    if (!quiet && mpi::rank() == 0)
        fmt::print("tumble resume: run of {} at step {} of {} (t = {:.6g} s)\n", plan.scenario_file, sim.step_count(),
                   plan.steps, sim.time());
    std::optional<FieldRecorder> fields = FieldRecorder::resumed(checkpoint.record, sim);
    RunLoop loop(sim, plan, dir, load_policy(checkpoint.record), true, checkpoint.record.numbers("snapshot_times"),
                 fields ? &*fields : nullptr);
    return loop.run();
}

}  // namespace tumble::cli
