// SPDX-License-Identifier: MIT
#include "experiments/limits.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "experiments/drum_setup.hpp"
#include "tumble/analysis/pair_collision.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/materials/pair_table.hpp"
#include "tumble/setup/paper_materials.hpp"
#include "tumble/sim/time_step.hpp"
#include "tumble/walls/facet_grid.hpp"

namespace tumble::experiments {

namespace {

// The peak comes with a checkpoint: the simulation (about 700 bytes per
// sphere with its 3 list pairs, docs/BENCHMARKS.md "Memory per sphere"),
// its captured copy and the encoded file, each with the neighbour list (50
// bytes per further pair) and the walls' contact history (40 per wall slot:
// the box's six faces and one per smooth wall); 48 per extra thread.
// Measured: 1.85 kB per sphere for lattices of 97336 and 343000 spheres
// (maximum resident size of tumble run, 2026-11-30).
constexpr double bytes_per_sphere = 1900.0, bytes_per_pair = 3 * 50.0, bytes_per_thread = 48.0,
                 bytes_per_wall_slot = 3 * 40.0;

double estimate(double spheres, double pairs_per_sphere, double wall_slots, int threads) {
    return spheres * (bytes_per_sphere + bytes_per_pair * std::max(0.0, pairs_per_sphere - 3.0) +
                      bytes_per_thread * (threads - 1) + bytes_per_wall_slot * wall_slots);
}

std::string gib(double bytes) { return fmt::format("{:.3g} GiB", bytes / (1024.0 * 1024.0 * 1024.0)); }

}  // namespace

std::int64_t step_count(double seconds, double dt, const std::string& what) {
    const double steps = std::ceil(seconds / dt - 1e-9);
    if (!(steps <= max_steps))
        throw Error(fmt::format("{}: {:g} s in steps of {:g} s is {:g} steps, more than any run can take (at most "
                                "{:g}); check the duration, the time step and the materials that set it",
                                what, seconds, dt, steps, max_steps));
    return steps > 0.0 ? static_cast<std::int64_t>(steps) : 0;
}

void check_drum_durations(double revolutions, double omega, int samples_per_revolution, double settle_max_time,
                          double dt) {
    step_count(settle_max_time, dt, "settle.max_time");
    const double rotation = revolutions * 2.0 * pi / omega;
    const char* what = "the rotation (--revolutions, and --omega, --rpm or --froude)";
    const std::int64_t steps = step_count(rotation, dt, what);
    const double sample = rotation / (revolutions * samples_per_revolution);  // s between samples
    if (steps < 1 || !(revolutions * samples_per_revolution >= 1.0) || !(sample >= dt))
        throw Error(fmt::format("{}: {:g} revolutions of {:g} s in steps of {:g} s (--dt) give {} steps, too few for "
                                "a sample after the start ({} samples per revolution, --samples)",
                                what, revolutions, rotation / revolutions, dt, steps, samples_per_revolution));
}

std::string finite_positive_problem(double value, const std::string& text) {
    return std::isfinite(value) && value > 0.0 ? std::string() : "must be a finite number > 0, got " + text;
}

std::string thread_count_problem(double value, const std::string& text) {
    return value >= 0.0 && value <= 1e9 && value == std::floor(value)
               ? std::string()
               : "must be a whole number >= 0 (0: every core), got " + text;
}

MemoryNeed scenario_memory(const io::RunConfig& settings, const io::ParticleCount& count, int threads) {
    const Scenario& s = settings.scenario;
    const double n = static_cast<double>(count.spheres), r_min = count.smallest_radius, r_max = count.largest_radius;
    const double skin = s.neighbor.skin > 0.0 ? s.neighbor.skin : 0.2 * r_max;
    // Pairs within reach in a dense packing (solid fraction 0.64), each stored once.
    const double pairs = std::min(0.5 * (n - 1.0), 0.5 * 0.64 * std::pow((2.0 * r_max + skin) / r_min, 3));
    const bool box_walls = s.domain.walls[0] || s.domain.walls[1] || s.domain.walls[2];
    double wall_slots = box_walls || !s.walls.empty() ? 6.0 + static_cast<double>(s.walls.size()) : 0.0;
    // The mesh walls: 3 more history slots per sphere each (mesh_wall_slots
    // = 4), and their triangles: the mesh, its topology and face and edge
    // geometry, and its listing in the facet grid, some 1000 bytes a
    // triangle, with the grid's cells (4 bytes each, at most a quarter of
    // FacetGrid::max_cells), twice over (the run's, and the fill's while
    // it places the spheres clear of the walls).
    double mesh_bytes = 0.0, triangles = 0.0;
    for (const Wall& w : s.walls) {
        if (w.shape != WallShape::mesh || w.mesh < 0 || static_cast<std::size_t>(w.mesh) >= s.meshes.size()) continue;
        const TriangleMesh& m = s.meshes[static_cast<std::size_t>(w.mesh)];
        wall_slots += 3.0;
        triangles += static_cast<double>(m.triangles.size());
        Vec3 lo = m.vertices.front(), hi = lo;
        for (const Vec3& v : m.vertices)
            for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], v[a]), hi[a] = std::max(hi[a], v[a]);
        double cells = 1.0;
        for (int a = 0; a < 3; ++a) cells *= (hi[a] - lo[a] + 2.0 * r_max) / (r_max + skin) + 2.0;
        mesh_bytes += 2.0 * (1000.0 * static_cast<double>(m.triangles.size()) +
                             4.0 * std::min(cells, static_cast<double>(FacetGrid::max_cells / 4)));
    }
    const double sphere_bytes = estimate(n, pairs, wall_slots, threads);
    MemoryNeed need{sphere_bytes + mesh_bytes,
                    fmt::format("{} spheres ({}), {:.3g} neighbour pairs each", count.spheres, count.keys, pairs)};
    if (pairs > 3.0 && s.neighbor.skin > 0.0) need.driver += " (neighbor.skin)";
    if (mesh_bytes > 0.0) need.driver += fmt::format(", and {:.0f} mesh triangles ({})", triangles, gib(mesh_bytes));
    return need;
}

io::ParticleCheck scenario_memory_check(int threads, double limit_bytes, const std::string& option) {
    return [=](const io::RunConfig& settings, const io::ParticleCount& count) {
        check_memory(scenario_memory(settings, count, threads), limit_bytes, settings.source.string(), option);
    };
}

double drum_wall_spheres(const DrumGeometry& g) {
    if (g.walls != DrumWalls::particles) return 0.0;  // smooth or mesh walls: no spheres
    // As build_drum_wall lays them out: rings of touching spheres along the
    // mantle, the caps filled at a little above the square packing.
    const double s = 2.0 * g.wall_radius, Rc = 0.5 * g.diameter + g.wall_radius;
    const double per_ring = s >= 2.0 * Rc ? 2.0 : pi / std::asin(s / (2.0 * Rc)) + 1.0;
    const double rings = (g.length + s) / s + 2.0;
    const double caps = 2.0 * (pi * Rc * Rc / (s * s) * 1.2 + Rc / s + 1.0);
    return per_ring * rings + caps;
}

void check_drum_size(const DrumGeometry& g, double grains, bool allowed, const std::string& source) {
    constexpr double per_grain = 50.0, floor = 100'000.0;
    const double wall = drum_wall_spheres(g);
    if (allowed || wall <= std::max(per_grain * grains, floor)) return;
    throw Error(fmt::format("{}: the drum's wall would take about {:.3g} spheres for {:.0f} grains (diameter {} m, "
                            "length {} m, wall radius {} m): more than {:.0f} times the grains and more than {:.0f}. "
                            "Sizes are in metres (the paper's drum: --diameter 0.08 --length 0.12). If this drum is "
                            "meant, add --large-drum",
                            source, wall, grains, g.diameter, g.length, g.wall_radius, per_grain, floor));
}

void check_stiffness(const Scenario& s, bool allowed, const std::string& source) {
    constexpr double largest_sinking = 0.05;  // of the radius, under the grain's weight
    if (allowed || !s.model.elastic) return;
    const double g = norm(s.gravity), v = s.time_step.reference_speed;
    std::vector<double> largest(s.materials.size(), 0.0);
    for (const ParticleSpec& p : s.particles)
        if (p.motion == free_motion) largest[p.material] = std::max(largest[p.material], p.radius);
    for (std::size_t a = 0; a < s.materials.size(); ++a) {
        if (!(largest[a] > 0.0)) continue;
        const Material& m = s.materials[a];
        // Two equal grains of the largest radius: R* = R/2, m* = m/2.
        const double R = largest[a], mass = 4.0 / 3.0 * pi * m.rho * R * R * R;
        const double E_star = make_pair_coefficients(m, m, s.pair_properties[a][a]).E_star;
        const std::string what = fmt::format("{}: material '{}' (E = {:.3g} Pa): ", source, m.name, m.E);
        const std::string hint = " E and G are in Pa (the paper's grains: 1e6 Pa); if this material is meant, add "
                                 "--allow-soft";
        // At rest, one on the other: m g = 4/3 E* sqrt(R*) h^(3/2) (Hertz).
        const double sinking = std::pow(3.0 * mass * g / (4.0 * E_star * std::sqrt(0.5 * R)), 2.0 / 3.0) / R;
        if (sinking > largest_sinking)
            throw Error(what + fmt::format("a grain of radius {:.3g} m resting on another under gravity {:.3g} "
                                           "m/s^2 would sink {:.3g} % of its radius into it (Hertz), more than "
                                           "{:.0f} % (the paper's grains: 0.44 %).",
                                           R, g, 100.0 * sinking, 100.0 * largest_sinking) +
                        hint);
        // Meeting head-on at the reference speed: the deepest Hertz overlap.
        const double h_max = hertz_max_overlap(0.5 * mass, E_star, 0.5 * R, v);
        if (h_max > 0.5 * R)
            throw Error(what + fmt::format("two grains of radius {:.3g} m meeting at {:.3g} m/s "
                                           "([time_step] reference_speed) would overlap by {:.3g} times their reduced "
                                           "radius (Hertz): they would pass through each other (the paper's "
                                           "grains at 1 m/s: 0.24).",
                                           R, v, h_max / (0.5 * R)) +
                        hint);
    }
    if (!s.model.attraction) return;
    for (const ContactPair& pair : contact_pairs(s)) {
        const double pulled_in = analysis::equilibrium_overlap(analysis::normal_law(pair, s.model)) / pair.R_star;
        if (!(pulled_in <= 1.0))  // NaN too: an attraction that overflows
            throw Error(fmt::format("{}: pair {} (W = {:.3g} J/m^2): its attraction alone would pull two grains at "
                                    "rest into each other by {:.3g} times their reduced radius (the paper's grains: "
                                    "0.025). W is in J/m^2 (the paper's grains: 0.2) and E in Pa; if this pair is "
                                    "meant, add --allow-soft",
                                    source, pair.name, s.pair_properties[pair.a][pair.b].W, pulled_in));
    }
}

void check_time_step(const TimeStepReport& t, const std::string& source) {
    if (!(t.dt > 0.0) || !std::isfinite(t.dt))
        throw Error(fmt::format("{}: the time step is {:g} s ({}), with which nothing advances; check the materials "
                                "(density, moduli, radii) and the reference speed that set it",
                                source, t.dt, t.automatic ? "set by " + t.recommended_by : "given"));
}

MemoryNeed drum_memory(const DrumGeometry& g, double grains, int threads, double skin) {
    const double wall = drum_wall_spheres(g);
    // 3 listed pairs per sphere at a skin of 0.2 R of the paper's large
    // grain; a larger skin lists the pairs within 2 R + skin (0: the drum's
    // automatic skin, drum_skin_per_radius x R).
    const double R = paper::material_1().radius;  // m
    const double listed = skin > 0.0 ? skin : drum_skin_per_radius * R;  // m
    const double pairs = 3.0 * std::max(1.0, std::pow((2.0 * R + listed) / (2.2 * R), 3));
    MemoryNeed need{estimate(grains + wall, pairs, 0.0, threads), ""};
    need.driver = wall > grains ? fmt::format("the drum's wall, {:.3g} spheres (--length, --diameter, --wall-radius)", wall)
                                : fmt::format("{:.3g} grains (--grains, --fill)", grains);
    if (pairs > 6.0) need.driver += fmt::format(", {:.3g} neighbour pairs each (--skin)", pairs);
    return need;
}

double memory_limit_bytes(double gib_limit) {
    if (gib_limit > 0.0) return gib_limit * 1024.0 * 1024.0 * 1024.0;
    double limit = 0.5 * static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
    rlimit address_space{};
    if (::getrlimit(RLIMIT_AS, &address_space) == 0 && address_space.rlim_cur != RLIM_INFINITY)
        limit = std::min(limit, static_cast<double>(address_space.rlim_cur));
    return limit;
}

void check_memory(const MemoryNeed& need, double limit_bytes, const std::string& source, const std::string& option) {
    if (!(need.bytes <= limit_bytes))
        throw Error(fmt::format("{}: the run would need about {} of memory for {}, more than the limit of {} "
                                "({}; default half the machine's memory)",
                                source, gib(need.bytes), need.driver, gib(limit_bytes), option));
}

}  // namespace tumble::experiments
