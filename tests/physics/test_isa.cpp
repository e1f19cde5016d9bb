// SPDX-License-Identifier: MIT
// The portable binary (tumble/core/isa.hpp): the hot loops compiled for each
// instruction set (and each vector width) give the same state, byte for
// byte, as the baseline x86-64 code. Each level the processor lacks is skipped, with the reason; in a
// build for one processor (TUMBLE_ARCH=native), a non-GCC or a non-x86
// build there is no level but the baseline and every case is skipped.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>

#include "drum_helpers.hpp"
#include "io/checkpoint.hpp"
#include "physics_helpers.hpp"
#include "tumble/core/isa.hpp"

namespace physics_test {
namespace {

using tumble::Isa;

// The checkpoint bytes (particles, neighbour list with every contact's
// history, wall history, time) of a simulation.
std::string state_bytes(const tumble::Simulation& sim) {
    return tumble::io::encode_checkpoint({{}, sim.scenario(), sim.capture()});
}

// The state bytes after `steps` steps of `scenario` on `threads` threads
// with the hot loops on `level`.
std::string run_on(Isa level, const tumble::Scenario& scenario, long steps, int threads) {
    tumble::use_isa(level);
    tumble::Simulation sim(scenario, threads);
    sim.advance(steps);
    return state_bytes(sim);
}

class PortableBinary : public testing::TestWithParam<Isa> {
protected:
    void SetUp() override {
        const std::vector<Isa> available = tumble::available_isas();
        if (std::find(available.begin(), available.end(), GetParam()) == available.end())
            GTEST_SKIP() << "this processor (or build: " << tumble::isa_description() << ") has no "
                         << tumble::isa_name(GetParam()) << " code to run";
    }
    void TearDown() override {
        tumble::use_isa(tumble::default_isa(tumble::available_isas(), tumble::processor_has_full_width_512()));
    }
};

// 64 grains of the three materials, every term of the model on, colliding
// in a periodic box (list rebuilds and re-sorts included), with each shear
// model (each has its own vectorised law), on two threads (so that the
// threads' forces are added up too).
TEST_P(PortableBinary, ShakenBoxStateIsTheBaselineBytes) {
    for (const tumble::ShearModel shear :
         {tumble::ShearModel::Paper, tumble::ShearModel::Coulomb, tumble::ShearModel::Spring}) {
        tumble::Scenario s = shaken_box();
        s.model.shear = shear;
        ASSERT_TRUE(s.model.all_terms_on());
        const long steps = 400;
        const std::string baseline = run_on(Isa::baseline, s, steps, 2);
        EXPECT_TRUE(run_on(GetParam(), s, steps, 2) == baseline)
            << tumble::isa_name(GetParam()) << " differs from baseline, shear model "
            << tumble::keyword_of(tumble::shear_models, shear);
    }
}

// A turning drum: 300 grains thrown at 0.5 m/s in random directions, among
// themselves and onto a wall of kinematic spheres turning at 5 rad/s (the
// kicks' and the drift's choices between free and prescribed motion).
TEST_P(PortableBinary, TurningDrumStateIsTheBaselineBytes) {
    tumble::DrumSetup setup = tumble::build_drum_scenario(tumble::DrumGeometry{}, "two-component", 300, 5);
    setup.scenario.motions[0].angular_velocity = 5.0;
    std::mt19937_64 rng(17);
    for (tumble::ParticleSpec& p : setup.scenario.particles)
        if (p.motion == tumble::free_motion) p.velocity = 0.5 * random_vector(rng);
    const long steps = 1500;
    tumble::use_isa(Isa::baseline);
    tumble::Simulation baseline(setup.scenario, 1);
    baseline.advance(steps);
    std::printf("  [measured] %zu contacts at the end\n", baseline.observe().contacts);
    EXPECT_GT(baseline.observe().contacts, 50u);
    EXPECT_TRUE(run_on(GetParam(), setup.scenario, steps, 1) == state_bytes(baseline))
        << tumble::isa_name(GetParam()) << " differs from baseline";
}

INSTANTIATE_TEST_SUITE_P(Levels, PortableBinary, testing::Values(Isa::avx2, Isa::avx512, Isa::avx512_wide),
                         [](const testing::TestParamInfo<Isa>& level) {
                             std::string name(tumble::isa_name(level.param));
                             std::replace(name.begin(), name.end(), '-', '_');  // a test name has no '-'
                             return name;
                         });

// The default level: the widest the processor runs, but 512-bit vectors
// only where they run at full rate (on an Intel Xeon they were 9 % slower
// than 256-bit ones, on an AMD Zen 5 9 to 15 % faster).
TEST(DefaultLevel, WideVectorsOnlyWhereTheyRunAtFullRate) {
    const std::vector<Isa> all = {Isa::baseline, Isa::avx2, Isa::avx512, Isa::avx512_wide};
    EXPECT_EQ(tumble::default_isa(all, true), Isa::avx512_wide);
    EXPECT_EQ(tumble::default_isa(all, false), Isa::avx512);
    EXPECT_EQ(tumble::default_isa({Isa::baseline, Isa::avx2}, true), Isa::avx2);
    EXPECT_EQ(tumble::default_isa({Isa::baseline}, false), Isa::baseline);
}

}  // namespace
}  // namespace physics_test
