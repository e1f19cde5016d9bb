// SPDX-License-Identifier: MIT
// The crossing of a band (analysis/band_crossing): random walkers of a
// known axial D, watched once per revolution, crossing a band of known
// width give D back by Fick's law, within its statistics and the
// discrete-frame correction; the same walkers' MSD estimator agrees; a band
// that drifts is followed; one that vanishes ends its count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "tumble/analysis/band_crossing.hpp"
#include "tumble/core/error.hpp"

namespace tumble::analysis {
namespace {

constexpr double L = 0.64;   // m: the study's bed length, caps at +-L/2
constexpr double D = 2e-5;   // m^2 per revolution: a step of sqrt(2 D) = 6.3 mm per revolution

// Walkers spread evenly over the bed, Gaussian steps of variance 2 D per
// frame (one frame per revolution), reflected at the caps.
AxialTracks walkers(std::size_t count, std::size_t frames, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> where(-0.5 * L, 0.5 * L);
    std::normal_distribution<double> step(0.0, std::sqrt(2.0 * D));
    AxialTracks t;
    std::vector<double> z(count);
    for (double& x : z) x = where(rng);
    for (std::size_t f = 0; f < frames; ++f) {
        t.revolutions.push_back(static_cast<double>(f));
        t.z.push_back(z);
        for (double& x : z) {
            x += step(rng);
            if (x > 0.5 * L) x = L - x;
            if (x < -0.5 * L) x = -L - x;
        }
    }
    return t;
}

TEST(BandCrossing, RandomWalkersGiveTheirDiffusionBack) {
    // 10,000 walkers (15,600 per m), 300 revolutions, a band 10 cm wide:
    // D n / (w + 2 beta sqrt(2 D)) = 2.9 crossings per revolution each way,
    // 1,700 in all. Over 20 seeds (the same walk in numpy) D came out
    // 1.3 % low on average (what the correction leaves at a step of 0.063 w)
    // with a spread of 1.8 % (one standard deviation); the test allows 8 %.
    // The uncorrected ratio is low by about 1.17 x 6.3 mm / 10 cm = 7 %:
    // the correction is needed.
    const AxialTracks t = walkers(10000, 300, 1);
    const std::vector<std::vector<BandSpan>> bands(300, {{-0.05, 0.05}});
    const CrossingEstimate e = band_crossing_diffusion(t, bands, 25.0);
    ASSERT_TRUE(e.determined) << e.note;
    std::printf("walkers of D = 2e-5 m^2/rev across 10 cm: D = %.4g [%.4g, %.4g] (uncorrected %.4g), %.0f crossings\n",
                e.D, e.interval.lo, e.interval.hi, e.D_uncorrected, e.crossings);
    EXPECT_EQ(e.blocks, 12u);
    EXPECT_NEAR(e.D, D, 0.08 * D) << e.crossings << " crossings";
    EXPECT_LT(e.D_uncorrected, e.D);
    EXPECT_NEAR(e.D_uncorrected / e.D, 1.0 / (1.0 + 2.0 * 0.5826 * std::sqrt(2.0 * e.D) / 0.1), 1e-6);
    EXPECT_LT(e.interval.lo, e.D);
    EXPECT_GT(e.interval.hi, e.D);
    EXPECT_LT(e.interval.lo, D * 1.02);  // the interval holds the truth (2 % for the bootstrap's own noise)
    EXPECT_GT(e.interval.hi, D * 0.98);
    EXPECT_NEAR(e.width, 0.1, 1e-12);
    EXPECT_NEAR(e.band_density, 10000.0 / L, 0.05 * 10000.0 / L);  // evenly spread: 640 inside, to a few %
    EXPECT_GT(e.crossings, 1000.0);

    // The MSD estimator of the same walkers (axial_msd.hpp) agrees, within
    // its own interval and this one's.
    MsdOptions o;
    o.block = 25.0;
    o.half_length = 0.5 * L;
    const MsdEstimate msd = estimate_axial_diffusion({axial_msd_blocks(t, o)}, o);
    ASSERT_TRUE(msd.determined) << msd.note;
    EXPECT_NEAR(msd.D, D, 0.05 * D);
}

TEST(BandCrossing, ADriftingBandIsFollowedAndAVanishedOneEnds) {
    // The band moves 0.2 mm per revolution (6 cm in 300): still D. A second
    // band, present only for the first 100 frames, adds its crossings then.
    const AxialTracks t = walkers(10000, 300, 2);
    std::vector<std::vector<BandSpan>> bands(300);
    for (std::size_t f = 0; f < 300; ++f) {
        const double shift = 2e-4 * static_cast<double>(f);
        bands[f].push_back({-0.2 + shift, -0.1 + shift});
        if (f < 100) bands[f].push_back({0.1, 0.2});
    }
    const CrossingEstimate e = band_crossing_diffusion(t, bands, 25.0);
    ASSERT_TRUE(e.determined) << e.note;
    EXPECT_NEAR(e.revolutions, 299.0 + 99.0, 1e-9);  // band-revolutions followed
    EXPECT_NEAR(e.D, D, 0.08 * D) << e.crossings << " crossings";
}

TEST(BandCrossing, TooLittleIsSaid) {
    const AxialTracks t = walkers(100, 10, 3);
    const CrossingEstimate e = band_crossing_diffusion(t, std::vector<std::vector<BandSpan>>(10, {{-0.05, 0.05}}), 1.0);
    EXPECT_FALSE(e.determined);
    EXPECT_NE(e.note.find("crossings"), std::string::npos) << e.note;
    const CrossingEstimate none = band_crossing_diffusion(t, std::vector<std::vector<BandSpan>>(10), 1.0);
    EXPECT_FALSE(none.determined);
    EXPECT_EQ(none.note, "no band followed over two frames");
    EXPECT_THROW(band_crossing_diffusion(t, std::vector<std::vector<BandSpan>>(9), 1.0), Error);
}

}  // namespace
}  // namespace tumble::analysis
