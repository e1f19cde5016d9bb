// SPDX-License-Identifier: MIT
#include "tumble/neighbor/candidate_pairs.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "tumble/core/error.hpp"

namespace tumble {

namespace {

bool both_kinematic(const ParticleStore& p, std::size_t i, std::size_t j) {
    return p.is_kinematic(i) && p.is_kinematic(j);
}

// The cell grid: on periodic axes it spans the box, on open axes the own
// particles' bounding box (the union of the chunks' extents; an MPI rank's
// ghosts outside it are put in the cells at its edge, see
// CellSearch::measure()). Cells are at least `cutoff` wide.
struct CellGrid {
    Vec3 origin;
    Vec3 cell_size;
    std::array<int, 3> count{1, 1, 1};
    std::array<bool, 3> periodic{};

    CellGrid(const std::vector<CellSearch::Extent>& extents, std::size_t particles, const Domain& domain,
             double cutoff) {
        Vec3 lo = domain.lo, hi = domain.hi;
        bool any = false, finite = true;
        for (const CellSearch::Extent& e : extents) {
            finite = finite && e.finite;
            if (e.empty) continue;
            for (int k = 0; k < 3; ++k) {
                if (domain.periodic[k]) continue;
                lo[k] = any ? std::min(lo[k], e.lo[k]) : e.lo[k];
                hi[k] = any ? std::max(hi[k], e.hi[k]) : e.hi[k];
            }
            any = true;
        }
        for (int k = 0; k < 3; ++k) {
            periodic[k] = domain.periodic[k];
            if (!periodic[k] && !any) lo[k] = hi[k] = 0.0;
        }
        // NaN or Inf would make a grid of ~10^18 cells.
        if (!finite)
            throw Error("neighbour search: a particle position is not finite: the simulation blew up (check "
                        "the time step and the input)");
        origin = lo;
        for (int k = 0; k < 3; ++k) {
            if (!periodic[k]) continue;
            const double extent = hi[k] - lo[k];
            if (!std::isfinite(extent))
                throw Error("neighbour search: periodic axis " + std::string(1, "xyz"[k]) + " has no finite length");
            if (!(std::floor(extent / cutoff) >= 3.0))
                throw Error("neighbour search: periodic axis " + std::string(1, "xyz"[k]) +
                            " is shorter than three interaction ranges (3 x (2 R_max + skin) = " +
                            std::to_string(3.0 * cutoff) + " m)");
        }
        // Periodic axes: a whole number of cells of at least one cutoff,
        // fewer and wider where there would be more than max(2^20, 2 per
        // particle) across them (a few spheres in a long periodic box asked
        // for 10^10 cells); at least three per axis.
        const double max_periodic_cells = std::max(1048576.0, 2.0 * static_cast<double>(particles));
        double periodic_cells = 1.0;
        for (double width = cutoff;; width *= 2.0) {
            periodic_cells = 1.0;
            for (int k = 0; k < 3; ++k) {
                if (!periodic[k]) continue;
                const double extent = hi[k] - lo[k];
                count[k] = static_cast<int>(std::clamp(std::floor(extent / width), 3.0, max_periodic_cells));
                cell_size[k] = extent / count[k];
                periodic_cells *= count[k];
            }
            if (periodic_cells <= max_periodic_cells) break;
        }
        // Open axes: cells one cutoff wide over the particles' extent, made
        // wider if needed so that a stray particle far away cannot blow the
        // grid up (at most ~2 cells per particle). Coordinates are clamped,
        // which is safe because every cell is at least one cutoff wide.
        const double max_cells = std::max(64.0, 2.0 * static_cast<double>(particles));
        double width = cutoff;
        for (;;) {
            double total = periodic_cells;
            for (int k = 0; k < 3; ++k)
                if (!periodic[k]) {
                    count[k] = static_cast<int>(std::min(1e6, std::floor((hi[k] - lo[k]) / width))) + 1;
                    cell_size[k] = width;
                    total *= count[k];
                }
            if (total <= max_cells || width > 1e300) break;
            width *= 2.0;
        }
    }

    int coordinate(const Vec3& x, int k) const {
        int c = static_cast<int>(std::floor((x[k] - origin[k]) / cell_size[k]));
        return std::clamp(c, 0, count[k] - 1);
    }
    std::size_t index(int cx, int cy, int cz) const {
        return static_cast<std::size_t>(cx) + static_cast<std::size_t>(count[0]) * (cy + static_cast<std::size_t>(count[1]) * cz);
    }
    std::size_t cell_of(const Vec3& x) const { return index(coordinate(x, 0), coordinate(x, 1), coordinate(x, 2)); }
    // f(cell, s) for the 27 cells around the one of x (fewer at an open
    // side), s[k] = -1 or 1 where the cell lies across a periodic boundary
    // (seen from x, it is shifted by s L), else 0.
    template <class F>
    void each_neighbor(const Vec3& x, F&& f) const {
        const int centre[3] = {coordinate(x, 0), coordinate(x, 1), coordinate(x, 2)};
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int delta[3] = {dx, dy, dz};
                    int nc[3], s[3];
                    bool outside = false;
                    for (int k = 0; k < 3; ++k) {
                        nc[k] = centre[k] + delta[k];
                        s[k] = 0;
                        if (nc[k] < 0 || nc[k] >= count[k]) {
                            if (!periodic[k]) { outside = true; break; }
                            s[k] = nc[k] < 0 ? -1 : 1;
                            nc[k] -= s[k] * count[k];
                        }
                    }
                    if (!outside) f(index(nc[0], nc[1], nc[2]), s);
                }
    }
    std::size_t cells() const { return static_cast<std::size_t>(count[0]) * count[1] * count[2]; }
};

// The bin of particle i: its cell, in the first set of cells for a free
// own particle, in the second for a kinematic one (so that they come after
// all the free ones), in the third for a ghost (i >= own_end).
[[gnu::always_inline]] inline std::uint32_t bin_of(const ParticleStore& p, const CellGrid& grid, std::size_t i, std::size_t own_end) {
    const std::size_t set = i >= own_end ? 2 : p.is_kinematic(i) ? 1 : 0;
    return static_cast<std::uint32_t>(grid.cell_of(p.position[i]) + set * grid.cells());
}

double largest_radius(const std::vector<CellSearch::Extent>& extents) {
    double r = 0.0;
    for (const CellSearch::Extent& e : extents) r = std::max(r, e.largest_radius);
    return r;
}

}  // namespace

void brute_force_pairs(const ParticleStore& p, const Domain& domain, double skin, PairList& out) {
    out.clear();
    const Vec3 L = domain.length();
    for (std::size_t i = 0; i < p.size(); ++i) {
        for (std::size_t j = i + 1; j < p.size(); ++j) {
            if (both_kinematic(p, i, j)) continue;
            Vec3 d = p.position[i] - p.position[j];
            int s[3] = {0, 0, 0};
            for (int k = 0; k < 3; ++k) {
                if (!domain.periodic[k]) continue;
                if (d[k] > 0.5 * L[k]) s[k] = -1;
                if (d[k] < -0.5 * L[k]) s[k] = 1;
                d[k] += s[k] * L[k];
            }
            const double range = p.radius[i] + p.radius[j] + skin;
            if (norm2(d) < range * range)
                out.add(static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j), image_code(s[0], s[1], s[2]));
        }
    }
}

void CellSearch::measure(const ParticleStore& p, std::size_t own_end, Team& team) {
    team.one([&] {
        extents_.resize(static_cast<std::size_t>(team.chunks()));
        parts_.resize(extents_.size());
        count_.resize(extents_.size());
        chunk_total_.resize(extents_.size());
        chunk_in_order_.resize(extents_.size());
        key_.resize(p.size());
        members_.resize(p.size());
    });
    team.each([&](int c) {
        const IndexRange r = team.range(c, p.size());
        Extent e;
        e.empty = r.begin >= std::min(r.end, own_end);
        if (!e.empty) e.lo = e.hi = p.position[r.begin];
        for (std::size_t i = r.begin; i < r.end; ++i) {
            const Vec3& x = p.position[i];
            for (int k = 0; k < 3; ++k) {
                if (i < own_end) {
                    e.lo[k] = std::min(e.lo[k], x[k]);
                    e.hi[k] = std::max(e.hi[k], x[k]);
                }
                e.finite = e.finite && std::isfinite(x[k]);  // min and max pass over a NaN
            }
            e.largest_radius = std::max(e.largest_radius, p.radius[i]);
            if (!p.is_kinematic(i))
                e.free_end = i + 1;
            else
                e.first_kinematic = std::min(e.first_kinematic, i);
        }
        extents_[static_cast<std::size_t>(c)] = e;
    });
}

// Three phases: each chunk counts its particles per bin; the counts are
// added up bin by bin, in chunk order within a bin, each chunk of the team
// taking a part of the bins (first their sums, then, from the sums of the
// parts before it, the place where each chunk's first particle of each bin
// goes); each chunk puts its particles there, in their order. Stable, and
// the same for every chunk count.
void CellSearch::counting_sort(std::size_t particles, std::size_t bins, Team& team,
                               std::vector<std::uint32_t>& sorted) {
    const auto chunks = static_cast<std::size_t>(team.chunks());
    team.each([&](int c) {
        std::vector<std::uint32_t>& count = count_[static_cast<std::size_t>(c)];
        count.assign(bins, 0);
        const IndexRange r = team.range(c, particles);
        for (std::size_t i = r.begin; i < r.end; ++i) ++count[key_[i]];
        if (c == 0) start_.resize(bins + 1);
    });
    team.each([&](int c) {
        const IndexRange b = team.range(c, bins);
        std::size_t total = 0;
        for (std::size_t bin = b.begin; bin < b.end; ++bin)
            for (std::size_t t = 0; t < chunks; ++t) total += count_[t][bin];
        chunk_total_[static_cast<std::size_t>(c)] = total;
    });
    team.each([&](int c) {
        std::size_t place = 0;
        for (int before = 0; before < c; ++before) place += chunk_total_[static_cast<std::size_t>(before)];
        const IndexRange b = team.range(c, bins);
        for (std::size_t bin = b.begin; bin < b.end; ++bin) {
            start_[bin] = static_cast<std::uint32_t>(place);
            for (std::size_t t = 0; t < chunks; ++t) {
                const std::uint32_t n = count_[t][bin];
                count_[t][bin] = static_cast<std::uint32_t>(place);
                place += n;
            }
        }
        if (c == team.chunks() - 1) start_[bins] = static_cast<std::uint32_t>(particles);
    });
    team.each([&](int c) {
        std::vector<std::uint32_t>& next = count_[static_cast<std::size_t>(c)];
        const IndexRange r = team.range(c, particles);
        for (std::size_t i = r.begin; i < r.end; ++i) sorted[next[key_[i]]++] = static_cast<std::uint32_t>(i);
    });
}

void CellSearch::sort_order(const ParticleStore& p, const Domain& domain, double skin, Team& team,
                            std::vector<std::uint32_t>& order) {
    measure(p, p.size(), team);
    const CellGrid grid(extents_, p.size(), domain, 2.0 * largest_radius(extents_) + skin);
    team.each([&](int c) {
        const IndexRange r = team.range(c, p.size());
        for (std::size_t i = r.begin; i < r.end; ++i) key_[i] = bin_of(p, grid, i, p.size());
        if (c == 0) order.resize(p.size());
    });
    counting_sort(p.size(), 2 * grid.cells(), team, order);
}

void CellSearch::find_pairs(const ParticleStore& p, const Domain& domain, double skin, std::size_t first_end,
                            Team& team, PairList& out) {
    // The grid spans the own particles (first_end), the grid in which
    // cell_order() sorted them; the ghosts after them are binned apart.
    measure(p, first_end, team);
    const CellGrid grid(extents_, first_end, domain, 2.0 * largest_radius(extents_) + skin);
    const std::size_t cells = grid.cells();
    const bool ghosts = first_end < p.size();
    // Whether the own particles are in the order of their bins, as
    // cell_order() leaves them (the Verlet list, and an MPI rank for its own
    // spheres, sort them so before every search, unless told not to): then
    // the particles of a bin are a stretch of the store, and those of a row
    // of bins too. Each chunk looks at its part, and at its first
    // particle's bin against that of the particle before.
    team.each([&](int c) {
        const IndexRange r = team.range(c, p.size());
        std::uint32_t previous = r.begin > 0 && r.begin < first_end ? bin_of(p, grid, r.begin - 1, first_end) : 0;
        bool in_order = true;
        for (std::size_t i = r.begin; i < r.end; ++i) {
            key_[i] = bin_of(p, grid, i, first_end);
            if (i >= first_end) continue;
            in_order = in_order && previous <= key_[i];
            previous = key_[i];
        }
        chunk_in_order_[static_cast<std::size_t>(c)] = in_order;
    });
    const bool in_order = std::all_of(chunk_in_order_.begin(), chunk_in_order_.end(), [](char part) { return part; });
    // If not (sorted in an older grid: sort_every above 1), the own
    // particles' bins are their cells alone, free and kinematic together:
    // fewer bins to look into one by one. The ghosts then take the second
    // set.
    if (!in_order)
        team.each([&](int c) {
            const IndexRange r = team.range(c, p.size());
            for (std::size_t i = r.begin; i < r.end; ++i)
                key_[i] = static_cast<std::uint32_t>(key_[i] % cells + (i >= first_end ? cells : 0));
        });
    const std::size_t own_sets = in_order ? 2 : 1, ghost_bins = own_sets * cells;
    counting_sort(p.size(), (own_sets + (ghosts ? 1 : 0)) * cells, team, members_);
    // A pair has a free particle and j > i: no pair starts after the last
    // free particle (with the store in cell_order(), the kinematic ones).
    std::size_t free_end = 0, first_kinematic = SIZE_MAX;
    for (const Extent& e : extents_) {
        free_end = std::max(free_end, e.free_end);
        first_kinematic = std::min(first_kinematic, e.first_kinematic);
    }
    // A kinematic particle pairs only with free ones after it: free particles
    // after the first kinematic one (an MPI rank's ghost grains, stored after
    // its own wall spheres). The cells next to one are marked, and a
    // kinematic particle elsewhere is passed over (on a rank of the long
    // drum, half its spheres are wall spheres, most of them far from a ghost).
    team.one([&] {
        near_late_free_.assign(cells, 0);
        for (std::size_t j = first_kinematic; j < free_end; ++j)
            if (!p.is_kinematic(j)) grid.each_neighbor(p.position[j], [&](std::size_t cell, const int*) { near_late_free_[cell] = 1; });
    });
    const Vec3 L = domain.length();
    team.each([&](int c) {
        Part& part = parts_[static_cast<std::size_t>(c)];
        part.first.clear();
        part.second.clear();
        part.image.clear();
        // The candidates j > i of one particle i, as j << 8 | image code
        // (one code per j: a cell is one of the 27 around i only once).
        std::vector<std::uint64_t>& near = part.near;
        // The cells around the last particle's cell, as runs of cells next
        // to each other in the grid's numbering (along x) seen through the
        // same periodic image: 9 runs of 3 inside the grid. The store is
        // sorted by cell, so the particles of a cell follow each other and
        // share them.
        struct Run {
            std::size_t first, last;  // cells
            std::uint8_t code;
            Vec3 shift;
        };
        std::array<Run, 27> runs;
        std::size_t run_count = 0, runs_of = SIZE_MAX;
        const Vec3* x = p.position.data();
        const double* radius = p.radius.data();
        const std::uint32_t* member = members_.data();
        std::size_t count = 0;
        // Members [from, to) of bins, all after i: every one is written, and
        // kept (count moves on) if it is in range and not a second kinematic
        // particle (`kinds`: i is kinematic, the bins hold both kinds); no
        // branch on the outcome, which is mostly "no" (one in 12 on the
        // long drum).
        const auto scan = [&](const Vec3& xi, double ri, bool kinds, std::size_t from, std::size_t to, const Run& run) {
            if (from >= to) return;
            if (near.size() < count + (to - from)) near.resize(2 * (count + (to - from)));
            std::uint64_t* candidate = near.data();
            for (std::size_t m = from; m < to; ++m) {
                const std::uint32_t j = member[m];
                const Vec3 d = xi - x[j] - run.shift;
                const double range_ij = ri + radius[j] + skin;
                candidate[count] = std::uint64_t{j} << 8 | run.code;
                count += norm2(d) < range_ij * range_ij && !(kinds && p.is_kinematic(j)) ? 1 : 0;
            }
        };
        const IndexRange range = team.range(c, std::min(free_end, first_end));
        for (auto i = static_cast<std::uint32_t>(range.begin); i < range.end; ++i) {
            const Vec3 xi = x[i];
            const double ri = radius[i];
            const bool i_kinematic = p.is_kinematic(i);
            const std::size_t cell = key_[i] % cells;
            if (i_kinematic && !near_late_free_[cell]) continue;
            if (cell != runs_of) {
                runs_of = cell;
                run_count = 0;
                grid.each_neighbor(xi, [&](std::size_t around, const int* s) {
                    // d = X_i - X_j + shift: j sits at X_j + s L seen from i,
                    // so shift = -s L, the image code of (-s).
                    const std::uint8_t code = image_code(-s[0], -s[1], -s[2]);
                    if (run_count > 0 && runs[run_count - 1].last + 1 == around && runs[run_count - 1].code == code)
                        runs[run_count - 1].last = around;
                    else
                        runs[run_count++] = {around, around, code, Vec3{s[0] * L.x, s[1] * L.y, s[2] * L.z}};
                });
            }
            count = 0;
            if (in_order) {
                // members_[m] = m: a run's own particles of one kind are
                // one stretch of the store, those after i at once. The free
                // ones, then the kinematic ones (none for a kinematic i).
                for (std::size_t bins = 0; bins < (i_kinematic ? 1u : 2u) * cells; bins += cells)
                    for (std::size_t r = 0; r < run_count; ++r)
                        scan(xi, ri, false, std::max<std::size_t>(start_[bins + runs[r].first], i + 1),
                             start_[bins + runs[r].last + 1], runs[r]);
            } else {
                // Cell by cell, each in ascending index (a stable counting
                // sort): a cell with none after i is passed over, and those
                // up to i are skipped at once.
                for (std::size_t r = 0; r < run_count; ++r)
                    for (std::size_t bin = runs[r].first; bin <= runs[r].last; ++bin) {
                        const std::uint32_t* m = member + start_[bin];
                        const std::uint32_t* end = member + start_[bin + 1];
                        if (m == end || end[-1] <= i) continue;
                        if (*m <= i) m = std::upper_bound(m, end, i);
                        scan(xi, ri, i_kinematic, static_cast<std::size_t>(m - member),
                             static_cast<std::size_t>(end - member), runs[r]);
                    }
            }
            // The ghosts, all after i: a run's are one stretch of members_.
            if (ghosts)
                for (std::size_t r = 0; r < run_count; ++r)
                    scan(xi, ri, i_kinematic, start_[ghost_bins + runs[r].first], start_[ghost_bins + runs[r].last + 1],
                         runs[r]);
            // Ascending j within each i: the pair order does not depend on cell layout.
            std::sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(count));
            for (std::size_t k = 0; k < count; ++k) {
                part.first.push_back(i);
                part.second.push_back(static_cast<std::uint32_t>(near[k] >> 8));
                part.image.push_back(static_cast<std::uint8_t>(near[k] & 0xff));
            }
        }
    });
    // The parts one after the other. Resizing keeps what the list held (its
    // length changes little from one build to the next), so the one thread
    // that does it writes only the difference.
    std::size_t total = 0;
    for (const Part& part : parts_) total += part.first.size();
    team.one([&] {
        out.first.resize(total);
        out.second.resize(total);
        out.image.resize(total);
        out.slip.resize(total);
        out.angular_slip.resize(total);
        out.viscous_force.resize(total);
    });
    team.each([&](int c) {
        std::size_t at = 0;
        for (int before = 0; before < c; ++before) at += parts_[static_cast<std::size_t>(before)].first.size();
        const Part& part = parts_[static_cast<std::size_t>(c)];
        std::copy(part.first.begin(), part.first.end(), out.first.begin() + static_cast<std::ptrdiff_t>(at));
        std::copy(part.second.begin(), part.second.end(), out.second.begin() + static_cast<std::ptrdiff_t>(at));
        std::copy(part.image.begin(), part.image.end(), out.image.begin() + static_cast<std::ptrdiff_t>(at));
        std::fill_n(out.slip.begin() + static_cast<std::ptrdiff_t>(at), part.first.size(), Vec3{});
        std::fill_n(out.angular_slip.begin() + static_cast<std::ptrdiff_t>(at), part.first.size(), 0.0);
        std::fill_n(out.viscous_force.begin() + static_cast<std::ptrdiff_t>(at), part.first.size(), 0.0);
    });
}

void cell_list_pairs(const ParticleStore& p, const Domain& domain, double skin, PairList& out, int chunks) {
    CellSearch search;
    run_in_team(chunks, [&](Team& team) { search.find_pairs(p, domain, skin, p.size(), team, out); });
}

std::vector<std::uint32_t> cell_order(const ParticleStore& p, const Domain& domain, double skin, int chunks) {
    CellSearch search;
    std::vector<std::uint32_t> order;
    run_in_team(chunks, [&](Team& team) { search.sort_order(p, domain, skin, team, order); });
    return order;
}

}  // namespace tumble
