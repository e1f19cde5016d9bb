// SPDX-License-Identifier: MIT
#include "tumble/particles/particle_store.hpp"

namespace tumble {

namespace {
template <class T>
void apply(std::vector<T>& field, const std::vector<std::uint32_t>& order) {
    std::vector<T> sorted(field.size());
    for (std::size_t k = 0; k < order.size(); ++k) sorted[k] = field[order[k]];
    field.swap(sorted);
}
}  // namespace

void ParticleStore::permute(const std::vector<std::uint32_t>& order) {
    apply(id, order);
    apply(position, order);
    apply(velocity, order);
    apply(angular_velocity, order);
    apply(force, order);
    apply(torque, order);
    apply(half_kick, order);
    apply(radius, order);
    apply(inv_mass, order);
    apply(inv_inertia, order);
    apply(mass, order);
    apply(material, order);
    apply(motion, order);
    apply(tag, order);
    apply(reference_position, order);
    apply(image_shift, order);
}

}  // namespace tumble
