// SPDX-License-Identifier: MIT
// The pair loop runs the paper's model (every term on) through the law with
// its switches fixed when compiling (AllTermsOn), which the compiler
// vectorises, and any other model through the same law with run-time
// switches, one contact at a time (sim/pair_loop.hpp). Both must give the
// same numbers bitwise: each contact goes through the same operations, and
// vector square roots, divisions, additions and multiplications round
// exactly as scalar ones. A compiler flag that reassociated or fused them
// (-ffast-math, contraction into FMA) would break this test.
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "physics_helpers.hpp"
#include "tumble/setup/benchmark_cube.hpp"
#include "tumble/sim/pair_loop.hpp"

namespace physics_test {
namespace {

struct LoopResult {
    std::vector<Vec3> force, torque;
    tumble::PairList pairs;
};

// One pass of the pair loop over the state of `sim`, on copies.
template <class Model>
LoopResult run_pair_loop(const tumble::Simulation& sim, const Model& model) {
    const tumble::ParticleStore& p = sim.particles();
    LoopResult r{std::vector<Vec3>(p.size()), std::vector<Vec3>(p.size()), sim.neighbors().pairs()};
    const tumble::PairTable table(sim.scenario().materials, sim.scenario().pair_properties);
    std::vector<tumble::ContactRecord> none;
    tumble::add_contact_forces<false, Model>(p, r.pairs, {0, r.pairs.size()}, sim.neighbors().images(), table, model,
                                      sim.dt(), r.force.data(), r.torque.data(), none);
    return r;
}

// A dense two-material lattice (the benchmark cube, 8^3, every second sphere
// of a stiffer material with its own friction against the first), spinning
// and rattling: every pair in contact, three pair types, histories grown
// over 300 steps and reset where contacts slipped.
tumble::Scenario two_material_cube(tumble::ShearModel shear) {
    tumble::Scenario s = tumble::benchmark_cube(8, 5);
    tumble::Material stiff = s.materials[0];
    stiff.name = "stiff";
    stiff.E *= 2.0;
    s.materials.push_back(stiff);
    tumble::PairProperties same = s.pair_properties[0][0], cross = same;
    cross.mu = 0.3;
    s.pair_properties = {{same, cross}, {cross, same}};
    std::mt19937_64 rng(17);
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
        s.particles[i].material = static_cast<int>(i % 2);
        s.particles[i].angular_velocity = 30.0 * random_vector(rng);
    }
    s.model.shear = shear;
    // Both friction limits go through the vectorised law: the JKR one with
    // the Coulomb reading, the paper's net normal force with the others.
    s.model.friction_normal = shear == tumble::ShearModel::Coulomb ? tumble::FrictionNormal::Jkr
                                                                    : tumble::FrictionNormal::Net;
    return s;
}

template <tumble::ShearModel Shear>
void expect_vector_law_matches_scalar_law() {
    tumble::Simulation sim(two_material_cube(Shear));
    sim.advance(300);
    const tumble::ContactModel& model = sim.scenario().model;
    ASSERT_TRUE(model.all_terms_on());

    // What the pair loop runs for this model (the vectorised law), against
    // the same law with the switches read at run time.
    tumble::AllTermsOn<Shear> fixed;
    fixed.friction_normal = model.friction_normal;
    fixed.slip_velocity_regularisation = model.slip_velocity_regularisation;
    const LoopResult vector = run_pair_loop(sim, fixed);
    const LoopResult scalar = run_pair_loop(sim, model);

    std::size_t with_history = 0;
    for (std::size_t k = 0; k < vector.pairs.size(); ++k) with_history += !vector.pairs.history(k).is_zero();
    std::printf("  [measured] %zu pairs, %zu with history after the pass\n", vector.pairs.size(), with_history);
    // Contacts with history in every lane of every block, so that a wrong
    // lane or a wrong field shows.
    ASSERT_GT(with_history, vector.pairs.size() / 2);

    EXPECT_TRUE(vector.force == scalar.force);
    EXPECT_TRUE(vector.torque == scalar.torque);
    EXPECT_TRUE(vector.pairs.angular_slip == scalar.pairs.angular_slip);
    EXPECT_TRUE(vector.pairs.slip == scalar.pairs.slip);
    EXPECT_TRUE(vector.pairs.viscous_force == scalar.pairs.viscous_force);
    // And the pass did something: forces on every particle of the dense box.
    std::size_t pushed = 0;
    for (const Vec3& f : vector.force) pushed += tumble::norm(f) > 0.0;
    EXPECT_GT(pushed, vector.force.size() / 2);
}

TEST(PairLoop, VectorisedLawIsBitwiseTheScalarLawWithThePaperShear) {
    expect_vector_law_matches_scalar_law<tumble::ShearModel::Paper>();
}

TEST(PairLoop, VectorisedLawIsBitwiseTheScalarLawWithTheCoulombShear) {
    expect_vector_law_matches_scalar_law<tumble::ShearModel::Coulomb>();
}

TEST(PairLoop, VectorisedLawIsBitwiseTheScalarLawWithTheSpringShear) {
    expect_vector_law_matches_scalar_law<tumble::ShearModel::Spring>();
}

}  // namespace
}  // namespace physics_test
