// SPDX-License-Identifier: MIT
// Axial band analysis (analysis/bands) on synthetic concentration fields
// whose bands are known: count, edges, wavelength, a merge at a known
// sample; none in a bed mixed at random; no flicker at the threshold; and
// the measurement of phi and the radial core from grains.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "tumble/analysis/bands.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace tumble::analysis {
namespace {

constexpr double L = 0.12;  // m, the paper's bed length
constexpr int bins = 30;    // the default for L: 4 mm bins
constexpr double w = L / bins;
constexpr double rich = 0.8, poor = 0.2;  // phi inside the bands
constexpr double many = 1e4;  // grains per bin where the noise should not matter

// phi per bin of a bed with bands between `edges` (z, m, ascending, the
// caps excluded), the first band rich: each bin the volume-weighted mix of
// the bands it overlaps.
std::vector<double> banded_row(const std::vector<double>& edges, bool first_rich = true) {
    std::vector<double> all{-0.5 * L};
    all.insert(all.end(), edges.begin(), edges.end());
    all.push_back(0.5 * L);
    std::vector<double> row(bins, 0.0);
    for (int b = 0; b < bins; ++b) {
        const double lo = -0.5 * L + b * w, hi = lo + w;
        for (std::size_t k = 0; k + 1 < all.size(); ++k) {
            const double part = std::max(0.0, std::min(hi, all[k + 1]) - std::max(lo, all[k])) / w;
            row[b] += part * (((k % 2 == 0) == first_rich) ? rich : poor);
        }
    }
    return row;
}

BandField field_of(const std::vector<std::vector<double>>& rows, double grains_per_bin = many) {
    BandField f;
    f.inner_length = L;
    for (std::size_t k = 0; k < rows.size(); ++k) {
        f.revolutions.push_back(static_cast<double>(k));
        f.small_fraction.push_back(rows[k]);
        f.grains.emplace_back(rows[k].size(), grains_per_bin);
    }
    return f;
}

TEST(Bands, KnownBandsAreFoundWithTheirEdgesWithinABin) {
    // Edges off the bin boundaries; widths from 2.6 to 5.9 bins.
    const std::vector<double> all_edges{-0.036, -0.013, 0.0105, 0.0342, 0.05};
    for (std::size_t k = 2; k <= 6; ++k) {
        const std::vector<double> edges(all_edges.begin(), all_edges.begin() + static_cast<std::ptrdiff_t>(k - 1));
        for (bool first_rich : {true, false}) {
            const BandHistory h = analyze_band_field(field_of({banded_row(edges, first_rich)}));
            const BandProfile& p = h.samples.at(0);
            ASSERT_EQ(p.bands.size(), k) << k << " bands";
            EXPECT_DOUBLE_EQ(p.bands.front().lo, -0.5 * L);
            EXPECT_DOUBLE_EQ(p.bands.back().hi, 0.5 * L);
            for (std::size_t i = 0; i < k; ++i) {
                EXPECT_EQ(p.bands[i].rich, (i % 2 == 0) == first_rich);
                if (i > 0) {
                    EXPECT_NEAR(p.bands[i].lo, edges[i - 1], w) << "edge " << i << " of " << k;
                }
                if (i + 1 < k) {
                    EXPECT_NEAR(p.bands[i].hi, edges[i], w);
                }
            }
            // The band contrast: between the band means, each a little
            // diluted by the bins an edge cuts.
            EXPECT_GT(p.band_contrast, 0.6 * (rich - poor));  // bands of 2.6 bins: up to 2 of them cut
            EXPECT_LE(p.band_contrast, rich - poor + 1e-12);
        }
    }
}

TEST(Bands, SinusoidGivesItsWavelengthAndBands) {
    // Three periods between the caps, in phase with them: the cosine
    // transform's mode k = 2 L / lambda = 6 holds all the power.
    const double lambda = L / 3.0;
    std::vector<double> row(bins);
    for (int b = 0; b < bins; ++b) row[b] = 0.5 + 0.2 * std::cos(2.0 * pi * (b + 0.5) * w / lambda);
    const BandProfile p = analyze_band_field(field_of({row})).samples.at(0);
    EXPECT_NEAR(p.dominant_wavelength, lambda, 1e-12);
    EXPECT_NEAR(p.dominant_share, 1.0, 1e-9);
    EXPECT_EQ(p.bands.size(), 7u);  // rich half bands at both caps, then one band per half period
    EXPECT_TRUE(p.bands.front().rich && p.bands.back().rich);
    for (std::size_t i = 1; i < p.bands.size(); ++i) EXPECT_NEAR(p.bands[i].lo, -0.5 * L + (2.0 * i - 1.0) * lambda / 4.0, 1e-9);

    // On a periodic axis the Fourier series: mode k has wavelength L / k.
    BandField f = field_of({row});
    f.periodic = true;
    const BandProfile q = analyze_band_field(f).samples.at(0);
    EXPECT_NEAR(q.dominant_wavelength, lambda, 1e-12);
    EXPECT_EQ(q.bands.size(), 6u);  // the two rich half bands at the seam are one
}

TEST(Bands, MergeIsFoundAtTheSampleWhereABandVanishes) {
    // Five bands; the second (poor) one narrows from 5 bins to 3 over samples
    // 0 .. 6 and is gone at sample 7: its neighbours join.
    constexpr int vanish = 7;
    const double centre = -0.02;
    std::vector<std::vector<double>> rows;
    for (int k = 0; k < 12; ++k) {
        const double half = k < vanish ? 0.5 * w * (5.0 - 2.0 * k / (vanish - 1.0)) : 0.0;
        rows.push_back(k < vanish ? banded_row({centre - half, centre + half, 0.015, 0.035})
                                  : banded_row({0.015, 0.035}));
    }
    const BandHistory h = analyze_band_field(field_of(rows));
    for (int k = 0; k < 12; ++k) EXPECT_EQ(h.samples[k].bands.size(), k < vanish ? 5u : 3u) << "sample " << k;
    ASSERT_EQ(h.events.size(), 1u);
    const BandEvent& e = h.events[0];
    EXPECT_EQ(e.kind, "merge");
    EXPECT_DOUBLE_EQ(e.revolutions, vanish);
    EXPECT_FALSE(e.rich);
    EXPECT_NEAR(e.z, centre, w);
    EXPECT_EQ(e.before, 5u);
    EXPECT_EQ(e.after, 3u);
}

TEST(Bands, CountChangeIsFoundOnceItHasHeldLongEnough) {
    // Five bands until sample 7, three from then on (the merge above),
    // samples one revolution apart: with a hold of 3 revolutions the change
    // is reported from sample 10 on, dated N = 7; not before, not with a
    // longer hold than the samples give.
    constexpr int vanish = 7;
    std::vector<std::vector<double>> rows;
    for (int k = 0; k < 12; ++k)
        rows.push_back(k < vanish ? banded_row({-0.03, -0.01, 0.015, 0.035}) : banded_row({0.015, 0.035}));
    const BandField all = field_of(rows);
    for (int last = 1; last < 12; ++last) {
        BandField f = all;  // the samples a run has seen by sample `last`
        for (auto* rows_of : {&f.small_fraction, &f.grains}) rows_of->resize(static_cast<std::size_t>(last) + 1);
        f.revolutions.resize(static_cast<std::size_t>(last) + 1);
        const double since = band_count_changed(analyze_band_field(f), 3.0);
        if (last < vanish + 3)
            EXPECT_TRUE(std::isnan(since)) << "sample " << last;
        else
            EXPECT_DOUBLE_EQ(since, vanish) << "sample " << last;
    }
    EXPECT_TRUE(std::isnan(band_count_changed(analyze_band_field(all), 5.0)));  // 4 revolutions of change only
    EXPECT_TRUE(std::isnan(band_count_changed(analyze_band_field(all), 0.0)));  // off
}

TEST(Bands, CountChangeThatReturnsDoesNotCount) {
    // Two halves, a third band for samples 3 to 6, two again from 7: the
    // last samples have the start's count, so nothing is reported; a start
    // without bands (a mixed start) that bands counts as a change.
    std::vector<std::vector<double>> rows;
    for (int k = 0; k < 10; ++k) rows.push_back(k >= 3 && k < 7 ? banded_row({-0.01, 0.02}) : banded_row({0.0}));
    EXPECT_TRUE(std::isnan(band_count_changed(analyze_band_field(field_of(rows)), 2.0)));
    rows.assign(3, std::vector<double>(bins, 0.5));
    for (int k = 0; k < 4; ++k) rows.push_back(banded_row({0.0}));
    EXPECT_DOUBLE_EQ(band_count_changed(analyze_band_field(field_of(rows)), 3.0), 3.0);
}

TEST(Bands, EndBandVanishingIsAnEndEvent) {
    const BandHistory h =
        analyze_band_field(field_of({banded_row({-0.04, 0.0, 0.03}), banded_row({0.0, 0.03}, false)}));
    ASSERT_EQ(h.events.size(), 1u);
    EXPECT_EQ(h.events[0].kind, "end");
    EXPECT_TRUE(h.events[0].rich);
}

// A bed mixed at random: in each bin of n grains each is small with the
// number fraction x that gives equal volumes of the paper's grains (3.6 and
// 2.4 mm: volume ratio 3.375, so x = 3.375 / 4.375).
std::vector<std::vector<double>> random_rows(int samples, int n_bins, int n, std::mt19937_64& rng,
                                             std::vector<std::vector<double>>& small) {
    const double ratio = 3.375, x = ratio / (1.0 + ratio);
    std::binomial_distribution<int> draw(n, x);
    std::vector<std::vector<double>> rows(samples, std::vector<double>(n_bins));
    small.assign(samples, std::vector<double>(n_bins));
    for (int k = 0; k < samples; ++k)
        for (int b = 0; b < n_bins; ++b) {
            const int s = draw(rng);
            small[k][b] = s;
            rows[k][b] = s / (s + (n - s) * ratio);
        }
    return rows;
}

TEST(Bands, RandomMixShowsNoBands) {
    // 2000 independent samples at each of two sizes: the paper's drum
    // (30 bins of 33 grains) and a long drum of 6,500 grains (160 bins of
    // 40). At the default thresholds none of 4000 samples per size showed a
    // band when they were chosen (95 % bound on the rate 7.5e-4; at z_enter
    // = 3 it was 7 % at 160 bins, which is why 4). Checked: fewer than 1
    // sample in 500.
    for (auto [n_bins, n] : {std::pair{30, 33}, std::pair{160, 40}}) {
        std::mt19937_64 rng(20261130 + n_bins);
        int with_bands = 0;
        constexpr int samples = 2000;
        for (int seed = 0; seed < samples / 20; ++seed) {
            std::vector<std::vector<double>> small;
            const std::vector<std::vector<double>> rows = random_rows(20, n_bins, n, rng, small);
            BandField f = field_of(rows, n);
            f.small_grains = small;
            const BandHistory h = analyze_band_field(f);
            for (const BandProfile& p : h.samples) with_bands += !p.bands.empty();
        }
        std::printf("random mix, %d bins of %d grains: %d of %d samples with bands\n", n_bins, n, with_bands, samples);
        EXPECT_LT(with_bands, samples / 500) << n_bins << " bins";
    }
}

TEST(Bands, HysteresisKeepsABandWhoseContrastHoversAtTheThreshold) {
    // Two halves whose contrast alternates between 0.2 (above the entry
    // threshold, 0.05) and 0.03 (below it, above the threshold to stay).
    std::vector<std::vector<double>> rows;
    for (int k = 0; k < 10; ++k) {
        const double a = k % 2 == 0 ? 0.2 : 0.03;
        std::vector<double> row(bins);
        for (int b = 0; b < bins; ++b) row[b] = 0.5 + (b < bins / 2 ? a : -a);
        rows.push_back(row);
    }
    const BandHistory h = analyze_band_field(field_of(rows));
    for (const BandProfile& p : h.samples) EXPECT_EQ(p.bands.size(), 2u) << "N = " << p.revolutions;
    EXPECT_TRUE(h.events.empty());
    // Without hysteresis the same field flickers.
    BandOptions none;
    none.min_contrast_leave = none.min_contrast;
    const BandHistory flicker = analyze_band_field(field_of(rows), none);
    for (const BandProfile& p : flicker.samples)
        EXPECT_EQ(p.bands.size(), static_cast<int>(p.revolutions) % 2 == 0 ? 2u : 0u);
    EXPECT_EQ(flicker.events.size(), 9u);
}

TEST(Bands, UniformAndEmptyRowsHaveNoBands) {
    std::vector<double> row(bins, 0.5);
    row[3] = row[4] = std::nan("");  // empty bins are left out
    const BandProfile p = analyze_band_field(field_of({row})).samples.at(0);
    EXPECT_TRUE(p.bands.empty());
    EXPECT_DOUBLE_EQ(p.contrast, 0.0);
    EXPECT_TRUE(std::isnan(p.dominant_wavelength));
    EXPECT_TRUE(std::isnan(p.band_contrast));
    const BandProfile one = analyze_band_field(field_of({std::vector<double>(bins, 1.0)})).samples.at(0);
    EXPECT_TRUE(one.bands.empty());  // one species only
}

// A store of free grains, for the measurement from grains.
struct Grains {
    ParticleStore p;
    void add(double x, double y, double z, double radius, int tag) {
        p.id.push_back(static_cast<std::int64_t>(p.id.size()));
        p.position.push_back({x, y, z});
        p.radius.push_back(radius);
        p.motion.push_back(free_motion);
        p.tag.push_back(tag);
    }
};

TEST(Bands, MeasuredFromGrains) {
    // Two slices: the left holds small grains (tag 1) and large ones, the
    // right large grains only; a wall particle is not counted.
    Grains g;
    for (int i = 0; i < 6; ++i) g.add(0.005 + 0.001 * i, 0.0, -0.03, 0.0012, 1);
    for (int i = 0; i < 2; ++i) g.add(0.035 + 0.001 * i, 0.0, -0.03, 0.0018, 0);
    for (int i = 0; i < 3; ++i) g.add(0.02 + 0.005 * i, 0.0, 0.03, 0.0018, 0);
    g.add(0.039, 0.0, 0.0, 0.003, 0);
    g.p.motion.back() = 0;  // a wall particle: not counted
    const BandSample s = measure_bands(g.p, {L, 2, 1});
    const double vs = 6 * std::pow(0.0012, 3), vl = 2 * std::pow(0.0018, 3);
    EXPECT_NEAR(s.small_fraction[0], vs / (vs + vl), 1e-12);
    EXPECT_DOUBLE_EQ(s.small_fraction[1], 0.0);
    EXPECT_DOUBLE_EQ(s.grains[0], 8.0);
    EXPECT_DOUBLE_EQ(s.small_grains[0], 6.0);
    EXPECT_DOUBLE_EQ(s.core_fraction[1], 0.0);
    EXPECT_EQ(default_band_bins(0.12), 30);
    EXPECT_EQ(default_band_bins(0.64), 160);
}

// The radial core is ranked from the bed's centre, not the drum axis. A bed
// of the paper's fill 0.3 in a drum of radius R = 4 cm: a circular segment
// of half angle a = 71.36 degrees (0.3 = (2a - sin 2a) / 2 pi), its flat
// surface 0.32 R from the axis, tilted by 40 degrees as at the angle of
// repose, filled with grains on a 2 mm square lattice (one slice, equal
// sizes, so phi is a number fraction). Small grains placed around the
// segment's centroid are the core; placed in the surface layer, the grains
// nearest the axis, they are not (the axis-referenced measure of before put
// 20 % of the core there, against 7 % now: the middle of the surface layer
// lies 0.28 R from the centroid, just inside the inner third's radius of
// 0.32 R).
TEST(Bands, RadialCoreAboutTheBedsCentreNotTheAxis) {
    constexpr double R = 0.04, spacing = 0.002, radius = 0.001, tilt = 40.0 * pi / 180.0;
    const double a = 71.3557 * pi / 180.0, surface = R * std::cos(a);
    const double centroid = 4.0 * R * std::pow(std::sin(a), 3) / (3.0 * (2.0 * a - std::sin(2.0 * a)));
    // Lattice points of the untilted segment (y < -surface), then turned.
    const auto bed = [&](auto small) {
        Grains g;
        for (double x = -R + 0.5 * spacing; x < R; x += spacing)
            for (double y = -R + 0.5 * spacing; y < -surface - 0.5 * spacing; y += spacing) {
                if (std::hypot(x, y) > R - radius) continue;
                const double c = std::cos(tilt), s = std::sin(tilt);
                g.add(c * x - s * y, s * x + c * y, 0.0, radius, small(x, y) ? 1 : 0);
            }
        return g;
    };
    const Grains around = bed([&](double x, double y) { return std::hypot(x, y + centroid) < 0.3 * R; });
    // The centre: the segment's centroid, on the line through the axis
    // perpendicular to the surface (turned with it), to within the lattice's
    // cut of the segment's edges (0.15 mm here; 0.5 mm allowed).
    const auto [cx, cy] = bed_centre(around.p);
    EXPECT_NEAR(cx, centroid * std::sin(tilt), 5e-4);
    EXPECT_NEAR(cy, -centroid * std::cos(tilt), 5e-4);
    const BandSample core = measure_bands(around.p, {L, 1, 1});
    EXPECT_GT(core.core_fraction[0], 0.95);  // a disc of 0.3 R holds nearly all of the inner third (0.32 R)
    EXPECT_DOUBLE_EQ(core.periphery_fraction[0], 0.0);
    // The surface layer, 1.5 lattice spacings deep.
    const Grains top = bed([&](double, double y) { return y > -surface - 1.5 * spacing; });
    const BandSample surface_layer = measure_bands(top.p, {L, 1, 1});
    EXPECT_LT(surface_layer.core_fraction[0], 0.1);
    EXPECT_GT(surface_layer.periphery_fraction[0], surface_layer.core_fraction[0]);
}

// A snapshot's grains on a square lattice of spacing 2 mm within a disc of
// radius 3 cm, centred at (x0, y0) (not the axis: the shells are ranked from
// the grains' centroid): the lattice is symmetric through its centre, so that
// is the volume-weighted centroid whenever a grain's radius depends on its
// distance from it only. kind(r) gives a grain at distance r its radius and
// tag.
template <class Kind>
GrainFrame lattice_frame(double x0, double y0, Kind kind) {
    constexpr double R = 0.03, spacing = 0.002;
    GrainFrame f;
    for (int i = -15; i <= 15; ++i)
        for (int j = -15; j <= 15; ++j) {
            const double x = i * spacing, y = j * spacing, r = std::hypot(x, y);
            if (r > R) continue;
            const auto [radius, tag] = kind(r);
            f.id.push_back(static_cast<std::int64_t>(f.id.size()));
            f.position.push_back({x0 + x, y0 + y, 0.0});
            f.radius.push_back(radius);
            f.tag.push_back(tag);
        }
    return f;
}

// Small grains exactly inside r0 = 1.5 cm, large ones outside, their radii
// chosen so that the small grains hold exactly a third of the volume:
// m rs^3 = (m rs^3 + (n - m) rl^3) / 3, rl^3 = 2 m rs^3 / (n - m). The two
// inner shells (of 6 of equal volume) are then all small, phi = 1, the four
// outer ones all large, phi = 0 (a grain's shell is that of the middle of its
// volume: the last small grain's lies half a small grain inside the third,
// the first large one's half a large grain outside), and the core excess is
// 1. Also exact: each shell's mean radius lies between the radii of its
// innermost and outermost grains.
TEST(Bands, RadialShellsOfAKnownCore) {
    constexpr double r0 = 0.015, rs = 0.0008;
    const GrainFrame lattice = lattice_frame(0.0, 0.0, [&](double r) { return std::pair{rs, r < r0 ? 1 : 0}; });
    const std::size_t n = lattice.tag.size(), m = static_cast<std::size_t>(std::count(lattice.tag.begin(), lattice.tag.end(), 1));
    const double rl = std::cbrt(2.0 * m * rs * rs * rs / static_cast<double>(n - m));
    const GrainFrame f = lattice_frame(0.011, -0.024, [&](double r) { return r < r0 ? std::pair{rs, 1} : std::pair{rl, 0}; });
    const auto [cx, cy] = bed_centre(f);
    EXPECT_NEAR(cx, 0.011, 1e-12);
    EXPECT_NEAR(cy, -0.024, 1e-12);
    const RadialShells s = radial_shells(f, 1);
    ASSERT_EQ(s.size(), 6u);
    for (std::size_t k = 0; k < 6; ++k) EXPECT_DOUBLE_EQ(s.small_fraction(k), k < 2 ? 1.0 : 0.0) << "shell " << k;
    EXPECT_DOUBLE_EQ(s.core_excess(), 1.0);
    EXPECT_DOUBLE_EQ(s.grains[0] + s.grains[1], static_cast<double>(m));
    EXPECT_LT(s.mean_radius(1), r0);
    EXPECT_GT(s.mean_radius(2), r0);
    EXPECT_GT(s.mean_radius(5), s.mean_radius(4));
    EXPECT_THROW(radial_shells(f, 1, 4), Error);  // not a multiple of 3
}

// Grains of one size: each shell holds n / 6 grains (to one grain), so with
// the m grains inside r0 tagged, shell k holds min(max(m - k n / 6, 0), n / 6)
// of them: 1, a fraction at the shell that r0 cuts, then 0.
TEST(Bands, RadialShellsOfEqualGrainsCutAtR0) {
    constexpr double r0 = 0.0185, radius = 0.0009;
    const GrainFrame f = lattice_frame(-0.005, 0.002, [&](double r) { return std::pair{radius, r < r0 ? 1 : 0}; });
    const RadialShells s = radial_shells(f, 1);
    double m = 0.0;
    for (int t : f.tag) m += t;
    for (std::size_t k = 0; k < 6; ++k) {
        const double expected = std::clamp(m - std::accumulate(s.grains.begin(), s.grains.begin() + k, 0.0), 0.0,
                                           s.grains[k]) / s.grains[k];
        EXPECT_NEAR(s.small_fraction(k), expected, 1e-12) << "shell " << k;
        EXPECT_NEAR(s.grains[k], static_cast<double>(f.tag.size()) / 6.0, 1.0);
    }
    EXPECT_GT(s.small_fraction(2), 0.0);  // r0 cuts the third shell (m = 277 of 701 grains: 2.37 shells)
    EXPECT_LT(s.small_fraction(2), 1.0);
}

// The null the shells are for: grains of one size tagged at random with
// probability 1/2. Each shell's phi then departs from the whole bed's by
// the binomial noise only, sqrt(phi (1 - phi) / n_k) (n_k = 117 grains, about
// 0.046); 4 standard errors is a two-sided tail of 6e-5 per shell. The core
// excess (two shells against two) has sqrt(2) times a third's noise.
TEST(Bands, RadialShellsOfARandomMixShowNoCore) {
    std::mt19937_64 random(7);
    std::bernoulli_distribution small(0.5);
    const GrainFrame f = lattice_frame(0.0, -0.02, [&](double) { return std::pair{0.001, small(random) ? 1 : 0}; });
    const RadialShells s = radial_shells(f, 1);
    double all = 0.0;
    for (int t : f.tag) all += t;
    const double phi = all / static_cast<double>(f.tag.size());
    for (std::size_t k = 0; k < 6; ++k)
        EXPECT_NEAR(s.small_fraction(k), phi, 4.0 * std::sqrt(phi * (1.0 - phi) / s.grains[k])) << "shell " << k;
    EXPECT_NEAR(s.core_excess(), 0.0, 4.0 * std::sqrt(2.0 * phi * (1.0 - phi) / (s.grains[0] + s.grains[1])));
}

// Snapshots pooled in the radial core's blocks of N: [0, 1), [1, 2), [2, 4),
// [4, 8); a snapshot a hair before N counts in N.
TEST(Bands, RadialShellsInBlocksOfRevolutions) {
    const GrainFrame inner = lattice_frame(0.0, 0.0, [](double r) { return std::pair{0.001, r < 0.0125 ? 1 : 0}; });
    const GrainFrame none = lattice_frame(0.0, 0.0, [](double) { return std::pair{0.001, 0}; });
    const std::vector<double> N{0.0, 1.0, 2.0, 3.0 - 1e-12, 4.5};
    const std::vector<RadialShells> shells{radial_shells(inner, 1), radial_shells(none, 1), radial_shells(inner, 1),
                                           radial_shells(none, 1), radial_shells(none, 1)};
    const std::vector<ShellBlock> blocks = radial_shell_blocks(N, shells);
    ASSERT_EQ(blocks.size(), 4u);
    EXPECT_DOUBLE_EQ(blocks[2].from, 2.0);
    EXPECT_DOUBLE_EQ(blocks[2].to, 4.0);
    EXPECT_EQ(blocks[2].snapshots, 2u);
    EXPECT_DOUBLE_EQ(blocks[2].shells.core_excess(), 0.5 * shells[0].core_excess());  // pooled with an untagged bed
    EXPECT_DOUBLE_EQ(blocks[1].shells.core_excess(), 0.0);
    EXPECT_DOUBLE_EQ(blocks[3].from, 4.0);
    EXPECT_EQ(blocks[3].snapshots, 1u);
}

// The radial core per block of revolutions: blocks [0, 1), [1, 2), [2, 4),
// [4, 8); revolution means; the interval needs 3 revolutions.
TEST(Bands, RadialCoreInBlocksOfRevolutions) {
    std::vector<double> N, core, periphery;
    for (int k = 0; k <= 28; ++k) {  // 4 samples per revolution, N = 0 .. 7
        N.push_back(0.25 * k);
        const bool late = N.back() >= 4.0;
        core.push_back(late ? 0.6 + 0.01 * (k % 3) : 0.5);
        periphery.push_back(0.4);
    }
    core[1] = std::nan("");  // an empty core: left out
    const std::vector<DifferenceBlock> blocks = difference_blocks(N, core, periphery);
    ASSERT_EQ(blocks.size(), 4u);
    EXPECT_DOUBLE_EQ(blocks[2].from, 2.0);
    EXPECT_DOUBLE_EQ(blocks[2].to, 4.0);
    EXPECT_EQ(blocks[0].revolutions, 1u);
    EXPECT_NEAR(blocks[0].difference, 0.1, 1e-12);
    EXPECT_TRUE(std::isnan(blocks[1].interval.lo));  // one revolution: no interval
    EXPECT_EQ(blocks[3].revolutions, 4u);            // 4, 5, 6 and the last sample, N = 7
    EXPECT_GT(blocks[3].difference, 0.2);
    EXPECT_LE(blocks[3].interval.lo, blocks[3].difference);
    EXPECT_GE(blocks[3].interval.hi, blocks[3].difference);
    EXPECT_GT(blocks[3].interval.lo, 0.19);
}

// The end layers: phi of the bins next to each cap against the row's phi0,
// grain-weighted, empty bins left out. A row of 10 bins of 10 grains with
// phi 0.2 in the first two bins, 0.6 in the last two and 0.4 between:
// phi0 = 0.4, the 2-bin layers 0.2 and 0.6.
TEST(Bands, EndLayersAgainstTheRowsMean) {
    BandField field;
    field.inner_length = 0.04;
    field.revolutions = {0.0, 1.0};
    for (int k = 0; k < 2; ++k) {
        std::vector<double> phi(10, 0.4), grains(10, 10.0);
        phi[0] = phi[1] = 0.2;
        phi[8] = phi[9] = 0.6;
        if (k == 1) phi[5] = std::nan(""), grains[5] = 0.0;  // an empty bin
        field.small_fraction.push_back(phi);
        field.grains.push_back(grains);
    }
    const EndLayers layers = end_layers(field, 2);
    for (std::size_t k = 0; k < 2; ++k) {
        EXPECT_NEAR(layers.left[k], 0.2, 1e-12);
        EXPECT_NEAR(layers.right[k], 0.6, 1e-12);
        EXPECT_NEAR(layers.mean[k], 0.4, 1e-12);
    }
}

// Bad thresholds are refused naming the setting as the caller spells it.
TEST(Bands, BadOptionsNamed) {
    BandOptions o;
    o.z_leave = 5.0;
    try {
        check_band_options(o, [](const std::string& f) { return "--band-" + f; });
        FAIL() << "z_leave > z_enter accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("--band-z_leave must lie in 0 .. --band-z_enter"), std::string::npos)
            << e.what();
    }
    o = {};
    o.min_width = 0;
    EXPECT_THROW(check_band_options(o), Error);
    o = {};
    o.min_contrast = std::nan("");
    EXPECT_THROW(check_band_options(o), Error);
    EXPECT_NO_THROW(check_band_options(BandOptions{}));
}

}  // namespace
}  // namespace tumble::analysis
