// SPDX-License-Identifier: MIT
// Axial self-diffusion from the mean squared displacement (MSD) of single
// grains. For grains that move at random along the axis,
//   MSD(tau) = <(z(N0 + tau) - z(N0))^2> = 2 D tau + c,     m^2,
// tau the lag in revolutions, D in m^2 per revolution, once tau exceeds the
// time over which a grain's axial steps are correlated (in a drum about a
// revolution: a grain is carried up with the wall and rolls down the free
// surface once or twice a turn); the constant c absorbs the shorter times.
// D is half the slope of the MSD against tau in that long-lag regime.
//
// End caps stop a grain: a window is used only if the grain starts farther
// from a cap than cap_margin x sqrt(2 D0 tau), D0 a first, generous guess
// (the MSD of the shortest lag over twice that lag). Conditioning on the
// start alone, not on the path, keeps the estimate unbiased.
//
// Errors: the run is cut into blocks of revolutions and only windows that
// lie inside one block count, so blocks share no displacement and are close
// to independent (a grain's position at a block's end is all they share);
// blocks, and seeds, are then the units of a bootstrap (bootstrap.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "tumble/analysis/bootstrap.hpp"
#include "tumble/analysis/depth_mobility.hpp"

namespace tumble::analysis {

// Axial positions of a set of grains at equally spaced instants.
struct AxialTracks {
    std::vector<double> revolutions;     // N of each frame, equally spaced, increasing
    std::vector<std::vector<double>> z;  // [frame][grain], m, continuous in time
};

// The tracks of the grains tagged `tag` in `frames` (the same grains in each,
// sorted by id). period > 0: the axis is periodic with that period (m) and
// z is unwrapped, assuming a grain moves less than period / 2 between frames.
// Throws tumble::Error for unequal spacing or differing grains.
AxialTracks axial_tracks(const std::vector<GrainFrame>& frames, std::int32_t tag, double period = 0.0);

struct MsdOptions {
    double block = 2.0;       // revolutions per block (rounded to whole frame spacings)
    double fit_from = 1.0;    // fit the lags from fit_from to block, revolutions: in the default drum the
                              // MSD of the small grains has a plateau at 0.5-0.9 rev (a grain buried in
                              // the bed between two passes through the flowing layer) and is linear from 1
    double half_length = std::numeric_limits<double>::infinity();  // m: caps at z = +-half_length
    double cap_margin = 3.0;  // see above
};

// Per block b and lag l (l frame spacings): the sum of dz^2 (m^2) over the
// windows used, and their number.
struct MsdBlocks {
    std::vector<double> lag;                   // revolutions, lag[l] = (l + 1) x spacing
    std::vector<std::vector<double>> sum_dz2;  // [block][lag]
    std::vector<std::vector<double>> count;    // [block][lag]
    std::size_t blocks() const { return sum_dz2.size(); }
};

MsdBlocks axial_msd_blocks(const AxialTracks& tracks, const MsdOptions& options);

// The MSD per lag of blocks weighted by `weight` (one per block; all 1: the
// pooled data), m^2; NaN for a lag without windows.
std::vector<double> weighted_msd(const MsdBlocks& b, const std::vector<double>& weight);

// D = slope / 2 of the least-squares line through (lag, msd) for lags in
// [lo, hi] (revolutions), m^2/rev; NaN with fewer than two lags.
double msd_line_diffusion(const std::vector<double>& lag, const std::vector<double>& msd, double lo, double hi);

struct MsdEstimate {
    double D = std::numeric_limits<double>::quiet_NaN();  // m^2/rev, from the pooled data
    Interval interval;             // 95 % bootstrap interval of D
    std::vector<double> lag, msd;  // the pooled MSD against lag (revolutions, m^2)
    double fit_lo = 0.0, fit_hi = 0.0;  // lags fitted, revolutions
    std::size_t runs = 0, blocks = 0;   // independent units
    bool determined = false;
    std::string note;              // why not, when not
};

// D from the blocks of one or more runs (seeds) of the same experiment: the
// pooled MSD's long-lag slope; the interval from a two-stage bootstrap
// (draw runs, then blocks within each drawn run). Not determined with fewer
// than 4 blocks in all, a D <= 0, or an interval wider than +-50 % of D.
MsdEstimate estimate_axial_diffusion(const std::vector<MsdBlocks>& runs, const MsdOptions& options);

}  // namespace tumble::analysis
