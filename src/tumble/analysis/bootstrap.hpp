// SPDX-License-Identifier: MIT
// Confidence intervals by resampling independent units (Efron's bootstrap):
// draw as many units as there are, with replacement, recompute the estimate,
// repeat; the central 95 % of the recomputed estimates is the interval (the
// percentile interval). The units must be independent: seeds of a run, and
// within a run blocks of revolutions long enough to forget each other
// (axial_msd.hpp). Deterministic: a fixed generator and seed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <random>
#include <vector>

namespace tumble::analysis {

struct Interval {
    double lo = 0.0;
    double hi = 0.0;
};

// Draws indices 0..n-1 uniformly (Lemire's multiply-shift, no dependence on
// the standard library's distributions, so every platform draws the same).
class Resampler {
public:
    explicit Resampler(std::uint64_t seed) : rng_(seed) {}
    std::size_t draw(std::size_t n);
    // How often each of n units is drawn in one resample of n draws.
    std::vector<double> weights(std::size_t n);

private:
    std::mt19937_64 rng_;
};

inline constexpr int bootstrap_replicates = 2000;
inline constexpr std::uint64_t bootstrap_seed = 20261130;

// The central `level` fraction of `values` (NaNs ignored): the percentile
// interval. NaN bounds if no value is finite.
Interval percentile_interval(std::vector<double> values, double level = 0.95);

}  // namespace tumble::analysis
