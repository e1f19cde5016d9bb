// SPDX-License-Identifier: MIT
// A frame of `tumble render`: the particles of one snapshot in two views side
// by side, at the same scale:
//   left   along the drum axis, seen from +z (x right, y up)
//   right  from the side, seen from -x (z right, y up; the drum's rotation
//          carries the bed up on the far side, toward +x)
// Grains are coloured by material or by tag; wall particles (kinematic) are
// grey, and in each view those nearer to the viewer than the wall's centre
// are cut away, so that the grains inside are seen: the near end cap and
// mantle half in the axial view, the near mantle half in the side view.
// No files: the command reads the snapshots and writes the PNG files.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "io/render/raster.hpp"
#include "io/snapshots.hpp"

namespace tumble::io::render {

enum class ColourBy { material, tag };

// An axis-aligned box, m; empty until something is added.
struct Box {
    Vec3 lo{+std::numeric_limits<double>::infinity(), +std::numeric_limits<double>::infinity(),
            +std::numeric_limits<double>::infinity()};
    Vec3 hi = -lo;
    bool empty() const { return !(lo.x <= hi.x); }
    Vec3 centre() const { return 0.5 * (lo + hi); }
    void add(const Vec3& centre, double radius);
    void add(const Box& other);
};

// What is common to every frame of a movie: gathered from all its snapshots.
struct Scene {
    Box particles;  // every particle of every snapshot, with its radius: what each view frames
    Box wall;       // the kinematic particles: its centre is where the cut-away plane passes
    std::vector<std::string> grain_materials;  // of the free particles, sorted: the colour order by material
    void add(const SnapshotParticles& snapshot);
    void add(const Scene& other);
};

// The colours: background, wall, and grains (by material or tag index, cycling).
constexpr Rgb background_colour{22, 24, 30};
constexpr Rgb wall_colour{100, 100, 108};
Rgb grain_colour(std::size_t index);

// The two views for frames whose views are `view_width` pixels wide: the
// axial view in [0, view_width), the side view in [view_width, 2 view_width);
// the height is even and as the frame box needs.
std::pair<View, View> scene_views(const Scene& scene, int view_width);

Image render_frame(const SnapshotParticles& snapshot, const Scene& scene, ColourBy colour_by, int view_width);

}  // namespace tumble::io::render
