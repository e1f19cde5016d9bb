// SPDX-License-Identifier: MIT
#include "tumble/sim/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <utility>
#include <limits>
#include <vector>

#include "tumble/contact/kuwabara_kono.hpp"
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

std::vector<ContactPair> contact_pairs(const Scenario& s) {
    // Smallest radius per material, among free and among kinematic particles.
    const std::size_t n_materials = s.materials.size();
    std::vector<double> free_radius(n_materials, inf), kinematic_radius(n_materials, inf);
    for (const auto& p : s.particles) {
        double& r = p.motion == free_motion ? free_radius[p.material] : kinematic_radius[p.material];
        r = std::min(r, p.radius);
    }
    for (const Insertion& q : s.insertions)  // free spheres poured in later
        free_radius[q.material] = std::min(free_radius[q.material], q.radius_min);
    auto mass = [&](std::size_t a, double R) { return 4.0 / 3.0 * pi * s.materials[a].rho * R * R * R; };
    std::vector<ContactPair> pairs;
    auto add = [&](std::string name, std::size_t a, std::size_t b, Partner partner, double R_a, double R_b) {
        ContactPair c{std::move(name), a, b, partner, R_a, R_b, 0.0, mass(a, R_a), {}};
        c.R_star = R_b == inf ? R_a : R_a * R_b / (R_a + R_b);
        if (partner == Partner::free) c.m_star = c.m_star * mass(b, R_b) / (c.m_star + mass(b, R_b));
        c.coefficients = make_pair_coefficients(s.materials[a], s.materials[b], s.pair_properties[a][b],
                                                s.model.tangential_stiffness);
        pairs.push_back(std::move(c));
    };
    const auto& walls = s.domain.walls;
    const bool any_wall = walls[0] || walls[1] || walls[2];
    for (std::size_t a = 0; a < n_materials; ++a) {
        const double Ra = free_radius[a];
        if (Ra == inf) continue;  // no free particle of this material
        const std::string& name = s.materials[a].name;
        for (std::size_t b = 0; b < n_materials; ++b) {
            const std::string pair = name + "-" + s.materials[b].name;
            if (b >= a && free_radius[b] != inf) add(pair, a, b, Partner::free, Ra, free_radius[b]);
            if (kinematic_radius[b] != inf) add(pair + " (kinematic)", a, b, Partner::kinematic, Ra, kinematic_radius[b]);
        }
        if (any_wall) {
            const auto w = static_cast<std::size_t>(s.domain.wall_material);
            add(name + "-flat wall", a, w, Partner::flat_wall, Ra, inf);
        }
        for (const Wall& w : s.walls) {  // at the largest R* the wall gives the grain
            add(name + "-" + w.name + " (wall)", a, static_cast<std::size_t>(w.material), Partner::flat_wall, Ra, inf);
            pairs.back().R_star = wall_contact_radius(Ra, largest_curvature(w));
        }
    }
    return pairs;
}

double hertz_max_overlap(double m_star, double E_star, double R_star, double v) {
    return std::pow(15.0 * m_star * v * v / (16.0 * E_star * std::sqrt(R_star)), 0.4);
}

double hertz_collision_time(double m_star, double E_star, double R_star, double v) {
    return 2.943275 * hertz_max_overlap(m_star, E_star, R_star, v) / v;
}

PairTimes pair_times(const ContactPair& p, const ContactModel& model, double v) {
    const PairCoefficients& c = p.coefficients;
    PairTimes t;
    if (!model.elastic || c.E_star <= 0.0) return t;
    const double h_max = hertz_max_overlap(p.m_star, c.E_star, p.R_star, v);
    t.collision = hertz_collision_time(p.m_star, c.E_star, p.R_star, v);
    // The tangential spring S a (N/m) at a = sqrt(R* h_max), moving 2/7 m*.
    const double spring = c.shear_stiffness * std::sqrt(p.R_star * h_max);
    if (model.shear != ShearModel::Off && c.mu > 0.0 && spring > 0.0)
        t.tangential = pi * std::sqrt(2.0 / 7.0 * p.m_star / spring);
    if (!model.viscous || c.B_star <= 0.0) return t;
    const double a = std::sqrt(p.R_star * h_max);
    const double damping = kuwabara_kono_coefficient(c.B_star, a), stiffness = 2.0 * c.E_star * a;  // N s/m, N/m
    t.viscous = p.m_star / damping;
    if (damping * damping > 4.0 * p.m_star * stiffness)
        t.creep = c.B_star / c.E_star;  // over-damped
    else
        t.ringing_viscous = t.viscous;
    return t;
}

TimeStepReport assess_time_step(const Scenario& s) {
    double collision = inf, viscous = inf, creep = inf, ringing = inf, tangential = inf, rayleigh = inf;
    std::string collision_pair, viscous_pair, creep_pair, ringing_pair, tangential_pair, rayleigh_material;
    const double v = s.time_step.reference_speed;
    // The Hertz collision at speed v and its viscous damping for each pair.
    for (const ContactPair& p : contact_pairs(s)) {
        const PairTimes times = pair_times(p, s.model, v);
        if (times.collision < collision) { collision = times.collision; collision_pair = p.name; }
        if (times.viscous < viscous) { viscous = times.viscous; viscous_pair = p.name; }
        if (times.creep < creep) { creep = times.creep; creep_pair = p.name; }
        if (times.ringing_viscous < ringing) { ringing = times.ringing_viscous; ringing_pair = p.name; }
        if (times.tangential < tangential) { tangential = times.tangential; tangential_pair = p.name; }
        // The Rayleigh time of each material of free grains (each has its pair with itself).
        if (p.partner != Partner::free || p.a != p.b) continue;
        const Material& ma = s.materials[p.a];
        const double t_R = pi * p.R_a * std::sqrt(ma.rho / ma.G) / (0.1631 * ma.nu + 0.8766);
        if (t_R < rayleigh) { rayleigh = t_R; rayleigh_material = ma.name; }
    }

    TimeStepReport r;
    r.collision_time = collision == inf ? 0.0 : collision;
    r.viscous_time = viscous == inf ? 0.0 : viscous;
    r.creep_time = creep == inf ? 0.0 : creep;
    r.ringing_viscous_time = ringing == inf ? 0.0 : ringing;
    r.tangential_time = tangential == inf ? 0.0 : tangential;
    r.rayleigh_time = rayleigh == inf ? 0.0 : rayleigh;
    const std::string collision_why = "the Hertz collision time at " + format(v, "m/s") + " (" +
                                      format_seconds(collision) + ", pair " + collision_pair + ")";
    const std::string viscous_why = "the viscous time m*/c (" + format_seconds(viscous) + ", pair " + viscous_pair +
                                    ") of the damping";
    const std::string creep_why = "the creep time B*/E* of an over-damped contact (" + format_seconds(creep) +
                                  ", pair " + creep_pair + ")";
    const std::string ringing_why = "the viscous time m*/c of a contact damped but not over-damped (" +
                                    format_seconds(ringing) + ", pair " + ringing_pair + ")";
    const std::string tangential_why = "the tangential spring's half period (" + format_seconds(tangential) +
                                       ", pair " + tangential_pair + ")";
    const std::string rayleigh_why = "the Rayleigh time (" + format_seconds(rayleigh) + ", material " +
                                     rayleigh_material + ")";
    // The smallest of the criteria, each a fraction of its time; the first wins a tie.
    auto smallest = [](std::initializer_list<std::pair<double, std::string>> criteria, std::string& why) {
        double value = inf;
        for (const auto& [t, text] : criteria)
            if (t < value) { value = t; why = text; }
        return value;
    };
    // The fractions were measured (docs/MODEL.md, "Time step"; tests
    // Restitution.*, ContactReport.*, TimeStepChoice.*, ObliqueImpact.*):
    // at t_c/20, tau/25 and 0.25 m*/c of a ringing contact restitution
    // and contact time stay within 1 % of the converged collision (with
    // the dashpot of integrate/dashpot.hpp), and at t_t/10 the tangential
    // rebound within 1 % of v_t; 0.7 m*/c is the bed's: a lone collision
    // is within 1 % up to 1.2 m*/c, but a slow drum, whose bed lies in
    // lasting contact, diffuses a fifth too slowly at 1.08 m*/c and
    // agrees with a quarter of that step at 0.7 (studies/time_step); at
    // the maximum, 2 m*/c, collisions err by about 2 % and dense beds stay
    // stable.
    r.recommended = smallest({{collision / 20.0, "a twentieth of " + collision_why},
                              {0.7 * viscous, "0.7 x " + viscous_why},
                              {creep / 25.0, "a 25th of " + creep_why},
                              {0.25 * ringing, "a quarter of " + ringing_why},
                              {tangential / 10.0, "a tenth of " + tangential_why},
                              {0.2 * rayleigh, "0.2 x " + rayleigh_why}},
                             r.recommended_by);
    r.maximum = smallest({{collision / 10.0, "a tenth of " + collision_why},
                          {2.0 * viscous, "2 x " + viscous_why},
                          {tangential / 5.0, "a fifth of " + tangential_why},
                          {0.5 * rayleigh, "half " + rayleigh_why}},
                         r.limiting);
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
