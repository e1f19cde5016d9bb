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
// the near mantle half in the side view. The smooth and mesh walls
// (SnapshotParticles::walls) are cut away at the same plane, pixel by pixel;
// what is left is drawn see-through over the grains behind it, with its
// outline and creases (wall_outline) and the edge of the cut (wall_cut) as
// thin light lines.
// No files: the command reads the snapshots and writes the PNG files.
#pragma once

#include <array>
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
    Box particles;  // every particle (with its radius) and wall point of every snapshot: what each view frames
    Box wall;       // the kinematic particles and the smooth walls: its centre is where the cut-away plane passes
    bool wall_particles = false, smooth_walls = false;  // which kinds of wall it has
    std::vector<std::string> grain_materials;  // of the free particles, sorted: the colour order by material
    std::vector<std::int32_t> grain_tags;      // |tag| of the free particles, sorted: the colour index by tag
    void add(const SnapshotParticles& snapshot);
    void add(const Scene& other);
};

// The colours: background, wall, text, and grains by species index (the
// order of tools/palette.txt, cycling), as in the figures.
constexpr Rgb background_colour{22, 24, 30};
constexpr Rgb wall_colour{100, 100, 108};
// The smooth walls: their triangles' colour (laid over what is behind at
// wall_opacity where they face the viewer) and that of their outline.
constexpr Rgb wall_fill_colour{150, 155, 168};
constexpr double wall_opacity = 0.3;
constexpr Rgb wall_line_colour{196, 200, 212};
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

// The lines that draw a wall's shape: the edges of its triangles that bound
// it (one triangle) or join more than two, and the creases, where the
// normals of the two triangles differ by more than 30 degrees (a cylinder's
// facets, 7.5 degrees apart at 48 around, show no line between them; its
// rims and a mesh's lifters do). Triangles share an edge where they share
// vertex indices, as wall_surface and welded meshes give them.
std::vector<std::array<Vec3, 2>> wall_outline(const WallSurface& walls);

// Where the plane through `point` with normal `normal` cuts the walls: a
// segment across each triangle that has corners on both sides of it. The
// edge of the cut-away (the top and bottom of a drum seen from the side).
std::vector<std::array<Vec3, 2>> wall_cut(const WallSurface& walls, const Vec3& point, const Vec3& normal);

struct LegendEntry {
    std::string name;
    Rgb colour;
};
// The species of the scene by material (their names) or by tag (tag_names[k]
// for tag k where given, else "tag k"), then the wall if there is one: "wall"
// in the wall particles' grey or the smooth walls' line colour, or both,
// "wall particles" and "smooth walls".
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
