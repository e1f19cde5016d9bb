// SPDX-License-Identifier: MIT
// Segregation and energetics of the bed from particle frames. Frame as in
// drum_measure.hpp: drum axis = z, centre at the origin; components by tag.
//
// Energetics. The paper compares the kinetic energies of the two species in
// the lab frame, where most of a grain's velocity is the mean flow (carried
// up with the wall, rolling down the surface). The fluctuation relative to
// the local mean flow is the granular temperature: in cells of the bed, the
// mass-weighted mean velocity u of all grains in the cell, and per grain
//   fluctuation energy  e_f = 1/2 m |v - u|^2        (J),
//   granular temperature T  = |v - u|^2 / 3           (m^2/s^2),
//   rotational energy   e_r = 1/2 (2/5 m R^2) |w|^2   (J, solid sphere).
// Only cells holding at least two grains of every component count, so the
// species are compared where both are present.
//
// Segregation. Per axial slice: the bed's grain volume relative to a
// uniform bed (1 everywhere if no volume moves along the axis), and per
// component the mean distance of its grains from the slice's centroid in the
// cross-section: a ratio below 1 for the small grains is a radial core.
#pragma once

#include <cstddef>
#include <vector>

#include "tumble/analysis/depth_mobility.hpp"

namespace tumble::analysis {

struct SpeciesEnergetics {
    double fluctuation_sum = 0.0;  // J, sum of e_f
    double temperature_sum = 0.0;  // m^2/s^2, sum of T
    double rotation_sum = 0.0;     // J, sum of e_r
    std::size_t grains = 0;        // grain-frames counted
    double fluctuation() const { return grains ? fluctuation_sum / grains : 0.0; }  // J per grain
    double temperature() const { return grains ? temperature_sum / grains : 0.0; }  // m^2/s^2
    double rotation() const { return grains ? rotation_sum / grains : 0.0; }        // J per grain
};

// Adds one frame (with velocity, angular velocity and mass) to `species`
// (one entry per component), in cubic cells of side `cell` (m). Throws
// tumble::Error for a frame without velocities.
void add_energetics(const GrainFrame& frame, double cell, std::vector<SpeciesEnergetics>& species);

struct AxialStructure {
    std::vector<double> z;                           // slice centres, m
    std::vector<double> relative_volume;             // grain volume / (total / slices)
    std::vector<std::vector<double>> mean_distance;  // [component][slice], m from the slice's centroid in (x, y); NaN if absent
};

// Slices of equal width over [-length/2, length/2].
AxialStructure axial_structure(const GrainFrame& frame, int components, double length, int slices);

// Where the motion happens. The free surface per axial slice:
// find_free_surface() (depth_mobility.hpp) on the grains of each slice, and
// its inclination, degrees: the angle of the surface's normal from the
// vertical, positive when the surface is raised on the +x side (toward
// which the bottom of a drum turning about +z moves). NaN for a slice with
// fewer than 10 grains.
std::vector<double> surface_angle_by_slice(const GrainFrame& frame, double inner_radius, double length, int slices);

// The flowing layer. In the cross-section, a grain's velocity along the
// free surface, downhill positive, against its depth below the surface:
// the surface layer flows down, the bed beneath turns up with the wall;
// the flowing layer's thickness is the depth where the mean velocity
// changes sign (linear between bin centres). Depth bins of `bin` metres
// from the surface down to `depth_max` (grains above the surface count in
// the first bin, deeper ones in the last).
class FlowProfile {
public:
    FlowProfile(double bin, double depth_max);
    // Adds a frame with velocities; throws tumble::Error without them.
    void add(const GrainFrame& frame, double inner_radius);
    std::size_t bins() const { return count_.size(); }
    double depth(std::size_t k) const { return (static_cast<double>(k) + 0.5) * bin_; }  // m, bin centre
    double velocity(std::size_t k) const;  // m/s, mean downhill velocity; NaN if empty
    double thickness() const;              // m; NaN if the velocity never changes sign
private:
    double bin_;
    std::vector<double> sum_, count_;
};

}  // namespace tumble::analysis
