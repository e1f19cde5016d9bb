// SPDX-License-Identifier: MIT
// Prescribed rigid motion of kinematic particles.
#pragma once

#include <cmath>

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

}  // namespace tumble
