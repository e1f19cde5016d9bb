// SPDX-License-Identifier: MIT
#pragma once

#include "tumble/particles/particle_store.hpp"
#include "tumble/sim/scenario.hpp"

namespace tumble {

// The particle store of a scenario: global id = index in Scenario::particles,
// masses from the material densities, solid-sphere inertia 2/5 m R^2;
// kinematic particles get zero inverse mass and inertia.
ParticleStore make_particle_store(const Scenario& s);

// One particle appended to the store, with global id `id`, as above.
void add_particle(ParticleStore& p, const ParticleSpec& spec, std::int64_t id, const std::vector<Material>& materials);

}  // namespace tumble
