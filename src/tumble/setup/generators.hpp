// SPDX-License-Identifier: MIT
// Particle generators: the ways a scenario can fill space without listing
// every particle. All are deterministic for a given seed.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tumble/sim/scenario.hpp"
#include "tumble/walls/clearance.hpp"

namespace tumble {

// A simple cubic lattice of counts[0] x counts[1] x counts[2] sites, the
// first centred at `origin`, spaced `spacing` apart along each axis; a
// sphere at every site clear of `walls` where given (WallDistances::clear:
// a lattice clipped to a hopper, meshes included).
std::vector<ParticleSpec> lattice(const Vec3& origin, const std::array<int, 3>& counts, double spacing,
                                  double radius, std::int32_t material, const WallDistances* walls = nullptr);

// `count` non-overlapping spheres of radius uniform in [radius_min,
// radius_max] placed at random in the box [lo, hi] (whole spheres inside),
// avoiding the spheres in `existing`, clear of `walls` where given (its
// reach at least radius_max). Throws tumble::Error
// if it cannot place them all within a bounded number of attempts.
std::vector<ParticleSpec> random_fill(const Vec3& lo, const Vec3& hi, std::size_t count, double radius_min,
                                      double radius_max, std::int32_t material, std::uint64_t seed,
                                      const std::vector<ParticleSpec>& existing, const WallDistances* walls = nullptr);

// Give each particle a velocity of the given magnitude in a random direction.
void randomize_velocities(std::vector<ParticleSpec>& particles, double speed, std::uint64_t seed);

}  // namespace tumble
