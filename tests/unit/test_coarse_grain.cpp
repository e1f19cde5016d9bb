// SPDX-License-Identifier: MIT
// Coarse-graining (tumble/analysis/coarse_grain.hpp) against answers known
// without it: the kernel's normalisation, the solid fraction of a lattice, a
// rigid rotation and a simple shear, the integral of a contact's stress,
// and the refusal of impossible settings.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "tumble/analysis/coarse_grain.hpp"
#include "tumble/core/error.hpp"

namespace {

using tumble::Vec3;
using namespace tumble::analysis;

constexpr double pi = 3.14159265358979323846;

struct Grains {
    std::vector<Vec3> x, v;
    std::vector<double> m, R;
    CgGrains view() const { return {x, v, m, R}; }
    void add(Vec3 position, Vec3 velocity, double mass, double radius) {
        x.push_back(position), v.push_back(velocity), m.push_back(mass), R.push_back(radius);
    }
};

// A simple cubic lattice of n^3 touching grains of diameter a (sites k a,
// k = 0 .. n-1), density rho_s, velocity velocity(x).
template <class Velocity>
Grains lattice(int n, double a, double rho_s, Velocity velocity) {
    Grains g;
    const double R = 0.5 * a, m = rho_s * 4.0 / 3.0 * pi * R * R * R;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                const Vec3 x{i * a, j * a, k * a};
                g.add(x, velocity(x), m, R);
            }
    return g;
}

// A grid over [lo, hi]^3 with cells of size h.
CgSettings cube_grid(double lo, double hi, double h, CgKernel kernel, double width) {
    CgSettings s;
    const auto n = static_cast<std::size_t>(std::lround((hi - lo) / h));
    s.grid.lo = {lo, lo, lo};
    s.grid.hi = {hi, hi, hi};
    s.grid.cells = {n, n, n};
    s.kernel = kernel;
    s.width = width;
    return s;
}

// Whether node (a, b, c) lies at least `margin` inside [lo, hi] on every axis.
bool inside(const CgGrid& g, std::size_t a, std::size_t b, std::size_t c, double lo, double hi, double margin) {
    const Vec3 x = g.node(a, b, c);
    for (int k = 0; k < 3; ++k)
        if (x[k] < lo + margin || x[k] > hi - margin) return false;
    return true;
}

template <class F>
void each_node(const CgGrid& g, F&& f) {
    std::size_t n = 0;
    for (std::size_t c = 0; c < g.cells[2]; ++c)
        for (std::size_t b = 0; b < g.cells[1]; ++b)
            for (std::size_t a = 0; a < g.cells[0]; ++a, ++n) f(n, a, b, c);
}

// The sum of a field over the nodes times the cell volume (the resolved
// axes'), the integral of the field over the grid's resolved axes.
double integral(const Fields& f, const std::vector<double>& v) {
    double cell = 1.0;
    for (int k = 0; k < 3; ++k)
        if (!f.grid.averaged[k]) cell *= f.grid.spacing(k);
    double sum = 0.0;
    for (double x : v) sum += x;
    return sum * cell;
}

// W integrates to 1 in 1, 2 and 3 dimensions, both kernels: one grain of
// mass 1 kg at the centre of a grid 8 cells per width, the density summed
// over the nodes. The sum is a midpoint rule of W; its error is that of
// the Gaussian's step at 3w (1.1 % of the peak over a shell one cell
// thick: < 1e-3 here), of the smooth Lucy kernel far less.
TEST(CoarseGrain, TheKernelHoldsTheMassExactlyInOneTwoAndThreeDimensions) {
    const double w = 1e-3, h = w / 8.0;
    Grains g;
    g.add({0.0, 0.0, 0.0}, {}, 1.0, 1e-4);
    for (CgKernel kernel : {CgKernel::gaussian, CgKernel::lucy})
        for (int averaged = 0; averaged < 3; ++averaged) {
            CgSettings s = cube_grid(-4e-3, 4e-3, h, kernel, w);
            for (int k = 0; k < averaged; ++k) s.grid.averaged[2 - k] = true, s.grid.cells[2 - k] = 1;
            const Fields f = coarse_grain(s, g.view(), {});
            // The averaged axes divide by their extent (8 mm each).
            const double mass = integral(f, f.density) * std::pow(8e-3, averaged);
            EXPECT_NEAR(mass, 1.0, kernel == CgKernel::gaussian ? 1e-3 : 1e-5)
                << (kernel == CgKernel::gaussian ? "gaussian" : "lucy") << ", " << 3 - averaged << "-D";
        }
}

// With every axis averaged the one node holds the box's mean: the mass of
// the grains inside over the box's volume, exactly.
TEST(CoarseGrain, EveryAxisAveragedGivesTheMassOverTheVolume) {
    const Grains g = lattice(6, 1e-3, 2500.0, [](const Vec3&) { return Vec3{}; });
    CgSettings s = cube_grid(-0.5e-3, 3.5e-3, 4e-3, CgKernel::gaussian, 1e-3);  // holds 4^3 of the 6^3 grains
    s.grid.averaged = {true, true, true};
    const Fields f = coarse_grain(s, g.view(), {});
    const double expected = 64.0 * g.m[0] / std::pow(4e-3, 3);
    EXPECT_NEAR(f.density[0], expected, 1e-12 * expected);
    EXPECT_NEAR(f.solid_fraction[0], pi / 6.0, 1e-12);
}

// A touching simple cubic lattice has phi = pi/6 = 0.5236. A kernel wider
// than the spacing a sees it as uniform: the sum over the lattice of W
// differs from its integral by W's Fourier transform at the lattice's wave
// numbers 2 pi / a, which for an uncut Gaussian is exp(-2 pi^2 w^2 / a^2)
// (4e-35 at w = 2 a); the step of the cut Gaussian at 3w (1.1 % of its
// peak) rings, decaying only slowly with w: 0.18 % at w = 2 a. Lucy's
// kernel is smooth at its edge: 0.22 % at w = a, 6e-5 at 1.5 a
// (docs/FIELDS.md, "Width"). The grid covers the nodes at least 3w inside
// the lattice, at positions all over the lattice's cell.
TEST(CoarseGrain, AUniformLatticeHasTheSolidFractionOfItsPacking) {
    const double a = 1e-3, rho_s = 2500.0;
    const Grains g = lattice(20, a, rho_s, [](const Vec3&) { return Vec3{}; });
    for (const auto& [kernel, w, tolerance] :
         {std::tuple{CgKernel::gaussian, 2.0 * a, 3e-3}, std::tuple{CgKernel::lucy, a, 3e-3}}) {
        const CgSettings s = cube_grid(3.0 * w, 19 * a - 3.0 * w, 0.37 * a, kernel, w);
        const Fields f = coarse_grain(s, g.view(), {});
        std::size_t checked = 0;
        double worst = 0.0;
        each_node(f.grid, [&](std::size_t n, std::size_t i, std::size_t j, std::size_t k) {
            if (!inside(f.grid, i, j, k, 0.0, 19 * a, 3.0 * w)) return;
            ++checked;
            worst = std::max(worst, std::abs(f.solid_fraction[n] / (pi / 6.0) - 1.0));
            EXPECT_NEAR(f.density[n], rho_s * f.solid_fraction[n], 1e-9 * rho_s);
            EXPECT_NEAR(f.diameter[n], a, 1e-12);
        });
        std::printf("  [measured] %s, w = %.2g a: largest |phi / (pi/6) - 1| = %.2e over %zu nodes (tolerance %.0e)\n",
                    kernel == CgKernel::gaussian ? "gaussian" : "lucy", w / a, worst, checked, tolerance);
        EXPECT_GT(checked, 100u);
        EXPECT_LT(worst, tolerance);
    }
}

// A rigid rotation v = omega x r: where the kernel sees the lattice
// symmetrically about a node (the nodes at the centres of the lattice's
// cells) the weighted mean of the grains' positions is the node itself, so
// V = omega x r there to round-off; V at a grain, interpolated linearly
// between those nodes, is its own velocity, so the fluctuations, the
// temperature and the kinetic stress vanish, and so does the strain rate.
TEST(CoarseGrain, ARigidRotationHasItsOwnVelocityFieldAndNoTemperature) {
    const double a = 1e-3, w = a;
    const Vec3 omega{0.3, -0.5, 1.2}, centre{7.5e-3, 7.5e-3, 7.5e-3};
    const Grains g = lattice(16, a, 2500.0, [&](const Vec3& x) { return cross(omega, x - centre); });
    const CgSettings s = cube_grid(0.0, 15 * a, a, CgKernel::gaussian, w);  // nodes at (k + 1/2) a
    const Fields f = coarse_grain(s, g.view(), {});
    const double speed = norm(omega) * 15 * a;
    std::size_t checked = 0;
    each_node(f.grid, [&](std::size_t n, std::size_t i, std::size_t j, std::size_t k) {
        // The node's kernel reaches only grains whose surrounding nodes are exact.
        if (!inside(f.grid, i, j, k, 0.0, 15 * a, 3.0 * w + 2.0 * a)) return;
        ++checked;
        const Vec3 expected = cross(omega, f.grid.node(i, j, k) - centre);
        EXPECT_NEAR(norm(f.velocity[n] - expected), 0.0, 1e-12 * speed);
        EXPECT_LT(f.temperature[n], 1e-24 * speed * speed);
        EXPECT_LT(f.shear_rate[n], 1e-9 * norm(omega));
    });
    EXPECT_GT(checked, 100u);
}

// A simple shear v_x = gamma_dot y: the shear rate of the field is
// gamma_dot, its temperature none.
TEST(CoarseGrain, ASimpleShearHasItsShearRate) {
    const double a = 1e-3, gamma_dot = 40.0;
    const Grains g = lattice(16, a, 2500.0, [&](const Vec3& x) { return Vec3{gamma_dot * x.y, 0.0, 0.0}; });
    const Fields f = coarse_grain(cube_grid(0.0, 15 * a, a, CgKernel::lucy, a), g.view(), {});
    std::size_t checked = 0;
    each_node(f.grid, [&](std::size_t n, std::size_t i, std::size_t j, std::size_t k) {
        if (!inside(f.grid, i, j, k, 0.0, 15 * a, 5.0 * a)) return;
        ++checked;
        EXPECT_NEAR(f.shear_rate[n], gamma_dot, 1e-9 * gamma_dot);
        EXPECT_LT(f.temperature[n], 1e-20);
    });
    EXPECT_GT(checked, 10u);
}

// A contact of two grains (force f on i, branch b) and one of a grain with
// a wall: the contact stress integrates over space to the sum of f (x) b,
// since every quadrature point carries its weight of W, whose integral is
// 1, and the Simpson weights sum to 1 (to the midpoint rule's error over
// the grid, 6 cells per width: < 2e-3).
TEST(CoarseGrain, AContactsStressIntegratesToItsForceTimesItsBranch) {
    const double w = 0.5e-3;
    Grains g;
    g.add({0.0, 0.0, 0.0}, {}, 1e-3, 0.5e-3);
    g.add({-0.6e-3, -0.3e-3, -0.7e-3}, {}, 1e-3, 0.5e-3);
    const Vec3 b = g.x[0] - g.x[1], f{2.0, -0.5, 3.0};
    const std::vector<CgContact> contacts{{0, 1, f, b}, {0, CgContact::wall, -1.0 * f, Vec3{0.0, 0.0, -0.4e-3}}};
    for (CgKernel kernel : {CgKernel::gaussian, CgKernel::lucy}) {
        const Fields out = coarse_grain(cube_grid(-2.4e-3, 2.4e-3, w / 6.0, kernel, w), g.view(), contacts);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) {
                std::vector<double> component(out.contact_stress.size());
                for (std::size_t n = 0; n < component.size(); ++n) component[n] = out.contact_stress[n](r, c);
                const double expected = f[r] * b[c] - f[r] * (c == 2 ? -0.4e-3 : 0.0);
                EXPECT_NEAR(integral(out, component), expected, 2e-3 * 3.0 * 1e-3) << r << c;
            }
    }
}

// Impossible settings are refused by the constructor, naming the setting.
TEST(CoarseGrain, ImpossibleSettingsAreRefusedNamingTheSetting) {
    const auto problem = [](auto change) {
        CgSettings s = cube_grid(0.0, 1.0, 0.5, CgKernel::gaussian, 0.1);
        change(s);
        return cg_settings_problem(s);
    };
    EXPECT_EQ(problem([](CgSettings&) {}), "");
    EXPECT_EQ(problem([](CgSettings& s) { s.width = 0.0; }).rfind("width: ", 0), 0u);
    EXPECT_EQ(problem([](CgSettings& s) { s.width = -1.0; }).rfind("width: ", 0), 0u);
    EXPECT_EQ(problem([](CgSettings& s) { s.width = std::nan(""); }).rfind("width: ", 0), 0u);
    EXPECT_EQ(problem([](CgSettings& s) { s.grid.hi.y = 0.0; }).rfind("hi: ", 0), 0u);
    EXPECT_EQ(problem([](CgSettings& s) { s.grid.cells[1] = 0; }).rfind("cells: ", 0), 0u);
    EXPECT_EQ(problem([](CgSettings& s) { s.grid.averaged[2] = true; }).rfind("cells: ", 0), 0u);
    CgSettings bad = cube_grid(0.0, 1.0, 0.5, CgKernel::gaussian, 0.0);
    EXPECT_THROW(FieldAccumulator{bad}, tumble::Error);

    Grains g;
    g.add({0.5, 0.5, 0.5}, {}, 1.0, 0.1);
    FieldAccumulator sum(cube_grid(0.0, 1.0, 0.5, CgKernel::gaussian, 0.1));
    const std::vector<CgContact> beyond{{0, 3, {}, {}}};
    EXPECT_THROW(sum.add(g.view(), beyond), tumble::Error);
    const std::vector<CgContact> infinite{{0, CgContact::wall, {0.0, 0.0, HUGE_VAL}, {}}};
    EXPECT_THROW(sum.add(g.view(), infinite), tumble::Error);
    g.R[0] = -0.1;
    EXPECT_THROW(sum.add(g.view(), {}), tumble::Error);
    g.R[0] = 0.1, g.x[0].y = std::nan("");
    EXPECT_THROW(sum.add(g.view(), {}), tumble::Error);
}

}  // namespace
