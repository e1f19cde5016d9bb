// SPDX-License-Identifier: MIT
#include "tumble/walls/facet_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "tumble/core/error.hpp"

namespace tumble {

FacetGrid::FacetGrid(double cell, double reach) : cell_(cell), per_cell_(1.0 / cell), reach_(reach) {
    if (!(cell > 0.0) || !std::isfinite(cell)) throw Error("facet grid: the cell must be a positive length");
    if (!(reach >= 0.0) || !std::isfinite(reach)) throw Error("facet grid: the reach must be a length >= 0");
}

void FacetGrid::rebuild(const MeshTopology& mesh) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    Vec3 lo{inf, inf, inf}, hi{-inf, -inf, -inf};
    for (const Vec3& v : mesh.vertices())
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], v[a]), hi[a] = std::max(hi[a], v[a]);
    double cells = 1.0;
    for (int a = 0; a < 3; ++a) {
        origin_[a] = lo[a] - reach_;
        const double n = std::floor((hi[a] + reach_ - origin_[a]) * per_cell_) + 1.0;
        cells *= n;
        if (!(cells <= static_cast<double>(max_cells)))
            throw Error("facet grid: the mesh's box, grown by the reach, spans more than " +
                        std::to_string(max_cells) + " cells: use a larger cell");
        dims_[a] = static_cast<std::size_t>(n);
    }

    // The cells a face's box grown by reach overlaps, per axis: from the
    // cell of its low end to that of its high end (each monotonic in the
    // coordinate, so a centre in the grown box lies in one of them). Of
    // those, the cells that come within reach of the face's plane: the
    // cell's centre p is |(p - x_0) . N| from it, and the cell's points are
    // within (cell / 2) (|N_x| + |N_y| + |N_z|) of p along N. (A large
    // tilted face's box is mostly far from the face.)
    auto index = [&](double x, int a) {
        const double u = std::floor((x - origin_[a]) * per_cell_);
        return static_cast<std::size_t>(std::clamp(u, 0.0, static_cast<double>(dims_[a] - 1)));
    };
    auto for_each_cell = [&](const FaceGeometry& g, auto&& visit) {
        std::array<std::size_t, 3> first{}, last{};
        for (int a = 0; a < 3; ++a) {
            const double low = std::min({g.corner[0][a], g.corner[1][a], g.corner[2][a]});
            const double high = std::max({g.corner[0][a], g.corner[1][a], g.corner[2][a]});
            first[a] = index(low - reach_, a);
            last[a] = index(high + reach_, a);
        }
        const double slab = reach_ + 0.5 * cell_ * (std::abs(g.normal.x) + std::abs(g.normal.y) + std::abs(g.normal.z));
        const double slack = 1e-12 * (reach_ + cell_);  // rounding
        for (std::size_t k = first[2]; k <= last[2]; ++k)
            for (std::size_t j = first[1]; j <= last[1]; ++j)
                for (std::size_t i = first[0]; i <= last[0]; ++i) {
                    const Vec3 centre = origin_ + cell_ * Vec3{i + 0.5, j + 0.5, k + 0.5};
                    if (std::abs(dot(centre - g.corner[0], g.normal)) <= slab + slack)
                        visit(i + dims_[0] * (j + dims_[1] * k));
                }
    };

    // Counting sort of (cell, face) with the faces in increasing order.
    const std::size_t n = dims_[0] * dims_[1] * dims_[2];
    start_.assign(n + 1, 0);
    std::size_t entries = 0;
    for (std::uint32_t f = 0; f < mesh.face_count(); ++f)
        for_each_cell(mesh.face(f), [&](std::size_t cell) { ++start_[cell + 1], ++entries; });
    if (entries > std::numeric_limits<std::uint32_t>::max())
        throw Error("facet grid: " + std::to_string(entries) + " entries of faces in cells: use a larger cell");
    for (std::size_t c = 0; c < n; ++c) start_[c + 1] += start_[c];
    faces_.resize(entries);
    std::vector<std::uint32_t> next(start_.begin(), start_.end() - 1);
    for (std::uint32_t f = 0; f < mesh.face_count(); ++f)
        for_each_cell(mesh.face(f), [&](std::size_t cell) { faces_[next[cell]++] = f; });
}

std::span<const std::uint32_t> FacetGrid::candidates(const Vec3& c) const {
    std::size_t cell = 0, stride = 1;
    for (int a = 0; a < 3; ++a) {
        const double u = std::floor((c[a] - origin_[a]) * per_cell_);  // as in rebuild()
        if (!(u >= 0.0 && u < static_cast<double>(dims_[a]))) return {};
        cell += static_cast<std::size_t>(u) * stride;
        stride *= dims_[a];
    }
    return {faces_.data() + start_[cell], faces_.data() + start_[cell + 1]};
}

double facet_cell(const TriangleMesh& m, double cell, double reach) {
    Vec3 lo = m.vertices.front(), hi = lo;
    for (const Vec3& v : m.vertices)
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], v[a]);
            hi[a] = std::max(hi[a], v[a]);
        }
    for (;;) {
        double cells = 1.0;
        for (int a = 0; a < 3; ++a) cells *= std::floor((hi[a] - lo[a] + 2.0 * reach) / cell) + 2.0;
        if (cells <= static_cast<double>(FacetGrid::max_cells / 4)) return cell;
        cell *= 1.5;
    }
}

}  // namespace tumble
