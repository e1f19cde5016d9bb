// SPDX-License-Identifier: MIT
// The grains and contacts of a simulation's state, as coarse_grain.hpp takes
// them: the free grains (the spheres on a prescribed motion, a drum's wall
// spheres, are walls), and every contact of the last step with its full
// force as the contact law gave it (normal, tangential, every wall: the
// box's faces, the smooth and mesh walls, the wall spheres).
#pragma once

#include <vector>

#include "tumble/analysis/coarse_grain.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::analysis {

struct GrainState {
    double time = 0.0;  // s
    std::vector<Vec3> position, velocity;  // m, m/s
    std::vector<double> mass, radius;      // kg, m
    std::vector<CgContact> contacts;
    CgGrains grains() const { return {position, velocity, mass, radius}; }
};

// The state of `sim` after a step taken with its contacts recorded
// (Simulation::set_contact_recording(true)): the grains in the order of
// their global ids, positions and velocities at the end of the step, and
// the contacts the step's forces came from. A contact of a grain with a
// wall sphere is a wall contact of the grain, its branch from the contact
// point to the grain's centre. (Without the recording the state has no
// contacts.)
GrainState grain_state(const Simulation& sim);

}  // namespace tumble::analysis
