// SPDX-License-Identifier: MIT
// The dashpot's time treatment (integrate/dashpot.hpp) on a lone linear
// dashpot, m v' = -c v (no spring, nothing else): the engine's sequence of
// half kick, force and half kick, with the force from
// dashpot_normal_velocity(), against the exact decay exp(-c t / m).
#include <gtest/gtest.h>

#include <cmath>

#include "tumble/integrate/dashpot.hpp"

namespace tumble {
namespace {

// One body against a fixed one: v is the normal velocity, 1/m* = 1/m. It
// starts without force, as a contact does (c = 0 at zero overlap).
struct LoneDashpot {
    double m = 1.0, c = 1.0, dt = 1.0;
    double v = 1.0, acceleration = 0.0, force = 0.0;
    void step() {
        const double v_half = v + 0.5 * dt * acceleration;
        const double predicted = v_half + 0.5 * dt * acceleration;  // the engine's prediction for t + dt
        force = -c * dashpot_normal_velocity(predicted, c, 1.0 / m, dt, force);
        acceleration = force / m;
        v = v_half + 0.5 * dt * acceleration;
    }
};

TEST(Dashpot, SmallStepGivesTheExplicitPrediction) {
    // lambda = 1e-9: the factor differs from 1 by lambda/2, the old force's share by dt/2 F/m*.
    EXPECT_NEAR(dashpot_normal_velocity(-0.3, 1.0, 1.0, 1e-9, 0.0), -0.3, 1e-9);
    EXPECT_NEAR(dashpot_normal_velocity(-0.3, 1.0, 0.0, 1.0, 5.0), -0.3, 0.0);  // two kinematic partners: no change
}

// The explicit prediction (psi = 1, without the old force's share taken out)
// grows for lambda = c dt / m > 1; the treated dashpot decays at every step
// for any lambda.
TEST(Dashpot, ALoneDashpotDecaysAtEveryStepForAnyStiffness) {
    for (double lambda : {0.1, 0.5, 1.0, 2.0, 5.0, 20.0, 1e3, 1e6}) {
        SCOPED_TRACE("lambda = " + std::to_string(lambda));
        LoneDashpot d;
        d.c = lambda;
        double before = std::abs(d.v);
        for (int k = 0; k < 100 && before > 1e-200; ++k) {
            d.step();
            EXPECT_LT(std::abs(d.v), before);
            before = std::abs(d.v);
        }
    }
}

// Accuracy where the step resolves the decay, from the state at t = 0
// (force -c v): at lambda = 0.1 the velocity after 10 steps is within 1e-4
// of exp(-1) (measured 2.1e-5, and 3.2e-7 at a quarter of the step: third
// order; the explicit prediction errs by 1.5e-3 and 9.6e-5).
TEST(Dashpot, ResolvedDecayFollowsTheExponential) {
    for (double dt : {0.1, 0.025}) {
        LoneDashpot d;
        d.dt = dt;
        d.force = -d.c * d.v;
        d.acceleration = d.force / d.m;
        for (int k = 0; k < static_cast<int>(std::lround(1.0 / dt)); ++k) d.step();
        EXPECT_NEAR(d.v, std::exp(-1.0), dt == 0.1 ? 1e-4 : 1e-6) << "dt = " << dt;
    }
}

}  // namespace
}  // namespace tumble
