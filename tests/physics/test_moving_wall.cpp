// SPDX-License-Identifier: MIT
// A wall that alone moves is still seen. step() bounds how far each
// prescribed motion has carried its spheres since the neighbour list was
// built (rigid_displacement_bound(), Simulation::walls_within_limit()) and
// checks the spheres one by one only where that bound nears half the skin.
// A wall sphere carried at 0.2 m/s (the drum wall's speed) towards a free
// sphere at rest, from three skins away, must enter the list and push it,
// by a translation and by a turn. Nothing else moves, so only the wall's
// check can rebuild the list: were it skipped for good, the wall sphere
// would pass through the grain without a force.
#include <gtest/gtest.h>

#include <cmath>

#include "physics_helpers.hpp"

namespace physics_test {
namespace {

constexpr double speed = 0.2;  // m/s

// A grain of material 1 at rest at the origin, no gravity, and a wall
// sphere (material 3) at `start` on `motion`; the automatic time step.
tumble::Scenario wall_and_grain(const tumble::RigidMotion& motion, const Vec3& start) {
    tumble::Scenario s = open_scenario(0.0);
    s.particles.push_back(sphere({}, R1, 0));
    tumble::ParticleSpec wall = sphere(start, R3, 2);
    wall.motion = 0;
    s.particles.push_back(wall);
    s.motions.push_back(motion);
    return s;
}

// Runs until the wall sphere has gone 2.5 of its start's gap past first
// touching (long enough to set the grain going at about its speed), then
// checks the grain's velocity along `along` and the list's builds.
void expect_pushed(const tumble::Scenario& s, const Vec3& along, const char* what) {
    tumble::Simulation sim(s, 1);
    const double skin = 0.2 * R1, gap = 3.0 * skin;  // the engine's skin; the start's gap
    const auto steps = static_cast<std::int64_t>(std::ceil(3.5 * gap / speed / sim.dt()));
    const std::int64_t builds = sim.observe().neighbor_builds;
    sim.advance(steps);
    const tumble::ParticleStore& p = sim.particles();
    const double pushed = tumble::dot(p.velocity[index_of(p, 0)], along);
    std::printf("  [measured] %s: grain pushed at %.4g m/s by the wall at %.3g m/s, %lld builds in %lld steps\n",
                what, pushed, speed, static_cast<long long>(sim.observe().neighbor_builds - builds),
                static_cast<long long>(steps));
    // Unseen, the grain stays at rest. Seen, it leaves the wall at its
    // speed or faster, or sticks to it (the pair's attraction) and goes
    // with it: half the wall's speed is far from both.
    EXPECT_GT(pushed, 0.5 * speed) << what;
    // Rebuilt as the wall came, not at every step (the bound skips the
    // spheres' check while it lies well below half the skin).
    EXPECT_GE(sim.observe().neighbor_builds - builds, 2) << what;
    EXPECT_LT(sim.observe().neighbor_builds - builds, steps / 5) << what;
}

TEST(MovingWall, ASphereCarriedTowardsAGrainAtRestIsSeenAndPushesIt) {
    const double contact = R1 + R3 + 3.0 * 0.2 * R1;  // centre distance at the start, m

    // A translation along -x.
    expect_pushed(wall_and_grain({{}, {0.0, 0.0, 1.0}, 0.0, {-speed, 0.0, 0.0}}, {contact, 0.0, 0.0}),
                  {-1.0, 0.0, 0.0}, "translation");

    // A turn about the z axis through (0, rho, 0), clockwise, on the circle
    // through the grain's centre: the wall sphere starts a chord `contact`
    // from it and moves along -x there.
    const double rho = 0.05, omega = -speed / rho;
    const double phi = 2.0 * std::asin(0.5 * contact / rho);
    expect_pushed(wall_and_grain({{0.0, rho, 0.0}, {0.0, 0.0, 1.0}, omega, {}},
                                 {rho * std::sin(phi), rho - rho * std::cos(phi), 0.0}),
                  {-1.0, 0.0, 0.0}, "turn");
}

}  // namespace
}  // namespace physics_test
