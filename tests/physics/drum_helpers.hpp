// SPDX-License-Identifier: MIT
// Running the drum experiment through the engine API, for the drum tests.
#pragma once

#include <cmath>
#include <vector>

#include "tumble/analysis/drum_measure.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/setup/drum.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::drum_test {

struct DrumRun {
    DrumSetup setup;
    Simulation sim;
    analysis::DrumFrame frame;

    DrumRun(const std::string& mode, std::size_t grains, std::uint64_t seed)
        : setup(build_drum_scenario(DrumGeometry{}, mode, grains, seed)), sim(setup.scenario),
          frame{setup.wall.inner_length, setup.wall.inner_radius, 2, 12, 1.0} {}

    void settle(double seconds) { sim.advance(std::llround(seconds / sim.dt())); }

    // Starts the rotation; returns the number of steps per revolution.
    std::int64_t rotate(double omega) {
        frame.rotation = omega;
        sim.set_motion(0, RigidMotion{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, omega, {0.0, 0.0, 0.0}});
        return std::llround(2.0 * pi / omega / sim.dt());
    }

    analysis::DrumState measure() const { return analysis::measure_drum(sim.particles(), frame); }
};

}  // namespace tumble::drum_test
