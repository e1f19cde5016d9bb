// SPDX-License-Identifier: MIT
// Element 4, the alternative shear model users of LIGGGHTS and LAMMPS know:
// a tangential spring vector kept in the contact plane and truncated at the
// Coulomb limit. Its stiffness is the paper's, 16/3 G* sqrt(R* h), so the two
// models agree until the first slip; under sustained sliding the spring holds
// the force at mu |F_n| where the paper's model saw-tooths from 0 to it.
#pragma once

#include <cmath>

#include "tumble/core/vec3.hpp"

namespace tumble {

// Tangential force on i, N. spring (m) is the tangential displacement of i
// relative to j accumulated since the contact began.
inline Vec3 mindlin_spring_force(double G_star, double mu, double contact_radius, double normal_force_abs,
                                 const Vec3& n, const Vec3& v_t, double dt, Vec3& spring) {
    // Keep the spring in the current contact plane, preserving its length,
    // as the pair rolls and the normal turns.
    const double old_length = norm(spring);
    spring -= dot(spring, n) * n;
    const double new_length = norm(spring);
    if (new_length > 0.0) spring *= old_length / new_length;

    spring += dt * v_t;
    const double stiffness = 16.0 / 3.0 * G_star * contact_radius;  // N/m
    Vec3 force = -stiffness * spring;
    const double limit = mu * normal_force_abs;
    const double magnitude = norm(force);
    if (magnitude > limit) {
        // Slip: shorten the spring to the length that carries the limit.
        const double scale = limit / magnitude;
        spring *= scale;
        force *= scale;
    }
    return force;
}

}  // namespace tumble
