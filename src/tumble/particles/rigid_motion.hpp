// SPDX-License-Identifier: MIT
// Prescribed rigid motion of kinematic particles.
#pragma once

#include <algorithm>
#include <cmath>

#include "tumble/core/constants.hpp"
#include "tumble/core/vec3.hpp"

namespace tumble {

// A rotation by an angle (rad, right-handed) about the unit axis u, with the
// angle's cosine and sine worked out once for all the points it turns.
struct Rotation {
    Vec3 u;
    double c = 1.0, s = 0.0;
    Rotation(const Vec3& axis, double angle) : u(axis), c(std::cos(angle)), s(std::sin(angle)) {}
};

// Rotate r (Rodrigues).
inline Vec3 rotate(const Vec3& r, const Rotation& R) {
    return R.c * r + R.s * cross(R.u, r) + ((1.0 - R.c) * dot(R.u, r)) * R.u;
}

// Where a prescribed motion is at one time, worked out once per step for
// all its particles: the axis point when the motion began (m) and now (m),
// the translation velocity (m/s), the rotation since it began and the
// angular velocity about turn.u (rad/s).
struct MotionNow {
    Vec3 start_axis_point, axis_point, velocity;
    Rotation turn;
    double angular_velocity;
};

// The distance of point x from the axis through `point` along the unit
// vector u (m).
inline double distance_from_axis(const Vec3& x, const Vec3& point, const Vec3& u) {
    const Vec3 d = x - point;
    return norm(d - dot(d, u) * u);
}

// The farthest a rigid motion (translation velocity v, m/s; angular velocity
// omega, rad/s) carries a point within `reach` (m) of its axis in a time t
// (s): the translation plus the chord of the turn, |v| t + 2 sin(min(|omega|
// t, pi) / 2) reach (m). Every sphere of the motion at the same reach or
// nearer moves no farther; the one at that reach, with v = 0, exactly so far.
inline double rigid_displacement_bound(const Vec3& v, double omega, double t, double reach) {
    const double turn = std::min(std::abs(omega * t), pi);
    return norm(v) * std::abs(t) + 2.0 * std::sin(0.5 * turn) * reach;
}

}  // namespace tumble
