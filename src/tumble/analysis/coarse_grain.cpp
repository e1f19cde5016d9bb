// SPDX-License-Identifier: MIT
#include "tumble/analysis/coarse_grain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#endif

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/core/isa.hpp"

namespace tumble::analysis {

namespace {

// The kernel reaches 3 widths: beyond, the Gaussian is below 1.1 % of its
// peak (exp(-4.5)).
constexpr double reach_in_widths = 3.0;

// Doubles held per node: the accumulator's sums (mass, volume, mass x
// diameter, momentum 3, kinetic 9, contact 9) and the sample's (mass,
// momentum 3); finish() adds the velocity, the stress and six scalars.
constexpr double doubles_per_node = 24 + 4 + 18;

// v becomes n zeros. A grid's arrays are large (hundreds of MB on a 3-D
// grid) and fresh memory is mapped page by page on first touch, each page
// a fault, which on a virtual machine takes longer than the coarse-graining
// itself. On Linux the arrays are marked for transparent huge pages (2 MiB
// pages instead of 4 KiB: a 512th of the faults) and mapped in one call
// before they are zeroed. Hints only: where the kernel does not take them,
// nothing else changes.
template <class T>
void assign_zeros(std::vector<T>& v, std::size_t n) {
    std::vector<T>().swap(v);
    v.reserve(n);
#if defined(__linux__)
    const auto advise = [&](std::uintptr_t page, int advice) {
        const auto from = reinterpret_cast<std::uintptr_t>(v.data()), to = from + n * sizeof(T);
        const std::uintptr_t start = (from + page - 1) & ~(page - 1);
        if (to > start + page) madvise(reinterpret_cast<void*>(start), (to - start) & ~(page - 1), advice);
    };
#if defined(MADV_HUGEPAGE)
    advise(std::uintptr_t{2} << 20, MADV_HUGEPAGE);
#endif
#if defined(MADV_POPULATE_WRITE)
    advise(4096, MADV_POPULATE_WRITE);
#endif
#endif
    v.resize(n);
}

std::string number(double v) {
    std::ostringstream out;
    out << v;
    return out.str();
}

// The dyad f (x) b: (a, b) = f_a b_b.
Tensor dyad(const Vec3& f, const Vec3& b) {
    Tensor t;
    for (int a = 0; a < 3; ++a)
        for (int k = 0; k < 3; ++k) t.c[static_cast<std::size_t>(3 * a + k)] = f[a] * b[k];
    return t;
}

// The kernel on the grid: W(r) = A f(|r|) for |r| < c = 3w, in the D axes
// the grid resolves, times 1 / L_k for each averaged axis k (its extent).
// A makes the integral of W over the D-ball of radius c exactly 1:
//   Gaussian f = exp(-r^2 / 2w^2):
//     D = 1: 1/A = sqrt(2 pi) w erf(3 / sqrt 2)
//     D = 2: 1/A = 2 pi w^2 (1 - e^-4.5)
//     D = 3: 1/A = 4 pi w^3 (sqrt(pi/2) erf(3 / sqrt 2) - 3 e^-4.5)
//   Lucy f = (1 + 3u)(1 - u)^3 = 1 - 6u^2 + 8u^3 - 3u^4, u = r / c:
//     D = 1: A = 5 / (4c);  D = 2: A = 5 / (pi c^2);  D = 3: A = 105 / (16 pi c^3)
//   D = 0 (every axis averaged): A = 1.
class GridKernel {
public:
    explicit GridKernel(const CgSettings& s) : g_(s.grid), kind_(s.kernel), w_(s.width) {
        c_ = reach_in_widths * w_;
        int D = 0;
        double per_length = 1.0;
        for (int k = 0; k < 3; ++k) {
            if (g_.averaged[k]) per_length /= g_.hi[k] - g_.lo[k];
            else ++D;
        }
        const double e = std::exp(-0.5 * reach_in_widths * reach_in_widths);
        const double erf3 = std::erf(reach_in_widths / std::sqrt(2.0));
        double A = 1.0;
        if (kind_ == CgKernel::gaussian) {
            if (D == 1) A = 1.0 / (std::sqrt(2.0 * pi) * w_ * erf3);
            if (D == 2) A = 1.0 / (2.0 * pi * w_ * w_ * (1.0 - e));
            if (D == 3) A = 1.0 / (4.0 * pi * w_ * w_ * w_ * (std::sqrt(0.5 * pi) * erf3 - reach_in_widths * e));
        } else {
            if (D == 1) A = 5.0 / (4.0 * c_);
            if (D == 2) A = 5.0 / (pi * c_ * c_);
            if (D == 3) A = 105.0 / (16.0 * pi * c_ * c_ * c_);
        }
        A_ = A * per_length;
    }

    // Calls add(node, W(node - x)) for every node where W is not zero, x in
    // m, W in 1/m^D; nothing if x lies outside [lo, hi) along an averaged axis.
    template <class Add>
    void spread(const Vec3& x, Add&& add) {
        const double one = 1.0;
        spread_sum({&x, 1}, {&one, 1}, add);
    }

    // The same for the sum of several points' kernels, psi(node) = sum_q
    // weight_q W(node - x_q): add(node, psi) once for each node where psi is
    // not zero. Points close together (a branch's quadrature points) share
    // most of their nodes, and summing the scalar psi first makes one pass
    // of add over the nodes instead of one per point.
    template <class Add>
    void spread_sum(std::span<const Vec3> xs, std::span<const double> weights, Add&& add) {
        Box all{{0, 0, 0}, {0, 0, 0}};
        bool any = false;
        for (const Vec3& x : xs) {
            Box box;
            if (!reach(x, box)) continue;
            for (int k = 0; k < 3; ++k) {
                const std::size_t end = any ? std::max(all.first[k] + all.count[k], box.first[k] + box.count[k])
                                            : box.first[k] + box.count[k];
                all.first[k] = any ? std::min(all.first[k], box.first[k]) : box.first[k];
                all.count[k] = end - all.first[k];
            }
            any = true;
        }
        if (!any) return;
        psi_.assign(all.count[0] * all.count[1] * all.count[2], 0.0);
        const double c2 = c_ * c_;
        for (std::size_t q = 0; q < xs.size(); ++q) {
            Box box;
            if (!reach(xs[q], box)) continue;
            // Whole rows of the point's box, the nodes beyond c given 0: a
            // loop the compiler vectorises.
            const std::size_t nx = box.count[0];
            const double* d2x = d2_[0].data();
            const double* ex = e_[0].data();
            for (std::size_t cz = 0; cz < box.count[2]; ++cz)
                for (std::size_t cy = 0; cy < box.count[1]; ++cy) {
                    const double r2_yz = d2_[2][cz] + d2_[1][cy];
                    if (r2_yz >= c2) continue;
                    const double within = c2 - r2_yz;
                    const std::size_t row =
                        box.first[1] + cy - all.first[1] + all.count[1] * (box.first[2] + cz - all.first[2]);
                    double* __restrict out = psi_.data() + (box.first[0] - all.first[0]) + all.count[0] * row;
                    if (kind_ == CgKernel::gaussian) {
                        const double scale = weights[q] * A_ * e_[2][cz] * e_[1][cy];
                        for (std::size_t cx = 0; cx < nx; ++cx) out[cx] += d2x[cx] < within ? scale * ex[cx] : 0.0;
                    } else {
                        const double scale = weights[q];
                        for (std::size_t cx = 0; cx < nx; ++cx)
                            out[cx] += d2x[cx] < within ? scale * lucy(r2_yz + d2x[cx]) : 0.0;
                    }
                }
        }
        for (std::size_t c = 0; c < all.count[2]; ++c)
            for (std::size_t b = 0; b < all.count[1]; ++b) {
                const std::size_t local = all.count[0] * (b + all.count[1] * c);
                const std::size_t global =
                    all.first[0] + g_.cells[0] * (all.first[1] + b + g_.cells[1] * (all.first[2] + c));
                for (std::size_t a = 0; a < all.count[0]; ++a)
                    if (psi_[local + a] != 0.0) add(global + a, psi_[local + a]);
            }
    }

private:
    // The nodes a point reaches: first[k] .. first[k] + count[k] - 1 along axis k.
    struct Box {
        std::array<std::size_t, 3> first{}, count{};
    };

    // The box of nodes within c of x, and per axis each of its nodes' squared
    // distance from x along the axis and (Gaussian) exp(-d^2 / 2w^2), into
    // d2_ and e_; false if x reaches no node.
    bool reach(const Vec3& x, Box& box) {
        for (int k = 0; k < 3; ++k) {
            std::vector<double>& d2 = d2_[k];
            std::vector<double>& e = e_[k];
            d2.clear(), e.clear();
            if (g_.averaged[k]) {
                double at = x[k];
                if (g_.periodic[k]) {
                    const double L = g_.hi[k] - g_.lo[k];
                    at -= L * std::floor((at - g_.lo[k]) / L);
                }
                if (!(at >= g_.lo[k] && at < g_.hi[k])) return false;
                box.first[k] = 0, box.count[k] = 1;
                d2.push_back(0.0), e.push_back(1.0);
                continue;
            }
            // Nodes at lo + (a + 1/2) h within c of x.
            const double h = g_.spacing(k);
            const double from = std::ceil((x[k] - c_ - g_.lo[k]) / h - 0.5);
            const double to = std::floor((x[k] + c_ - g_.lo[k]) / h - 0.5);
            const double last = static_cast<double>(g_.cells[k] - 1);
            if (!(to >= 0.0 && from <= last)) return false;  // (also a non-finite x)
            box.first[k] = static_cast<std::size_t>(std::max(from, 0.0));
            box.count[k] = static_cast<std::size_t>(std::min(to, last)) + 1 - box.first[k];
            for (std::size_t a = 0; a < box.count[k]; ++a) {
                const double d = g_.lo[k] + (static_cast<double>(box.first[k] + a) + 0.5) * h - x[k];
                d2.push_back(d * d);
                e.push_back(kind_ == CgKernel::gaussian ? std::exp(-0.5 * d * d / (w_ * w_)) : 0.0);
            }
        }
        return true;
    }

    double lucy(double r2) const {
        const double u = std::sqrt(r2) / c_, v = 1.0 - u;
        return A_ * (1.0 + 3.0 * u) * v * v * v;
    }

    CgGrid g_;
    CgKernel kind_;
    double w_, c_, A_ = 1.0;
    // Per axis, for the point at hand: each node's squared distance from it
    // along the axis, and (Gaussian) exp(-d^2 / 2w^2).
    std::array<std::vector<double>, 3> d2_, e_;
    std::vector<double> psi_;  // spread_sum's nodes, 1/m^D
};

// The sample's velocity V = j / rho carried to x: multilinear interpolation
// between the nodes around x along the resolved axes (x beyond the outer
// nodes takes the outer ones), over the nodes that hold mass, their weights
// renormalised. A linear V is reproduced exactly.
Vec3 velocity_at(const CgGrid& g, const std::vector<double>& mass, const std::vector<Vec3>& momentum, const Vec3& x) {
    std::array<std::size_t, 3> a0{}, a1{};
    std::array<double, 3> t{};
    for (int k = 0; k < 3; ++k) {
        if (g.averaged[k] || g.cells[k] == 1) continue;
        const double u = (x[k] - g.lo[k]) / g.spacing(k) - 0.5;
        const double last = static_cast<double>(g.cells[k] - 1);
        const double clamped = std::isfinite(u) ? std::clamp(u, 0.0, last) : 0.0;
        a0[k] = static_cast<std::size_t>(std::min(std::floor(clamped), last - 1.0));
        a1[k] = a0[k] + 1;
        t[k] = clamped - static_cast<double>(a0[k]);
    }
    Vec3 sum;
    double weights = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
        double weight = 1.0;
        std::array<std::size_t, 3> a{};
        for (int k = 0; k < 3; ++k) {
            const bool upper = (corner >> k) & 1;
            if (upper && a1[k] == 0) weight = 0.0;  // an axis with one node: one corner
            a[k] = upper ? a1[k] : a0[k];
            weight *= upper ? t[k] : (a1[k] == 0 ? 1.0 : 1.0 - t[k]);
        }
        const std::size_t n = a[0] + g.cells[0] * (a[1] + g.cells[1] * a[2]);
        if (weight == 0.0 || !(mass[n] > 0.0)) continue;
        sum += (weight / mass[n]) * momentum[n];
        weights += weight;
    }
    return weights > 0.0 ? (1.0 / weights) * sum : Vec3{};
}

// The points' indices in the order of the grid's nodes nearest to them
// (x fastest, z slowest; ties by index). Points taken in this order spread
// over nodes that overlap their predecessors', which are then still in the
// cache: on a 3-D grid of a million nodes and more, taken in the order they
// are stored the points' spreading waits mostly for memory.
std::vector<std::size_t> grid_order(const CgGrid& g, std::size_t count, auto&& point) {
    std::vector<std::pair<std::size_t, std::size_t>> key(count);
    for (std::size_t i = 0; i < count; ++i) {
        const Vec3 x = point(i);
        std::size_t node = 0;
        for (int k = 2; k >= 0; --k) {
            const double u = std::floor((x[k] - g.lo[k]) / g.spacing(k));
            const double last = static_cast<double>(g.cells[k] - 1);
            node = node * g.cells[k] + static_cast<std::size_t>(std::isfinite(u) ? std::clamp(u, 0.0, last) : 0.0);
        }
        key[i] = {node, i};
    }
    std::sort(key.begin(), key.end());
    std::vector<std::size_t> order(count);
    for (std::size_t i = 0; i < count; ++i) order[i] = key[i].second;
    return order;
}

}  // namespace

Vec3 CgGrid::node(std::size_t a, std::size_t b, std::size_t c) const {
    const std::array<std::size_t, 3> index{a, b, c};
    Vec3 x;
    for (int k = 0; k < 3; ++k) x[k] = lo[k] + (static_cast<double>(index[k]) + 0.5) * spacing(k);
    return x;
}

std::string cg_settings_problem(const CgSettings& s) {
    if (!(std::isfinite(s.width) && s.width > 0.0))
        return "width: the kernel's width must be a finite number > 0 m, got " + number(s.width);
    const char* axes = "xyz";
    for (int k = 0; k < 3; ++k) {
        const std::string axis(1, axes[k]);
        if (!(std::isfinite(s.grid.lo[k]) && std::isfinite(s.grid.hi[k])))
            return "lo, hi: must be finite, got " + number(s.grid.lo[k]) + " and " + number(s.grid.hi[k]) + " along " +
                   axis;
        if (!(s.grid.hi[k] > s.grid.lo[k]))
            return "hi: must be above lo along every axis, got hi " + number(s.grid.hi[k]) + " <= lo " +
                   number(s.grid.lo[k]) + " along " + axis;
        if (s.grid.cells[k] < 1) return "cells: at least 1 along every axis, got 0 along " + axis;
        if (s.grid.averaged[k] && s.grid.cells[k] != 1)
            return "cells: an averaged axis has one cell, got " + std::to_string(s.grid.cells[k]) + " along " + axis;
        if (s.grid.periodic[k] && !s.grid.averaged[k])
            return "periodic: only an averaged axis can be periodic, not " + axis;
    }
    const double nodes = static_cast<double>(s.grid.cells[0]) * static_cast<double>(s.grid.cells[1]) *
                         static_cast<double>(s.grid.cells[2]);
    if (nodes > 1e12) return "cells: " + number(nodes) + " nodes, more than any memory holds";
    return {};
}

double cg_memory_bytes(std::size_t nodes) { return doubles_per_node * 8.0 * static_cast<double>(nodes); }

FieldAccumulator::FieldAccumulator(const CgSettings& settings) : s_(settings) {
    if (const std::string problem = cg_settings_problem(settings); !problem.empty()) throw Error(problem);
    const std::size_t n = s_.grid.nodes();
    assign_zeros(mass_, n), assign_zeros(volume_, n), assign_zeros(mass_diameter_, n);
    assign_zeros(momentum_, n);
    assign_zeros(kinetic_, n), assign_zeros(contact_, n);
    assign_zeros(sample_mass_, n), assign_zeros(sample_momentum_, n);
}

void FieldAccumulator::add(const CgGrains& grains, std::span<const CgContact> contacts) {
    const std::size_t N = grains.position.size();
    if (grains.velocity.size() != N || grains.mass.size() != N || grains.radius.size() != N)
        throw Error("coarse-graining: the grains' positions, velocities, masses and radii differ in number (" +
                    std::to_string(N) + ", " + std::to_string(grains.velocity.size()) + ", " +
                    std::to_string(grains.mass.size()) + ", " + std::to_string(grains.radius.size()) + ")");
    const auto finite = [](const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
    for (std::size_t i = 0; i < N; ++i)
        if (!finite(grains.position[i]) || !finite(grains.velocity[i]) || !(grains.mass[i] >= 0.0) ||
            !(grains.radius[i] >= 0.0) || !std::isfinite(grains.mass[i]) || !std::isfinite(grains.radius[i]))
            throw Error("coarse-graining: grain " + std::to_string(i) +
                        " has a position, velocity, mass or radius that is not finite, or a negative mass or radius");
    for (std::size_t k = 0; k < contacts.size(); ++k) {
        const CgContact& c = contacts[k];
        if (c.i >= N || (c.j != CgContact::wall && c.j >= N))
            throw Error("coarse-graining: contact " + std::to_string(k) + " names a grain beyond the " +
                        std::to_string(N) + " given");
        if (!finite(c.force) || !finite(c.branch))
            throw Error("coarse-graining: contact " + std::to_string(k) + " has a force or branch that is not finite");
    }
    GridKernel W(s_);
    const std::vector<std::size_t> by_node = grid_order(s_.grid, N, [&](std::size_t i) { return grains.position[i]; });
    std::fill(sample_mass_.begin(), sample_mass_.end(), 0.0);
    std::fill(sample_momentum_.begin(), sample_momentum_.end(), Vec3{});

    // The passes over the grains and contacts run on the processor's widest
    // vectors (core/isa.hpp): the same numbers on every level.
    run_for_isa([&] {
        // Mass, volume and momentum: rho(r) = sum_i m_i W(r - r_i) and so on.
        for (const std::size_t i : by_node) {
            const double m = grains.mass[i], R = grains.radius[i];
            const double V = 4.0 / 3.0 * pi * R * R * R;
            const Vec3 p = m * grains.velocity[i];
            W.spread(grains.position[i], [&](std::size_t n, double w) {
                sample_mass_[n] += m * w;
                volume_[n] += V * w;
                mass_diameter_[n] += 2.0 * R * m * w;
                sample_momentum_[n] += w * p;
            });
        }
        for (std::size_t n = 0; n < mass_.size(); ++n) mass_[n] += sample_mass_[n], momentum_[n] += sample_momentum_[n];

        // The contact stress, sigma_c(r) = sum_contacts f (x) b psi(r), where
        // psi(r) = int_0^1 W(r - r_i + s b) ds is the kernel along the branch
        // from r_i (s = 0) to r_i - b (s = 1). Its divergence is
        // f (W(r - r_i + b) - W(r - r_i)), so that the contacts' sum balances
        // each grain's contact force: div sigma = rho g at rest, exactly up to
        // the quadrature. Quadrature: the composite Simpson rule with M panels
        // of length |b| / M <= w (M = ceil(|b| / w)), points s_q = q / 2M, q =
        // 0 .. 2M, weights (1, 4, 2, 4, ..., 4, 1) / 6M; its error is at most
        // 3 (|b| / 2M)^4 / 180 w^4, about 0.1 % of the Gaussian's peak. The points at
        // s = 0 (at r_i) and s = 1 at the centre of j go with the grains' own
        // sums below; the others, and a wall's contact point, are spread here.
        std::vector<Tensor> at_grain(N);
        std::vector<Vec3> xs;  // a branch's quadrature points spread here, m
        std::vector<double> weights;
        for (const std::size_t k : grid_order(s_.grid, contacts.size(), [&](std::size_t k) {
                 return grains.position[contacts[k].i] - 0.5 * contacts[k].branch;
             })) {
            const CgContact& c = contacts[k];
            const double length = norm(c.branch);
            const double panels = std::max(1.0, std::ceil(length / s_.width));
            const Tensor fb = dyad(c.force, c.branch);
            const double end_weight = 1.0 / (6.0 * panels);
            add_scaled(at_grain[c.i], end_weight, fb);
            const Vec3 other_end = grains.position[c.i] - c.branch;
            const bool at_j = c.j != CgContact::wall && norm(other_end - grains.position[c.j]) <= 1e-9 * length;
            if (at_j) add_scaled(at_grain[c.j], end_weight, fb);
            const auto points = static_cast<std::size_t>(2.0 * panels);
            xs.clear(), weights.clear();
            for (std::size_t q = 1; q <= points; ++q) {
                if (q == points && at_j) break;
                weights.push_back((q == points ? 1.0 : (q % 2 == 1 ? 4.0 : 2.0)) * end_weight);
                xs.push_back(grains.position[c.i] - (static_cast<double>(q) / static_cast<double>(points)) * c.branch);
            }
            W.spread_sum(xs, weights, [&](std::size_t n, double psi) { add_scaled(contact_[n], psi, fb); });
        }

        // The kinetic stress, sum_i m_i v'_i (x) v'_i W(r - r_i) with the
        // fluctuation v'_i = v_i - V(r_i) from the sample's velocity field, and
        // the contacts' ends at the grains.
        for (const std::size_t i : by_node) {
            const Vec3 u = grains.velocity[i] - velocity_at(s_.grid, sample_mass_, sample_momentum_, grains.position[i]);
            const Tensor k = dyad(grains.mass[i] * u, u);
            const Tensor& t = at_grain[i];
            W.spread(grains.position[i], [&](std::size_t n, double w) {
                add_scaled(kinetic_[n], w, k);
                add_scaled(contact_[n], w, t);
            });
        }
    });
    ++samples_;
}

std::vector<double> FieldAccumulator::sums() const {
    std::vector<double> out;
    out.reserve(sums_per_node * mass_.size());
    for (std::size_t n = 0; n < mass_.size(); ++n) {
        out.insert(out.end(), {mass_[n], volume_[n], mass_diameter_[n], momentum_[n].x, momentum_[n].y, momentum_[n].z});
        out.insert(out.end(), kinetic_[n].c.begin(), kinetic_[n].c.end());
        out.insert(out.end(), contact_[n].c.begin(), contact_[n].c.end());
    }
    return out;
}

void FieldAccumulator::restore(std::span<const double> sums, std::size_t samples) {
    if (sums.size() != sums_per_node * mass_.size())
        throw Error("coarse-graining: " + std::to_string(sums.size()) + " sums to go on from, where a grid of " +
                    std::to_string(mass_.size()) + " nodes has " + std::to_string(sums_per_node * mass_.size()));
    if (!std::all_of(sums.begin(), sums.end(), [](double x) { return std::isfinite(x); }))
        throw Error("coarse-graining: a sum to go on from is not finite");
    for (std::size_t n = 0; n < mass_.size(); ++n) {
        const double* x = sums.data() + sums_per_node * n;
        mass_[n] = x[0], volume_[n] = x[1], mass_diameter_[n] = x[2];
        momentum_[n] = Vec3{x[3], x[4], x[5]};
        std::copy(x + 6, x + 15, kinetic_[n].c.begin());
        std::copy(x + 15, x + 24, contact_[n].c.begin());
    }
    samples_ = samples;
}

Fields FieldAccumulator::finish() && {
    const std::size_t n = mass_.size();
    const CgGrid& g = s_.grid;
    Fields f;
    f.grid = g;
    f.samples = samples_;
    sample_mass_ = {}, sample_momentum_ = {};
    // The sums over the samples become their means.
    const double per_sample = samples_ > 0 ? 1.0 / static_cast<double>(samples_) : 0.0;
    f.density = std::move(mass_), f.solid_fraction = std::move(volume_), f.diameter = std::move(mass_diameter_);
    f.momentum = std::move(momentum_), f.kinetic_stress = std::move(kinetic_), f.contact_stress = std::move(contact_);
    assign_zeros(f.velocity, n), assign_zeros(f.stress, n), assign_zeros(f.pressure, n);
    assign_zeros(f.shear_stress, n), assign_zeros(f.temperature, n), assign_zeros(f.shear_rate, n);
    assign_zeros(f.inertial_number, n), assign_zeros(f.friction, n);
    for (std::size_t k = 0; k < n; ++k) {
        const double mass = f.density[k];
        f.diameter[k] = mass > 0.0 ? f.diameter[k] / mass : 0.0;
        f.velocity[k] = mass > 0.0 ? (1.0 / mass) * f.momentum[k] : Vec3{};
        f.density[k] *= per_sample;
        f.solid_fraction[k] *= per_sample;
        f.momentum[k] *= per_sample;
        for (double& c : f.kinetic_stress[k].c) c *= per_sample;
        for (double& c : f.contact_stress[k].c) c *= per_sample;
        add_scaled(f.stress[k], 1.0, f.kinetic_stress[k]);
        add_scaled(f.stress[k], 1.0, f.contact_stress[k]);
        f.temperature[k] = mass > 0.0 ? f.kinetic_stress[k].trace() / (3.0 * f.density[k]) : 0.0;
        const Tensor& s = f.stress[k];
        const double p = s.trace() / 3.0;
        const double dxx = s(0, 0) - p, dyy = s(1, 1) - p, dzz = s(2, 2) - p;
        const double sxy = 0.5 * (s(0, 1) + s(1, 0)), sxz = 0.5 * (s(0, 2) + s(2, 0)), syz = 0.5 * (s(1, 2) + s(2, 1));
        f.pressure[k] = p;
        f.shear_stress[k] = std::sqrt(0.5 * (dxx * dxx + dyy * dyy + dzz * dzz) + sxy * sxy + sxz * sxz + syz * syz);
    }
    // The strain rate from the velocity gradient G_kl = dV_l / dx_k.
    const std::array<std::size_t, 3> stride{1, g.cells[0], g.cells[0] * g.cells[1]};
    for (std::size_t c = 0; c < g.cells[2]; ++c)
        for (std::size_t b = 0; b < g.cells[1]; ++b)
            for (std::size_t a = 0; a < g.cells[0]; ++a) {
                const std::array<std::size_t, 3> at{a, b, c};
                const std::size_t k = a + stride[1] * b + stride[2] * c;
                std::array<Vec3, 3> G{};
                for (int axis = 0; axis < 3; ++axis) {
                    const std::size_t cells = g.cells[axis];
                    if (g.averaged[axis] || cells < 2) continue;
                    const std::size_t lower = at[axis] > 0 ? k - stride[axis] : k;
                    const std::size_t upper = at[axis] + 1 < cells ? k + stride[axis] : k;
                    const double span = g.spacing(axis) * static_cast<double>((upper - lower) / stride[axis]);
                    G[axis] = (1.0 / span) * (f.velocity[upper] - f.velocity[lower]);
                }
                f.shear_rate[k] = shear_rate_of(G);
                f.inertial_number[k] = inertial_number_at(f, k, f.shear_rate[k]);
                if (f.pressure[k] > 0.0 && f.solid_fraction[k] > 0.0) f.friction[k] = f.shear_stress[k] / f.pressure[k];
            }
    return f;
}

double shear_rate_of(const std::array<Vec3, 3>& G) {
    // D = (G + G^T) / 2, its deviatoric part D', gamma_dot = sqrt(2 D':D').
    const double tr = (G[0].x + G[1].y + G[2].z) / 3.0;
    const double dxx = G[0].x - tr, dyy = G[1].y - tr, dzz = G[2].z - tr;
    const double dxy = 0.5 * (G[0].y + G[1].x), dxz = 0.5 * (G[0].z + G[2].x), dyz = 0.5 * (G[1].z + G[2].y);
    return std::sqrt(2.0 * (dxx * dxx + dyy * dyy + dzz * dzz + 2.0 * (dxy * dxy + dxz * dxz + dyz * dyz)));
}

double inertial_number_at(const Fields& f, std::size_t k, double shear_rate) {
    const double p = f.pressure[k];
    if (!(p > 0.0 && f.solid_fraction[k] > 0.0)) return 0.0;
    const double grain_density = f.density[k] / f.solid_fraction[k];
    return shear_rate * f.diameter[k] / std::sqrt(p / grain_density);
}

Fields coarse_grain(const CgSettings& settings, const CgGrains& grains, std::span<const CgContact> contacts) {
    FieldAccumulator sum(settings);
    sum.add(grains, contacts);
    return std::move(sum).finish();
}

}  // namespace tumble::analysis
