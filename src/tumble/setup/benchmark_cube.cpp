// SPDX-License-Identifier: MIT
#include "tumble/setup/benchmark_cube.hpp"

#include "tumble/core/error.hpp"
#include "tumble/setup/generators.hpp"
#include "tumble/setup/paper_materials.hpp"

namespace tumble {

Scenario benchmark_cube(int n, std::uint64_t seed) {
    if (n < 4) throw Error("benchmark cube: the lattice needs at least 4 spheres per edge");
    Scenario s;
    s.materials = {paper::material_1()};
    s.pair_properties = {{paper::pair_properties()[0][0]}};
    const double R = s.materials[0].radius;
    const double spacing = 1.98 * R;
    const double edge = n * spacing;
    s.domain = {{0.0, 0.0, 0.0}, {edge, edge, edge}, {true, true, true}};
    s.particles = lattice({0.5 * spacing, 0.5 * spacing, 0.5 * spacing}, {n, n, n}, spacing, R, 0);
    randomize_velocities(s.particles, 0.05, seed);
    s.time_step.dt = 1e-5;
    return s;
}

}  // namespace tumble
