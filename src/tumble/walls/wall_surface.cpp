// SPDX-License-Identifier: MIT
#include "tumble/walls/wall_surface.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tumble/core/constants.hpp"

namespace tumble {

namespace {

// Unit vectors e1, e2 with (e1, e2, n) right-handed.
std::array<Vec3, 2> basis(const Vec3& n) {
    const Vec3 other = std::abs(n.x) < 0.9 ? Vec3{1.0, 0.0, 0.0} : Vec3{0.0, 1.0, 0.0};
    Vec3 e1 = cross(other, n);
    e1 = (1.0 / norm(e1)) * e1;
    return {e1, cross(n, e1)};
}

// The corners of a box.
std::array<Vec3, 8> corners(const Domain& box) {
    std::array<Vec3, 8> c;
    for (int k = 0; k < 8; ++k)
        c[static_cast<std::size_t>(k)] = {k & 1 ? box.hi.x : box.lo.x, k & 2 ? box.hi.y : box.lo.y,
                                          k & 4 ? box.hi.z : box.lo.z};
    return c;
}

// A quadrilateral a b c d as two triangles.
void add_quad(WallSurface& s, std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    s.triangles.push_back({a, b, c});
    s.triangles.push_back({a, c, d});
}

// A surface of revolution about the unit axis u through p, from radius r0
// at s0 to r1 at s1 along it: `segments` quadrilaterals around.
void add_revolution(WallSurface& s, const Vec3& p, const Vec3& u, double s0, double r0, double s1, double r1,
                    int segments) {
    const auto [e1, e2] = basis(u);
    const auto first = static_cast<std::uint32_t>(s.vertices.size());
    for (int k = 0; k < segments; ++k) {
        const double phi = 2.0 * pi * k / segments;
        const Vec3 radial = std::cos(phi) * e1 + std::sin(phi) * e2;
        s.vertices.push_back(p + s0 * u + r0 * radial);
        s.vertices.push_back(p + s1 * u + r1 * radial);
    }
    const auto n = static_cast<std::uint32_t>(segments);
    for (std::uint32_t k = 0; k < n; ++k) {
        const std::uint32_t next = (k + 1) % n;
        add_quad(s, first + 2 * k, first + 2 * next, first + 2 * next + 1, first + 2 * k + 1);
    }
}

}  // namespace

WallSurface wall_surface(const PlacedWall& placed, const Domain& bounds, int segments, const TriangleMesh* mesh) {
    const Wall& w = *placed.wall;
    WallSurface s;
    // The box's reach about a point along a direction u, and across it.
    const auto along = [&](const Vec3& p, const Vec3& u) {
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (const Vec3& c : corners(bounds)) {
            lo = std::min(lo, dot(c - p, u));
            hi = std::max(hi, dot(c - p, u));
        }
        return std::array<double, 2>{lo, hi};
    };
    const auto [e1, e2] = basis(w.normal);
    switch (w.shape) {
        case WallShape::plane: {  // a square across the box, about the box's centre seen on the plane
            const Vec3 centre = 0.5 * (bounds.lo + bounds.hi);
            const Vec3 middle = centre - dot(centre - w.point, w.normal) * w.normal;
            const double half = 0.5 * norm(bounds.hi - bounds.lo);
            for (const auto& [a, b] : {std::array<double, 2>{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
                s.vertices.push_back(middle + (a * half) * e1 + (b * half) * e2);
            add_quad(s, 0, 1, 2, 3);
            break;
        }
        case WallShape::rectangle: {
            const Vec3 f = cross(w.normal, w.edge);
            for (const auto& [a, b] : {std::array<double, 2>{-1, -1}, {1, -1}, {1, 1}, {-1, 1}})
                s.vertices.push_back(w.point + (a * w.half_width) * w.edge + (b * w.half_height) * f);
            add_quad(s, 0, 1, 2, 3);
            break;
        }
        case WallShape::disc:
            if (w.hole_radius > 0.0) {  // an annulus: a flat ring of quadrilaterals
                add_revolution(s, w.point, w.normal, 0.0, w.hole_radius, 0.0, w.radius, segments);
                break;
            }
            s.vertices.push_back(w.point);  // a fan about the centre
            for (std::uint32_t k = 0, n = static_cast<std::uint32_t>(segments); k < n; ++k) {
                const double phi = 2.0 * pi * k / segments;
                s.vertices.push_back(w.point + w.radius * (std::cos(phi) * e1 + std::sin(phi) * e2));
                s.triangles.push_back({0, 1 + k, 1 + (k + 1) % n});
            }
            break;
        case WallShape::cylinder: {
            double s0 = 0.0, s1 = w.length;
            if (std::isinf(w.length)) {  // across the box
                const std::array<double, 2> reach = along(w.point, w.normal);
                s0 = reach[0];
                s1 = reach[1];
            }
            add_revolution(s, w.point, w.normal, s0, w.radius, s1, w.radius, segments);
            break;
        }
        case WallShape::cone:
            add_revolution(s, w.point, w.normal, 0.0, w.radius, w.length, w.end_radius, segments);
            break;
        case WallShape::mesh:  // its triangles, placed at the start of its motion
            if (mesh) {
                s.vertices = mesh->vertices;
                s.triangles = mesh->triangles;
            }
            break;
    }
    if (const MotionNow* now = placed.now)  // where the motion has carried it
        for (Vec3& v : s.vertices) v = now->axis_point + rotate(v - now->start_axis_point, now->turn);
    return s;
}

}  // namespace tumble
