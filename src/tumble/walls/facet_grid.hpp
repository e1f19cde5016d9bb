// SPDX-License-Identifier: MIT
// The faces of a mesh that a sphere may touch, found in O(1): a uniform grid
// of cubic cells over the mesh's bounding box grown by `reach`, each cell
// listing (in increasing order) the faces whose bounding box, grown by
// `reach`, overlaps the cell and whose plane comes within `reach` of the
// cell. The candidates of a centre c are its cell's list, and they hold
// every face within `reach` of c: if a face's point q has |c - q| <= reach,
// then |c_i - q_i| <= reach on each axis, so c lies in the face's box grown
// by reach, and c, a point of its cell, lies within reach of the face's
// plane. The lists may hold faces farther away (mesh_contacts drops them
// at the cost of a few dot products each).
//
// reach: the largest radius of the spheres, plus how far they may move
// between rebuilds if the candidates are kept (none when they are looked
// up each step), m. cell: the cells' edge, m; the neighbour list's cell
// (twice the largest radius plus the skin) is a good size: smaller cells
// list each face more often, larger ones list more faces per cell. The grid
// is dense: a mesh box of more than max_cells cells is refused (tumble::Error)
// and needs a larger cell.
//
// A moving mesh: after MeshTopology::set_vertices, rebuild(). (For a mesh
// that only turns and shifts, a grid built once in the mesh's own frame and
// asked with the centre carried into that frame saves the rebuilds.)
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "tumble/core/vec3.hpp"
#include "tumble/walls/mesh.hpp"

namespace tumble {

class FacetGrid {
public:
    static constexpr std::size_t max_cells = std::size_t{1} << 24;

    FacetGrid(double cell, double reach);  // cell > 0 and reach >= 0, finite, else tumble::Error

    void rebuild(const MeshTopology& mesh);

    // The faces that may lie within reach of c, in increasing order; none
    // when c lies outside the grid (farther than reach from every face).
    std::span<const std::uint32_t> candidates(const Vec3& c) const;

private:
    double cell_, per_cell_, reach_;     // m, 1/m, m
    Vec3 origin_;                        // the low corner of cell (0, 0, 0), m
    std::array<std::size_t, 3> dims_{};  // cells along x, y, z
    // Cell (i, j, k), number i + nx (j + ny k), lists faces_[start_[cell]] to
    // faces_[start_[cell + 1] - 1].
    std::vector<std::uint32_t> start_, faces_;
};

// The cell of a mesh's facet grid: `cell` (m), or larger where the mesh's
// box grown by `reach` would need more than a quarter of
// FacetGrid::max_cells.
double facet_cell(const TriangleMesh& m, double cell, double reach);

}  // namespace tumble
