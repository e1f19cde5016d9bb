// SPDX-License-Identifier: MIT
#include "tumble/analysis/series.hpp"

#include <algorithm>
#include <cmath>

namespace tumble::analysis {

double integrated_autocorrelation(const std::vector<double>& r) {
    const std::size_t n = r.size();
    if (n < 3) return 1.0;
    double mean = 0.0;
    for (double v : r) mean += v;
    mean /= static_cast<double>(n);
    double c0 = 0.0;
    for (double v : r) c0 += (v - mean) * (v - mean);
    if (c0 <= 0.0) return 1.0;
    double tau = 1.0;
    std::size_t window = 0;
    while (++window < n / 2) {
        double c = 0.0;
        for (std::size_t i = 0; i + window < n; ++i) c += (r[i] - mean) * (r[i + window] - mean);
        tau += 2.0 * c / c0;
        if (static_cast<double>(window) >= 3.0 * tau) break;
    }
    tau *= 1.0 + static_cast<double>(2 * window + 1) / static_cast<double>(n);
    return std::max(tau, 1.0);
}

double student_t_quantile(double level, double dof) {
    // The normal quantile z = sqrt(2) erfc^-1(1 - level) by Newton's method
    // on erfc (monotone, convex on z > 0: converges from z = 1).
    const double tail = 1.0 - level;
    double x = 1.0;
    for (int k = 0; k < 50; ++k) {
        const double step = (std::erfc(x) - tail) / (-2.0 / std::sqrt(M_PI) * std::exp(-x * x));
        x -= step;
        if (std::abs(step) < 1e-15 * x) break;
    }
    const double z = std::sqrt(2.0) * x, z2 = z * z;
    const double g1 = (z2 + 1.0) * z / 4.0;
    const double g2 = ((5.0 * z2 + 16.0) * z2 + 3.0) * z / 96.0;
    const double g3 = (((3.0 * z2 + 19.0) * z2 + 17.0) * z2 - 15.0) * z / 384.0;
    const double g4 = ((((79.0 * z2 + 776.0) * z2 + 1482.0) * z2 - 1920.0) * z2 - 945.0) * z / 92160.0;
    const double v = 1.0 / dof;
    return z + v * (g1 + v * (g2 + v * (g3 + v * g4)));
}

namespace {

// The mean of the finite values and, given their autocorrelation time
// (`tau` of the values, or 1 for independent ones), its t interval.
SeriesMean mean_with_interval(const std::vector<double>& values, double level, bool correlated) {
    std::vector<double> x;
    for (double v : values)
        if (std::isfinite(v)) x.push_back(v);
    SeriesMean m;
    const auto n = static_cast<double>(x.size());
    m.interval = {std::nan(""), std::nan("")};
    if (x.empty()) {
        m.mean = std::nan("");
        return m;
    }
    for (double v : x) m.mean += v / n;
    m.tau = correlated ? integrated_autocorrelation(x) : 1.0;
    m.effective = n / m.tau;
    if (m.effective < 3.0) return m;
    double s2 = 0.0;
    for (double v : x) s2 += (v - m.mean) * (v - m.mean) / (n - 1.0);
    const double half = student_t_quantile(level, m.effective - 1.0) * std::sqrt(m.tau * s2 / n);
    m.interval = {m.mean - half, m.mean + half};
    return m;
}

}  // namespace

SeriesMean series_mean(const std::vector<double>& values, double level) {
    return mean_with_interval(values, level, true);
}

SeriesMean independent_mean(const std::vector<double>& values, double level) {
    return mean_with_interval(values, level, false);
}

}  // namespace tumble::analysis
