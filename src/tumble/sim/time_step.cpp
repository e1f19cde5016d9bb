// SPDX-License-Identifier: MIT
#include "tumble/sim/time_step.hpp"

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <vector>

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/materials/pair_table.hpp"
#include "tumble/sim/scenario.hpp"

namespace tumble {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();

std::string format(double value, const char* unit) {
    char buffer[48];
    std::snprintf(buffer, sizeof buffer, "%.3g %s", value, unit);
    return buffer;
}
std::string format_seconds(double t) { return format(t, "s"); }
}  // namespace

TimeStepReport assess_time_step(const Scenario& s) {
    // Smallest radius per material, among free and among kinematic particles.
    const std::size_t n_materials = s.materials.size();
    std::vector<double> free_radius(n_materials, inf), kinematic_radius(n_materials, inf);
    for (const auto& p : s.particles) {
        double& r = p.motion == free_motion ? free_radius[p.material] : kinematic_radius[p.material];
        r = std::min(r, p.radius);
    }

    double collision = inf, viscous = inf, rayleigh = inf;
    std::string collision_pair, viscous_pair, rayleigh_material;
    const double v = s.time_step.reference_speed;
    // The Hertz collision at speed v and its viscous damping for one pair.
    auto consider = [&](const std::string& pair, const PairCoefficients& c, double R_star, double m_star) {
        if (!s.model.elastic || c.E_star <= 0.0) return;
        const double h_max = std::pow(15.0 * m_star * v * v / (16.0 * c.E_star * std::sqrt(R_star)), 0.4);
        const double t_c = 2.943275 * h_max / v;
        if (t_c < collision) { collision = t_c; collision_pair = pair; }
        if (!s.model.viscous || c.B_star <= 0.0) return;
        const double damping = 2.0 * c.B_star * std::sqrt(R_star * h_max);  // N s/m
        if (m_star / damping < viscous) { viscous = m_star / damping; viscous_pair = pair; }
    };
    auto mass = [&](std::size_t a, double R) { return 4.0 / 3.0 * pi * s.materials[a].rho * R * R * R; };
    auto coefficients = [&](std::size_t a, std::size_t b) {
        return make_pair_coefficients(s.materials[a], s.materials[b], s.pair_properties[a][b]);
    };
    const auto& walls = s.domain.walls;
    const bool any_wall = walls[0] || walls[1] || walls[2];
    for (std::size_t a = 0; a < n_materials; ++a) {
        const double Ra = free_radius[a];
        if (Ra == inf) continue;  // no free particle of this material
        const Material& ma = s.materials[a];
        const double t_R = pi * Ra * std::sqrt(ma.rho / ma.G) / (0.1631 * ma.nu + 0.8766);
        if (t_R < rayleigh) { rayleigh = t_R; rayleigh_material = ma.name; }
        for (std::size_t b = 0; b < n_materials; ++b) {
            const std::string pair = ma.name + "-" + s.materials[b].name;
            // Two free grains: the reduced mass.
            if (const double Rb = free_radius[b]; b >= a && Rb != inf)
                consider(pair, coefficients(a, b), Ra * Rb / (Ra + Rb), mass(a, Ra) * mass(b, Rb) / (mass(a, Ra) + mass(b, Rb)));
            // A free grain against a kinematic one, whose motion is prescribed
            // (infinite mass): m* = m. Two kinematic particles never interact.
            if (const double Rb = kinematic_radius[b]; Rb != inf)
                consider(pair + " (kinematic)", coefficients(a, b), Ra * Rb / (Ra + Rb), mass(a, Ra));
        }
        if (any_wall) {
            // A flat wall: infinite radius and mass, so R* = R and m* = m.
            const auto w = static_cast<std::size_t>(s.domain.wall_material);
            consider(ma.name + "-flat wall", coefficients(a, w), Ra, mass(a, Ra));
        }
    }

    TimeStepReport r;
    r.collision_time = collision == inf ? 0.0 : collision;
    r.viscous_time = viscous == inf ? 0.0 : viscous;
    r.rayleigh_time = rayleigh == inf ? 0.0 : rayleigh;
    r.recommended = std::min({collision / 50.0, 0.2 * viscous, 0.2 * rayleigh});
    r.maximum = inf;
    auto limit = [&](double value, const std::string& why) {
        if (value < r.maximum) { r.maximum = value; r.limiting = why; }
    };
    limit(collision / 10.0, "a tenth of the Hertz collision time at " + format(v, "m/s") + " (" +
                                format_seconds(collision) + ", pair " + collision_pair + ")");
    limit(0.5 * viscous, "half the viscous time m*/c (" + format_seconds(viscous) + ", pair " + viscous_pair +
                             "), above which the damping is unstable");
    limit(0.5 * rayleigh, "half the Rayleigh time (" + format_seconds(rayleigh) + ", material " +
                              rayleigh_material + ")");
    if (r.recommended == inf) throw Error("time step: no free particles to derive a time step from");

    const double given = s.time_step.dt;
    if (given == 0.0) {
        r.dt = r.recommended;
        r.automatic = true;
    } else {
        if (!(given > 0.0) || !std::isfinite(given)) throw Error("time step: dt must be a positive number of seconds");
        if (given > r.maximum && !s.time_step.allow_unsafe)
            throw Error("time step: dt = " + format_seconds(given) + " is larger than the safe maximum " +
                        format_seconds(r.maximum) + ", set by " + r.limiting +
                        "; use a smaller dt or leave it out to have one chosen (recommended " +
                        format_seconds(r.recommended) + ")");
        r.dt = given;
    }
    return r;
}

}  // namespace tumble
