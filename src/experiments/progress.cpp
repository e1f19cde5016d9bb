// SPDX-License-Identifier: MIT
#include "experiments/progress.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>
#include <vector>
#include <unistd.h>

#include <fmt/format.h>

namespace tumble::experiments {

ProgressStyle progress_style(bool quiet, double log_every) {
    using Output = ProgressStyle::Output;
    if (quiet) return {Output::none, log_every};
    if (isatty(fileno(stderr)) && std::getenv("CI") == nullptr) return {Output::terminal, log_every};
    return {log_every > 0.0 ? Output::log : Output::none, log_every};
}

std::string format_duration(double s) {
    if (!std::isfinite(s) || s < 0.0) return "?";
    if (s < 90.0) return fmt::format("{:.0f} s", s);
    if (s < 5400.0) return fmt::format("{:.0f} min {:02.0f} s", std::floor(s / 60.0), std::fmod(s, 60.0));
    return fmt::format("{:.0f} h {:02.0f} min", std::floor(s / 3600.0), std::floor(std::fmod(s, 3600.0) / 60.0));
}

Progress::Progress(std::string phase, std::int64_t first, std::int64_t total, ProgressStyle style, ProgressScale scale)
    : phase_(std::move(phase)), first_(first), total_(total), style_(style), scale_(std::move(scale)),
      start_(Clock::now()), last_print_(start_) {}

double Progress::elapsed_seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

// The log line (full) names every count and rate; the terminal's fits a line.
std::string Progress::line(std::int64_t at, const std::string& note, bool full) const {
    const double elapsed = elapsed_seconds();
    const double rate = elapsed > 0.0 ? static_cast<double>(at - first_) / elapsed : 0.0;  // counted per second
    const bool bounded = total_ > 0;
    std::vector<std::string> fields;
    const std::string percent = bounded ? fmt::format("{:.1f} %", 100.0 * static_cast<double>(at) / total_) : "";
    if (full)
        fields.push_back(bounded ? fmt::format("{} {} of {} ({})", scale_.unit, at, total_, percent)
                                 : fmt::format("{} {}", scale_.unit, at));
    else if (bounded)
        fields.push_back(percent);
    if (const double per = scale_.seconds_per_step; per > 0.0)
        fields.push_back(bounded ? fmt::format("t = {:.4g} s of {:.4g} s", at * per, total_ * per)
                                 : fmt::format("t = {:.4g} s", at * per));
    if (const double per = scale_.steps_per_revolution; per > 0.0)
        fields.push_back(bounded ? fmt::format("revolution {:.2f} of {:.4g}", at / per, total_ / per)
                                 : fmt::format("revolution {:.2f}", at / per));
    if (full) fields.push_back(fmt::format("{:.3g} {}/s", rate, scale_.unit));
    if (scale_.steps_per_revolution > 0.0)
        fields.push_back(fmt::format("{:.3g} rev/h", rate * 3600.0 / scale_.steps_per_revolution));
    if (full && scale_.particles > 0)
        fields.push_back(fmt::format("{:.3g} particle updates/s", rate * static_cast<double>(scale_.particles)));
    if (!note.empty()) fields.push_back(note);
    if (full) fields.push_back("elapsed " + format_duration(elapsed));
    if (bounded) fields.push_back("ETA " + format_duration(rate > 0.0 ? (total_ - at) / rate : -1.0));

    std::string text = full ? "progress: " + phase_ + ":" : "  " + phase_;
    for (std::size_t k = 0; k < fields.size(); ++k) text += (full && k > 0 ? ", " : full ? " " : "  ") + fields[k];
    return text;
}

void Progress::update(std::int64_t at, const std::string& note) {
    using Output = ProgressStyle::Output;
    if (style_.output == Output::none) return;
    const auto now = Clock::now();
    const auto interval = style_.output == Output::terminal
                              ? std::chrono::duration<double>(0.5)
                              : std::chrono::duration<double>(style_.log_every);
    if (now - last_print_ < interval) return;
    last_print_ = now;
    if (style_.output == Output::terminal) {
        fmt::print(stderr, "\r{}   ", line(at, note, false));
        std::fflush(stderr);
    } else {
        fmt::print("{}\n", line(at, note, true));
    }
}

void Progress::finish() {
    if (style_.output == ProgressStyle::Output::terminal) fmt::print(stderr, "\r\033[K");
}

}  // namespace tumble::experiments
