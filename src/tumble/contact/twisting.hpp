// SPDX-License-Identifier: MIT
// Element 5: the twisting couple about the normal (Mindlin, no partial slip;
// paper eq. 9).
#pragma once

#include <algorithm>
#include <cmath>

#include "tumble/core/constants.hpp"

namespace tumble {

// Couple on i about +n, N m (the couple on j is its negative):
//   min(8/3 G* da (R* h)^(3/2), 3 pi/16 sqrt(R* h) mu |F_n|) (-sign w_n),
// where da (rad) is the angular slip integrated since the contact began,
// reset to zero when the static limit is reached, as for the shear force.
// w_n = (omega_i - omega_j) . n. The sign is regularised like the shear
// direction: the rim of the contact slides at |w_n| a, and below the slip
// speed v_reg the couple fades linearly.
inline double twisting_couple(double G_star, double mu, double contact_radius, double normal_force_abs,
                              double w_n, double dt, double v_reg, double& integrated_angular_slip) {
    integrated_angular_slip += std::abs(w_n) * dt;
    const double a = contact_radius;
    const double elastic = 8.0 / 3.0 * G_star * integrated_angular_slip * a * a * a;
    const double limit = 3.0 * pi / 16.0 * a * mu * normal_force_abs;
    double magnitude = elastic;
    if (elastic >= limit) {
        magnitude = limit;
        integrated_angular_slip = 0.0;
    }
    const double w_reg = a > 0.0 ? v_reg / a : v_reg;
    return -magnitude * w_n / std::max(std::abs(w_n), w_reg);
}

}  // namespace tumble
