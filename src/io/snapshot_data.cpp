// SPDX-License-Identifier: MIT
#include "io/snapshot_data.hpp"

#include <optional>

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
    for (const Wall& w : sim.scenario().walls) s.wall_names.push_back(w.name);
    s.walls = wall_surfaces(sim);
    return s;
}

std::vector<WallSurface> wall_surfaces(const Simulation& sim) {
    std::vector<WallSurface> drawn;
    for (const Wall& w : sim.scenario().walls) {
        std::optional<MotionNow> now;
        if (w.motion >= 0) now = sim.motion_now(static_cast<std::size_t>(w.motion));
        const TriangleMesh* mesh = w.mesh >= 0 ? &sim.scenario().meshes[static_cast<std::size_t>(w.mesh)] : nullptr;
        drawn.push_back(wall_surface(place_wall(w, now ? &*now : nullptr), sim.scenario().domain, 48, mesh));
    }
    return drawn;
}

}  // namespace tumble::io
