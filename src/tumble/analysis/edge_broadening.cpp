// SPDX-License-Identifier: MIT
#include "tumble/analysis/edge_broadening.hpp"

#include <algorithm>
#include <cmath>

namespace tumble::analysis {

namespace {

// phi made non-increasing by pooling adjacent violators (each pool the
// weighted mean of its bins).
std::vector<double> non_increasing(const std::vector<double>& phi, const std::vector<double>& weight) {
    struct Pool {
        double value, weight;
        std::size_t size;
    };
    std::vector<Pool> pools;
    for (std::size_t k = 0; k < phi.size(); ++k) {
        pools.push_back({phi[k], weight[k], 1});
        while (pools.size() > 1 && pools[pools.size() - 2].value < pools.back().value) {
            const Pool last = pools.back();
            pools.pop_back();
            Pool& p = pools.back();
            p.value = (p.value * p.weight + last.value * last.weight) / (p.weight + last.weight);
            p.weight += last.weight;
            p.size += last.size;
        }
    }
    std::vector<double> out;
    for (const Pool& p : pools) out.insert(out.end(), p.size, p.value);
    return out;
}

// z where the piecewise-linear, non-increasing phi(z) first falls through
// level (NaN if it never does).
double z_at(const std::vector<double>& z, const std::vector<double>& phi, double level) {
    for (std::size_t k = 0; k + 1 < z.size(); ++k)
        if (phi[k] >= level && level >= phi[k + 1] && phi[k] > phi[k + 1])
            return z[k] + (phi[k] - level) / (phi[k] - phi[k + 1]) * (z[k + 1] - z[k]);
    return nan_value;
}

}  // namespace

MatanoProfile boltzmann_matano(const std::vector<double>& z, const std::vector<double>& phi,
                               const std::vector<double>& weight, double phi_rich, double phi_poor, double t,
                               const std::vector<double>& levels) {
    MatanoProfile out;
    out.D.assign(levels.size(), nan_value);
    const std::vector<double> p = non_increasing(phi, weight);
    if (!p.empty()) out.first = p.front(), out.last = p.back();
    const double jump = phi_rich - phi_poor;
    if (p.size() < 3 || !(jump > 0.0) || !(t > 0.0)) return out;
    // The Matano plane: rich (z_M - z_0) + poor (z_n - z_M) = integral of phi.
    double integral = 0.0;
    for (std::size_t k = 0; k + 1 < p.size(); ++k) integral += 0.5 * (p[k] + p[k + 1]) * (z[k + 1] - z[k]);
    const double zM = (integral + phi_rich * z.front() - phi_poor * z.back()) / jump;
    out.matano = zM;
    for (std::size_t l = 0; l < levels.size(); ++l) {
        const double level = phi_poor + levels[l] * jump;
        const double z_level = z_at(z, p, level);
        const double slope = (z_at(z, p, level + 0.05 * jump) - z_at(z, p, level - 0.05 * jump)) / (0.1 * jump);
        if (!std::isfinite(z_level) || !std::isfinite(slope)) continue;
        // The integral of (z - z_M) dphi from phi_poor up to the level: over
        // the segments beyond z_level, where -dphi/dz is constant, and the
        // tail below the last bin's phi counted at the last bin.
        double moment = (z.back() - zM) * (p.back() - phi_poor);
        for (std::size_t k = 0; k + 1 < p.size(); ++k) {
            const double a = std::max(z[k], z_level), b = z[k + 1];
            if (b <= a) continue;
            const double fall = (p[k] - p[k + 1]) / (z[k + 1] - z[k]);  // -dphi/dz
            moment += fall * (0.5 * (b * b - a * a) - zM * (b - a));
        }
        out.D[l] = -slope * moment / (2.0 * t);
    }
    return out;
}

EdgeDiffusion edge_diffusion(const BandField& field, const std::vector<double>& band_edges, double first_revolution,
                             double block_revolutions) {
    EdgeDiffusion out;
    if (band_edges.size() < 3) {
        out.note = "no boundary between bands at the start (a mixed start)";
        return out;
    }
    if (field.periodic) {
        out.note = "a periodic axis: its bands wrap";
        return out;
    }
    const std::size_t samples = field.revolutions.size();
    const std::vector<double> levels(edge_levels.begin(), edge_levels.end());
    for (std::size_t e = 1; e + 1 < band_edges.size(); ++e) {
        const double edge = band_edges[e];
        const double lo = e == 1 ? band_edges[0] + edge_end_margin : 0.5 * (band_edges[e - 1] + edge);
        const double hi = e + 2 == band_edges.size() ? band_edges[e + 1] - edge_end_margin
                                                     : 0.5 * (edge + band_edges[e + 1]);
        std::vector<std::size_t> bins;
        for (std::size_t b = 0; b < field.bins(); ++b)
            if (field.bin_centre(b) >= lo && field.bin_centre(b) <= hi) bins.push_back(b);
        if (samples == 0 || bins.size() < 4) continue;
        // The start's plateaus on each side; the rich side first (z mirrored
        // if it is on the right).
        double side[2] = {0.0, 0.0}, grains[2] = {0.0, 0.0};
        for (std::size_t b : bins)
            if (std::isfinite(field.small_fraction[0][b])) {
                const int s = field.bin_centre(b) < edge ? 0 : 1;
                side[s] += field.grains[0][b] * field.small_fraction[0][b];
                grains[s] += field.grains[0][b];
            }
        if (!(grains[0] > 0.0 && grains[1] > 0.0)) continue;
        const bool left_rich = side[0] / grains[0] > side[1] / grains[1];
        const double rich = std::max(side[0] / grains[0], side[1] / grains[1]);
        const double poor = std::min(side[0] / grains[0], side[1] / grains[1]);
        if (!(rich - poor > 0.5)) continue;  // not a step between two bands
        if (!left_rich) std::reverse(bins.begin(), bins.end());
        std::vector<double> z;
        for (std::size_t b : bins) z.push_back(left_rich ? field.bin_centre(b) : -field.bin_centre(b));
        out.boundaries.push_back(edge);
        out.species_left.push_back(left_rich);
        const std::size_t boundary = out.boundaries.size() - 1;

        std::vector<EdgeBlock> mine;
        for (double from = first_revolution;; from += block_revolutions) {
            std::vector<double> sum(bins.size(), 0.0), weight(bins.size(), 0.0);
            double N = 0.0, count = 0.0, last = -1.0;
            for (std::size_t k = 0; k < samples; ++k) {
                const double n = field.revolutions[k];
                last = std::max(last, n);
                if (n < from || n >= from + block_revolutions) continue;
                for (std::size_t i = 0; i < bins.size(); ++i) {
                    const double phi = field.small_fraction[k][bins[i]], g = field.grains[k][bins[i]];
                    if (std::isfinite(phi) && g > 0.0) sum[i] += g * phi, weight[i] += g;
                }
                N += n, count += 1.0;
            }
            if (from > last) break;
            if (count < 2.0) continue;
            std::vector<double> zs, phi, w;
            for (std::size_t i = 0; i < bins.size(); ++i)
                if (weight[i] > 0.0) zs.push_back(z[i]), phi.push_back(sum[i] / weight[i]), w.push_back(weight[i]);
            if (zs.size() < 4) continue;
            const MatanoProfile m = boltzmann_matano(zs, phi, w, rich, poor, N / count, levels);
            // The step must still be alone in its window: both plateaus reached.
            if (m.first < rich - 0.1 * (rich - poor) || m.last > poor + 0.1 * (rich - poor)) continue;
            EdgeBlock block{boundary, N / count, left_rich ? m.matano : -m.matano};
            std::copy(m.D.begin(), m.D.end(), block.D.begin());
            mine.push_back(block);
        }
        std::array<double, edge_levels.size()> mean{nan_value, nan_value, nan_value};
        if (!mine.empty()) {
            const double half = 0.5 * (mine.front().revolutions + mine.back().revolutions);
            for (std::size_t l = 0; l < edge_levels.size(); ++l) {
                double s = 0.0, n = 0.0;
                for (const EdgeBlock& b : mine)
                    if (b.revolutions >= half && std::isfinite(b.D[l])) s += b.D[l], n += 1.0;
                if (n > 0.0) mean[l] = s / n;
            }
        }
        out.boundary_D.push_back(mean);
        out.blocks.insert(out.blocks.end(), mine.begin(), mine.end());
    }
    std::size_t measured = 0;
    for (std::size_t l = 0; l < edge_levels.size(); ++l) {
        std::vector<double> values;
        for (const auto& d : out.boundary_D)
            if (std::isfinite(d[l])) values.push_back(d[l]);
        measured = std::max(measured, values.size());
        if (values.empty()) continue;
        const SeriesMean m = independent_mean(values);
        out.D[l] = m.mean;
        out.interval[l] = m.interval;
    }
    out.determined = measured >= 3 && std::isfinite(out.interval[1].lo);
    if (out.boundaries.empty())
        out.note = "no step between two bands in any boundary's window";
    else if (measured == 0)
        out.note = "no block of " + std::to_string(static_cast<int>(block_revolutions)) +
                   " revolutions with the step alone in its window";
    else if (!out.determined)
        out.note = std::to_string(measured) + (measured == 1 ? " boundary" : " boundaries") +
                   " measured: an interval needs 3 or more (more bands, or the runs of other seeds together)";
    return out;
}

}  // namespace tumble::analysis
