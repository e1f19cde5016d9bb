// SPDX-License-Identifier: MIT
#include "io/render/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include "io/render/text.hpp"
#include "tumble/core/constants.hpp"

namespace tumble::io::render {

void Box::add(const Vec3& centre, double radius) {
    for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], centre[k] - radius);
        hi[k] = std::max(hi[k], centre[k] + radius);
    }
}

void Box::add(const Box& other) {
    if (other.empty()) return;
    add(other.lo, 0.0);
    add(other.hi, 0.0);
}

namespace {

template <class T>
void sorted_union(std::vector<T>& into, const std::vector<T>& more) {
    into.insert(into.end(), more.begin(), more.end());
    std::sort(into.begin(), into.end());
    into.erase(std::unique(into.begin(), into.end()), into.end());
}

}  // namespace

void Scene::add(const SnapshotParticles& snapshot) {
    std::vector<bool> grain_material(snapshot.material_names.size(), false);
    Scene names;
    for (std::size_t i = 0; i < snapshot.position.size(); ++i) {
        particles.add(snapshot.position[i], snapshot.radius[i]);
        if (snapshot.kinematic[i]) {
            wall.add(snapshot.position[i], snapshot.radius[i]);
            wall_particles = true;
        } else {
            grain_material[static_cast<std::size_t>(snapshot.material[i])] = true;
            names.grain_tags.push_back(std::abs(snapshot.tag[i]));
        }
    }
    for (std::size_t m = 0; m < grain_material.size(); ++m)
        if (grain_material[m]) names.grain_materials.push_back(snapshot.material_names[m]);
    for (const Vec3& v : snapshot.walls.vertices) {
        particles.add(v, 0.0);
        wall.add(v, 0.0);
    }
    smooth_walls = smooth_walls || !snapshot.walls.triangles.empty();
    add(names);
}

void Scene::add(const Scene& other) {
    particles.add(other.particles);
    wall.add(other.wall);
    wall_particles = wall_particles || other.wall_particles;
    smooth_walls = smooth_walls || other.smooth_walls;
    sorted_union(grain_materials, other.grain_materials);
    sorted_union(grain_tags, other.grain_tags);
}

namespace {

// TUMBLE_PALETTE: the colours of tools/palette.txt, "rrggbb rrggbb ..."
// (CMakeLists.txt).
const std::vector<Rgb>& palette() {
    static const std::vector<Rgb> colours = [] {
        std::vector<Rgb> out;
        std::istringstream words(TUMBLE_PALETTE);
        for (std::string hex; words >> hex;) {
            const unsigned long v = std::stoul(hex, nullptr, 16);
            out.push_back({static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>(v >> 8 & 0xff),
                           static_cast<std::uint8_t>(v & 0xff)});
        }
        return out;
    }();
    return colours;
}

}  // namespace

std::vector<std::array<Vec3, 2>> wall_outline(const WallSurface& walls) {
    const double crease = std::cos(30.0 * pi / 180.0);  // cosine of the least angle between normals drawn
    // Each edge (lower vertex index first) and the triangles on it.
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<std::size_t>> edges;
    std::vector<Vec3> normal;
    for (std::size_t t = 0; t < walls.triangles.size(); ++t) {
        const auto& v = walls.triangles[t];
        const Vec3 n = cross(walls.vertices[v[1]] - walls.vertices[v[0]], walls.vertices[v[2]] - walls.vertices[v[0]]);
        const double length = std::sqrt(dot(n, n));
        normal.push_back(length > 0.0 ? (1.0 / length) * n : Vec3{});
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t a = v[k], b = v[(k + 1) % 3];
            edges[{std::min(a, b), std::max(a, b)}].push_back(t);
        }
    }
    std::vector<std::array<Vec3, 2>> lines;
    for (const auto& [edge, on] : edges)
        if (on.size() != 2 || dot(normal[on[0]], normal[on[1]]) < crease)
            lines.push_back({walls.vertices[edge.first], walls.vertices[edge.second]});
    return lines;
}

std::vector<std::array<Vec3, 2>> wall_cut(const WallSurface& walls, const Vec3& point, const Vec3& normal) {
    std::vector<std::array<Vec3, 2>> lines;
    for (const auto& t : walls.triangles) {
        // The points where the plane crosses the triangle's edges (m from the
        // plane: h; an edge from h <= 0 to h > 0 crosses it once).
        std::vector<Vec3> crossing;
        for (int k = 0; k < 3; ++k) {
            const Vec3 &a = walls.vertices[t[k]], &b = walls.vertices[t[(k + 1) % 3]];
            const double ha = dot(a - point, normal), hb = dot(b - point, normal);
            if ((ha <= 0.0) != (hb <= 0.0)) crossing.push_back(a + (ha / (ha - hb)) * (b - a));
        }
        if (crossing.size() == 2) lines.push_back({crossing[0], crossing[1]});
    }
    return lines;
}

Rgb grain_colour(std::size_t index) { return palette()[index % palette().size()]; }
std::size_t palette_size() { return palette().size(); }

Orientation drum_orientation() { return {{0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}}; }

Orientation orientation_against(const Vec3& gravity) {
    int axis = 2;
    for (int k = 0; k < 3; ++k)
        if (std::abs(gravity[k]) > std::abs(gravity[axis])) axis = k;
    Vec3 up, first, second;
    up[axis] = gravity[axis] > 0.0 ? -1.0 : 1.0;
    first[(axis + 1) % 3] = 1.0;
    second[(axis + 2) % 3] = 1.0;
    return {up, first, second};
}

std::vector<LegendEntry> scene_legend(const Scene& scene, ColourBy colour_by, const std::vector<std::string>& tag_names) {
    std::vector<LegendEntry> legend;
    if (colour_by == ColourBy::material) {
        for (std::size_t k = 0; k < scene.grain_materials.size(); ++k)
            legend.push_back({scene.grain_materials[k], grain_colour(k)});
    } else {
        for (const std::int32_t tag : scene.grain_tags) {
            const auto k = static_cast<std::size_t>(tag);
            legend.push_back({k < tag_names.size() ? tag_names[k] : "tag " + std::to_string(tag), grain_colour(k)});
        }
    }
    const bool both = scene.wall_particles && scene.smooth_walls;
    if (scene.wall_particles) legend.push_back({both ? "wall particles" : "wall", wall_colour});
    if (scene.smooth_walls) legend.push_back({both ? "smooth walls" : "wall", wall_line_colour});
    return legend;
}

FrameLayout frame_layout(const Scene& scene, const FrameStyle& style) {
    constexpr double fill = 0.94;  // of the view the frame box spans, leaving a margin
    const int width = style.view_width;
    const Orientation& o = style.orientation;
    const Vec3 extent = scene.particles.hi - scene.particles.lo;
    const auto along = [&](const Vec3& axis) { return std::abs(dot(extent, axis)); };
    const double scale = fill * width / std::max(along(o.right_first), along(o.right_second));
    const int views_height = 2 * static_cast<int>(std::ceil(0.5 * along(o.up) * scale / fill));
    const Vec3 centre = scene.particles.centre();
    FrameLayout layout;
    layout.first = {o.right_first, o.up, centre, scale, 0, 0, width, views_height};
    layout.second = {o.right_second, o.up, centre, scale, width, 0, width, views_height};
    layout.text_scale = std::max(1, static_cast<int>(std::lround(width / 320.0)));
    const int line = text_height(layout.text_scale) + 4 * layout.text_scale;
    layout.caption_top = views_height;
    layout.height = views_height + 2 * line + 2 * layout.text_scale;  // two lines and a margin: even
    return layout;
}

namespace {

std::vector<Sphere> visible_spheres(const SnapshotParticles& snapshot, const Scene& scene, ColourBy colour_by,
                                    const View& view) {
    std::vector<std::size_t> material_colour;
    for (const std::string& name : snapshot.material_names) {
        const auto found = std::lower_bound(scene.grain_materials.begin(), scene.grain_materials.end(), name);
        material_colour.push_back(static_cast<std::size_t>(found - scene.grain_materials.begin()));
    }
    const Vec3 toward = view.toward_viewer(), cut = scene.wall.centre();
    std::vector<Sphere> spheres;
    spheres.reserve(snapshot.position.size());
    for (std::size_t i = 0; i < snapshot.position.size(); ++i) {
        const Vec3& x = snapshot.position[i];
        if (snapshot.kinematic[i]) {
            if (dot(x - cut, toward) <= 0.0) spheres.push_back({x, snapshot.radius[i], wall_colour});
            continue;
        }
        const auto tag = static_cast<std::size_t>(std::abs(snapshot.tag[i]));
        const std::size_t index = colour_by == ColourBy::tag
                                      ? tag
                                      : material_colour[static_cast<std::size_t>(snapshot.material[i])];
        spheres.push_back({x, snapshot.radius[i], grain_colour(index)});
    }
    return spheres;
}

// "+z" for the unit vector along +z.
std::string axis_name(const Vec3& unit) {
    for (int k = 0; k < 3; ++k)
        if (unit[k] != 0.0) return std::string(unit[k] > 0.0 ? "+" : "-") + "xyz"[k];
    return "?";
}

// Each view's corner says how it looks, if the view is wide enough: "seen
// from +z: x right, y up".
void draw_view_label(Image& image, const View& view, int scale) {
    const auto plain = [](const std::string& name) { return name[0] == '+' ? name.substr(1) : name; };
    const std::string label = "seen from " + axis_name(view.toward_viewer()) + ": " + plain(axis_name(view.right)) +
                              " right, " + plain(axis_name(view.up)) + " up";
    if (text_width(label, scale) <= view.width - 4 * scale)
        draw_text(image, view.x0 + 2 * scale, view.y0 + 2 * scale, label, text_colour, scale);
}

// The caption strip: the clock on its first line, the legend (a square of
// each colour, then its name) on the second.
void draw_caption(Image& image, const FrameLayout& layout, const std::vector<LegendEntry>& legend,
                  const std::string& clock) {
    const int s = layout.text_scale, line = text_height(s) + 4 * s;
    const int left = 4 * s, top = layout.caption_top + 2 * s;
    draw_text(image, left, top, clock, text_colour, s);
    int x = left;
    const int y = top + line;
    for (const LegendEntry& entry : legend) {
        for (int dy = 0; dy < text_height(s); ++dy)
            for (int dx = 0; dx < text_height(s); ++dx)
                if (x + dx < image.width()) image.set(x + dx, y + dy, entry.colour);
        x += text_height(s) + 2 * s;
        draw_text(image, x, y, entry.name, text_colour, s);
        x += text_width(entry.name, s) + 3 * text_advance(s);
    }
}

}  // namespace

Image render_frame(const SnapshotParticles& snapshot, const Scene& scene, const FrameStyle& style,
                   const std::string& clock) {
    const FrameLayout layout = frame_layout(scene, style);
    Image image(2 * style.view_width, layout.height, background_colour);
    const std::vector<std::array<Vec3, 2>> outline = wall_outline(snapshot.walls);
    Surface walls{{}, {}, wall_fill_colour, wall_line_colour, wall_opacity};
    for (const auto& v : snapshot.walls.triangles)
        walls.triangles.push_back({snapshot.walls.vertices[v[0]], snapshot.walls.vertices[v[1]],
                                   snapshot.walls.vertices[v[2]]});
    for (const View& view : {layout.first, layout.second}) {
        DepthBuffer depth(view);
        draw_spheres(image, view, visible_spheres(snapshot, scene, style.colour_by, view), depth);
        walls.lines = outline;
        if (!scene.wall.empty()) {
            // The wall particles' cut-away, and half a pixel more, so that
            // the edge of the cut, in its plane, is drawn whole despite round-off.
            const auto edge = wall_cut(snapshot.walls, scene.wall.centre(), view.toward_viewer());
            walls.lines.insert(walls.lines.end(), edge.begin(), edge.end());
            walls.cut = view.project(scene.wall.centre()).z + 0.5 / view.pixels_per_metre;
        }
        draw_surface(image, view, walls, depth);
        draw_view_label(image, view, layout.text_scale);
    }
    draw_caption(image, layout, style.legend, clock);
    return image;
}

}  // namespace tumble::io::render
