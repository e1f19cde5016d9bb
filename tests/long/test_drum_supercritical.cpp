// SPDX-License-Identifier: MIT
// Above the critical speed the grains are held against the wall and axial
// transport nearly stops. Minutes of run time: label "long"
// (ctest --test-dir build -L long).
//
// How far above: Fr = omega^2 R / g > 1 only lifts the grains off the
// bottom. To be carried round without slipping everywhere, a grain at angle
// theta from the bottom needs mu (Fr + cos theta) >= sin theta, i.e.
// Fr >= sqrt(1 + mu^2) / mu: 5.1 on the wall (mu = 0.2) and 10 between
// material-1 grains (mu = 0.1). Measured with 300 grains: at Fr = 2 the bed
// is a ring against the wall that keeps slipping (0.07 m/s relative to the
// drum, axial speeds of 2 cm/s, axial D as large as at Fr = 0.2); at Fr = 12
// it is locked (slip 1.6 mm/s, axial speeds 0.4 mm/s). So the test compares
// Fr = 0.2 with Fr = 12.
//
// What is compared: the axial diffusion coefficient from the grains' axial
// mean-squared displacement per revolution, D = <(z(N2) - z(N1))^2> /
// (2 (N2 - N1)), in m^2 per revolution like the Hogg D, over revolutions 4
// to 10. The first revolutions are left out because the drum starts
// abruptly and the bed first has to spin up (a Hogg fit from N = 0 would
// measure that start-up mixing).
#include <gtest/gtest.h>

#include <cstdio>

#include "../physics/drum_helpers.hpp"

using namespace tumble;

namespace {

std::vector<double> axial_positions_by_id(const ParticleStore& p) {
    std::vector<double> z(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) z[static_cast<std::size_t>(p.id[i])] = p.position[i].z;
    return z;
}

double axial_diffusion(double froude) {
    drum_test::DrumRun run("self", 300, 5);
    run.settle(0.4);
    const double omega = std::sqrt(froude * 9.81 / run.setup.wall.inner_radius);
    const std::int64_t per_revolution = run.rotate(omega);
    run.sim.advance(4 * per_revolution);
    const std::vector<double> start = axial_positions_by_id(run.sim.particles());
    run.sim.advance(6 * per_revolution);
    const std::vector<double> end = axial_positions_by_id(run.sim.particles());
    double sum = 0.0;
    std::size_t grains = 0;
    for (std::size_t i = 0; i < run.sim.particles().size(); ++i) {
        if (run.sim.particles().is_kinematic(i)) continue;
        const auto id = static_cast<std::size_t>(run.sim.particles().id[i]);
        sum += (end[id] - start[id]) * (end[id] - start[id]);
        ++grains;
    }
    const double D = sum / static_cast<double>(grains) / (2.0 * 6.0);
    std::printf("[measured] Froude %.2f: axial D from the mean-squared displacement = %.3e m^2/rev\n", froude, D);
    return D;
}

}  // namespace

TEST(DrumLong, AboveTheCriticalSpeedAxialDiffusionNearlyStops) {
    const double moderate = axial_diffusion(0.2);
    const double centrifuging = axial_diffusion(12.0);
    // A cascading bed moves its grains axially by millimetres per revolution
    // (D of order 1e-5 m^2/rev); grains pinned to the wall only creep.
    // "Much smaller": below a tenth.
    EXPECT_GT(moderate, 1e-6);
    EXPECT_LT(centrifuging, 0.1 * moderate);
}
