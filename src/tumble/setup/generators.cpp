// SPDX-License-Identifier: MIT
#include "tumble/setup/generators.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>
#include <utility>
#include <vector>
#include <string>

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace tumble {

namespace {
// Uniform in [0, 1) from the top 53 bits: the same on every platform, unlike
// std::uniform_real_distribution.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Hash grid of placed spheres for the overlap test of random_fill.
class PlacementGrid {
public:
    explicit PlacementGrid(double cell) : cell_(cell) {}
    void add(const Vec3& x, double r) {
        cells_[key(x)].push_back({x, r});
    }
    bool free(const Vec3& x, double r, double largest) const {
        const long cx = coord(x.x), cy = coord(x.y), cz = coord(x.z);
        const long reach = static_cast<long>(std::ceil((r + largest) / cell_));
        for (long dz = -reach; dz <= reach; ++dz)
            for (long dy = -reach; dy <= reach; ++dy)
                for (long dx = -reach; dx <= reach; ++dx) {
                    const auto found = cells_.find(pack(cx + dx, cy + dy, cz + dz));
                    if (found == cells_.end()) continue;
                    for (const auto& [y, ry] : found->second)
                        if (norm2(x - y) < (r + ry) * (r + ry)) return false;
                }
        return true;
    }

private:
    long coord(double v) const { return static_cast<long>(std::floor(v / cell_)); }
    static std::uint64_t pack(long x, long y, long z) {
        return (static_cast<std::uint64_t>(x & 0x1FFFFF) << 42) | (static_cast<std::uint64_t>(y & 0x1FFFFF) << 21) |
               static_cast<std::uint64_t>(z & 0x1FFFFF);
    }
    std::uint64_t key(const Vec3& x) const { return pack(coord(x.x), coord(x.y), coord(x.z)); }
    double cell_;
    std::unordered_map<std::uint64_t, std::vector<std::pair<Vec3, double>>> cells_;
};
}  // namespace

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
    double largest = radius_max;
    for (const auto& p : existing) largest = std::max(largest, p.radius);
    PlacementGrid grid(2.0 * radius_max);
    for (const auto& p : existing) grid.add(p.position, p.radius);

    std::mt19937_64 rng(seed);
    std::vector<ParticleSpec> out;
    out.reserve(count);
    // Give up when this many tries in a row find no room: the region is full.
    constexpr std::size_t max_failures = 100000;
    std::size_t failures = 0;
    while (out.size() < count) {
        if (failures == max_failures)
            throw Error("random fill: placed only " + std::to_string(out.size()) + " of " + std::to_string(count) +
                        " spheres; " + std::to_string(max_failures) +
                        " random tries in a row found no room (enlarge the region or ask for fewer)");
        const double r = radius_min + (radius_max - radius_min) * uniform(rng);
        Vec3 x;
        for (int k = 0; k < 3; ++k) x[k] = lo[k] + r + (hi[k] - lo[k] - 2.0 * r) * uniform(rng);
        if (!grid.free(x, r, largest) || (walls && !walls->clear(x, r))) {
            ++failures;
            continue;
        }
        failures = 0;
        grid.add(x, r);
        ParticleSpec p;
        p.position = x;
        p.radius = r;
        p.material = material;
        out.push_back(p);
    }
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
