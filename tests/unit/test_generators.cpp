// SPDX-License-Identifier: MIT
// Particle generators: the lattice's count and spacing, random_fill's
// guarantees (inside, no overlap, deterministic per seed, refuses what does
// not fit), and randomize_velocities' exact speed.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <tuple>
#include <vector>

#include "tumble/core/error.hpp"
#include "tumble/setup/generators.hpp"

namespace tumble {
namespace {

TEST(Generators, LatticeCountAndSpacing) {
    const Vec3 origin{-1e-3, 2e-3, 0.5e-3};
    const double spacing = 7.128e-3, radius = 3.6e-3;
    const auto grains = lattice(origin, {4, 3, 5}, spacing, radius, 2);
    ASSERT_EQ(grains.size(), 4u * 3u * 5u);

    // Every site (i, j, k) exactly once, at origin + spacing (i, j, k); the
    // sum of two doubles is exact to an ulp of the 3 cm coordinates.
    std::set<std::tuple<int, int, int>> sites;
    for (const ParticleSpec& p : grains) {
        const Vec3 steps = (1.0 / spacing) * (p.position - origin);
        const int i = static_cast<int>(std::lround(steps.x));
        const int j = static_cast<int>(std::lround(steps.y));
        const int k = static_cast<int>(std::lround(steps.z));
        EXPECT_NEAR(p.position.x, origin.x + i * spacing, 1e-17);
        EXPECT_NEAR(p.position.y, origin.y + j * spacing, 1e-17);
        EXPECT_NEAR(p.position.z, origin.z + k * spacing, 1e-17);
        EXPECT_TRUE(0 <= i && i < 4 && 0 <= j && j < 3 && 0 <= k && k < 5);
        sites.insert({i, j, k});
        EXPECT_EQ(p.radius, radius);
        EXPECT_EQ(p.material, 2);
        EXPECT_EQ(p.velocity, Vec3{});
        EXPECT_EQ(p.motion, free_motion);
    }
    EXPECT_EQ(sites.size(), grains.size());
    EXPECT_EQ(grains.front().position, origin);

    // Nearest-neighbour distance is the spacing (to round-off of 1e-18 m).
    double nearest = 1.0;
    for (std::size_t a = 0; a < grains.size(); ++a)
        for (std::size_t b = a + 1; b < grains.size(); ++b)
            nearest = std::min(nearest, norm(grains[a].position - grains[b].position));
    EXPECT_NEAR(nearest, spacing, 1e-15);
}

void expect_valid_fill(const std::vector<ParticleSpec>& grains, const Vec3& lo, const Vec3& hi, double r_min,
                       double r_max, const std::vector<ParticleSpec>& existing) {
    for (std::size_t a = 0; a < grains.size(); ++a) {
        const ParticleSpec& p = grains[a];
        EXPECT_GE(p.radius, r_min);
        EXPECT_LE(p.radius, r_max);
        // The whole sphere inside; x = lo + r + ... minus r may round an ulp
        // (~5e-18 m at 4 cm) below lo, hence 1e-16 m.
        for (int k = 0; k < 3; ++k) {
            EXPECT_GE(p.position[k] - p.radius, lo[k] - 1e-16);
            EXPECT_LE(p.position[k] + p.radius, hi[k] + 1e-16);
        }
        // No overlap: distance >= sum of radii (strict geometry, no slack).
        for (std::size_t b = a + 1; b < grains.size(); ++b)
            EXPECT_GE(norm(p.position - grains[b].position), p.radius + grains[b].radius) << a << " " << b;
        for (const ParticleSpec& q : existing)
            EXPECT_GE(norm(p.position - q.position), p.radius + q.radius);
    }
}

TEST(Generators, RandomFillPlacesNonOverlappingSpheresInsideTheBox) {
    const Vec3 lo{0.0, -0.01, 0.02}, hi{0.04, 0.03, 0.05};
    const double r_min = 2.4e-3, r_max = 3.6e-3;
    // 60 spheres of mean volume 1.1e-7 m^3 fill 14 % of the 4.8e-5 m^3
    // box: easy for random sequential placement (it jams near 38 %).
    const auto grains = random_fill(lo, hi, 60, r_min, r_max, 1, 42, {});
    ASSERT_EQ(grains.size(), 60u);
    expect_valid_fill(grains, lo, hi, r_min, r_max, {});
    for (const ParticleSpec& p : grains) EXPECT_EQ(p.material, 1);

    // The radii really spread over [r_min, r_max].
    double smallest = 1.0, largest = 0.0;
    for (const ParticleSpec& p : grains) {
        smallest = std::min(smallest, p.radius);
        largest = std::max(largest, p.radius);
    }
    EXPECT_LT(smallest, r_min + 0.1 * (r_max - r_min));
    EXPECT_GT(largest, r_max - 0.1 * (r_max - r_min));
}

TEST(Generators, RandomFillAvoidsExistingSpheres) {
    const Vec3 lo{0.0, 0.0, 0.0}, hi{0.03, 0.03, 0.03};
    const auto wall = lattice({0.0, 0.0, 0.0}, {6, 6, 6}, 0.006, 2.0e-3, 2);
    const auto grains = random_fill(lo, hi, 40, 1.0e-3, 1.5e-3, 0, 7, wall);
    ASSERT_EQ(grains.size(), 40u);
    expect_valid_fill(grains, lo, hi, 1.0e-3, 1.5e-3, wall);
}

TEST(Generators, RandomFillIsDeterministicPerSeed) {
    const Vec3 lo{0.0, 0.0, 0.0}, hi{0.03, 0.03, 0.03};
    const auto a = random_fill(lo, hi, 50, 1e-3, 2e-3, 0, 5, {});
    const auto b = random_fill(lo, hi, 50, 1e-3, 2e-3, 0, 5, {});
    const auto c = random_fill(lo, hi, 50, 1e-3, 2e-3, 0, 6, {});
    ASSERT_EQ(a.size(), b.size());
    std::size_t same_as_other_seed = 0;
    for (std::size_t k = 0; k < a.size(); ++k) {
        EXPECT_EQ(a[k].position, b[k].position);  // bit for bit
        EXPECT_EQ(a[k].radius, b[k].radius);
        if (a[k].position == c[k].position) ++same_as_other_seed;
    }
    EXPECT_EQ(same_as_other_seed, 0u);
}

TEST(Generators, RandomFillRefusesMoreThanFits) {
    // A 1 cm cube holds at most 0.74 x 1e-6 / 4.19e-9 = 176 spheres of
    // radius 1 mm even in the densest packing; ask for 300.
    const Vec3 lo{0.0, 0.0, 0.0}, hi{0.01, 0.01, 0.01};
    EXPECT_THROW(random_fill(lo, hi, 300, 1e-3, 1e-3, 0, 1, {}), Error);
    // A region thinner than one sphere.
    EXPECT_THROW(random_fill(lo, {0.01, 0.01, 1e-3}, 1, 1e-3, 1e-3, 0, 1, {}), Error);
    // Bad radii.
    EXPECT_THROW(random_fill(lo, hi, 1, 0.0, 1e-3, 0, 1, {}), Error);
    EXPECT_THROW(random_fill(lo, hi, 1, 2e-3, 1e-3, 0, 1, {}), Error);
}

TEST(Generators, RandomizedVelocitiesHaveTheExactSpeed) {
    auto grains = lattice({0.0, 0.0, 0.0}, {10, 10, 10}, 0.01, 1e-3, 0);
    randomize_velocities(grains, 0.05, 3);
    Vec3 sum;
    for (const ParticleSpec& p : grains) {
        // |v| of a unit vector times the speed: a few ulp of 0.05 m/s.
        EXPECT_NEAR(norm(p.velocity), 0.05, 1e-16);
        sum += p.velocity;
    }
    // Directions are spread over the sphere: the mean of 1000 random unit
    // vectors has length ~ 1/sqrt(1000) = 0.03 of the speed; 0.15 is five
    // standard deviations.
    EXPECT_LT(norm((1.0 / grains.size()) * sum), 0.15 * 0.05);

    // Deterministic for a seed, different for another.
    auto again = lattice({0.0, 0.0, 0.0}, {10, 10, 10}, 0.01, 1e-3, 0);
    randomize_velocities(again, 0.05, 3);
    auto other = again;
    randomize_velocities(other, 0.05, 4);
    for (std::size_t k = 0; k < grains.size(); ++k) {
        EXPECT_EQ(again[k].velocity, grains[k].velocity);
        EXPECT_NE(other[k].velocity, grains[k].velocity);
    }
}

}  // namespace
}  // namespace tumble
