// SPDX-License-Identifier: MIT
#include "tumble/analysis/flowing_layer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tumble/core/error.hpp"

namespace tumble::analysis {

Vec3 DrumSurface::along() const { return {-std::cos(angle), -std::sin(angle), 0.0}; }
Vec3 DrumSurface::normal() const { return {-std::sin(angle), std::cos(angle), 0.0}; }
Vec3 DrumSurface::point(const Vec3& r) const { return {dot(along(), r), level - dot(normal(), r), r.z}; }
Vec3 DrumSurface::vector(const Vec3& v) const { return {dot(along(), v), -dot(normal(), v), v.z}; }

namespace {

// Bilinear interpolation on a cross-section's grid (resolved in x and y,
// one node along z): the four nodes around a point (x, y) and their
// weights; the edge nodes' values out to the grid's edge, nothing beyond it.
class Bilinear {
public:
    explicit Bilinear(const CgGrid& g) : g_(g) {}
    struct Corners {
        std::array<std::size_t, 4> node{};
        std::array<double, 4> weight{};  // 0 each outside the grid
    };
    Corners operator()(double x, double y) const {
        Corners c;
        if (x < g_.lo.x || x > g_.hi.x || y < g_.lo.y || y > g_.hi.y) return c;
        const auto [a, u] = cell(x, 0);
        const auto [b, v] = cell(y, 1);
        const std::size_t nx = g_.cells[0];
        c.node = {a + nx * b, a + 1 + nx * b, a + nx * (b + 1), a + 1 + nx * (b + 1)};
        c.weight = {(1 - u) * (1 - v), u * (1 - v), (1 - u) * v, u * v};
        return c;
    }

private:
    // The node below x along axis k and the fraction of the way to the next.
    std::pair<std::size_t, double> cell(double x, int k) const {
        const double n = static_cast<double>(g_.cells[static_cast<std::size_t>(k)]);
        const double at = std::clamp((x - g_.lo[k]) / g_.spacing(k) - 0.5, 0.0, n - 1.0);
        const double below = std::min(std::floor(at), std::max(n - 2.0, 0.0));
        return {static_cast<std::size_t>(below), at - below};
    }
    const CgGrid& g_;
};

// The solid fraction of a cross-section at a point (x, y), bilinear between
// the nodes (Bilinear).
class CrossSection {
public:
    explicit CrossSection(const Fields& f) : f_(f), at_(f.grid) {}
    double operator()(double x, double y) const {
        const Bilinear::Corners c = at_(x, y);
        double phi = 0.0;
        for (std::size_t k = 0; k < 4; ++k) phi += c.weight[k] * f_.solid_fraction[c.node[k]];
        return phi;
    }

private:
    const Fields& f_;
    Bilinear at_;
};

// A tensor's components in the drum's frame, T' = Q T Q^T, Q's rows t, -n
// and z: each column turned as a vector (DrumSurface::vector), then each row.
Tensor turned(const DrumSurface& surface, const Tensor& T) {
    Tensor QT, out;
    for (int b = 0; b < 3; ++b) {
        const Vec3 column = surface.vector({T(0, b), T(1, b), T(2, b)});
        for (int a = 0; a < 3; ++a) QT.c[static_cast<std::size_t>(3 * a + b)] = column[a];
    }
    for (int a = 0; a < 3; ++a) {
        const Vec3 row = surface.vector({QT(a, 0), QT(a, 1), QT(a, 2)});
        for (int b = 0; b < 3; ++b) out.c[static_cast<std::size_t>(3 * a + b)] = row[b];
    }
    return out;
}

bool is_cross_section(const CgGrid& g) {
    return g.averaged[2] && !g.averaged[0] && !g.averaged[1] && g.cells[0] >= 2 && g.cells[1] >= 2;
}

// Where the column s t + h n (h from `top` down) first reaches phi >= level:
// its h, linear between steps of `step`; NaN if it does not.
double first_crossing(const CrossSection& phi, const Vec3& t, const Vec3& n, double s, double top, double step,
                      double level) {
    double above = phi(s * t.x + top * n.x, s * t.y + top * n.y);
    for (double h = top - step; h > -top; h -= step) {
        const double here = phi(s * t.x + h * n.x, s * t.y + h * n.y);
        if (here >= level) return h + step * (here - level) / (here - above);
        above = here;
    }
    return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

DrumSurface find_drum_surface(const Fields& cs, double reach, double span) {
    const CgGrid& g = cs.grid;
    if (!is_cross_section(g))
        throw Error("drum frame: the surface is found on a cross-section resolved in x and y (2 nodes or more each) "
                    "and averaged along z");
    if (!(reach > 0.0 && std::isfinite(reach)) || !(span > 0.0 && span <= 1.0))
        throw Error("drum frame: the reach must be > 0 and the span in (0, 1]");
    DrumSurface out;
    // phi's centroid (cx, cy), m.
    double sum = 0.0, cx = 0.0, cy = 0.0;
    for (std::size_t b = 0; b < g.cells[1]; ++b)
        for (std::size_t a = 0; a < g.cells[0]; ++a) {
            const double phi = cs.solid_fraction[a + g.cells[0] * b];
            const Vec3 x = g.node(a, b, 0);
            sum += phi, cx += phi * x.x, cy += phi * x.y;
        }
    if (!(sum > 0.0)) throw Error("drum frame: no grains in the cross-section");
    cx /= sum, cy /= sum;
    // phi_ref: the median of phi over the nodes weighted by phi, the solid
    // fraction at or above which half the grains' volume lies.
    std::vector<double> sorted(cs.solid_fraction.begin(), cs.solid_fraction.end());
    std::sort(sorted.begin(), sorted.end());
    double below = 0.0;
    for (const double phi : sorted)
        if ((below += phi) >= 0.5 * sum) {
            out.solid_fraction = phi;
            break;
        }
    // phi's second moments about its centroid (m^2 per node), and their
    // long principal axis (cos a, sin a): tan 2a = 2 I_xy / (I_xx - I_yy),
    // a in (-90, 90] degrees, so that n = (-sin a, cos a) points up.
    double ixx = 0.0, iyy = 0.0, ixy = 0.0;
    for (std::size_t b = 0; b < g.cells[1]; ++b)
        for (std::size_t a = 0; a < g.cells[0]; ++a) {
            const double phi = cs.solid_fraction[a + g.cells[0] * b];
            const Vec3 x = g.node(a, b, 0);
            ixx += phi * (x.x - cx) * (x.x - cx);
            iyy += phi * (x.y - cy) * (x.y - cy);
            ixy += phi * (x.x - cx) * (x.y - cy);
        }
    out.angle = 0.5 * std::atan2(2.0 * ixy, ixx - iyy);

    const CrossSection phi(cs);
    const double step = 0.25 * std::min(g.spacing(0), g.spacing(1));  // m, along a column
    const double column = std::min(g.spacing(0), g.spacing(1));       // m, between columns
    double top = 0.0;  // m: the grid's farthest corner from the axis
    for (const double x : {g.lo.x, g.hi.x})
        for (const double y : {g.lo.y, g.hi.y}) top = std::max(top, std::hypot(x, y));
    const double phi_half = 0.5 * out.solid_fraction;  // the surface's solid fraction
    // In the fits, columns run along the uphill direction u = -t = (cos a, sin a) at s' = -s.
    {
        const Vec3 u = -out.along();
        out.level = first_crossing(phi, u, out.normal(), 0.0, top, step, phi_half);
        if (!std::isfinite(out.level)) throw Error("drum frame: no free surface: the column through the axis crosses "
                                                   "no solid fraction of half the bed's");
    }
    for (out.iterations = 1; out.iterations <= 100; ++out.iterations) {
        if (!(std::abs(out.level) < reach))
            throw Error("drum frame: no free surface: the surface line misses the circle the grains reach");
        out.half_length = std::sqrt(reach * reach - out.level * out.level);
        const Vec3 u = -out.along(), n = out.normal();
        // Least squares of h = h0 + slope s' over the columns.
        double m = 0.0, ms = 0.0, mh = 0.0, mss = 0.0, msh = 0.0;
        const double half = span * out.half_length;
        for (double s = -std::floor(half / column) * column; s <= half; s += column) {
            const double h = first_crossing(phi, u, n, s, top, step, phi_half);
            if (!std::isfinite(h)) continue;
            m += 1, ms += s, mh += h, mss += s * s, msh += s * h;
        }
        out.columns = static_cast<int>(m);
        if (m < 3 || !(m * mss - ms * ms > 0.0))
            throw Error("drum frame: no free surface: fewer than 3 columns cross half the bed's solid fraction");
        const double slope = (m * msh - ms * mh) / (m * mss - ms * ms);
        const double h0 = (mh - slope * ms) / m;
        // The line h = h0 + slope s' is at angle atan(slope) to the current one
        // and at distance h0 cos(atan slope) from the axis.
        const double turn = std::atan(slope);
        out.angle += turn;
        out.level = h0 * std::cos(turn);
        if (std::abs(turn) < 1e-6) break;
    }
    out.iterations = std::min(out.iterations, 100);
    out.half_length = std::sqrt(std::max(reach * reach - out.level * out.level, 0.0));
    return out;
}

GrainState to_drum_frame(const GrainState& state, const DrumSurface& surface) {
    GrainState out = state;
    for (Vec3& r : out.position) r = surface.point(r);
    for (Vec3& v : out.velocity) v = surface.vector(v);
    for (CgContact& c : out.contacts) {
        c.force = surface.vector(c.force);
        c.branch = surface.vector(c.branch);
    }
    return out;
}

Fields drum_profile_of(const Fields& cs, const DrumSurface& surface, const CgSettings& profile) {
    const CgGrid &g = cs.grid, &p = profile.grid;
    if (!is_cross_section(g))
        throw Error("drum frame: a profile from an average is taken on a cross-section resolved in x and y (2 nodes or "
                    "more each) and averaged along z");
    if (!(p.averaged[2] && !p.averaged[1] && p.cells[2] == 1))
        throw Error("drum frame: a profile from a cross-section is resolved along d and averaged along z");
    FieldAccumulator sum(profile);  // checks the settings before anything is allocated
    const Bilinear at(g);
    const Vec3 t = surface.along(), n = surface.normal();
    const double step = 0.25 * std::min(g.spacing(0), g.spacing(1));  // m, between points along s
    const double samples = static_cast<double>(cs.samples);
    constexpr std::size_t per_node = FieldAccumulator::sums_per_node;
    std::vector<double> sums(per_node * p.nodes(), 0.0);
    for (std::size_t b = 0; b < p.cells[1]; ++b)
        for (std::size_t a = 0; a < p.cells[0]; ++a) {
            const std::size_t node = a + p.cells[0] * b;
            const double d = p.node(a, b, 0).y, s0 = p.lo.x + static_cast<double>(a) * p.spacing(0);
            const int points = std::max(1, static_cast<int>(std::ceil(p.spacing(0) / step)));
            // The means along the node's line s t + (level - d) n, s over its
            // cell: rho, phi, rho x diameter (kg/m^3, 1, kg/m^2), j (kg/(m^2 s)),
            // the kinetic and contact stresses (Pa), in the lab's axes.
            double rho = 0.0, phi = 0.0, rho_d = 0.0;
            Vec3 j;
            Tensor kinetic, contact;
            for (int k = 0; k < points; ++k) {
                const double s = s0 + (k + 0.5) * p.spacing(0) / points;
                const Vec3 r = s * t + (surface.level - d) * n;
                const Bilinear::Corners c = at(r.x, r.y);
                for (std::size_t q = 0; q < 4; ++q) {
                    const double w = c.weight[q] / points;
                    if (w == 0.0) continue;
                    const std::size_t i = c.node[q];
                    rho += w * cs.density[i], phi += w * cs.solid_fraction[i], rho_d += w * cs.density[i] * cs.diameter[i];
                    j += w * cs.momentum[i];
                    add_scaled(kinetic, w, cs.kinetic_stress[i]);
                    add_scaled(contact, w, cs.contact_stress[i]);
                }
            }
            // Into the frame (DrumSurface::vector, turned), times the
            // samples: the accumulator's sums, in FieldAccumulator::sums()'s order.
            double* x = sums.data() + per_node * node;
            const Vec3 j_frame = surface.vector(j);
            const Tensor k_frame = turned(surface, kinetic), c_frame = turned(surface, contact);
            x[0] = samples * rho, x[1] = samples * phi, x[2] = samples * rho_d;
            for (int k = 0; k < 3; ++k) x[3 + k] = samples * j_frame[k];
            for (std::size_t k = 0; k < 9; ++k) x[6 + k] = samples * k_frame.c[k], x[15 + k] = samples * c_frame.c[k];
        }
    sum.restore(sums, cs.samples);
    return std::move(sum).finish();
}

FlowingLayer flowing_layer(const Fields& p) {
    const CgGrid& g = p.grid;
    if (!(g.averaged[0] && !g.averaged[1] && g.averaged[2] && g.cells[1] >= 2))
        throw Error("drum frame: a depth profile is resolved along d (2 nodes or more) and averaged along s and z");
    FlowingLayer out;
    const std::size_t n = g.cells[1];
    const auto depth = [&](std::size_t k) { return g.lo.y + (static_cast<double>(k) + 0.5) * g.spacing(1); };
    const auto u = [&](std::size_t k) { return p.velocity[k].x; };
    // The nodes k, k + 1 around d = 0 (the end nearest it if none).
    const double at = std::clamp(-g.lo.y / g.spacing(1) - 0.5, 0.0, static_cast<double>(n) - 1.0);
    const std::size_t k0 = std::min(static_cast<std::size_t>(at), n - 2);
    out.surface_velocity = u(k0) + (at - static_cast<double>(k0)) * (u(k0 + 1) - u(k0));
    out.thickness = std::numeric_limits<double>::quiet_NaN();
    if (out.surface_velocity > 0.0)
        for (std::size_t k = k0; k + 1 < n; ++k) {
            // From the surface down: the first node pair across which u turns uphill.
            const double a = k == k0 ? out.surface_velocity : u(k), b = u(k + 1);
            const double d = k == k0 ? std::max(depth(k0), 0.0) : depth(k);
            if (a > 0.0 && b <= 0.0) {
                out.thickness = d + (depth(k + 1) - d) * a / (a - b);
                break;
            }
        }
    double mass = 0.0, diameter = 0.0;
    for (std::size_t k = 0; k < n; ++k) mass += p.density[k], diameter += p.density[k] * p.diameter[k];
    out.diameter = mass > 0.0 ? diameter / mass : 0.0;
    return out;
}

void use_in_plane_shear_rate(Fields& profile, const Fields& across) {
    const CgGrid &p = profile.grid, &a = across.grid;
    if (!(p.averaged[0] && !p.averaged[1] && p.averaged[2] && a.cells[0] == 2 && !a.averaged[0] &&
          a.cells[1] == p.cells[1] && a.averaged[2] && a.lo.y == p.lo.y && a.hi.y == p.hi.y))
        throw Error("drum frame: the shear rate across the span needs the profile's depth nodes at 2 points along s");
    const std::size_t depths = p.cells[1];
    for (std::size_t k = 0; k < depths; ++k) {
        // G[k][l] = dV_l / dx_k in (s, d, z): along s across the span, along
        // d central differences between the profile's nodes (one-sided at
        // its ends), none along the averaged z.
        std::array<Vec3, 3> G{};
        G[0] = (1.0 / a.spacing(0)) * (across.velocity[1 + 2 * k] - across.velocity[2 * k]);
        const std::size_t lower = k > 0 ? k - 1 : k, upper = k + 1 < depths ? k + 1 : k;
        if (upper > lower)
            G[1] = (1.0 / (p.spacing(1) * static_cast<double>(upper - lower))) *
                   (profile.velocity[upper] - profile.velocity[lower]);
        profile.shear_rate[k] = shear_rate_of(G);
        profile.inertial_number[k] = inertial_number_at(profile, k, profile.shear_rate[k]);
    }
}

}  // namespace tumble::analysis
