// SPDX-License-Identifier: MIT
// Everything that changes while a Simulation runs, as plain data: what a
// checkpoint must hold so that a restored run continues bit for bit as the
// original would have. The scenario (materials, domain, settings) is not
// part of it; Simulation::restore() takes a state captured from a run of
// the same scenario. No file format here: src/io/checkpoint.hpp writes it.
//
// Random numbers are drawn only while a scenario is built (generators,
// drum filling), never while it runs, so there is no generator state to keep.
#pragma once

#include <cstdint>
#include <vector>

#include "tumble/neighbor/verlet_list.hpp"
#include "tumble/particles/particle_store.hpp"
#include "tumble/sim/scenario.hpp"
#include "tumble/sim/slabs.hpp"

namespace tumble {

// A prescribed motion and the time it began (set_motion() restarts it).
struct MotionClock {
    RigidMotion motion;
    double start_time = 0.0;  // s
};

struct SimulationState {
    ParticleStore particles;                 // every field, in array order
    NeighborState neighbors;
    std::vector<ContactHistory> wall_history;  // slots x global id + slot (Simulation::wall_slots()); empty without walls
    // Per slot of wall_history: the feature of a mesh wall whose contact the
    // slot follows (mesh_feature_code()), 0 for none and for the other walls.
    std::vector<std::uint32_t> wall_feature;
    std::vector<MotionClock> motions;
    std::vector<std::int64_t> inserted;      // per Scenario::insertions, the spheres poured in so far
    double dt = 0.0;                         // s
    double time = 0.0;                       // s
    std::int64_t step = 0;
    // Shared among ranks (sim/slabs.hpp): the rank's own spheres are the
    // first `owned` of `particles`, the ghosts follow; on one rank owned is
    // every particle and the slab state empty.
    std::size_t owned = 0;
    SlabState slabs;
    int ranks = 1;  // the ranks of the run it was captured from (one state per rank)
    // Made by whole_state() from several ranks' states: the pairs hold the
    // histories of the touching pairs only, not the Verlet list of a run,
    // which restore() finds anew. Not kept in checkpoint files.
    bool list_from_histories = false;
};

}  // namespace tumble
