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

std::string model_name(tumble::ShearModel m) {
    for (const auto& e : tumble::shear_models)
        if (e.model == m) return std::string(e.keyword);
    return "?";
}

// Overlap at which Hertz - attraction = load for the material-1 grain on
// material 3 with reduced radius R_star (bisection on the monotonic part).
double overlap_for_load(double R_star, double load) {
    const auto materials = paper_materials();
    const double E_star = e_star(materials[grain], materials[wall]);
    const double K = 4.0 / 3.0 * E_star * std::sqrt(R_star);
    const double A = attraction_prefactor(paper_pairs()[grain][wall].W, E_star);
    auto net = [&](double h) { return K * std::pow(h, 1.5) - A * std::pow(R_star * h, 0.75) - load; };
    double lo = std::pow(A / K, 4.0 / 3.0) * R_star, hi = R1;
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        (net(mid) < 0.0 ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

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
        // 1 %: the bound. The deceleration is measured over 5 ms
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

}  // namespace
}  // namespace physics_test
