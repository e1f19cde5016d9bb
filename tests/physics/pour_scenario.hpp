// SPDX-License-Identifier: MIT
// The scenario of the pouring tests (test_insertion.cpp, and on MPI ranks
// test_slabs.cpp), with the [[insert]] tables each test gives.
#pragma once

#include <string>

namespace physics_test {

// A box 40 x 40 x 80 mm with steel walls where `walls` says (all six by
// default), the soft glass of examples/hopper.toml, gravity along -z, and
// the given [[insert]] (and [[wall]]) tables.
inline std::string pour(const std::string& insert, const std::string& walls = "[true, true, true]") {
    return R"(
[simulation]
duration = 0.1
seed = 7
gravity = [0.0, 0.0, -9.81]

[time_step]
reference_speed = 1.5

[domain]
lo = [-0.02, -0.02, 0.0]
hi = [0.02, 0.02, 0.08]
walls = )" + walls + R"(
wall_material = "steel"

[[material]]
name = "glass"
E = 5.0e6
G = 2.0e6
nu = 0.25
xi = 20.0
eta = 20.0
rho = 2500.0
radius = 2.0e-3

[[material]]
name = "steel"
E = 1.0e7
G = 4.0e6
nu = 0.3
xi = 20.0
eta = 20.0
rho = 7800.0
radius = 2.0e-3

[[pair]]
materials = ["glass", "glass"]
mu = 0.3
W = 0.0

[[pair]]
materials = ["glass", "steel"]
mu = 0.4
W = 0.0

[[pair]]
materials = ["steel", "steel"]
mu = 0.4
W = 0.0
)" + insert;
}

}  // namespace physics_test
