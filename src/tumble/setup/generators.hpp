// SPDX-License-Identifier: MIT
// Particle generators: the ways a scenario can fill space without listing
// every particle. All are deterministic for a given seed.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tumble/sim/scenario.hpp"

namespace tumble {

// Whether a sphere at x of radius r lies clear of every wall: on the
// grains' side of each and touching none (walls/wall.hpp, in the walls'
// frames at the start of their motions).
bool clear_of_walls(const Vec3& x, double r, const std::vector<Wall>& walls);

// A simple cubic lattice of counts[0] x counts[1] x counts[2] sites, the
// first centred at `origin`, spaced `spacing` apart along each axis; a
// sphere at every site clear of `walls` (a lattice clipped to a hopper).
std::vector<ParticleSpec> lattice(const Vec3& origin, const std::array<int, 3>& counts, double spacing,
                                  double radius, std::int32_t material, const std::vector<Wall>& walls = {});

// `count` non-overlapping spheres of radius uniform in [radius_min,
// radius_max] placed at random in the box [lo, hi] (whole spheres inside),
// avoiding the spheres in `existing`, clear of `walls`. Throws tumble::Error
// if it cannot place them all within a bounded number of attempts.
std::vector<ParticleSpec> random_fill(const Vec3& lo, const Vec3& hi, std::size_t count, double radius_min,
                                      double radius_max, std::int32_t material, std::uint64_t seed,
                                      const std::vector<ParticleSpec>& existing, const std::vector<Wall>& walls = {});

// Give each particle a velocity of the given magnitude in a random direction.
void randomize_velocities(std::vector<ParticleSpec>& particles, double speed, std::uint64_t seed);

}  // namespace tumble
