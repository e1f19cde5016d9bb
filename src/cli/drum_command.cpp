// SPDX-License-Identifier: MIT
// tumble drum: the paper's experiment. Build the particle-walled drum, fill
// it, let the bed settle with the drum at rest, turn the drum at constant
// speed for the asked number of revolutions while sampling <z> per
// component, then analyse (tumble analyze). docs/DRUM.md explains it all.
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "io/drum_output.hpp"
#include "io/output.hpp"
#include "io/snapshots.hpp"
#include "tumble/analysis/drum_measure.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::cli {

namespace {

double rms_grain_speed(const ParticleStore& p) {
    double sum = 0.0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (!p.is_kinematic(i)) {
            sum += norm2(p.velocity[i]);
            ++n;
        }
    return n ? std::sqrt(sum / static_cast<double>(n)) : 0.0;
}

std::vector<io::DrumComponent> components_of(const Simulation& sim, const std::string& mode) {
    std::vector<io::DrumComponent> out(2);
    out[0] = {mode == "self" ? "left" : "material-1", 0, 0.0, -1.0};
    out[1] = {mode == "self" ? "right" : "material-2", 0, 0.0, +1.0};
    const ParticleStore& p = sim.particles();
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.is_kinematic(i)) continue;
        io::DrumComponent& c = out.at(static_cast<std::size_t>(p.tag[i]));
        ++c.grains;
        c.mass += p.mass[i];
    }
    return out;
}

}  // namespace

int drum_command(const DrumOptions& options) {
    io::DrumSettings s = options.settings;
    const double omega = s.omega();
    const double inner_radius = 0.5 * s.geometry.diameter;
    if (omega * omega * inner_radius / 9.81 > 1.0 && !options.quiet)
        fmt::print("note: Froude number {:.3g} > 1: above the critical speed the grains are held against the wall\n",
                   omega * omega * inner_radius / 9.81);

    DrumSetup setup = build_drum_scenario(s.geometry, s.mode, s.grain_count(), s.seed);
    if (s.dt > 0.0) setup.scenario.time_step.dt = s.dt;
    Simulation sim(std::move(setup.scenario), resolve_threads(options.threads));
    const double dt = sim.dt();

    io::DrumRunInfo info;
    info.mode = s.mode;
    info.omega = omega;
    info.froude = omega * omega * setup.wall.inner_radius / 9.81;
    info.revolutions = s.revolutions;
    info.seed = s.seed;
    info.wall_particles = setup.wall.particles.size();
    info.inner_radius = setup.wall.inner_radius;
    info.inner_length = setup.wall.inner_length;
    info.dt = dt;
    info.threads = sim.threads();
    info.samples_per_revolution = s.samples_per_revolution;
    info.profile_bins = s.profile_bins;
    info.components = components_of(sim, s.mode);
    double grain_volume = 0.0;
    std::size_t grains = 0;
    for (std::size_t i = 0; i < sim.particles().size(); ++i)
        if (!sim.particles().is_kinematic(i)) {
            grain_volume += 4.0 / 3.0 * pi * std::pow(sim.particles().radius[i], 3);
            ++grains;
        }
    info.solid_fraction = grain_volume / (pi * info.inner_radius * info.inner_radius * info.inner_length);

    io::prepare_output_directory(s.output, options.force);
    const bool talk = !options.quiet;
    if (talk)
        fmt::print("tumble drum: {} mode, {} grains ({} {}, {} {}), {} wall particles, inner radius {:.4g} m, "
                   "length {:.4g} m; dt = {:.3g} s\n",
                   s.mode, grains, info.components[0].grains, info.components[0].name, info.components[1].grains,
                   info.components[1].name, info.wall_particles, info.inner_radius, info.inner_length, dt);

    // Settle with the drum at rest: at least the time to fall the drum's
    // diameter twice, until the rms grain speed is below settle_speed.
    io::TimeSeriesWriter series(s.output / "time_series.csv", sim.scenario().materials);
    const double fall_time = 2.0 * std::sqrt(2.0 * s.geometry.diameter / 9.81);
    const std::int64_t check_every = std::max<std::int64_t>(1, std::llround(1e-3 / dt));
    {
        Progress progress(std::llround(s.settle_max_time / dt), grains, talk && progress_wanted());
        if (talk) fmt::print("settling (rms grain speed below {} m/s, at most {} s)\n", s.settle_speed, s.settle_max_time);
        while (sim.time() < s.settle_max_time) {
            sim.advance(check_every);
            progress.update(sim.step_count());
            if (sim.time() >= fall_time && rms_grain_speed(sim.particles()) < s.settle_speed) {
                info.settled = true;
                break;
            }
        }
        progress.finish();
    }
    info.settle_time = sim.time();
    series.write(sim.observe());
    analysis::DrumFrame frame{info.inner_length, info.inner_radius, 2, s.profile_bins, omega};
    info.fill_fraction = analysis::measure_drum(sim.particles(), frame).fill_fraction;
    if (talk)
        fmt::print("{} after {:.3g} s: rms grain speed {:.3g} m/s; fill fraction {:.3f}, solid fraction {:.3f}\n",
                   info.settled ? "settled" : "warning: NOT settled", info.settle_time,
                   rms_grain_speed(sim.particles()), info.fill_fraction, info.solid_fraction);

    // Rotate. Revolution N = 0 is the start of rotation.
    sim.set_motion(0, RigidMotion{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, omega, {0.0, 0.0, 0.0}});
    const double start = sim.time();
    const double period = 2.0 * pi / omega;
    const std::int64_t steps = std::llround(s.revolutions * period / dt);
    const std::int64_t sample_every = std::max<std::int64_t>(1, std::llround(period / s.samples_per_revolution / dt));
    const std::int64_t snapshot_every =
        s.snapshots_per_revolution > 0
            ? std::max<std::int64_t>(1, std::llround(period / s.snapshots_per_revolution / dt))
            : 0;
    std::optional<io::SnapshotSeries> snapshots;
    if (snapshot_every) snapshots.emplace(s.output);
    io::write_drum_run_info(s.output / "drum_run.toml", info);
    io::DrumSeriesWriter drum_series(s.output, info);
    if (talk) {
        fmt::print("rotating at {:.4g} rad/s (Froude {:.3g}) for {} revolutions: {} steps, {} samples per revolution\n",
                   omega, info.froude, s.revolutions, steps, s.samples_per_revolution);
        if (s.revolutions < 10.0)
            fmt::print("note: {} revolutions is a short run (the default is reduced so that it takes minutes); the "
                       "paper's runs span tens of revolutions: --revolutions N\n",
                       s.revolutions);
    }
    auto sample = [&] {
        const double revolutions = omega * (sim.time() - start) / (2.0 * pi);
        drum_series.write(revolutions, sim.time(), analysis::measure_drum(sim.particles(), frame));
        series.write(sim.observe());
    };
    Progress progress(steps, grains, talk && progress_wanted());
    sample();
    if (snapshot_every) snapshots->write(sim);
    for (std::int64_t k = 1; k <= steps; ++k) {
        sim.step();
        if (k % sample_every == 0) sample();
        if (snapshot_every && k % snapshot_every == 0) snapshots->write(sim);
        progress.update(k);
    }
    if (steps % sample_every != 0) sample();  // always end with the final state
    progress.finish();
    info.wall_seconds = progress.elapsed_seconds();
    info.grain_updates_per_second =
        info.wall_seconds > 0.0 ? static_cast<double>(grains) * static_cast<double>(steps) / info.wall_seconds : 0.0;
    io::write_drum_run_info(s.output / "drum_run.toml", info);
    if (talk)
        fmt::print("rotation simulated in {:.1f} s: {:.3g} grain updates/s on {} thread{} ({:.1f} s per revolution)\n\n",
                   info.wall_seconds, info.grain_updates_per_second, info.threads, info.threads == 1 ? "" : "s",
                   info.wall_seconds / s.revolutions);
    const std::string summary = io::analyze_drum_run(s.output);
    if (talk) fmt::print("{}\nwritten to {}\n", summary, s.output.string());
    if (options.plot) {
        // The figures are a convenience: a machine without matplotlib still
        // has every number in the run directory.
        if (plot_command("run", {s.output.string()}, "", options.quiet) != 0)
            fmt::print(stderr, "tumble drum: warning: the figures could not be drawn (tumble plot {})\n",
                       s.output.string());
    }
    return 0;
}

int analyze_command(const std::string& directory) {
    fmt::print("{}", io::analyze_drum_run(directory));
    return 0;
}

}  // namespace tumble::cli
