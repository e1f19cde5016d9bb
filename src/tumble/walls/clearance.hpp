// SPDX-License-Identifier: MIT
// How far a point lies from the walls of a scenario, meshes included: for
// placing grains clear of the equipment and for checking a scenario's
// grains before it runs (not for the time step, which finds its contacts
// itself). The walls as they are at the start of their motions.
#pragma once

#include <vector>

#include "tumble/core/vec3.hpp"
#include "tumble/walls/facet_grid.hpp"
#include "tumble/walls/mesh.hpp"
#include "tumble/walls/wall.hpp"

namespace tumble {

class WallDistances {
public:
    // reach: the largest radius that will be asked about (m, > 0); meshes:
    // the scenario's (Wall::mesh indexes them).
    WallDistances(const std::vector<Wall>& walls, const std::vector<TriangleMesh>& meshes, double reach);

    std::size_t size() const { return walls_.size(); }

    // Of wall k, m: wall_touch()'s distance for an analytic wall (negative
    // beyond a one-sided one; for a cylinder or a cone also outside it
    // between its ends where the nearest point is its rim, as a grain just
    // outside a hopper below its rim: minus how far); for a mesh the
    // distance to its nearest point where that is below the reach, else
    // infinity, and for a closed mesh with a side (Wall::sided) negative
    // on the other side: minus that distance, at most the reach (the
    // winding number decides, at a cost of every face per point).
    double distance(std::size_t k, const Vec3& x) const;

    // Whether a sphere at x of radius r (<= reach) lies clear of every wall:
    // on the grains' side of each and touching none.
    bool clear(const Vec3& x, double r) const;
    // The same with the walls where their motions have carried them (now:
    // per motion of the scenario, where it is; a wall without one at rest;
    // empty: every wall at the start of its motion, as above).
    bool clear(const Vec3& x, double r, const std::vector<MotionNow>& now) const;

private:
    struct MeshGrid {
        MeshTopology topology;
        FacetGrid grid;
    };
    std::vector<Wall> walls_;
    std::vector<MeshGrid> meshes_;  // per wall k with a mesh, at mesh_of_[k]
    std::vector<std::size_t> mesh_of_;
    double reach_;
    mutable std::vector<MeshContact> found_;
};

}  // namespace tumble
