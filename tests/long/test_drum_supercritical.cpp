// SPDX-License-Identifier: MIT
// Above the critical speed (Froude number omega^2 R / g > 1) the grains are
// held against the wall and axial transport nearly stops: D measured there is
// much smaller than at a moderate speed (issue 3). Minutes of run time:
// label "long" (ctest --test-dir build -L long).
#include <gtest/gtest.h>

#include <cstdio>

#include "../physics/drum_helpers.hpp"
#include "tumble/analysis/hogg.hpp"

using namespace tumble;

namespace {

// Self-diffusion fit over `revolutions` at speed `froude`.
analysis::DiffusionFit self_diffusion(double froude, double revolutions) {
    drum_test::DrumRun run("self", 300, 5);
    run.settle(0.4);
    const double omega = std::sqrt(froude * 9.81 / run.setup.wall.inner_radius);
    const std::int64_t per_revolution = run.rotate(omega);
    const int samples_per_revolution = 10;
    std::vector<double> N, z;
    for (int k = 0; k <= revolutions * samples_per_revolution; ++k) {
        if (k > 0) run.sim.advance(per_revolution / samples_per_revolution);
        N.push_back(static_cast<double>(k) / samples_per_revolution);
        z.push_back(run.measure().components[1].mean_z);  // tag 1 started at z > 0
    }
    const auto fit = analysis::fit_diffusion(N, z, run.setup.wall.inner_length);
    std::printf("[measured] Froude %.2f: D = %.3e +- %.1e m^2/rev (%s), <z> %.4f -> %.4f m\n", froude, fit.D,
                fit.D_stderr, fit.determined ? "determined" : fit.note.c_str(), z.front(), z.back());
    return fit;
}

}  // namespace

TEST(DrumLong, AboveTheCriticalSpeedAxialDiffusionNearlyStops) {
    const auto moderate = self_diffusion(0.2, 8.0);
    const auto centrifuging = self_diffusion(2.0, 8.0);
    ASSERT_TRUE(moderate.determined) << moderate.note;
    ASSERT_GT(moderate.D, 0.0);
    // "Much smaller": a factor 5 leaves room for the statistical error of
    // the moderate-speed D (tens of per cent over 8 revolutions) while a
    // bed that still cascades would give a D of the same order.
    EXPECT_LT(centrifuging.D, 0.2 * moderate.D);
}
