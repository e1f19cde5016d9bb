// SPDX-License-Identifier: MIT
// Placing spheres at random where there is room (random sequential
// addition): for the random fills of a scenario and for the spheres poured
// in while it runs. Deterministic for a given seed.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "tumble/core/vec3.hpp"
#include "tumble/sim/scenario.hpp"

namespace tumble {

// Uniform in [0, 1) from the top 53 bits: the same on every platform, unlike
// std::uniform_real_distribution.
inline double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// SplitMix64's mixing (Steele, Lea & Flood 2014): to derive independent
// seeds from one.
constexpr std::uint64_t splitmix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

// Whether a sphere at x of radius r lies clear of the walls (always, without walls).
using ClearOfWalls = std::function<bool(const Vec3& x, double r)>;

// Up to `count` spheres of radius uniform in [radius_min, radius_max] at
// random in the box [lo, hi] (whole spheres inside), overlapping neither
// each other nor the spheres of `existing`, and clear of the walls. Stops
// early, with fewer, when `give_up_after` tries in a row find no room.
// Draws from std::mt19937_64 seeded with `seed`: per sphere its radius,
// then x, y and z, each from the top 53 bits of one number.
std::vector<ParticleSpec> place_at_random(const Vec3& lo, const Vec3& hi, std::size_t count, double radius_min,
                                          double radius_max, std::int32_t material, std::uint64_t seed,
                                          const std::vector<ParticleSpec>& existing, const ClearOfWalls& clear,
                                          std::size_t give_up_after);

}  // namespace tumble
