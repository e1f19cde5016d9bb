// SPDX-License-Identifier: MIT
// One simulation shared among MPI ranks (sim/slabs.hpp) against the same
// simulation on one process. Run under mpirun on 2 and 3 ranks (ctest
// label "mpi"; tests/CMakeLists.txt); on one rank the shared run is the
// one-process run and every comparison is trivially met.
//
// Every rank also runs the scenario alone (Ranks::one) and compares its own
// spheres, by global id, with that run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../physics/physics_helpers.hpp"
#include "../physics/pour_scenario.hpp"
#include "io/checkpoint.hpp"
#include "io/config.hpp"
#include "io/step_times.hpp"
#include "tumble/core/mpi.hpp"
#include "tumble/setup/drum.hpp"

namespace physics_test {
namespace {

using tumble::Ranks;
using tumble::Simulation;

// Largest |a - b| of a field over this rank's own spheres of `shared`
// against the same spheres of the one-process run `alone`, over all ranks.
double largest_difference(const Simulation& shared, const Simulation& alone,
                          std::vector<Vec3> tumble::ParticleStore::*field) {
    const auto& p = shared.particles();
    const auto& q = alone.particles();
    double worst = 0.0;
    for (std::size_t i = 0; i < shared.owned(); ++i)
        worst = std::max(worst, tumble::norm((p.*field)[i] - (q.*field)[index_of(q, p.id[i])]));
    return tumble::mpi::max(worst);
}

// The short drum (physics_helpers.hpp), 6 cm long and 8 cm across: cut
// across the rotation axis (along x, its longest), so grains and wall
// spheres both migrate.

// The tolerance of test_threads.cpp's ShortDrumOneAndTwoThreadsAgreeOverARun
// and its reason: the shared run adds each sphere's contact forces in
// another order than one process does (ghost pairs are computed from the
// other sphere's side, the lists are ordered by slab), a difference in the
// last bit that the collisions amplify (e-folding in about 30 steps) but
// that stays below 1e-12 of the grain radius, the throw speed and speed
// over radius after 200 steps. A contact or history lost at a cut shows at
// 1e-6 of those scales or more.
void expect_agreement(const tumble::Scenario& s, int steps, double R, double speed, const char* what,
                      int threads = 1) {
    Simulation alone(s, 1), shared(s, threads, Ranks::world);
    alone.advance(steps);
    shared.advance(steps);
    const double dx = largest_difference(shared, alone, &tumble::ParticleStore::position);
    const double dv = largest_difference(shared, alone, &tumble::ParticleStore::velocity);
    const double dw = largest_difference(shared, alone, &tumble::ParticleStore::angular_velocity);
    const double dF = largest_difference(shared, alone, &tumble::ParticleStore::force);
    const double dT = largest_difference(shared, alone, &tumble::ParticleStore::torque);
    double F = 0.0, T = 0.0;  // the largest force and torque of the one-process run
    for (std::size_t i = 0; i < alone.particles().size(); ++i) {
        F = std::max(F, tumble::norm(alone.particles().force[i]));
        T = std::max(T, tumble::norm(alone.particles().torque[i]));
    }
    const auto owned = static_cast<std::int64_t>(shared.owned());
    if (tumble::mpi::rank() == 0)
        std::printf("  [measured] %s on %d ranks of %d threads, %d steps: positions differ by %.3g m, velocities by "
                    "%.3g m/s, spins by %.3g rad/s, forces by %.3g of %.3g N, torques by %.3g of %.3g N m\n",
                    what, tumble::mpi::size(), threads, steps, dx, dv, dw, dF, F, dT, T);
    EXPECT_EQ(tumble::mpi::sum(owned), static_cast<std::int64_t>(s.particles.size()));  // each sphere on one rank
    EXPECT_LE(dx, 1e-12 * R);
    EXPECT_LE(dv, 1e-12 * speed);
    EXPECT_LE(dw, 1e-12 * speed / R);
    // Forces and torques (what a checkpoint keeps, and on the wall spheres
    // the grains' load on the drum): the same round-off, through the Hertz
    // law's stiffness. F ~ h^(3/2), so a change dh of the overlap changes a
    // force by 3/2 F dh / h, most at the largest overlap: 1e-12 R in
    // position stays below 1e-8 of the largest force while that overlap
    // is above 1.5e-4 R. A contact missed at a cut, or a rank's or thread's
    // part of a sum left out, shows at one contact's force, 1e-3 of the
    // largest or more.
    EXPECT_LE(dF, 1e-8 * F);
    EXPECT_LE(dT, 1e-8 * T);
    const tumble::Observables a = alone.observe(), b = shared.observe();
    EXPECT_EQ(a.contacts, b.contacts);
    EXPECT_NEAR(b.kinetic_translational, a.kinetic_translational, 1e-12 * a.kinetic_translational);
    EXPECT_GT(a.neighbor_builds, 5);
}

TEST(Slabs, WalledDrumAgreesWithOneProcess) { expect_agreement(short_drum(), 200, R2, 1.0, "short drum"); }

// The short drum's grains in a smooth drum (a turning capped cylinder, no
// wall spheres), and with the mantle in triangles (a mesh wall): the walls'
// contact histories migrate with their grains (one slot per analytic wall
// and grain, four per mesh with the features they follow) and the loads on
// the walls are the sums over the ranks: the same tolerances and reason,
// the loads within 1e-8 of the largest, as the forces.
TEST(Slabs, SmoothDrumAgreesWithOneProcess) {
    for (const bool mesh : {false, true}) {  // the mantle a cylinder, or in triangles (a mesh wall's four slots)
        tumble::Scenario s = short_drum();
        std::erase_if(s.particles, [](const tumble::ParticleSpec& p) { return p.motion != tumble::free_motion; });
        const double R = 0.04, half = 0.03;
        tumble::Wall mantle{.name = "mantle", .shape = tumble::WallShape::cylinder, .point = {0.0, 0.0, -half},
                            .radius = R, .length = 2.0 * half, .material = 2, .motion = 0};
        if (mesh) {
            tumble::DrumGeometry g;
            g.length = 2.0 * half;
            g.diameter = 2.0 * R;
            s.meshes = {tumble::drum_mantle_mesh(g, 2.4e-3)};
            mantle.shape = tumble::WallShape::mesh;
            mantle.mesh = 0;
        }
        tumble::Wall cap{.name = "start", .shape = tumble::WallShape::disc, .point = {0.0, 0.0, -half}, .radius = R,
                         .material = 2, .motion = 0};
        s.walls = {mantle, cap};
        cap.name = "end";
        cap.point.z = half;
        s.walls.push_back(cap);
        const char* what = mesh ? "drum on a mesh mantle" : "smooth drum";
        expect_agreement(s, 200, R2, 1.0, what);
        Simulation alone(s, 1), shared(s, 1, Ranks::world);
        alone.advance(200);
        shared.advance(200);
        const std::vector<tumble::WallLoad> a = alone.wall_loads(), b = shared.wall_loads();
        ASSERT_EQ(a.size(), 3u);
        double F = 0.0;
        for (const tumble::WallLoad& l : a) F = std::max(F, tumble::norm(l.force));
        EXPECT_GT(F, 0.0) << what;  // the grains were thrown at the wall
        for (std::size_t k = 0; k < a.size(); ++k) EXPECT_LE(tumble::norm(a[k].force - b[k].force), 1e-8 * F) << what << k;
    }
}

// Spheres poured in on ranks: every rank places the same batch among the
// spheres all ranks hold near the region, keeps those in its slab, and
// the run goes on as on one process: three batches of 20 into a closed box
// sliced along its height, the first grains through the cuts by the end;
// the same tolerances and reason as above.
TEST(Slabs, APourAgreesWithOneProcess) {
    const std::string text = pour(R"(
[[insert]]
material = "glass"
lo = [-0.02, -0.02, 0.06]
hi = [0.02, 0.02, 0.08]
radius_min = 1.5e-3
radius_max = 2.0e-3
count = 60
batch = 20
every = 0.02
velocity = [0.0, 0.0, -1.0]
)");
    const tumble::Scenario s = tumble::io::parse_run_config(text, "pour.toml", ".").scenario;
    Simulation alone(s, 1), shared(s, 1, Ranks::world);
    const std::int64_t steps = static_cast<std::int64_t>(std::ceil(0.07 / alone.dt()));
    alone.advance(steps);
    shared.advance(steps);
    ASSERT_EQ(alone.inserted(), std::vector<std::int64_t>{60});
    ASSERT_EQ(shared.inserted(), alone.inserted());
    EXPECT_EQ(tumble::mpi::sum(static_cast<std::int64_t>(shared.owned())), 60);  // each sphere on one rank
    const double dx = largest_difference(shared, alone, &tumble::ParticleStore::position);
    const double dv = largest_difference(shared, alone, &tumble::ParticleStore::velocity);
    if (tumble::mpi::rank() == 0)
        std::printf("  [measured] a pour on %d ranks: positions differ by %.3g m, velocities by %.3g m/s\n",
                    tumble::mpi::size(), dx, dv);
    EXPECT_LE(dx, 1e-12 * 2.0e-3);
    EXPECT_LE(dv, 1e-12 * 1.5);
    double lowest = 1.0;
    for (double z : [&] { std::vector<double> zs; for (const Vec3& x : alone.particles().position) zs.push_back(x.z); return zs; }())
        lowest = std::min(lowest, z);
    EXPECT_LT(lowest, 0.01) << "the first batch has fallen to the floor, through the cuts";
}

// Hybrid: threads inside each rank (the chunks of the pair list sum in
// another order again); the same tolerance.
TEST(Slabs, TwoThreadsPerRankAgreeWithOneProcess) {
    expect_agreement(short_drum(), 200, R2, 1.0, "short drum", 2);
}

// The periodic box of test_determinism.cpp (64 spheres of the three
// materials, periodic on every axis, spinning and colliding), cut along z:
// ghosts and migrants cross the period between the first and last slabs.
// The same tolerance and reason as the drum's.
TEST(Slabs, PeriodicBoxAgreesWithOneProcess) { expect_agreement(shaken_box(), 300, R2, 0.5, "periodic box"); }

// Shared runs are deterministic: twice the same on the same ranks, bit for
// bit; and a state captured on the ranks and restored into a new shared
// simulation goes on bit for bit as the uninterrupted run (checkpoints).
TEST(Slabs, CaptureAndRestoreContinueBitwise) {
    const tumble::Scenario s = short_drum();
    Simulation whole(s, 1, Ranks::world), first(s, 1, Ranks::world);
    whole.advance(300);
    first.advance(150);
    Simulation resumed(s, 1, Ranks::world);
    resumed.restore(first.capture());
    resumed.advance(150);
    const auto& p = whole.particles();
    const auto& q = resumed.particles();
    EXPECT_EQ(whole.owned(), resumed.owned());
    EXPECT_TRUE(p.id == q.id);
    EXPECT_TRUE(p.position == q.position);
    EXPECT_TRUE(p.velocity == q.velocity);
    EXPECT_TRUE(p.angular_velocity == q.angular_velocity);
    EXPECT_TRUE(whole.neighbors().pairs().slip == resumed.neighbors().pairs().slip);
}

// The states of the ranks make the whole state (whole_state(): a run of N
// ranks continued on another number): gathered on rank 0 through the
// checkpoint encoding, merged, restored into one process and run on, it
// stays with the shared run as one process does (the tolerance of
// expect_agreement, and its reason: only the order of the force sums
// differs); a sphere or a contact history lost in the merge shows at 1e-6.
TEST(Slabs, StatesOfTheRanksMakeTheWholeState) {
    const tumble::Scenario s = short_drum();
    Simulation shared(s, 1, Ranks::world);
    shared.advance(150);
    const std::string mine = tumble::io::encode_checkpoint({{}, s, shared.capture()});
    const auto parts = tumble::mpi::gather(tumble::mpi::Bytes(mine.begin(), mine.end()));
    shared.advance(50);
    const tumble::ParticleStore expected = shared.gathered();
    if (tumble::mpi::rank() != 0) return;
    std::vector<tumble::SimulationState> states;
    for (const auto& part : parts)
        states.push_back(tumble::io::decode_checkpoint(std::string_view(part.data(), part.size()), "rank").state);
    Simulation alone(s, 1);
    alone.restore(tumble::whole_state(states));
    EXPECT_EQ(alone.step_count(), 150);
    alone.advance(50);
    const auto& p = alone.particles();
    double dx = 0.0, dw = 0.0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const std::size_t j = index_of(expected, p.id[i]);
        dx = std::max(dx, tumble::norm(p.position[i] - expected.position[j]));
        dw = std::max(dw, tumble::norm(p.angular_velocity[i] - expected.angular_velocity[j]));
    }
    std::printf("  [measured] %d ranks merged into one process after 150 steps, 50 more: positions differ by %.3g m, "
                "spins by %.3g rad/s\n",
                tumble::mpi::size(), dx, dw);
    EXPECT_EQ(p.size(), s.particles.size());
    EXPECT_LE(dx, 1e-12 * R2);
    EXPECT_LE(dw, 1e-12 * 1.0 / R2);
}

// The cuts follow the work (Slabs::rebalance): 240 grains spread through a
// walled column 12 cm tall fall to its floor under gravity, so the slabs
// cut at the start (z quantiles of the spread grains) end with every
// grain in the lowest one unless the cuts move. After 0.2 s (5,000 steps of
// 4e-5 s, hundreds of rebuilds with a small skin: a rebalance every 50) each rank
// holds its share of the grains to within 20 % (the cut moves to the
// quantile of a 1,024-bin histogram and by at most half a slab per
// rebalance; bins of 0.2 mm against grains of 4.8 to 7.2 mm); and a run
// captured and restored half way goes on bit for bit (the cuts are in the
// state).
TEST(Slabs, CutsFollowTheGrains) {
    tumble::Scenario s = open_scenario(4e-5);
    s.domain.lo = {-0.02, -0.02, 0.0};
    s.domain.hi = {0.02, 0.02, 0.12};
    s.domain.walls = {true, true, true};
    s.gravity = {0.0, 0.0, -9.81};
    s.neighbor.skin = 0.1 * R1;
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> jitter(-0.5e-3, 0.5e-3);
    for (int k = 0; k < 240; ++k) {  // a 4 x 4 grid of columns, 15 layers 7.5 mm apart
        const int m = k % 2;
        const Vec3 x{-0.012 + 0.008 * (k % 4) + jitter(rng), -0.012 + 0.008 * ((k / 4) % 4) + jitter(rng),
                     0.008 + 0.0075 * (k / 16) + jitter(rng)};
        s.particles.push_back(sphere(x, s.materials[static_cast<std::size_t>(m)].radius, m));
    }
    const int steps = 5000;
    Simulation whole(s, 1, Ranks::world), first(s, 1, Ranks::world);
    whole.advance(steps);
    first.advance(steps / 2);
    Simulation resumed(s, 1, Ranks::world);
    resumed.restore(first.capture());
    resumed.advance(steps / 2);
    EXPECT_TRUE(whole.particles().id == resumed.particles().id);
    EXPECT_TRUE(whole.particles().position == resumed.particles().position);
    EXPECT_TRUE(whole.slabs() == nullptr || whole.slabs()->cuts() == resumed.slabs()->cuts());
    const double mine = static_cast<double>(whole.owned());
    const double mean = 240.0 / tumble::mpi::size();
    if (tumble::mpi::rank() == 0 && whole.slabs())
        std::printf("  [measured] %d ranks: cuts after 0.2 s at %s\n", tumble::mpi::size(), [&] {
            std::string cuts;
            for (double c : whole.slabs()->cuts()) cuts += " " + std::to_string(c);
            return cuts;
        }().c_str());
    EXPECT_EQ(tumble::mpi::sum(static_cast<std::int64_t>(whole.owned())), 240);
    EXPECT_LE(tumble::mpi::max(std::abs(mine - mean)), 0.2 * mean) << "rank " << tumble::mpi::rank() << " holds " << mine;
    double highest = 0.0;
    for (std::size_t i = 0; i < whole.owned(); ++i) highest = std::max(highest, whole.particles().position[i].z);
    EXPECT_LT(tumble::mpi::max(highest), 0.05);  // the grains did fall
}

// The cuts follow the pairs as well as the grains: a column of 128 grains
// at rest on a square lattice 2 x 2 x 32 (spacing 2 R + skin / 2, so each
// has its nearest neighbours in the list: 252 pairs) under 128 grains of a
// gas above it (moving at 0.3 m/s in a box 40 mm wide, so the list is
// rebuilt every 15 steps or so and the cuts are looked at every 50
// rebuilds), no gravity. The start's cuts split the grains equally, at the
// gap between lattice and gas. A sphere's work is a grain's 1 plus 0.85
// per pair (Slabs::rebalance): the lattice weighs 342, the gas about 128,
// so after 4,000 steps the cuts lie inside the lattice and the ranks hold
// unequal grains (the top rank at least 1.2 times the mean) but equal
// work, grains + 0.85 pairs, within 10 % of the mean (a lattice layer,
// 10.8, is 5 % of a rank's share on 2 ranks). Cuts that counted grains
// only would leave the work 2.7 to 1 on 2 ranks.
TEST(Slabs, CutsFollowThePairs) {
    tumble::Scenario s = open_scenario(4e-5);
    s.domain.lo = {-0.02, -0.02, 0.0};
    s.domain.hi = {0.02, 0.02, 0.6};
    s.domain.walls = {true, true, true};
    s.neighbor.skin = 0.1 * R1;
    const double spacing = 2.0 * R1 + 0.5 * s.neighbor.skin;
    for (int k = 0; k < 128; ++k)
        s.particles.push_back(
            sphere({spacing * (k % 2 - 0.5), spacing * ((k / 2) % 2 - 0.5), 0.01 + spacing * (k / 4)}, R1, 0));
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> speed(-0.3, 0.3);
    for (int k = 0; k < 128; ++k) {  // a 4 x 4 x 8 grid, 10 mm by 10 mm by 35 mm
        tumble::ParticleSpec gas = sphere({-0.015 + 0.01 * (k % 4), -0.015 + 0.01 * ((k / 4) % 4), 0.3 + 0.035 * (k / 16)}, R1, 0);
        gas.velocity = {speed(rng), speed(rng), speed(rng)};
        s.particles.push_back(gas);
    }
    Simulation shared(s, 1, Ranks::world);
    shared.advance(4000);
    const double grains = static_cast<double>(shared.owned());
    const double work = grains + 0.85 * static_cast<double>(shared.neighbors().pairs().size());
    const double ranks = tumble::mpi::size();
    const double mean_work = tumble::mpi::sum(work) / ranks, mean_grains = 256.0 / ranks;
    std::printf("  [measured] rank %d: %g grains, work %g (mean %g)\n", tumble::mpi::rank(), grains, work, mean_work);
    EXPECT_EQ(tumble::mpi::sum(static_cast<std::int64_t>(shared.owned())), 256);
    EXPECT_LE(tumble::mpi::max(std::abs(work - mean_work)), 0.1 * mean_work) << "rank " << tumble::mpi::rank();
    if (ranks > 1) {
        EXPECT_GE(tumble::mpi::max(grains), 1.2 * mean_grains);
    }
}

// A grain sliding on a flat floor across the cut between two ranks keeps
// its wall contact's history: its friction force, step by step, is the
// one-process run's. Two grains 20 cm apart in x slide towards each other's
// side along z at 0.5 m/s, 3 mm from the cut (at z = 0, the median of the
// two), crossing it after 6 ms, while friction turns their sliding into
// rolling; nothing else touches them, so the forces are the same bit for bit.
TEST(Slabs, SlidingGrainKeepsItsFrictionAcrossTheCut) {
    if (tumble::mpi::size() != 2) GTEST_SKIP() << "two ranks only (the cut lies between the two grains)";
    tumble::Scenario s = open_scenario(1e-5);
    s.domain.walls = {false, true, false};
    s.gravity = {0.0, -9.81, 0.0};
    const double floor = s.domain.lo.y + R1 - 1e-6;  // resting on it, slightly pressed
    s.particles.push_back(sphere({-0.1, floor, -0.003}, R1, 0, {0.0, 0.0, 0.5}));
    s.particles.push_back(sphere({0.1, floor, 0.003}, R1, 0, {0.0, 0.0, -0.5}));
    Simulation alone(s, 1), shared(s, 1, Ranks::world);
    alone.set_contact_recording(true);
    shared.set_contact_recording(true);
    int compared = 0, owners_of_grain_0 = 0;
    bool owned_at_start = false, owned_at_end = false;
    for (int step = 0; step < 1500; ++step) {
        alone.step();
        shared.step();
        for (const tumble::ContactRecord& r : shared.contact_records())
            for (const tumble::ContactRecord& q : alone.contact_records())
                if (q.id_i == r.id_i && q.id_j == r.id_j) {
                    ++compared;
                    EXPECT_EQ(r.forces.force_i, q.forces.force_i) << "step " << step;
                    EXPECT_EQ(r.history.slip, q.history.slip) << "step " << step;
                }
        const bool mine = shared.owned() > 0 && std::find(shared.particles().id.begin(),
                                                          shared.particles().id.begin() + static_cast<std::ptrdiff_t>(shared.owned()),
                                                          0) != shared.particles().id.begin() + static_cast<std::ptrdiff_t>(shared.owned());
        if (step == 0) owned_at_start = mine;
        if (step == 1499) owned_at_end = mine;
        owners_of_grain_0 += mine;
    }
    // Each step both grains touch the floor, on the rank that owns them.
    EXPECT_EQ(tumble::mpi::sum(static_cast<std::int64_t>(compared)), 2 * 1500);
    EXPECT_EQ(tumble::mpi::sum(static_cast<std::int64_t>(owners_of_grain_0)), 1500);
    // Grain 0 starts below the cut (rank 0) and ends above it (rank 1).
    EXPECT_EQ(owned_at_start, tumble::mpi::rank() == 0);
    EXPECT_EQ(owned_at_end, tumble::mpi::rank() == 1);
    const auto& p = alone.particles();
    const std::size_t g = index_of(p, 0);
    EXPECT_GT(p.position[g].z, 0.003);  // it did cross
    EXPECT_GT(std::abs(p.angular_velocity[g].x), 1.0);  // friction set it spinning
}

// The time by phase of a shared run: on several ranks the exchange of the
// ghosts has taken time, and the spread over the ranks is in order.
TEST(Slabs, StepTimesTellTheExchangeAndTheRanksSpread) {
    Simulation shared(short_drum(), 1, Ranks::world);
    shared.advance(100);
    const tumble::StepTimes& t = shared.step_times();
    EXPECT_EQ(t.steps, 100);
    const double exchange = t.seconds[static_cast<std::size_t>(tumble::StepPhase::exchange)];
    if (tumble::mpi::size() > 1)
        EXPECT_GT(exchange, 0.0);
    else
        EXPECT_EQ(exchange, 0.0);
    const tumble::io::StepTimesSpread s = tumble::io::step_times_spread(t, 1.0, 1, shared.shared());
    EXPECT_EQ(s.ranks, tumble::mpi::size());
    for (const tumble::io::PhaseSpread& phase : s.phases) {
        EXPECT_LE(phase.least, phase.mean);
        EXPECT_LE(phase.mean, phase.most);
    }
}

}  // namespace
}  // namespace physics_test

// MPI for the whole suite (started only under a launcher).
int main(int argc, char** argv) {
    tumble::mpi::Session session(argc, argv);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
