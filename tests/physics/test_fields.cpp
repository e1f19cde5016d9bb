// SPDX-License-Identifier: MIT
// Coarse-grained fields (tumble/analysis/coarse_grain.hpp) of a column of
// grains at rest under gravity in the engine: the vertical stress is the
// weight above, and the stress balances the weight, div sigma = rho g, as
// the exact momentum balance of the coarse-graining demands.
#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>
#include <cmath>
#include <cstdio>
#include <vector>

#include "physics_helpers.hpp"
#include "tumble/analysis/coarse_grain.hpp"
#include "tumble/analysis/simulation_fields.hpp"
#include "tumble/setup/generators.hpp"

namespace {

using namespace physics_test;
using namespace tumble::analysis;

// 300 grains of the paper's material 1 (radii 3.0 to 3.6 mm, no
// attraction, mu = 0.3) poured into a box periodic in x and y (8 diameters
// wide) on a flat floor, settled until the rms speed is below 0.1 mm/s:
// about 7 layers.
tumble::Simulation settled_column() {
    tumble::Scenario s = open_scenario(0.0);
    s.materials = {paper_material("grain", R1)};
    s.pair_properties = {{{0.3, 0.0}}};
    const double L = 16.0 * R1;
    s.domain.lo = {0.0, 0.0, 0.0};
    s.domain.hi = {L, L, 0.3};
    s.domain.periodic = {true, true, false};
    s.domain.walls = {false, false, true};
    s.gravity = {0.0, 0.0, -9.81};
    s.particles = tumble::random_fill({0.0, 0.0, 0.0}, {L, L, 0.15}, 300, 3.0e-3, R1, 0, 7, {});
    tumble::Simulation sim(s);
    const auto rms_speed = [&] {
        const tumble::ParticleStore& p = sim.particles();
        double sum = 0.0;
        for (const Vec3& v : p.velocity) sum += tumble::norm2(v);
        return std::sqrt(sum / static_cast<double>(p.size()));
    };
    const auto block = static_cast<std::int64_t>(std::ceil(0.01 / sim.dt()));
    while (sim.time() < 0.3 || (rms_speed() > 1e-4 && sim.time() < 3.0)) sim.advance(block);
    EXPECT_LT(rms_speed(), 1e-4) << "the column did not settle";
    sim.set_contact_recording(true);
    sim.step();
    return sim;
}

TEST(Fields, AColumnAtRestCarriesItsWeightAndBalancesIt) {
    tumble::Simulation sim = settled_column();
    const GrainState state = grain_state(sim);
    const double g = 9.81, w = 0.5 * R1;
    double top = 0.0;
    for (std::size_t i = 0; i < state.position.size(); ++i) top = std::max(top, state.position[i].z + state.radius[i]);
    // A profile in z, averaged over the periodic x and y, 8 nodes per width.
    // Lucy's kernel is smooth: the quadrature along the branches is nearly
    // exact. The Gaussian's step at 3w (1.1 % of its peak) costs it more:
    // the quadrature along the branches cuts the steps, and every grain and
    // branch point leaves a jump in the profile 3w away, which a central
    // difference over 2h = w/4 reads as a slope of 4/w times the jump
    // (6.5 % of rho_max g here: for derivatives, the smooth kernel).
    for (const auto& [kernel, stress_tolerance, balance_tolerance] :
         {std::tuple{CgKernel::lucy, 1e-3, 1.5e-2}, std::tuple{CgKernel::gaussian, 3e-3, 0.1}}) {
        CgSettings s;
        const tumble::Domain& d = sim.scenario().domain;
        s.grid.lo = {d.lo.x, d.lo.y, 0.0};
        s.grid.hi = {d.hi.x, d.hi.y, top + 4.0 * w};
        s.grid.cells = {1, 1, static_cast<std::size_t>(std::ceil((top + 4.0 * w) / (w / 8.0)))};
        s.grid.averaged = {true, true, false};
        s.grid.periodic = {true, true, false};
        s.kernel = kernel;
        s.width = w;
        const Fields f = coarse_grain(s, state.grains(), state.contacts);
        const std::size_t n = f.grid.cells[2];
        const double h = f.grid.spacing(2);

        // The weight above each node, g int_z^top rho dz (trapezoids between
        // the nodes: the smooth profile's error is ~1e-4).
        std::vector<double> weight(n, 0.0);
        for (std::size_t k = n - 1; k-- > 0;) weight[k] = weight[k + 1] + 0.5 * h * g * (f.density[k] + f.density[k + 1]);
        const double bottom = weight[static_cast<std::size_t>(3.0 * w / h)];

        // The floor's contacts act at z = 0, as sources of stress within 3w
        // of it; above, the balance has only the grains' weight (and the
        // residual motion of the grains, rms 0.1 mm/s). The derivative is a
        // central difference, whose error, h^2/6 times the third derivative
        // of the stress, on a profile layered at the scale of the grains is
        // up to 1 % of rho_max g.
        double worst_stress = 0.0, worst_balance = 0.0, rho_max = 0.0;
        for (double rho : f.density) rho_max = std::max(rho_max, rho);
        for (std::size_t k = 1; k + 1 < n; ++k) {
            if (f.grid.node(0, 0, k).z < 3.0 * w) continue;
            worst_stress = std::max(worst_stress, std::abs(f.stress[k](2, 2) - weight[k]) / bottom);
            // div sigma = rho g: d sigma_zz / dz = -rho g, d sigma_xz / dz = 0.
            const double dzz = (f.stress[k + 1](2, 2) - f.stress[k - 1](2, 2)) / (2.0 * h);
            const double dxz = (f.stress[k + 1](0, 2) - f.stress[k - 1](0, 2)) / (2.0 * h);
            worst_balance = std::max({worst_balance, std::abs(dzz + f.density[k] * g) / (rho_max * g),
                                      std::abs(dxz) / (rho_max * g)});
        }
        // The solid fraction and the stress ratio in the middle of the column.
        const std::size_t middle = static_cast<std::size_t>(0.5 * top / h);
        const char* name = kernel == CgKernel::lucy ? "lucy" : "gaussian";
        std::printf("  [measured] %s: top %.4g m, %zu contacts, phi(middle) %.3f, sigma_zz at 3w %.4g Pa, K = "
                    "sigma_xx / sigma_zz %.3f, p / sigma_zz %.3f\n",
                    name, top, state.contacts.size(), f.solid_fraction[middle], bottom,
                    f.stress[middle](0, 0) / f.stress[middle](2, 2), f.pressure[middle] / f.stress[middle](2, 2));
        std::printf("  [measured] %s: largest |sigma_zz - weight above| / sigma_zz(3w) = %.2e (tolerance %.0e); "
                    "largest |div sigma - rho g| / (rho_max g) = %.2e (tolerance %.1e)\n",
                    name, worst_stress, stress_tolerance, worst_balance, balance_tolerance);
        EXPECT_LT(worst_stress, stress_tolerance) << name;
        EXPECT_LT(worst_balance, balance_tolerance) << name;
    }
}

}  // namespace
