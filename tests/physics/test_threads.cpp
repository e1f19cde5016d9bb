// SPDX-License-Identifier: MIT
// Threads do not change the physics. The pair loop gives each thread a part
// of the pair list and its own force arrays, summed per particle in thread
// order (Simulation::compute_forces): the same thread count must give the
// same numbers bitwise, and another thread count the same numbers up to the
// order of the floating-point additions.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "physics_helpers.hpp"
#include "tumble/setup/benchmark_cube.hpp"

namespace physics_test {
namespace {

// Largest |a - b| over the particles, matched by global id.
double largest_difference(const tumble::Simulation& a, const tumble::Simulation& b,
                          std::vector<Vec3> tumble::ParticleStore::*field) {
    const auto& p = a.particles();
    const auto& q = b.particles();
    double worst = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const std::size_t j = index_of(q, p.id[i]);
        worst = std::max(worst, tumble::norm((p.*field)[i] - (q.*field)[j]));
    }
    return worst;
}

double largest_norm(const tumble::Simulation& a, std::vector<Vec3> tumble::ParticleStore::*field) {
    double worst = 0.0;
    for (const Vec3& v : a.particles().*field) worst = std::max(worst, tumble::norm(v));
    return worst;
}

TEST(Threads, SameThreadCountIsBitwiseIdentical) {
    const tumble::Scenario s = shaken_box();
    tumble::Simulation a(s, 2), b(s, 2);
    a.advance(1500);  // 7.5 ms, through list rebuilds and re-sorts (test_determinism)
    b.advance(1500);
    EXPECT_GT(a.observe().neighbor_builds, 20);
    const auto& p = a.particles();
    const auto& q = b.particles();
    EXPECT_TRUE(p.id == q.id);
    EXPECT_TRUE(p.position == q.position);
    EXPECT_TRUE(p.velocity == q.velocity);
    EXPECT_TRUE(p.angular_velocity == q.angular_velocity);
    EXPECT_TRUE(p.force == q.force);
    EXPECT_TRUE(p.torque == q.torque);
    const auto ha = a.neighbors().pairs().histories();
    const auto hb = b.neighbors().pairs().histories();
    ASSERT_EQ(ha.size(), hb.size());
    for (std::size_t k = 0; k < ha.size(); ++k) {
        EXPECT_EQ(ha[k].slip, hb[k].slip);
        EXPECT_EQ(ha[k].angular_slip, hb[k].angular_slip);
    }
}

// The forces of one configuration: 1, 2 and 3 threads sum the same pair
// forces in another order. Each component is a sum of at most 12 terms (6
// contacts per sphere: force and torque of each), so reordering moves it by
// at most ~12 x 2^-52 of the largest term; 1e-14 of the largest force (or
// torque) in the cube bounds that with room.
TEST(Threads, ForcesMatchOneThreadToRoundOff) {
    const tumble::Scenario s = tumble::benchmark_cube(8, 1);  // 512 spheres, all terms on
    tumble::Simulation one(s, 1);
    one.advance(20);
    for (int threads : {2, 3}) {
        tumble::Simulation many(s, 1);
        many.advance(19);
        many.set_threads(threads);
        many.advance(1);  // the same state as `one` before the last force evaluation
        const double force_scale = largest_norm(one, &tumble::ParticleStore::force);
        const double torque_scale = largest_norm(one, &tumble::ParticleStore::torque);
        const double df = largest_difference(one, many, &tumble::ParticleStore::force);
        const double dt = largest_difference(one, many, &tumble::ParticleStore::torque);
        std::printf("  [measured] %d threads: largest force difference %.3g N (of %.3g N), torque %.3g N m (of %.3g N m)\n",
                    threads, df, force_scale, dt, torque_scale);
        EXPECT_GT(force_scale, 0.0);
        EXPECT_LE(df, 1e-14 * force_scale);
        EXPECT_LE(dt, 1e-14 * torque_scale);
    }
}

// A whole run on 1 and 2 threads: the round-off differences of the force
// sums feed back through the dynamics. In the benchmark cube (dense, very
// viscous contacts that all persist, no rebuilds) they stay at round-off
// level: positions agree to 1e-12 of the 7 mm lattice spacing over 500 steps
// (measured ~1e-17 m), velocities to 1e-9 of the initial 0.05 m/s.
TEST(Threads, OneAndTwoThreadsAgreeOverARun) {
    const tumble::Scenario s = tumble::benchmark_cube(8, 1);
    tumble::Simulation one(s, 1), two(s, 2);
    one.advance(500);
    two.advance(500);
    const double dx = largest_difference(one, two, &tumble::ParticleStore::position);
    const double dv = largest_difference(one, two, &tumble::ParticleStore::velocity);
    const double dw = largest_difference(one, two, &tumble::ParticleStore::angular_velocity);
    std::printf("  [measured] after 500 steps: positions differ by %.3g m, velocities by %.3g m/s, spins by %.3g rad/s\n",
                dx, dv, dw);
    const double spacing = 1.98 * s.materials[0].radius;
    EXPECT_LE(dx, 1e-12 * spacing);
    EXPECT_LE(dv, 1e-9 * 0.05);
    EXPECT_LE(dw, 1e-9 * 0.05 / s.materials[0].radius);
    EXPECT_EQ(one.observe().contacts, two.observe().contacts);
}

}  // namespace
}  // namespace physics_test
