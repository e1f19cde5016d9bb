// SPDX-License-Identifier: MIT
#include "tumble/analysis/bands.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "tumble/analysis/series.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"

namespace tumble::analysis {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

}  // namespace

int default_band_bins(double inner_length) { return std::max(2, static_cast<int>(std::lround(inner_length / 0.004))); }

namespace {

// The volume-weighted centroid of the grains i < position.size() with
// counted(i): x_c = sum r_i^3 x_i / sum r_i^3 (r^3 the volume up to
// 4 pi / 3), the same for y; m. (0, 0) without such grains.
template <class Counted>
std::pair<double, double> volume_centroid(const std::vector<Vec3>& position, const std::vector<double>& radius,
                                          Counted counted) {
    double volume = 0.0, x = 0.0, y = 0.0;
    for (std::size_t i = 0; i < position.size(); ++i) {
        if (!counted(i)) continue;
        const double v = radius[i] * radius[i] * radius[i];
        volume += v, x += v * position[i].x, y += v * position[i].y;
    }
    return volume > 0.0 ? std::pair{x / volume, y / volume} : std::pair{0.0, 0.0};
}

}  // namespace

std::pair<double, double> bed_centre(const ParticleStore& p) {
    return volume_centroid(p.position, p.radius, [&](std::size_t i) { return !p.is_kinematic(i); });
}

std::pair<double, double> bed_centre(const GrainFrame& f) {
    return volume_centroid(f.position, f.radius, [](std::size_t) { return true; });
}

BandSample measure_bands(const ParticleStore& p, const BandFrame& frame) {
    if (frame.bins < 1 || !(frame.inner_length > 0.0))
        throw Error("band measurement: need at least one bin and a positive length");
    const auto bins = static_cast<std::size_t>(frame.bins);
    std::vector<std::vector<std::size_t>> members(bins);
    for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.is_kinematic(i)) continue;
        const double relative = (p.position[i].z + 0.5 * frame.inner_length) / frame.inner_length;
        members[static_cast<std::size_t>(std::clamp(relative * static_cast<double>(bins), 0.0, bins - 1.0))].push_back(i);
    }
    BandSample s;
    for (auto* v : {&s.small_fraction, &s.grains, &s.small_grains, &s.core_fraction, &s.periphery_fraction})
        v->resize(bins);
    const auto volume = [&](std::size_t i) { return 4.0 / 3.0 * pi * p.radius[i] * p.radius[i] * p.radius[i]; };
    const auto counted = [&](std::size_t i) { return p.tag[i] == frame.species_tag; };
    // Not a structured binding: clang 14 (scripts/fuzz.sh) cannot capture one in a lambda.
    const std::pair<double, double> centre = bed_centre(p);
    const double cx = centre.first, cy = centre.second;
    const auto distance = [&](std::size_t i) { return std::hypot(p.position[i].x - cx, p.position[i].y - cy); };
    for (std::size_t b = 0; b < bins; ++b) {
        std::vector<std::size_t>& m = members[b];
        // Outward from the bed's centre; ties by id, so the order does not depend on the array order.
        std::sort(m.begin(), m.end(), [&](std::size_t i, std::size_t j) {
            const double ri = distance(i), rj = distance(j);
            return ri != rj ? ri < rj : p.id[i] < p.id[j];
        });
        double total = 0.0, species = 0.0, small = 0.0;
        for (std::size_t i : m) {
            total += volume(i);
            if (counted(i)) species += volume(i), small += 1.0;
        }
        s.grains[b] = static_cast<double>(m.size());
        s.small_grains[b] = small;
        s.small_fraction[b] = total > 0.0 ? species / total : nan;
        // A grain belongs to the core (the periphery) when the middle of its
        // volume lies in the inner (outer) third of the bin's volume.
        double before = 0.0, core = 0.0, core_species = 0.0, outer = 0.0, outer_species = 0.0;
        for (std::size_t i : m) {
            const double v = volume(i), middle = before + 0.5 * v;
            if (middle < total / 3.0) core += v, core_species += counted(i) ? v : 0.0;
            if (middle > 2.0 * total / 3.0) outer += v, outer_species += counted(i) ? v : 0.0;
            before += v;
        }
        s.core_fraction[b] = core > 0.0 ? core_species / core : nan;
        s.periphery_fraction[b] = outer > 0.0 ? outer_species / outer : nan;
    }
    return s;
}

RadialShells& RadialShells::operator+=(const RadialShells& other) {
    for (auto [to, from] : {std::pair{&volume, &other.volume}, std::pair{&species_volume, &other.species_volume},
                            std::pair{&moment, &other.moment}, std::pair{&grains, &other.grains}}) {
        if (to->size() < from->size()) to->resize(from->size());
        for (std::size_t k = 0; k < from->size(); ++k) (*to)[k] += (*from)[k];
    }
    return *this;
}

double RadialShells::small_fraction(std::size_t shell) const {
    return volume[shell] > 0.0 ? species_volume[shell] / volume[shell] : nan;
}

double RadialShells::mean_radius(std::size_t shell) const {
    return volume[shell] > 0.0 ? moment[shell] / volume[shell] : nan;
}

double RadialShells::core_excess() const {
    const std::size_t third = size() / 3;
    // phi over shells [from, to), pooled by volume.
    const auto pooled = [&](std::size_t from, std::size_t to) {
        double v = 0.0, species = 0.0;
        for (std::size_t k = from; k < to; ++k) v += volume[k], species += species_volume[k];
        return v > 0.0 ? species / v : nan;
    };
    return third > 0 ? pooled(0, third) - pooled(size() - third, size()) : nan;
}

RadialShells radial_shells(const GrainFrame& f, int species_tag, int shells) {
    if (shells < 3 || shells % 3 != 0) throw Error("radial shells: a positive multiple of 3 shells expected");
    const auto [cx, cy] = bed_centre(f);
    std::vector<double> distance(f.position.size());
    for (std::size_t i = 0; i < distance.size(); ++i)
        distance[i] = std::hypot(f.position[i].x - cx, f.position[i].y - cy);
    std::vector<std::size_t> order(distance.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
        return distance[i] != distance[j] ? distance[i] < distance[j] : f.id[i] < f.id[j];
    });
    // V = 4 pi r^3 / 3 per grain, m^3.
    const auto volume = [&](std::size_t i) { return 4.0 / 3.0 * pi * f.radius[i] * f.radius[i] * f.radius[i]; };
    double total = 0.0;
    for (std::size_t i : order) total += volume(i);
    const auto n = static_cast<std::size_t>(shells);
    RadialShells s;
    for (auto* v : {&s.volume, &s.species_volume, &s.moment, &s.grains}) v->assign(n, 0.0);
    double before = 0.0;
    for (std::size_t i : order) {
        const double v = volume(i), middle = before + 0.5 * v;
        // The shell of the middle of the grain's volume: floor(middle / (total / shells)).
        const auto k = std::min(n - 1, static_cast<std::size_t>(middle / total * static_cast<double>(n)));
        s.volume[k] += v, s.moment[k] += v * distance[i], s.grains[k] += 1.0;
        if (f.tag[i] == species_tag) s.species_volume[k] += v;
        before += v;
    }
    return s;
}

std::vector<ShellBlock> radial_shell_blocks(const std::vector<double>& revolutions,
                                            const std::vector<RadialShells>& shells) {
    if (shells.size() != revolutions.size()) throw Error("radial shell blocks: one set of shells per snapshot expected");
    std::vector<ShellBlock> blocks;
    for (std::size_t k = 0; k < shells.size(); ++k) {
        if (!(revolutions[k] >= 0.0)) continue;
        // The block [from, 2 from) (from a power of 2) or [0, 1) holding N; a
        // snapshot time rounded just below N counts in N (as in difference_blocks).
        const double N = std::floor(revolutions[k] + 1e-9);
        const double from = N < 1.0 ? 0.0 : std::exp2(std::floor(std::log2(N))), to = std::max(1.0, 2.0 * from);
        if (blocks.empty() || blocks.back().from != from) blocks.push_back({from, to, 0, {}});
        blocks.back().snapshots += 1;
        blocks.back().shells += shells[k];
    }
    return blocks;
}

double BandField::bin_centre(std::size_t b) const {
    return -0.5 * inner_length + (static_cast<double>(b) + 0.5) * inner_length / static_cast<double>(bins());
}

namespace {

// A bin in the order the segmentation walks it: z unwrapped (on a periodic
// axis the walk starts at a sign change and z grows past L / 2).
struct Cell {
    std::size_t bin;
    double z, phi, deviation, smoothed, grains;
};

// A maximal stretch of cells of one sign of the smoothed deviation.
struct Run {
    std::size_t first, last;  // cells
    double lo, hi;            // unwrapped z
    bool rich, significant = false;
};

// [lo, hi] on the axis as up to two pieces within [-L/2, L/2].
std::vector<std::pair<double, double>> pieces(const Band& b, double L) {
    if (b.lo <= b.hi) return {{b.lo, b.hi}};
    return {{b.lo, 0.5 * L}, {-0.5 * L, b.hi}};
}

bool overlap(const Band& a, const Band& b, double L) {
    for (auto [alo, ahi] : pieces(a, L))
        for (auto [blo, bhi] : pieces(b, L))
            if (std::min(ahi, bhi) > std::max(alo, blo)) return true;
    return false;
}

// z wrapped into [-L/2, L/2) on a periodic axis.
double wrapped(double z, double L, bool periodic) {
    if (!periodic) return z;
    return z - L * std::floor((z + 0.5 * L) / L);
}

class RowSegmenter {
public:
    RowSegmenter(const BandField& f, const BandOptions& o) : field_(f), options_(o) {}

    BandProfile segment(std::size_t k, const BandProfile* previous) const {
        const std::vector<double>& phi = field_.small_fraction[k];
        const std::vector<double>& n = field_.grains[k];
        const std::size_t bins = phi.size();
        BandProfile out;
        out.revolutions = field_.revolutions[k];
        out.band_contrast = nan;
        double grains = 0.0, weighted = 0.0, small = 0.0;
        for (std::size_t b = 0; b < bins; ++b)
            if (std::isfinite(phi[b]) && n[b] > 0.0) {
                grains += n[b];
                weighted += n[b] * phi[b];
                if (!field_.small_grains.empty()) small += field_.small_grains[k][b];
            }
        out.mean = grains > 0.0 ? weighted / grains : nan;
        spectrum(phi, out);
        if (!(grains > 0.0)) return out;
        for (std::size_t b = 0; b < bins; ++b)
            if (std::isfinite(phi[b]) && n[b] > 0.0) out.contrast += n[b] * std::abs(phi[b] - out.mean) / grains;
        // The variance of phi in a bin of one grain of a random mix (see the header).
        const double x0 = field_.small_grains.empty() ? out.mean : small / grains;
        if (!(x0 > 0.0 && x0 < 1.0)) return out;  // one species only
        const double noise = out.mean * out.mean * (1.0 - out.mean) * (1.0 - out.mean) / (x0 * (1.0 - x0));

        const std::vector<Cell> cells = walk(phi, n, out.mean);
        if (cells.empty()) return out;
        std::vector<Run> runs = find_runs(cells);
        for (Run& r : runs) r.significant = significant(cells, r, noise, previous);
        out.bands = join(cells, runs);
        double rich = 0.0, rich_n = 0.0, poor = 0.0, poor_n = 0.0;
        for (const Band& b : out.bands) {
            (b.rich ? rich : poor) += b.small_fraction * b.grains;
            (b.rich ? rich_n : poor_n) += b.grains;
        }
        if (!out.bands.empty()) out.band_contrast = rich / rich_n - poor / poor_n;
        return out;
    }

private:
    double L() const { return field_.inner_length; }

    // The non-empty bins with their smoothed deviation, in walking order.
    std::vector<Cell> walk(const std::vector<double>& phi, const std::vector<double>& n, double mean) const {
        const auto bins = static_cast<std::ptrdiff_t>(phi.size());
        const std::ptrdiff_t half = std::max(0, options_.smoothing / 2);
        std::vector<Cell> cells;
        for (std::ptrdiff_t b = 0; b < bins; ++b) {
            if (!(std::isfinite(phi[b]) && n[b] > 0.0)) continue;
            double sum = 0.0, count = 0.0;
            for (std::ptrdiff_t j = b - half; j <= b + half; ++j) {
                std::ptrdiff_t i = j;
                if (field_.periodic) i = ((j % bins) + bins) % bins;
                else if (j < 0 || j >= bins) continue;  // truncated at the caps
                if (std::isfinite(phi[i]) && n[i] > 0.0) sum += phi[i] - mean, count += 1.0;
            }
            cells.push_back({static_cast<std::size_t>(b), field_.bin_centre(static_cast<std::size_t>(b)), phi[b],
                             phi[b] - mean, sum / count, n[b]});
        }
        if (!field_.periodic) return cells;
        // Start the walk at a sign change, so that no run is cut by the seam.
        const auto rich = [](const Cell& c) { return c.smoothed > 0.0; };
        std::size_t start = 0;
        for (std::size_t c = 0; c < cells.size(); ++c)
            if (rich(cells[c]) != rich(cells[(c + cells.size() - 1) % cells.size()])) {
                start = c;
                break;
            }
        std::rotate(cells.begin(), cells.begin() + static_cast<std::ptrdiff_t>(start), cells.end());
        for (std::size_t c = 1; c < cells.size(); ++c)
            if (cells[c].z < cells[c - 1].z) cells[c].z += L();
        return cells;
    }

    std::vector<Run> find_runs(const std::vector<Cell>& cells) const {
        const auto rich = [](const Cell& c) { return c.smoothed > 0.0; };
        // Where the smoothed deviation crosses zero between cells a and b.
        const auto crossing = [](const Cell& a, const Cell& b) {
            return a.z + (b.z - a.z) * a.smoothed / (a.smoothed - b.smoothed);
        };
        // With caps the runs span the bed from cap to cap; on a ring the walk
        // starts at a sign change, so the first run starts at the crossing
        // from the last cell (a period back) and the last run ends there.
        double start = -0.5 * L();
        if (field_.periodic) {
            Cell last = cells.back();
            last.z -= L();
            if (rich(last) != rich(cells.front())) start = crossing(last, cells.front());
        }
        std::vector<Run> runs;
        double lo = start;
        std::size_t first = 0;
        for (std::size_t c = 1; c <= cells.size(); ++c) {
            if (c < cells.size() && rich(cells[c]) == rich(cells[first])) continue;
            const double hi = c < cells.size() ? crossing(cells[c - 1], cells[c])
                              : field_.periodic ? start + L()
                                                : 0.5 * L();
            runs.push_back({first, c - 1, lo, hi, rich(cells[first])});
            lo = hi;
            first = c;
        }
        return runs;
    }

    // noise: the variance of phi in a bin of one grain of a random mix.
    bool significant(const std::vector<Cell>& cells, const Run& r, double noise, const BandProfile* previous) const {
        double sum = 0.0, grains = 0.0;
        for (std::size_t c = r.first; c <= r.last; ++c) sum += cells[c].grains * cells[c].deviation, grains += cells[c].grains;
        const double d = sum / grains, z = std::abs(d) / std::sqrt(noise / grains);
        if ((d > 0.0) != r.rich || static_cast<int>(r.last - r.first + 1) < options_.min_width) return false;
        bool known = false;  // a band of this sign was here at the previous sample
        if (previous) {
            const Band here{r.rich, wrapped(r.lo, L(), field_.periodic), wrapped(r.hi, L(), field_.periodic)};
            for (const Band& b : previous->bands) known = known || (b.rich == r.rich && overlap(b, here, L()));
        }
        return known ? z >= options_.z_leave && std::abs(d) >= options_.min_contrast_leave
                     : z >= options_.z_enter && std::abs(d) >= options_.min_contrast;
    }

    // Significant runs of one sign, with what lies between them, are a band.
    std::vector<Band> join(const std::vector<Cell>& cells, const std::vector<Run>& runs) const {
        std::vector<std::pair<const Run*, const Run*>> groups;  // first and last significant run
        for (const Run& r : runs) {
            if (!r.significant) continue;
            if (!groups.empty() && groups.back().second->rich == r.rich) groups.back().second = &r;
            else groups.push_back({&r, &r});
        }
        if (groups.empty()) return {};
        const bool ring = field_.periodic;
        if (ring && groups.size() > 1 && groups.front().first->rich == groups.back().first->rich) {
            groups.front().first = groups.back().first;
            groups.pop_back();
        }
        if (groups.size() < 2) return {};
        std::vector<Band> bands;
        for (std::size_t g = 0; g < groups.size(); ++g) {
            Band b;
            b.rich = groups[g].first->rich;
            const auto& before = groups[(g + groups.size() - 1) % groups.size()];
            const auto& after = groups[(g + 1) % groups.size()];
            // Edges midway between neighbouring groups (unwrapped: a group's
            // start may lie a period before its end when it spans the seam).
            double start = groups[g].first->lo, end = groups[g].second->hi;
            if (end < start) start -= L();
            double prev_end = before.second->hi, next_start = after.first->lo;
            while (prev_end > start) prev_end -= L();
            while (next_start < end) next_start += L();
            b.lo = (!ring && g == 0) ? -0.5 * L() : 0.5 * (prev_end + start);
            b.hi = (!ring && g + 1 == groups.size()) ? 0.5 * L() : 0.5 * (end + next_start);
            b.centre = wrapped(0.5 * (b.lo + b.hi), L(), ring);
            b.lo = wrapped(b.lo, L(), ring);
            b.hi = wrapped(b.hi, L(), ring);
            bands.push_back(b);
        }
        // Each bin to the band holding its centre.
        std::vector<double> phi_sum(bands.size(), 0.0);
        for (const Cell& c : cells) {
            const Band point{false, wrapped(c.z, L(), ring) - 1e-12 * L(), wrapped(c.z, L(), ring) + 1e-12 * L()};
            for (std::size_t i = 0; i < bands.size(); ++i)
                if (overlap(bands[i], point, L())) {
                    bands[i].grains += c.grains;
                    phi_sum[i] += c.grains * c.phi;
                    break;
                }
        }
        for (std::size_t i = 0; i < bands.size(); ++i)
            bands[i].small_fraction = bands[i].grains > 0.0 ? phi_sum[i] / bands[i].grains : nan;
        if (!ring) return bands;
        // On a ring, list the bands by their centres along z.
        std::sort(bands.begin(), bands.end(), [](const Band& a, const Band& b) { return a.centre < b.centre; });
        return bands;
    }

    // With end caps the bed mirrors at each cap: the cosine transform
    // (DCT-II); on a periodic axis the Fourier series.
    void spectrum(const std::vector<double>& phi, BandProfile& out) const {
        const std::size_t n = phi.size();
        std::vector<double> d(n, 0.0);
        for (std::size_t b = 0; b < n; ++b)
            if (std::isfinite(phi[b]) && std::isfinite(out.mean)) d[b] = phi[b] - out.mean;
        const std::size_t modes = field_.periodic ? n / 2 : n - 1;
        out.power.assign(modes, 0.0);
        for (std::size_t k = 1; k <= modes; ++k) {
            double re = 0.0, im = 0.0;
            for (std::size_t b = 0; b < n; ++b) {
                const double x = static_cast<double>(k) * (static_cast<double>(b) + (field_.periodic ? 0.0 : 0.5)) /
                                 static_cast<double>(n);
                if (field_.periodic) re += d[b] * std::cos(2.0 * pi * x), im -= d[b] * std::sin(2.0 * pi * x);
                else re += d[b] * std::cos(pi * x);
            }
            out.power[k - 1] = re * re + im * im;
        }
        const double total = std::accumulate(out.power.begin(), out.power.end(), 0.0);
        if (!(total > 1e-30)) {
            out.dominant_wavelength = out.dominant_share = nan;
            return;
        }
        const auto best = static_cast<std::size_t>(std::max_element(out.power.begin(), out.power.end()) - out.power.begin());
        const double k = static_cast<double>(best + 1);
        out.dominant_wavelength = (field_.periodic ? 1.0 : 2.0) * L() / k;
        out.dominant_share = out.power[best] / total;
    }

    const BandField& field_;
    BandOptions options_;
};

// The changes between the bands of two samples (see BandEvent).
void add_events(const BandProfile& before, const BandProfile& after, double L, bool periodic,
                std::vector<BandEvent>& events) {
    const std::size_t nb = before.bands.size(), na = after.bands.size();
    const auto event = [&](std::string kind, bool rich, double z) {
        events.push_back({after.revolutions, std::move(kind), rich, z, nb, na});
    };
    if (nb == 0 && na == 0) return;
    if (nb == 0 || na == 0) {
        event(nb == 0 ? "onset" : "dissolve", false, 0.0);
        return;
    }
    const auto followed = [&](const Band& a, const std::vector<Band>& in) {
        return std::any_of(in.begin(), in.end(), [&](const Band& b) { return b.rich == a.rich && overlap(a, b, L); });
    };
    for (std::size_t i = 0; i < nb; ++i) {
        const Band& a = before.bands[i];
        if (followed(a, after.bands)) continue;
        const bool end = !periodic && (i == 0 || i + 1 == nb);
        bool merged = false;
        if (!end) {
            const Band& left = before.bands[(i + nb - 1) % nb];
            const Band& right = before.bands[(i + 1) % nb];
            for (const Band& b : after.bands)
                merged = merged || (b.rich == left.rich && overlap(b, left, L) && overlap(b, right, L));
        }
        event(end ? "end" : merged ? "merge" : "vanish", a.rich, a.centre);
    }
    for (const Band& b : after.bands)
        if (!followed(b, before.bands)) event("appear", b.rich, b.centre);
}

}  // namespace

void check_band_options(const BandOptions& o, const std::function<std::string(const std::string&)>& name) {
    const auto fail = [&](const std::string& field, const std::string& why) {
        throw Error("band analysis: " + name(field) + " " + why);
    };
    const auto number = [](double v) {
        std::ostringstream text;
        text << v;  // 6 significant digits, as %g
        return text.str();
    };
    if (o.smoothing < 1) fail("smoothing", "must be at least 1 bin, got " + std::to_string(o.smoothing));
    if (o.min_width < 1) fail("min_width", "must be at least 1 bin, got " + std::to_string(o.min_width));
    if (!(std::isfinite(o.z_enter) && o.z_enter > 0.0)) fail("z_enter", "must be positive, got " + number(o.z_enter));
    if (!(std::isfinite(o.z_leave) && o.z_leave >= 0.0 && o.z_leave <= o.z_enter))
        fail("z_leave", "must lie in 0 .. " + name("z_enter") + " (" + number(o.z_enter) + "), got " +
                            number(o.z_leave));
    if (!(o.min_contrast >= 0.0 && o.min_contrast <= 1.0))
        fail("min_contrast", "must lie in 0 .. 1 (a volume fraction), got " + number(o.min_contrast));
    if (!(o.min_contrast_leave >= 0.0 && o.min_contrast_leave <= o.min_contrast))
        fail("min_contrast_leave", "must lie in 0 .. " + name("min_contrast") + " (" + number(o.min_contrast) +
                                       "), got " + number(o.min_contrast_leave));
}

BandHistory analyze_band_field(const BandField& field, const BandOptions& options) {
    const std::size_t samples = field.revolutions.size();
    if (field.small_fraction.size() != samples || field.grains.size() != samples ||
        (!field.small_grains.empty() && field.small_grains.size() != samples))
        throw Error("band analysis: as many rows of phi, grains and small grains as samples expected");
    for (std::size_t k = 0; k < samples; ++k)
        if (field.small_fraction[k].size() != field.bins() || field.grains[k].size() != field.bins() ||
            (!field.small_grains.empty() && field.small_grains[k].size() != field.bins()))
            throw Error("band analysis: sample " + std::to_string(k) + " has not " + std::to_string(field.bins()) +
                        " bins");
    if (samples > 0 && (field.bins() < 2 || !(field.inner_length > 0.0)))
        throw Error("band analysis: need at least 2 bins and a positive length");
    check_band_options(options);
    BandHistory h;
    const RowSegmenter segmenter(field, options);
    for (std::size_t k = 0; k < samples; ++k) {
        h.samples.push_back(segmenter.segment(k, k ? &h.samples[k - 1] : nullptr));
        if (k) add_events(h.samples[k - 1], h.samples[k], field.inner_length, field.periodic, h.events);
    }
    return h;
}

double band_count_changed(const BandHistory& history, double hold) {
    const std::vector<BandProfile>& s = history.samples;
    if (!(hold > 0.0) || !std::isfinite(hold) || s.size() < 2) return std::nan("");
    const std::size_t start = s.front().bands.size();
    std::size_t k = s.size();  // s[k], ..., the last: counts other than the start's
    while (k > 1 && s[k - 1].bands.size() != start) --k;
    if (k == s.size()) return std::nan("");
    const double since = s[k].revolutions;
    // N is omega t / 2 pi of the sample times: a quarter revolution apart is
    // 0.25 to within an ulp or so, hence the tolerance.
    return s.back().revolutions - since >= hold * (1.0 - 1e-9) ? since : std::nan("");
}

std::vector<DifferenceBlock> difference_blocks(const std::vector<double>& revolutions, const std::vector<double>& a,
                                               const std::vector<double>& b) {
    if (a.size() != revolutions.size() || b.size() != revolutions.size())
        throw Error("difference blocks: as many values of each quantity as samples expected");
    // Per whole revolution: the sums of the finite samples.
    struct Turn {
        double a = 0.0, b = 0.0, count = 0.0;
    };
    std::vector<Turn> turns;
    for (std::size_t k = 0; k < revolutions.size(); ++k) {
        if (!(std::isfinite(a[k]) && std::isfinite(b[k]) && revolutions[k] >= 0.0)) continue;
        const auto r = static_cast<std::size_t>(revolutions[k] + 1e-9);  // a sample time rounded just below N
        if (turns.size() <= r) turns.resize(r + 1);
        turns[r].a += a[k], turns[r].b += b[k], turns[r].count += 1.0;
    }
    std::vector<DifferenceBlock> blocks;
    for (std::size_t from = 0, to = 1; from < turns.size(); from = to, to *= 2) {
        DifferenceBlock block;
        block.from = static_cast<double>(from), block.to = static_cast<double>(to);
        std::vector<double> difference;
        for (std::size_t r = from; r < std::min(to, turns.size()); ++r) {
            const Turn& t = turns[r];
            if (!(t.count > 0.0)) continue;
            block.a += t.a / t.count, block.b += t.b / t.count;
            difference.push_back((t.a - t.b) / t.count);
        }
        block.revolutions = difference.size();
        const double n = static_cast<double>(difference.size());
        block.a = n > 0.0 ? block.a / n : nan;
        block.b = n > 0.0 ? block.b / n : nan;
        block.difference = block.a - block.b;
        const SeriesMean m = series_mean(difference);
        block.correlation = m.tau;
        block.interval = m.interval;
        blocks.push_back(block);
    }
    return blocks;
}

EndLayers end_layers(const BandField& field, std::size_t bins) {
    EndLayers layers;
    const std::size_t n = field.bins();
    bins = std::min(bins, n);
    // Grain-weighted phi over bins [from, to) of sample k.
    const auto pooled = [&](std::size_t k, std::size_t from, std::size_t to) {
        double sum = 0.0, grains = 0.0;
        for (std::size_t i = from; i < to; ++i)
            if (std::isfinite(field.small_fraction[k][i]))
                sum += field.grains[k][i] * field.small_fraction[k][i], grains += field.grains[k][i];
        return grains > 0.0 ? sum / grains : nan;
    };
    for (std::size_t k = 0; k < field.revolutions.size(); ++k) {
        layers.left.push_back(pooled(k, 0, bins));
        layers.right.push_back(pooled(k, n - bins, n));
        layers.mean.push_back(pooled(k, 0, n));
    }
    return layers;
}

}  // namespace tumble::analysis
