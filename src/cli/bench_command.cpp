// SPDX-License-Identifier: MIT
// tumble bench: the paper's dense periodic cube (SPEC-NOTES "Speed").
#include <chrono>
#include <fstream>

#include <unistd.h>

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "experiments/machine.hpp"
#include "tumble/setup/benchmark_cube.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::cli {

namespace {
constexpr double paper_best_updates_per_second = 45.2e3;  // IBM Power2, paper table 1

// Resident memory of this process now, bytes (Linux /proc/self/statm; 0 elsewhere).
double resident_bytes() {
    std::ifstream statm("/proc/self/statm");
    double pages_total = 0.0, pages_resident = 0.0;
    if (!(statm >> pages_total >> pages_resident)) return 0.0;
    return pages_resident * static_cast<double>(sysconf(_SC_PAGESIZE));
}
}  // namespace

int bench_command(const BenchOptions& options) {
    const double resident_before = resident_bytes();
    Simulation sim(benchmark_cube(options.size, options.seed), resolve_threads(options.threads));
    const std::size_t n = sim.particles().size();
    if (!options.json)
        fmt::print("tumble bench: {0}^3 = {1} spheres of material 1, periodic cube, dt = {2} s, all terms on\n",
                   options.size, n, sim.dt());
    sim.advance(options.warmup);
    const std::int64_t builds_before = sim.neighbors().builds();
    const auto start = std::chrono::steady_clock::now();
    sim.advance(options.steps);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const Observables o = sim.observe();
    const double updates = static_cast<double>(n) * static_cast<double>(options.steps) / seconds;
    const double contacts_per_particle = 2.0 * static_cast<double>(o.contacts) / static_cast<double>(n);
    const std::string machine = machine_description();
    const std::int64_t builds = sim.neighbors().builds() - builds_before;
    // What the simulation holds (particles, neighbour list with history, the
    // scenario it was built from, thread buffers), per particle: the growth of
    // the resident memory from before the set-up to the end of the run.
    const double bytes_per_particle = (resident_bytes() - resident_before) / static_cast<double>(n);

    if (!options.json) {
        fmt::print("  steps            {} (after {} warm-up steps)\n", options.steps, options.warmup);
        fmt::print("  wall time        {:.3f} s\n", seconds);
        fmt::print("  updates/s        {:.4g}  ({:.0f}x the paper's best, 45.2 thousand on an IBM Power2)\n",
                   updates, updates / paper_best_updates_per_second);
        fmt::print("  contacts/sphere  {:.3f}\n", contacts_per_particle);
        fmt::print("  list rebuilds    {}\n", builds);
        fmt::print("  threads          {}\n", sim.threads());
        fmt::print("  memory           {:.0f} bytes per sphere (resident, measured)\n", bytes_per_particle);
        fmt::print("  machine          {}\n", machine);
    }
    if (options.json)
        fmt::print(
        "{{\"code\": \"tumble\", \"version\": \"{}\", \"particles\": {}, \"steps\": {}, \"seconds\": {}, "
        "\"updates_per_second\": {}, \"contacts_per_particle\": {}, \"neighbor_builds\": {}, \"threads\": {}, "
        "\"bytes_per_particle\": {:.0f}, \"dt\": {}, \"machine\": \"{}\"}}\n",
        TUMBLE_VERSION, n, options.steps, seconds, updates, contacts_per_particle, builds, sim.threads(),
        bytes_per_particle, sim.dt(), machine);
    return 0;
}

}  // namespace tumble::cli
