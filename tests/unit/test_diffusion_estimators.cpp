// SPDX-License-Identifier: MIT
// The diffusion estimators on synthetic data with a known answer:
// random walkers for the grains' axial MSD (axial_msd.hpp) and its bootstrap
// interval, Hogg series with an offset and a start-up transient for the
// free-amplitude fit, and a series with diffusion and drift (hogg.hpp).
// Noise: std::mt19937_64 with a hand-written Box-Muller, so the numbers do
// not depend on the standard library's distributions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "tumble/analysis/axial_msd.hpp"
#include "tumble/analysis/bed_structure.hpp"
#include "tumble/analysis/bootstrap.hpp"
#include "tumble/analysis/hogg.hpp"
#include "tumble/core/constants.hpp"

namespace tumble::analysis {
namespace {

constexpr double drum_L = 0.12;     // m, the default drum's bed length
constexpr double true_D = 1.5e-5;   // m^2/rev, the size measured in the default drum

struct Gauss {
    std::mt19937_64 rng;
    explicit Gauss(std::uint64_t seed) : rng(seed) {}
    double operator()() {
        const double u1 = (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53;
        const double u2 = (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53;
        return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * pi * u2);
    }
    double uniform() { return (static_cast<double>(rng() >> 11) + 0.5) * 0x1.0p-53; }
};

// Walkers with Gaussian steps of variance 2 D h per frame (h revolutions),
// started uniformly in [-half, half] and reflected at +-half (end caps);
// half = inf: free walkers.
AxialTracks walkers(std::size_t grains, double revolutions, double h, double half, std::uint64_t seed) {
    Gauss g(seed);
    AxialTracks t;
    std::vector<double> z(grains);
    for (double& x : z) x = std::isfinite(half) ? half * (2.0 * g.uniform() - 1.0) : 0.0;
    const auto frames = static_cast<std::size_t>(std::llround(revolutions / h)) + 1;
    for (std::size_t f = 0; f < frames; ++f) {
        if (f > 0)
            for (double& x : z) {
                x += std::sqrt(2.0 * true_D * h) * g();
                if (x > half) x = 2.0 * half - x;
                if (x < -half) x = -2.0 * half - x;
            }
        t.revolutions.push_back(static_cast<double>(f) * h);
        t.z.push_back(z);
    }
    return t;
}

// 2000 walkers over 40 revolutions, sampled 8 times a revolution, in a
// 12 cm bed with reflecting caps; the default blocks of 2 revolutions and
// lags of 1-2 revolutions. The pooled MSD's slope has a statistical error
// of about 1 % here, so 3 % tests the estimator, not the noise.
TEST(AxialMsd, RecoversTheDiffusionCoefficientOfWalkersBetweenCaps) {
    const AxialTracks t = walkers(2000, 40.0, 0.125, 0.5 * drum_L, 1);
    MsdOptions o;
    o.half_length = 0.5 * drum_L;
    const MsdEstimate e = estimate_axial_diffusion({axial_msd_blocks(t, o)}, o);
    ASSERT_TRUE(e.determined) << e.note;
    EXPECT_NEAR(e.D, true_D, 0.03 * true_D);
    EXPECT_LE(e.interval.lo, e.D);
    EXPECT_GE(e.interval.hi, e.D);
    EXPECT_EQ(e.blocks, 20u);
}

// Over the default 2-revolution blocks the walkers feel the caps: without the exclusion
// (margin 0) D comes out about 10 % low; with the default margin of 3
// displacement scales the bias is gone to within the 3 % tolerance (8000
// walkers: statistical error about 1 %).
TEST(AxialMsd, ExcludingGrainsNearTheCapsRemovesTheirBias) {
    const AxialTracks t = walkers(8000, 40.0, 0.125, 0.5 * drum_L, 2);
    MsdOptions o;
    o.half_length = 0.5 * drum_L;
    const MsdEstimate kept = estimate_axial_diffusion({axial_msd_blocks(t, o)}, o);
    o.cap_margin = 0.0;
    const MsdEstimate all = estimate_axial_diffusion({axial_msd_blocks(t, o)}, o);
    EXPECT_NEAR(kept.D, true_D, 0.03 * true_D);
    EXPECT_LT(all.D, 0.95 * true_D) << "the caps should bias an estimate that keeps every grain";
}

// A periodic axis: positions wrapped into [-L/2, L/2) are unwrapped.
TEST(AxialMsd, UnwrapsAPeriodicAxis) {
    const AxialTracks free = walkers(500, 20.0, 0.125, INFINITY, 3);
    std::vector<GrainFrame> frames;
    for (std::size_t f = 0; f < free.revolutions.size(); ++f) {
        GrainFrame frame;
        frame.revolutions = free.revolutions[f];
        for (std::size_t k = 0; k < free.z[f].size(); ++k) {
            const double z = free.z[f][k] + 0.05;  // wraps for many grains
            frame.id.push_back(static_cast<std::int64_t>(k));
            frame.position.push_back({0.0, 0.0, z - drum_L * std::floor(z / drum_L + 0.5)});
            frame.radius.push_back(1e-3);
            frame.tag.push_back(0);
        }
        frames.push_back(frame);
    }
    const AxialTracks t = axial_tracks(frames, 0, drum_L);
    for (std::size_t f = 0; f < t.z.size(); ++f)
        for (std::size_t k = 0; k < t.z[f].size(); k += 50)
            EXPECT_NEAR(t.z[f][k] - t.z[0][k], free.z[f][k] - free.z[0][k], 1e-12);
}

// Coverage of the 95 % block-bootstrap interval: 300 independent data sets
// of 100 free walkers over 20 one-revolution blocks (lags 0.5-1); the interval should
// hold the true D in 90-98 % of them (binomial spread of the count at 95 %:
// +-1.3 %, so the band allows for the percentile interval's known slight
// under-coverage with 20 units).
TEST(AxialMsd, BootstrapIntervalCoversTheTrueValue) {
    int covered = 0;
    const int sets = 300;
    MsdOptions o;
    o.block = 1.0;
    o.fit_from = 0.5;
    for (int k = 0; k < sets; ++k) {
        const MsdEstimate e =
            estimate_axial_diffusion({axial_msd_blocks(walkers(100, 20.0, 0.125, INFINITY, 100 + k), o)}, o);
        covered += e.interval.lo <= true_D && true_D <= e.interval.hi;
    }
    const double coverage = static_cast<double>(covered) / sets;
    EXPECT_GE(coverage, 0.90);
    EXPECT_LE(coverage, 0.98);
}

// The Hogg series sampled 20 times a revolution for 12 revolutions (the
// linear regime), with <z>(0) off L/4 by dz0 and AR(1) noise.
struct HoggData {
    std::vector<double> N, z;
};
HoggData hogg_series(double dz0, double transient, double drift, double revolutions, double noise, std::uint64_t seed) {
    Gauss g(seed);
    HoggData d;
    double r = 0.0;
    const double rho = 0.9;  // correlation from one sample to the next
    for (int k = 0; k <= static_cast<int>(std::lround(revolutions * 20)); ++k) {
        const double N = k / 20.0;
        r = rho * r + std::sqrt(1.0 - rho * rho) * noise * g();
        d.N.push_back(N);
        d.z.push_back((1.0 + 4.0 * dz0 / drum_L) * hogg_mean_position(true_D, N, drum_L) +
                      transient * std::exp(-5.0 * N) + drift * N + r);
    }
    return d;
}

// dz0 = 0.4 mm as in the default run. The pinned fit (fit_diffusion, A =
// L/4) is off by -0.75 dz0 L / (D T) = -20 % on noise-free data; the free
// amplitude fit from N = 1 recovers D within 3 % despite a start-up transient
// of 1 mm decaying over a fifth of a revolution and 0.05 mm correlated noise.
TEST(HoggFree, RecoversDWhereThePinnedFitIsBiased) {
    const double dz0 = 4e-4, T = 12.0;
    const HoggData clean = hogg_series(dz0, 0.0, 0.0, T, 0.0, 1);
    const double predicted = -0.75 * dz0 * drum_L / (true_D * T);
    const double pinned = fit_diffusion(clean.N, clean.z, drum_L).D / true_D - 1.0;
    EXPECT_NEAR(pinned, predicted, 0.1 * std::abs(predicted)) << "pinned bias against the linear-regime formula";

    const HoggData noisy = hogg_series(dz0, 1e-3, 0.0, T, 5e-5, 2);
    const HoggFit free = fit_hogg(noisy.N, noisy.z, drum_L);
    ASSERT_TRUE(free.determined) << free.note;
    EXPECT_NEAR(free.D, true_D, 0.03 * true_D);
    EXPECT_NEAR(free.amplitude, 0.25 * drum_L + dz0, 1e-4);
}

// Diffusion and a drift of 2e-5 m/rev (a 3 mm shift over the run) over 150
// revolutions, long enough for the curvature that separates them (a = 1.5
// at the end): both within 5 %.
TEST(HoggFree, SeparatesDriftFromDiffusionOnALongSeries) {
    const double v = 2e-5;
    const HoggData d = hogg_series(0.0, 0.0, v, 150.0, 5e-5, 3);
    HoggFitOptions o;
    o.drift = true;
    const HoggFit f = fit_hogg(d.N, d.z, drum_L, o);
    ASSERT_TRUE(f.determined) << f.note;
    EXPECT_NEAR(f.D, true_D, 0.05 * true_D);
    EXPECT_NEAR(f.drift, v, 0.05 * v);
    // With D held at the true value (as from the MSD), the drift alone.
    o.fixed_D = true_D;
    const HoggFit held = fit_hogg(d.N, d.z, drum_L, o);
    EXPECT_NEAR(held.drift, v, 0.05 * v);
    EXPECT_GT(std::abs(held.drift), 3.0 * held.drift_stderr);
}

}  // namespace
}  // namespace tumble::analysis

namespace tumble::analysis {
namespace {

// Four grains in one cell, two of each kind, moving with a common flow
// (1, 0, 0) m/s plus +-0.1 m/s along y: the local mean flow is the common
// one, so each grain's fluctuation energy is 1/2 m 0.01 J, its granular
// temperature 0.01/3 m^2/s^2, its rotational energy 1/5 m R^2 w^2; a grain
// alone in another cell (one kind only) is left out.
TEST(BedStructure, FluctuationAboutTheLocalMeanFlow) {
    GrainFrame f;
    const double m = 2e-3, R = 1e-3;
    auto add = [&](Vec3 x, Vec3 v, std::int32_t tag) {
        f.id.push_back(static_cast<std::int64_t>(f.id.size()));
        f.position.push_back(x);
        f.velocity.push_back(v);
        f.angular_velocity.push_back({0.0, 0.0, 10.0});
        f.radius.push_back(R);
        f.mass.push_back(m);
        f.tag.push_back(tag);
    };
    for (std::int32_t tag : {0, 1})
        for (double s : {-1.0, 1.0}) add({0.001, 0.002, 0.003}, {1.0, 0.1 * s, 0.0}, tag);
    add({0.05, 0.05, 0.05}, {5.0, 0.0, 0.0}, 0);
    std::vector<SpeciesEnergetics> e(2);
    add_energetics(f, 0.01, e);
    for (const SpeciesEnergetics& s : e) {
        EXPECT_EQ(s.grains, 2u);
        EXPECT_NEAR(s.fluctuation(), 0.5 * m * 0.01, 1e-15);
        EXPECT_NEAR(s.temperature(), 0.01 / 3.0, 1e-15);
        EXPECT_NEAR(s.rotation(), 0.2 * m * R * R * 100.0, 1e-18);
    }
    // Four grains in the slice of z = 0.003 m, one in that of z = 0.05 m, of
    // four slices over 0.12 m: relative volumes 0, 0, 4 x 4/5, 4 x 1/5; the
    // four grains' centroid is where they sit, so their distance from it is 0.
    const AxialStructure a = axial_structure(f, 2, 0.12, 4);
    EXPECT_NEAR(a.relative_volume[2], 3.2, 1e-12);
    EXPECT_NEAR(a.relative_volume[3], 0.8, 1e-12);
    EXPECT_EQ(a.relative_volume[0], 0.0);
    EXPECT_NEAR(a.mean_distance[1][2], 0.0, 1e-15);
    EXPECT_TRUE(std::isnan(a.mean_distance[1][3]));
}


// A bed filling a circular segment of the circle grain centres can reach
// (R = 39 mm: inner radius 40 mm less the 1 mm grain radius), its chord 10 mm
// below the axis and inclined by 30 degrees (raised on the +x side), grains
// on a 1 mm grid, moving along the surface at 0.1 (d0 - depth)/d0 m/s
// downhill: the surface angle per slice is 30 degrees (to the grid's 1.5)
// and the flowing layer d0 = 5 mm deep (to half a bin, 0.5 mm, the
// profile's resolution).
TEST(BedStructure, SurfacePerSliceAndFlowingLayerOfASyntheticBed) {
    const double R = 0.039, h = 0.01, theta = 30.0 * pi / 180.0, d0 = 0.005;
    const Vec3 up{-std::sin(theta), std::cos(theta), 0.0};  // normal from the bed toward the axis
    Vec3 downhill{-up.y, up.x, 0.0};
    if (downhill.y > 0.0) downhill = -1.0 * downhill;
    GrainFrame f;
    for (double z = -0.055; z < 0.06; z += 0.002)
        for (double x = -R; x <= R; x += 0.001)
            for (double y = -R; y <= R; y += 0.001) {
                const Vec3 p{x, y, z};
                const double depth = -h - dot(Vec3{x, y, 0.0}, up);
                if (x * x + y * y > R * R || depth < 0.0) continue;
                f.id.push_back(static_cast<std::int64_t>(f.id.size()));
                f.position.push_back(p);
                f.radius.push_back(1e-3);
                f.tag.push_back(0);
                f.velocity.push_back((0.1 * (d0 - depth) / d0) * downhill);
                f.angular_velocity.push_back({});
                f.mass.push_back(1e-5);
            }
    for (double angle : surface_angle_by_slice(f, 0.04, 0.12, 6)) EXPECT_NEAR(angle, 30.0, 1.5);
    FlowProfile flow(0.5e-3, 0.03);
    flow.add(f, 0.04);
    EXPECT_NEAR(flow.thickness(), d0, 0.5e-3);
}

}  // namespace
}  // namespace tumble::analysis
