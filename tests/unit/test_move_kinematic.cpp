// SPDX-License-Identifier: MIT
// The prescribed motion of kinematic spheres (integrate/velocity_verlet.cpp,
// move_kinematic) against the rigid motion written out here: a turn about a
// tilted axis through a moving point, x = P(t) + R(theta) (X0 - P0) + shift,
// v = V + omega u x arm, spin omega u, F = T = 0. Two ways through the code:
// a range where every sphere has the one motion (the drum's wall: the loop
// on several spheres per instruction) and a range mixing free spheres and
// two motions (each sphere its own motion, the free ones untouched).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "tumble/integrate/velocity_verlet.hpp"
#include "tumble/particles/particle_store.hpp"
#include "tumble/particles/rigid_motion.hpp"

namespace tumble {
namespace {

// A motion at time t: angular velocity w about unit axis u through a point
// that starts at P0 and moves with velocity V.
MotionNow motion_at(const Vec3& P0, const Vec3& V, const Vec3& u, double w, double t) {
    return {P0, P0 + t * V, V, Rotation(u, w * t), w};
}

// The rotation of a about unit axis u by angle theta, as a matrix would do
// it (independent of rotate(): the matrix of the turn, row by row).
Vec3 turned(const Vec3& a, const Vec3& u, double theta) {
    const double c = std::cos(theta), s = std::sin(theta), k = 1.0 - c;
    return {(c + u.x * u.x * k) * a.x + (u.x * u.y * k - u.z * s) * a.y + (u.x * u.z * k + u.y * s) * a.z,
            (u.y * u.x * k + u.z * s) * a.x + (c + u.y * u.y * k) * a.y + (u.y * u.z * k - u.x * s) * a.z,
            (u.z * u.x * k - u.y * s) * a.x + (u.z * u.y * k + u.x * s) * a.y + (c + u.z * u.z * k) * a.z};
}

ParticleStore spheres(const std::vector<std::int32_t>& motions) {
    ParticleStore p;
    p.resize(motions.size());
    for (std::size_t i = 0; i < motions.size(); ++i) {
        const double a = 0.37 * static_cast<double>(i);
        p.motion[i] = motions[i];
        p.reference_position[i] = {0.04 * std::cos(a), 0.05 * std::sin(a), 0.01 * static_cast<double>(i)};
        p.image_shift[i] = {0.0, 0.0, i % 3 == 0 ? 0.2 : 0.0};
        p.position[i] = {1.0, 2.0, 3.0};  // what a free sphere keeps
        p.velocity[i] = {4.0, 5.0, 6.0};
        p.angular_velocity[i] = {7.0, 8.0, 9.0};
        p.force[i] = {0.5, 0.25, 0.125};  // a kinematic sphere's sums are spent
        p.torque[i] = {1.5, 1.25, 1.125};
    }
    return p;
}

// Every sphere of p where its motion (or, if free, its old values) puts it.
// 1e-15 m and m/s: the two ways of turning differ by round-off of numbers
// of order 0.1.
void expect_moved(const ParticleStore& p, const std::vector<Vec3>& P0, const std::vector<Vec3>& V,
                  const std::vector<Vec3>& u, const std::vector<double>& w, double t) {
    for (std::size_t i = 0; i < p.size(); ++i) {
        SCOPED_TRACE("sphere " + std::to_string(i));
        const std::int32_t m = p.motion[i];
        if (m == free_motion) {
            EXPECT_EQ(p.position[i].x, 1.0);
            EXPECT_EQ(p.velocity[i].y, 5.0);
            EXPECT_EQ(p.angular_velocity[i].z, 9.0);
            EXPECT_EQ(p.force[i].x, 0.5);
            EXPECT_EQ(p.torque[i].z, 1.125);
            continue;
        }
        const auto k = static_cast<std::size_t>(m);
        const Vec3 arm = turned(p.reference_position[i] - P0[k], u[k], w[k] * t);
        const Vec3 x = P0[k] + t * V[k] + arm + p.image_shift[i];
        const Vec3 v = V[k] + w[k] * cross(u[k], arm);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(p.position[i][c], x[c], 1e-15);
            EXPECT_NEAR(p.velocity[i][c], v[c], 1e-15);
            EXPECT_NEAR(p.angular_velocity[i][c], w[k] * u[k][c], 1e-15);
            EXPECT_EQ(p.force[i][c], 0.0);
            EXPECT_EQ(p.torque[i][c], 0.0);
        }
    }
}

const double norm_of_axis = std::sqrt(1.0 + 0.04 + 0.09);

TEST(MoveKinematic, OneMotionTurnsEverySphereOfTheRangeAsARigidBody) {
    // 37 spheres: several full vectors of 8 and a remainder.
    ParticleStore p = spheres(std::vector<std::int32_t>(37, 0));
    const std::vector<Vec3> P0{{0.01, -0.02, 0.0}}, V{{0.0, 0.0, 0.3}};
    const std::vector<Vec3> u{Vec3{0.2, -0.3, 1.0} * (1.0 / norm_of_axis)};
    const std::vector<double> w{5.0};
    const double t = 0.173;
    move_kinematic(p, {motion_at(P0[0], V[0], u[0], w[0], t)}, {0, p.size()});
    expect_moved(p, P0, V, u, w, t);
}

TEST(MoveKinematic, EachSphereFollowsItsOwnMotionAndFreeOnesKeepTheirs) {
    ParticleStore p = spheres({0, free_motion, 1, 0, 1, free_motion, 0, 0, 1, 0, 0});
    const std::vector<Vec3> P0{{0.01, -0.02, 0.0}, {0.0, 0.0, 0.1}}, V{{0.0, 0.0, 0.3}, {0.1, 0.0, 0.0}};
    const std::vector<Vec3> u{Vec3{0.2, -0.3, 1.0} * (1.0 / norm_of_axis), {1.0, 0.0, 0.0}};
    const std::vector<double> w{5.0, -2.0};
    const double t = 0.173;
    move_kinematic(p, {motion_at(P0[0], V[0], u[0], w[0], t), motion_at(P0[1], V[1], u[1], w[1], t)},
                   {0, p.size()});
    expect_moved(p, P0, V, u, w, t);
}

TEST(MoveKinematic, OneMotionOnAPartOfTheStoreLeavesTheRestAlone) {
    // The range [3, 9) of spheres with motion 0; those outside keep their
    // values though they have the motion too.
    ParticleStore p = spheres(std::vector<std::int32_t>(12, 0));
    const MotionNow now = motion_at({0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, 5.0, 0.1);
    move_kinematic(p, {now}, {3, 9});
    for (std::size_t i = 0; i < p.size(); ++i) {
        const bool inside = i >= 3 && i < 9;
        EXPECT_EQ(p.position[i].x == 1.0, !inside) << i;
        EXPECT_EQ(p.force[i].x == 0.5, !inside) << i;
    }
}

}  // namespace
}  // namespace tumble
