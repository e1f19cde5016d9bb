// SPDX-License-Identifier: MIT
// Element 2: internal friction after Kuwabara and Kono (paper eq. 4).
#pragma once

namespace tumble {

// Normal force on i along +n, N:
//   -2 B* sqrt(R*) h^(1/2) v_n = -2 B* a v_n,
// with v_n = v . n the normal relative velocity (negative while the spheres
// approach, so the force then pushes them apart). B* in Pa s.
inline double kuwabara_kono_force(double B_star, double contact_radius, double v_n) {
    return -2.0 * B_star * contact_radius * v_n;
}

}  // namespace tumble
