// SPDX-License-Identifier: MIT
#pragma once

#include <array>
#include <cstdint>

#include "tumble/core/vec3.hpp"

namespace tumble {

// The simulation box. Periodic axes wrap at [lo, hi). Walled axes have a
// flat wall of wall_material at lo and at hi. On the other axes the box only
// bounds where particles start (space is open).
struct Domain {
    Vec3 lo;
    Vec3 hi;
    std::array<bool, 3> periodic{false, false, false};
    std::array<bool, 3> walls{false, false, false};
    std::int32_t wall_material = 0;

    Vec3 length() const { return hi - lo; }
};

}  // namespace tumble
