// SPDX-License-Identifier: MIT
#include "tumble/analysis/band_crossing.hpp"

#include <algorithm>
#include <cmath>

#include "tumble/core/error.hpp"

namespace tumble::analysis {

namespace {

// Per block: the crossings times the width (grains m) and twice the
// density times the time (2 n dt, grains rev / m), whose ratio is D; the
// exposure-weighted width for the correction; the totals for the report.
struct BlockSums {
    double crossed_width = 0.0, exposure = 0.0, crossings = 0.0;
    double width_weight = 0.0;  // sum of exposure x w
    double density_time = 0.0, time = 0.0;
};

// D from the raw ratio: the rate seen is D n / (w + 2 beta sqrt(2 D dt)),
// so D = D_raw (1 + 2 beta sqrt(2 D dt) / w); a fixed point, the correction
// being small (converges in a few steps for sqrt(2 D dt) / w < 1).
double corrected(double raw, double width, double dt) {
    constexpr double beta = 0.5825971579390106;  // -zeta(1/2) / sqrt(2 pi)
    if (!(raw > 0.0 && width > 0.0)) return raw;
    double D = raw;
    for (int k = 0; k < 50; ++k) D = raw * (1.0 + 2.0 * beta * std::sqrt(2.0 * D * dt) / width);
    return D;
}

}  // namespace

CrossingEstimate band_crossing_diffusion(const AxialTracks& tracks, const std::vector<std::vector<BandSpan>>& bands,
                                         double block) {
    const std::size_t frames = tracks.revolutions.size();
    if (bands.size() != frames || tracks.z.size() != frames)
        throw Error("band crossing: one list of bands and one row of positions per frame expected");
    if (!(block > 0.0)) throw Error("band crossing: the block must be positive");
    CrossingEstimate e;
    if (frames < 2) {
        e.note = "fewer than two frames";
        return e;
    }
    const double dt = tracks.revolutions[1] - tracks.revolutions[0];
    const std::size_t grains = tracks.z.front().size();
    // A band followed: its span at the last frame and each grain's weight
    // on "last seen on the left".
    struct Followed {
        BandSpan span;
        std::vector<double> left;
    };
    const auto inside = [&](std::size_t f, const BandSpan& b) {
        return static_cast<double>(std::count_if(tracks.z[f].begin(), tracks.z[f].end(),
                                                 [&](double z) { return z >= b.lo && z <= b.hi; }));
    };
    const auto start = [&](std::size_t f, const BandSpan& b) {
        Followed t{b, std::vector<double>(grains)};
        for (std::size_t g = 0; g < grains; ++g) {
            const double z = tracks.z[f][g];
            t.left[g] = z < b.lo ? 1.0 : z > b.hi ? 0.0 : (b.hi - z) / (b.hi - b.lo);
        }
        return t;
    };
    std::vector<Followed> followed;
    for (const BandSpan& b : bands.front()) followed.push_back(start(0, b));
    std::vector<BlockSums> sums;
    for (std::size_t f = 1; f < frames; ++f) {
        const auto k = static_cast<std::size_t>((tracks.revolutions[f - 1] - tracks.revolutions[0]) / block + 1e-9);
        if (sums.size() <= k) sums.resize(k + 1);
        std::vector<Followed> next;
        for (const BandSpan& b : bands[f]) {
            if (!(b.hi > b.lo)) throw Error("band crossing: a band's edges must satisfy lo < hi");
            const auto before = std::find_if(followed.begin(), followed.end(), [&](const Followed& t) {
                return std::min(t.span.hi, b.hi) > std::max(t.span.lo, b.lo);
            });
            if (before == followed.end()) {
                next.push_back(start(f, b));
                continue;
            }
            Followed t = std::move(*before);
            followed.erase(before);  // one band continues one band
            double crossed = 0.0;
            for (std::size_t g = 0; g < grains; ++g) {
                const double z = tracks.z[f][g];
                if (z < b.lo) crossed += 1.0 - t.left[g], t.left[g] = 1.0;
                else if (z > b.hi) crossed += t.left[g], t.left[g] = 0.0;
            }
            const double w = 0.5 * (t.span.hi - t.span.lo + b.hi - b.lo);
            const double n = 0.5 * (inside(f - 1, t.span) / (t.span.hi - t.span.lo) + inside(f, b) / (b.hi - b.lo));
            BlockSums& s = sums[k];
            s.crossings += crossed;
            s.crossed_width += crossed * w;
            s.exposure += 2.0 * n * dt;
            s.width_weight += 2.0 * n * dt * w;
            s.density_time += n * dt;
            s.time += dt;
            t.span = b;
            next.push_back(std::move(t));
        }
        followed = std::move(next);
    }
    // D of a set of blocks weighted by how often each is drawn.
    const auto estimate = [&](const std::vector<double>& weight, bool correct) {
        double cw = 0.0, exposure = 0.0, ww = 0.0;
        for (std::size_t b = 0; b < sums.size(); ++b)
            cw += weight[b] * sums[b].crossed_width, exposure += weight[b] * sums[b].exposure,
                ww += weight[b] * sums[b].width_weight;
        if (!(exposure > 0.0)) return std::numeric_limits<double>::quiet_NaN();
        return correct ? corrected(cw / exposure, ww / exposure, dt) : cw / exposure;
    };
    const std::vector<double> all(sums.size(), 1.0);
    for (const BlockSums& s : sums) {
        e.crossings += s.crossings;
        e.revolutions += s.time;
        e.band_density += s.density_time;
        e.width += s.width_weight;
    }
    double exposure = 0.0;
    for (const BlockSums& s : sums) exposure += s.exposure;
    e.blocks = static_cast<std::size_t>(std::count_if(sums.begin(), sums.end(), [](const BlockSums& s) { return s.time > 0.0; }));
    if (!(e.revolutions > 0.0)) {
        e.note = "no band followed over two frames";
        return e;
    }
    e.rate = e.crossings / e.revolutions;
    e.band_density /= e.revolutions;
    e.width = exposure > 0.0 ? e.width / exposure : std::numeric_limits<double>::quiet_NaN();
    e.D_uncorrected = estimate(all, false);
    e.D = estimate(all, true);
    Resampler resample(bootstrap_seed);
    std::vector<double> replicates(bootstrap_replicates);
    for (double& r : replicates) r = estimate(resample.weights(sums.size()), true);
    e.interval = percentile_interval(std::move(replicates));
    if (e.blocks < 4) e.note = "only " + std::to_string(e.blocks) + " blocks (4 needed)";
    else if (e.crossings < 20.0) e.note = "fewer than 20 crossings";
    e.determined = e.note.empty();
    return e;
}

}  // namespace tumble::analysis
