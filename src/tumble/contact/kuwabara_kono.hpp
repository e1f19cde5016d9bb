// SPDX-License-Identifier: MIT
// Element 2: internal friction after Kuwabara and Kono (paper eq. 4).
#pragma once

namespace tumble {

// The dashpot's coefficient c = 2 B* sqrt(R* h) = 2 B* a, N s/m (B* in Pa s,
// a the contact radius in m). It grows as h^(1/2): the stiff part of the
// model, whose time treatment is integrate/dashpot.hpp's.
inline double kuwabara_kono_coefficient(double B_star, double contact_radius) {
    return 2.0 * B_star * contact_radius;
}

// Normal force on i along +n (n from the centre of j to that of i), N:
//   -2 B* sqrt(R*) h^(1/2) v_n = -c v_n,
// with v_n = v . n the normal relative velocity, m/s (negative while the
// spheres approach, so the force then pushes them apart). The engine hands
// it the velocity of integrate/dashpot.hpp.
inline double kuwabara_kono_force(double B_star, double contact_radius, double v_n) {
    return -kuwabara_kono_coefficient(B_star, contact_radius) * v_n;
}

}  // namespace tumble
