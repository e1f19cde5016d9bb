// SPDX-License-Identifier: MIT
// The steps' time by phase (sim/step_clock.hpp): every step counted once,
// the phases within the wall-clock time of the steps and most of it, and
// reading the clock leaves the results alone.
#include <gtest/gtest.h>

#include <chrono>
#include <numeric>

#include "physics_helpers.hpp"

namespace physics_test {
namespace {

double seconds_of_advance(tumble::Simulation& sim, std::int64_t steps) {
    const auto start = std::chrono::steady_clock::now();
    sim.advance(steps);
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The shaken box through list rebuilds, on 1 and 2 threads. The phases are
// laps of one clock inside advance(), so their sum cannot exceed its wall
// time (1 ms for the two clocks' readings apart); what lies outside them
// (starting the team, the prescribed motions' positions) is a few
// microseconds a step, far below half of a step's work, whatever the load
// of the machine (a thread held up is held up inside a phase).
TEST(StepClock, ThePhasesFillTheStepsAndCountEachOnce) {
    for (const int threads : {1, 2}) {
        tumble::Simulation sim(shaken_box(), threads);
        sim.advance(10);  // not counted: reset below
        sim.reset_step_times();
        const std::int64_t builds = sim.observe().neighbor_builds;
        const double wall = seconds_of_advance(sim, 3000);
        const tumble::StepTimes& t = sim.step_times();
        EXPECT_EQ(t.steps, 3000) << threads;
        const double sum = std::accumulate(t.seconds.begin(), t.seconds.end(), 0.0);
        EXPECT_LE(sum, wall + 1e-3) << threads;
        EXPECT_GE(sum, 0.5 * wall) << threads;
        const auto phase = [&](tumble::StepPhase p) { return t.seconds[static_cast<std::size_t>(p)]; };
        EXPECT_GT(phase(tumble::StepPhase::forces), 0.0);
        EXPECT_GT(phase(tumble::StepPhase::motion), 0.0);
        ASSERT_GT(sim.observe().neighbor_builds, builds + 5);  // the list was rebuilt: its time is told
        EXPECT_GT(phase(tumble::StepPhase::neighbours), 0.0);
        EXPECT_EQ(phase(tumble::StepPhase::exchange), 0.0);  // one process: nothing exchanged
        // Steps one at a time are counted alike (tumble run takes them so).
        for (int k = 0; k < 5; ++k) sim.step();
        EXPECT_EQ(sim.step_times().steps, 3005);
    }
}

TEST(StepClock, ResultsAreTheSameWithTheClockReadOrReset) {
    tumble::Simulation a(shaken_box(), 2), b(shaken_box(), 2);
    a.advance(200);
    for (int k = 0; k < 4; ++k) {
        b.reset_step_times();
        b.advance(50);
    }
    EXPECT_TRUE(a.particles().position == b.particles().position);
    EXPECT_TRUE(a.particles().velocity == b.particles().velocity);
    EXPECT_TRUE(a.particles().force == b.particles().force);
}

}  // namespace
}  // namespace physics_test
