// SPDX-License-Identifier: MIT
#include "io/render/raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

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

void draw_spheres(Image& image, const View& view, const std::vector<Sphere>& spheres) {
    std::vector<float> depth(static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height),
                             -std::numeric_limits<float>::infinity());
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
                float& nearest = depth[static_cast<std::size_t>(j - view.y0) * view.width + (i - view.x0)];
                const auto surface = static_cast<float>(c.z + sphere.radius * nz);
                if (surface <= nearest) continue;
                nearest = surface;
                image.set(i, j, scaled(sphere.colour, shade({nx, ny, nz})));
            }
    }
}

}  // namespace tumble::io::render
