// SPDX-License-Identifier: MIT
// What a contact remembers between time steps. A record is zero when the
// contact starts and is dropped when it ends (overlap <= 0). The neighbour
// list stores one record per candidate pair and carries it, keyed by the
// global ids of the two particles, across re-sorts and list rebuilds.
#pragma once

#include "tumble/core/vec3.hpp"

namespace tumble {

struct ContactHistory {
    Vec3 slip;                 // delta s of eq. 8: the tangential displacement of i relative to j
                               // integrated since the contact began, kept in the contact plane, m
    double angular_slip = 0.0; // delta alpha of eq. 9: the relative rotation of i about +n
                               // integrated since the contact began, rad
    double viscous_force = 0.0; // element 2 (eq. 4) of the last step, on i along +n, N: the
                                // dashpot's time treatment takes its share out of the predicted
                                // velocity (integrate/dashpot.hpp)

    bool is_zero() const { return slip == Vec3{} && angular_slip == 0.0 && viscous_force == 0.0; }
    // The record seen from the other particle of the pair: both slips are
    // those of the first particle relative to the second, and n flips with
    // the pair, so the slip vector flips and the rotation about n does not;
    // the viscous force along n on the first particle does not either.
    ContactHistory swapped() const {
        ContactHistory h = *this;
        h.slip = -slip;
        return h;
    }
};

}  // namespace tumble
