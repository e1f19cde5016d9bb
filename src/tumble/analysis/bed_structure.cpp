// SPDX-License-Identifier: MIT
#include "tumble/analysis/bed_structure.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace tumble::analysis {

void add_energetics(const GrainFrame& f, double cell, std::vector<SpeciesEnergetics>& species) {
    const std::size_t n = f.id.size();
    if (f.velocity.size() != n || f.angular_velocity.size() != n || f.mass.size() != n)
        throw Error("energetics: the frame has no velocities, angular velocities or masses");
    using Key = std::tuple<long, long, long>;
    auto key = [&](const Vec3& x) {
        return Key{std::lround(std::floor(x.x / cell)), std::lround(std::floor(x.y / cell)),
                   std::lround(std::floor(x.z / cell))};
    };
    struct Cell {
        Vec3 momentum;
        double mass = 0.0;
        std::vector<std::size_t> count;
    };
    std::map<Key, Cell> cells;
    for (std::size_t k = 0; k < n; ++k) {
        Cell& c = cells[key(f.position[k])];
        c.count.resize(species.size(), 0);
        c.momentum += f.mass[k] * f.velocity[k];
        c.mass += f.mass[k];
        ++c.count.at(static_cast<std::size_t>(f.tag[k]));
    }
    for (std::size_t k = 0; k < n; ++k) {
        const Cell& c = cells[key(f.position[k])];
        bool mixed = true;
        for (std::size_t s : c.count) mixed = mixed && s >= 2;
        if (!mixed) continue;
        const Vec3 dv = f.velocity[k] - (1.0 / c.mass) * c.momentum;
        const double R = f.radius[k];
        SpeciesEnergetics& e = species.at(static_cast<std::size_t>(f.tag[k]));
        e.fluctuation_sum += 0.5 * f.mass[k] * norm2(dv);
        e.temperature_sum += norm2(dv) / 3.0;
        e.rotation_sum += 0.5 * 0.4 * f.mass[k] * R * R * norm2(f.angular_velocity[k]);
        ++e.grains;
    }
}

AxialStructure axial_structure(const GrainFrame& f, int components, double length, int slices) {
    AxialStructure a;
    const double width = length / slices;
    std::vector<double> volume(static_cast<std::size_t>(slices), 0.0);
    std::vector<Vec3> centroid(static_cast<std::size_t>(slices));
    auto slice_of = [&](double z) {
        return static_cast<std::size_t>(std::clamp(static_cast<int>(std::floor((z + 0.5 * length) / width)), 0,
                                                   slices - 1));
    };
    double total = 0.0;
    for (std::size_t k = 0; k < f.id.size(); ++k) {
        const double v = 4.0 / 3.0 * pi * std::pow(f.radius[k], 3);  // m^3
        const std::size_t s = slice_of(f.position[k].z);
        volume[s] += v;
        centroid[s] += v * Vec3{f.position[k].x, f.position[k].y, 0.0};
        total += v;
    }
    std::vector<std::vector<double>> sum(static_cast<std::size_t>(components), std::vector<double>(volume.size(), 0.0));
    std::vector<std::vector<double>> count = sum;
    for (std::size_t k = 0; k < f.id.size(); ++k) {
        const std::size_t s = slice_of(f.position[k].z);
        const Vec3 c = (1.0 / volume[s]) * centroid[s];
        const auto t = static_cast<std::size_t>(f.tag[k]);
        sum.at(t)[s] += std::hypot(f.position[k].x - c.x, f.position[k].y - c.y);
        count.at(t)[s] += 1.0;
    }
    a.mean_distance = sum;
    for (std::size_t s = 0; s < volume.size(); ++s) {
        a.z.push_back(-0.5 * length + (static_cast<double>(s) + 0.5) * width);
        a.relative_volume.push_back(total > 0.0 ? volume[s] / (total / slices) : 0.0);
        for (int t = 0; t < components; ++t)
            a.mean_distance[t][s] = count[t][s] > 0.0 ? sum[t][s] / count[t][s]
                                                      : std::numeric_limits<double>::quiet_NaN();
    }
    return a;
}

std::vector<double> surface_angle_by_slice(const GrainFrame& f, double inner_radius, double length, int slices) {
    std::vector<GrainFrame> slice(static_cast<std::size_t>(slices));
    const double width = length / slices;
    for (std::size_t k = 0; k < f.id.size(); ++k) {
        const int s = std::clamp(static_cast<int>(std::floor((f.position[k].z + 0.5 * length) / width)), 0, slices - 1);
        GrainFrame& g = slice[static_cast<std::size_t>(s)];
        g.id.push_back(f.id[k]);
        g.position.push_back(f.position[k]);
        g.radius.push_back(f.radius[k]);
        g.tag.push_back(f.tag[k]);
    }
    std::vector<double> angle;
    for (const GrainFrame& g : slice) {
        if (g.id.size() < 10) {
            angle.push_back(std::numeric_limits<double>::quiet_NaN());
            continue;
        }
        const FreeSurface s = find_free_surface(g, inner_radius);
        angle.push_back(std::atan2(-s.up.x, s.up.y) * 180.0 / pi);
    }
    return angle;
}

FlowProfile::FlowProfile(double bin, double depth_max)
    : bin_(bin), sum_(static_cast<std::size_t>(std::ceil(depth_max / bin)), 0.0), count_(sum_.size(), 0.0) {}

void FlowProfile::add(const GrainFrame& f, double inner_radius) {
    if (f.velocity.size() != f.id.size()) throw Error("flow profile: the frame has no velocities");
    const FreeSurface s = find_free_surface(f, inner_radius);
    // Along the surface in the cross-section, pointing downhill (gravity -y).
    Vec3 downhill{-s.up.y, s.up.x, 0.0};
    if (downhill.y > 0.0) downhill = -1.0 * downhill;
    for (std::size_t k = 0; k < f.id.size(); ++k) {
        const double d = std::max(s.depth(f.position[k]), 0.0);
        const auto b = std::min(static_cast<std::size_t>(d / bin_), sum_.size() - 1);
        sum_[b] += dot(f.velocity[k], downhill);
        count_[b] += 1.0;
    }
}

double FlowProfile::velocity(std::size_t k) const {
    return count_[k] > 0.0 ? sum_[k] / count_[k] : std::numeric_limits<double>::quiet_NaN();
}

double FlowProfile::thickness() const {
    for (std::size_t k = 1; k < bins(); ++k) {
        const double above = velocity(k - 1), here = velocity(k);
        if (above > 0.0 && here <= 0.0) return depth(k - 1) + bin_ * above / (above - here);
    }
    return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace tumble::analysis
