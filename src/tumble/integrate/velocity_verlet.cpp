// SPDX-License-Identifier: MIT
#include "tumble/integrate/velocity_verlet.hpp"

namespace tumble {

void kick(ParticleStore& p, const Vec3& gravity, double half_dt) {
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.is_kinematic(i)) continue;
        p.velocity[i] += half_dt * (p.inv_mass[i] * p.force[i] + gravity);
        p.angular_velocity[i] += (half_dt * p.inv_inertia[i]) * p.torque[i];
    }
}

void drift(ParticleStore& p, double dt) {
    for (std::size_t i = 0; i < p.size(); ++i)
        if (!p.is_kinematic(i)) p.position[i] += dt * p.velocity[i];
}

}  // namespace tumble
