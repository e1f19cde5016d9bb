// SPDX-License-Identifier: MIT
// Prescribed rigid motion of kinematic particles.
#pragma once

#include <cmath>

#include "tumble/core/vec3.hpp"

namespace tumble {

// Rotate r by `angle` (rad, right-handed) about the unit axis u (Rodrigues).
inline Vec3 rotate(const Vec3& r, const Vec3& u, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return c * r + s * cross(u, r) + ((1.0 - c) * dot(u, r)) * u;
}

}  // namespace tumble
