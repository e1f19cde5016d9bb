// SPDX-License-Identifier: MIT
// The pair loop: the contact law applied to a range of the half neighbour
// list. Simulation::compute_forces() runs it, one range per thread; the
// micro-benchmarks (bench/) time it alone.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "tumble/contact/contact_law.hpp"
#include "tumble/core/parallel.hpp"
#include "tumble/materials/pair_table.hpp"
#include "tumble/neighbor/pair_list.hpp"
#include "tumble/neighbor/periodic_images.hpp"
#include "tumble/particles/particle_store.hpp"

namespace tumble {

// One contact as seen by the force law in the last step (when recording).
// For a contact with a flat wall, id_j is wall_id(face).
struct ContactRecord {
    std::int64_t id_i = 0, id_j = 0;
    ContactGeometry geometry;
    ContactForces forces;
    ContactHistory history;  // after the step
};

// The pair loop over pairs [range.begin, range.end) of the half list: for
// every candidate pair in contact, build the contact geometry, apply the
// contact law, and add the result to both particles (Newton's third law; the
// half list holds each pair once) in `force` and `torque`. A pair that is
// not touching drops its history. Each thread runs it on its own range of
// pairs into its own force arrays; the force law itself does not change.
template <bool Record>
[[gnu::flatten]] inline void add_contact_forces(const ParticleStore& p, PairList& pairs, IndexRange range,
                                         const PeriodicImages& images, const PairTable& table,
                                         const ContactModel& model, double dt, Vec3* force, Vec3* torque,
                                         std::vector<ContactRecord>& records) {
    for (std::size_t k = range.begin; k < range.end; ++k) {
        const std::uint32_t i = pairs.first[k], j = pairs.second[k];
        const Vec3 d = p.position[i] - p.position[j] + images[pairs.image[k]];
        const double distance2 = norm2(d);
        const double reach = p.radius[i] + p.radius[j];
        ContactHistory& history = pairs.history[k];
        if (distance2 >= reach * reach) {
            if (!history.is_zero()) history = ContactHistory{};  // contact ended
            continue;
        }
        const ContactGeometry g =
            make_contact_geometry(d, std::sqrt(distance2), p.radius[i], p.radius[j], p.velocity[i], p.velocity[j],
                                  p.angular_velocity[i], p.angular_velocity[j]);
        const ContactForces f = contact_law(table(p.material[i], p.material[j]), g, model, dt, history);
        force[i] += f.force_i;
        force[j] -= f.force_i;
        torque[i] += f.torque_i;
        torque[j] += f.torque_j;
        if constexpr (Record) records.push_back({p.id[i], p.id[j], g, f, history});
    }
}

}  // namespace tumble
