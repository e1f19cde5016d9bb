// SPDX-License-Identifier: MIT
#include "tumble/neighbor/candidate_pairs.hpp"

#include <algorithm>
#include <cmath>

#include "tumble/core/error.hpp"

namespace tumble {

namespace {

bool both_kinematic(const ParticleStore& p, std::size_t i, std::size_t j) {
    return p.is_kinematic(i) && p.is_kinematic(j);
}

double largest_radius(const ParticleStore& p) {
    double r = 0.0;
    for (double radius : p.radius) r = std::max(r, radius);
    return r;
}

// The cell grid: on periodic axes it spans the box, on open axes the
// particles' bounding box. Cells are at least `cutoff` wide.
struct CellGrid {
    Vec3 origin;
    Vec3 cell_size;
    std::array<int, 3> count{1, 1, 1};
    std::array<bool, 3> periodic{};

    CellGrid(const ParticleStore& p, const Domain& domain, double cutoff) {
        Vec3 lo = domain.lo, hi = domain.hi;
        for (int k = 0; k < 3; ++k) {
            periodic[k] = domain.periodic[k];
            if (periodic[k]) continue;
            lo[k] = hi[k] = p.size() ? p.position[0][k] : 0.0;
            bool finite = true;
            for (const Vec3& x : p.position) {
                lo[k] = std::min(lo[k], x[k]);
                hi[k] = std::max(hi[k], x[k]);
                finite = finite && std::isfinite(x[k]);  // min and max pass over a NaN
            }
            // NaN or Inf would make a grid of ~10^18 cells.
            if (!finite)
                throw Error("neighbour search: a particle position is not finite: the simulation blew up (check "
                            "the time step and the input)");
        }
        origin = lo;
        // Periodic axes: a whole number of cells of at least one cutoff.
        double periodic_cells = 1.0;
        for (int k = 0; k < 3; ++k) {
            if (!periodic[k]) continue;
            const double extent = hi[k] - lo[k];
            count[k] = static_cast<int>(std::floor(extent / cutoff));
            if (count[k] < 3)
                throw Error("neighbour search: periodic axis " + std::string(1, "xyz"[k]) +
                            " is shorter than three interaction ranges (3 x (2 R_max + skin) = " +
                            std::to_string(3.0 * cutoff) + " m)");
            cell_size[k] = extent / count[k];
            periodic_cells *= count[k];
        }
        // Open axes: cells one cutoff wide over the particles' extent, made
        // wider if needed so that a stray particle far away cannot blow the
        // grid up (at most ~2 cells per particle). Coordinates are clamped,
        // which is safe because every cell is at least one cutoff wide.
        const double max_cells = std::max(64.0, 2.0 * static_cast<double>(p.size()));
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
    std::size_t cells() const { return static_cast<std::size_t>(count[0]) * count[1] * count[2]; }
};

// Counting sort of particle indices by cell: start[c]..start[c+1] in `order`.
void bin(const ParticleStore& p, const CellGrid& grid, std::vector<std::uint32_t>& start,
         std::vector<std::uint32_t>& order) {
    std::vector<std::size_t> cell(p.size());
    start.assign(grid.cells() + 1, 0);
    for (std::size_t i = 0; i < p.size(); ++i) {
        cell[i] = grid.cell_of(p.position[i]);
        ++start[cell[i] + 1];
    }
    for (std::size_t c = 0; c < grid.cells(); ++c) start[c + 1] += start[c];
    order.resize(p.size());
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < p.size(); ++i) order[fill[cell[i]]++] = static_cast<std::uint32_t>(i);
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

std::vector<std::uint32_t> cell_order(const ParticleStore& p, const Domain& domain, double skin) {
    const CellGrid grid(p, domain, 2.0 * largest_radius(p) + skin);
    std::vector<std::uint32_t> start, order;
    bin(p, grid, start, order);
    std::stable_partition(order.begin(), order.end(), [&](std::uint32_t i) { return !p.is_kinematic(i); });
    return order;
}

void cell_list_pairs(const ParticleStore& p, const Domain& domain, double skin, PairList& out) {
    out.clear();
    if (p.size() == 0) return;
    const CellGrid grid(p, domain, 2.0 * largest_radius(p) + skin);
    std::vector<std::uint32_t> start, members;
    bin(p, grid, start, members);
    const Vec3 L = domain.length();
    std::vector<std::uint32_t> near;  // candidates j > i with their image codes
    std::vector<std::uint8_t> near_image;

    for (std::uint32_t i = 0; i < p.size(); ++i) {
        const Vec3& xi = p.position[i];
        const int c[3] = {grid.coordinate(xi, 0), grid.coordinate(xi, 1), grid.coordinate(xi, 2)};
        near.clear();
        near_image.clear();
        for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int delta[3] = {dx, dy, dz};
                    int nc[3], s[3];
                    bool outside = false;
                    for (int k = 0; k < 3; ++k) {
                        nc[k] = c[k] + delta[k];
                        s[k] = 0;
                        if (nc[k] < 0 || nc[k] >= grid.count[k]) {
                            if (!grid.periodic[k]) { outside = true; break; }
                            // j lives across the boundary: shift its image toward i.
                            s[k] = nc[k] < 0 ? -1 : 1;
                            nc[k] -= s[k] * grid.count[k];
                        }
                    }
                    if (outside) continue;
                    const std::size_t cell = grid.index(nc[0], nc[1], nc[2]);
                    const std::uint8_t code = image_code(-s[0], -s[1], -s[2]);
                    // d = X_i - X_j + shift: j sits at X_j + s L seen from i,
                    // so shift = -s L, the image code of (-s).
                    for (std::uint32_t m = start[cell]; m < start[cell + 1]; ++m) {
                        const std::uint32_t j = members[m];
                        if (j <= i || both_kinematic(p, i, j)) continue;
                        Vec3 d = xi - p.position[j];
                        for (int k = 0; k < 3; ++k) d[k] -= s[k] * L[k];
                        const double range = p.radius[i] + p.radius[j] + skin;
                        if (norm2(d) < range * range) {
                            near.push_back(j);
                            near_image.push_back(code);
                        }
                    }
                }
        // Ascending j within each i: the pair order does not depend on cell layout.
        std::vector<std::size_t> idx(near.size());
        for (std::size_t k = 0; k < idx.size(); ++k) idx[k] = k;
        std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) { return near[a] < near[b]; });
        for (std::size_t k : idx) out.add(i, near[k], near_image[k]);
    }
}

}  // namespace tumble
