// SPDX-License-Identifier: MIT
#include "tumble/integrate/velocity_verlet.hpp"

#include "tumble/core/parallel.hpp"

namespace tumble {

void kick(ParticleStore& p, const Vec3& gravity, double half_dt, int chunks) {
    parallel_for(chunks, p.size(), [&](std::size_t i) {
        if (p.is_kinematic(i)) return;
        p.velocity[i] += half_dt * (p.inv_mass[i] * p.force[i] + gravity);
        p.angular_velocity[i] += (half_dt * p.inv_inertia[i]) * p.torque[i];
    });
}

void drift(ParticleStore& p, double dt, int chunks) {
    parallel_for(chunks, p.size(), [&](std::size_t i) {
        if (!p.is_kinematic(i)) p.position[i] += dt * p.velocity[i];
    });
}

}  // namespace tumble
