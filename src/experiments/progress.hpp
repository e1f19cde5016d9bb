// SPDX-License-Identifier: MIT
// The progress of a long loop (a run, a drum's settling and rotation, a
// movie's frames, a sweep), told one of two ways:
//   on a terminal  a live line on stderr, redrawn twice a second and wiped at
//                  the end (when stderr is a terminal and CI is unset);
//   in a log       otherwise (nohup, a batch system, a redirected run), a line
//                  on stdout every `log_every` seconds, as LAMMPS's thermo
//                  lines: "progress: rotation: step 24000 of 576950 (4.2 %),
//                  revolution 0.50 of 12, 3.4e+03 steps/s, 26 rev/h, ...".
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace tumble::experiments {

inline constexpr double default_progress_every = 30.0;  // s between log lines (--progress-every)

struct ProgressStyle {
    enum class Output { none, terminal, log };
    Output output = Output::none;
    double log_every = default_progress_every;  // s between log lines
};

// Nothing when quiet; the live line when stderr is a terminal (and CI is
// unset); else log lines every log_every seconds, none if it is 0.
ProgressStyle progress_style(bool quiet, double log_every = default_progress_every);

// What the counted steps mean: each shown only when set (non-zero).
struct ProgressScale {
    std::string unit = "steps";         // what is counted ("frames", "points")
    std::size_t particles = 0;          // moved per step: the rate in particle updates/s too
    double seconds_per_step = 0.0;      // simulated time per step: t of the total
    double steps_per_revolution = 0.0;  // revolutions of the total, and the rate in revolutions per hour
};

// "42 s", "3 min 05 s", "2 h 10 min"; "?" if not finite or negative.
std::string format_duration(double seconds);

class Progress {
public:
    // Counts from `first` (> 0 after a resume) to `total` (0: no known end,
    // so no percentage or ETA: the caller's note says how far it is).
    Progress(std::string phase, std::int64_t first, std::int64_t total, ProgressStyle style, ProgressScale scale = {});
    // Position `at` reached; `note` is added to the line (e.g. how near the
    // bed is to settled).
    void update(std::int64_t at, const std::string& note = {});
    void finish();
    double elapsed_seconds() const;

private:
    using Clock = std::chrono::steady_clock;
    std::string line(std::int64_t at, const std::string& note, bool full) const;

    std::string phase_;
    std::int64_t first_, total_;
    ProgressStyle style_;
    ProgressScale scale_;
    Clock::time_point start_;
    Clock::time_point last_print_;
};

}  // namespace tumble::experiments
