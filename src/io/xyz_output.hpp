// SPDX-License-Identifier: MIT
// Particle snapshots as extended XYZ, the text format of ASE and OVITO
// (https://github.com/libAtoms/extxyz): OVITO opens snapshots/*.xyz as an
// animation, with the material names as particle types.
//
//   line 1        the number of particles
//   line 2        key=value pairs: Lattice and Origin (the domain's box, m;
//                 left out when an axis is unbounded), pbc (periodic axes),
//                 Time (s), step, and Properties, the columns that follow
//   then          one line per particle, ordered by global id:
//                 species (material name; a blank in it written as '_'),
//                 pos (m, 3 columns), radius (m), id, velo (m/s, 3),
//                 omega (angular velocity, rad/s, 3), tag, kinematic (1 for
//                 spheres on a prescribed motion, else 0)
//
// Numbers are in the shortest form that reads back to the same double.
#pragma once

#include <filesystem>

#include "io/snapshot_data.hpp"
#include "tumble/sim/simulation.hpp"

namespace tumble::io {

// Writes the particles of `sim` to `file` (.xyz), or tumble::Error naming it.
void write_xyz_snapshot(const std::filesystem::path& file, const SnapshotData& snapshot);
void write_xyz_snapshot(const std::filesystem::path& file, const Simulation& sim);

}  // namespace tumble::io
