// SPDX-License-Identifier: MIT
// The mean of a correlated series (analysis/series.hpp), checked on
// synthetic series with a known mean: AR(1) noise x_k = phi x_{k-1} + e_k,
// whose integrated autocorrelation time is (1 + phi) / (1 - phi).
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
// Resampling the values as if independent covers only about half as often:
// what the end layers' intervals did before.
TEST(Series, IntervalCoversTheMean) {
    EXPECT_NEAR(coverage(0.0, 32, 1000), 0.95, 0.025);
    EXPECT_NEAR(coverage(0.8, 128, 1000), 0.92, 0.035);
    EXPECT_NEAR(coverage(0.8, 64, 1000), 0.88, 0.04);

    std::mt19937_64 rng(20261130);
    int covered = 0;
    for (int s = 0; s < 300; ++s) {
        const Interval i = bootstrap_mean_interval(ar1(rng, 0.8, 128));
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
