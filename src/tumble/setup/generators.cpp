// SPDX-License-Identifier: MIT
#include "tumble/setup/generators.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>
#include <vector>
#include <string>

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/sim/placement.hpp"

namespace tumble {


std::vector<ParticleSpec> lattice(const Vec3& origin, const std::array<int, 3>& counts, double spacing,
                                  double radius, std::int32_t material, const WallDistances* walls) {
    std::vector<ParticleSpec> out;
    out.reserve(static_cast<std::size_t>(counts[0]) * counts[1] * counts[2]);
    for (int k = 0; k < counts[2]; ++k)
        for (int j = 0; j < counts[1]; ++j)
            for (int i = 0; i < counts[0]; ++i) {
                ParticleSpec p;
                p.position = origin + Vec3{i * spacing, j * spacing, k * spacing};
                p.radius = radius;
                p.material = material;
                if (!walls || walls->clear(p.position, radius)) out.push_back(p);
            }
    return out;
}

std::vector<ParticleSpec> random_fill(const Vec3& lo, const Vec3& hi, std::size_t count, double radius_min,
                                      double radius_max, std::int32_t material, std::uint64_t seed,
                                      const std::vector<ParticleSpec>& existing, const WallDistances* walls) {
    if (!(radius_min > 0.0) || radius_max < radius_min) throw Error("random fill: need 0 < radius_min <= radius_max");
    for (int k = 0; k < 3; ++k)
        if (hi[k] - lo[k] < 2.0 * radius_max)
            throw Error("random fill: the region is thinner than one sphere along " + std::string(1, "xyz"[k]));
    // Give up when this many tries in a row find no room: the region is full.
    constexpr std::size_t max_failures = 100000;
    ClearOfWalls clear;
    if (walls) clear = [walls](const Vec3& x, double r) { return walls->clear(x, r); };
    std::vector<ParticleSpec> out =
        place_at_random(lo, hi, count, radius_min, radius_max, material, seed, existing, clear, max_failures);
    if (out.size() < count)
        throw Error("random fill: placed only " + std::to_string(out.size()) + " of " + std::to_string(count) +
                    " spheres; " + std::to_string(max_failures) +
                    " random tries in a row found no room (enlarge the region or ask for fewer)");
    return out;
}

void randomize_velocities(std::vector<ParticleSpec>& particles, double speed, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    for (auto& p : particles) {
        // Uniform direction on the sphere: cos(theta) uniform in [-1, 1].
        const double cos_theta = 2.0 * uniform(rng) - 1.0;
        const double phi = 2.0 * pi * uniform(rng);
        const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
        p.velocity = speed * Vec3{sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
    }
}

}  // namespace tumble
