// SPDX-License-Identifier: MIT
#include "io/snapshot_data.hpp"

namespace tumble::io {

SnapshotData snapshot_of(const Simulation& sim) {
    SnapshotData s;
    s.particles = sim.gathered();
    s.contacts = contact_counts(sim);
    s.links = contact_network(sim);
    s.time = sim.time();
    s.step = sim.step_count();
    for (const Material& m : sim.scenario().materials) s.material_names.push_back(m.name);
    s.domain = sim.scenario().domain;
    return s;
}

}  // namespace tumble::io
