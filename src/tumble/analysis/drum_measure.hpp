// SPDX-License-Identifier: MIT
// What the drum experiment measures at one instant (paper section 4;
// SPEC-NOTES "The drum experiment"). Frame: the drum axis is the z axis, its
// centre the origin, gravity along -y. Grains are split into components by
// their tag: in the two-component mode tag 0 is material 1 (started left,
// z < 0) and tag 1 material 2 (started right); in the self-diffusion mode
// the tag is the half a grain started in. Kinematic (wall) particles are
// ignored.
#pragma once

#include <cstddef>
#include <vector>

#include "tumble/core/vec3.hpp"
#include "tumble/particles/particle_store.hpp"

namespace tumble::analysis {

struct DrumFrame {
    double inner_length = 0.12;  // m, the axial extent of the grain space (the bed length L)
    double inner_radius = 0.04;  // m
    int components = 2;          // tags 0 .. components-1
    int profile_bins = 12;       // axial bins of the concentration profile C(z)
    double rotation = 1.0;       // angular velocity of the drum about +z (only its sign is used)
};

struct ComponentState {
    std::size_t grains = 0;
    double mass = 0.0;                 // kg
    double mean_z = 0.0;               // <z>, m from the drum centre
    double mean_z_stderr = 0.0;        // standard error of <z>: std(z) / sqrt(grains), m
    double kinetic_energy = 0.0;       // translational, J (the paper compares velocities)
    double kinetic_per_grain = 0.0;    // J
    std::vector<double> concentration; // C(z): volume fraction of this component per axial bin, -1 if the bin is empty
};

struct DrumState {
    std::vector<ComponentState> components;  // by tag
    // Dynamic angle of repose, degrees: the inclination of the principal
    // (long) axis of the bed's cross-section, which for a bed shaped like a
    // circular segment is parallel to its free surface; positive when the
    // surface is raised on the side toward which the bottom of the drum
    // moves, as a rotating drum does. The few grains that adhesion carries
    // over the top with the wall shift it little, unlike a fit to the
    // highest grains.
    double angle_of_repose = 0.0;
    // Fraction of the drum's cross-section filled by the bed: the circular
    // segment (of the circle the grain centres can reach) whose centroid
    // lies as far from the axis as the bed's centre of mass.
    double fill_fraction = 0.0;
    Vec3 bed_centre;  // centre of mass of all grains, m
};

DrumState measure_drum(const ParticleStore& p, const DrumFrame& frame);

// The circular segment of a circle of radius R whose centroid lies
// `centroid_distance` from the centre (0 <= distance < R; distance R: empty,
// 0: full): its central angle theta, radians. It fills the fraction
// (theta - sin theta) / (2 pi) of the circle, and its chord lies R cos(theta/2)
// from the centre, on the side of the centroid.
double segment_angle(double centroid_distance, double R);
double segment_fill_fraction(double centroid_distance, double R);

}  // namespace tumble::analysis
