// SPDX-License-Identifier: MIT
// Element 3: surface attraction after Johnson, Kendall and Roberts (paper eq. 7).
#pragma once

#include <cmath>

namespace tumble {

// Normal force on i along +n (negative: attractive), N:
//   -sqrt(4/3 * 8 pi W E*) (R*)^(3/4) h^(3/4) = -prefactor a^(3/2).
// The paper prints (R*)^(1/4); SPEC-NOTES corrects the exponent to 3/4, the
// JKR term sqrt(8 pi W E* a^3) with a = sqrt(R* h). prefactor in N m^-3/2.
inline double attraction_force(double prefactor, double contact_radius) {
    return -prefactor * contact_radius * std::sqrt(contact_radius);
}

// Energy of the attraction, J: the integral of attraction_force over h,
//   -4/7 prefactor (R*)^(3/4) h^(7/4) = -4/7 prefactor a^(3/2) h.
inline double attraction_energy(double prefactor, double contact_radius, double overlap) {
    return -4.0 / 7.0 * prefactor * contact_radius * std::sqrt(contact_radius) * overlap;
}

}  // namespace tumble
