// SPDX-License-Identifier: MIT
// tumble bench: the paper's dense periodic cube (docs/BENCHMARKS.md), or the
// long flowing drum (docs/BENCHMARKS.md).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <fstream>
#include <iterator>
#include <optional>

#include <unistd.h>

#include <fmt/format.h>

#include "experiments/run_control.hpp"
#include "cli/commands.hpp"
#include "experiments/drum_setup.hpp"
#include "experiments/limits.hpp"
#include "experiments/machine.hpp"
#include "io/checkpoint.hpp"
#include "io/drum_config.hpp"
#include "io/json.hpp"
#include "io/output.hpp"
#include "io/step_times.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/core/isa.hpp"
#include "tumble/core/mpi.hpp"
#include "tumble/setup/benchmark_cube.hpp"
#include "tumble/setup/drum.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::cli {

namespace fs = std::filesystem;

namespace {
constexpr double paper_best_updates_per_second = 45.2e3;  // IBM Power2, paper table 1

// Resident memory of this process now, bytes (Linux /proc/self/statm; 0 elsewhere).
double resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    double pages_total = 0.0, pages_resident = 0.0;
    if (!(statm >> pages_total >> pages_resident)) return 0.0;
    return pages_resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}

// CPU time of this process so far, all threads, s.
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// Times `steps` steps of `sim`; returns the wall time, s, and sets `cpu`
// to the process's CPU time over them (about threads x wall when each
// thread had a core to itself; less when it waited for one). The steps'
// time by phase (sim.step_times()) is then theirs alone.
double timed_advance(Simulation& sim, std::int64_t steps, double& cpu) {
    sim.reset_step_times();
    const double cpu_start = cpu_seconds();
    const auto start = std::chrono::steady_clock::now();
    sim.advance(steps);
    cpu = cpu_seconds() - cpu_start;
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

int cube_bench(const BenchOptions& options) {
    const std::int64_t steps = options.steps.value_or(2000), warmup = options.warmup.value_or(200);
    const double resident_before = resident_bytes();
    Simulation sim(benchmark_cube(options.size, options.seed), resolve_threads(options.threads));
    const std::size_t n = sim.particles().size();
    if (!options.json)
        fmt::print("tumble bench: {0}^3 = {1} spheres of material 1, periodic cube, dt = {2} s, all terms on\n",
                   options.size, n, sim.dt());
    sim.advance(warmup);
    const std::int64_t builds_before = sim.neighbors().builds();
    double cpu = 0.0;
    const double seconds = timed_advance(sim, steps, cpu);
    const io::StepTimesSpread phases = io::step_times_spread(sim.step_times(), seconds, sim.threads(), false);
    const Observables o = sim.observe();
    const double updates = static_cast<double>(n) * static_cast<double>(steps) / seconds;
    const double contacts_per_particle = 2.0 * static_cast<double>(o.contacts) / static_cast<double>(n);
    const std::string machine = machine_description();
    const std::int64_t builds = sim.neighbors().builds() - builds_before;
    // What the simulation holds (particles, neighbour list with history, the
    // scenario it was built from, thread buffers), per particle: the growth of
    // the resident memory from before the set-up to the end of the run.
    const double bytes_per_particle = (resident_bytes() - resident_before) / static_cast<double>(n);

    if (!options.json) {
        fmt::print("  steps            {} (after {} warm-up steps)\n", steps, warmup);
        fmt::print("  wall time        {:.3f} s (CPU {:.3f} s)\n", seconds, cpu);
        fmt::print("  updates/s        {:.4g}  ({:.0f}x the paper's best, 45.2 thousand on an IBM Power2)\n",
                   updates, updates / paper_best_updates_per_second);
        fmt::print("  contacts/sphere  {:.3f}\n", contacts_per_particle);
        fmt::print("  list rebuilds    {}\n", builds);
        fmt::print("  threads          {} (bound to cores: {})\n", sim.threads(), thread_binding());
        fmt::print("  instruction set  {}\n", isa_description());
        fmt::print("  memory           {:.0f} bytes per sphere (resident, measured)\n", bytes_per_particle);
        fmt::print("  machine          {}\n", machine);
        fmt::print("\n{}", io::step_times_text(phases, "the timed steps"));
    }
    if (options.json)
        fmt::print("{}\n", io::json_line(io::Json{{"code", "tumble"},
                                                  {"version", TUMBLE_VERSION},
                                                  {"case", "cube"},
                                                  {"particles", n},
                                                  {"steps", steps},
                                                  {"seconds", seconds},
                                                  {"updates_per_second", updates},
                                                  {"contacts_per_particle", contacts_per_particle},
                                                  {"neighbor_builds", builds},
                                                  {"threads", sim.threads()},
                                                  {"thread_binding", thread_binding()},
                                                  {"bytes_per_particle", std::llround(bytes_per_particle)},
                                                  {"dt", sim.dt()},
                                                  {"cpu_seconds", cpu},
                                                  {"time_by_phase", io::step_times_json(phases)},
                                                  {"machine", machine},
                                                  {"isa", isa_description()}}));
    return 0;
}

// A bed kept in the cache as a checkpoint file: read if an earlier run left
// it there (`made` false), else made by make() and stored there (`made` true).
template <class Make>
Simulation cached_bed(const fs::path& file, std::size_t particles, int threads, bool& made, Make&& make) {
    if (std::ifstream in{file, std::ios::binary}) {
        const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        io::Checkpoint bed = io::decode_checkpoint(bytes, file.string());
        if (bed.scenario.particles.size() != particles)
            throw Error(file.string() + ": the stored bed has " + std::to_string(bed.scenario.particles.size()) +
                        " particles, this drum " + std::to_string(particles) + "; remove the file to have it made again");
        Simulation sim(std::move(bed.scenario), threads);
        sim.restore(std::move(bed.state));
        made = false;
        return sim;
    }
    Simulation sim = make();
    made = true;
    if (mpi::rank() != 0) return sim;  // under mpirun every rank makes the same bed; rank 0 stores it
    fs::create_directories(file.parent_path());
    const fs::path part = file.string() + ".tmp";
    {
        std::ofstream out(part, std::ios::binary | std::ios::trunc);
        out << io::encode_checkpoint(checkpoint_of(sim));
        if (!out.flush()) throw Error(part.string() + ": cannot write the bed");
    }
    fs::rename(part, file);  // a run killed while writing leaves no partial bed under the real name
    return sim;
}

// The drum's bed, settled at rest as tumble drum settles it, then turned for
// `turned` revolutions at the drum's speed (0: not at all); each read from
// the cache if an earlier run left it there, else made and stored there.
// `made` tells which.
Simulation drum_bed(const io::DrumSettings& d, double turned, const fs::path& cache, int threads, bool& made) {
    io::DrumSettings automatic = d;  // the bed at the automatic skin, whatever --skin asks of the timed steps
    automatic.skin = 0.0;
    DrumSetup setup = build_drum(automatic);
    const std::size_t particles = setup.scenario.particles.size();
    // The bed is settled at the step and skin it will run at: the name holds
    // both, so a change of the automatic step or skin makes a new bed.
    // (Any checkpoint format this tumble reads will do: a new format needs no new bed.)
    const double dt = assess_time_step(setup.scenario).dt;
    // The particle-walled bed keeps the name it had before smooth walls.
    const std::string walls =
        d.geometry.walls == DrumWalls::particles ? std::string() : fmt::format("-{}", keyword_of(drum_wall_kinds, d.geometry.walls));
    const std::string stem = fmt::format("long-drum{}-length{}-fill{}-seed{}-dt{:.6g}-skin{:.6g}", walls,
                                         d.geometry.length, d.fill_fraction, d.seed, dt, setup.scenario.neighbor.skin);
    auto settle = [&] {
        Simulation sim(std::move(setup.scenario), threads);
        const std::int64_t check_every = std::max<std::int64_t>(1, std::llround(1e-3 / sim.dt()));
        const double fall_time = drum_fall_time(d);
        while (sim.time() < d.settle_max_time &&
               (sim.time() < fall_time || rms_grain_speed(sim) >= d.settle_speed))
            sim.advance(check_every);
        if (rms_grain_speed(sim) >= d.settle_speed)
            fmt::print(stderr, "tumble bench: warning: the bed did not settle within {} s\n", d.settle_max_time);
        return sim;
    };
    if (turned == 0.0) return cached_bed(cache / (stem + ".tck"), particles, threads, made, settle);
    return cached_bed(cache / fmt::format("{}-turned{}.tck", stem, turned), particles, threads, made, [&] {
        bool settled_made = false;
        Simulation sim = cached_bed(cache / (stem + ".tck"), particles, threads, settled_made, settle);
        sim.set_motion(0, drum_rotation(d.omega()));
        sim.advance(std::llround(turned * 2.0 * pi / d.omega() / sim.dt()));
        return sim;
    });
}

fs::path default_cache() {
    std::error_code error;
    const fs::path executable = fs::read_symlink("/proc/self/exe", error);
    return (error ? fs::current_path() : executable.parent_path()) / "bench-cache";
}

int long_drum_bench(const BenchOptions& options) {
    const std::int64_t steps = options.steps.value_or(10000), warmup = options.warmup.value_or(2000);
    io::DrumSettings d;  // the paper's drum: two components, 5 rad/s, end caps
    d.geometry.length = options.length;
    d.fill_fraction = options.fill;
    d.skin = options.skin;  // checked with the rest; drum_bed() settles at the automatic skin
    d.geometry.walls = find_keyword(drum_wall_kinds, options.walls)->value;
    io::check_drum_settings(d, "command line");
    const int threads = resolve_threads(options.threads);
    check_memory(drum_memory(d.geometry, static_cast<double>(d.grain_count()), threads, options.skin),
                 memory_limit_bytes(0.0), "command line", "--max-memory GIB");
    const double resident_before = resident_bytes();
    const fs::path cache = options.cache.empty() ? default_cache() : options.cache;
    bool made = false;
    Simulation bed = drum_bed(d, options.turned, cache, threads, made);
    const std::string bed_name =
        options.turned == 0.0 ? std::string("settled") : fmt::format("turned {} revolutions", options.turned);
    if (!options.export_dir.empty()) {  // the start of a peer code's run on the same bed
        const fs::path file = io::write_snapshot(options.export_dir, 0, bed);
        if (!options.json) fmt::print("tumble bench: the bed ({}) is in {}\n", bed_name, file.string());
        return 0;
    }
    // Under mpirun the bed is shared out among the ranks, a slab each; with
    // --skin its list is found anew with that skin (the bed's pairs and their
    // histories kept, by global id); with --law peer the timed steps run the
    // law of bench/peers/lammps_drum.in, which LAMMPS's pair_style granular
    // can run: no attraction (W = 0 for every pair: hertz/material has
    // none) and the tangential spring held at the friction limit (shear =
    // spring: tangential mindlin; the twisting couple held at its limit, as
    // twisting marshall), at the bed's step, so that the two codes do the
    // same work on the same bed (studies/performance/LOG.md, "The same law in both
    // codes").
    const bool peer_law = options.law == "peer";
    std::optional<Simulation> shared;
    if (mpi::size() > 1 || options.skin > 0.0 || peer_law) {
        Scenario scenario = bed.scenario();
        SimulationState state = bed.capture();
        if (options.skin > 0.0) {
            scenario.neighbor.skin = options.skin;
            state.list_from_histories = true;
        }
        if (peer_law) {
            for (auto& row : scenario.pair_properties)
                for (PairProperties& pair : row) pair.W = 0.0;
            scenario.model.shear = ShearModel::Spring;
            scenario.time_step.dt = bed.dt();
        }
        shared.emplace(std::move(scenario), threads, mpi::size() > 1 ? Ranks::world : Ranks::one);
        shared->restore(std::move(state));
    }
    Simulation& sim = shared ? *shared : bed;
    const bool talk = mpi::rank() == 0;
    const std::size_t n = sim.scenario().particles.size(), grains = sim.scenario().free_count();
    const double omega = d.omega();
    if (!options.json && talk)
        fmt::print("tumble bench: long drum, length {} m, fill {}: {} grains, {}, {} rad/s, {}; {} bed {}\n",
                   d.geometry.length, d.fill_fraction, grains,
                   d.geometry.walls == DrumWalls::particles
                       ? fmt::format("{} wall spheres", n - grains)
                       : std::string(d.geometry.walls == DrumWalls::smooth ? "smooth walls"
                                                                           : "a mantle of triangles and smooth caps"),
                   omega,
                   peer_law ? "the peer's law (no attraction, shear = spring)" : "the drum's law", bed_name,
                   (made ? "made and stored in " : "read from ") + cache.string());
    sim.set_motion(0, drum_rotation(omega));  // (a turned bed turns on: its wall spheres stay where they are)
    sim.advance(warmup);
    const std::int64_t builds_before = sim.neighbors().builds();
    double cpu = 0.0;
    mpi::any(false);  // shared among ranks: all start the clock together (a barrier)...
    double seconds = timed_advance(sim, steps, cpu);
    const io::StepTimesSpread phases = io::step_times_spread(sim.step_times(), seconds, sim.threads(), sim.shared());
    seconds = mpi::max(seconds);  // ...and the slowest stops it
    cpu = mpi::sum(cpu);
    const std::int64_t builds = sim.neighbors().builds() - builds_before;
    // A peer on the same bed is checked against this (bench/compare_drum.sh).
    const Observables o = sim.observe();
    const double grain_updates = static_cast<double>(grains) * static_cast<double>(steps) / seconds;
    const double steps_per_revolution = 2.0 * pi / omega / sim.dt();
    const double seconds_per_revolution = seconds / static_cast<double>(steps) * steps_per_revolution;
    const double revolutions_per_hour = 3600.0 / seconds_per_revolution;
    const TimeStepReport& t = sim.time_step_report();
    const std::string limited_by = t.automatic  ? t.recommended_by
                                   : peer_law ? "the bed's (the drum's automatic step, kept for --law peer)"
                                              : "given (--dt of the stored bed)";
    const double bytes_per_particle = (resident_bytes() - resident_before) / static_cast<double>(n);
    const std::string machine = machine_description();
    // Shared among ranks: the bytes each rank sent its neighbours per step
    // (ghost updates; and, averaged over the steps, the rebuilds'
    // migrations and ghost lists), the mean over the ranks; the ghosts it holds.
    double update_bytes = 0.0, rebuild_bytes = 0.0, ghosts = 0.0;
    // The neighbour list's pairs at the end (within the reach plus the skin;
    // `contacts` of them touch): what the pair loop works through. Shared
    // among ranks, the sum of the ranks' lists, which both hold a pair
    // across a cut (`contacts` counts it once).
    const double candidate_pairs = mpi::sum(static_cast<double>(sim.neighbors().pairs().size()));
    if (sim.slabs()) {
        const Slabs::Traffic& t = sim.slabs()->traffic();
        const auto ranks = static_cast<double>(mpi::size());
        update_bytes = mpi::sum(static_cast<double>(t.update_bytes) / static_cast<double>(t.updates)) / ranks;
        rebuild_bytes = mpi::sum(static_cast<double>(t.rebuild_bytes) / static_cast<double>(t.updates)) / ranks;
        ghosts = mpi::sum(static_cast<double>(sim.particles().size() - sim.owned())) / ranks;
    }
    if (!talk) return 0;

    if (!options.json) {
        fmt::print("  steps              {} (after {} warm-up steps turning, from the {} bed)\n", steps, warmup,
                   bed_name);
        fmt::print("  wall time          {:.3f} s (CPU {:.3f} s)\n", seconds, cpu);
        fmt::print("  grain updates/s    {:.4g}\n", grain_updates);
        fmt::print("  revolutions/hour   {:.4g}  ({:.4g} s per revolution)\n", revolutions_per_hour,
                   seconds_per_revolution);
        fmt::print("  steps/revolution   {:.0f}\n", steps_per_revolution);
        fmt::print("  dt                 {:.4g} s, set by {}\n", sim.dt(), limited_by);
        fmt::print("  list rebuilds      {} (skin {:.3g} m)\n", builds, sim.neighbors().skin());
        fmt::print("  pairs              {:.0f} in the list, {} of them touching (at the end)\n", candidate_pairs,
                   o.contacts);
        fmt::print("  kinetic energy     {:.4g} J translational, {:.4g} J rotational (grains, at the end)\n",
                   o.kinetic_translational, o.kinetic_rotational);
        fmt::print("  threads            {} (bound to cores: {})\n", sim.threads(), thread_binding());
        if (sim.slabs())
            fmt::print("  MPI ranks          {} (slabs along z): per rank and step {:.0f} bytes of ghost updates, {:.0f} of "
                       "rebuilds, {:.0f} ghosts\n",
                       mpi::size(), update_bytes, rebuild_bytes, ghosts);
        fmt::print("  instruction set    {}\n", isa_description());
        fmt::print("  memory             {:.0f} bytes per particle (grains and wall, resident, measured)\n",
                   bytes_per_particle);
        fmt::print("  machine            {}\n", machine);
        fmt::print("\n{}", io::step_times_text(phases, "the timed steps"));
    }
    if (options.json)
        fmt::print("{}\n", io::json_line(io::Json{{"code", "tumble"},
                                                  {"version", TUMBLE_VERSION},
                                                  {"case", "long-drum"},
                                                  {"length", d.geometry.length},
                                                  {"fill", d.fill_fraction},
                                                  {"grains", grains},
                                                  {"particles", n},
                                                  {"bed", made ? "made" : "read"},
                                                  {"turned", options.turned},
                                                  {"law", options.law},
                                                  {"walls", options.walls},
                                                  {"steps", steps},
                                                  {"warmup", warmup},
                                                  {"seconds", seconds},
                                                  {"grain_updates_per_second", grain_updates},
                                                  {"revolutions_per_hour", revolutions_per_hour},
                                                  {"seconds_per_revolution", seconds_per_revolution},
                                                  {"steps_per_revolution", steps_per_revolution},
                                                  {"dt", sim.dt()},
                                                  {"dt_limited_by", limited_by},
                                                  {"neighbor_builds", builds},
                                                  {"skin", sim.neighbors().skin()},
                                                  {"kinetic_translational", o.kinetic_translational},
                                                  {"kinetic_rotational", o.kinetic_rotational},
                                                  {"contacts", o.contacts},
                                                  {"candidate_pairs", std::llround(candidate_pairs)},
                                                  {"threads", sim.threads()},
                                                  {"thread_binding", thread_binding()},
                                                  {"ranks", mpi::size()},
                                                  {"ghost_update_bytes_per_step", update_bytes},
                                                  {"rebuild_bytes_per_step", rebuild_bytes},
                                                  {"ghosts_per_rank", ghosts},
                                                  {"bytes_per_particle", std::llround(bytes_per_particle)},
                                                  {"cpu_seconds", cpu},
                                                  {"time_by_phase", io::step_times_json(phases)},
                                                  {"machine", machine},
                                                  {"isa", isa_description()}}));
    return 0;
}
}  // namespace

int bench_command(const BenchOptions& options) {
    return options.bench_case == "long-drum" ? long_drum_bench(options) : cube_bench(options);
}

}  // namespace tumble::cli
