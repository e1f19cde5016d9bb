// SPDX-License-Identifier: MIT
// Where a run's time went, as printed and written (io/step_times.hpp).
#include <gtest/gtest.h>

#include <string>

#include "io/step_times.hpp"

namespace {

tumble::StepTimes some_times() {
    tumble::StepTimes t;
    t.seconds = {1.0, 0.0, 0.5, 6.0};  // motion, exchange, neighbours, forces
    t.steps = 1000;
    return t;
}

TEST(StepTimes, OneProcessTheRestIsOtherAndTheShareOfTheWall) {
    const tumble::io::StepTimesSpread s = tumble::io::step_times_spread(some_times(), 8.0, 1, false);
    EXPECT_DOUBLE_EQ(s.other.mean, 0.5);  // 8 s less the phases' 7.5
    EXPECT_EQ(s.ranks, 1);
    const std::string text = tumble::io::step_times_text(s, "the run");
    EXPECT_EQ(text,
              "time by phase of the run: 8 s, 1000 steps\n"
              "  forces          6.000 s  75.0 %\n"
              "  neighbours      0.500 s   6.2 %\n"
              "  motion          1.000 s  12.5 %\n"
              "  other           0.500 s   6.2 %\n");  // no exchange: nothing was
    const tumble::io::Json j = tumble::io::step_times_json(s);
    EXPECT_EQ(j["steps"], 1000);
    EXPECT_DOUBLE_EQ(j["phases"]["forces"]["share"].get<double>(), 0.75);
    EXPECT_DOUBLE_EQ(j["phases"]["exchange"]["seconds"].get<double>(), 0.0);
    EXPECT_DOUBLE_EQ(j["phases"]["other"]["most"].get<double>(), 0.5);
}

// A clock that ran ahead of the wall time (they are read apart) leaves no
// negative rest.
TEST(StepTimes, TheRestIsNeverNegative) {
    EXPECT_EQ(tumble::io::step_times_spread(some_times(), 7.4, 1, false).other.mean, 0.0);
}

// Several ranks: the least and most of a rank beside the mean, and the
// threads' waits said.
TEST(StepTimes, RanksShowTheirSpread) {
    tumble::io::StepTimesSpread s = tumble::io::step_times_spread(some_times(), 8.0, 2, false);
    s.ranks = 2;
    s.phases[static_cast<std::size_t>(tumble::StepPhase::exchange)] = {0.25, 0.5, 0.75};
    const std::string text = tumble::io::step_times_text(s, "the timed steps");
    EXPECT_NE(text.find("on 2 ranks"), std::string::npos) << text;
    EXPECT_NE(text.find("2 threads, each phase with their wait for the slowest"), std::string::npos) << text;
    EXPECT_NE(text.find("  exchange        0.500 s   6.2 %   0.250 .. 0.750 s\n"), std::string::npos) << text;
}

}  // namespace
