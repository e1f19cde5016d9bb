// SPDX-License-Identifier: MIT
// Element 1: Hertz elasticity (paper eq. 1).
#pragma once

namespace tumble {

// Normal force on i along +n (repulsive), N:
//   4/3 E* sqrt(R*) h^(3/2) = 4/3 E* a h,  with contact radius a = sqrt(R* h).
inline double hertz_force(double E_star, double contact_radius, double overlap) {
    return 4.0 / 3.0 * E_star * contact_radius * overlap;
}

// Elastic energy stored in the contact, J: the integral of hertz_force over
// h, 8/15 E* sqrt(R*) h^(5/2) = 8/15 E* a h^2.
inline double hertz_energy(double E_star, double contact_radius, double overlap) {
    return 8.0 / 15.0 * E_star * contact_radius * overlap * overlap;
}

}  // namespace tumble
