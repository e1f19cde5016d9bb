// SPDX-License-Identifier: MIT
// Friction and twisting on a nearly flat fixed surface: the top of a
// kinematic sphere of radius 1 km (the paper's wall material, at rest),
// with a material-1 grain resting on it under gravity. Every term of the
// model is on (viscosity and attraction included).
//
// 1. Launched sliding without spin, the grain ends rolling without slip at
//    5/7 of its launch speed: friction acts at the contact point, so the
//    angular momentum about that point, m v L + I omega, is conserved while
//    it slides; rolling means v = omega L. With the lever L = R - h/2 and
//    I = 2/5 m R^2 that gives v_f = v_0 / (1 + 2/5 (R/L)^2), which is 5/7
//    for L = R. The tangential force never exceeds mu |F_n|.
// 2. Spinning about the contact normal it comes to rest, and the couple
//    never exceeds 3 pi/16 a mu |F_n|.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>
#include <string>

#include "physics_helpers.hpp"

namespace physics_test {
namespace {

constexpr double R_big = 1000.0;  // m: so flat that the slope changes the final speed by only ~1e-4
constexpr double g = 9.81;        // m/s^2
constexpr int grain_material = 0, surface_material = 2;

// Overlap at which the grain rests on the big sphere: Hertz - attraction = m g.
double resting_overlap() {
    return physics_test::resting_overlap(grain_material, surface_material, reduced(R1, R_big), sphere_mass(1000.0, R1) * g);
}

// Particle 0: the grain on top, at its resting overlap; particle 1: the big
// sphere, fixed, centre R_big below the origin.
tumble::Scenario dome_scenario(double dt, tumble::ShearModel shear, Vec3 v, Vec3 w) {
    tumble::Scenario s = open_scenario(dt);
    s.model.shear = shear;
    s.gravity = {0.0, 0.0, -g};
    s.motions.push_back(tumble::RigidMotion{});  // at rest
    s.particles.push_back(sphere({0.0, 0.0, R1 - resting_overlap()}, R1, grain_material, v, w));
    tumble::ParticleSpec big = sphere({0.0, 0.0, -R_big}, R_big, surface_material);
    big.motion = 0;
    s.particles.push_back(big);
    return s;
}

// The grain's contact record (the grain may be i or j) and the grain's lever.
struct GrainContact {
    const tumble::ContactRecord* record = nullptr;
    double lever = 0.0;
};
GrainContact grain_contact(const tumble::Simulation& sim) {
    GrainContact c;
    for (const auto& r : sim.contact_records())
        if (r.id_i == 0 || r.id_j == 0) {
            c.record = &r;
            c.lever = r.id_i == 0 ? r.geometry.lever_i : r.geometry.lever_j;
        }
    return c;
}

}  // namespace
}  // namespace physics_test

namespace tumble {
// Names the shear model in test output (gtest finds it by argument lookup).
inline void PrintTo(ShearModel m, std::ostream* out) {
    *out << keyword_of(shear_models, m);
}
}  // namespace tumble

namespace physics_test {
namespace {

class SlidingToRolling : public ::testing::TestWithParam<tumble::ShearModel> {};

TEST_P(SlidingToRolling, EndsRollingAtFiveSeventhsWithinTheCoulombLimit) {
    const double v0 = 0.1;  // m/s, 1000 x the slip regularisation speed
    const double dt = 2e-6;
    tumble::Simulation sim(dome_scenario(dt, GetParam(), {v0, 0.0, 0.0}, {}));
    sim.set_contact_recording(true);
    const double mu = paper_pairs()[grain_material][surface_material].mu;
    const double m = sphere_mass(1000.0, R1), I = 0.4 * m * R1 * R1;

    // Kinetic friction mu m g stops the slip after 2 v0 / (7 mu g) = 15 ms;
    // the paper's slip model saw-tooths between 0 and mu |F_n| and takes
    // about twice as long. Run 200 ms and average over the last 150 ms.
    const long steps = std::lround(0.2 / dt), average_from = steps / 4;
    double worst_ratio = 0.0;  // max |F_t| / (mu |F_n|)
    double lever = 0.0, J = 0.0;
    double sum_v = 0.0, sum_v_roll = 0.0, sum_slip = 0.0, worst_late_slip = 0.0;
    long contact_steps = 0;
    for (long k = 0; k < steps; ++k) {
        sim.step();
        const GrainContact c = grain_contact(sim);
        if (!c.record) continue;
        ++contact_steps;
        const auto& f = c.record->forces;
        const Vec3 F_t = f.force_i - f.normal_force * c.record->geometry.n;
        worst_ratio = std::max(worst_ratio, tumble::norm(F_t) / (mu * std::abs(f.normal_force)));
        lever = c.lever;
        // J: the grain's angular momentum about the contact point (y
        // component), m v L + I w. Contact forces act at that point and
        // cannot change it; only gravity, acting at the centre L n above the
        // point, does: dJ/dt = L m g n_x (the dome's slope, n_x = x / 1 km).
        const Vec3 n = c.record->id_i == 0 ? c.record->geometry.n : -c.record->geometry.n;
        if (k == 0) J = m * v0 * lever;
        J += dt * lever * m * g * n.x;
        if (k >= average_from) {
            const auto& p = sim.particles();
            const std::size_t i = index_of(p, 0);
            const double slip = p.velocity[i].x - p.angular_velocity[i].y * lever;  // contact-point speed
            sum_v += p.velocity[i].x;
            sum_v_roll += J / (m * lever + I / lever);  // speed of pure rolling with this J
            sum_slip += slip;
            worst_late_slip = std::max(worst_late_slip, std::abs(slip));
        }
    }
    ASSERT_EQ(contact_steps, steps) << "the grain lost contact with the surface";

    // Coulomb limit: by construction |F_t| <= mu |F_n|; only the round-off
    // of F_t = force_i - F_n n (a few ulp of |F_n|) may show.
    EXPECT_LE(worst_ratio, 1.0 + 1e-12);
    // And the limit was reached: the grain really slid. (The paper's
    // saw-tooth, seen over a step's window, peaks up to half a step's slip
    // below the limit: 0.5 % here.)
    EXPECT_GT(worst_ratio, 0.99);

    // The engine's J at the end against the one integrated here. The
    // friction torque -L n x F_t with the lever of the force's point of
    // action conserves it exactly, also in the kick-drift-kick scheme; what
    // is left is the rectangle-rule quadrature of the gravity term (itself
    // only ~1e-4 of J), so 1e-7. A torque with the lever R instead of the
    // force's lever R - h/2 would shift J by ~2e-3.
    const auto& p = sim.particles();
    const std::size_t i = index_of(p, 0);
    const double J_engine = m * p.velocity[i].x * lever + I * p.angular_velocity[i].y;
    report("contact-point angular momentum at the end (kg m^2/s)", J_engine, J, 1e-7);
    EXPECT_LT(relative_difference(J_engine, J), 1e-7);

    // Rolling without slip at the end, on average. After sticking, the
    // tangential contact spring (16/3 G* a ~ 200 N/m, period ~3 ms) is not
    // damped by any term of the model (viscosity acts along n only): the
    // spring variant keeps ringing with a slip-speed amplitude A ~ 3e-3 m/s
    // around pure rolling, the paper's slip model loses it at the resets.
    // Averaging over T = 150 ms leaves at most 2 A / (omega T) ~ 2.5e-5 m/s.
    const double samples = static_cast<double>(steps - average_from);
    const double mean_v = sum_v / samples, mean_v_roll = sum_v_roll / samples, mean_slip = sum_slip / samples;
    std::printf("  [measured] late slip: mean %.3g m/s, largest %.3g m/s (v0 = %.3g m/s)\n", mean_slip, worst_late_slip,
                v0);
    EXPECT_LT(std::abs(mean_slip), 1e-3 * v0);
    EXPECT_LT(worst_late_slip, 0.1 * v0);  // it is rolling, not sliding (sliding: slip ~ v0)

    // 5/7 for the ideal lever L = R; the lever R - h/2 lowers it by 0.46 %,
    // rolling down the 1 km dome raises it by ~1e-4. 1 % covers both and
    // still fails for a wrong moment of inertia (I = m R^2 gives 1/2) or a
    // torque whose lever differs from the force's point of action.
    report("mean final speed / launch speed vs 5/7", mean_v / v0, 5.0 / 7.0, 1e-2);
    EXPECT_LT(relative_difference(mean_v / v0, 5.0 / 7.0), 1e-2);
    // Tighter: against pure rolling with the J integrated above, i.e.
    // v0 / (1 + 2/5 (R/L)^2) plus the dome's push; the averaging residual
    // (< 4e-4 relative) is what remains.
    const double ideal = 1.0 / (1.0 + 0.4 * (R1 / lever) * (R1 / lever));
    std::printf("  [measured] 1/(1 + 2/5 (R/L)^2) = %.10g, with the dome %.10g\n", ideal, mean_v_roll / v0);
    report("mean final speed vs pure rolling (m/s)", mean_v, mean_v_roll, 1e-3);
    EXPECT_LT(relative_difference(mean_v, mean_v_roll), 1e-3);
}

std::string shear_name(const ::testing::TestParamInfo<tumble::ShearModel>& info) {
    std::ostringstream name;
    tumble::PrintTo(info.param, &name);
    return name.str();
}

INSTANTIATE_TEST_SUITE_P(EveryShearModel, SlidingToRolling,
                         ::testing::Values(tumble::ShearModel::Paper, tumble::ShearModel::Coulomb,
                                           tumble::ShearModel::Spring),
                         shear_name);

TEST(Twisting, SpinAboutTheNormalStopsWithinTheCoupleLimit) {
    const double omega0 = 5.0;  // rad/s: rim slip speed omega0 a = 2.2e-3 m/s, 20 x the 1e-4 m/s regularisation
    const double dt = 2e-6;
    tumble::Simulation sim(dome_scenario(dt, tumble::ShearModel::Paper, {}, {0.0, 0.0, omega0}));
    sim.set_contact_recording(true);
    const double mu = paper_pairs()[grain_material][surface_material].mu;

    // Fastest possible stop, at the full limiting couple with |F_n| = m g:
    // t_min = I omega0 / (3 pi/16 a mu m g) ~ 50 ms.
    const double m = sphere_mass(1000.0, R1), I = 0.4 * m * R1 * R1;
    const double a = std::sqrt(reduced(R1, R_big) * resting_overlap());
    const double t_min = I * omega0 / (3.0 * pi / 16.0 * a * mu * m * g);

    // The couple (the paper's reading: the angular slip restarts at the
    // limit) saw-tooths from 0 to the limit, half of it on average, so the
    // spin lasts ~2 t_min; run 4 t_min.
    const long steps = std::lround(4.0 * t_min / dt);
    double worst_ratio = 0.0;
    double stop_time = -1.0;
    for (long k = 0; k < steps; ++k) {
        sim.step();
        const GrainContact c = grain_contact(sim);
        ASSERT_NE(c.record, nullptr) << "the grain lost contact";
        const double limit =
            3.0 * pi / 16.0 * c.record->geometry.contact_radius * mu * std::abs(c.record->forces.normal_force);
        worst_ratio = std::max(worst_ratio, std::abs(c.record->forces.twisting_couple) / limit);
        const auto& p = sim.particles();
        if (stop_time < 0.0 && std::abs(p.angular_velocity[index_of(p, 0)].z) < 0.01 * omega0) stop_time = sim.time();
    }
    // The limit is built in; only round-off of a few ulp may show.
    EXPECT_LE(worst_ratio, 1.0 + 1e-12);
    EXPECT_GT(worst_ratio, 0.999);  // it was reached: the contact twisted and slipped
    // A couple bounded by the limit cannot stop the spin before t_min; 1 %
    // of omega0 is left at 0.99 t_min at the earliest.
    ASSERT_GT(stop_time, 0.0) << "still spinning after 4 t_min";
    EXPECT_GT(stop_time, 0.99 * t_min);
    std::printf("  [measured] twist: stop (|w| < 1%% w0) after %.4g s, t_min = %.4g s\n", stop_time, t_min);
    // Once stopped the contact sticks: the couple is then the elastic
    // -8/3 G* a^3 da, an undamped torsion spring (the model has no damping in
    // twist), so the grain rings about the angle where it stopped. The
    // twist it stopped with is at most the limit's, so the ringing spin is
    // at most cap / sqrt(k I): bounded, and no creep beyond it.
    const auto& p = sim.particles();
    const double w_end = p.angular_velocity[index_of(p, 0)].z;
    const double cap = 3.0 * pi / 16.0 * a * mu * m * g, k = 8.0 / 3.0 * g_star(paper_materials()[grain_material], paper_materials()[surface_material]) * a * a * a;
    const double ringing = cap / std::sqrt(k * I);
    std::printf("  [measured] twist: final spin %.3g rad/s, elastic bound %.3g rad/s\n", w_end, ringing);
    EXPECT_LT(std::abs(w_end), 1.05 * ringing);  // 5 %: |F_n| is m g only on average (the normal force rings too)
}

}  // namespace
}  // namespace physics_test
