// SPDX-License-Identifier: MIT
// Head-on binary collisions. Without damping the engine must reproduce the
// Hertz analytic collision (duration, deepest overlap, no energy lost); with
// the paper's internal friction its coefficient of restitution must match an
// independent high-accuracy integration of the 1-D normal equation written
// here, which uses no engine code.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <ostream>
#include <string>
#include <vector>

#include "physics_helpers.hpp"

namespace physics_test {
namespace {

struct Collision {
    double contact_time = 0.0;      // s, interpolated zero crossings of h
    double max_overlap = 0.0;       // m
    double separation_speed = 0.0;  // m/s, relative normal speed after the contact (0: never separated)
    double kinetic_before = 0.0;    // J
    double kinetic_after = 0.0;     // J
    bool separated = false;
};

// What sphere 0 (radius Ra, material ma) hits: a free sphere 1 (Rb, mb), a
// kinematic one at rest (infinite mass), or a flat wall of material mb.
enum class Partner { Free, Kinematic, FlatWall };

// The pair's scenario: sphere 0 at -x and the partner at +x approach each
// other at relative speed v (zero total momentum for two free spheres),
// starting a gap of about two steps apart (dt = 0: the automatic step, with
// the gap of 2 v 1e-5 m).
tumble::Scenario collision_scenario(double Ra, int ma, double Rb, int mb, double v, const tumble::ContactModel& model,
                                    double dt, Partner partner) {
    tumble::Scenario s = open_scenario(dt);
    s.model = model;
    const double rho = s.materials[0].rho;
    const double m_a = sphere_mass(rho, Ra), m_b = sphere_mass(rho, Rb);
    const bool free = partner == Partner::Free;
    const double v_a = free ? v * m_b / (m_a + m_b) : v, v_b = free ? -v * m_a / (m_a + m_b) : 0.0;
    const double gap = 2.0 * v * (dt > 0.0 ? dt : 1e-5);
    s.particles.push_back(sphere({-Ra - 0.5 * gap, 0.0, 0.0}, Ra, ma, {v_a, 0.0, 0.0}));
    if (partner == Partner::FlatWall) {
        s.domain.hi.x = 0.5 * gap;
        s.domain.walls = {true, false, false};
        s.domain.wall_material = mb;
        return s;
    }
    s.particles.push_back(sphere({Rb + 0.5 * gap, 0.0, 0.0}, Rb, mb, {v_b, 0.0, 0.0}));
    if (partner == Partner::Kinematic) {
        s.motions.push_back(tumble::RigidMotion{});  // at rest
        s.particles.back().motion = 0;
    }
    return s;
}

// The pair's overlap: with sphere 1, or with the wall at x = hi.
double pair_overlap(const tumble::Simulation& sim, Partner partner) {
    const auto& p = sim.particles();
    if (partner != Partner::FlatWall) return overlap(p, 0, 1);
    const std::size_t i = index_of(p, 0);
    return p.position[i].x + p.radius[i] - sim.scenario().domain.hi.x;
}

// Runs the collision until the pair separates or max_steps have passed.
Collision collide(double Ra, int ma, double Rb, int mb, double v, const tumble::ContactModel& model, double dt,
                  long max_steps, Partner partner = Partner::Free) {
    const tumble::Scenario s = collision_scenario(Ra, ma, Rb, mb, v, model, dt, partner);
    const double m_a = sphere_mass(s.materials[0].rho, Ra), m_b = sphere_mass(s.materials[0].rho, Rb);
    const double v_a = s.particles[0].velocity.x, v_b = partner == Partner::Free ? s.particles[1].velocity.x : 0.0;
    tumble::Simulation sim(s);

    Collision c;
    c.kinetic_before = 0.5 * m_a * v_a * v_a + 0.5 * m_b * v_b * v_b;
    double t_in = -1.0;
    double h_old = pair_overlap(sim, partner);
    for (long k = 0; k < max_steps; ++k) {
        sim.step();
        const double h = pair_overlap(sim, partner);
        c.max_overlap = std::max(c.max_overlap, h);
        // h is linear in t near its zeros (the force vanishes there), so
        // linear interpolation of the crossing is accurate to O(dt^2).
        if (h_old <= 0.0 && h > 0.0) t_in = sim.time() - sim.dt() * h / (h - h_old);
        if (t_in >= 0.0 && h_old > 0.0 && h <= 0.0) {
            c.contact_time = sim.time() - sim.dt() * h / (h - h_old) - t_in;
            c.separated = true;
            break;
        }
        h_old = h;
    }
    sim.step();  // no force any more: the velocities are final
    const auto& p = sim.particles();
    const std::size_t ia = index_of(p, 0);
    const double v_b_after = partner == Partner::Free ? p.velocity[index_of(p, 1)].x : 0.0;
    c.separation_speed = c.separated ? v_b_after - p.velocity[ia].x : 0.0;
    c.kinetic_after = 0.5 * m_a * tumble::norm2(p.velocity[ia]) + 0.5 * m_b * v_b_after * v_b_after;
    return c;
}

tumble::ContactModel elastic_only() {
    tumble::ContactModel m;
    m.viscous = false;
    m.attraction = false;
    m.shear = tumble::ShearModel::Off;
    m.twisting = false;
    return m;
}

// The constant of the Hertz collision time, t_c = C h_max / v:
// 2 int_0^1 (1 - x^(5/2))^(-1/2) dx = 4/5 B(2/5, 1/2) = 2.943275...
// time_step.cpp uses 2.943275; six decimals, hence the tolerance.
TEST(HertzCollisionConstant, IsFourFifthsBetaTwoFifthsOneHalf) {
    EXPECT_NEAR(hertz_duration_constant(), 2.943275, 1e-6);
}

// A head-on collision: sphere a (radius, material index) against sphere b
// at relative speed v (m/s). Used by the Hertz and the restitution tests.
struct CollisionCase {
    double Ra;
    int ma;
    double Rb;
    int mb;
    double v;
};

std::ostream& operator<<(std::ostream& out, const CollisionCase& k) {
    return out << "R " << k.Ra << " m (material " << k.ma + 1 << ") against R " << k.Rb << " m (material " << k.mb + 1
               << ") at " << k.v << " m/s";
}

class HertzCollision : public ::testing::TestWithParam<CollisionCase> {};

// Elastic spheres, no viscosity, attraction or friction: duration and
// deepest overlap are Hertz's, and the kinetic energy comes back.
TEST_P(HertzCollision, MatchesAnalyticDurationOverlapAndEnergy) {
    const CollisionCase k = GetParam();
    const auto materials = paper_materials();
    const double E_star = e_star(materials[k.ma], materials[k.mb]);
    const double m_star = reduced(sphere_mass(1000.0, k.Ra), sphere_mass(1000.0, k.Rb));
    const double R_star = reduced(k.Ra, k.Rb);
    const double h_max = hertz_max_overlap(m_star, E_star, R_star, k.v);
    const double t_c = hertz_duration_constant() * h_max / k.v;
    const double dt = t_c / 2000.0;

    const Collision c = collide(k.Ra, k.ma, k.Rb, k.mb, k.v, elastic_only(), dt, 4000);
    ASSERT_TRUE(c.separated);
    // The required bound is 1 %. Velocity Verlet with 2000 steps per collision
    // errs by O((dt/t_c)^2) ~ 1e-6 and the zero crossings are interpolated
    // to O(dt^2); 1e-4 keeps a wide margin yet would still catch a factor in
    // E*, R* or m* (any of those moves t_c and h_max by >= 1e-2).
    report("contact time (s)", c.contact_time, t_c, 1e-4);
    report("max overlap (m)", c.max_overlap, h_max, 1e-4);
    report("kinetic energy after (J)", c.kinetic_after, c.kinetic_before, 1e-6);
    EXPECT_LT(relative_difference(c.contact_time, t_c), 1e-4) << "t_c = " << c.contact_time << " vs " << t_c;
    EXPECT_LT(relative_difference(c.max_overlap, h_max), 1e-4) << "h_max = " << c.max_overlap << " vs " << h_max;
    // Symplectic integrator, conservative force that is C^1 at h = 0: the
    // energy error after the contact is O((dt/t_c)^2) ~ 2.5e-7 times an
    // O(1) constant; 1e-6 is the brief's bound.
    EXPECT_LT(relative_difference(c.kinetic_after, c.kinetic_before), 1e-6)
        << "KE " << c.kinetic_after << " vs " << c.kinetic_before;
}

INSTANTIATE_TEST_SUITE_P(PaperMaterials, HertzCollision,
                         ::testing::Values(CollisionCase{R1, 0, R1, 0, 1.0},   // 1-1 at 1 m/s
                                           CollisionCase{R1, 0, R2, 1, 0.3}),  // 1-2 at 0.3 m/s
                         [](const auto& info) { return info.index == 0 ? "Material11At1" : "Material12At0p3"; });

// ---- Restitution with the paper's internal friction ----------------------

// Independent reference: the 1-D normal equation of the pair,
//   m* h'' = -(4/3 E* sqrt(R*) h^(3/2) + 2 B* sqrt(R*) h^(1/2) h'),
// from h = 0, h' = v, integrated with classical RK4 at a fixed step, until h
// returns to 0. Returns the separation speed -h' at that moment, or 0 if h
// has not returned to zero by t_end (never separated).
double reference_separation_speed(double m_star, double E_star, double B_star, double R_star, double v, double step,
                                  double t_end) {
    const double K = 4.0 / 3.0 * E_star * std::sqrt(R_star);
    const double C = 2.0 * B_star * std::sqrt(R_star);
    auto accel = [&](double h, double u) {
        const double hp = std::max(h, 0.0);
        return -(K * hp * std::sqrt(hp) + C * std::sqrt(hp) * u) / m_star;
    };
    double h = 0.0, u = v;
    for (double t = 0.0; t < t_end; t += step) {
        const double k1h = u, k1u = accel(h, u);
        const double k2h = u + 0.5 * step * k1u, k2u = accel(h + 0.5 * step * k1h, u + 0.5 * step * k1u);
        const double k3h = u + 0.5 * step * k2u, k3u = accel(h + 0.5 * step * k2h, u + 0.5 * step * k2u);
        const double k4h = u + step * k3u, k4u = accel(h + step * k3h, u + step * k3u);
        const double h_new = h + step / 6.0 * (k1h + 2.0 * k2h + 2.0 * k3h + k4h);
        const double u_new = u + step / 6.0 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u);
        if (t > 0.0 && h_new <= 0.0) {
            // Crossed zero inside this step: interpolate the speed (it barely
            // changes in the last step, the force being ~ sqrt(h)).
            const double f = h / (h - h_new);
            return -(u + f * (u_new - u));
        }
        h = h_new;
        u = u_new;
    }
    return 0.0;
}

struct RestitutionCase {
    double Ra;
    int ma;
    double Rb;
    int mb;
    Partner partner;
    double v;
};

std::ostream& operator<<(std::ostream& out, const RestitutionCase& k) {
    const char* partner[] = {"free", "kinematic", "flat wall of"};
    return out << "R " << k.Ra << " m (material " << k.ma + 1 << ") against " << partner[static_cast<int>(k.partner)]
               << " material " << k.mb + 1 << " at " << k.v << " m/s";
}

// Every pair of the paper's materials that meets in a drum (grains 1 and 2
// against each other, against the wall spheres of material 3 and against a
// flat wall of it) at 0.05, 0.1, 0.3 and 1 m/s.
std::vector<RestitutionCase> restitution_cases() {
    std::vector<RestitutionCase> cases;
    for (double v : {0.02, 0.05, 0.07, 0.1, 0.3, 1.0}) {
        cases.push_back({R1, 0, R1, 0, Partner::Free, v});
        cases.push_back({R1, 0, R2, 1, Partner::Free, v});
        cases.push_back({R2, 1, R2, 1, Partner::Free, v});
        cases.push_back({R1, 0, R3, 2, Partner::Kinematic, v});
        cases.push_back({R2, 1, R3, 2, Partner::Kinematic, v});
        cases.push_back({R1, 0, R3, 2, Partner::FlatWall, v});
        cases.push_back({R2, 1, R3, 2, Partner::FlatWall, v});
    }
    return cases;
}

std::string restitution_case_name(const ::testing::TestParamInfo<RestitutionCase>& info) {
    const RestitutionCase& k = info.param;
    const char* partner[] = {"Free", "Kinematic", "FlatWall"};
    std::string speed = std::to_string(static_cast<int>(std::lround(k.v * 100)));
    return "Material" + std::to_string(k.ma + 1) + partner[static_cast<int>(k.partner)] + std::to_string(k.mb + 1) +
           "At" + speed + "cm";
}

class Restitution : public ::testing::TestWithParam<RestitutionCase> {};

// What to expect first. For material 1 at 1 m/s: m* = 9.8e-5 kg, Hertz time
// 1.3 ms, but the viscous time m*/(2 B* sqrt(R* h_max)) is only 0.1 ms: the
// collision is heavily over-damped. The spheres stop, then creep apart, the
// overlap decaying like exp(-K t / C) (K = 4/3 E* sqrt(R*), C = 2 B*
// sqrt(R*)) until inertia takes over at tiny h and they leave at a finite
// speed. That speed is nearly independent of the impact speed (scale
// m*^2 K^3 / C^5 ~ mm/s), so e ~ 0.005 m/s / v: about 0.04 at 0.1 m/s and
// 0.005 at 1 m/s. Both sides use one definition: e = separation speed when
// h returns to 0, divided by the impact speed. The surface attraction is
// off: with it these grains stick at all these speeds (docs/MODEL.md).
TEST_P(Restitution, AtTheAutomaticStepMatchesIndependentIntegrationOfTheNormalEquation) {
    const RestitutionCase k = GetParam();
    const auto materials = paper_materials();
    const tumble::Material& a = materials[k.ma];
    const tumble::Material& b = materials[k.mb];
    const double E_star = e_star(a, b), B_star = b_star(a, b);
    const double m_a = sphere_mass(a.rho, k.Ra);
    const double m_star = k.partner == Partner::Free ? reduced(m_a, sphere_mass(b.rho, k.Rb)) : m_a;
    const double R_star = k.partner == Partner::FlatWall ? k.Ra : reduced(k.Ra, k.Rb);
    const double t_c = hertz_duration_constant() * hertz_max_overlap(m_star, E_star, R_star, k.v) / k.v;

    const double reference = reference_separation_speed(m_star, E_star, B_star, R_star, k.v, t_c * 1e-4, 40.0 * t_c);
    const double coarser = reference_separation_speed(m_star, E_star, B_star, R_star, k.v, t_c * 2e-4, 40.0 * t_c);
    ASSERT_GT(reference, 0.0) << "reference: the spheres never separate";
    // The reference must be far more accurate than the 1 % under test:
    // halving its step moves it by < 1e-4 (RK4, slowed near h = 0 by sqrt(h)).
    ASSERT_LT(relative_difference(coarser, reference), 1e-4);

    tumble::ContactModel model;  // paper's viscosity on
    model.attraction = false;
    model.shear = tumble::ShearModel::Off;
    model.twisting = false;
    const tumble::Scenario s = collision_scenario(k.Ra, k.ma, k.Rb, k.mb, k.v, model, 0.0, k.partner);
    const double dt = tumble::Simulation(s).dt();
    const long steps = std::lround(40.0 * t_c / dt);
    const Collision c = collide(k.Ra, k.ma, k.Rb, k.mb, k.v, model, dt, steps, k.partner);
    ASSERT_TRUE(c.separated) << "engine: the spheres never separated within 40 t_c";
    const double e_engine = c.separation_speed / k.v, e_reference = reference / k.v;

    // The step chosen for this impact speed ([time_step] reference_speed =
    // v rather than the default 1 m/s): at 0.02 to 0.07 m/s the pairs of
    // material 1 ring once, near critical damping, and the step is a quarter
    // of m*/c (at t_c/20 they were 0.9 to 1.8 % low). Measured: within 0.6 %.
    tumble::Scenario at_v = s;
    at_v.time_step.reference_speed = k.v;
    const double dt_v = tumble::Simulation(at_v).dt();
    const Collision own = collide(k.Ra, k.ma, k.Rb, k.mb, k.v, model, dt_v, std::lround(40.0 * t_c / dt_v), k.partner);
    ASSERT_TRUE(own.separated);
    report("restitution at the automatic step " + std::to_string(dt_v) + " s for " + std::to_string(k.v) + " m/s",
           own.separation_speed / k.v, e_reference, 1e-2);
    EXPECT_LT(relative_difference(own.separation_speed / k.v, e_reference), 1e-2);
    // The required bound. The damping sees the velocity predicted for t + dt
    // (second order) and solves its own dashpot over the step
    // (integrate/dashpot.hpp); with the half-step velocity it was 1.2 to 4 %
    // low here. Measured: within 0.67 % (the step is tau/25 or t_c/20).
    // The printed viscous Poisson ratio (B* off by 1.6 %) would move e by
    // 6-8 % (e falls steeply with B*), so it is caught.
    report("restitution at the automatic step " + std::to_string(dt) + " s", e_engine, e_reference, 1e-2);
    EXPECT_LT(relative_difference(e_engine, e_reference), 1e-2)
        << "e = " << e_engine << " vs reference " << e_reference << " at " << k.v << " m/s";

    // Converged: at a quarter of the step the error of a second-order scheme
    // falls 16-fold, to < 1e-3 here (measured: < 4.7e-4).
    const Collision fine = collide(k.Ra, k.ma, k.Rb, k.mb, k.v, model, dt / 4.0, 4 * steps, k.partner);
    ASSERT_TRUE(fine.separated);
    report("restitution at a quarter of it", fine.separation_speed / k.v, e_reference, 1e-3);
    EXPECT_LT(relative_difference(fine.separation_speed / k.v, e_reference), 1e-3);
}

INSTANTIATE_TEST_SUITE_P(PaperViscosity, Restitution, ::testing::ValuesIn(restitution_cases()),
                         restitution_case_name);

}  // namespace
}  // namespace physics_test
