// SPDX-License-Identifier: MIT
#include "tumble/analysis/depth_mobility.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "tumble/analysis/drum_measure.hpp"
#include "tumble/core/error.hpp"

namespace tumble::analysis {

GrainFrame grain_frame(const ParticleStore& p, double revolutions) {
    std::vector<std::size_t> grains;
    for (std::size_t i = 0; i < p.size(); ++i)
        if (!p.is_kinematic(i)) grains.push_back(i);
    std::sort(grains.begin(), grains.end(), [&](std::size_t a, std::size_t b) { return p.id[a] < p.id[b]; });
    GrainFrame f;
    f.revolutions = revolutions;
    for (std::size_t i : grains) {
        f.id.push_back(p.id[i]);
        f.position.push_back(p.position[i]);
        f.radius.push_back(p.radius[i]);
        f.tag.push_back(p.tag[i]);
        f.velocity.push_back(p.velocity[i]);
        f.angular_velocity.push_back(p.angular_velocity[i]);
        f.mass.push_back(p.mass[i]);
    }
    return f;
}

FreeSurface find_free_surface(const GrainFrame& frame, double inner_radius) {
    if (frame.id.empty()) throw Error("free surface: no grains");
    double volume = 0.0, radius_sum = 0.0;
    Vec3 centroid;
    for (std::size_t k = 0; k < frame.id.size(); ++k) {
        const double r = frame.radius[k], v = r * r * r;  // volume up to 4 pi / 3
        centroid += v * Vec3{frame.position[k].x, frame.position[k].y, 0.0};
        volume += v;
        radius_sum += r;
    }
    centroid *= 1.0 / volume;
    FreeSurface s;
    s.mean_diameter = 2.0 * radius_sum / static_cast<double>(frame.id.size());
    const double reach = inner_radius - 0.5 * s.mean_diameter;  // where grain centres can be
    const double distance = norm(centroid);
    // A bed centred on the axis fills the drum: no free surface to speak of;
    // take "up" as +y so that depths stay defined.
    s.up = distance > 0.0 ? (-1.0 / distance) * centroid : Vec3{0.0, 1.0, 0.0};
    s.level = -reach * std::cos(0.5 * segment_angle(distance, reach));
    return s;
}

DepthMobility::DepthMobility(int components, int layers, double period)
    : components_(components),
      layers_(layers),
      period_(period),
      samples_(static_cast<std::size_t>(std::max(0, components * layers))),
      sum_dz2_per_revolution_(samples_.size()) {
    if (components < 1 || layers < 1) throw Error("depth mobility: need at least one component and one layer");
}

void DepthMobility::add(const GrainFrame& before, const GrainFrame& after, double inner_radius) {
    const FreeSurface surface = find_free_surface(before, inner_radius);
    std::vector<double> depth(before.id.size());
    for (std::size_t k = 0; k < depth.size(); ++k) depth[k] = surface.depth(before.position[k]) / surface.mean_diameter;
    record(before, after, depth);
}

void DepthMobility::add_window(const GrainFrame* frames, std::size_t count, double inner_radius) {
    if (count < 2) throw Error("depth mobility: a window needs at least two frames");
    std::vector<double> depth(frames[0].id.size(), 0.0);
    for (std::size_t f = 0; f < count; ++f) {
        if (frames[f].id != frames[0].id) throw Error("depth mobility: the frames hold different grains");
        const FreeSurface surface = find_free_surface(frames[f], inner_radius);
        for (std::size_t k = 0; k < depth.size(); ++k)
            depth[k] += surface.depth(frames[f].position[k]) / surface.mean_diameter / static_cast<double>(count);
    }
    record(frames[0], frames[count - 1], depth);
}

void DepthMobility::record(const GrainFrame& before, const GrainFrame& after, const std::vector<double>& depth) {
    const double dN = after.revolutions - before.revolutions;
    if (!(dN > 0.0))
        throw Error("depth mobility: the second frame (N = " + std::to_string(after.revolutions) +
                    ") must come after the first (N = " + std::to_string(before.revolutions) + ")");
    if (before.id != after.id) throw Error("depth mobility: the two frames hold different grains");
    for (std::size_t k = 0; k < before.id.size(); ++k) {
        const int c = before.tag[k];
        if (c < 0 || c >= components_)
            throw Error("depth mobility: grain " + std::to_string(before.id[k]) + " has tag " + std::to_string(c) +
                        ", expected 0 .. " + std::to_string(components_ - 1));
        const int layer = static_cast<int>(std::clamp(std::floor(depth[k]), 0.0, layers_ - 1.0));
        double dz = after.position[k].z - before.position[k].z;
        if (period_ > 0.0) dz -= period_ * std::round(dz / period_);
        const auto slot = static_cast<std::size_t>(c * layers_ + layer);
        ++samples_[slot];
        sum_dz2_per_revolution_[slot] += dz * dz / dN;
    }
    ++intervals_;
}

double DepthMobility::msd_per_revolution(int component, int layer) const {
    const std::size_t n = samples(component, layer);
    return n ? at(sum_dz2_per_revolution_, component, layer) / static_cast<double>(n)
             : std::numeric_limits<double>::quiet_NaN();
}

double DepthMobility::share(int component, int layer) const {
    const auto first = sum_dz2_per_revolution_.begin() + component * layers_;
    const double total = std::accumulate(first, first + layers_, 0.0);
    return total > 0.0 ? at(sum_dz2_per_revolution_, component, layer) / total : 0.0;
}

double DepthMobility::occupancy(int component, int layer) const {
    const auto first = samples_.begin() + component * layers_;
    const std::size_t total = std::accumulate(first, first + layers_, std::size_t{0});
    return total ? static_cast<double>(samples(component, layer)) / static_cast<double>(total) : 0.0;
}

}  // namespace tumble::analysis
