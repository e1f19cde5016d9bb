// SPDX-License-Identifier: MIT
#include "tumble/sim/particle_setup.hpp"

#include "tumble/core/constants.hpp"

namespace tumble {

ParticleStore make_particle_store(const Scenario& s) {
    ParticleStore p;
    for (std::size_t i = 0; i < s.particles.size(); ++i) {
        const ParticleSpec& spec = s.particles[i];
        const double R = spec.radius;
        const double mass = 4.0 / 3.0 * pi * s.materials[spec.material].rho * R * R * R;
        const bool kinematic = spec.motion != free_motion;
        p.id.push_back(static_cast<std::int64_t>(i));
        p.position.push_back(spec.position);
        p.velocity.push_back(spec.velocity);
        p.angular_velocity.push_back(spec.angular_velocity);
        p.force.emplace_back();
        p.torque.emplace_back();
        p.half_kick.emplace_back();
        p.radius.push_back(R);
        p.mass.push_back(mass);
        p.inv_mass.push_back(kinematic ? 0.0 : 1.0 / mass);
        p.inv_inertia.push_back(kinematic ? 0.0 : 1.0 / (0.4 * mass * R * R));
        p.material.push_back(spec.material);
        p.motion.push_back(spec.motion);
        p.tag.push_back(spec.tag);
        p.reference_position.push_back(spec.position);
        p.image_shift.emplace_back();
    }
    return p;
}

}  // namespace tumble
