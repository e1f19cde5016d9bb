// SPDX-License-Identifier: MIT
// How fast the boundaries of a prepared start blur (docs/BAND-ANALYSIS.md): the
// axial interdiffusion coefficient D(phi) of the two species at each
// boundary between bands, by the Boltzmann-Matano analysis of the
// composition profile across it.
//
// Why. Kohring's argument for the odd band counts rests on small grains
// passing through bands of large ones. Counting grains that cross a whole
// band (band_crossing.hpp) needs many crossings, and a prepared band of
// large grains 20 cm wide is crossed by almost none in a hundred
// revolutions. Its edges, though, blur from the first revolution on: the
// same diffusion, seen where it acts. They blur unevenly: in the long drum
// the large grains run far into a band of small ones while the small
// grains barely enter the large band, so the coefficient depends on the
// composition, and one erf profile (a constant D) does not fit.
//
// The method (Matano 1933, after Boltzmann 1894). A step of phi (the
// species' volume fraction) between two bands, spreading by
// dphi/dt = d/dz (D(phi) dphi/dz) from a sharp start, is a function of
// z / sqrt(t) alone, and
//   D(phi*) = -1 / (2 t) (dz/dphi)(phi*) integral from phi_poor to phi* of (z - z_M) dphi
// with z_M the Matano plane, which splits the step so that as much of the
// species left one side as came to the other. For a constant D this gives
// D at every level (phi = erfc form).
//
// From the band samples: per boundary, the run from first_revolution on is
// cut into blocks of `block_revolutions`; the block's samples are averaged
// per bin (weighted by grains) at the block's mean N (t in revolutions, D
// in m^2 per revolution); the profile over the window (from the boundary
// halfway to the neighbouring boundaries, or to within end_margin of a
// cap) is made
// monotone (pool-adjacent-violators: the noise of a bin of 40 grains would
// otherwise fold z(phi)), and read as z(phi) by linear interpolation. The
// plateaus are the start's compositions of the two bands (the first
// sample's grain-weighted means over each side of the window); a block
// whose profile no longer reaches them within the window (within a tenth of
// the step) is left out: the blur has reached the neighbouring boundary or
// cap, and the step is no longer alone. D is read at three levels of the
// normalised composition u = (phi - phi_poor) / (phi_rich - phi_poor):
// u = 0.25 (mostly the poor species' grains: for phi the small grains'
// fraction, small grains among large), 0.5 and 0.75; dz/dphi by a central
// difference over u +- 0.05 (+-0.1 read an erfc step's D 3.6 % high at
// u = 0.25 and 0.75; +-0.05 within 1 %).
//
// Errors. The blocks of one boundary are not independent (each profile
// holds the whole history), so they are not the units of an interval. A
// boundary's D is the mean of its blocks in the second half of its
// measured span (the step well developed: the start's own blur, a few mm,
// is a small part of the step by then); the boundaries, and across runs
// the seeds, are the independent units: the interval is Student's t of
// the boundaries' mean (series.hpp, independent_mean), not determined with
// fewer than 3.
// Validated on steps spread numerically with a known D(phi), constant and
// varying tenfold, with the noise of 40 grains per bin
// (tests/unit/test_edge_broadening.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "tumble/analysis/bands.hpp"
#include "tumble/analysis/bootstrap.hpp"
#include "tumble/analysis/series.hpp"

namespace tumble::analysis {

// The normalised compositions at which D is read.
inline constexpr std::array<double, 3> edge_levels{0.25, 0.5, 0.75};
// Revolutions per block: a few samples of the blur's growth in a run of 150.
inline constexpr double edge_block_revolutions = 10.0;
// Kept away from a cap: the end layers segregate on their own (BANDS.md).
inline constexpr double edge_end_margin = 0.02;  // m

inline constexpr double nan_value = std::numeric_limits<double>::quiet_NaN();

// One profile: z(phi) of a monotone step, z increasing as phi falls from
// rich to poor. Returns D at phi_poor + u (phi_rich - phi_poor) for each u
// of `levels` (NaN where the level or its +-0.1 lies outside the step), t
// the profile's age.
struct MatanoProfile {
    double matano = nan_value;           // z_M, m
    std::vector<double> D;               // per level, m^2 per unit of t
    double first = nan_value, last = nan_value;  // phi of the monotone profile at its two ends
};
MatanoProfile boltzmann_matano(const std::vector<double>& z, const std::vector<double>& phi,
                               const std::vector<double>& weight, double phi_rich, double phi_poor, double t,
                               const std::vector<double>& levels);

struct EdgeBlock {
    std::size_t boundary = 0;
    double revolutions = 0.0;  // the block's mean N
    double matano = nan_value; // m
    std::array<double, edge_levels.size()> D{nan_value, nan_value, nan_value};  // m^2 per revolution
};

struct EdgeDiffusion {
    std::vector<double> boundaries;            // z of the start's boundaries between bands, m
    std::vector<bool> species_left;            // the species (phi's) band is left of the boundary
    std::vector<EdgeBlock> blocks;             // those measured, by boundary then N
    // Per boundary: the mean of its blocks in the second half of its span.
    std::vector<std::array<double, edge_levels.size()>> boundary_D;
    // Across the boundaries, per level: the mean and its t interval.
    std::array<double, edge_levels.size()> D{nan_value, nan_value, nan_value};
    std::array<Interval, edge_levels.size()> interval{Interval{nan_value, nan_value}, Interval{nan_value, nan_value},
                                                      Interval{nan_value, nan_value}};
    bool determined = false;
    std::string note;  // why not determined
};

// band_edges: the start's edges from cap to cap (DrumRunInfo::band_edges:
// -L/2, the boundaries, L/2); fewer than three: nothing measured (a mixed
// start); nor on a periodic axis (its bands wrap: not done).
EdgeDiffusion edge_diffusion(const BandField& field, const std::vector<double>& band_edges,
                             double first_revolution = edge_block_revolutions,
                             double block_revolutions = edge_block_revolutions);

}  // namespace tumble::analysis
