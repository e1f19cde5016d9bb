// SPDX-License-Identifier: MIT
// The contact network of the current state: every pair of spheres that
// touches, with its normal force, for snapshots and analysis. Reads the
// simulation only; the contact history is not touched.
//
// Left out: contacts with the flat walls of the domain (Domain::walls).
// Only sphere-sphere contacts are listed and counted; a particle-walled drum
// has its wall as kinematic spheres, so its wall contacts are included.
#pragma once

#include <cstdint>
#include <vector>

#include "tumble/contact/history.hpp"
#include "tumble/core/vec3.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble {

// One touching pair. Oriented id_i < id_j; n is the unit normal from the
// centre of j to the centre of i (the paper's convention, geometry.hpp),
// taken between i and the periodic image of j nearest to it.
struct ContactLink {
    std::int64_t id_i = 0, id_j = 0;  // global ids
    Vec3 point;                        // contact point X_i - (R_i - h/2) n, m
    Vec3 n;                            // unit normal, j -> i
    double overlap = 0.0;              // h = R_i + R_j - |X_i - X_j| > 0, m
    // F_n along n on i, N: the sum of the stateless normal terms that are
    // switched on in Scenario::model, Hertz (eq. 1) + Kuwabara-Kono (eq. 4) +
    // attraction (eq. 7), from the present positions and velocities.
    // Positive pushes the spheres apart.
    double normal_force = 0.0;
    // The contact's memory (eq. 8's slip of i relative to j, eq. 9's twist
    // about n), seen from i, as the last step left it.
    ContactHistory history;
};

// Every touching pair of the neighbour list, sorted by (id_i, id_j).
// Contacts with flat walls are not included (see above). Shared among
// ranks: collective, every rank's pairs on rank 0 (a pair of a rank's own
// sphere and a ghost once, from the rank of the lower id), none elsewhere.
std::vector<ContactLink> contact_network(const Simulation& sim);

// Number of sphere-sphere contacts of each particle, indexed by global id
// (ids are 0 .. N-1). Flat-wall contacts are not counted. Shared among
// ranks: collective, the counts of all ranks on every rank.
std::vector<std::uint32_t> contact_counts(const Simulation& sim);

}  // namespace tumble
