// SPDX-License-Identifier: MIT
// The neighbour list's rebuild check done by the loops that move the
// particles (integrate/velocity_verlet.hpp, DisplacementLimit): kick_drift(),
// kick_kick_drift() and move_kinematic() count the particles they carry
// farther than half the skin from where the list last saw them. The count
// must be the one written out here, particle by particle, and agree with
// VerletList::needs_rebuild(), the check as a pass of its own; each loop counts
// only the particles it moves. The bound on a rigid motion with which
// step() skips the wall's count holds for every kinematic sphere.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tumble/core/constants.hpp"
#include "tumble/core/domain.hpp"
#include "tumble/integrate/velocity_verlet.hpp"
#include "tumble/neighbor/verlet_list.hpp"
#include "tumble/particles/particle_store.hpp"
#include "tumble/particles/rigid_motion.hpp"

namespace tumble {
namespace {

constexpr double skin = 0.4e-3, radius = 1e-3;  // m
constexpr double dt = 1e-4, half_dt = 0.5 * dt;  // s

// 45 spheres on a line along x, 4 mm apart (several vectors of 8 and a
// remainder): every third one kinematic (motion 0), the others free, with
// velocities that carry free sphere i by (0.2 + 0.02 i) of the skin in one
// drift, so that those from i = 16 on go beyond half of it (0.5 skin lies
// between two of them, far from round-off). No force.
ParticleStore line_of_spheres() {
    ParticleStore p;
    p.resize(45);
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double x = 4e-3 * static_cast<double>(i);
        p.id[i] = static_cast<std::int64_t>(i);
        p.radius[i] = radius;
        p.motion[i] = i % 3 == 0 ? 0 : free_motion;
        p.position[i] = p.reference_position[i] = {x, 0.0, 0.0};
        const bool free = p.motion[i] == free_motion;
        p.inv_mass[i] = free ? 1.0 : 0.0;
        p.inv_inertia[i] = free ? 1.0 : 0.0;
        p.mass[i] = 1.0;
        const double moved = (0.2 + 0.02 * static_cast<double>(i)) * skin;
        if (free) p.velocity[i] = {0.0, moved / dt, 0.0};
    }
    return p;
}

// The turn of motion 0 about the z axis through the origin by angle theta:
// the kinematic sphere at x moves by the chord 2 x sin(theta / 2).
MotionNow turned_by(double theta) { return {{}, {}, {}, Rotation({0.0, 0.0, 1.0}, theta), 0.0}; }

// Particle by particle: how many of the kinematic (or free) ones are
// farther than half the skin from where they were.
std::size_t count_beyond(const ParticleStore& p, const std::vector<Vec3>& before, bool kinematic) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (p.is_kinematic(i) == kinematic && norm(p.position[i] - before[i]) > 0.5 * skin) ++n;
    return n;
}

struct Checked {
    ParticleStore p = line_of_spheres();
    VerletList list{Domain{{-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}, {false, false, false}, {false, false, false}},
                    skin, 0};  // never sorts: the indices stay put
    std::vector<Vec3> before;
    Checked() {
        list.rebuild(p);
        before = p.position;
    }
    DisplacementLimit limit() const { return {list.positions_at_build(p.size()), list.rebuild_limit2()}; }
};

TEST(RebuildCheck, TheDriftCountsTheFreeSpheresItCarriesBeyondHalfTheSkin) {
    for (const bool twice : {false, true}) {
        SCOPED_TRACE(twice ? "kick_kick_drift" : "kick_drift");
        Checked c;
        ASSERT_NE(c.limit().at_build, nullptr);
        EXPECT_FALSE(c.list.needs_rebuild(c.p));
        const IndexRange all{0, c.p.size()};
        const std::size_t far = twice ? kick_kick_drift(c.p, {}, half_dt, dt, all, c.limit())
                                      : kick_drift(c.p, {}, half_dt, dt, all, c.limit());
        const std::size_t expected = count_beyond(c.p, c.before, false);
        EXPECT_EQ(far, expected);
        EXPECT_EQ(expected, 20u);  // the free ones of spheres 16 to 44: 20 of the 30
        EXPECT_TRUE(c.list.needs_rebuild(c.p));
        // A part of the store: only its own spheres.
        Checked d;
        EXPECT_EQ(kick_drift(d.p, {}, half_dt, dt, {0, 23}, d.limit()), 5u);  // 16, 17, 19, 20, 22
    }
}

TEST(RebuildCheck, TheWallsMotionCountsTheKinematicSpheresItCarriesBeyondHalfTheSkin) {
    Checked c;
    const IndexRange all{0, c.p.size()};
    // A turn that carries the kinematic spheres beyond 0.5 skin from x =
    // 70 mm on (the chord 2 x sin(theta/2) at theta = 0.5 skin / 70 mm;
    // the spheres are 4 mm apart): 9 of the 15 kinematic ones.
    const double theta = 0.5 * skin / 70e-3;
    const std::size_t far = move_kinematic(c.p, {turned_by(theta)}, all, c.limit());
    EXPECT_EQ(far, count_beyond(c.p, c.before, true));
    EXPECT_EQ(far, 9u);  // 18, 21, ..., 42
    EXPECT_TRUE(c.list.needs_rebuild(c.p));
    // The free spheres are not the wall's to count, nor the kinematic ones
    // the drift's: each loop counts what it moves, so that the two together
    // count every sphere once.
    EXPECT_EQ(kick_drift(c.p, {}, half_dt, dt, all, c.limit()), 20u);
    EXPECT_EQ(move_kinematic(c.p, {turned_by(theta)}, all, c.limit()), 9u);
    // Turned back to where they were: none.
    EXPECT_EQ(move_kinematic(c.p, {turned_by(0.0)}, all, c.limit()), 0u);
}

// rigid_displacement_bound(), which step() takes instead of looking at each
// wall sphere while it lies well below half the skin: no kinematic sphere
// moves farther than it says, and in a turn alone the farthest (at the
// reach) moves that far, to round-off. A turn past pi is bounded by the
// diameter, 2 reach.
TEST(RebuildCheck, TheRigidBoundHoldsForEveryKinematicSphereAndATurnReachesIt) {
    const Vec3 z{0.0, 0.0, 1.0};
    for (const Vec3 v : {Vec3{}, Vec3{3e-3, -4e-3, 0.0}}) {  // m/s: 5 mm in the 1 s of the motion below
        for (const double theta : {1e-7, 1e-3, 0.3, 2.0, 4.0}) {
            Checked c;
            move_kinematic(c.p, {{{}, v, v, Rotation(z, theta), theta}}, {0, c.p.size()});  // 1 s at theta rad/s
            double farthest = 0.0, reach = 0.0;
            for (std::size_t i = 0; i < c.p.size(); ++i) {
                if (!c.p.is_kinematic(i)) continue;
                farthest = std::max(farthest, norm(c.p.position[i] - c.before[i]));
                reach = std::max(reach, distance_from_axis(c.before[i], {}, z));
            }
            const double bound = rigid_displacement_bound(v, theta, 1.0, reach);
            EXPECT_LE(farthest, bound * (1.0 + 1e-14)) << theta;
            if (v == Vec3{} && theta < pi) {
                EXPECT_NEAR(farthest, bound, 1e-14 * reach) << theta;
            }
        }
    }
    EXPECT_DOUBLE_EQ(rigid_displacement_bound({}, 4.0, 1.0, 0.1), 0.2);
    EXPECT_EQ(rigid_displacement_bound({}, 0.0, 1.0, 0.1), 0.0);  // a motion at rest moves nothing
}

TEST(RebuildCheck, WithoutTheListsPositionsNothingIsCounted) {
    Checked c;
    const IndexRange all{0, c.p.size()};
    EXPECT_EQ(kick_drift(c.p, {}, half_dt, dt, all, {}), 0u);
    EXPECT_EQ(move_kinematic(c.p, {turned_by(0.1)}, all), 0u);
    // A list that has not seen a store of this size has no positions for it.
    EXPECT_EQ(c.list.positions_at_build(c.p.size() + 1), nullptr);
}

}  // namespace
}  // namespace tumble
