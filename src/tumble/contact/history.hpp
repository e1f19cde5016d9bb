// SPDX-License-Identifier: MIT
// What a contact remembers between time steps. A record is zero when the
// contact starts and is dropped when it ends (overlap <= 0). The neighbour
// list stores one record per candidate pair and carries it, keyed by the
// global ids of the two particles, across re-sorts and list rebuilds.
#pragma once

#include "tumble/core/vec3.hpp"

namespace tumble {

struct ContactHistory {
    double integrated_slip = 0.0;          // delta s of eq. 8, m (paper's shear model)
    double integrated_angular_slip = 0.0;  // delta alpha of eq. 9, rad
    Vec3 tangential_spring;                // displacement of i relative to j in the contact
                                           // plane, m (spring shear model only)

    bool is_zero() const {
        return integrated_slip == 0.0 && integrated_angular_slip == 0.0 && tangential_spring == Vec3{};
    }
    // The record seen from the other particle of the pair: the spring vector
    // is the displacement of the first relative to the second, so it flips.
    ContactHistory swapped() const {
        ContactHistory h = *this;
        h.tangential_spring = -tangential_spring;
        return h;
    }
};

}  // namespace tumble
