// SPDX-License-Identifier: MIT
// The seed paper's materials (tables 2 and 3; SPEC-NOTES "The materials"),
// in SI units: 5000 poise = 500 Pa s.
#pragma once

#include <vector>

#include "tumble/materials/material.hpp"

namespace tumble::paper {

inline Material material(const char* name, double radius) {
    return {name, 1.0e6, 0.3e6, 0.25, 500.0, 500.0, 1000.0, radius};
}
inline Material material_1() { return material("material-1", 3.6e-3); }
inline Material material_2() { return material("material-2", 2.4e-3); }
inline Material material_3() { return material("wall", 3.0e-3); }  // the drum wall

inline std::vector<Material> materials() { return {material_1(), material_2(), material_3()}; }

// The surface energy W of every pair of the paper's materials, J/m^2.
inline constexpr double surface_energy = 0.2;

// mu and W for every pair of materials(): 1-1, 1-2, 2-2, and 0.2 for any
// pair with the wall; W = surface_energy throughout.
inline std::vector<std::vector<PairProperties>> pair_properties() {
    const double W = surface_energy;
    return {{{0.1, W}, {0.2, W}, {0.2, W}},
            {{0.2, W}, {0.5, W}, {0.2, W}},
            {{0.2, W}, {0.2, W}, {0.2, W}}};
}

}  // namespace tumble::paper
