// SPDX-License-Identifier: MIT
// The rotating drum of the paper (section 4; SPEC-NOTES "The drum
// experiment"): a horizontal cylinder whose mantle and end caps are made of
// kinematic wall spheres, filled with grains that settle before it turns.
//
// Frame (the drum measurement relies on it): the drum axis is the z axis,
// the drum's centre the origin, gravity (0, -9.81, 0) m/s^2; the drum turns
// about +z (motion 0, axis through the origin). "Left" is z < 0, "right"
// z > 0.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tumble/core/keyword.hpp"
#include "tumble/sim/scenario.hpp"
#include "tumble/walls/clearance.hpp"

namespace tumble {

// What walls the drum: a wall of kinematic spheres (the paper's), smooth
// analytic walls (walls/wall.hpp): the mantle a cylinder of the inner
// radius, the caps two discs in the planes z = +-length/2; or the same with
// the mantle a triangle mesh (walls/mesh.hpp), as a drum from a CAD file.
enum class DrumWalls { particles, smooth, mesh };
inline constexpr std::array<Keyword<DrumWalls>, 3> drum_wall_kinds{{
    {"particles", DrumWalls::particles, "a wall of spheres turning with the drum, as the paper's (the default)"},
    {"smooth", DrumWalls::smooth, "smooth walls: a cylinder of the inner radius and two discs, no wall spheres"},
    {"mesh", DrumWalls::mesh, "the smooth drum with its mantle in triangles (a mesh wall), the caps smooth discs"},
}};

// The space the grains live in: a cylinder `length` long (inner, along z)
// and `diameter` across (inner), walled by spheres of radius wall_radius
// or by smooth walls.
struct DrumGeometry {
    double length = 0.12;         // m
    double diameter = 0.08;       // m
    double wall_radius = 3.0e-3;  // m, radius of the wall spheres (the paper's material 3)
    // No end caps: the axis is periodic with period `length` (a grain that
    // leaves at one end enters at the other), so no cap friction drives
    // axial recirculation. The mantle then has an even number of rings at
    // z = -length/2 + (k + 1/2) x step, and build_drum_scenario makes the
    // domain periodic in z over [-length/2, length/2).
    bool periodic_axis = false;
    // particles: the wall of spheres below (build_drum_wall); smooth: no
    // wall spheres (wall_radius unused), the walls of drum_smooth_walls();
    // mesh: those with the mantle in triangles, `mantle` where given (the
    // user's, from an STL file: a drum with lifters or baffles, in the
    // drum's frame: the axis z through the origin, the caps at z =
    // +-length/2), else drum_mantle_mesh().
    DrumWalls walls = DrumWalls::particles;
    std::shared_ptr<const TriangleMesh> mantle;
};

// The drum wall. Layout (s = 2 wall_radius, the nominal spacing):
//  - mantle: rings of spheres centred on the cylinder of radius
//    inner_radius + wall_radius, from z = -(inner_length/2 + wall_radius) to
//    +(inner_length/2 + wall_radius) at equal axial steps <= s; each ring has
//    the fewest spheres whose neighbours are at most s apart (chord), and
//    neighbouring rings are staggered by half that angle. The two end rings
//    lie in the cap planes and close the corner.
//  - caps: discs at z = +-(inner_length/2 + wall_radius) of concentric rings
//    at equal radial steps <= s inside the mantle's end ring, plus one sphere
//    on the axis, each ring again with neighbours at most s apart.
// So the inner surface of the wall is the cylinder of radius inner_radius
// and the planes z = +-inner_length/2 (the innermost points of the wall
// spheres); no spacing is wider than s, so neighbours touch or overlap
// slightly (with the defaults each sphere's nearest neighbour is 0.896 s to
// s away). Grains nestle a little way into the hollows between wall spheres
// (a settled 2.4 mm grain reaches about 1.5 mm beyond the inner surface).
struct DrumWall {
    std::vector<ParticleSpec> particles;  // kinematic (motion as given), tag -1 (not a grain)
    double inner_radius = 0.0;  // m, distance from the axis to the innermost points of the mantle spheres
    double inner_length = 0.0;  // m, distance between the inner surfaces of the two caps
    // Radius (m) of the largest sphere that could pass through the wall: an
    // upper bound, certified to largest_gap_tolerance, on max over the
    // closed surface S through all wall-sphere centres (the mantle cylinder
    // of radius inner_radius + wall_radius and the two cap discs) of the
    // distance to the nearest wall-sphere centre, minus wall_radius. A grain
    // leaving the drum must have its centre on S at some instant without
    // overlapping a wall sphere, so grains larger than this cannot leak.
    double largest_gap = 0.0;
    std::size_t mantle_particles = 0;
    std::size_t cap_particles = 0;  // both caps together
    std::size_t mantle_rings = 0;
    double axial_step = 0.0;  // m, between mantle rings
};

// Absolute accuracy (m) to which build_drum_wall() computes largest_gap
// (it is an upper bound, at most this much above the true maximum).
inline constexpr double largest_gap_tolerance = 1e-7;

// Builds the wall. Throws tumble::Error naming the parameter if the geometry
// is impossible (length, diameter or wall_radius not positive and finite,
// diameter below 6 wall radii, a negative material or motion index,
// smallest_grain_radius not positive) or if a grain of
// smallest_grain_radius could pass through the wall.
DrumWall build_drum_wall(const DrumGeometry& g, std::int32_t wall_material, std::int32_t motion,
                         double smallest_grain_radius);

// The smooth drum (DrumWalls::smooth), carried by `motion`: the mantle
// "drum", the cylinder about z of radius diameter/2 from z = -length/2 to
// +length/2, grains inside, of `wall_material`; the caps "drum.start" (z =
// -length/2) and "drum.end" (+length/2), discs of the same radius, of
// `cap_material`. With a periodic axis the mantle is infinite and there are
// no caps. The inner surface is where the particle wall's innermost points
// are (DrumWall::inner_radius, inner_length).
std::vector<Wall> drum_smooth_walls(const DrumGeometry& g, std::int32_t wall_material, std::int32_t cap_material,
                                    std::int32_t motion);

// The mantle of the mesh drum (DrumWalls::mesh): the smooth mantle's
// cylinder in facets, in the drum's frame. `segments` around (the fewest,
// at least 48 and a multiple of 8, whose polygon lies within 1 % of
// `grain_radius` of the circle: its sagitta R (1 - cos(pi / segments))),
// rings at z = +-length/2 and between them at axial steps of at most one
// diameter (long panels, as a CAD export makes them: few faces near a
// grain), each quadrilateral in two triangles. Its vertices lie on the
// circle of radius diameter/2, its faces at most the sagitta inside it
// (within the fill's clearance, fill_wall_clearance). Throws tumble::Error
// where the axis is periodic (a mesh has ends).
TriangleMesh drum_mantle_mesh(const DrumGeometry& g, double grain_radius);

// Clearance (as a fraction of the grain radius) that fill_drum_region()
// keeps between a new grain and the inner surface of the wall.
inline constexpr double fill_wall_clearance = 0.02;

// `count` non-overlapping grains of `radius` placed uniformly at random
// inside the drum and between z_lo and z_hi, whole spheres inside: distance
// from the axis <= inner radius - radius (1 + fill_wall_clearance), |z| <=
// length/2 - radius (1 + fill_wall_clearance), z_lo + radius <= z <= z_hi -
// radius; none overlaps another or a sphere of `existing`, nor the smooth
// walls of the same geometry (the clearance keeps them off the inner
// surface, where both kinds of wall lie), nor the walls in `walls` where
// given (a mesh mantle's lifters). Velocities zero, free motion.
// Deterministic for a seed.
// Method: random sequential placement (uniform random positions, each kept
// if it overlaps nothing). It stalls near 30 % solid fraction; if it does,
// the remaining grains go to uniform random positions and all new grains are
// pushed apart (existing spheres stay put) until none overlaps, which works
// up to about 50 %. Throws tumble::Error if the region cannot hold one grain
// or is too full: the grains would fill more than 50 % of it, or pushing
// them apart does not converge.
std::vector<ParticleSpec> fill_drum_region(const DrumGeometry& g, double z_lo, double z_hi, std::size_t count,
                                           double radius, std::int32_t material, std::int32_t tag,
                                           std::uint64_t seed, const std::vector<ParticleSpec>& existing,
                                           const WallDistances* walls = nullptr);

// Of `total` grains of masses m1 and m2, how many of the first kind make the
// two masses most nearly equal (n1 m1 ~ (total - n1) m2): the two masses
// differ by at most (m1 + m2) / 2.
std::size_t equal_mass_count(std::size_t total, double m1, double m2);

// The drum's angular velocity t seconds after the start of rotation, with a
// linear spin-up from rest over `ramp` seconds (0: full speed at once):
// omega min(1, t / ramp), rad/s.
double drum_angular_velocity(double omega, double ramp, double t);

// How a run drives the spin-up: before step k (k = 1 the first step after
// the start of rotation, time step dt) the drum's angular velocity is set to
// its value at the step's middle, so a linear ramp turns the drum by exactly
// omega t^2 / 2T; once more at full speed after the ramp's end, then never
// again. Returns the value to set before step k, or a negative number when
// nothing is to be set.
double spin_up_setting(double omega, double ramp, double dt, std::int64_t k);

// The grains' axial arrangement at the start, before they settle (z along
// the axis, the drum's centre at 0; "small" is material-2, "large"
// material-1):
//   halves      large grains in z < 0, small in z > 0 (self mode: all of
//               material-1, tagged by half);
//   mixed       both species anywhere along the whole length (self mode:
//               tagged by the half they start in);
//   bands       K alternating single-species bands of given widths;
//   boundaries  alternating single-species bands between given z.
enum class Arrangement { halves, mixed, bands, boundaries };
inline constexpr std::array<Keyword<Arrangement>, 4> arrangements{{
    {"halves", Arrangement::halves, "large grains in the left half, small in the right (the default)"},
    {"mixed", Arrangement::mixed, "both species at random along the whole length"},
    {"bands", Arrangement::bands, "K alternating bands of given widths (--bands, --band-widths, --ends)"},
    {"boundaries", Arrangement::boundaries, "alternating bands between given z (--boundaries, --ends)"},
}};

// A problem with the drum's settings: the key (the drum file's) and the reason.
struct DrumFillProblem {
    std::string key;
    std::string reason;
};

enum class Species { small, large };  // material-2, material-1 (or the drum's own materials: DrumMaterials)
inline constexpr std::array<Keyword<Species>, 2> species_names{{
    {"small", Species::small, "material-2, 2.4 mm (or the small grains' own material)"},
    {"large", Species::large, "material-1, 3.6 mm (or the large grains' own material)"},
}};

// The drum's materials and which is which: the large grains (tag 0 in the
// two-component mode; every grain in the self mode), the small grains (tag
// 1), the wall and, if it has its own, the caps. A grain's radius is its
// material's `radius`. The paper's (paper_drum_materials()): material-1,
// material-2 and wall, the caps of the wall's.
struct DrumMaterials {
    std::vector<Material> materials;
    std::vector<std::vector<PairProperties>> pair_properties;  // mu and W of every pair of `materials`
    std::int32_t large = 0;
    std::int32_t small = 1;  // -1: none (allowed in the self mode only)
    std::int32_t wall = 2;
    std::int32_t cap = -1;   // -1: the caps are of the wall's material
    // Whether these are the paper's materials (tumble drum without
    // [[material]] tables); the run records the others.
    bool paper = true;
};
DrumMaterials paper_drum_materials();

// What is wrong with the materials for this mode, if anything: the role
// ("large", "small", "wall", "cap": the key of the drum file's
// [materials]) and the reason. A drum with a periodic axis has no caps.
std::optional<DrumFillProblem> drum_materials_problem(const DrumMaterials& m, const std::string& mode,
                                                      bool periodic_axis = false);

// How the drum is filled, beyond the grain count and the seed, and the
// friction of its end caps. The defaults are the paper's drum.
struct DrumFill {
    Arrangement arrangement = Arrangement::halves;
    // bands: the number of bands K >= 2 and their widths as fractions of the
    // length, summing to 1 (empty: an even fill, band_widths()).
    int bands = 0;
    std::vector<double> band_widths;
    // boundaries: the z (m) between bands, strictly increasing inside
    // (-length/2, length/2); n boundaries make n + 1 bands.
    std::vector<double> boundaries;
    // bands, boundaries: the species of the leftmost band; the species
    // alternate from there (so with an odd number of bands both end bands
    // are of this species, with an even number the right end is the other).
    Species ends = Species::small;
    // Two-component: the small grains' share of the grains' volume, in
    // (0, 1); none: equal masses (equal_mass_count()).
    std::optional<double> small_volume_fraction;
    // Friction coefficient between the grains and the end caps (their
    // spheres, or the smooth caps); none: that of the caps' material (the
    // wall's unless DrumMaterials::cap). Needs end caps.
    std::optional<double> cap_friction;
};

// The name of the caps' own material that cap_friction makes.
inline constexpr const char* drum_cap_material_name = "cap";

// How far from 1 the band widths may sum (they are then scaled to 1).
inline constexpr double band_width_tolerance = 1e-6;

// What is wrong with a fill for this geometry, mode and these materials
// (the grains' radii set the narrowest band), if anything: the key (as
// DrumFill's field, which is the TOML key) and the reason.
std::optional<DrumFillProblem> drum_fill_problem(const DrumGeometry& g, const std::string& mode, const DrumFill& fill,
                                                 const DrumMaterials& materials = paper_drum_materials());

// The widths of the bands of Arrangement::bands, as fractions of the
// length: the fill's, or by default an even fill, the bed as deep in every
// band: each species' share of the grains' volume (small_volume_fraction;
// equal masses of the paper's grains, of one density, are equal volumes)
// split equally among its bands. For an even K with equal volumes these are
// K equal widths; for 3 bands, small at the ends, 1/4, 1/2, 1/4. (Equal
// widths with an odd K put twice the grain volume per length into the
// middle species' bands, and the bed levels itself by an axial flow in the
// first ten revolutions: docs/BAND-ANALYSIS.md.)
std::vector<double> band_widths(const DrumFill& fill);

// The bands of an arrangement along z, left to right, as boundaries z_0 =
// -length/2 < z_1 < ... < z_K = length/2 (halves: 2 bands; mixed: 1).
std::vector<double> band_edges(const DrumGeometry& g, const DrumFill& fill);

// A one-line description of the fill for reports and drum_run.toml, e.g.
// "bands 3 (widths 0.25 0.5 0.25, small at the ends), small volume fraction 0.5".
std::string describe(const DrumFill& fill);

// `total` grains split into counts per band in proportion to the bands'
// widths (edges as band_edges()), the largest remainders rounded up, so the
// counts sum to `total` exactly.
std::vector<std::size_t> counts_per_band(std::size_t total, const std::vector<double>& widths);

struct DrumSetup {
    Scenario scenario;
    DrumWall wall;  // smooth walls: no particles, the inner surface's radius and length
    std::size_t grains_left = 0;   // tag 0 (two-component: the large grains)
    std::size_t grains_right = 0;  // tag 1 (two-component: the small grains)
    double solid_fraction = 0.0;   // grain volume / inner drum volume
};

// The paper's drum experiment, ready to settle:
//  - materials: the used ones of `materials` in the order large, small,
//    wall, cap (each once; the paper's: 0 material-1, 1 material-2, 2 wall)
//    with their pairs' mu and W, the full contact model;
//  - gravity (0, -9.81, 0); motion 0 the drum's rotation about +z through
//    the origin at angular velocity 0 (the bed settles at rest; start the
//    rotation later with Simulation::set_motion(0, ...));
//  - an open domain bounding the drum with a margin;
//  - particles: the grains first (left half, then right half), then the
//    wall's spheres; smooth walls (g.walls): none, and Scenario::walls
//    drum_smooth_walls(), carried by motion 0.
// mode "two-component": the large grains (tag 0) and the small ones (tag
//   1), `grains` in all: equal masses (so N2/N1 ~ 3.375 for the paper's,
//   see equal_mass_count()) or the fill's small_volume_fraction; placed as
//   the fill's arrangement says (halves: large in the left half, small in
//   the right).
// mode "self": `grains` of the large grains' material tagged 0 if they
//   start at z < 0, 1 otherwise; halves: half in each half; mixed:
//   anywhere. (For the same fill level as a two-component drum of `grains`,
//   pass 2 x equal_mass_count(grains, m1, m2).)
// Bands: each species' grains are shared among its bands in proportion to
// their widths (counts_per_band()); each band is filled by
// fill_drum_region() with its own seed from `seed`, so every grain lies
// whole inside its band. The caps' material (materials.cap) goes to every
// wall sphere in the cap planes (the cap discs and the mantle's end rings)
// or to the smooth caps. With cap_friction, one more material "cap" (the
// caps', with that mu against the grains) takes its place there.
// Grains start at random, at rest; they fall when the simulation begins.
// Throws tumble::Error for an unknown mode, no grains, a fill that
// drum_fill_problem() refuses, materials that drum_materials_problem()
// refuses, or a drum that cannot hold them.
DrumSetup build_drum_scenario(const DrumGeometry& g = {}, const std::string& mode = "two-component",
                              std::size_t grains = 1000, std::uint64_t seed = 1, const DrumFill& fill = {},
                              const DrumMaterials& materials = paper_drum_materials());

}  // namespace tumble
