// SPDX-License-Identifier: MIT
#include "tumble/walls/wall.hpp"

namespace tumble {

namespace {

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

std::string wall_problem(const Wall& w) {
    if (!finite(w.point) || !finite(w.normal) || !finite(w.edge)) return "its point and directions must be finite";
    if (std::abs(norm(w.normal) - 1.0) > 1e-12) return "its normal (or axis) must be a unit vector";
    switch (w.shape) {
        case WallShape::plane: return {};
        case WallShape::rectangle:
            if (std::abs(norm(w.edge) - 1.0) > 1e-12 || std::abs(dot(w.edge, w.normal)) > 1e-12)
                return "its edge must be a unit vector in its plane";
            if (!(w.half_width > 0.0) || !(w.half_height > 0.0) || !std::isfinite(w.half_width) ||
                !std::isfinite(w.half_height))
                return "its sides must be positive and finite";
            return {};
        case WallShape::disc:
            if (!(w.radius > 0.0) || !std::isfinite(w.radius)) return "its radius must be positive and finite";
            if (!(w.hole_radius >= 0.0 && w.hole_radius < w.radius)) return "its hole_radius must lie in [0, radius)";
            return {};
        case WallShape::cylinder:
            if (!(w.radius > 0.0) || !std::isfinite(w.radius)) return "its radius must be positive and finite";
            if (!(w.length > 0.0)) return "its length must be positive (or infinite)";
            return {};
        case WallShape::cone:
            if (!(w.radius >= 0.0) || !(w.end_radius >= 0.0) || !std::isfinite(w.radius) ||
                !std::isfinite(w.end_radius) || (w.radius == 0.0 && w.end_radius == 0.0))
                return "its radii must be finite, >= 0 and not both 0";
            if (!(w.length > 0.0) || !std::isfinite(w.length)) return "its length must be positive and finite";
            return {};
        case WallShape::mesh:
            if (w.mesh < 0) return "it names no mesh";
            return {};
    }
    return "unknown shape";
}

double largest_curvature(const Wall& w) {
    if (!w.inside) return 0.0;
    if (w.shape == WallShape::cylinder) return 1.0 / w.radius;
    if (w.shape != WallShape::cone) return 0.0;
    const double cos_alpha = w.length / std::hypot(w.length, w.end_radius - w.radius);
    const double narrowest = std::min(w.radius, w.end_radius);
    return narrowest > 0.0 ? cos_alpha / narrowest : std::numeric_limits<double>::infinity();
}

PlacedWall place_wall(const Wall& w, const MotionNow* now) {
    // Still where its surface stays put and its shape is given by its point
    // and normal alone (a rectangle's edge turns with it: one carried by a
    // motion, even a motion that has stopped, is touched in its own frame).
    const bool still = stays_put(w, now) && !(now && w.shape == WallShape::rectangle);
    PlacedWall p{&w, now, w.point, w.normal, still};
    if (now) {
        p.origin = now->axis_point + rotate(w.point - now->start_axis_point, now->turn);
        p.normal = rotate(w.normal, now->turn);
    }
    return p;
}

}  // namespace tumble
