// SPDX-License-Identifier: MIT
// Shared pieces of the physics tests: the paper's materials written out again
// from SPEC-NOTES (not taken from the engine, so a typo there would show),
// the pair constants E*, G*, B*, R*, m* worked out by hand from the
// SPEC-NOTES formulas, and small scenario builders.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "tumble/sim/scenario.hpp"
#include "tumble/setup/drum.hpp"
#include "tumble/sim/simulation.hpp"

namespace physics_test {

using tumble::Vec3;

inline constexpr double pi = 3.14159265358979323846;

// SPEC-NOTES "The materials": E, G, nu, xi, eta, rho, R (SI; 5000 poise = 500 Pa s).
inline tumble::Material paper_material(const char* name, double radius) {
    return {name, 1.0e6, 0.3e6, 0.25, 500.0, 500.0, 1000.0, radius};
}
inline constexpr double R1 = 3.6e-3, R2 = 2.4e-3, R3 = 3.0e-3;  // m

inline std::vector<tumble::Material> paper_materials() {
    return {paper_material("material-1", R1), paper_material("material-2", R2), paper_material("wall", R3)};
}

// mu and W per pair: 1-1 0.1, 1-2 0.2, 2-2 0.5, anything with 3: 0.2; W = 0.2 J/m^2.
inline std::vector<std::vector<tumble::PairProperties>> paper_pairs() {
    const double W = 0.2;
    return {{{0.1, W}, {0.2, W}, {0.2, W}}, {{0.2, W}, {0.5, W}, {0.2, W}}, {{0.2, W}, {0.2, W}, {0.2, W}}};
}

// ---- Pair constants by hand (SPEC-NOTES "Notation") ----------------------

inline double e_star(const tumble::Material& i, const tumble::Material& j) {
    return i.E * j.E / (i.E * (1.0 - j.nu * j.nu) + j.E * (1.0 - i.nu * i.nu));
}
inline double g_star(const tumble::Material& i, const tumble::Material& j) {
    return i.G * j.G / (i.G * (2.0 - j.nu) + j.G * (2.0 - i.nu));
}
// B = 9 xi eta / (3 xi + eta); corrected viscous Poisson ratio
// s = (3 xi - 2 eta) / (2 (3 xi + eta)) (SPEC-NOTES "Corrections").
inline double viscous_B(const tumble::Material& m) { return 9.0 * m.xi * m.eta / (3.0 * m.xi + m.eta); }
inline double viscous_s(const tumble::Material& m) { return (3.0 * m.xi - 2.0 * m.eta) / (2.0 * (3.0 * m.xi + m.eta)); }
inline double b_star(const tumble::Material& i, const tumble::Material& j) {
    const double Bi = viscous_B(i), Bj = viscous_B(j), si = viscous_s(i), sj = viscous_s(j);
    return Bi * Bj / (Bi * (1.0 - sj * sj) + Bj * (1.0 - si * si));
}
// Prefactor of the attraction: sqrt(4/3 * 8 pi W E*), so F = -A (R* h)^(3/4).
inline double attraction_prefactor(double W, double E_star) { return std::sqrt(4.0 / 3.0 * 8.0 * pi * W * E_star); }

inline double reduced(double a, double b) { return a * b / (a + b); }
inline double sphere_mass(double rho, double R) { return 4.0 / 3.0 * pi * rho * R * R * R; }

// Hertz head-on collision, no damping: deepest overlap and duration.
// t_c = 2 h_max / v * int_0^1 dx / sqrt(1 - x^(5/2)) = (h_max / v) * 4/5 B(2/5, 1/2),
// worked out here with tgamma instead of the rounded 2.9432.
inline double hertz_duration_constant() { return 0.8 * std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9); }
inline double hertz_max_overlap(double m_star, double E_star, double R_star, double v) {
    return std::pow(15.0 * m_star * v * v / (16.0 * E_star * std::sqrt(R_star)), 0.4);
}

// Overlap at which a contact of materials a and b with reduced radius R_star
// carries `load` at rest: Hertz - attraction = load (bisection on the part
// above the attraction's balance, where the net force grows with h).
inline double resting_overlap(int a, int b, double R_star, double load) {
    const auto materials = paper_materials();
    const double E_star = e_star(materials[a], materials[b]);
    const double K = 4.0 / 3.0 * E_star * std::sqrt(R_star);
    const double A = attraction_prefactor(paper_pairs()[a][b].W, E_star);
    auto net = [&](double h) { return K * std::pow(h, 1.5) - A * std::pow(R_star * h, 0.75) - load; };
    double lo = std::pow(A / K, 4.0 / 3.0) * R_star, hi = R_star;  // net < 0 at lo (= -load), > 0 at h = R*
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (net(mid) < 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

// ---- Scenarios -----------------------------------------------------------

// Paper materials, open space (no periodic axes, no walls), no gravity.
inline tumble::Scenario open_scenario(double dt) {
    tumble::Scenario s;
    s.materials = paper_materials();
    s.pair_properties = paper_pairs();
    s.domain.lo = {-1.0, -1.0, -1.0};
    s.domain.hi = {1.0, 1.0, 1.0};
    s.time_step.dt = dt;
    return s;
}

inline tumble::ParticleSpec sphere(Vec3 x, double R, int material, Vec3 v = {}, Vec3 w = {}) {
    tumble::ParticleSpec p;
    p.position = x;
    p.velocity = v;
    p.angular_velocity = w;
    p.radius = R;
    p.material = material;
    return p;
}

// Array index of the particle with global id `id` (the store may be re-sorted).
inline std::size_t index_of(const tumble::ParticleStore& p, std::int64_t id) {
    for (std::size_t k = 0; k < p.size(); ++k)
        if (p.id[k] == id) return k;
    throw std::logic_error("no particle with that id");
}

// Overlap of two particles by id (open boundaries).
inline double overlap(const tumble::ParticleStore& p, std::int64_t a, std::int64_t b) {
    const std::size_t i = index_of(p, a), j = index_of(p, b);
    return p.radius[i] + p.radius[j] - tumble::norm(p.position[i] - p.position[j]);
}

inline double relative_difference(double measured, double expected) {
    return std::abs(measured - expected) / std::abs(expected);
}

// One line per measured quantity on stdout, so a run of the suite shows how
// close each experiment came, not just that it passed.
inline void report(const std::string& what, double measured, double expected, double tolerance) {
    std::printf("  [measured] %s: %.10g, expected %.10g (rel. diff %.2e, tolerance %.1e)\n", what.c_str(), measured,
                expected, relative_difference(measured, expected), tolerance);
}

// Random unit-ish vector with components uniform in [-1, 1].
inline Vec3 random_vector(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    const double x = u(rng), y = u(rng), z = u(rng);
    return {x, y, z};
}

// 64 grains of all three materials on a jittered 4 x 4 x 4 lattice in a box
// periodic on all axes, random velocities (0.5 m/s) and spins.
inline tumble::Scenario shaken_box() {
    tumble::Scenario s = open_scenario(5e-6);
    const double spacing = 7.5e-3, L = 4 * spacing;  // 4 cells of 2 R_max + skin per axis
    s.domain.lo = {0.0, 0.0, 0.0};
    s.domain.hi = {L, L, L};
    s.domain.periodic = {true, true, true};
    s.neighbor.skin = 0.05 * R1;  // small: a rebuild every ~0.2 ms
    s.neighbor.sort_every = 1;    // re-sort at every rebuild
    std::mt19937_64 rng(99);
    std::uniform_int_distribution<int> material(0, 2);
    std::uniform_real_distribution<double> jitter(-0.1e-3, 0.1e-3);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) {
                const int m = material(rng);
                const Vec3 x{(i + 0.5) * spacing + jitter(rng), (j + 0.5) * spacing + jitter(rng),
                             (k + 0.5) * spacing + jitter(rng)};
                s.particles.push_back(
                    sphere(x, s.materials[m].radius, m, 0.5 * random_vector(rng), 50.0 * random_vector(rng)));
            }
    return s;
}

// The long drum of `tumble bench --case long-drum` (docs/BENCHMARKS.md) at reduced size: the
// paper's cross-section and wall spheres, end caps, two components, but 6 cm
// long with 300 grains, and turning at 5 rad/s from the start while the
// grains, placed at random and thrown with velocity components up to 1 m/s,
// collide with each other and the wall. Grains and wall spheres move,
// contacts begin and end, and the list is rebuilt and re-sorted (its
// history carried over) every few tens of steps.
inline tumble::Scenario short_drum() {
    tumble::DrumGeometry g;
    g.length = 0.06;
    tumble::Scenario s = tumble::build_drum_scenario(g, "two-component", 300, 5).scenario;
    s.motions[0].angular_velocity = 5.0;
    std::mt19937_64 rng(13);
    for (tumble::ParticleSpec& grain : s.particles)
        if (grain.motion == tumble::free_motion) grain.velocity = random_vector(rng);
    return s;
}

}  // namespace physics_test
