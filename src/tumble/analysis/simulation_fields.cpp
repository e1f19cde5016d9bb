// SPDX-License-Identifier: MIT
#include "tumble/analysis/simulation_fields.hpp"

#include <algorithm>
#include <cstdint>


namespace tumble::analysis {

GrainState grain_state(const Simulation& sim) {
    const ParticleStore& p = sim.particles();
    // Array index by global id; the grains numbered in the order of their ids.
    std::vector<std::size_t> at(sim.scenario().particles.size(), CgContact::wall), grain(at.size(), CgContact::wall);
    for (std::size_t k = 0; k < p.size(); ++k) at[static_cast<std::size_t>(p.id[k])] = k;
    GrainState s;
    s.time = sim.time();
    for (std::size_t id = 0; id < at.size(); ++id) {
        const std::size_t k = at[id];
        if (k == CgContact::wall || p.is_kinematic(k)) continue;
        grain[id] = s.position.size();
        s.position.push_back(p.position[k]);
        s.velocity.push_back(p.velocity[k]);
        s.mass.push_back(p.mass[k]);
        s.radius.push_back(p.radius[k]);
    }
    const auto grain_of = [&](std::int64_t id) {
        return id < 0 ? CgContact::wall : grain[static_cast<std::size_t>(id)];
    };
    for (const ContactRecord& r : sim.contact_records()) {
        const ContactGeometry& g = r.geometry;
        const std::size_t i = grain_of(r.id_i), j = grain_of(r.id_j);
        // n points from j (or the wall) to i; the contact point lies
        // lever_i from the centre of i, lever_j from that of j.
        if (i != CgContact::wall && j != CgContact::wall)
            s.contacts.push_back({i, j, r.forces.force_i, (g.lever_i + g.lever_j) * g.n});
        else if (i != CgContact::wall)
            s.contacts.push_back({i, CgContact::wall, r.forces.force_i, g.lever_i * g.n});
        else if (j != CgContact::wall)  // a wall sphere i against grain j: j feels -F, its branch the other way
            s.contacts.push_back({j, CgContact::wall, -r.forces.force_i, -(g.lever_j * g.n)});
    }
    return s;
}

}  // namespace tumble::analysis
