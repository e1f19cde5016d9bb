// SPDX-License-Identifier: MIT
// The flowing layer of a rotating drum in its own coordinates
// (docs/FIELDS.md, "The drum's frame"): the free surface found on the
// coarse-grained cross-section, the grains and contacts carried into the
// frame of that surface, and the numbers of the depth profile.
//
// Frame: the drum's axis is the z axis through the origin, gravity along -y,
// the drum turning about +z (drum_measure.hpp), so that the surface is raised
// on the +x side and the grains at the surface flow toward -x.
//
// The drum's coordinates (s, d, z), right-handed:
//   t = -(cos a, sin a, 0)   along the surface, downhill for a > 0 (the flow's direction)
//   n = (-sin a, cos a, 0)   the surface's normal, out of the bed (n.y > 0)
//   s = t . r                position along the surface, m; 0 at the foot of the
//                            perpendicular from the axis (the chord's middle)
//   d = level - n . r        depth below the surface, m (> 0 in the bed)
//   z                        the axis, unchanged
// with a the surface's angle (the dynamic angle of repose) and `level` the
// signed distance of the surface line from the axis along n (< 0 for a drum
// less than half full). A vector's components in the frame are (t . v,
// -n . v, v_z): e_s x e_d = e_z.
#pragma once

#include "tumble/analysis/coarse_grain.hpp"
#include "tumble/analysis/simulation_fields.hpp"

namespace tumble::analysis {

struct DrumSurface {
    double angle = 0.0;          // a, rad: the surface's inclination, > 0 raised on the +x side
    double level = 0.0;          // m, the surface line's distance from the axis along n
    double half_length = 0.0;    // m, half the chord of the circle the grain centres reach at `level`
    double solid_fraction = 0.0; // phi_ref, the bed's: the median of phi over the cross-section's nodes weighted by phi
    int columns = 0;             // the columns of the last fit
    int iterations = 0;          // fits until the angle settled

    Vec3 along() const;   // t, downhill
    Vec3 normal() const;  // n, out of the bed
    // (s, d, z) of a point r, and a vector's components (t . v, -n . v, v_z).
    Vec3 point(const Vec3& r) const;
    Vec3 vector(const Vec3& v) const;
};

// The free surface of a drum's cross-section: `cross_section` resolved in x
// and y and averaged along z (tumble::Error otherwise), `reach` the largest
// distance of a grain centre from the axis, m, and `span` the middle part of
// the surface's length that the fit uses, in (0, 1].
//
// The surface is the line where the solid fraction phi (bilinear between the
// nodes) falls to phi_ref / 2, half the bed's (phi_ref the median of phi
// weighted by phi: half the grains' volume lies where phi >= phi_ref): along columns normal to the
// current line, spaced by the grid's cell across the middle `span` of the
// chord (the circle of radius `reach` cut by the line), each column's first
// crossing of phi_ref / 2 coming down from above; the line fitted to the
// crossings by least squares (offset along n against s) gives the next angle
// and level, until the angle changes by less than 1e-6 rad (at most 100
// fits). The first line: the long principal axis of phi's second moments
// (parallel to the chord for a bed shaped like a circular segment), through
// the first crossing of the column through the axis. tumble::Error when no
// surface is found (no column crosses, or the line misses the circle).
DrumSurface find_drum_surface(const Fields& cross_section, double reach, double span);

// The state in the drum's coordinates: positions to (s, d, z), velocities,
// forces and branches to their components along (t, -n, z).
GrainState to_drum_frame(const GrainState& state, const DrumSurface& surface);

// The depth profile of fields averaged in the lab, for fields taken during
// a run, whose surface is known only at its end: `cross_section` (resolved
// in x and y, averaged along z) carried onto `profile`, a grid in the
// drum's coordinates (resolved along d, averaged along z; its cells along s
// within the surface's chord). Each node takes the mean, over its cell's
// extent along s, of the cross-section's averages (bilinear between its
// nodes, at points a quarter of its smaller cell apart) along the line at
// its depth: density, solid fraction, mass x diameter, momentum and the two
// stresses, the vectors and tensors turned into the frame (v' = (t . v, -n
// . v, v_z), T' = Q T Q^T with Q's rows t, -n, z); the velocity, pressure
// and the rest follow from them as FieldAccumulator::finish derives them.
// For a steady surface this is the profile of the same states carried into
// the frame grain by grain and coarse-grained there (to_drum_frame), but for
// the kernel's ends at the span's edges and the interpolation
// (docs/FIELDS.md, "During a run"); the kinetic stress is about the lab
// grid's mean velocity. tumble::Error for grids of other shapes.
Fields drum_profile_of(const Fields& cross_section, const DrumSurface& surface, const CgSettings& profile);

// The depth profile's shear rate and inertial number from the whole velocity
// gradient in the plane (s, d). Averaged along s, the profile has only the
// gradient along d: |du_s/dd| in a layer sheared along the surface, but in
// the bed below, which turns with the drum as a solid, the drum's angular
// velocity: a rotation, not a strain. `across` holds the same samples'
// fields on the profile's depth nodes at two points across its span (its
// grid: 2 cells along s over the profile's extent, the profile's along d,
// averaged along z; tumble::Error otherwise); their difference over the
// cells' spacing is the gradient along s, whose du_d/ds cancels the
// rotation's du_s/dd. Each depth's shear rate becomes gamma_dot of that
// gradient (shear_rate_of), its I follows (inertial_number_at).
void use_in_plane_shear_rate(Fields& profile, const Fields& across);

// The numbers of a depth profile: fields in the drum's coordinates resolved
// along d (the grid's y) only.
struct FlowingLayer {
    // u(0): the velocity along the surface, downhill positive, at the
    // surface (d = 0, linear between the nodes), m/s
    double surface_velocity = 0.0;
    // The flowing layer's thickness: the first depth below the surface where
    // u changes sign from downhill to uphill (the bed turning with the drum),
    // linear between the nodes, m; NaN if it does not
    double thickness = 0.0;
    // The mass-weighted mean grain diameter of the profile, m
    double diameter = 0.0;
};
FlowingLayer flowing_layer(const Fields& profile);

}  // namespace tumble::analysis
