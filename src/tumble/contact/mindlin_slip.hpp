// SPDX-License-Identifier: MIT
// Element 4, the paper's shear model: Mindlin without partial slip, with the
// slip integrated since the contact began (paper eq. 8).
#pragma once

#include <algorithm>
#include <cmath>

#include "tumble/core/vec3.hpp"

namespace tumble {

// Unit vector against the sliding velocity, -v_t/|v_t|, regularised: below
// the slip speed v_reg (m/s) it becomes -v_t/v_reg, so the force fades
// linearly to zero as the tangential velocity vanishes instead of flipping
// at random with round-off. SPEC-NOTES leaves this choice open.
inline Vec3 against_slip(const Vec3& v_t, double v_reg) {
    return (-1.0 / std::max(norm(v_t), v_reg)) * v_t;
}

// Tangential force on i, N:
//   min(16/3 G* ds sqrt(R* h), mu |F_n|) (-v_t/|v_t|),
// where ds (m) is the slip integrated since the contact began: ds grows by
// |v_t| dt each step; when the elastic value reaches the static limit
// mu |F_n| the contact slips and ds is reset to zero (SPEC-NOTES item 4).
inline Vec3 mindlin_slip_force(double G_star, double mu, double contact_radius, double normal_force_abs,
                               const Vec3& v_t, double dt, double v_reg, double& integrated_slip) {
    integrated_slip += norm(v_t) * dt;
    const double elastic = 16.0 / 3.0 * G_star * integrated_slip * contact_radius;
    const double limit = mu * normal_force_abs;
    double magnitude = elastic;
    if (elastic >= limit) {
        magnitude = limit;
        integrated_slip = 0.0;
    }
    return magnitude * against_slip(v_t, v_reg);
}

}  // namespace tumble
