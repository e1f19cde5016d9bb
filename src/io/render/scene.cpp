// SPDX-License-Identifier: MIT
#include "io/render/scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>

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

void Scene::add(const SnapshotParticles& snapshot) {
    std::vector<bool> grain_material(snapshot.material_names.size(), false);
    for (std::size_t i = 0; i < snapshot.position.size(); ++i) {
        particles.add(snapshot.position[i], snapshot.radius[i]);
        if (snapshot.kinematic[i])
            wall.add(snapshot.position[i], snapshot.radius[i]);
        else
            grain_material[static_cast<std::size_t>(snapshot.material[i])] = true;
    }
    Scene names;
    for (std::size_t m = 0; m < grain_material.size(); ++m)
        if (grain_material[m]) names.grain_materials.push_back(snapshot.material_names[m]);
    add(names);
}

void Scene::add(const Scene& other) {
    particles.add(other.particles);
    wall.add(other.wall);
    grain_materials.insert(grain_materials.end(), other.grain_materials.begin(), other.grain_materials.end());
    std::sort(grain_materials.begin(), grain_materials.end());
    grain_materials.erase(std::unique(grain_materials.begin(), grain_materials.end()), grain_materials.end());
}

Rgb grain_colour(std::size_t index) {
    static constexpr std::array<Rgb, 6> palette{
        Rgb{235, 110, 40}, Rgb{50, 130, 235}, Rgb{80, 190, 80}, Rgb{240, 205, 50}, Rgb{170, 90, 210}, Rgb{40, 200, 200}};
    return palette[index % palette.size()];
}

std::pair<View, View> scene_views(const Scene& scene, int view_width) {
    constexpr double fill = 0.94;  // of the view the frame box spans, leaving a margin
    const Vec3 extent = scene.particles.hi - scene.particles.lo;
    const double scale = fill * view_width / std::max(extent.x, extent.z);
    const int height = 2 * static_cast<int>(std::ceil(0.5 * extent.y * scale / fill));
    View axial{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, scene.particles.centre(), scale, 0, 0, view_width, height};
    View side{{0.0, 0.0, 1.0}, {0.0, 1.0, 0.0}, scene.particles.centre(), scale, view_width, 0, view_width, height};
    return {axial, side};
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

}  // namespace

Image render_frame(const SnapshotParticles& snapshot, const Scene& scene, ColourBy colour_by, int view_width) {
    const auto [axial, side] = scene_views(scene, view_width);
    Image image(2 * view_width, axial.height, background_colour);
    for (const View& view : {axial, side}) draw_spheres(image, view, visible_spheres(snapshot, scene, colour_by, view));
    return image;
}

}  // namespace tumble::io::render
