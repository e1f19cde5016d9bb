// SPDX-License-Identifier: MIT
// The time-step check against the hand formulas of time_step.hpp for the
// paper's material 1 (R = 3.6 mm) at a reference speed of 1 m/s:
//   h_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5), t_c = 2.943275 h_max / v,
//   viscous time m* / (2 B* sqrt(R* h_max)), creep time B*/E* (over-damped),
//   Rayleigh time pi R sqrt(rho/G) / (0.1631 nu + 0.8766).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/sim/time_step.hpp"
#include "tumble/setup/benchmark_cube.hpp"
#include "tumble/setup/generators.hpp"
#include "tumble/setup/paper_materials.hpp"
#include "tumble/sim/scenario.hpp"

namespace tumble {
namespace {

// Hand formulas and engine take the same few steps in a different order:
// agreement to 1e-12 relative is round-off, not luck.
constexpr double round_off = 1e-12;

// A 3 x 3 x 3 lattice of material-1 grains, nothing else.
Scenario material_one(double dt) {
    Scenario s;
    s.materials = {paper::material_1()};
    s.pair_properties = {{paper::pair_properties()[0][0]}};
    s.domain = {{0.0, 0.0, 0.0}, {0.03, 0.03, 0.03}};
    s.particles = lattice({0.005, 0.005, 0.005}, {3, 3, 3}, 0.008, 3.6e-3, 0);
    s.time_step.dt = dt;
    s.time_step.reference_speed = 1.0;
    return s;
}

struct Hand {
    double collision, viscous, rayleigh, creep;
};

Hand hand_times() {
    const double E = 1e6, G = 0.3e6, nu = 0.25, xi = 500.0, eta = 500.0, rho = 1000.0, R = 3.6e-3, v = 1.0;
    const double E_star = E / (2.0 * (1.0 - nu * nu));  // 533333.33 Pa
    const double B = 9.0 * xi * eta / (3.0 * xi + eta);
    const double s = (3.0 * xi - 2.0 * eta) / (2.0 * (3.0 * xi + eta));
    const double B_star = B / (2.0 * (1.0 - s * s));  // 571.43 Pa s
    const double m = 4.0 / 3.0 * pi * rho * R * R * R;
    const double m_star = m / 2.0, R_star = R / 2.0;
    // Energy balance 1/2 m* v^2 = 8/15 E* sqrt(R*) h_max^(5/2).
    const double h_max = std::pow(0.5 * m_star * v * v / (8.0 / 15.0 * E_star * std::sqrt(R_star)), 0.4);
    return {2.943275 * h_max / v, m_star / (2.0 * B_star * std::sqrt(R_star * h_max)),
            pi * R * std::sqrt(rho / G) / (0.1631 * nu + 0.8766), B_star / E_star};
}

TEST(TimeStep, MaterialOneAtOneMetrePerSecondMatchesHandFormulas) {
    const Hand hand = hand_times();
    // Orders of magnitude for the record: t_c = 1.29 ms, viscous time
    // 96.1 us, Rayleigh time 712 us; these very soft, very viscous grains are
    // limited by their damping.
    EXPECT_NEAR(hand.collision, 1.2934e-3, 1e-7);
    EXPECT_NEAR(hand.viscous, 9.6134e-5, 1e-9);
    EXPECT_NEAR(hand.rayleigh, 7.1178e-4, 1e-8);

    const TimeStepReport r = assess_time_step(material_one(0.0));
    EXPECT_NEAR(r.collision_time, hand.collision, hand.collision * round_off);
    EXPECT_NEAR(r.viscous_time, hand.viscous, hand.viscous * round_off);
    EXPECT_NEAR(r.rayleigh_time, hand.rayleigh, hand.rayleigh * round_off);
    // Over-damped: c^2 / (4 m* k) = tau / (4 m*/c) = 1.07 ms / 0.385 ms > 1.
    EXPECT_NEAR(r.creep_time, hand.creep, hand.creep * round_off);
    EXPECT_NEAR(hand.creep, 1.0714e-3, 1e-7);
    const double recommended =
        std::min({hand.collision / 20.0, 0.7 * hand.viscous, hand.creep / 25.0, 0.2 * hand.rayleigh});
    const double maximum = std::min({hand.collision / 10.0, 2.0 * hand.viscous, 0.5 * hand.rayleigh});
    EXPECT_NEAR(r.recommended, recommended, recommended * round_off);
    EXPECT_NEAR(r.maximum, maximum, maximum * round_off);
    // At 1 m/s the creep sets the step (tau/25 = 42.9 us < t_c/20 = 64.7 us
    // < 0.7 m*/c = 67.4 us) and the collision time the maximum (t_c/10 =
    // 129 us < 2 m*/c = 192 us).
    EXPECT_NEAR(r.recommended, hand.creep / 25.0, recommended * round_off);
    EXPECT_NEAR(r.maximum, hand.collision / 10.0, maximum * round_off);
    EXPECT_NE(r.recommended_by.find("creep"), std::string::npos) << r.recommended_by;
    EXPECT_NE(r.limiting.find("collision"), std::string::npos) << r.limiting;
}

TEST(TimeStep, AutomaticStepIsTheRecommendedOne) {
    const TimeStepReport r = assess_time_step(material_one(0.0));
    EXPECT_TRUE(r.automatic);
    EXPECT_EQ(r.dt, r.recommended);
    EXPECT_LT(r.dt, r.maximum);
}

TEST(TimeStep, GivenStepAboveTheMaximumIsRefusedNamingTheCriterion) {
    // The Hertz collision time limits material 1 at 1 m/s:
    // t_c / 10 = 129 us < 2 m*/c = 192 us < t_R / 2 = 356 us.
    const double maximum = hand_times().collision / 10.0;
    try {
        assess_time_step(material_one(1.1 * maximum));
        FAIL() << "a step 10 % above t_c/10 was accepted";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("Hertz collision"), std::string::npos) << message;
    }
    // Just below the maximum is fine (1 % is far above round-off).
    EXPECT_NO_THROW(assess_time_step(material_one(0.99 * maximum)));
    // Four times as viscous, the damping limits: m*/c is a quarter of
    // 96.1 us, so 2 m*/c = 48 us < t_c / 10.
    const double viscous_maximum = 2.0 * hand_times().viscous / 4.0;
    Scenario viscous = material_one(1.1 * viscous_maximum);
    viscous.materials[0].xi *= 4.0;
    viscous.materials[0].eta *= 4.0;
    try {
        assess_time_step(viscous);
        FAIL() << "a step 10 % above 2 m*/c was accepted";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("viscous"), std::string::npos) << message;
    }
}

TEST(TimeStep, AllowUnsafeLetsAnOversizedStepThrough) {
    Scenario s = material_one(5.0 * hand_times().viscous);
    s.time_step.allow_unsafe = true;
    TimeStepReport r;
    ASSERT_NO_THROW(r = assess_time_step(s));
    EXPECT_EQ(r.dt, s.time_step.dt);
    EXPECT_FALSE(r.automatic);
    EXPECT_GT(r.dt, r.maximum);
}

TEST(TimeStep, NonPositiveStepIsRefused) {
    EXPECT_THROW(assess_time_step(material_one(-1e-6)), Error);
    Scenario s = material_one(-1e-6);
    s.time_step.allow_unsafe = true;
    EXPECT_THROW(assess_time_step(s), Error);
}

TEST(TimeStep, PaperBenchmarkStepIsAcceptedForMaterialOne) {
    // SPEC-NOTES "Speed": dt = 1e-5 s, below the 129 us maximum.
    TimeStepReport r;
    ASSERT_NO_THROW(r = assess_time_step(material_one(1e-5)));
    EXPECT_EQ(r.dt, 1e-5);
    EXPECT_FALSE(r.automatic);
    // And in the benchmark scenario itself (smaller lattice, same grains).
    const Scenario bench = benchmark_cube(4);
    ASSERT_NO_THROW(r = assess_time_step(bench));
    EXPECT_EQ(r.dt, 1e-5);
}

TEST(TimeStep, SmallestGrainsOfAMaterialSetTheStep) {
    // The Rayleigh time is proportional to R; with a 1.8 mm grain among the
    // 3.6 mm ones it halves.
    Scenario s = material_one(0.0);
    s.particles[5].radius = 1.8e-3;
    const TimeStepReport r = assess_time_step(s);
    EXPECT_NEAR(r.rayleigh_time, 0.5 * hand_times().rayleigh, hand_times().rayleigh * round_off);
    EXPECT_LT(r.recommended, assess_time_step(material_one(0.0)).recommended);
}

}  // namespace
}  // namespace tumble
