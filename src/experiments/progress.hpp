// SPDX-License-Identifier: MIT
// A one-line progress report on a terminal: done, rate (by default in
// particle updates per second: steps x particles), and the time left. Silent when stderr is not a terminal or
// when CI is set, so logs stay clean.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace tumble::experiments {

bool progress_wanted();

class Progress {
public:
    Progress(std::int64_t total_steps, std::size_t particles, bool enabled,
             std::string rate_unit = "particle updates/s");
    void update(std::int64_t steps_done);
    void finish();
    double elapsed_seconds() const;

private:
    using Clock = std::chrono::steady_clock;
    std::int64_t total_;
    double particles_;
    bool enabled_;
    std::string rate_unit_;
    Clock::time_point start_;
    Clock::time_point last_print_;
};

}  // namespace tumble::experiments
