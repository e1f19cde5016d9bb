// SPDX-License-Identifier: MIT
// What a run may ask of the machine, checked from its inputs before any
// work is done (docs/CHECKPOINTS.md, "Limits"): the number of steps, the
// threads, and the memory, each refused with the value and the option or
// key that drives it.
#pragma once

#include <cstdint>
#include <string>

#include "io/config.hpp"
#include "tumble/setup/drum.hpp"
#include "tumble/sim/scenario.hpp"
#include "tumble/sim/time_step.hpp"

namespace tumble::experiments {

// More steps than any run can finish (10^12: days at a million steps a second).
inline constexpr double max_steps = 1e12;

// ceil(seconds / dt), the steps of an interval; tumble::Error naming `what`
// (the option or key) if it is not a finite count of at most max_steps.
std::int64_t step_count(double seconds, double dt, const std::string& what);

// A drum's settling and rotation in steps of dt: each a count a run can
// finish, and the rotation long enough for a sample after its start (the
// analysis needs two). For a new run, a checkpoint's plan and a sweep's
// points alike; tumble::Error naming the options otherwise.
void check_drum_durations(double revolutions, double omega, int samples_per_revolution, double settle_max_time,
                          double dt);

// The command line's checks of the numbers a run is given, in its words
// (the option validators of cli/main.cpp), so that the Python functions
// refuse their arguments alike, naming them: "" if `value` is fine, else
// "must be ..., got TEXT" (TEXT: the value as given).
std::string finite_positive_problem(double value, const std::string& text);
// A thread count: a whole number >= 0 (0: every core).
std::string thread_count_problem(double value, const std::string& text);

// The memory a run will need, estimated from its inputs
// (docs/BENCHMARKS.md, "Memory per sphere"), and what drives it.
struct MemoryNeed {
    double bytes = 0.0;
    std::string driver;  // the option or key that makes it large, with the count
};
// A scenario's from its settings and its spheres as its reader counts them
// (io::ParticleCount), before any is made.
MemoryNeed scenario_memory(const io::RunConfig& settings, const io::ParticleCount& count, int threads);
// skin: the drum's neighbour skin, m (0: automatic).
MemoryNeed drum_memory(const DrumGeometry& g, double grains, int threads, double skin);

// The number of wall spheres build_drum_wall lays out for g (none for
// smooth walls), estimated in floating point (no overflow for any size).
double drum_wall_spheres(const DrumGeometry& g);

// A drum whose wall needs far more spheres than the drum holds grains is
// nearly always a unit slip (--diameter 8 meant as 8 cm builds 2.9 million
// wall spheres for 1000 grains). More than max(50 x grains, 100,000) wall
// spheres is refused, before any work, with the numbers, unless `allowed`
// (tumble drum --large-drum). tumble::Error "SOURCE: ...".
void check_drum_size(const DrumGeometry& g, double grains, bool allowed, const std::string& source);

// A material so soft that its grains sink into each other under their own
// weight is nearly always a unit slip (E = 1.0 meant as 1 MPa: 39 %
// overlaps in a bed). For each material of free grains, with its largest
// grains: a Hertz overlap of one resting on another under gravity above 5 %
// of the radius (the paper's grains: 0.44 %), or of two meeting head-on at
// the reference speed above their reduced radius (they would pass through
// each other), is refused before any work, with the numbers, unless
// `allowed` (tumble run --allow-soft). So is a surface energy W whose
// attraction alone would pull two grains at rest into each other by more
// than their reduced radius (the paper's grains: 2.5 %; nearly always W in
// the wrong unit), for every kind of contact of the scenario.
// tumble::Error "SOURCE: ...".
void check_stiffness(const Scenario& s, bool allowed, const std::string& source);

// The time step in use (TimeStepReport::dt) must be > 0 s and finite: a
// density, modulus or radius out of range (rho = 1e-300 kg/m^3), or a
// reference speed of 1e308 m/s, gives 0 s, with which nothing advances.
// tumble::Error "SOURCE: ..." naming what set it.
void check_time_step(const TimeStepReport& t, const std::string& source);

// The limit: `gib` GiB if > 0, else half the machine's memory (or the
// process's address-space limit, ulimit -v, if lower).
double memory_limit_bytes(double gib);
// tumble::Error "SOURCE: ..." with the estimate, its driver and the limit if
// need > limit; `source` is the input file or "command line", `option` the
// setting of the limit ("--max-memory GIB").
void check_memory(const MemoryNeed& need, double limit_bytes, const std::string& source, const std::string& option);

// The scenario reader's check (io::ParticleCheck) of the memory a run of
// the scenario on `threads` threads will need, against limit_bytes: a
// scenario of more is refused before any of its spheres is made (a lattice
// of 10^7 spheres in a second, not after building gigabytes).
io::ParticleCheck scenario_memory_check(int threads, double limit_bytes, const std::string& option);

}  // namespace tumble::experiments
