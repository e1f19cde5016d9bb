// SPDX-License-Identifier: MIT
#include "tumble/particles/particle_store.hpp"

#include <utility>

namespace tumble {

namespace {
template <class T>
void gather_field(std::vector<T>& to, const std::vector<T>& from, const std::vector<std::uint32_t>& order, IndexRange r) {
    for (std::size_t k = r.begin; k < r.end; ++k) to[k] = from[order[k]];
}
}  // namespace

void ParticleStore::gather(const ParticleStore& from, const std::vector<std::uint32_t>& order, IndexRange r) {
    gather_field(id, from.id, order, r);
    gather_field(position, from.position, order, r);
    gather_field(velocity, from.velocity, order, r);
    gather_field(angular_velocity, from.angular_velocity, order, r);
    gather_field(force, from.force, order, r);
    gather_field(torque, from.torque, order, r);
    gather_field(half_kick, from.half_kick, order, r);
    gather_field(radius, from.radius, order, r);
    gather_field(inv_mass, from.inv_mass, order, r);
    gather_field(inv_inertia, from.inv_inertia, order, r);
    gather_field(mass, from.mass, order, r);
    gather_field(material, from.material, order, r);
    gather_field(motion, from.motion, order, r);
    gather_field(tag, from.tag, order, r);
    gather_field(reference_position, from.reference_position, order, r);
    gather_field(image_shift, from.image_shift, order, r);
}

void ParticleStore::permute(const std::vector<std::uint32_t>& order) {
    ParticleStore sorted = *this;
    sorted.gather(*this, order, {0, size()});
    *this = std::move(sorted);
}

}  // namespace tumble
