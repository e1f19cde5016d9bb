// SPDX-License-Identifier: MIT
#include "io/render/raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace tumble::io::render {

Image::Image(int width, int height, Rgb fill)
    : width_(width), height_(height), rgb_(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3) {
    for (std::size_t k = 0; k < rgb_.size(); k += 3) {
        rgb_[k] = fill.r;
        rgb_[k + 1] = fill.g;
        rgb_[k + 2] = fill.b;
    }
}

Rgb Image::at(int x, int y) const {
    const std::uint8_t* p = &rgb_[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + x) * 3];
    return {p[0], p[1], p[2]};
}

void Image::set(int x, int y, Rgb colour) {
    std::uint8_t* p = &rgb_[(static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + x) * 3];
    p[0] = colour.r;
    p[1] = colour.g;
    p[2] = colour.b;
}

namespace {

// Light from above left, in front of the image plane (screen coordinates).
const Vec3 light = (1.0 / std::sqrt(0.35 * 0.35 + 0.45 * 0.45 + 1.0)) * Vec3{-0.35, 0.45, 1.0};
constexpr double ambient = 0.25;

Rgb scaled(Rgb c, double f) {
    auto channel = [f](std::uint8_t v) { return static_cast<std::uint8_t>(std::lround(f * v)); };
    return {channel(c.r), channel(c.g), channel(c.b)};
}

// The pixel index range [lo, hi) whose centres may lie within [a - r, a + r],
// clipped to [first, first + count).
std::pair<int, int> pixel_span(double a, double r, int first, int count) {
    const double lo = std::clamp(std::floor(a - r), double(first), double(first + count));
    const double hi = std::clamp(std::ceil(a + r), double(first), double(first + count));
    return {static_cast<int>(lo), static_cast<int>(hi)};
}

}  // namespace

double shade(const Vec3& normal) {
    const double diffuse = (1.0 - ambient) / light.z;  // facing the viewer (n = z): exactly 1
    return std::min(1.0, ambient + diffuse * std::max(0.0, dot(normal, light)));
}

DepthBuffer::DepthBuffer(const View& view)
    : x0_(view.x0), y0_(view.y0), width_(view.width),
      depth_(static_cast<std::size_t>(std::max(0, view.width)) * static_cast<std::size_t>(std::max(0, view.height)),
             -std::numeric_limits<float>::infinity()) {}

void draw_spheres(Image& image, const View& view, const std::vector<Sphere>& spheres) {
    DepthBuffer depth(view);
    draw_spheres(image, view, spheres, depth);
}

void draw_spheres(Image& image, const View& view, const std::vector<Sphere>& spheres, DepthBuffer& depth) {
    for (const Sphere& sphere : spheres) {
        const Vec3 c = view.project(sphere.centre);
        const double px = c.x, py = c.y, r = view.pixels_per_metre * sphere.radius;
        const auto [i_lo, i_hi] = pixel_span(px, r, view.x0, view.width);
        const auto [j_lo, j_hi] = pixel_span(py, r, view.y0, view.height);
        for (int j = j_lo; j < j_hi; ++j)
            for (int i = i_lo; i < i_hi; ++i) {
                const double nx = (i + 0.5 - px) / r, ny = (py - j - 0.5) / r;  // unit normal, screen coordinates
                const double q = 1.0 - nx * nx - ny * ny;
                if (q < 0.0) continue;
                const double nz = std::sqrt(q);
                float& nearest = depth.at(i, j);
                const auto surface = static_cast<float>(c.z + sphere.radius * nz);
                if (surface <= nearest) continue;
                nearest = surface;
                image.set(i, j, scaled(sphere.colour, shade({nx, ny, nz})));
            }
    }
}

namespace {

// Whether a point of a surface at height z toward the viewer shows at pixel
// (i, j): in front of the sphere there, not in the part cut away.
bool shows(const DepthBuffer& depth, int i, int j, double z, double cut) {
    return z <= cut && z > depth.at(i, j);
}

Rgb blend(Rgb under, Rgb over, double opacity) {
    auto channel = [opacity](std::uint8_t a, std::uint8_t b) {
        return static_cast<std::uint8_t>(std::lround((1.0 - opacity) * a + opacity * b));
    };
    return {channel(under.r, over.r), channel(under.g, over.g), channel(under.b, over.b)};
}

// Twice the signed area of the triangle (p, q, pixel point (x, y)) in
// pixels^2, zero on the line p q; its sign tells the side. Computed from the
// same end whichever way the edge is taken, so that edge(q, p) is exactly
// -edge(p, q).
double edge(const Vec3& p, const Vec3& q, double x, double y) {
    if (p.x > q.x || (p.x == q.x && p.y > q.y)) return -edge(q, p, x, y);
    return (q.x - p.x) * (y - p.y) - (q.y - p.y) * (x - p.x);
}

// Whether a pixel centre exactly on the edge p -> q of a triangle (corners
// in the order that makes its area positive) is the triangle's: two
// triangles that share the edge go along it in opposite directions, so
// exactly one of them takes such a pixel, and a see-through surface is not
// laid twice along its inner edges.
bool owns(const Vec3& p, const Vec3& q) { return q.y > p.y || (q.y == p.y && q.x < p.x); }

void fill_triangle(Image& image, const View& view, const std::array<Vec3, 3>& corners, const Surface& surface,
                   const DepthBuffer& depth) {
    const Vec3 a = view.project(corners[0]);
    Vec3 b = view.project(corners[1]), c = view.project(corners[2]);
    // Twice the area in pixels^2; a triangle seen edge-on covers no pixel centre.
    double area = edge(a, b, c.x, c.y);
    if (std::abs(area) < 1e-9) return;
    if (area < 0.0) {
        std::swap(b, c);
        area = -area;
    }
    const Vec3 n = cross(corners[1] - corners[0], corners[2] - corners[0]);
    Vec3 facing{dot(n, view.right), dot(n, view.up), dot(n, view.toward_viewer())};
    facing = (facing.z < 0.0 ? -1.0 : 1.0) / std::sqrt(dot(facing, facing)) * facing;
    const Rgb colour = scaled(surface.fill, shade(facing));
    const double x_lo = std::min({a.x, b.x, c.x}), x_hi = std::max({a.x, b.x, c.x});
    const double y_lo = std::min({a.y, b.y, c.y}), y_hi = std::max({a.y, b.y, c.y});
    const auto [i_lo, i_hi] = pixel_span(0.5 * (x_lo + x_hi), 0.5 * (x_hi - x_lo), view.x0, view.width);
    const auto [j_lo, j_hi] = pixel_span(0.5 * (y_lo + y_hi), 0.5 * (y_hi - y_lo), view.y0, view.height);
    const auto inside = [](double e, const Vec3& p, const Vec3& q) { return e > 0.0 || (e == 0.0 && owns(p, q)); };
    for (int j = j_lo; j < j_hi; ++j)
        for (int i = i_lo; i < i_hi; ++i) {
            const double x = i + 0.5, y = j + 0.5;
            // Each corner's weight is the area of the triangle the pixel
            // centre makes with the opposite edge: all >= 0 inside.
            const double ea = edge(b, c, x, y), eb = edge(c, a, x, y), ec = edge(a, b, x, y);
            if (!inside(ea, b, c) || !inside(eb, c, a) || !inside(ec, a, b)) continue;
            if (shows(depth, i, j, (ea * a.z + eb * b.z + ec * c.z) / area, surface.cut))
                image.set(i, j, blend(image.at(i, j), colour, surface.opacity));
        }
}

// A step of at most a pixel along the line, from end to end.
void draw_line(Image& image, const View& view, const std::array<Vec3, 2>& ends, const Surface& surface,
               const DepthBuffer& depth) {
    const Vec3 a = view.project(ends[0]), b = view.project(ends[1]);
    const int steps = static_cast<int>(std::ceil(std::max(std::abs(b.x - a.x), std::abs(b.y - a.y))));
    for (int s = 0; s <= steps; ++s) {
        const double t = steps == 0 ? 0.0 : static_cast<double>(s) / steps;
        const Vec3 p = a + t * (b - a);
        const int i = static_cast<int>(std::floor(p.x)), j = static_cast<int>(std::floor(p.y));
        if (i < view.x0 || i >= view.x0 + view.width || j < view.y0 || j >= view.y0 + view.height) continue;
        if (shows(depth, i, j, p.z, surface.cut)) image.set(i, j, surface.line);
    }
}

}  // namespace

void draw_surface(Image& image, const View& view, const Surface& surface, const DepthBuffer& depth) {
    for (const auto& corners : surface.triangles) fill_triangle(image, view, corners, surface, depth);
    for (const auto& ends : surface.lines) draw_line(image, view, ends, surface, depth);
}

}  // namespace tumble::io::render
