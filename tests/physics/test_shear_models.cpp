// SPDX-License-Identifier: MIT
// The three shear models (contact/mindlin_shear.hpp) as a user runs them:
// at the automatic time step, and converged as the step shrinks.
//
// 1. Sustained sliding: a grain launched along a flat wall, and along the
//    top of a kinematic sphere of radius 1 km, decelerates at mu_eff g while
//    it slides. The continuum values: Coulomb and Spring mu; Paper mu / 2
//    (a saw-tooth from 0 to mu |F_n| and back). The step must not matter.
// 2. Static friction: a grain clamped between two flat walls under a
//    tangential load r mu |F_n| per contact holds without creep.
// 3. Twisting: a grain clamped between a wall and a big sphere that turns
//    about the contact normal; the sphere's contact slips, the wall's
//    (twice the friction coefficient) holds.
// 4. A settled bed of adhesive grains comes to rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>

#include "physics_helpers.hpp"

namespace physics_test {
namespace {

constexpr double g = 9.81;  // m/s^2
constexpr int grain = 0, wall = 2;  // material 1 on material 3 (the drum's wall): mu = 0.2
constexpr double R_big = 1000.0;    // m

std::string model_name(tumble::ShearModel m) { return std::string(tumble::keyword_of(tumble::shear_models, m)); }

// Overlap at which the material-1 grain rests on material 3 under `load`.
double overlap_for_load(double R_star, double load) { return resting_overlap(grain, wall, R_star, load); }

// ---- 1. Sustained sliding ----------------------------------------------

enum class Surface { FlatWall, BigSphere };

// A grain resting on the surface (top at z = 0) under gravity, launched at
// v0 along x without spin.
tumble::Scenario sliding_scenario(tumble::ShearModel model, Surface surface, double v0) {
    tumble::Scenario s = open_scenario(0.0);
    s.model.shear = model;
    s.gravity = {0.0, 0.0, -g};
    const double m = sphere_mass(1000.0, R1);
    if (surface == Surface::FlatWall) {
        s.domain.lo.z = 0.0;
        s.domain.walls = {false, false, true};
        s.domain.wall_material = wall;
        s.particles.push_back(sphere({0.0, 0.0, R1 - overlap_for_load(R1, m * g)}, R1, grain, {v0, 0.0, 0.0}));
    } else {
        s.motions.push_back(tumble::RigidMotion{});  // at rest
        s.particles.push_back(
            sphere({0.0, 0.0, R1 - overlap_for_load(reduced(R1, R_big), m * g)}, R1, grain, {v0, 0.0, 0.0}));
        tumble::ParticleSpec big = sphere({0.0, 0.0, -R_big}, R_big, wall);
        big.motion = 0;
        s.particles.push_back(big);
    }
    return s;
}

// The automatic step of a scenario.
double automatic_step(const tumble::Scenario& s) { return tumble::Simulation(s).dt(); }

// mu_eff = (v0 - v(t)) / (g t) over the first t = 5 ms, while the grain
// slides (it slides for 2 v0 / (7 mu_eff g) >= 15 ms at v0 = 0.1 m/s).
double effective_friction(tumble::Scenario s, double dt) {
    s.time_step.dt = dt;
    tumble::Simulation sim(s);
    const double v0 = s.particles[0].velocity.x, t = 5e-3;
    sim.advance(std::lround(t / dt));
    const auto& p = sim.particles();
    return (v0 - p.velocity[index_of(p, 0)].x) / (g * sim.time());
}

struct SlidingCase {
    tumble::ShearModel model;
    Surface surface;
};

class SustainedSliding : public ::testing::TestWithParam<SlidingCase> {};

TEST_P(SustainedSliding, FrictionIsTheContinuumValueAtEveryStep) {
    const auto [model, surface] = GetParam();
    const double mu = paper_pairs()[grain][wall].mu;
    const double expected = model == tumble::ShearModel::Paper ? 0.5 * mu : mu;
    const tumble::Scenario s = sliding_scenario(model, surface, 0.1);
    const double dt = automatic_step(s);
    for (double fraction : {1.0, 0.1, 0.01}) {
        const double mu_eff = effective_friction(s, fraction * dt);
        std::ostringstream what;
        what << model_name(model) << (surface == Surface::FlatWall ? " on a flat wall" : " on a big sphere")
             << ", mu_eff at " << fraction << " x the automatic step " << dt << " s";
        // 1 %: the required bound. The deceleration is measured over 5 ms
        // (hundreds of teeth of the paper's saw-tooth, whose phase at the
        // end adds at most mu/2 x one tooth's time / 5 ms ~ 0.2 %); the
        // normal force is m g on average (the grain starts at rest on its
        // resting overlap; the dome's slope is 5e-6).
        report(what.str(), mu_eff, expected, 1e-2);
        EXPECT_LT(relative_difference(mu_eff, expected), 1e-2) << what.str();
    }
}

std::string sliding_name(const ::testing::TestParamInfo<SlidingCase>& info) {
    return model_name(info.param.model) + (info.param.surface == Surface::FlatWall ? "OnAFlatWall" : "OnABigSphere");
}

INSTANTIATE_TEST_SUITE_P(
    EveryShearModel, SustainedSliding,
    ::testing::Values(SlidingCase{tumble::ShearModel::Paper, Surface::FlatWall},
                      SlidingCase{tumble::ShearModel::Coulomb, Surface::FlatWall},
                      SlidingCase{tumble::ShearModel::Spring, Surface::FlatWall},
                      SlidingCase{tumble::ShearModel::Paper, Surface::BigSphere},
                      SlidingCase{tumble::ShearModel::Coulomb, Surface::BigSphere},
                      SlidingCase{tumble::ShearModel::Spring, Surface::BigSphere}),
    sliding_name);

// ---- 2. Static friction: a clamped grain ----------------------------------

// The grain between two flat walls of material 3 at x = -+(R - h), so each
// contact carries F_n = Hertz - attraction at overlap h (about 15 mN here,
// 8 x the grain's weight), under a "gravity" along -z that loads each
// contact tangentially with r mu |F_n| (the two torques cancel: no rolling).
// The load comes on at once, from rest.
struct Clamp {
    tumble::Scenario scenario;
    double load_acceleration = 0.0;  // m/s^2
};
Clamp clamped_grain(tumble::ShearModel model, double r) {
    const double h = 1e-4;  // m
    const auto materials = paper_materials();
    const double E_star = e_star(materials[grain], materials[wall]);
    const double F_n = 4.0 / 3.0 * E_star * std::sqrt(R1) * std::pow(h, 1.5) -
                       attraction_prefactor(paper_pairs()[grain][wall].W, E_star) * std::pow(R1 * h, 0.75);
    Clamp c;
    c.load_acceleration = 2.0 * r * paper_pairs()[grain][wall].mu * F_n / sphere_mass(1000.0, R1);
    c.scenario = open_scenario(0.0);
    c.scenario.model.shear = model;
    c.scenario.gravity = {0.0, 0.0, -c.load_acceleration};
    c.scenario.domain.lo.x = -(R1 - h);
    c.scenario.domain.hi.x = R1 - h;
    c.scenario.domain.walls = {true, false, false};
    c.scenario.domain.wall_material = wall;
    c.scenario.particles.push_back(sphere({0.0, 0.0, 0.0}, R1, grain));
    return c;
}

// The grain's mean height over [t, t + window] (the contact's undamped
// tangential ringing, period ~4 ms and a few um, averages out over 0.2 s to
// ~1e-8 m).
double mean_height(tumble::Simulation& sim, double window) {
    const long steps = std::lround(window / sim.dt());
    double sum = 0.0;
    for (long k = 0; k < steps; ++k) {
        sim.step();
        sum += sim.particles().position[0].z;
    }
    return sum / static_cast<double>(steps);
}

struct HoldCase {
    tumble::ShearModel model;
    double r;
};
class StaticFriction : public ::testing::TestWithParam<HoldCase> {};

// Coulomb and Spring hold any load below the limit: the slip vector is a
// spring below it, the force at rest points against the slip, and at the
// limit the slip is held there while the contact slides, so the grain stops
// and sticks. The paper's reading holds a load whose elastic peak (twice the
// load, applied at once) stays below the limit: r < 1/2; see below for more.
TEST_P(StaticFriction, ClampedGrainHoldsWithoutCreep) {
    const auto [model, r] = GetParam();
    tumble::Simulation sim(clamped_grain(model, r).scenario);
    mean_height(sim, 0.05);  // settle
    const double first = mean_height(sim, 0.2), second = mean_height(sim, 0.2);
    const double creep = std::abs(second - first) / 0.2;
    std::printf("  [measured] %s, load %.2f mu |F_n|: creep %.3g m/s, height %.3g m\n", model_name(model).c_str(), r,
                creep, second);
    // The required bound: below 1 um/s. (The paper's rule as it was crept
    // at 0.28 to 0.73 mm/s here, and a regularised direction at v_reg r.)
    // (Where the load's elastic peak, 2 r mu |F_n|, passes the limit, the
    // grain slides once, tens of um, before it sticks.)
    EXPECT_LT(creep, 1e-6);
}

std::string hold_name(const ::testing::TestParamInfo<HoldCase>& info) {
    return model_name(info.param.model) + "At" + std::to_string(std::lround(100 * info.param.r)) + "Percent";
}

INSTANTIATE_TEST_SUITE_P(BelowTheLimit, StaticFriction,
                         ::testing::Values(HoldCase{tumble::ShearModel::Coulomb, 0.1},
                                           HoldCase{tumble::ShearModel::Coulomb, 0.5},
                                           HoldCase{tumble::ShearModel::Coulomb, 0.9},
                                           HoldCase{tumble::ShearModel::Spring, 0.1},
                                           HoldCase{tumble::ShearModel::Spring, 0.5},
                                           HoldCase{tumble::ShearModel::Spring, 0.9},
                                           HoldCase{tumble::ShearModel::Paper, 0.1},
                                           HoldCase{tumble::ShearModel::Paper, 0.4}),
                         hold_name);

// What the paper's reading cannot hold: a load applied at once whose peak
// reaches the limit makes the contact slip, and sliding it feels only the
// saw-tooth's mean mu |F_n| / 2, less than the load: the grain slides on,
// accelerating at (1 - 1/(2 r)) times the load's acceleration.
TEST(StaticFriction, PaperReadingSlidesOnUnderNinetyPercentOfTheLimit) {
    const double r = 0.9;
    const Clamp c = clamped_grain(tumble::ShearModel::Paper, r);
    tumble::Simulation sim(c.scenario);
    const double t = 0.05;
    sim.advance(std::lround(t / sim.dt()));
    const double z = sim.particles().position[0].z;
    const double expected = -0.5 * (1.0 - 1.0 / (2.0 * r)) * c.load_acceleration * t * t;
    // 3 %: the first tooth (the elastic overshoot before the first slip) and
    // the saw-tooth's phase at the end, each a few um of 1.4 mm.
    report("paper reading, 90 % load: distance slid in 50 ms (m)", z, expected, 3e-2);
    EXPECT_LT(relative_difference(z, expected), 3e-2);
}

// ---- 3. Twisting held ----------------------------------------------------

// The grain between a flat wall of material 3 (x = -(R - h); mu 0.2) and a
// kinematic sphere of material 1 (radius 1 km, mu 0.1 with the grain)
// turning at 2 rad/s about the common normal x. Both contacts carry the same
// F_n. The sphere's contact twists to its limit and slips; the wall's holds
// that couple (half its own limit, a quarter on the paper's average): the
// grain must not turn on.
TEST(TwistingHeld, ACoupleBelowTheLimitIsHeld) {
    const double h = 1e-4;  // m
    for (tumble::ShearModel model : {tumble::ShearModel::Paper, tumble::ShearModel::Coulomb,
                                     tumble::ShearModel::Spring}) {
        tumble::Scenario s = open_scenario(0.0);
        s.model.shear = model;
        s.domain.lo.x = -(R1 - h);
        s.domain.hi.x = R1 + 2.0 * R_big;  // the wall at hi is never touched
        s.domain.walls = {true, false, false};
        s.domain.wall_material = wall;
        s.particles.push_back(sphere({0.0, 0.0, 0.0}, R1, grain));
        tumble::RigidMotion turning;
        turning.axis_point = {R1 - h + R_big, 0.0, 0.0};
        turning.axis_direction = {1.0, 0.0, 0.0};
        turning.angular_velocity = 2.0;
        s.motions.push_back(turning);
        tumble::ParticleSpec big = sphere(turning.axis_point, R_big, grain);
        big.motion = 0;
        s.particles.push_back(big);
        tumble::Simulation sim(s);
        // The grain rings in twist (undamped, period ~20 ms, a few 1e-3 rad):
        // compare its mean angle over two windows of 0.5 s (residual of the
        // ringing ~1e-4 rad/s) after a settling 0.1 s.
        auto mean_angle = [&](double window, double& angle) {
            const long steps = std::lround(window / sim.dt());
            double sum = 0.0;
            for (long k = 0; k < steps; ++k) {
                sim.step();
                const auto& p = sim.particles();
                angle += sim.dt() * p.angular_velocity[index_of(p, 0)].x;
                sum += angle;
            }
            return sum / static_cast<double>(steps);
        };
        double angle = 0.0;
        mean_angle(0.1, angle);
        const double first = mean_angle(0.5, angle), second = mean_angle(0.5, angle);
        const double rim_creep = std::abs(second - first) / 0.5 * std::sqrt(R1 * h);
        std::printf("  [measured] %s: the grain's rim creeps at %.3g m/s (the sphere's rim turns at %.3g m/s)\n",
                    model_name(model).c_str(), rim_creep, 2.0 * std::sqrt(R1 * h));
        EXPECT_LT(rim_creep, 1e-6) << model_name(model);  // the required static-friction bound
    }
}

// ---- 4. A settled adhesive bed comes to rest -------------------------------

// 216 grains of material 1 dropped in a walled box (6 x 6 x 6 jittered
// lattice, random velocities 0.05 m/s), every term on; after 1 s the rms
// speed must be below 1e-6 m/s (the required bound; the paper's rule as it
// was kept 0.2 mm/s).
TEST(SettledBed, AdhesiveGrainsComeToRest) {
    for (tumble::ShearModel model : {tumble::ShearModel::Coulomb, tumble::ShearModel::Spring}) {
        tumble::Scenario s = open_scenario(0.0);
        s.model.shear = model;
        s.gravity = {0.0, 0.0, -g};
        const double spacing = 7.6e-3;
        s.domain.lo = {0.0, 0.0, 0.0};
        s.domain.hi = {6 * spacing, 6 * spacing, 12 * spacing};
        s.domain.walls = {true, true, true};
        s.domain.wall_material = wall;
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> jitter(-0.2e-3, 0.2e-3);
        for (int i = 0; i < 6; ++i)
            for (int j = 0; j < 6; ++j)
                for (int k = 0; k < 6; ++k)
                    s.particles.push_back(sphere({(i + 0.5) * spacing + jitter(rng), (j + 0.5) * spacing + jitter(rng),
                                                  (k + 0.5) * spacing + jitter(rng)},
                                                 R1, grain, 0.05 * random_vector(rng)));
        tumble::Simulation sim(s);
        sim.advance(std::lround(1.0 / sim.dt()));
        double sum = 0.0;
        for (const Vec3& v : sim.particles().velocity) sum += tumble::norm2(v);
        const double rms = std::sqrt(sum / static_cast<double>(sim.particles().size()));
        std::printf("  [measured] %s: rms speed after 1 s %.3g m/s\n", model_name(model).c_str(), rms);
        EXPECT_LT(rms, 1e-6) << model_name(model);
    }
}

}  // namespace
}  // namespace physics_test
