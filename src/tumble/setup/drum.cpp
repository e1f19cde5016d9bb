// SPDX-License-Identifier: MIT
#include "tumble/setup/drum.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <queue>
#include <random>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/setup/paper_materials.hpp"

namespace tumble {

namespace {

std::string metres(double v) {
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "%.4g m", v);
    return buffer;
}

// Uniform in [0, 1) from the top 53 bits: the same on every platform, unlike
// std::uniform_real_distribution.
double uniform(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// Spheres binned in a hash grid of cubic cells, for overlap tests,
// neighbourhood visits and nearest-centre queries. Each sphere carries an id
// (its index in the caller's list).
class SphereGrid {
public:
    explicit SphereGrid(double cell) : cell_(cell) {}

    void add(const Vec3& x, double r, std::size_t id = 0) {
        cells_[key(coord(x.x), coord(x.y), coord(x.z))].push_back({x, r, id});
        largest_ = std::max(largest_, r);
        ++size_;
    }

    // f(centre, radius, id) for every sphere that may overlap the sphere (x, r).
    template <class F>
    void for_each_near(const Vec3& x, double r, F&& f) const {
        visit(x, static_cast<long>(std::ceil((r + largest_) / cell_)), f);
    }

    // Whether a sphere (x, r) overlaps none of the spheres held.
    bool free(const Vec3& x, double r) const {
        bool clear = true;
        for_each_near(x, r, [&](const Vec3& y, double ry, std::size_t) {
            if (norm2(x - y) < (r + ry) * (r + ry)) clear = false;
        });
        return clear;
    }

    // Distance from x to the nearest centre held. Searches blocks of cells of
    // growing reach k: a centre outside the block is more than k cells away.
    double nearest_centre(const Vec3& x) const {
        if (size_ == 0) throw Error("drum: nearest-centre query on an empty grid");
        for (long reach = 1;; ++reach) {
            double best2 = INFINITY;
            visit(x, reach, [&](const Vec3& y, double, std::size_t) { best2 = std::min(best2, norm2(x - y)); });
            if (best2 <= (reach * cell_) * (reach * cell_)) return std::sqrt(best2);
        }
    }

private:
    struct Entry {
        Vec3 x;
        double r;
        std::size_t id;
    };
    template <class F>
    void visit(const Vec3& x, long reach, F&& f) const {
        const long cx = coord(x.x), cy = coord(x.y), cz = coord(x.z);
        for (long dz = -reach; dz <= reach; ++dz)
            for (long dy = -reach; dy <= reach; ++dy)
                for (long dx = -reach; dx <= reach; ++dx) {
                    const auto found = cells_.find(key(cx + dx, cy + dy, cz + dz));
                    if (found == cells_.end()) continue;
                    for (const Entry& e : found->second) f(e.x, e.r, e.id);
                }
    }
    long coord(double v) const { return static_cast<long>(std::floor(v / cell_)); }
    static std::uint64_t key(long x, long y, long z) {
        return (static_cast<std::uint64_t>(x & 0x1FFFFF) << 42) | (static_cast<std::uint64_t>(y & 0x1FFFFF) << 21) |
               static_cast<std::uint64_t>(z & 0x1FFFFF);
    }
    double cell_;
    double largest_ = 0.0;
    std::size_t size_ = 0;
    std::unordered_map<std::uint64_t, std::vector<Entry>> cells_;
};

// Where fill_drum_region() may put the centres of its grains: the cylinder
// rho <= rho_max between z_min and z_max.
struct FillRegion {
    double rho_max, z_min, z_max;

    Vec3 sample(std::mt19937_64& rng) const {
        const double rho = rho_max * std::sqrt(uniform(rng));  // uniform in the disc
        const double phi = 2.0 * pi * uniform(rng);
        return {rho * std::cos(phi), rho * std::sin(phi), z_min + (z_max - z_min) * uniform(rng)};
    }
    Vec3 clamp(Vec3 x) const {
        const double rho = std::hypot(x.x, x.y);
        if (rho > rho_max) {
            x.x *= rho_max / rho;
            x.y *= rho_max / rho;
        }
        x.z = std::clamp(x.z, z_min, z_max);
        return x;
    }
};

// Moves the grains at x (all of `radius`) apart until none overlaps another
// or a fixed sphere: each sweep pushes every overlapping pair apart to 1.001
// times contact (half each between grains, all of it for the grain against a
// fixed sphere), then clamps the grains into the region. Returns whether it
// got there within max_sweeps.
bool separate(std::vector<Vec3>& x, double radius, const SphereGrid& fixed, const FillRegion& region,
              int max_sweeps) {
    std::vector<Vec3> shift(x.size());
    for (int sweep = 0; sweep < max_sweeps; ++sweep) {
        SphereGrid grains(2.0 * radius);
        for (std::size_t i = 0; i < x.size(); ++i) grains.add(x[i], radius, i);
        bool overlapping = false;
        for (std::size_t i = 0; i < x.size(); ++i) {
            shift[i] = {};
            auto push = [&](const Vec3& y, double ry, double share) {
                const double target = 1.001 * (radius + ry);
                const Vec3 d = x[i] - y;
                const double distance = norm(d);
                if (distance >= target) return;
                if (distance < radius + ry) overlapping = true;
                // Coincident centres part along z.
                const Vec3 away = distance > 0.0 ? (1.0 / distance) * d : Vec3{0.0, 0.0, 1.0};
                shift[i] += share * (target - distance) * away;
            };
            grains.for_each_near(x[i], radius, [&](const Vec3& y, double ry, std::size_t j) {
                if (j != i) push(y, ry, 0.5);
            });
            fixed.for_each_near(x[i], radius, [&](const Vec3& y, double ry, std::size_t) { push(y, ry, 1.0); });
        }
        if (!overlapping) return true;
        for (std::size_t i = 0; i < x.size(); ++i) x[i] = region.clamp(x[i] + shift[i]);
    }
    return false;
}

// The fewest spheres on a ring of radius rho whose neighbours are at most
// `spacing` apart (chord 2 rho sin(pi/n) <= spacing).
std::size_t ring_count(double rho, double spacing) {
    if (spacing >= 2.0 * rho) return 2;
    // The small allowance keeps round-off from adding a sphere when the ring
    // holds a whole number of them exactly.
    return static_cast<std::size_t>(std::ceil(pi / std::asin(spacing / (2.0 * rho)) - 1e-9));
}

// Equal steps of at most `spacing` over `extent`: the number of intervals.
std::size_t interval_count(double extent, double spacing) {
    return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(extent / spacing - 1e-9)));
}

void add_ring(std::vector<ParticleSpec>& out, double rho, double z, std::size_t n, double phase, double radius,
              std::int32_t material, std::int32_t motion) {
    for (std::size_t k = 0; k < n; ++k) {
        const double phi = phase + 2.0 * pi * static_cast<double>(k) / static_cast<double>(n);
        ParticleSpec p;
        p.position = {rho * std::cos(phi), rho * std::sin(phi), z};
        p.radius = radius;
        p.material = material;
        p.motion = motion;
        p.tag = -1;
        out.push_back(p);
    }
}

// max over the closed surface S (mantle cylinder of radius Rc for |z| <= Zc
// and the discs of radius Rc at z = +-Zc) of the distance to the nearest
// wall-sphere centre, as a certified upper bound within `tolerance`.
//
// Branch and bound over rectangular patches of surface parameters: (u, z)
// with u = Rc phi on the mantle (unrolling it; a 3-D chord is never longer
// than the unrolled distance), (x, y) on each cap. The distance to the
// nearest centre, f, is 1-Lipschitz, so f <= f(patch centre) + half diagonal
// on the whole patch. Patches are split, highest bound first, and dropped
// once their bound is within `tolerance` of the best value found at a point
// of S; the answer, that best value + tolerance, then bounds f on all of S.
// caps = false: the mantle alone (a periodic axis; `centres` then holds the
// images of the rings one period away).
double largest_hole(const SphereGrid& centres, double Rc, double Zc, double initial_patch, double tolerance,
                    bool caps) {
    enum Surface { mantle, cap_high, cap_low };
    struct Patch {
        double bound;
        Surface surface;
        double a, b;    // centre (u, z) or (x, y)
        double ha, hb;  // half widths
        bool operator<(const Patch& o) const { return bound < o.bound; }
    };
    auto point = [&](Surface s, double a, double b) -> Vec3 {
        if (s == mantle) return {Rc * std::cos(a / Rc), Rc * std::sin(a / Rc), b};
        return {a, b, s == cap_high ? Zc : -Zc};
    };
    double best = 0.0;  // f at some point of S
    std::priority_queue<Patch> queue;
    auto consider = [&](Surface s, double a, double b, double ha, double hb) {
        if (s != mantle) {
            // Drop patches that miss the disc; sample patches whose centre
            // lies outside it at the nearest point of the rim.
            const double dx = std::max(0.0, std::abs(a) - ha), dy = std::max(0.0, std::abs(b) - hb);
            if (dx * dx + dy * dy > Rc * Rc) return;
        }
        const double f = centres.nearest_centre(point(s, a, b));
        const double r = std::hypot(a, b);
        if (s == mantle || r <= Rc)
            best = std::max(best, f);
        else
            best = std::max(best, centres.nearest_centre(point(s, a * Rc / r, b * Rc / r)));
        const double bound = f + std::hypot(ha, hb);
        if (bound > best + tolerance) queue.push({bound, s, a, b, ha, hb});
    };
    auto tile = [&](Surface s, double a0, double a1, double b0, double b1) {
        const std::size_t na = interval_count(a1 - a0, initial_patch), nb = interval_count(b1 - b0, initial_patch);
        const double ha = 0.5 * (a1 - a0) / na, hb = 0.5 * (b1 - b0) / nb;
        for (std::size_t i = 0; i < na; ++i)
            for (std::size_t j = 0; j < nb; ++j)
                consider(s, a0 + (2 * i + 1) * ha, b0 + (2 * j + 1) * hb, ha, hb);
    };
    tile(mantle, 0.0, 2.0 * pi * Rc, -Zc, Zc);
    if (caps) {
        tile(cap_high, -Rc, Rc, -Rc, Rc);
        tile(cap_low, -Rc, Rc, -Rc, Rc);
    }
    // Every patch dropped had a bound <= best + tolerance at the time.
    while (!queue.empty() && queue.top().bound > best + tolerance) {
        const Patch p = queue.top();
        queue.pop();
        const double ha = 0.5 * p.ha, hb = 0.5 * p.hb;
        for (const double sa : {-1.0, 1.0})
            for (const double sb : {-1.0, 1.0}) consider(p.surface, p.a + sa * ha, p.b + sb * hb, ha, hb);
    }
    return best + tolerance;
}

}  // namespace

DrumWall build_drum_wall(const DrumGeometry& g, std::int32_t wall_material, std::int32_t motion,
                         double smallest_grain_radius) {
    auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
    if (!positive(g.length)) throw Error("drum: length must be a positive number of metres");
    if (!positive(g.diameter)) throw Error("drum: diameter must be a positive number of metres");
    if (!positive(g.wall_radius)) throw Error("drum: wall_radius must be a positive number of metres");
    if (g.diameter < 6.0 * g.wall_radius)
        throw Error("drum: diameter (" + metres(g.diameter) + ") must be at least 6 wall_radius (" +
                    metres(6.0 * g.wall_radius) + ") for the wall spheres to form a drum");
    if (wall_material < 0) throw Error("drum: wall_material must be a material index (>= 0)");
    if (motion < 0) throw Error("drum: the wall's motion must be a prescribed-motion index (>= 0)");
    if (!positive(smallest_grain_radius)) throw Error("drum: smallest_grain_radius must be positive");

    DrumWall wall;
    const double rw = g.wall_radius;
    const double spacing = 2.0 * rw;  // wall spheres touch (or overlap slightly)
    wall.inner_radius = 0.5 * g.diameter;
    wall.inner_length = g.length;
    const double Rc = wall.inner_radius + rw;  // cylinder of the mantle's centres
    const double Zc = 0.5 * g.length + rw;     // planes of the caps' centres

    const std::size_t per_ring = ring_count(Rc, spacing);
    SphereGrid centres(spacing);
    if (g.periodic_axis) {
        // Mantle only, periodic in z with period `length`: rings at
        // z = -length/2 + (k + 1/2) step, an even number of them so that the
        // stagger repeats across the period; the gap search sees the rings'
        // images one period away.
        std::size_t rings = interval_count(g.length, spacing);
        rings += rings % 2;
        wall.mantle_rings = rings;
        wall.axial_step = g.length / static_cast<double>(rings);
        for (std::size_t k = 0; k < rings; ++k)
            add_ring(wall.particles, Rc, -0.5 * g.length + (static_cast<double>(k) + 0.5) * wall.axial_step, per_ring,
                     (k % 2) * pi / static_cast<double>(per_ring), rw, wall_material, motion);
        wall.mantle_particles = wall.particles.size();
        for (const ParticleSpec& p : wall.particles)
            for (const double shift : {-g.length, 0.0, g.length})
                centres.add(p.position + Vec3{0.0, 0.0, shift}, p.radius);
        wall.largest_gap = largest_hole(centres, Rc, 0.5 * g.length, 0.5 * spacing, largest_gap_tolerance, false) - rw;
    } else {
        // Mantle: rings from cap plane to cap plane, staggered by half a step.
        const std::size_t intervals = interval_count(2.0 * Zc, spacing);
        wall.mantle_rings = intervals + 1;
        wall.axial_step = 2.0 * Zc / static_cast<double>(intervals);
        for (std::size_t k = 0; k <= intervals; ++k) {
            const double z = -Zc + static_cast<double>(k) * wall.axial_step;
            const double phase = (k % 2) * pi / static_cast<double>(per_ring);
            add_ring(wall.particles, Rc, k == intervals ? Zc : z, per_ring, phase, rw, wall_material, motion);
        }
        wall.mantle_particles = wall.particles.size();

        // Caps: concentric rings inside the mantle's end rings, and the axis.
        const std::size_t cap_steps = interval_count(Rc, spacing);
        const double radial_step = Rc / static_cast<double>(cap_steps);
        for (const double z : {-Zc, Zc}) {
            add_ring(wall.particles, 0.0, z, 1, 0.0, rw, wall_material, motion);
            for (std::size_t k = 1; k < cap_steps; ++k) {
                const double rho = static_cast<double>(k) * radial_step;
                const std::size_t n = ring_count(rho, spacing);
                add_ring(wall.particles, rho, z, n, (k % 2) * pi / static_cast<double>(n), rw, wall_material, motion);
            }
        }
        wall.cap_particles = wall.particles.size() - wall.mantle_particles;
        for (const ParticleSpec& p : wall.particles) centres.add(p.position, p.radius);
        wall.largest_gap = largest_hole(centres, Rc, Zc, 0.5 * spacing, largest_gap_tolerance, true) - rw;
    }
    if (wall.largest_gap >= smallest_grain_radius)
        throw Error("drum: a sphere of radius " + metres(wall.largest_gap) +
                    " could pass between the wall spheres, not smaller than the smallest grain (smallest_grain_radius " +
                    metres(smallest_grain_radius) + "); use larger wall spheres (wall_radius)");
    return wall;
}

std::vector<Wall> drum_smooth_walls(const DrumGeometry& g, std::int32_t wall_material, std::int32_t cap_material,
                                    std::int32_t motion) {
    auto positive = [](double v) { return v > 0.0 && std::isfinite(v); };
    if (!positive(g.length)) throw Error("drum: length must be a positive number of metres");
    if (!positive(g.diameter)) throw Error("drum: diameter must be a positive number of metres");
    if (wall_material < 0 || cap_material < 0) throw Error("drum: the walls' materials must be material indices (>= 0)");
    Wall mantle;
    mantle.name = "drum";
    mantle.shape = WallShape::cylinder;
    mantle.normal = {0.0, 0.0, 1.0};
    mantle.radius = 0.5 * g.diameter;
    mantle.inside = true;
    mantle.material = wall_material;
    mantle.motion = motion;
    if (g.periodic_axis) return {mantle};  // infinite (Wall's default length), through the origin
    mantle.point = {0.0, 0.0, -0.5 * g.length};
    mantle.length = g.length;
    Wall cap = mantle;
    cap.shape = WallShape::disc;
    cap.material = cap_material;
    cap.name = "drum.start";
    Wall end = cap;
    end.name = "drum.end";
    end.point = {0.0, 0.0, 0.5 * g.length};
    return {mantle, cap, end};
}

TriangleMesh drum_mantle_mesh(const DrumGeometry& g, double grain_radius) {
    if (g.periodic_axis) throw Error("drum: a mesh mantle needs the drum's caps (not a periodic axis)");
    if (!(grain_radius > 0.0)) throw Error("drum: the grain radius must be positive");
    const double R = 0.5 * g.diameter;
    // Sagitta R (1 - cos(pi/n)) <= 0.01 r, i.e. cos(pi/n) >= 1 - 0.01 r / R.
    const double angle = std::acos(std::max(-1.0, 1.0 - 0.01 * grain_radius / R));
    const auto at_least = static_cast<std::size_t>(std::ceil(pi / angle - 1e-9));
    const std::size_t n = std::max<std::size_t>(48, (at_least + 7) / 8 * 8);
    const std::size_t rings = interval_count(g.length, g.diameter) + 1;
    TriangleMesh mesh;
    for (std::size_t k = 0; k < rings; ++k) {
        const double z = -0.5 * g.length + g.length * static_cast<double>(k) / static_cast<double>(rings - 1);
        for (std::size_t j = 0; j < n; ++j) {
            const double phi = 2.0 * pi * static_cast<double>(j) / static_cast<double>(n);
            mesh.vertices.push_back({R * std::cos(phi), R * std::sin(phi), z});
        }
    }
    const auto id = [n](std::size_t k, std::size_t j) { return static_cast<std::uint32_t>(k * n + j % n); };
    for (std::size_t k = 0; k + 1 < rings; ++k)
        for (std::size_t j = 0; j < n; ++j) {  // normals towards the axis (a mesh is touched from both sides)
            mesh.triangles.push_back({id(k, j), id(k + 1, j), id(k, j + 1)});
            mesh.triangles.push_back({id(k, j + 1), id(k + 1, j), id(k + 1, j + 1)});
        }
    return mesh;
}

std::vector<ParticleSpec> fill_drum_region(const DrumGeometry& g, double z_lo, double z_hi, std::size_t count,
                                           double radius, std::int32_t material, std::int32_t tag,
                                           std::uint64_t seed, const std::vector<ParticleSpec>& existing,
                                           const WallDistances* walls) {
    if (!(radius > 0.0) || !std::isfinite(radius)) throw Error("drum fill: radius must be positive");
    if (!(g.length > 0.0) || !(g.diameter > 0.0)) throw Error("drum fill: length and diameter must be positive");
    if (!(z_lo < z_hi)) throw Error("drum fill: need z_lo < z_hi");
    const double clearance = fill_wall_clearance * radius;
    const double rho_max = 0.5 * g.diameter - radius - clearance;  // for centres
    const double z_min = std::max(z_lo + radius, -0.5 * g.length + radius + clearance);
    const double z_max = std::min(z_hi - radius, 0.5 * g.length - radius - clearance);
    if (rho_max < 0.0)
        throw Error("drum fill: a grain of radius " + metres(radius) + " does not fit in the drum's diameter (" +
                    metres(g.diameter) + ")");
    if (z_min > z_max)
        throw Error("drum fill: a grain of radius " + metres(radius) + " does not fit between z = " + metres(z_lo) +
                    " and " + metres(z_hi) + " inside the drum");

    const FillRegion region{rho_max, z_min, z_max};
    const double grain_volume = 4.0 / 3.0 * pi * radius * radius * radius;
    const double region_volume = pi * (rho_max + radius) * (rho_max + radius) * (z_max - z_min + 2.0 * radius);
    // Random close packing of equal spheres is about 64 %; well below it the
    // separation below converges quickly, near it not at all.
    constexpr double densest = 0.5;
    if (static_cast<double>(count) * grain_volume > densest * region_volume)
        throw Error("drum fill: " + std::to_string(count) + " grains of radius " + metres(radius) + " would fill " +
                    std::to_string(static_cast<int>(100.0 * count * grain_volume / region_volume)) +
                    " % of the region between z = " + metres(z_lo) + " and " + metres(z_hi) +
                    " (at most " + std::to_string(static_cast<int>(100.0 * densest)) +
                    " % can be placed): the region is too full, ask for fewer grains");

    // Random sequential placement: uniform random positions, each kept if it
    // overlaps nothing placed so far. It stalls near 30 % solid fraction.
    SphereGrid fixed(2.0 * radius);
    for (const ParticleSpec& p : existing) fixed.add(p.position, p.radius);
    SphereGrid grid = fixed;
    std::mt19937_64 rng(seed);
    std::vector<Vec3> x;
    x.reserve(count);
    constexpr std::size_t stall = 20000;  // tries in a row that found no room
    for (std::size_t failures = 0; x.size() < count && failures < stall;) {
        const Vec3 candidate = region.sample(rng);
        if (!grid.free(candidate, radius) || (walls && !walls->clear(candidate, radius))) {
            ++failures;
            continue;
        }
        failures = 0;
        grid.add(candidate, radius);
        x.push_back(candidate);
    }
    // If it stalled: the rest at uniform random positions, overlaps and all,
    // then every new grain is pushed apart until nothing overlaps.
    if (x.size() < count) {
        const std::size_t placed = x.size();
        while (x.size() < count) x.push_back(region.sample(rng));
        constexpr int max_sweeps = 2000;
        const auto clear = [&](const Vec3& y) { return walls->clear(y, radius); };
        if (!separate(x, radius, fixed, region, max_sweeps) || (walls && !std::all_of(x.begin(), x.end(), clear)))
            throw Error("drum fill: random placement stalled after " + std::to_string(placed) + " of " +
                        std::to_string(count) + " grains of radius " + metres(radius) + " between z = " +
                        metres(z_lo) + " and " + metres(z_hi) +
                        ", and pushing the rest apart did not clear them of one another and of the walls in " +
                        std::to_string(max_sweeps) + " sweeps: the region is too full, ask for fewer grains");
    }

    std::vector<ParticleSpec> out(count);
    for (std::size_t i = 0; i < count; ++i) {
        out[i].position = x[i];
        out[i].radius = radius;
        out[i].material = material;
        out[i].tag = tag;
    }
    return out;
}

double drum_angular_velocity(double omega, double ramp, double t) {
    return ramp > 0.0 ? omega * std::clamp(t / ramp, 0.0, 1.0) : omega;
}

double spin_up_setting(double omega, double ramp, double dt, std::int64_t k) {
    const double t_before = static_cast<double>(k - 1) * dt;
    if (!(ramp > 0.0) || t_before > ramp + dt) return -1.0;
    return drum_angular_velocity(omega, ramp, t_before + 0.5 * dt);
}

std::size_t equal_mass_count(std::size_t total, double m1, double m2) {
    if (!(m1 > 0.0) || !(m2 > 0.0)) throw Error("equal_mass_count: masses must be positive");
    // n1 m1 = (total - n1) m2 at n1 = total m2 / (m1 + m2); take the nearer
    // of the two whole numbers around it.
    const double exact = static_cast<double>(total) * m2 / (m1 + m2);
    const auto low = static_cast<std::size_t>(std::floor(exact));
    auto imbalance = [&](std::size_t n1) {
        return std::abs(static_cast<double>(n1) * m1 - static_cast<double>(total - n1) * m2);
    };
    if (low >= total) return total;
    return imbalance(low + 1) < imbalance(low) ? low + 1 : low;
}

namespace {

// The species of band i (left to right) of a banded fill.
Species band_species(const DrumFill& fill, std::size_t i) {
    if (fill.arrangement == Arrangement::halves) return i == 0 ? Species::large : Species::small;
    const Species other = fill.ends == Species::small ? Species::large : Species::small;
    return i % 2 == 0 ? fill.ends : other;
}

std::string numbers_text(const std::vector<double>& v) {
    std::string out;
    char buffer[32];
    for (double x : v) {
        std::snprintf(buffer, sizeof buffer, "%.6g", x);
        if (!out.empty()) out += ' ';
        out += buffer;
    }
    return out;
}

// A grain's diameter with the clearance fill_drum_region() keeps from the wall.
double fill_width(double radius) { return 2.0 * radius * (1.0 + fill_wall_clearance); }


// The radius of a species' grains (0 where the materials do not say).
double grain_radius(const DrumMaterials& m, Species species) {
    const std::int32_t index = species == Species::small ? m.small : m.large;
    return index >= 0 && static_cast<std::size_t>(index) < m.materials.size() ? m.materials[index].radius : 0.0;
}

// The materials a drum of these materials uses, each once, in the order
// large, small, wall, cap (the scenario's order), and where each role went.
struct UsedMaterials {
    std::vector<std::int32_t> source;  // index into DrumMaterials::materials
    std::int32_t large = -1, small = -1, wall = -1, cap = -1;
};
UsedMaterials used_indices(const DrumMaterials& m) {
    UsedMaterials u;
    auto take = [&](std::int32_t index) {
        if (index < 0) return std::int32_t{-1};
        for (std::size_t k = 0; k < u.source.size(); ++k)
            if (u.source[k] == index) return static_cast<std::int32_t>(k);
        u.source.push_back(index);
        return static_cast<std::int32_t>(u.source.size() - 1);
    };
    u.large = take(m.large);
    u.small = take(m.small);
    u.wall = take(m.wall);
    u.cap = m.cap >= 0 ? take(m.cap) : u.wall;
    return u;
}
std::vector<Material> used_materials(const DrumMaterials& m) {
    std::vector<Material> out;
    for (const std::int32_t k : used_indices(m).source)
        if (k >= 0 && static_cast<std::size_t>(k) < m.materials.size()) out.push_back(m.materials[k]);
    return out;
}

}  // namespace

DrumMaterials paper_drum_materials() {
    DrumMaterials m;
    m.materials = paper::materials();
    m.pair_properties = paper::pair_properties();
    return m;
}

std::optional<DrumFillProblem> drum_materials_problem(const DrumMaterials& m, const std::string& mode,
                                                      bool periodic_axis) {
    const auto n = static_cast<std::int32_t>(m.materials.size());
    if (m.pair_properties.size() != m.materials.size())
        return DrumFillProblem{"pair", "the pair table must have a row for every material"};
    for (const auto& row : m.pair_properties)
        if (row.size() != m.materials.size())
            return DrumFillProblem{"pair", "the pair table must have a column for every material"};
    auto defined = [&](std::int32_t i) { return i >= 0 && i < n; };
    if (!defined(m.large)) return DrumFillProblem{"large", "missing: name the large grains' material"};
    if (!defined(m.wall)) return DrumFillProblem{"wall", "missing: name the wall's material"};
    if (m.small != -1 && !defined(m.small)) return DrumFillProblem{"small", "not a material of the drum"};
    if (m.cap != -1 && !defined(m.cap)) return DrumFillProblem{"cap", "not a material of the drum"};
    if (m.cap != -1 && periodic_axis) return DrumFillProblem{"cap", "a drum with a periodic axis has no end caps"};
    if (mode == "two-component") {
        if (m.small < 0)
            return DrumFillProblem{"small", "missing: the two-component mode needs the small grains' material (or "
                                            "take mode \"self\", grains of the large grains' material only)"};
        if (m.small == m.large)
            return DrumFillProblem{"small", "the same material as the large grains (\"" + m.materials[m.large].name +
                                                "\"): the two components need two materials; for one kind of grain "
                                                "take mode \"self\""};
    }
    for (const auto& [role, index] : {std::pair{"large", m.large}, std::pair{"small", m.small}}) {
        if (index < 0) continue;
        const double R = m.materials[index].radius;
        if (!(R > 0.0) || !std::isfinite(R))
            return DrumFillProblem{role, "the grains' radius is the material's radius, which must be positive, got " +
                                             numbers_text({R}) + " (material \"" + m.materials[index].name + "\")"};
    }
    return std::nullopt;
}

std::optional<DrumFillProblem> drum_fill_problem(const DrumGeometry& g, const std::string& mode, const DrumFill& f,
                                                 const DrumMaterials& materials) {
    const bool banded = f.arrangement == Arrangement::bands || f.arrangement == Arrangement::boundaries;
    const std::string arrangement(keyword_of(arrangements, f.arrangement));
    if (banded && mode != "two-component")
        return DrumFillProblem{"arrangement", "\"" + arrangement + "\" needs two species (mode \"two-component\"); "
                                              "a self-diffusion drum takes \"halves\" or \"mixed\""};
    if (f.small_volume_fraction && mode != "two-component")
        return DrumFillProblem{"small_volume_fraction", "needs two species (mode \"two-component\")"};
    if (f.small_volume_fraction && !(*f.small_volume_fraction > 0.0 && *f.small_volume_fraction < 1.0))
        return DrumFillProblem{"small_volume_fraction",
                               "must lie strictly between 0 and 1, got " + numbers_text({*f.small_volume_fraction})};
    if (f.cap_friction && g.periodic_axis)
        return DrumFillProblem{"cap_friction", "a drum with a periodic axis has no end caps"};
    if (f.cap_friction)
        for (const Material& m : used_materials(materials))
            if (m.name == drum_cap_material_name)
                return DrumFillProblem{"cap_friction", "the caps' own material would be named \"" +
                                                           std::string(drum_cap_material_name) +
                                                           "\", the name of a material of the drum; give that "
                                                           "material's friction in its [[pair]] tables instead"};
    if (f.cap_friction && !(*f.cap_friction >= 0.0 && std::isfinite(*f.cap_friction)))
        return DrumFillProblem{"cap_friction", "must be a finite number >= 0, got " + numbers_text({*f.cap_friction})};
    if (f.arrangement != Arrangement::bands && (f.bands != 0 || !f.band_widths.empty()))
        return DrumFillProblem{f.bands != 0 ? "bands" : "band_widths",
                               "given, but the arrangement is \"" + arrangement + "\" (it needs \"bands\")"};
    if (f.arrangement != Arrangement::boundaries && !f.boundaries.empty())
        return DrumFillProblem{"boundaries", "given, but the arrangement is \"" + arrangement +
                                                 "\" (it needs \"boundaries\")"};
    if (f.arrangement == Arrangement::bands) {
        if (f.bands < 2) return DrumFillProblem{"bands", "need at least 2 bands, got " + std::to_string(f.bands)};
        if (!f.band_widths.empty()) {
            if (f.band_widths.size() != static_cast<std::size_t>(f.bands))
                return DrumFillProblem{"band_widths", "need one width per band (" + std::to_string(f.bands) +
                                                          "), got " + std::to_string(f.band_widths.size())};
            double sum = 0.0;
            for (double w : f.band_widths) {
                if (!(w > 0.0) || !std::isfinite(w))
                    return DrumFillProblem{"band_widths", "every width must be > 0, got " + numbers_text(f.band_widths)};
                sum += w;
            }
            if (std::abs(sum - 1.0) > band_width_tolerance)
                return DrumFillProblem{"band_widths", "the widths (fractions of the length) must sum to 1, got " +
                                                          numbers_text({sum})};
        }
    }
    if (f.arrangement == Arrangement::boundaries) {
        if (f.boundaries.empty()) return DrumFillProblem{"boundaries", "give at least one boundary z (m)"};
        for (std::size_t i = 0; i < f.boundaries.size(); ++i) {
            const double z = f.boundaries[i];
            if (!(std::abs(z) < 0.5 * g.length))
                return DrumFillProblem{"boundaries", "every boundary must lie inside the drum, -length/2 < z < "
                                                     "length/2 = " + numbers_text({0.5 * g.length}) + " m, got " +
                                                     numbers_text({z})};
            if (i > 0 && !(z > f.boundaries[i - 1]))
                return DrumFillProblem{"boundaries", "must be strictly increasing, got " + numbers_text(f.boundaries)};
        }
    }
    if (banded) {
        const std::vector<double> edges = band_edges(g, f);
        for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
            const Species species = band_species(f, i);
            const double need = fill_width(grain_radius(materials, species));
            if (edges[i + 1] - edges[i] < need)
                return DrumFillProblem{f.arrangement == Arrangement::boundaries ? "boundaries"
                                       : f.band_widths.empty()                  ? "bands"
                                                                                : "band_widths",
                                       "band " + std::to_string(i + 1) + " (z from " + numbers_text({edges[i]}) +
                                           " to " + numbers_text({edges[i + 1]}) + " m) is narrower than a " +
                                           std::string(keyword_of(species_names, species)) + " grain (" +
                                           numbers_text({need}) + " m)"};
        }
    }
    return std::nullopt;
}

std::vector<double> band_widths(const DrumFill& f) {
    const auto k = static_cast<std::size_t>(std::max(f.bands, 1));
    if (!f.band_widths.empty()) {
        if (f.band_widths.size() != k)
            throw Error("drum: band_widths: need one width per band (" + std::to_string(k) + ")");
        return f.band_widths;
    }
    // An even fill: each species' volume share over its number of bands.
    const double small_share = f.small_volume_fraction.value_or(0.5);
    double small_bands = 0.0;
    for (std::size_t i = 0; i < k; ++i) small_bands += band_species(f, i) == Species::small;
    std::vector<double> widths(k);
    for (std::size_t i = 0; i < k; ++i)
        widths[i] = band_species(f, i) == Species::small ? small_share / small_bands
                                                         : (1.0 - small_share) / (static_cast<double>(k) - small_bands);
    return widths;
}

std::vector<double> band_edges(const DrumGeometry& g, const DrumFill& f) {
    const double half = 0.5 * g.length;
    std::vector<double> edges{-half};
    switch (f.arrangement) {
        case Arrangement::halves: edges.push_back(0.0); break;
        case Arrangement::mixed: break;
        case Arrangement::bands: {
            const std::vector<double> widths = band_widths(f);
            double sum = 0.0;  // the widths' sum, 1 to within band_width_tolerance
            for (double w : widths) sum += w;
            double at = 0.0;
            for (std::size_t i = 0; i + 1 < widths.size(); ++i) {
                at += widths[i] / sum;
                edges.push_back(-half + at * g.length);
            }
            break;
        }
        case Arrangement::boundaries: edges.insert(edges.end(), f.boundaries.begin(), f.boundaries.end()); break;
    }
    edges.push_back(half);
    return edges;
}

std::string describe(const DrumFill& f) {
    std::string text(keyword_of(arrangements, f.arrangement));
    const std::string ends = std::string(keyword_of(species_names, f.ends));
    if (f.arrangement == Arrangement::bands)
        text += " " + std::to_string(f.bands) + " (widths " + numbers_text(band_widths(f)) +
                (f.band_widths.empty() ? std::string(": an even fill") : std::string()) + ", " + ends +
                " at the left end)";
    if (f.arrangement == Arrangement::boundaries)
        text += " at z = " + numbers_text(f.boundaries) + " m (" + ends + " at the left end)";
    if (f.small_volume_fraction) text += ", small volume fraction " + numbers_text({*f.small_volume_fraction});
    if (f.cap_friction) text += ", cap friction " + numbers_text({*f.cap_friction});
    return text;
}

std::vector<std::size_t> counts_per_band(std::size_t total, const std::vector<double>& widths) {
    double sum = 0.0;
    for (double w : widths) sum += w;
    if (!(sum > 0.0)) throw Error("counts_per_band: the widths must sum to more than 0");
    std::vector<std::size_t> counts(widths.size());
    std::vector<std::pair<double, std::size_t>> remainders;  // (fraction dropped, band)
    std::size_t given = 0;
    for (std::size_t i = 0; i < widths.size(); ++i) {
        const double exact = static_cast<double>(total) * widths[i] / sum;
        counts[i] = std::min(total - given, static_cast<std::size_t>(std::floor(exact)));
        given += counts[i];
        remainders.push_back({exact - static_cast<double>(counts[i]), i});
    }
    // The largest remainders first; equal ones from the left.
    std::stable_sort(remainders.begin(), remainders.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });
    for (std::size_t k = 0; given < total; k = (k + 1) % remainders.size(), ++given) ++counts[remainders[k].second];
    return counts;
}

DrumSetup build_drum_scenario(const DrumGeometry& g, const std::string& mode, std::size_t grains, std::uint64_t seed,
                              const DrumFill& fill, const DrumMaterials& materials) {
    const bool two_component = mode == "two-component";
    if (!two_component && mode != "self")
        throw Error("drum: unknown mode '" + mode + "' (expected \"two-component\" or \"self\")");
    if (grains < 2) throw Error("drum: need at least 2 grains (one in each half)");
    if (const auto problem = drum_materials_problem(materials, mode, g.periodic_axis))
        throw Error("drum: materials." + problem->key + ": " + problem->reason);
    if (const auto problem = drum_fill_problem(g, mode, fill, materials))
        throw Error("drum: " + problem->key + ": " + problem->reason);

    DrumSetup setup;
    Scenario& s = setup.scenario;
    // The materials used, each once: large, small, wall, cap (the paper's:
    // material-1, material-2, wall).
    const UsedMaterials used = used_indices(materials);
    for (const std::int32_t a : used.source) {
        s.materials.push_back(materials.materials[a]);
        s.pair_properties.emplace_back();
        for (const std::int32_t b : used.source) s.pair_properties.back().push_back(materials.pair_properties[a][b]);
    }
    const std::int32_t large = used.large, small = two_component ? used.small : used.large, wall_material = used.wall;
    std::int32_t cap_material = used.cap;
    auto mass = [&](std::int32_t m) {
        const double R = s.materials[m].radius;
        return 4.0 / 3.0 * pi * s.materials[m].rho * R * R * R;
    };
    auto volume = [&](std::int32_t m) { return mass(m) / s.materials[m].rho; };

    s.gravity = {0.0, -9.81, 0.0};
    RigidMotion rotation;  // about +z through the origin, at rest while the bed settles
    rotation.axis_point = {0.0, 0.0, 0.0};
    rotation.axis_direction = {0.0, 0.0, 1.0};
    rotation.angular_velocity = 0.0;
    s.motions = {rotation};

    if (fill.cap_friction) {
        // The caps' own material: the caps' (the wall's unless they have
        // their own), with its own mu against the grains.
        const auto own = static_cast<std::int32_t>(s.materials.size());
        Material cap = s.materials[cap_material];
        cap.name = drum_cap_material_name;
        s.materials.push_back(cap);
        for (auto& row : s.pair_properties) row.push_back(row[cap_material]);
        s.pair_properties.push_back(s.pair_properties[cap_material]);
        for (const std::int32_t grain : {large, small})
            s.pair_properties[grain][own].mu = s.pair_properties[own][grain].mu = *fill.cap_friction;
        cap_material = own;
    }
    if (g.walls != DrumWalls::particles) {
        // No wall spheres: the inner surface is the smooth walls'; a mesh
        // mantle's in facets in its place.
        setup.wall.inner_radius = 0.5 * g.diameter;
        setup.wall.inner_length = g.length;
        s.walls = drum_smooth_walls(g, wall_material, cap_material, 0);
        if (g.walls == DrumWalls::mesh) {
            s.meshes = {g.mantle ? *g.mantle
                                 : drum_mantle_mesh(g, std::min(s.materials[large].radius, s.materials[small].radius))};
            Wall& mantle = s.walls.front();
            mantle.shape = WallShape::mesh;
            mantle.mesh = 0;
            mantle.point = {};  // loads about the drum's centre
        }
    } else {
        setup.wall =
            build_drum_wall(g, wall_material, 0, std::min(s.materials[large].radius, s.materials[small].radius));
        if (cap_material != wall_material) {
            // The cap planes' spheres: the discs and the mantle's end rings,
            // the next rings lying a whole axial step inside.
            const double cap_plane = 0.5 * g.length + g.wall_radius;
            for (ParticleSpec& p : setup.wall.particles)
                if (std::abs(p.position.z) > cap_plane - 0.25 * setup.wall.axial_step) p.material = cap_material;
        }
    }
    DrumWall& wall = setup.wall;

    // Where each kind of grain goes: regions (z range, count, material, tag),
    // filled in this order, each after the ones before.
    struct Region {
        double z_lo, z_hi;
        std::size_t count;
        std::int32_t material, tag;
    };
    const double half = 0.5 * g.length;
    const std::size_t n_large =
        !two_component ? grains / 2
        : fill.small_volume_fraction
            // n_L v_L F = n_S v_S (1 - F) makes the small grains' volume share F.
            ? equal_mass_count(grains, volume(large) * *fill.small_volume_fraction,
                               volume(small) * (1.0 - *fill.small_volume_fraction))
            : equal_mass_count(grains, mass(large), mass(small));
    const std::size_t n_small = grains - n_large;
    std::vector<Region> regions;
    if (!two_component) {
        if (fill.arrangement == Arrangement::mixed)
            regions = {{-half, half, grains, large, 0}};
        else
            regions = {{-half, 0.0, n_large, large, 0}, {0.0, half, n_small, large, 1}};
    } else if (fill.arrangement == Arrangement::mixed) {
        regions = {{-half, half, n_large, large, 0}, {-half, half, n_small, small, 1}};
    } else {
        // Bands (halves too: large, then small): each species' grains shared
        // among its bands by width.
        const std::vector<double> edges = band_edges(g, fill);
        const std::size_t k = edges.size() - 1;
        std::vector<double> large_widths(k, 0.0), small_widths(k, 0.0);
        for (std::size_t i = 0; i < k; ++i)
            (band_species(fill, i) == Species::large ? large_widths : small_widths)[i] = edges[i + 1] - edges[i];
        const std::vector<std::size_t> large_counts = counts_per_band(n_large, large_widths),
                                       small_counts = counts_per_band(n_small, small_widths);
        for (std::size_t i = 0; i < k; ++i)
            regions.push_back(large_widths[i] > 0.0 ? Region{edges[i], edges[i + 1], large_counts[i], large, 0}
                                                    : Region{edges[i], edges[i + 1], small_counts[i], small, 1});
    }
    const char* place = fill.arrangement == Arrangement::halves  ? "half"
                        : fill.arrangement == Arrangement::mixed ? "species"
                                                                 : "band";
    for (const Region& r : regions)
        if (r.count == 0)
            throw Error("drum: too few grains (" + std::to_string(grains) + ") to put some in each " + place +
                        ": ask for more grains");

    // Independent streams for the regions, all fixed by the seed.
    std::mt19937_64 seeds(seed);
    std::vector<std::uint64_t> region_seeds;
    for (std::size_t i = 0; i < regions.size(); ++i) region_seeds.push_back(seeds());
    std::vector<ParticleSpec> placed = wall.particles;
    std::optional<WallDistances> mesh;  // the grains kept clear of a mesh mantle's lifters
    if (g.walls == DrumWalls::mesh)
        mesh.emplace(s.walls, s.meshes, std::max(s.materials[large].radius, s.materials[small].radius));
    for (std::size_t i = 0; i < regions.size(); ++i) {
        const Region& r = regions[i];
        auto grains_here = fill_drum_region(g, r.z_lo, r.z_hi, r.count, s.materials[r.material].radius, r.material,
                                            r.tag, region_seeds[i], placed, mesh ? &*mesh : nullptr);
        placed.insert(placed.end(), grains_here.begin(), grains_here.end());
        s.particles.insert(s.particles.end(), grains_here.begin(), grains_here.end());
    }
    if (!two_component && fill.arrangement == Arrangement::mixed)
        for (ParticleSpec& p : s.particles) p.tag = p.position.z < 0.0 ? 0 : 1;  // by starting half
    double grain_volume = 0.0;
    for (const ParticleSpec& p : s.particles) {
        grain_volume += 4.0 / 3.0 * pi * p.radius * p.radius * p.radius;
        ++(p.tag == 0 ? setup.grains_left : setup.grains_right);
    }
    setup.solid_fraction = grain_volume / (pi * wall.inner_radius * wall.inner_radius * wall.inner_length);
    s.particles.insert(s.particles.end(), wall.particles.begin(), wall.particles.end());

    // Open space around the drum with a margin of one wall sphere, or of the
    // largest grain beyond smooth walls (the domain only bounds where
    // particles start; a grain's centre outside it has passed through the
    // wall).
    const double margin = g.walls != DrumWalls::particles
                              ? 2.0 * std::max(s.materials[large].radius, s.materials[small].radius)
                              : 3.0 * g.wall_radius;
    const double reach_r = wall.inner_radius + margin, reach_z = half + margin;
    s.domain.lo = {-reach_r, -reach_r, -reach_z};
    s.domain.hi = {reach_r, reach_r, reach_z};
    if (g.periodic_axis) {  // no caps: the drum's length is the period
        s.domain.lo.z = -half;
        s.domain.hi.z = half;
        s.domain.periodic[2] = true;
    }

    // dt is chosen automatically from the Hertz collision at this impact
    // speed. The fastest impact in the drum: a grain carried at the wall
    // speed of a drum turning at its critical speed, omega_c R = sqrt(g R),
    // that then falls the whole diameter D = 2R, gains 2 g D in v^2, so v^2
    // <= g R + 4 g R = 5 g R (1.40 m/s for the paper's drum). While the bed
    // settles grains fall at most D from rest (sqrt(2 g D) = 1.25 m/s).
    const double R_drum = wall.inner_radius;
    s.time_step.dt = 0.0;
    s.time_step.reference_speed = std::sqrt(5.0 * 9.81 * R_drum);
    return setup;
}

}  // namespace tumble
