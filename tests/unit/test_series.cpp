// SPDX-License-Identifier: MIT
// The mean of a correlated series (analysis/series.hpp), checked on
// synthetic series with a known mean: AR(1) noise x_k = phi x_{k-1} + e_k,
// whose integrated autocorrelation time is (1 + phi) / (1 - phi); and the
// mean of a few independent values (seeds, band boundaries).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "tumble/analysis/bootstrap.hpp"
#include "tumble/analysis/series.hpp"

using namespace tumble::analysis;

namespace {

// n values of stationary AR(1) noise of mean 0 (started from its stationary
// distribution, so no burn-in is needed).
std::vector<double> ar1(std::mt19937_64& rng, double phi, std::size_t n) {
    std::normal_distribution<double> e(0.0, 1.0);
    std::vector<double> x(n);
    x[0] = e(rng) / std::sqrt(1.0 - phi * phi);
    for (std::size_t k = 1; k < n; ++k) x[k] = phi * x[k - 1] + e(rng);
    return x;
}

// The fraction of `series` AR(1) series whose 95 % interval holds the true
// mean 0, among those that have an interval.
double coverage(double phi, std::size_t n, int series) {
    std::mt19937_64 rng(20261130);
    int with = 0, covered = 0;
    for (int s = 0; s < series; ++s) {
        const SeriesMean m = series_mean(ar1(rng, phi, n));
        if (!std::isfinite(m.interval.lo)) continue;
        ++with;
        covered += m.interval.lo <= 0.0 && 0.0 <= m.interval.hi;
    }
    return static_cast<double>(covered) / with;
}

}  // namespace

// Student's t at 95 % against the tables (Abramowitz & Stegun table 26.10):
// the expansion's stated accuracy, 0.8 %, from 2 degrees of freedom on.
TEST(Series, StudentQuantileAgainstTheTable) {
    const double table[][2] = {{2, 4.303}, {3, 3.182}, {5, 2.571}, {10, 2.228}, {30, 2.042}, {1e9, 1.960}};
    for (const auto& [dof, t] : table) EXPECT_NEAR(student_t_quantile(0.95, dof), t, 0.008 * t) << dof;
    EXPECT_NEAR(student_t_quantile(0.95, 1e9), 1.959964, 1e-6);  // the normal quantile itself
}

// tau of a long AR(1) series: 9 for phi = 0.8; the estimate's own scatter
// over 100,000 values is about 2 % (Sokal), so 6 % is three of it.
TEST(Series, AutocorrelationTimeOfAr1) {
    std::mt19937_64 rng(7);
    EXPECT_NEAR(integrated_autocorrelation(ar1(rng, 0.8, 100000)), 9.0, 0.06 * 9.0);
    EXPECT_NEAR(integrated_autocorrelation(ar1(rng, 0.0, 100000)), 1.0, 0.06);
}

// Coverage of the 95 % interval over 1,000 series (binomial scatter about
// 0.007 at 0.95, 0.01 at 0.9): white noise near 0.95; AR(1) with tau = 9,
// 128 values (14 correlation times) near 0.92 and 64 values (7) near 0.88
// (tau read from a short series is low: the stated limit of the method).
// Taking the values as independent covers only about half as often: what
// the end layers' intervals did before (they resampled the values).
TEST(Series, IntervalCoversTheMean) {
    EXPECT_NEAR(coverage(0.0, 32, 1000), 0.95, 0.025);
    EXPECT_NEAR(coverage(0.8, 128, 1000), 0.92, 0.035);
    EXPECT_NEAR(coverage(0.8, 64, 1000), 0.88, 0.04);

    std::mt19937_64 rng(20261130);
    int covered = 0;
    for (int s = 0; s < 300; ++s) {
        const Interval i = independent_mean(ar1(rng, 0.8, 128)).interval;
        covered += i.lo <= 0.0 && 0.0 <= i.hi;
    }
    EXPECT_LT(covered / 300.0, 0.6);
}

// A constant series has no spread (tau 1, a zero-width interval), NaNs are
// left out, and too few values give no interval.
TEST(Series, EdgeCases) {
    const SeriesMean flat = series_mean({0.5, 0.5, std::nan(""), 0.5, 0.5});
    EXPECT_DOUBLE_EQ(flat.mean, 0.5);
    EXPECT_DOUBLE_EQ(flat.tau, 1.0);
    EXPECT_DOUBLE_EQ(flat.interval.lo, 0.5);
    EXPECT_DOUBLE_EQ(flat.interval.hi, 0.5);
    EXPECT_TRUE(std::isnan(series_mean({1.0, 2.0}).interval.lo));
    EXPECT_TRUE(std::isnan(series_mean({}).mean));
}

// The mean of a few independent values: over 4,000 sets (binomial scatter
// 0.0035 at 0.95), Student's t interval covers the true mean 0.95 of the
// time for normal values of 3 and 5 (exact for normal values), and 0.91 for
// 4 lognormal ones (sigma 0.5: skewed like a D; t is approximate there).
// The percentile bootstrap of the mean, which the seeds' and boundaries'
// intervals used before, covers 0.76 and 0.84 (its spread is sqrt((n-1)/n)
// of s / sqrt(n) and its quantiles are the normal's).
TEST(Series, IndependentMeanCoversWithFewValues) {
    const auto cover = [](std::size_t n, bool lognormal, bool bootstrap) {
        std::mt19937_64 rng(20261201);
        std::normal_distribution<double> normal(0.0, 1.0);
        const double truth = lognormal ? std::exp(0.5 * 0.5 * 0.5) : 0.0;  // E[e^(sigma Z)] = e^(sigma^2 / 2)
        Resampler resample(bootstrap_seed);
        int covered = 0;
        const int sets = 4000;
        for (int s = 0; s < sets; ++s) {
            std::vector<double> x(n);
            for (double& v : x) v = lognormal ? std::exp(0.5 * normal(rng)) : normal(rng);
            Interval i = independent_mean(x).interval;
            if (bootstrap) {
                std::vector<double> means(500);
                for (double& m : means) {
                    const std::vector<double> w = resample.weights(n);
                    m = 0.0;
                    for (std::size_t k = 0; k < n; ++k) m += w[k] * x[k] / static_cast<double>(n);
                }
                i = percentile_interval(std::move(means));
            }
            covered += i.lo <= truth && truth <= i.hi;
        }
        return static_cast<double>(covered) / sets;
    };
    EXPECT_NEAR(cover(3, false, false), 0.95, 0.012);
    EXPECT_NEAR(cover(5, false, false), 0.95, 0.012);
    EXPECT_NEAR(cover(4, true, false), 0.91, 0.02);
    EXPECT_LT(cover(3, false, true), 0.80);
    EXPECT_LT(cover(5, false, true), 0.87);
}

// Fewer than 3 values give no interval; the interval holds the mean.
TEST(Series, IndependentMeanEdgeCases) {
    EXPECT_TRUE(std::isnan(independent_mean({1.0, 2.0}).interval.lo));
    const SeriesMean m = independent_mean({1.0, 2.0, 3.0, 4.0, 5.0});
    EXPECT_DOUBLE_EQ(m.mean, 3.0);
    EXPECT_DOUBLE_EQ(m.tau, 1.0);
    // 3 +- t(0.95, 4) sqrt(2.5 / 5) = 3 +- 2.776 * 0.7071 (the table's t: 2.776)
    EXPECT_NEAR(m.interval.lo, 3.0 - 2.776 * std::sqrt(0.5), 0.01);
    EXPECT_NEAR(m.interval.hi, 3.0 + 2.776 * std::sqrt(0.5), 0.01);
}
