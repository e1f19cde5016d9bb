// SPDX-License-Identifier: MIT
#include "tumble/walls/clearance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tumble/core/error.hpp"

namespace tumble {

WallDistances::WallDistances(const std::vector<Wall>& walls, const std::vector<TriangleMesh>& meshes, double reach)
    : walls_(walls), mesh_of_(walls.size(), 0), reach_(reach) {
    if (!(reach > 0.0) || !std::isfinite(reach)) throw Error("wall distances: the reach must be a positive length");
    for (std::size_t k = 0; k < walls_.size(); ++k) {
        if (walls_[k].shape != WallShape::mesh) continue;
        const TriangleMesh& mesh = meshes.at(static_cast<std::size_t>(walls_[k].mesh));
        MeshTopology topology(mesh);
        FacetGrid grid(facet_cell(mesh, 2.0 * reach, reach), reach);
        grid.rebuild(topology);
        mesh_of_[k] = meshes_.size();
        meshes_.push_back({std::move(topology), std::move(grid)});
    }
}

namespace {

// For a cylinder or cone (one-sided: its grains inside, or outside): how far
// x lies beyond its surface, m, where x lies between its ends (along the
// axis); <= 0 on the grains' side or beyond the ends. wall_touch() measures
// from the rim circle where the meridian's nearest point is the rim, which
// a grain just outside a hopper below its rim's height clears; but such a
// grain falls onto the mantle from behind, so a fill must not place it.
double beyond_revolution(const Wall& w, const Vec3& x) {
    const Vec3 d = x - w.point;
    const double s = dot(d, w.normal);
    if (!(s >= 0.0 && s <= w.length)) return 0.0;
    const double rho = norm(d - s * w.normal);
    double radius = w.radius;
    if (w.shape == WallShape::cone) radius += (w.end_radius - w.radius) * (s / w.length);
    return w.inside ? rho - radius : radius - rho;
}

}  // namespace

double WallDistances::distance(std::size_t k, const Vec3& x) const {
    const Wall& w = walls_[k];
    if (w.shape == WallShape::cylinder || w.shape == WallShape::cone) {
        const double beyond = beyond_revolution(w, x);
        return beyond > 0.0 ? -beyond : wall_touch(w, x).distance;
    }
    if (w.shape != WallShape::mesh) return wall_touch(w, x).distance;
    // The nearest point of the surface is one of the local minima of the
    // distance that mesh_contacts() gives within the reach: the distance
    // is the reach less the largest overlap.
    const MeshGrid& m = meshes_[mesh_of_[k]];
    mesh_contacts(m.topology, x, reach_, m.grid.candidates(x), found_);
    double deepest = -1.0;
    for (const MeshContact& c : found_) deepest = std::max(deepest, c.overlap);
    const double d = deepest >= 0.0 ? reach_ - deepest : std::numeric_limits<double>::infinity();
    if (!w.sided || d == 0.0) return d;
    // A closed mesh: beyond it where the winding number says x lies on the
    // other side (|w| is 1 inside, 0 outside; 1/2 is the surface).
    const bool within = std::abs(winding_number(m.topology, x)) > 0.5;
    return within == w.inside ? d : -std::min(d, reach_);
}

bool WallDistances::clear(const Vec3& x, double r) const { return clear(x, r, {}); }

bool WallDistances::clear(const Vec3& x, double r, const std::vector<MotionNow>& now) const {
    for (std::size_t k = 0; k < walls_.size(); ++k) {
        const std::int32_t m = walls_[k].motion;  // x in the wall's frame at the start of its motion
        const bool moved = m >= 0 && !now.empty();
        if (distance(k, moved ? to_start_frame(&now.at(static_cast<std::size_t>(m)), x) : x) < r) return false;
    }
    return true;
}

}  // namespace tumble
