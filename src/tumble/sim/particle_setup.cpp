// SPDX-License-Identifier: MIT
#include "tumble/sim/particle_setup.hpp"

#include "tumble/core/constants.hpp"

namespace tumble {

void add_particle(ParticleStore& p, const ParticleSpec& spec, std::int64_t id, const std::vector<Material>& materials) {
    const double R = spec.radius;
    const double mass = 4.0 / 3.0 * pi * materials[static_cast<std::size_t>(spec.material)].rho * R * R * R;
    const bool kinematic = spec.motion != free_motion;
    p.id.push_back(id);
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

ParticleStore make_particle_store(const Scenario& s) {
    ParticleStore p;
    for (std::size_t i = 0; i < s.particles.size(); ++i)
        add_particle(p, s.particles[i], static_cast<std::int64_t>(i), s.materials);
    return p;
}

}  // namespace tumble
