// SPDX-License-Identifier: MIT
#include "tumble/analysis/pair_collision.hpp"

#include <cmath>
#include <string>

#include "tumble/contact/attraction.hpp"
#include "tumble/contact/hertz.hpp"
#include "tumble/contact/kuwabara_kono.hpp"
#include "tumble/core/error.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::analysis {

namespace {

constexpr double reference_steps_per_hertz_time = 1e4;
constexpr double hertz_times_to_separate = 40.0;  // the over-damped creep apart takes a few

// Elastic plus attraction energy of the law at overlap h (0 at h = 0), J.
double potential_energy(const NormalLaw& law, double h) {
    const double a = std::sqrt(law.R_star * h);
    return hertz_energy(law.E_star, a, h) + attraction_energy(law.attraction, a, h);
}

// The pair's two spheres (sphere a at -x, moving at +x; the partner at +x,
// or a wall at x = gap/2), a gap of two steps apart, approaching at
// relative speed v with zero total momentum for two free spheres. The wall
// is a plane where the pair's R* is the grain's radius, else the inside of
// a cylinder about z whose curvature kappa gives that R* (walls/wall.hpp:
// R* = R / sqrt(1 - kappa R), so kappa = (1 - (R/R*)^2) / R).
Scenario pair_scenario(const Scenario& base, const ContactPair& pair, const ContactModel& model, double v, double dt) {
    Scenario s;
    s.materials = base.materials;
    s.pair_properties = base.pair_properties;
    s.model = model;
    s.time_step = base.time_step;
    s.time_step.dt = dt;
    s.domain.lo = {-1.0, -1.0, -1.0};
    s.domain.hi = {1.0, 1.0, 1.0};
    const double gap = 2.0 * v * (dt > 0.0 ? dt : 1e-5);
    const double m_a = 4.0 / 3.0 * pi * base.materials[pair.a].rho * std::pow(pair.R_a, 3);
    // The grain's share of the relative speed: m*/m_a of it (all of it against a fixed partner).
    ParticleSpec grain;
    grain.position = {-pair.R_a - 0.5 * gap, 0.0, 0.0};
    grain.velocity = {v * pair.m_star / m_a, 0.0, 0.0};
    grain.radius = pair.R_a;
    grain.material = static_cast<std::int32_t>(pair.a);
    s.particles.push_back(grain);
    if (pair.partner == Partner::flat_wall) {
        Wall wall;
        wall.name = "wall";
        wall.material = static_cast<std::int32_t>(pair.b);
        const double ratio = pair.R_a / pair.R_star, curvature = (1.0 - ratio * ratio) / pair.R_a;
        if (curvature == 0.0) {
            wall.point = {0.5 * gap, 0.0, 0.0};
            wall.normal = {-1.0, 0.0, 0.0};
        } else {
            wall.shape = WallShape::cylinder;
            wall.radius = 1.0 / std::abs(curvature);
            wall.inside = curvature > 0.0;
            wall.point = {0.5 * gap + (wall.inside ? -wall.radius : wall.radius), 0.0, 0.0};
        }
        s.walls.push_back(wall);
        return s;
    }
    ParticleSpec partner;
    partner.position = {pair.R_b + 0.5 * gap, 0.0, 0.0};
    partner.radius = pair.R_b;
    partner.material = static_cast<std::int32_t>(pair.b);
    if (pair.partner == Partner::free) {
        const double m_b = 4.0 / 3.0 * pi * base.materials[pair.b].rho * std::pow(pair.R_b, 3);
        partner.velocity = {-v * pair.m_star / m_b, 0.0, 0.0};
    } else {
        s.motions.push_back(RigidMotion{});  // at rest
        partner.motion = 0;
    }
    s.particles.push_back(partner);
    return s;
}

}  // namespace

NormalLaw normal_law(const ContactPair& pair, const ContactModel& model) {
    const PairCoefficients& c = pair.coefficients;
    return {pair.m_star, pair.R_star, model.elastic ? c.E_star : 0.0, model.viscous ? c.B_star : 0.0,
            model.attraction ? c.attraction : 0.0};
}

double normal_force(const NormalLaw& law, double overlap, double overlap_rate) {
    if (overlap <= 0.0) return 0.0;
    const double a = std::sqrt(law.R_star * overlap);
    // The engine's v_n is the normal relative velocity, -h'.
    return hertz_force(law.E_star, a, overlap) + kuwabara_kono_force(law.B_star, a, -overlap_rate) +
           attraction_force(law.attraction, a);
}

double hertz_collision_time(const NormalLaw& law, double v) {
    return tumble::hertz_collision_time(law.m_star, law.E_star, law.R_star, v);
}

Collision converged_collision(const NormalLaw& law, double v) {
    const double t_c = hertz_collision_time(law, v);
    const double step = t_c / reference_steps_per_hertz_time;
    const auto steps = static_cast<long>(hertz_times_to_separate * reference_steps_per_hertz_time);
    auto accel = [&](double h, double u) { return -normal_force(law, h, u) / law.m_star; };
    double h = 0.0, u = v;
    for (long k = 0; k < steps; ++k) {
        const double k1h = u, k1u = accel(h, u);
        const double k2h = u + 0.5 * step * k1u, k2u = accel(h + 0.5 * step * k1h, u + 0.5 * step * k1u);
        const double k3h = u + 0.5 * step * k2u, k3u = accel(h + 0.5 * step * k2h, u + 0.5 * step * k2u);
        const double k4h = u + step * k3u, k4u = accel(h + step * k3h, u + step * k3u);
        const double h_new = h + step / 6.0 * (k1h + 2.0 * k2h + 2.0 * k3h + k4h);
        const double u_new = u + step / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
        if (k > 0 && h_new <= 0.0) {
            // Crossed zero inside this step: interpolate (the force ~ sqrt(h) barely acts there).
            const double f = h / (h - h_new);
            return {true, -(u + f * (u_new - u)) / v, (static_cast<double>(k) + f) * step};
        }
        h = h_new;
        u = u_new;
        if (law.attraction > 0.0 && 0.5 * law.m_star * u * u + potential_energy(law, h) < 0.0) break;  // bound
    }
    return {};
}

Collision engine_collision(const Scenario& base, const ContactPair& pair, const ContactModel& model, double v,
                           double dt) {
    if (!model.elastic) throw Error("contact: the elastic term is off, so nothing ends a collision");
    Simulation sim(pair_scenario(base, pair, model, v, dt));
    const ParticleStore& p = sim.particles();
    auto index = [&](std::int64_t id) {
        for (std::size_t k = 0; k < p.size(); ++k)
            if (p.id[k] == id) return k;
        throw Error("contact: lost particle " + std::to_string(id));
    };
    const bool wall = pair.partner == Partner::flat_wall;
    auto overlap = [&] {
        const std::size_t i = index(0);
        if (wall) return p.radius[i] - wall_touch(sim.scenario().walls[0], p.position[i]).distance;
        const std::size_t j = index(1);
        return p.radius[i] + p.radius[j] - norm(p.position[j] - p.position[i]);
    };
    const auto steps = std::llround(hertz_times_to_separate * hertz_collision_time(normal_law(pair, model), v) / dt) + 4;
    Collision c;
    double t_in = -1.0, h_old = overlap();
    for (long long k = 0; k < steps && !c.separated; ++k) {
        sim.step();
        const double h = overlap();
        // h is linear in t near its zeros (the force vanishes there): interpolate the crossings.
        if (h_old <= 0.0 && h > 0.0) t_in = sim.time() - dt * h / (h - h_old);
        if (t_in >= 0.0 && h_old > 0.0 && h <= 0.0) {
            c.contact_time = sim.time() - dt * h / (h - h_old) - t_in;
            c.separated = true;
        }
        h_old = h;
    }
    if (!c.separated) return c;
    sim.step();  // no force any more: the velocities are final
    const double partner_velocity = pair.partner == Partner::free ? p.velocity[index(1)].x : 0.0;
    c.restitution = (partner_velocity - p.velocity[index(0)].x) / v;
    return c;
}

double equilibrium_overlap(const NormalLaw& law) {
    if (law.attraction <= 0.0 || law.E_star <= 0.0) return 0.0;
    // F(h, 0) < 0 below the root (attraction ~ h^(3/4) wins), > 0 above; bisect in log h.
    double lo = law.R_star * 1e-16, hi = law.R_star * 1e-16;
    while (normal_force(law, hi, 0.0) < 0.0) lo = hi, hi *= 2.0;
    while (hi - lo > 1e-15 * hi) {
        const double mid = std::sqrt(lo * hi);
        (normal_force(law, mid, 0.0) < 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

double pull_off_force(const NormalLaw& law) {
    const double h_eq = equilibrium_overlap(law);
    if (h_eq <= 0.0) return 0.0;
    // F(h, 0) has one minimum in (0, h_eq): golden-section search in log h.
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double lo = std::log(h_eq * 1e-8), hi = std::log(h_eq);
    auto f = [&](double log_h) { return normal_force(law, std::exp(log_h), 0.0); };
    double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo), f1 = f(x1), f2 = f(x2);
    while (hi - lo > 1e-10) {
        if (f1 < f2) {
            hi = x2, x2 = x1, f2 = f1;
            x1 = hi - g * (hi - lo), f1 = f(x1);
        } else {
            lo = x1, x1 = x2, f1 = f2;
            x2 = lo + g * (hi - lo), f2 = f(x2);
        }
    }
    return -std::min(f1, f2);
}

double sticking_speed(const NormalLaw& law) {
    double lo = 0.0, hi = 1e-3;
    while (!converged_collision(law, hi).separated) {
        if (hi >= max_sticking_speed) return max_sticking_speed;
        lo = hi;
        hi = std::min(2.0 * hi, max_sticking_speed);
    }
    while (hi - lo > 1e-6 * hi) {
        const double mid = 0.5 * (lo + hi);
        (converged_collision(law, mid).separated ? hi : lo) = mid;
    }
    return lo;
}

ContactReport contact_report(const Scenario& scenario, const std::vector<double>& speeds) {
    for (double v : speeds)
        if (!(v > 0.0 && v <= max_impact_speed))
            throw Error("contact: impact speeds must be > 0 and at most " + std::to_string(static_cast<int>(max_impact_speed)) +
                        " m/s, got " + std::to_string(v));
    ContactReport report;
    report.time_step = assess_time_step(scenario);
    report.reference_speed = scenario.time_step.reference_speed;
    report.tangential_stiffness = scenario.model.tangential_stiffness;
    // Restitution of the visco-elastic law alone: no attraction, no shear (head-on anyway).
    ContactModel bouncing = scenario.model;
    bouncing.attraction = false;
    bouncing.shear = ShearModel::Off;
    bouncing.twisting = false;
    for (const ContactPair& pair : contact_pairs(scenario)) {
        PairContactReport r;
        r.pair = pair;
        r.law = normal_law(pair, scenario.model);
        r.times = pair_times(pair, scenario.model, scenario.time_step.reference_speed);
        const NormalLaw law = normal_law(pair, bouncing);
        for (double v : speeds)
            r.impacts.push_back(
                {v, engine_collision(scenario, pair, bouncing, v, report.time_step.dt), converged_collision(law, v)});
        r.equilibrium_overlap = equilibrium_overlap(r.law);
        r.pull_off_force = pull_off_force(r.law);
        r.sticking_speed = r.law.attraction > 0.0 ? sticking_speed(r.law) : 0.0;
        report.pairs.push_back(std::move(r));
    }
    return report;
}

}  // namespace tumble::analysis
