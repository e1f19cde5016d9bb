// SPDX-License-Identifier: MIT
// Small grains crossing a band of large grains (docs/BAND-ANALYSIS.md): the flux
// that Kohring's argument for the odd band counts needs, as an effective
// axial diffusion coefficient inside the band by Fick's law.
//
// The count. Each grain carries the side of the band it was last seen on:
// left of the band's lower edge or right of its upper edge (a grain inside
// keeps the side it came from). A crossing is a change of that side between
// two frames: the grain left the band on the side opposite to the one it
// entered by. The edges are those of the band at each frame, so a band
// that drifts is followed.
//
// Fick's law. A band of width w whose interior holds n grains of the
// species per metre of axis, in which they diffuse with D, passes
//   r = D n / w   grains per unit time in each direction
// (the steady one-way flux through a slab whose far side absorbs the
// grains that came from the near side: the density of those grains falls
// linearly from n to 0 across the band, their gradient is n / w). So
//   D_eff = (crossings in both directions) w / (2 n T)
// over a time T. The band's n and w are averaged over the two frames of
// each interval, and the sum runs over the intervals and the bands.
//
// When a band is first seen its inner grains have no side yet. Each is
// given the side of the left edge with the weight (hi - z) / w and of the
// right with the rest: in a steady band the grains that last came from the
// left fall linearly across it, so the count is steady from the first
// frame and does not wait for the band's grains to be sorted by a first
// crossing (a band can take longer to cross, w^2 / 2 D, than the run).
//
// Snapshots see a grain only once per frame: one that leaves the band and
// returns in between is not seen to leave. For a random walk this is the
// same as moving the band's edges outward by beta sqrt(2 D dt),
// beta = -zeta(1/2) / sqrt(2 pi) = 0.5826 (the continuity correction of
// Broadie, Glasserman & Kou 1997 for a barrier watched at discrete times),
// so the rate seen is D n / (w + 2 beta sqrt(2 D dt)); D_eff is solved with
// that width. Without the correction D would be low by about
// 1.17 sqrt(2 D dt) / w: 7 % for a 6 mm step per frame across a band of 10 cm.
//
// Errors: the intervals are grouped into blocks of revolutions; the blocks
// are the units of a bootstrap of the ratio (bootstrap.hpp). A grain's
// side links neighbouring blocks, which the interval ignores; blocks much
// longer than a grain's time to cross an edge region (a few revolutions)
// keep that small.
//
// It holds for a band in a steady state. A band whose inside is still
// filling with the species (a prepared band of pure large grains at the
// start) crosses fewer grains than its n says, and D_eff is low until the
// band has been crossed a few times (w^2 / 2 D).
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "tumble/analysis/axial_msd.hpp"
#include "tumble/analysis/bootstrap.hpp"

namespace tumble::analysis {

// A band at one frame: its edges along the axis, m, lo < hi.
struct BandSpan {
    double lo = 0.0, hi = 0.0;
};

struct CrossingEstimate {
    double D = std::numeric_limits<double>::quiet_NaN();  // m^2 per revolution (per unit of tracks.revolutions)
    Interval interval;             // 95 % bootstrap interval over the blocks
    double D_uncorrected = std::numeric_limits<double>::quiet_NaN();  // without the discrete-frame correction
    double crossings = 0.0;        // in both directions, all bands
    double rate = 0.0;             // crossings per revolution and band, both directions
    double band_density = 0.0;     // n, grains of the species per m inside a band (time-weighted mean)
    double width = 0.0;            // w, m (time-weighted mean)
    double revolutions = 0.0;      // time the bands were followed, summed over bands
    std::size_t blocks = 0;
    bool determined = false;
    std::string note;              // why not, when not
};

// tracks: the species' axial positions at equally spaced frames (no
// periodic axis: a band's two sides must be distinct); bands[f]: the
// bands followed at frame f, along z (a band at frame f + 1 continues one
// at frame f that it overlaps, else it is new); block: revolutions per
// block. Determined with at least 4 blocks and 20 crossings.
CrossingEstimate band_crossing_diffusion(const AxialTracks& tracks, const std::vector<std::vector<BandSpan>>& bands,
                                         double block);

}  // namespace tumble::analysis
