// SPDX-License-Identifier: MIT
#include "experiments/progress.hpp"

#include <cstdio>
#include <cstdlib>
#include <utility>
#include <unistd.h>

#include <fmt/format.h>

namespace tumble::experiments {

bool progress_wanted() { return isatty(fileno(stderr)) && std::getenv("CI") == nullptr; }

Progress::Progress(std::int64_t total_steps, std::size_t particles, bool enabled, std::string rate_unit)
    : total_(total_steps), particles_(static_cast<double>(particles)), enabled_(enabled),
      rate_unit_(std::move(rate_unit)), start_(Clock::now()), last_print_(start_) {}

double Progress::elapsed_seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

void Progress::update(std::int64_t done) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (now - last_print_ < std::chrono::milliseconds(500)) return;
    last_print_ = now;
    const double elapsed = elapsed_seconds();
    const double rate = done > 0 ? done / elapsed : 0.0;
    const double left = rate > 0 ? (total_ - done) / rate : 0.0;
    fmt::print(stderr, "\r  {:5.1f} %  {:8.3g} {}  ETA {:4.0f} s   ",
               100.0 * static_cast<double>(done) / static_cast<double>(total_), rate * particles_, rate_unit_, left);
    std::fflush(stderr);
}

void Progress::finish() {
    if (enabled_) fmt::print(stderr, "\r{:70}\r", "");
}

}  // namespace tumble::experiments
