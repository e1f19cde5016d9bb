// SPDX-License-Identifier: MIT
#include "tumble/analysis/bootstrap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tumble::analysis {

std::size_t Resampler::draw(std::size_t n) {
    // floor(u n / 2^64) for a uniform 64-bit u: bias below n / 2^64.
    __extension__ using u128 = unsigned __int128;
    return static_cast<std::size_t>((static_cast<u128>(rng_()) * n) >> 64);
}

std::vector<double> Resampler::weights(std::size_t n) {
    std::vector<double> w(n, 0.0);
    for (std::size_t k = 0; k < n; ++k) w[draw(n)] += 1.0;
    return w;
}

Interval percentile_interval(std::vector<double> values, double level) {
    values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
                 values.end());
    if (values.empty()) return {std::nan(""), std::nan("")};
    std::sort(values.begin(), values.end());
    // Linear interpolation between order statistics at (n - 1) q.
    auto quantile = [&](double q) {
        const double at = q * static_cast<double>(values.size() - 1);
        const auto i = static_cast<std::size_t>(at);
        const double f = at - static_cast<double>(i);
        return i + 1 < values.size() ? (1.0 - f) * values[i] + f * values[i + 1] : values[i];
    };
    return {quantile(0.5 * (1.0 - level)), quantile(0.5 * (1.0 + level))};
}

}  // namespace tumble::analysis
