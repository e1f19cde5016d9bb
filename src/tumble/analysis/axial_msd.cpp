// SPDX-License-Identifier: MIT
#include "tumble/analysis/axial_msd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tumble/core/error.hpp"

namespace tumble::analysis {

namespace {
constexpr double nan = std::numeric_limits<double>::quiet_NaN();

std::string fmt_revolutions(double N) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.3g", N);
    return buffer;
}
}  // namespace

AxialTracks axial_tracks(const std::vector<GrainFrame>& frames, std::int32_t tag, double period) {
    AxialTracks t;
    for (std::size_t f = 0; f < frames.size(); ++f) {
        const GrainFrame& frame = frames[f];
        if (f > 0 && frame.id != frames[0].id) throw Error("axial tracks: the frames hold different grains");
        if (f > 1) {
            const double h = frames[1].revolutions - frames[0].revolutions;
            if (std::abs(frame.revolutions - frames[f - 1].revolutions - h) > 1e-6 * h)
                throw Error("axial tracks: frames are not equally spaced in time");
        }
        std::vector<double> z;
        for (std::size_t k = 0; k < frame.id.size(); ++k)
            if (frame.tag[k] == tag) z.push_back(frame.position[k].z);
        if (period > 0.0 && f > 0)
            for (std::size_t g = 0; g < z.size(); ++g)  // the image nearest the previous position
                z[g] -= period * std::round((z[g] - t.z.back()[g]) / period);
        t.revolutions.push_back(frame.revolutions);
        t.z.push_back(std::move(z));
    }
    return t;
}

MsdBlocks axial_msd_blocks(const AxialTracks& t, const MsdOptions& o) {
    const std::size_t frames = t.revolutions.size();
    if (frames < 2) throw Error("axial MSD: fewer than two frames");
    const double h = t.revolutions[1] - t.revolutions[0];
    if (!(h > 0.0)) throw Error("axial MSD: frames must be increasing in time");
    const std::size_t m = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(o.block / h)));
    const std::size_t grains = t.z[0].size();

    // D0, the generous guess for the cap margin: MSD(h) / 2h over all frames.
    double sum = 0.0, count = 0.0;
    for (std::size_t s = 0; s + 1 < frames; ++s)
        for (std::size_t g = 0; g < grains; ++g) {
            const double dz = t.z[s + 1][g] - t.z[s][g];
            sum += dz * dz;
            count += 1.0;
        }
    const double D0 = count > 0.0 ? sum / count / (2.0 * h) : 0.0;

    MsdBlocks b;
    for (std::size_t l = 1; l <= m; ++l) b.lag.push_back(static_cast<double>(l) * h);
    const std::size_t blocks = (frames - 1) / m;
    b.sum_dz2.assign(blocks, std::vector<double>(m, 0.0));
    b.count.assign(blocks, std::vector<double>(m, 0.0));
    for (std::size_t k = 0; k < blocks; ++k)
        for (std::size_t l = 1; l <= m; ++l) {
            const double reach = o.half_length - o.cap_margin * std::sqrt(2.0 * D0 * b.lag[l - 1]);
            for (std::size_t s = k * m; s + l <= (k + 1) * m; ++s)
                for (std::size_t g = 0; g < grains; ++g) {
                    if (std::abs(t.z[s][g]) > reach) continue;
                    const double dz = t.z[s + l][g] - t.z[s][g];
                    b.sum_dz2[k][l - 1] += dz * dz;
                    b.count[k][l - 1] += 1.0;
                }
        }
    return b;
}

std::vector<double> weighted_msd(const MsdBlocks& b, const std::vector<double>& weight) {
    std::vector<double> msd(b.lag.size(), nan);
    for (std::size_t l = 0; l < b.lag.size(); ++l) {
        double sum = 0.0, count = 0.0;
        for (std::size_t k = 0; k < b.blocks(); ++k) {
            sum += weight[k] * b.sum_dz2[k][l];
            count += weight[k] * b.count[k][l];
        }
        if (count > 0.0) msd[l] = sum / count;
    }
    return msd;
}

double msd_line_diffusion(const std::vector<double>& lag, const std::vector<double>& msd, double lo, double hi) {
    // Ordinary least squares of msd = 2 D tau + c.
    double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (std::size_t l = 0; l < lag.size(); ++l) {
        if (lag[l] < lo - 1e-9 || lag[l] > hi + 1e-9 || !std::isfinite(msd[l])) continue;
        n += 1.0, sx += lag[l], sy += msd[l], sxx += lag[l] * lag[l], sxy += lag[l] * msd[l];
    }
    const double det = n * sxx - sx * sx;
    if (n < 2.0 || det <= 0.0) return nan;
    return 0.5 * (n * sxy - sx * sy) / det;
}

MsdEstimate estimate_axial_diffusion(const std::vector<MsdBlocks>& runs, const MsdOptions& o) {
    MsdEstimate e;
    e.runs = runs.size();
    if (runs.empty()) {
        e.note = "no runs";
        return e;
    }
    // Runs share the lags (the same sampling); pool them as one set of blocks.
    MsdBlocks all;
    all.lag = runs[0].lag;
    for (const MsdBlocks& r : runs) {
        if (r.lag.size() != all.lag.size()) throw Error("axial MSD: runs with different lags");
        all.sum_dz2.insert(all.sum_dz2.end(), r.sum_dz2.begin(), r.sum_dz2.end());
        all.count.insert(all.count.end(), r.count.begin(), r.count.end());
    }
    e.blocks = all.blocks();
    e.lag = all.lag;
    e.msd = weighted_msd(all, std::vector<double>(all.blocks(), 1.0));
    e.fit_hi = all.lag.empty() ? 0.0 : all.lag.back();
    e.fit_lo = o.fit_from;
    e.D = msd_line_diffusion(e.lag, e.msd, e.fit_lo, e.fit_hi);

    Resampler resample(bootstrap_seed);
    std::vector<double> replicates(bootstrap_replicates);
    for (double& D : replicates) {
        std::vector<double> weight;
        const std::vector<double> run_weight = resample.weights(runs.size());
        for (std::size_t r = 0; r < runs.size(); ++r) {
            std::vector<double> w(runs[r].blocks(), 0.0);
            for (int copy = 0; copy < static_cast<int>(run_weight[r]); ++copy) {
                const std::vector<double> drawn = resample.weights(runs[r].blocks());
                for (std::size_t k = 0; k < w.size(); ++k) w[k] += drawn[k];
            }
            weight.insert(weight.end(), w.begin(), w.end());
        }
        D = msd_line_diffusion(e.lag, weighted_msd(all, weight), e.fit_lo, e.fit_hi);
    }
    e.interval = percentile_interval(std::move(replicates));

    if (e.blocks < 4)
        e.note = "only " + std::to_string(e.blocks) + " blocks of " + fmt_revolutions(e.fit_hi) +
                 " revolutions; at least 4 are needed for an interval (run longer: --revolutions)";
    else if (!(e.fit_hi > e.fit_lo))
        e.note = "blocks of " + fmt_revolutions(e.fit_hi) + " revolutions hold no lag beyond " +
                 fmt_revolutions(e.fit_lo) + " to fit";
    else if (!(e.D > 0.0))
        e.note = "the MSD does not grow with the lag";
    else if (!(0.5 * (e.interval.hi - e.interval.lo) <= 0.5 * e.D))
        e.note = "the 95 % interval is wider than +-50 % of D";
    e.determined = e.note.empty();
    return e;
}

}  // namespace tumble::analysis
