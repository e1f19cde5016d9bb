// SPDX-License-Identifier: MIT
// Where in the bed the axial motion happens. The paper (section 4) reads
// from its videos that single-species diffusion "is initiated at the free
// surface of the granulate, diffusion in the bulk plays a subordinate role",
// while in the two-component drum the small grains "diffuse through
// material 1 not only at the surfaces, but also in the bulk". This measures
// it: between two instants N0 < N1 (revolutions) every grain's axial
// displacement dz = z(N1) - z(N0) is attributed to its depth below the free
// surface at N0, and per component and depth layer the result is the mean
// squared axial displacement per revolution <dz^2> / (N1 - N0), m^2/rev
// (for a random walk, twice the local axial diffusion coefficient).
//
// Frame as in drum_measure.hpp: drum axis = z, centre at the origin.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tumble/core/vec3.hpp"
#include "tumble/particles/particle_store.hpp"

namespace tumble::analysis {

// The free grains at one instant, sorted by global id.
struct GrainFrame {
    double revolutions = 0.0;  // N since the start of rotation
    std::vector<std::int64_t> id;
    std::vector<Vec3> position;       // m
    std::vector<double> radius;       // m
    std::vector<std::int32_t> tag;    // component
    // Filled where known (empty otherwise): for the energetics (bed_structure.hpp).
    std::vector<Vec3> velocity;          // m/s
    std::vector<Vec3> angular_velocity;  // rad/s
    std::vector<double> mass;            // kg
};

GrainFrame grain_frame(const ParticleStore& p, double revolutions);

// The free surface of the bed in the cross-section (x, y). The bed is taken
// as the circular segment of the circle the grain centres can reach (radius
// inner_radius minus the mean grain radius) whose centroid is the bed's
// volume-weighted centroid; its chord is the free surface. `up` is the unit
// normal of the chord pointing from the bed toward the axis (in the x-y
// plane), and a grain centre x lies `level - x.up` below the surface.
struct FreeSurface {
    Vec3 up;
    double level = 0.0;          // m, along `up` from the axis
    double mean_diameter = 0.0;  // m, of the grains
    double depth(const Vec3& x) const { return level - dot(x, up); }
};

FreeSurface find_free_surface(const GrainFrame& frame, double inner_radius);

// Accumulates axial displacements by depth over any number of intervals.
// Depth layers are one mean grain diameter thick: layer k holds depths in
// [k, k + 1) diameters, layer 0 also everything above the surface, the last
// layer everything deeper.
class DepthMobility {
public:
    // period > 0: the axis is periodic with this period (m); a displacement
    // is taken to the nearest image (grains move far less than period / 2
    // between the frames compared).
    DepthMobility(int components, int layers, double period = 0.0);

    // Adds the interval from `before` to `after` (the same grains; throws
    // tumble::Error otherwise, or if after.revolutions <= before.revolutions).
    void add(const GrainFrame& before, const GrainFrame& after, double inner_radius);
    // Adds the window frames[0 .. count-1] (the same grains, in time order):
    // each grain's axial displacement from the first frame to the last,
    // attributed to its mean depth over the window's frames. For lags of a
    // revolution or more, over which a grain passes through several depths:
    // where the grains that move far along the axis spend their time.
    void add_window(const GrainFrame* frames, std::size_t count, double inner_radius);

    int components() const { return components_; }
    int layers() const { return layers_; }
    std::size_t intervals() const { return intervals_; }
    // Grain-intervals counted in a layer.
    std::size_t samples(int component, int layer) const { return at(samples_, component, layer); }
    // <dz^2> / dN in the layer, m^2/rev; NaN where a layer had no grain.
    double msd_per_revolution(int component, int layer) const;
    // The layer's share of the component's whole axial sum of dz^2 / dN
    // (the shares of a component add up to 1).
    double share(int component, int layer) const;
    // The fraction of the component's grain-intervals spent in the layer.
    double occupancy(int component, int layer) const;

private:
    // Accumulates dz^2 / dN of each grain at its depth (mean grain diameters).
    void record(const GrainFrame& before, const GrainFrame& after, const std::vector<double>& depth);
    template <class T>
    const T& at(const std::vector<T>& v, int component, int layer) const {
        return v.at(static_cast<std::size_t>(component * layers_ + layer));
    }
    int components_, layers_;
    double period_;
    std::size_t intervals_ = 0;
    std::vector<std::size_t> samples_;
    std::vector<double> sum_dz2_per_revolution_;
};

}  // namespace tumble::analysis
