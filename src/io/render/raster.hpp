// SPDX-License-Identifier: MIT
// A small sphere rasteriser: an RGB image, orthographic views, and spheres
// drawn by splatting (each sphere fills the pixels of its projected disc)
// with a depth buffer and Lambert shading. No files: png.hpp writes the
// image, scene.hpp composes the drum's frames (`tumble render`).
//
// Pixel (i, j) covers [i, i+1) x [j, j+1) with j growing downwards; its
// centre is (i + 0.5, j + 0.5).
#pragma once

#include <cstdint>
#include <vector>

#include "tumble/core/vec3.hpp"

namespace tumble::io::render {

struct Rgb {
    std::uint8_t r = 0, g = 0, b = 0;
    bool operator==(const Rgb&) const = default;
};

class Image {
public:
    Image(int width, int height, Rgb fill = {});
    int width() const { return width_; }
    int height() const { return height_; }
    Rgb at(int x, int y) const;
    void set(int x, int y, Rgb colour);
    // Rows from the top, 3 bytes (r, g, b) per pixel.
    const std::uint8_t* data() const { return rgb_.data(); }
    std::uint8_t* data() { return rgb_.data(); }

private:
    int width_, height_;
    std::vector<std::uint8_t> rgb_;
};

// An orthographic view of the world drawn into a rectangle of an image.
struct View {
    Vec3 right{1.0, 0.0, 0.0};  // unit screen axes in world coordinates, orthogonal
    Vec3 up{0.0, 1.0, 0.0};
    Vec3 centre;                // world point at the centre of the rectangle
    double pixels_per_metre = 1.0;
    int x0 = 0, y0 = 0, width = 0, height = 0;  // the rectangle, pixels

    // Toward the viewer: right x up, so that (right, up, toward) is right-handed.
    Vec3 toward_viewer() const { return cross(right, up); }
    // A world point in image pixels (x right, y down) and its height toward
    // the viewer from `centre` (m).
    Vec3 project(const Vec3& world) const {
        const Vec3 d = world - centre;
        return {x0 + 0.5 * width + pixels_per_metre * dot(d, right), y0 + 0.5 * height - pixels_per_metre * dot(d, up),
                dot(d, toward_viewer())};
    }
};

struct Sphere {
    Vec3 centre;  // m
    double radius = 0.0;
    Rgb colour;
};

// The fraction of its colour that a surface with unit normal n (screen
// coordinates: x right, y up, z toward the viewer) shows: ambient light
// plus Lambert light from above left of the viewer, scaled so that a
// surface facing the viewer shows exactly its colour; capped at 1.
double shade(const Vec3& normal);

// Draws the spheres into the view's rectangle (nothing outside it). Where
// spheres cover the same pixel, the one whose surface is nearer to the
// viewer wins, whatever the order of the list; what the rectangle held
// before counts as infinitely far.
void draw_spheres(Image& image, const View& view, const std::vector<Sphere>& spheres);

}  // namespace tumble::io::render
