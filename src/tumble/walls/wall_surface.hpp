// SPDX-License-Identifier: MIT
// A wall's surface as triangles, for drawing it (ParaView, Python): where
// its motion has carried it, infinite planes and cylinders cut to a box
// they are drawn across, curved surfaces by `segments` facets around.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tumble/core/domain.hpp"
#include "tumble/walls/mesh.hpp"
#include "tumble/walls/wall.hpp"

namespace tumble {

struct WallSurface {
    std::vector<Vec3> vertices;                          // m
    std::vector<std::array<std::uint32_t, 3>> triangles;  // vertex indices, counter-clockwise seen from n (planes)
};

// A mesh wall's surface is its triangles (`mesh`: Scenario::meshes[wall.mesh];
// none when it is not given).
WallSurface wall_surface(const PlacedWall& placed, const Domain& bounds, int segments = 48,
                         const TriangleMesh* mesh = nullptr);

}  // namespace tumble
