// SPDX-License-Identifier: MIT
// Drum options: the periodic axis (no end caps; the drum's
// length is the period) and the spin-up ramp; the neighbour skin; the
// surface energy.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "experiments/drum_setup.hpp"
#include "io/drum_config.hpp"
#include "tumble/analysis/pair_collision.hpp"
#include "tumble/core/error.hpp"
#include "tumble/setup/drum.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble {
namespace {

DrumGeometry periodic_geometry() {
    DrumGeometry g;
    g.periodic_axis = true;
    return g;
}

// No caps; an even number of staggered rings whose spacing across the
// period's ends equals the step inside (so the wall repeats seamlessly);
// no gap a grain could pass (build_drum_wall would throw).
TEST(PeriodicDrum, WallHasNoCapsAndRepeatsAcrossThePeriod) {
    const DrumGeometry g = periodic_geometry();
    const DrumWall w = build_drum_wall(g, 2, 0, 2.4e-3);
    EXPECT_EQ(w.cap_particles, 0u);
    EXPECT_EQ(w.mantle_rings % 2, 0u);
    double lo = INFINITY, hi = -INFINITY;
    for (const ParticleSpec& p : w.particles) {
        lo = std::min(lo, p.position.z);
        hi = std::max(hi, p.position.z);
        EXPECT_NEAR(std::hypot(p.position.x, p.position.y), w.inner_radius + g.wall_radius, 1e-12);
    }
    EXPECT_NEAR(hi - lo + w.axial_step, g.length, 1e-12);  // the gap across the ends is one step
    EXPECT_LE(w.axial_step, 2.0 * g.wall_radius + 1e-12);
    EXPECT_LT(w.largest_gap, 2.4e-3);
}

// A grain thrown toward +z leaves the period at z = +L/2 and comes back at
// -L/2; every grain stays in the drum (radially) and none is lost. 40 grains
// of the self mode, 0.04 s: the thrown grain (0.8 m/s, from the right end)
// travels about 3 cm before the wall's friction stops it.
TEST(PeriodicDrum, AGrainLeavingAtOneEndEntersAtTheOther) {
    DrumSetup setup = build_drum_scenario(periodic_geometry(), "self", 40, 7);
    ASSERT_TRUE(setup.scenario.domain.periodic[2]);
    const double half = 0.5 * setup.wall.inner_length;
    std::size_t thrown = 0;
    for (std::size_t i = 0; i < setup.scenario.particles.size(); ++i)
        if (setup.scenario.particles[i].motion < 0 &&
            setup.scenario.particles[i].position.z > setup.scenario.particles[thrown].position.z)
            thrown = i;
    const double z0 = setup.scenario.particles[thrown].position.z;
    ASSERT_GT(z0, half - 0.02);
    setup.scenario.particles[thrown].velocity = {0.0, 0.0, 0.8};
    Simulation sim(setup.scenario);
    sim.advance(std::llround(0.04 / sim.dt()));
    const ParticleStore& p = sim.particles();
    EXPECT_EQ(p.free_count(), 40u);
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.is_kinematic(i)) continue;
        EXPECT_LT(std::hypot(p.position[i].x, p.position[i].y), setup.wall.inner_radius) << "grain " << p.id[i];
        // Wrapped at neighbour-list rebuilds: at most half a skin outside.
        EXPECT_LT(std::abs(p.position[i].z), half + 0.01) << "grain " << p.id[i];
        if (p.id[i] == static_cast<std::int64_t>(thrown)) {
            EXPECT_LT(p.position[i].z, 0.0) << "the thrown grain should have re-entered at -L/2";
            EXPECT_GT(p.position[i].z, -half);
        }
    }
}

// The ramp: omega t / T during the spin-up, omega from t = T on.
TEST(SpinUp, RampReachesFullSpeedAtTheStatedTime) {
    const double omega = 12.0, T = 0.5;
    EXPECT_EQ(drum_angular_velocity(omega, T, 0.0), 0.0);
    EXPECT_DOUBLE_EQ(drum_angular_velocity(omega, T, 0.25), 6.0);
    EXPECT_DOUBLE_EQ(drum_angular_velocity(omega, T, 0.5), omega);
    EXPECT_DOUBLE_EQ(drum_angular_velocity(omega, T, 3.0), omega);
    EXPECT_DOUBLE_EQ(drum_angular_velocity(omega, 0.0, 0.0), omega);  // no ramp: full speed at once
}

// Driven as tumble drum drives it (spin_up_setting before each step): the
// wall turns at omega after T, and the angle turned is that of the linear
// ramp, omega (t - T/2), to the accuracy of the last step.
TEST(SpinUp, WallTurnsAtFullSpeedAfterTheRampWithTheRampsAngle) {
    DrumSetup setup = build_drum_scenario(DrumGeometry{}, "self", 20, 3);
    Simulation sim(setup.scenario);
    const double omega = 5.0, T = 0.02;
    const std::int64_t steps = std::llround(1.5 * T / sim.dt());
    std::size_t wall = 0;
    while (!sim.particles().is_kinematic(wall)) ++wall;
    const std::int64_t id = sim.particles().id[wall];
    auto wall_position = [&] {
        const ParticleStore& p = sim.particles();
        for (std::size_t i = 0; i < p.size(); ++i)
            if (p.id[i] == id) return std::pair{p.position[i], p.velocity[i]};
        return std::pair{Vec3{}, Vec3{}};
    };
    const Vec3 start = wall_position().first;
    for (std::int64_t k = 1; k <= steps; ++k) {
        if (const double w = spin_up_setting(omega, T, sim.dt(), k); w >= 0.0)
            sim.set_motion(0, RigidMotion{{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, w, {0.0, 0.0, 0.0}});
        sim.step();
    }
    const auto [x, v] = wall_position();
    const double rho = std::hypot(x.x, x.y);
    EXPECT_NEAR(std::hypot(v.x, v.y), omega * rho, 1e-9 * omega * rho);
    const double turned = std::atan2(x.y, x.x) - std::atan2(start.y, start.x);
    const double t = static_cast<double>(steps) * sim.dt();
    EXPECT_NEAR(turned, omega * (t - 0.5 * T), omega * sim.dt());
}

// The drum's neighbour skin (tumble drum --skin, [neighbor] skin) sets which
// pairs are listed and how often the list is rebuilt, never a force: the
// bed falling into the turning drum with twice the drum's automatic skin
// (0.3 x the largest radius, 1.08 mm; not the 0.2 x of other scenarios)
// follows the automatic run to round-off (the sums over a sphere's
// contacts come in another order), with fewer builds.
TEST(NeighbourSkin, ChangesTheRebuildsNotTheMotion) {
    struct Outcome {
        std::vector<Vec3> position;  // by global id
        std::int64_t builds;
        double skin;
    };
    auto run = [](double skin) {
        io::DrumSettings s;
        s.grains = 400;
        s.skin = skin;
        io::check_drum_settings(s, "test");
        DrumSetup setup = experiments::build_drum(s);
        Simulation sim(setup.scenario);
        sim.set_motion(0, experiments::drum_rotation(5.0));
        sim.advance(1200);  // 0.048 s: the grains fall and meet the wall and each other
        const ParticleStore& p = sim.particles();
        Outcome out{std::vector<Vec3>(p.size()), sim.neighbors().builds(), sim.neighbors().skin()};
        for (std::size_t i = 0; i < p.size(); ++i) out.position[static_cast<std::size_t>(p.id[i])] = p.position[i];
        return out;
    };
    const Outcome automatic = run(0.0), wide = run(2.16e-3);
    EXPECT_DOUBLE_EQ(automatic.skin, 0.3 * 3.6e-3);  // the large grain's radius
    EXPECT_DOUBLE_EQ(wide.skin, 2.16e-3);
    {  // A drum checkpointed before the drum had its own skin holds skin 0
       // (automatic): it goes on at the engine's 0.2 x, as its list was built.
        io::DrumSettings s;
        s.grains = 400;
        DrumSetup old = experiments::build_drum(s);
        old.scenario.neighbor.skin = 0.0;
        EXPECT_DOUBLE_EQ(Simulation(old.scenario).neighbors().skin(), 0.2 * 3.6e-3);
    }
    // Half the skin moved before a build falls due, twice as far: at most
    // two thirds of the builds (about half, where the fastest grain keeps
    // its speed).
    EXPECT_LT(3 * wide.builds, 2 * automatic.builds) << wide.builds << " against " << automatic.builds;
    double largest = 0.0;
    for (std::size_t i = 0; i < automatic.position.size(); ++i)
        largest = std::max(largest, norm(wide.position[i] - automatic.position[i]));
    // The runs are bitwise equal for the first 800 steps; then the sums'
    // order gives 1e-18 m, which the collisions amplify tenfold every 100
    // steps (7e-16 m at step 1200, 1e-9 m by step 1550, the grains' size by
    // step 3000). So the comparison is made at step 1200, with 1e-12 m: a
    // contact missed for one step would put its grains some 1e-8 m off.
    EXPECT_LT(largest, 1e-12) << "largest difference " << largest << " m";
}

// --surface-energy W sets W of every pair, the caps' included. W = 0 is the
// law without its attraction: the term is exactly zero, so a collision of
// two small grains at the automatic step runs to the same restitution and
// contact time as the scalar law with the attraction switched off
// (ContactModel::attraction = false) on the paper's coefficients, to the
// bit. With the paper's W = 0.2 J/m^2 the same grains stick at 0.1 m/s
// (pull-off 1.5 mN, 2.6 weights of a small grain; docs/DRUM.md).
TEST(SurfaceEnergy, ZeroIsTheLawWithoutItsAttraction) {
    io::DrumSettings s;
    s.grains = 60;
    s.fill.cap_friction = 0.5;  // a cap material too
    const Scenario paper = experiments::build_drum(s).scenario;
    s.surface_energy = 0.0;
    const Scenario cohesionless = experiments::build_drum(s).scenario;
    ASSERT_EQ(cohesionless.pair_properties.size(), 4u);  // grains 1 and 2, wall, caps
    for (std::size_t a = 0; a < 4; ++a)
        for (std::size_t b = 0; b < 4; ++b) {
            EXPECT_EQ(paper.pair_properties[a][b].W, 0.2);
            EXPECT_EQ(cohesionless.pair_properties[a][b].W, 0.0);
            EXPECT_EQ(cohesionless.pair_properties[a][b].mu, paper.pair_properties[a][b].mu);
        }
    const auto small_pair = [](const Scenario& scenario) {
        for (const ContactPair& pair : contact_pairs(scenario))
            if (pair.name == "material-2-material-2") return pair;
        throw Error("no material-2-material-2 pair");
    };
    const ContactPair zero = small_pair(cohesionless), with = small_pair(paper);
    EXPECT_EQ(zero.coefficients.attraction, 0.0);
    EXPECT_EQ(zero.coefficients.pull_off, 0.0);
    const double dt = assess_time_step(paper).dt;  // the automatic step, the same for both
    EXPECT_EQ(assess_time_step(cohesionless).dt, dt);
    ContactModel no_attraction;
    no_attraction.attraction = false;
    const analysis::Collision a = analysis::engine_collision(cohesionless, zero, ContactModel{}, 0.1, dt);
    const analysis::Collision b = analysis::engine_collision(paper, with, no_attraction, 0.1, dt);
    ASSERT_TRUE(a.separated && b.separated);
    EXPECT_EQ(a.restitution, b.restitution);
    EXPECT_EQ(a.contact_time, b.contact_time);
    EXPECT_GT(a.restitution, 0.005);  // 0.0066 at this speed (tumble contact --drum --surface-energy 0)
    EXPECT_FALSE(analysis::engine_collision(paper, with, ContactModel{}, 0.1, dt).separated);  // sticks
}

}  // namespace
}  // namespace tumble
