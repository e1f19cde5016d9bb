// SPDX-License-Identifier: MIT
// Periodic boundaries: a pair in contact across the box's corner (so across
// the x, y and z faces at once) must feel exactly the forces of the same pair
// in the middle of the box, step after step, while it drifts and its grains
// wrap around.
//
// For exactness the box is [1.25, 1.3125) m on every axis: all coordinates,
// also those a grain takes just outside the box before the next list build
// wraps it, then share one binade of doubles ([1, 2), spacing 2^-52; a box
// starting at 1 would not do: a grain at 1 - 1e-4 has twice finer
// rounding than its copy at 1.0624), the shift between
// the two copies (1/32 m) and the box length are multiples of that spacing,
// and so every difference X_i - X_j, every image shift, every wrap and every
// drift x += dt v rounds identically for both copies. Any discrepancy is then
// a real difference in how the engine treats the periodic pair, and the
// comparison can be bitwise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "physics_helpers.hpp"
#include "tumble/neighbor/periodic_images.hpp"

namespace physics_test {
namespace {

constexpr double lo = 1.25, L = 1.0 / 16.0, shift = 1.0 / 32.0;

tumble::Scenario periodic_pair(const Vec3& xa, const Vec3& xb, double dt) {
    tumble::Scenario s = open_scenario(dt);  // every term on
    s.domain.lo = {lo, lo, lo};
    s.domain.hi = {lo + L, lo + L, lo + L};  // 62.5 mm: 7 cells of 2 R_max + skin per axis
    s.domain.periodic = {true, true, true};
    s.neighbor.skin = 1e-4;  // small: rebuilds (and with them the wraps) every ~0.2 ms
    // A common drift (0.3, -0.2, 0.25) m/s carries the pair across faces; a
    // small approach and spins exercise viscosity, shear and twisting.
    const Vec3 drift{0.3, -0.2, 0.25};
    s.particles.push_back(sphere(xa, R1, 0, drift + Vec3{-0.02, 0.01, 0.0}, {10.0, -5.0, 20.0}));
    s.particles.push_back(sphere(xb, R2, 1, drift + Vec3{0.02, 0.0, -0.01}, {-3.0, 8.0, 0.0}));
    return s;
}

// x + shift, brought back into [lo, lo + L): exact in this binade.
Vec3 shifted(Vec3 x) {
    for (int k = 0; k < 3; ++k) {
        x[k] += shift;
        if (x[k] >= lo + L) x[k] -= L;
    }
    return x;
}

// Separation of a and b reduced to the nearest image (exact here).
Vec3 nearest_separation(const tumble::ParticleStore& p) {
    Vec3 d = p.position[index_of(p, 0)] - p.position[index_of(p, 1)];
    for (int k = 0; k < 3; ++k) {
        if (d[k] > 0.5 * L) d[k] -= L;
        if (d[k] < -0.5 * L) d[k] += L;
    }
    return d;
}

TEST(Periodic, PairAcrossTheCornerFeelsBitwiseTheForcesOfThePairInTheMiddle) {
    const double dt = 2e-6;
    // Middle: centred on lo + L/2, separation 5.9 mm (overlap 0.1 mm) along
    // a generic direction.
    const Vec3 centre{lo + 0.5 * L, lo + 0.5 * L, lo + 0.5 * L};
    const Vec3 u = (1.0 / std::sqrt(29.0)) * Vec3{2.0, -3.0, 4.0};
    const Vec3 xa = centre + (0.5 * 5.9e-3) * u, xb = centre - (0.5 * 5.9e-3) * u;
    // Across: the same pair moved by L/2 on every axis, i.e. centred on the
    // corner of the box, each grain on the other side of every face.
    const Vec3 ya = shifted(xa), yb = shifted(xb);
    for (int k = 0; k < 3; ++k) ASSERT_NE(ya[k] < lo + 0.5 * L, yb[k] < lo + 0.5 * L) << "not across axis " << k;

    tumble::Simulation middle(periodic_pair(xa, xb, dt));
    tumble::Simulation across(periodic_pair(ya, yb, dt));
    // The pair is found through an image in every axis.
    ASSERT_EQ(across.neighbors().pairs().size(), 1u);
    EXPECT_NE(across.neighbors().pairs().image[0], tumble::no_shift);

    const long steps = 5000;  // 10 ms: the pair drifts 3 mm, 2 mm and 2.5 mm
    long mismatches = 0, wraps_seen = 0;
    Vec3 last[2] = {across.particles().position[index_of(across.particles(), 0)],
                    across.particles().position[index_of(across.particles(), 1)]};
    for (long k = 0; k <= steps; ++k) {
        if (k > 0) {
            middle.step();
            across.step();
        }
        const auto& p = middle.particles();
        const auto& q = across.particles();
        ASSERT_EQ(middle.observe().contacts, 1u) << "the pair must stay in contact (step " << k << ")";
        for (std::int64_t id = 0; id < 2; ++id) {
            const std::size_t i = index_of(p, id), j = index_of(q, id);
            // Bitwise: the same doubles, not merely close ones.
            if (!(p.force[i] == q.force[j]) || !(p.torque[i] == q.torque[j]) || !(p.velocity[i] == q.velocity[j]) ||
                !(p.angular_velocity[i] == q.angular_velocity[j]))
                ++mismatches;
        }
        if (!(nearest_separation(p) == nearest_separation(q))) ++mismatches;
        for (std::int64_t id = 0; id < 2; ++id) {
            const Vec3 x = q.position[index_of(q, id)];
            for (int axis = 0; axis < 3; ++axis)
                if (std::abs(x[axis] - last[id][axis]) > 0.5 * L) ++wraps_seen;
            last[id] = x;
        }
    }
    const auto& q = across.particles();
    std::printf("  [measured] %ld mismatching steps; %ld wraps of a coordinate; %lld list builds\n", mismatches,
                wraps_seen, static_cast<long long>(across.neighbors().builds()));
    // The run did cross faces: coordinates wrapped (each grain starts within
    // 3 mm of the faces it moves towards).
    EXPECT_GE(wraps_seen, 2);
    EXPECT_GT(across.neighbors().builds(), 10);
    // Zero tolerance: see the file comment for why every operation rounds
    // identically for the two copies. (Were the box elsewhere, copies in
    // different binades would differ by ~1e-16 m in position, ~1e-12 of h.)
    EXPECT_EQ(mismatches, 0);
    // Sanity: it is not a pair that never touched.
    EXPECT_GT(tumble::norm(q.force[index_of(q, 0)]), 0.0);
}

}  // namespace
}  // namespace physics_test
