// SPDX-License-Identifier: MIT
// The speed benchmark (SPEC-NOTES "Speed"): an n x n x n simple cubic lattice
// of material-1 spheres, spacing 1.98 R so each overlaps its six neighbours,
// periodic in x, y and z, no gravity, random velocities of 0.05 m/s, dt =
// 1e-5 s, every model term on. The paper's system is n = 21 (9261 spheres).
#pragma once

#include <cstdint>

#include "tumble/sim/scenario.hpp"

namespace tumble {

Scenario benchmark_cube(int n = 21, std::uint64_t seed = 1);

}  // namespace tumble
