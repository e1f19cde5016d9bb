// SPDX-License-Identifier: MIT
// Settings of the drum experiment (`tumble drum`), from an optional TOML file
// (examples/drum_*.toml; docs/DRUM.md lists every key) and the command line,
// which wins. Defaults are the paper's set-up with a reduced number of
// revolutions.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "tumble/contact/contact_law.hpp"
#include "tumble/setup/drum.hpp"
#include "tumble/setup/paper_materials.hpp"

namespace tumble::io {

enum class SpeedUnit { rad_per_s, rpm, froude };

struct DrumSettings {
    // inner length, inner diameter, wall-particle radius (m), periodic
    // axis, the walls' kind ([drum] walls: particles, smooth or mesh), and
    // a mesh mantle's triangles (read from `mesh` by load_drum_mantle())
    DrumGeometry geometry;
    // [drum] mesh, --mesh: the STL file of the mantle of a mesh drum (its
    // lifters and baffles with it), in the drum's frame; empty: the smooth
    // mantle in triangles. mesh_scale: the file's unit in m (1e-3: mm).
    std::filesystem::path mesh;
    double mesh_scale = 1.0;
    std::string mode = "two-component";  // or "self"
    // The axial arrangement at the start, the species' volume shares and the
    // caps' friction (setup/drum.hpp; [fill] arrangement, bands, band_widths,
    // boundaries, ends, small_volume_fraction; [drum] cap_friction).
    DrumFill fill;
    std::size_t grains = 1000;         // total number of grains
    // If > 0, the fill fraction (bed cross-section over drum cross-section)
    // to aim at instead of `grains`: the grain count is chosen so that the
    // grains at a packing fraction of 0.6 fill that fraction of the drum.
    double fill_fraction = 0.0;
    std::uint64_t seed = 1;
    double speed = 5.0;                // in `speed_unit`
    SpeedUnit speed_unit = SpeedUnit::rad_per_s;
    // Linear spin-up from rest to omega over this time, s (0: the drum
    // starts at full speed); revolutions are counted at full speed from the
    // start, N = omega t / 2 pi, so the ramp ends at N = omega T / 2 pi.
    double spin_up_time = 0.0;
    double revolutions = 12.0;         // after the bed has settled (the MSD's D needs 5 blocks of 2 after N = 1)
    // If > 0: end the rotation early, once the band count has differed from
    // its value at the start for this many revolutions
    // (analysis::band_count_changed; docs/BAND-ANALYSIS.md): a prepared start's
    // bands merged, lost an end band or dissolved. 0: every revolution.
    double until_band_change = 0.0;
    int samples_per_revolution = 20;
    int profile_bins = 12;
    int band_bins = 0;                 // axial bins of the band profile (docs/BAND-ANALYSIS.md); 0: L / 4 mm
    int snapshots_per_revolution = 8;  // per-particle snapshots (snapshots/NNNNNN.csv, 000000 at N = 0;
                                       // the grains' axial MSD needs them); 0: none
    double settle_speed = 0.01;        // m/s: settled when the rms grain speed is below this
    double settle_max_time = 3.0;      // s: give up settling (with a warning) after this
    double dt = 0.0;                   // s; 0: chosen from the materials
    // m: the neighbour list's skin, the margin beyond contact within which
    // pairs are listed; the list is rebuilt when a sphere has moved half of
    // it (0: 0.3 x the largest radius, drum_skin_per_radius of
    // experiments/drum_setup.hpp). Speed only: it changes which pairs
    // are listed, not the forces (LAMMPS's `neighbor` distance).
    double skin = 0.0;
    ShearModel shear = ShearModel::Paper;              // the reading of the friction limit (docs/MODEL.md)
    FrictionNormal friction_normal = FrictionNormal::Net;  // which normal force limits friction
    TangentialStiffness tangential_stiffness = TangentialStiffness::Paper;  // the shear and twisting springs
    // J/m^2: if given, the surface energy W of every pair (grains, wall,
    // caps), which sets the attraction (eq. 7) and the pull-off force
    // 2 pi W R*; 0 for cohesionless grains (docs/DRUM.md). None: each pair's
    // own W, the paper's 0.2 for the paper's materials.
    std::optional<double> surface_energy;
    // The grains', the wall's and the caps' materials and their pairs:
    // the paper's, or the drum file's [[material]], [[pair]] and
    // [materials] tables (docs/DRUM.md, "Materials").
    DrumMaterials materials = paper_drum_materials();
    std::filesystem::path output = "drum-out";

    // Angular velocity in rad/s: from rpm (2 pi / 60) or from the Froude
    // number Fr = omega^2 R / g with R the inner radius and g = 9.81 m/s^2.
    double omega() const;

    // The number of grains to make: `grains`, or the count that gives
    // `fill_fraction` (see above) with the grains' radii.
    std::size_t grain_count() const;

    // W of every pair of the drum that can touch (a grain and a grain, the
    // wall or a cap): surface_energy if given, else the one W all those
    // pairs share; none if they differ.
    std::optional<double> uniform_surface_energy() const;
};

// Reads a drum TOML file over the defaults; ConfigError names file, key, reason.
DrumSettings load_drum_settings(const std::filesystem::path& file);

// Reads the mantle's STL file (`mesh`, its coordinates times mesh_scale)
// into geometry.mantle; none where `mesh` is empty. A file given makes the
// walls "mesh" where they are still the default (particles); with smooth
// walls, or a periodic axis, it is refused. ConfigError with `source` as
// the file and the key `key` (drum.mesh, or --mesh on the command line),
// naming the STL file and, for a bad triangle, its place in it.
void load_drum_mantle(DrumSettings& s, const std::string& source, const std::string& key);

// Checks values that the command line may have set; ConfigError with
// `source` (e.g. "command line") as the file, the key and, in the reason,
// the command-line option.
void check_drum_settings(const DrumSettings& s, const std::string& source);

}  // namespace tumble::io
