// SPDX-License-Identifier: MIT
#include "io/step_times.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "tumble/core/mpi.hpp"

namespace tumble::io {

namespace {

PhaseSpread spread(double mine, bool shared) {
    if (!shared) return {mine, mine, mine};
    return {-mpi::max(-mine), mpi::sum(mine) / mpi::size(), mpi::max(mine)};
}

// The rows: the phases, the dearest first as a rule (as LAMMPS lists Pair,
// Neigh, Comm), then the rest.
struct Row {
    std::string_view name;
    const PhaseSpread* times;
};
std::array<Row, step_phase_count + 1> rows(const StepTimesSpread& s) {
    const auto row = [&](StepPhase p) {
        const auto k = static_cast<std::size_t>(p);
        return Row{step_phase_names[k], &s.phases[k]};
    };
    return {row(StepPhase::forces), row(StepPhase::neighbours), row(StepPhase::motion), row(StepPhase::exchange),
            Row{"other", &s.other}};
}

double share(const StepTimesSpread& s, double seconds) {
    return s.wall_seconds > 0.0 ? seconds / s.wall_seconds : 0.0;
}

}  // namespace

StepTimesSpread step_times_spread(const StepTimes& times, double wall_seconds, int threads, bool shared) {
    StepTimesSpread s;
    double in_steps = 0.0;
    for (std::size_t k = 0; k < step_phase_count; ++k) {
        s.phases[k] = spread(times.seconds[k], shared);
        in_steps += times.seconds[k];
    }
    // The clock's laps lie within the loop, so the rest is >= 0 but for
    // the clocks' own resolution.
    s.other = spread(std::max(wall_seconds - in_steps, 0.0), shared);
    s.wall_seconds = spread(wall_seconds, shared).mean;
    s.steps = times.steps;
    s.ranks = shared ? mpi::size() : 1;
    s.threads = threads;
    return s;
}

std::string step_times_text(const StepTimesSpread& s, std::string_view what) {
    const bool ranks = s.ranks > 1;
    std::string text = fmt::format("time by phase of {}: {:.3g} s, {} steps", what, s.wall_seconds, s.steps);
    if (ranks) text += fmt::format(" on {} ranks (s: mean of the ranks, then least and most)", s.ranks);
    if (s.threads > 1) text += fmt::format("; {} threads, each phase with their wait for the slowest", s.threads);
    text += "\n";
    for (const Row& row : rows(s)) {
        const PhaseSpread& t = *row.times;
        if (t.most <= 0.0 && row.name != "other") continue;  // a phase no step had (exchange on one rank)
        text += fmt::format("  {:<11} {:>9.3f} s {:>5.1f} %", row.name, t.mean, 100.0 * share(s, t.mean));
        if (ranks) text += fmt::format("   {:.3f} .. {:.3f} s", t.least, t.most);
        text += "\n";
    }
    return text;
}

Json step_times_json(const StepTimesSpread& s) {
    Json phases = Json::object();
    for (const Row& row : rows(s))
        phases[std::string(row.name)] = Json{{"seconds", row.times->mean},
                                             {"share", share(s, row.times->mean)},
                                             {"least", row.times->least},
                                             {"most", row.times->most}};
    return Json{{"wall_seconds", s.wall_seconds},
                {"steps", s.steps},
                {"ranks", s.ranks},
                {"threads", s.threads},
                {"phases", phases}};
}

}  // namespace tumble::io
