// SPDX-License-Identifier: MIT
// A small sphere rasteriser: an RGB image, orthographic views, and spheres
// drawn by splatting (each sphere fills the pixels of its projected disc)
// with a depth buffer and Lambert shading; then surfaces of triangles and
// lines (the smooth walls) laid over them, see-through, where no sphere is
// nearer. No files: png.hpp writes the image, scene.hpp composes the drum's
// frames (`tumble render`).
//
// Pixel (i, j) covers [i, i+1) x [j, j+1) with j growing downwards; its
// centre is (i + 0.5, j + 0.5).
#pragma once

#include <array>
#include <cstdint>
#include <limits>
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

// Per pixel of a view's rectangle, the height toward the viewer (m, from
// View::centre) of the nearest sphere surface drawn there; -infinity where
// there is none.
class DepthBuffer {
public:
    explicit DepthBuffer(const View& view);
    // Image pixel (i, j), which must lie in the view's rectangle.
    float& at(int i, int j) { return depth_[index(i, j)]; }
    float at(int i, int j) const { return depth_[index(i, j)]; }

private:
    std::size_t index(int i, int j) const {
        return static_cast<std::size_t>(j - y0_) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(i - x0_);
    }
    int x0_, y0_, width_;
    std::vector<float> depth_;
};

// Draws the spheres into the view's rectangle (nothing outside it). Where
// spheres cover the same pixel, the one whose surface is nearer to the
// viewer wins, whatever the order of the list; what the rectangle held
// before counts as infinitely far. The second form keeps the depth of what
// it drew in `depth` (and tests against what is there already).
void draw_spheres(Image& image, const View& view, const std::vector<Sphere>& spheres);
void draw_spheres(Image& image, const View& view, const std::vector<Sphere>& spheres, DepthBuffer& depth);

// Triangles seen through and lines over them: how the smooth walls are drawn.
struct Surface {
    std::vector<std::array<Vec3, 3>> triangles;  // corners, m
    std::vector<std::array<Vec3, 2>> lines;      // ends, m
    Rgb fill, line;
    double opacity = 0.3;  // the fraction of a triangle's shaded colour laid over what is behind it
    // Height toward the viewer from View::centre, m: the parts nearer than
    // this are left out (the cut-away).
    double cut = std::numeric_limits<double>::infinity();
};

// Draws the surface into the view's rectangle: each triangle blended over
// the pixels whose centres it covers, flat-shaded as shade() gives for its
// normal (whichever side faces the viewer), then the lines in their colour,
// unshaded, one pixel wide. A point of either is drawn only where it is
// nearer to the viewer than the sphere in `depth` and not nearer than
// `surface.cut`; `depth` is not changed. Triangles seen edge-on fill no pixel.
void draw_surface(Image& image, const View& view, const Surface& surface, const DepthBuffer& depth);

}  // namespace tumble::io::render
