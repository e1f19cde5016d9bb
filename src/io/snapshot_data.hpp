// SPDX-License-Identifier: MIT
// What a snapshot shows of a simulation at one moment, for the writers of
// output.hpp (CSV), vtk_output.hpp (ParaView) and xyz_output.hpp (OVITO):
// every sphere, the contact network and each sphere's contact count, the
// clock, the material names and the box. On one rank taken from the
// simulation; shared among ranks (sim/slabs.hpp) gathered onto rank 0, so
// that a run on any number of ranks writes the same one file per snapshot.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tumble/core/domain.hpp"
#include "tumble/particles/particle_store.hpp"
#include "tumble/sim/contact_network.hpp"
#include "tumble/sim/simulation.hpp"
#include "tumble/walls/wall_surface.hpp"

namespace tumble::io {

struct SnapshotData {
    ParticleStore particles;               // every sphere (shared: in the order of global ids)
    std::vector<std::uint32_t> contacts;   // sphere-sphere contacts per global id
    std::vector<ContactLink> links;        // the contact network, by (id_i, id_j)
    double time = 0.0;                     // s
    std::int64_t step = 0;
    std::vector<std::string> material_names;
    Domain domain;
    std::vector<std::string> wall_names;  // Scenario::walls
    std::vector<WallSurface> walls;       // each drawn where its motion has carried it (walls/wall_surface.hpp)
};

// Collective when `sim` is shared among ranks: every rank calls it, rank 0
// gets the whole snapshot, the others an empty one (no particles).
SnapshotData snapshot_of(const Simulation& sim);

// The surfaces of the scenario's smooth walls where their motions have
// carried them at sim.time(), infinite ones cut to the domain box.
std::vector<WallSurface> wall_surfaces(const Simulation& sim);

}  // namespace tumble::io
