// SPDX-License-Identifier: MIT
// Blow-up detection (tumble/sim/health.hpp) and its use by tumble drum: an
// unphysical run stops with a diagnostic and exit code 5.
#include <gtest/gtest.h>

#include <filesystem>
#include <limits>

#include "io/checkpoint.hpp"
#include "test_support.hpp"
#include "tumble/sim/health.hpp"

namespace {

using namespace tumble;

Scenario two_spheres(const Vec3& second_position, const Vec3& second_velocity) {
    Scenario s;
    Material m{"m", 1e6, 0.3e6, 0.25, 500.0, 500.0, 1000.0, 1e-3};
    s.materials = {m};
    s.pair_properties = {{PairProperties{0.1, 0.0}}};
    s.domain.lo = {-0.01, -0.01, -0.01};
    s.domain.hi = {0.01, 0.01, 0.01};
    s.domain.walls = {true, true, true};
    s.particles = {ParticleSpec{{}, {}, {}, 1e-3, 0}, ParticleSpec{second_position, second_velocity, {}, 1e-3, 0}};
    return s;
}

std::string problem_of(const Scenario& s) {
    const Simulation sim(s);
    return health_problem(sim, default_health_limits(s));
}

TEST(Health, APhysicalStateHasNoProblem) { EXPECT_EQ(problem_of(two_spheres({3e-3, 0, 0}, {0.5, 0, 0})), ""); }

TEST(Health, NamesTheParticleThatIsTooFast) {
    // The default limit is 100 x the reference impact speed of 1 m/s.
    const std::string why = problem_of(two_spheres({3e-3, 0, 0}, {150.0, 0, 0}));
    EXPECT_NE(why.find("step 0 (t = 0 s): particle 1 (free) at (0.003, 0, 0) m moves at 150 m/s"), std::string::npos)
        << why;
}

TEST(Health, NamesTheContactThatOverlapsTooMuch) {
    // Centres 0.8 R apart: the overlap is 1.2 R, above the limit of 0.5 R.
    const std::string why = problem_of(two_spheres({0.8e-3, 0, 0}, {}));
    EXPECT_NE(why.find("the contact of particle 0"), std::string::npos) << why;
    EXPECT_NE(why.find("and particle 1 (free)"), std::string::npos) << why;
    EXPECT_NE(why.find("1.2 of the smaller radius"), std::string::npos) << why;
}

TEST(Health, NamesAParticleOutsideTheRegion) {
    // The scenario refuses a sphere beyond its walls, so open the domain and
    // bound the region by hand, as tumble drum does.
    Scenario s = two_spheres({0.0125, 0, 0}, {});
    s.domain.walls = {false, false, false};
    HealthLimits limits = default_health_limits(s);
    limits.bounded = {true, true, true};
    limits.lo = s.domain.lo;
    limits.hi = s.domain.hi;
    const std::string why = health_problem(Simulation(s), limits);
    EXPECT_NE(why.find("particle 1 (free) at (0.0125, 0, 0) m is outside the domain"), std::string::npos) << why;
}

TEST(Health, NamesANonFiniteVelocity) {
    // The scenario refuses NaN, so put it into the running state.
    const Scenario s = two_spheres({3e-3, 0, 0}, {});
    Simulation sim(s);
    SimulationState state = sim.capture();
    state.particles.velocity[1].x = std::numeric_limits<double>::quiet_NaN();
    sim.restore(state);
    const std::string why = health_problem(sim, default_health_limits(s));
    EXPECT_NE(why.find("particle 1 (free) at (0.003, 0, 0) m has a non-finite"), std::string::npos) << why;
}

class BlowUp : public test_support::ScratchTest {};

TEST_F(BlowUp, ATooLargeTimeStepForcedThroughStopsWithADiagnostic) {
    // dt = 5e-4 s, five times the safe maximum of this drum (1.02e-4 s, the
    // viscous time): refused without the override, and with it the grains
    // gain energy at every contact until one flies off.
    // Checkpoints every 6 us of wall time: one at each look during the
    // settling (every 2 steps here) however fast the steps run (at 0.6 ms
    // the first came after the blow-up, near step 60, once the neighbour
    // build got faster).
    const std::string drum = std::string(TUMBLE_BINARY) +
                             " drum -q --mode self --grains 20 --length 0.03 --diameter 0.03 --revolutions 0.2 "
                             "--no-plot --dt 5e-4 --checkpoint-every-minutes 0.0000001 --out " +
                             (dir_ / "run").string();
    const auto refused = test_support::run_command(drum);
    EXPECT_EQ(refused.exit_code, 2);
    EXPECT_NE(refused.output.find("larger than the safe maximum"), std::string::npos) << refused.output;

    const auto r = test_support::run_command(drum + " --allow-unsafe-dt --force");
    EXPECT_EQ(r.exit_code, 5) << r.output;
    EXPECT_NE(r.output.find("the simulation blew up at step"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("particle"), std::string::npos) << r.output;
    const auto kept = io::checkpoint_files(dir_ / "run");
    ASSERT_FALSE(kept.empty()) << "checkpoints are written every few steps here";
    EXPECT_NE(r.output.find("The last good checkpoint is kept: " + kept.back().string()), std::string::npos)
        << r.output;
    EXPECT_NO_THROW(io::load_newest_checkpoint(dir_ / "run"));
}

}  // namespace
