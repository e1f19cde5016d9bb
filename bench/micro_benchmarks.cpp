// SPDX-License-Identifier: MIT
// Micro-benchmarks (Google Benchmark) of the parts of the time step, on the
// paper's benchmark cube (SPEC-NOTES "Speed"; 21^3 = 9261 spheres, 3 pairs
// and 6 contacts per sphere). Run: build/bench/tumble_micro
//   [--benchmark_filter=PairLoop] [--benchmark_repetitions=5]
// Rates: items_per_second counts pairs (PairLoop, ContactLaw), particles
// (NeighbourBuild, Step). Two more measure the machine's own limits for the
// estimate in docs/BENCHMARKS.md: memory bandwidth (Triad, bytes_per_second)
// and the sqrt and divide throughput, scalar (SqrtDivide) and vectorised
// (SqrtDivideVector). The engine's loops run on the instruction set in use
// (tumble/core/isa.hpp; TUMBLE_ISA chooses another), as in a simulation.
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "tumble/core/isa.hpp"
#include "tumble/neighbor/candidate_pairs.hpp"
#include "tumble/setup/benchmark_cube.hpp"
#include "tumble/sim/pair_loop.hpp"
#include "tumble/sim/simulation.hpp"

namespace {

using namespace tumble;

// The cube after 200 steps: every contact of the lattice is on, with history.
Simulation settled_cube(int size, int threads) {
    Simulation sim(benchmark_cube(size, 1), threads);
    sim.advance(200);
    return sim;
}

// The contact law alone, on one contact of the lattice (overlap 0.02 R,
// small relative velocities): the cost of the physics per contact.
void ContactLaw(benchmark::State& state) {
    const Scenario s = benchmark_cube(4, 1);
    const PairTable table(s.materials, s.pair_properties);
    const double R = s.materials[0].radius;
    const ContactGeometry g = make_contact_geometry({1.98 * R, 0.0, 0.0}, 1.98 * R, R, R,
                                                    Vec3{1e-3, 2e-4, -3e-4} - Vec3{-1e-3, 1e-4, 2e-4}, {1e-6, 0.0, 0.0},
                                                    {0.1, -0.2, 0.3}, {-0.1, 0.05, 0.2});
    ContactHistory history;
    for (auto _ : state) {
        benchmark::DoNotOptimize(g);
        run_for_isa([&] {
            ContactForces f = contact_law(table(0, 0), g, s.model, 1e-5, history);
            benchmark::DoNotOptimize(f);
        });
    }
    state.SetItemsProcessed(state.iterations());
}
BENCHMARK(ContactLaw);

// The pair loop over the whole half list of the cube, one thread: gather
// the two spheres, geometry, contact law, scatter to both.
void PairLoop(benchmark::State& state) {
    Simulation sim = settled_cube(static_cast<int>(state.range(0)), 1);
    ParticleStore p = sim.particles();
    PairList pairs = sim.neighbors().pairs();
    const PairTable table(sim.scenario().materials, sim.scenario().pair_properties);
    std::vector<ContactRecord> none;
    for (auto _ : state) {
        run_for_isa([&] {
            add_contact_forces<false>(p, pairs, {0, pairs.size()}, sim.neighbors().images(), table,
                                      sim.scenario().model, sim.dt(), p.force.data(), p.torque.data(), none);
        });
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(pairs.size()));
    state.counters["pairs"] = static_cast<double>(pairs.size());
}
BENCHMARK(PairLoop)->Arg(21)->Arg(46)->Unit(benchmark::kMicrosecond);

// A neighbour-list build from scratch by linked cells (the candidate pairs
// only; VerletList::rebuild adds the sort and the history transfer).
void NeighbourBuild(benchmark::State& state) {
    const Simulation sim = settled_cube(static_cast<int>(state.range(0)), 1);
    PairList pairs;
    for (auto _ : state) {
        cell_list_pairs(sim.particles(), sim.scenario().domain, sim.neighbors().skin(), pairs);
        benchmark::DoNotOptimize(pairs.first.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sim.particles().size()));
}
BENCHMARK(NeighbourBuild)->Arg(21)->Arg(46)->Unit(benchmark::kMillisecond);

// A whole time step (kicks, drift, rebuild check, forces) on 1 or 2 threads.
void Step(benchmark::State& state) {
    Simulation sim = settled_cube(21, static_cast<int>(state.range(0)));
    for (auto _ : state) sim.step();
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(sim.particles().size()));
}
BENCHMARK(Step)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond)->UseRealTime();

// Memory bandwidth: a[i] = b[i] + s c[i] over three 64 MiB arrays (far
// beyond the caches), 24 bytes moved per element (STREAM's triad, counting
// no write-allocate traffic).
void Triad(benchmark::State& state) {
    const std::size_t n = std::size_t{8} << 20;
    std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
    for (auto _ : state) {
        for (std::size_t i = 0; i < n; ++i) a[i] = b[i] + 0.5 * c[i];
        benchmark::DoNotOptimize(a.data());
        benchmark::ClobberMemory();
    }
    state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(3 * n * sizeof(double)));
}
BENCHMARK(Triad)->Unit(benchmark::kMillisecond);

// Scalar square roots and divisions, as the pair loop does them (one of
// each per item, independent from item to item): their throughput bounds
// a scalar force loop that needs four of each per contact.
[[gnu::optimize("no-tree-vectorize")]] void SqrtDivide(benchmark::State& state) {
    std::vector<double> x(4096);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = 1.0 + 1e-3 * static_cast<double>(i);
    double sum = 0.0;
    for (auto _ : state) {
        for (double v : x) sum += 1.0 / std::sqrt(v);
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(x.size()));
}
BENCHMARK(SqrtDivide);

// The same, vectorised as the compiler vectorises the contact law (8 lanes
// with AVX-512): the bound of the vectorised pair loop.
void SqrtDivideVector(benchmark::State& state) {
    std::vector<double> x(4096), y(4096);
    for (std::size_t i = 0; i < x.size(); ++i) x[i] = 1.0 + 1e-3 * static_cast<double>(i);
    for (auto _ : state) {
        for (std::size_t i = 0; i < x.size(); ++i) y[i] = 1.0 / std::sqrt(x[i]);
        benchmark::DoNotOptimize(y.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(x.size()));
}
BENCHMARK(SqrtDivideVector);

}  // namespace

BENCHMARK_MAIN();
