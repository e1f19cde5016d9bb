// SPDX-License-Identifier: MIT
// tumble run FILE: read a scenario, simulate it, write the output directory.
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "io/config.hpp"
#include "io/output.hpp"
#include "io/snapshots.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::cli {

namespace {
// Steps between two samples at the given interval (s); 0 if never.
std::int64_t every(double interval, double dt) {
    return interval > 0.0 ? std::max<std::int64_t>(1, std::llround(interval / dt)) : 0;
}
}  // namespace

int run_command(const RunOptions& options) {
    // Everything is read and checked before anything is written.
    io::RunConfig config = io::load_run_config(options.scenario_file);
    if (!options.output_directory.empty()) config.output.directory = options.output_directory;
    Simulation sim(std::move(config.scenario), resolve_threads(options.threads));
    const double dt = sim.dt();
    const std::int64_t steps = std::llround(std::ceil(config.duration / dt - 1e-9));
    const std::int64_t sample_every = every(config.output.time_series_interval, dt);
    const std::int64_t snapshot_every = every(config.output.snapshot_interval, dt);
    std::size_t free_particles = 0;
    for (std::size_t i = 0; i < sim.particles().size(); ++i) free_particles += !sim.particles().is_kinematic(i);

    const auto& dir = config.output.directory;
    io::prepare_output_directory(dir, options.force);
    io::TimeSeriesWriter series(dir / "time_series.csv", sim.scenario().materials);
    const bool talk = !options.quiet;
    if (talk) {
        const TimeStepReport& t = sim.time_step_report();
        fmt::print("tumble run {}: {} particles ({} free), {} steps of {:.3g} s ({}; safe maximum {:.3g} s)\n",
                   options.scenario_file, sim.particles().size(), free_particles, steps, dt,
                   t.automatic ? "chosen automatically" : "given", t.maximum);
    }

    std::optional<io::SnapshotSeries> snapshots;
    if (snapshot_every) snapshots.emplace(dir);
    auto sample = [&] {
        if (sample_every && sim.step_count() % sample_every == 0) series.write(sim.observe());
        if (snapshot_every && sim.step_count() % snapshot_every == 0) snapshots->write(sim);
    };
    Progress progress(steps, free_particles, talk && progress_wanted());
    sample();
    for (std::int64_t s = 0; s < steps; ++s) {
        sim.step();
        sample();
        progress.update(s + 1);
    }
    progress.finish();
    if (!sample_every || steps % sample_every != 0) series.write(sim.observe());  // always end with the final state

    const double seconds = progress.elapsed_seconds();
    io::write_run_json(dir / "run.json", sim,
                       {options.scenario_file, config.seed, config.duration, steps, seconds, sim.particles().size(),
                        free_particles});
    if (talk)
        fmt::print("done in {:.1f} s ({:.3g} particle updates/s); output in {}\n", seconds,
                   seconds > 0 ? static_cast<double>(free_particles) * steps / seconds : 0.0, dir.string());
    return 0;
}

}  // namespace tumble::cli
