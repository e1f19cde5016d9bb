// SPDX-License-Identifier: MIT
#include "tumble/sim/placement.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>

namespace tumble {

namespace {

// Hash grid of placed spheres for the overlap test.
class PlacementGrid {
public:
    explicit PlacementGrid(double cell) : cell_(cell) {}
    void add(const Vec3& x, double r) { cells_[key(x)].push_back({x, r}); }
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

std::vector<ParticleSpec> place_at_random(const Vec3& lo, const Vec3& hi, std::size_t count, double radius_min,
                                          double radius_max, std::int32_t material, std::uint64_t seed,
                                          const std::vector<ParticleSpec>& existing, const ClearOfWalls& clear,
                                          std::size_t give_up_after) {
    double largest = radius_max;
    for (const auto& p : existing) largest = std::max(largest, p.radius);
    PlacementGrid grid(2.0 * radius_max);
    for (const auto& p : existing) grid.add(p.position, p.radius);

    std::mt19937_64 rng(seed);
    std::vector<ParticleSpec> out;
    out.reserve(count);
    std::size_t failures = 0;
    while (out.size() < count && failures < give_up_after) {
        const double r = radius_min + (radius_max - radius_min) * uniform(rng);
        Vec3 x;
        for (int k = 0; k < 3; ++k) x[k] = lo[k] + r + (hi[k] - lo[k] - 2.0 * r) * uniform(rng);
        if (!grid.free(x, r, largest) || (clear && !clear(x, r))) {
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

}  // namespace tumble
