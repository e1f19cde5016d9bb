// SPDX-License-Identifier: MIT
// A frame of `tumble render`: the particles of one snapshot in two views side
// by side, at the same scale, each labelled in its corner with the direction
// it is seen from and its axes, above a caption strip with the clock (time,
// and revolutions for a drum) and the legend (a colour per species, and the
// wall). The views (Orientation):
//   the drum  left along the drum axis, seen from +z (x right, y up); right
//             from the side, seen from -x (z right, y up; the drum's rotation
//             carries the bed up on the far side, toward +x);
//   a scenario  both with "up" against gravity, seen along the two other axes.
// Grains are coloured by material or by tag (the palette of the figures,
// tools/palette.txt); wall particles (kinematic) are grey, and in each view
// those nearer to the viewer than the wall's centre are cut away, so that the
// grains inside are seen: the near end cap and mantle half in the axial view,
// the near mantle half in the side view.
// No files: the command reads the snapshots and writes the PNG files.
#pragma once

#include <cstdint>
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
    std::vector<std::int32_t> grain_tags;      // |tag| of the free particles, sorted: the colour index by tag
    void add(const SnapshotParticles& snapshot);
    void add(const Scene& other);
};

// The colours: background, wall, text, and grains by species index (the
// order of tools/palette.txt, cycling), as in the figures.
constexpr Rgb background_colour{22, 24, 30};
constexpr Rgb wall_colour{100, 100, 108};
constexpr Rgb text_colour{225, 225, 230};
Rgb grain_colour(std::size_t index);
std::size_t palette_size();

// The world axes each view shows: `up` in both, `right` per view.
struct Orientation {
    Vec3 up;
    Vec3 right_first, right_second;
};
Orientation drum_orientation();
// Up against gravity's largest component (+z when there is no gravity); the
// views look along the two other axes, in cyclic order.
Orientation orientation_against(const Vec3& gravity);

struct LegendEntry {
    std::string name;
    Rgb colour;
};
// The species of the scene by material (their names) or by tag (tag_names[k]
// for tag k where given, else "tag k"), then the wall if there is one.
std::vector<LegendEntry> scene_legend(const Scene& scene, ColourBy colour_by,
                                      const std::vector<std::string>& tag_names = {});

// How the frames of a movie are drawn.
struct FrameStyle {
    int view_width = 640;  // pixels of each of the two views
    ColourBy colour_by = ColourBy::material;
    Orientation orientation = drum_orientation();
    std::vector<LegendEntry> legend;
};

// The frame's layout: the first view in [0, view_width), the second in
// [view_width, 2 view_width), both as high as the frame box needs; below
// them the caption strip. The frame's height is even.
struct FrameLayout {
    View first, second;
    int text_scale = 1;      // image pixels per font pixel
    int caption_top = 0;     // first row of the caption strip
    int height = 0;          // of the whole frame
};
FrameLayout frame_layout(const Scene& scene, const FrameStyle& style);

// clock: the caption's first line (e.g. "t = 0.50 s, N = 2.00 revolutions").
Image render_frame(const SnapshotParticles& snapshot, const Scene& scene, const FrameStyle& style,
                   const std::string& clock);

}  // namespace tumble::io::render
