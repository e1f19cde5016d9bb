// SPDX-License-Identifier: MIT
// Spheres poured in while the run goes ([[insert]], sim/scenario.hpp
// Insertion): each batch at its step, clear of every grain and wall there,
// with the next global ids; a region too full for a batch leaves the rest
// to the next; the whole pour is in the weight the floor carries; a run
// stopped between batches resumes from its checkpoint bit for bit; and the
// silo example fills its silo.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/config.hpp"
#include "physics_helpers.hpp"
#include "pour_scenario.hpp"
#include "tumble/sim/simulation.hpp"

namespace physics_test {
namespace {

// Beads of radius 1.5 to 2 mm poured from the top 20 mm, 20 at a time
// every 0.02 s from 0.01 s.
const std::string batches = R"(
[[insert]]
material = "glass"
lo = [-0.02, -0.02, 0.06]
hi = [0.02, 0.02, 0.08]
radius_min = 1.5e-3
radius_max = 2.0e-3
count = 60
batch = 20
every = 0.02
start = 0.01
velocity = [0.0, 0.0, -0.2]
tag = 4
)";

tumble::Scenario scenario_of(const std::string& text) { return tumble::io::parse_run_config(text, "pour.toml", ".").scenario; }

// The largest overlap of sphere i with any other, relative to the smaller radius.
double worst_overlap_of(const tumble::ParticleStore& p, std::size_t i) {
    double worst = 0.0;
    for (std::size_t j = 0; j < p.size(); ++j)
        if (j != i)
            worst = std::max(worst, (p.radius[i] + p.radius[j] - norm(p.position[i] - p.position[j])) /
                                        std::min(p.radius[i], p.radius[j]));
    return worst;
}

// Batch k comes at the start of the step from step first + k period: not
// before (advance up to that step pours nothing), then 20 spheres with the
// next ids, whole inside the region, overlapping none of the grains that
// fell before them (a step moves them 5 um, 0.3 % of a radius: the
// tolerance), of the insertion's tag and velocity.
TEST(Insertion, PoursEachBatchAtItsStepClearOfEveryGrain) {
    tumble::Simulation sim(scenario_of(pour(batches)));
    const tumble::Insertion& q = sim.scenario().insertions.at(0);
    const tumble::InsertionSteps at = tumble::insertion_steps(q, sim.dt());
    EXPECT_EQ(at.first, static_cast<std::int64_t>(std::ceil(0.01 / sim.dt())));
    EXPECT_EQ(at.period, std::llround(0.02 / sim.dt()));
    EXPECT_EQ(sim.particles().size(), 0u);
    for (std::int64_t k = 0; k < 3; ++k) {
        sim.advance(at.first + k * at.period - sim.step_count());
        EXPECT_EQ(sim.particles().size(), static_cast<std::size_t>(20 * k)) << "before batch " << k;
        sim.advance(1);
        ASSERT_EQ(sim.inserted().at(0), 20 * (k + 1)) << "batch " << k;
        const tumble::ParticleStore& p = sim.particles();
        ASSERT_EQ(p.size(), static_cast<std::size_t>(20 * (k + 1)));
        for (std::size_t i = 0; i < p.size(); ++i) {
            EXPECT_EQ(p.id[i] >= 0 && p.id[i] < static_cast<std::int64_t>(p.size()), true);
            if (p.id[i] < 20 * k) continue;  // an earlier batch's
            SCOPED_TRACE("sphere " + std::to_string(p.id[i]));
            EXPECT_LT(worst_overlap_of(p, i), 0.003);
            EXPECT_GE(p.radius[i], 1.5e-3);
            EXPECT_LE(p.radius[i], 2.0e-3);
            EXPECT_EQ(p.tag[i], 4);
            EXPECT_NEAR(p.velocity[i].z, -0.2, 9.81 * sim.dt() + 1e-12);  // one step of gravity since
            for (int a = 0; a < 2; ++a) {
                EXPECT_GE(p.position[i][a] - p.radius[i], -0.02 - 1e-5);
                EXPECT_LE(p.position[i][a] + p.radius[i], 0.02 + 1e-5);
            }
            EXPECT_GE(p.position[i].z - p.radius[i], 0.06 - 1e-5);
        }
        std::vector<std::int64_t> ids = p.id;
        std::sort(ids.begin(), ids.end());
        for (std::size_t n = 0; n < ids.size(); ++n) ASSERT_EQ(ids[n], static_cast<std::int64_t>(n));
    }
    sim.advance(at.period * 3);  // no fourth batch: the count is reached
    EXPECT_EQ(sim.particles().size(), 60u);
    EXPECT_EQ(sim.scenario().particles.size(), 60u);
}

// A region that holds fewer than a batch (4 mm beads in a 12 mm cube: about
// six fit) places what fits; the rest follows with the next batches, as
// the beads before fall out of it, until the count is in. Then the floor
// carries the pour: its mean load over 0.5 s is the beads' weight (the sum
// of m g) and the rate their momentum changed.
TEST(Insertion, AFullRegionLeavesTheRestToTheNextBatchAndTheFloorCarriesThePour) {
    const std::string tight = R"(
[[wall]]
name = "floor"
shape = "plane"
material = "steel"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[insert]]
material = "glass"
lo = [-0.006, -0.006, 0.06]
hi = [0.006, 0.006, 0.072]
count = 20
every = 0.03
)";
    tumble::Simulation sim(scenario_of(pour(tight, "[true, true, false]")));
    sim.advance(1);
    const std::int64_t first = sim.inserted().at(0);
    EXPECT_GT(first, 0);
    EXPECT_LT(first, 20) << "a 12 mm cube holds fewer than 20 beads of 4 mm";
    sim.advance(static_cast<std::int64_t>(std::ceil(0.6 / sim.dt())));
    EXPECT_EQ(sim.inserted().at(0), 20);
    ASSERT_EQ(sim.particles().size(), 20u);
    double weight = 0.0;
    for (double m : sim.particles().mass) weight += m * 9.81;
    // Over 0.5 s the floor's mean load is the weight less what the beads'
    // vertical momentum gained (they still bounce and roll: restitution 0.9
    // and no rolling resistance) and less what the box's side walls take by
    // friction from beads that strike them spinning.
    const auto momentum = [&] {
        double P = 0.0;
        for (std::size_t i = 0; i < sim.particles().size(); ++i) P += sim.particles().mass[i] * sim.particles().velocity[i].z;
        return P;
    };
    const double P0 = momentum();
    double load = 0.0;
    const int samples = 2000, every = 10;
    for (int k = 0; k < samples; ++k) {
        sim.advance(every);
        load += sim.wall_loads().at(0).force.z / samples;
    }
    const double gained = (momentum() - P0) / (samples * every * sim.dt());
    // Newton over the window: floor on beads = weight + dP/dt - side walls'
    // share, which is 0.5 % of the weight here: 1 % is the tolerance.
    EXPECT_NEAR(-load, weight + gained, 0.01 * weight) << "the floor carries the beads (pushed down)";
}

// Stopped between the first and the second batch, written to a checkpoint
// and read back, the run goes on to the third batch and beyond bit for bit
// as the one never stopped.
TEST(Insertion, ARunStoppedBetweenBatchesResumesBitForBit) {
    const tumble::Scenario s = scenario_of(pour(batches));
    tumble::Simulation whole(s);
    const tumble::InsertionSteps at = tumble::insertion_steps(s.insertions.at(0), whole.dt());
    const std::int64_t stop = at.first + at.period / 2, end = at.first + 2 * at.period + 200;
    whole.advance(end);

    tumble::Simulation first(s);
    first.advance(stop);
    const std::string bytes = tumble::io::encode_checkpoint({{}, first.scenario(), first.capture()});
    tumble::io::Checkpoint back = tumble::io::decode_checkpoint(bytes, "pour.tck");
    EXPECT_EQ(back.scenario.particles.size(), 20u);
    EXPECT_EQ(back.state.inserted, std::vector<std::int64_t>{20});
    tumble::Simulation resumed(back.scenario);
    resumed.restore(std::move(back.state));
    resumed.advance(end - stop);

    ASSERT_EQ(resumed.inserted(), whole.inserted());
    const tumble::ParticleStore a = whole.gathered(), b = resumed.gathered();
    ASSERT_EQ(a.size(), 60u);
    ASSERT_EQ(b.size(), a.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        ASSERT_EQ(a.id[i], b.id[i]);
        EXPECT_EQ(a.position[i], b.position[i]) << "sphere " << a.id[i];
        EXPECT_EQ(a.velocity[i], b.velocity[i]) << "sphere " << a.id[i];
    }
}

}  // namespace
}  // namespace physics_test

namespace physics_test {
namespace {

// examples/silo_pour.toml as written: 600 beads poured in six batches
// settle in the silo by its end (0.6 s), and the floor and the silo's wall
// carry their weight (the sum of m g) within 2 %: the last batch landed
// 0.35 s before and the bed has stopped to that.
TEST(Insertion, TheSiloExampleFillsItsSilo) {
    const tumble::io::RunConfig c = tumble::io::load_run_config(std::string(TUMBLE_SOURCE_DIR) + "/examples/silo_pour.toml");
    tumble::Simulation sim(c.scenario);
    sim.advance(static_cast<std::int64_t>(std::llround(c.duration / sim.dt())));
    ASSERT_EQ(sim.particles().size(), 600u);
    double weight = 0.0, highest = -1.0;
    for (std::size_t i = 0; i < 600; ++i) {
        weight += sim.particles().mass[i] * 9.81;
        highest = std::max(highest, sim.particles().position[i].z);
        EXPECT_LT(std::hypot(sim.particles().position[i].x, sim.particles().position[i].y), 0.03) << "in the silo";
    }
    const std::vector<tumble::WallLoad> loads = sim.wall_loads();
    EXPECT_NEAR(-(loads.at(0).force.z + loads.at(1).force.z), weight, 0.02 * weight);
    EXPECT_LT(highest, 0.0) << "the bed lies in the silo's lower half";
}

}  // namespace
}  // namespace physics_test
