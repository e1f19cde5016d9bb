// SPDX-License-Identifier: MIT
// Janssen's saturation, read from the coarse-grained stress of a column of
// grains in a tall narrow box with frictional walls, sliding slowly down
// them on a sinking floor (so that the walls' friction is mobilised, as in
// a silo's discharge; a column poured and left at rest holds almost none):
// the walls carry part of the weight, so the vertical stress falls below the weight
// above and saturates with depth. Janssen's slice balance, with the walls'
// shear stress mu_w times their normal stress K sigma_zz, reads
//
//     d sigma_zz / dz' = rho g - sigma_zz / lambda,   lambda = A / (K mu_w P),
//
// z' the depth (m), A and P the box's cross-section area (m^2) and perimeter
// (m); for a uniform rho its solution is p_inf (1 - exp(-z'/lambda)), p_inf =
// rho g lambda. Here lambda is fitted to the coarse-grained sigma_zz(z') (the
// solution for the measured rho(z')), and compared with A / (K mu_w P) for
// the measured K = sigma_xx / sigma_zz and the measured wall friction mu_w
// (the friction the walls' contacts carry, which Janssen assumes the same
// everywhere).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <vector>

#include "physics_helpers.hpp"
#include "tumble/analysis/coarse_grain.hpp"
#include "tumble/analysis/simulation_fields.hpp"
#include "tumble/setup/generators.hpp"

namespace {

using namespace physics_test;
using namespace tumble::analysis;

constexpr double g = 9.81;        // m/s^2
constexpr double L = 10.0 * R1;   // m: the box's side, 5 grain diameters
constexpr double mu_wall = 0.8;   // grain-wall friction
constexpr double mu_grain = 0.5;  // grain-grain friction

// Grains of the paper's material 1 (radii 3.0 to 3.6 mm, no attraction,
// static friction) poured into the square box L x L with flat side walls of
// friction mu_wall, onto a floor that sinks at `sink` m/s: the column
// settles on it and then slides down the side walls with it, slowly, so
// that every wall contact slides and carries mu_wall times its normal force
// upward (the state Janssen assumes: the friction fully mobilised, as in a
// silo's discharge). Returned after `time` s, its contacts recorded.
constexpr double sink = 0.005;  // m/s

tumble::Simulation sliding_column(std::size_t grains, double fill_height) {
    tumble::Scenario s = open_scenario(0.0);
    s.materials = {paper_material("grain", R1), paper_material("wall", R3)};
    s.pair_properties = {{{mu_grain, 0.0}, {mu_wall, 0.0}}, {{mu_wall, 0.0}, {mu_wall, 0.0}}};
    s.domain.lo = {0.0, 0.0, -0.1};
    s.domain.hi = {L, L, fill_height + 0.05};
    s.domain.walls = {true, true, false};
    s.domain.wall_material = 1;
    tumble::Wall floor;
    floor.name = "floor";
    floor.point = {0.0, 0.0, 0.0};
    floor.normal = {0.0, 0.0, 1.0};
    floor.material = 1;
    floor.motion = 0;
    s.walls = {floor};
    s.motions = {tumble::RigidMotion{{}, {0.0, 0.0, 1.0}, 0.0, {0.0, 0.0, -sink}}};
    // Static friction: a tangential spring up to Coulomb's limit
    // (docs/MODEL.md); the paper's shear force vanishes with the sliding
    // speed.
    s.model.shear = tumble::ShearModel::Spring;
    s.gravity = {0.0, 0.0, -g};
    s.particles = tumble::random_fill({0.0, 0.0, 0.0}, {L, L, fill_height}, grains, 3.0e-3, R1, 0, 11, {});
    return tumble::Simulation(s);
}

TEST(Fields, ATallBoxWithFrictionalWallsSaturatesAsJanssenSays) {
    tumble::Simulation sim = sliding_column(400, 0.2);
    // Poured and settled on the sinking floor by 0.6 s (the grains' speeds
    // relative to the floor's are then below 1 mm/s); then 20 states 10 ms
    // apart, averaged.
    sim.advance(static_cast<std::int64_t>(std::ceil(0.6 / sim.dt())));
    const double w = 0.5 * R1;
    // The states in the floor's frame (z from the floor, which lies at
    // -sink t), on a profile in z averaged over the box's cross-section, 4
    // nodes per width; Lucy's kernel (smooth: docs/FIELDS.md, "Checks").
    // Besides, the side walls' contacts (a horizontal branch): their upward
    // force and their normal force, summed over the states.
    const auto between = static_cast<std::int64_t>(std::ceil(0.01 / sim.dt()));
    std::optional<FieldAccumulator> sum;
    double top = 0.0, up = 0.0, normal = 0.0, sinking = 0.0;
    std::size_t grains = 0;
    for (int k = 0; k < 20; ++k) {
        sim.set_contact_recording(true);
        sim.step();
        GrainState state = grain_state(sim);
        for (Vec3& x : state.position) x.z += sink * sim.time();
        if (!sum) {
            for (std::size_t i = 0; i < state.position.size(); ++i)
                top = std::max(top, state.position[i].z + state.radius[i]);
            CgSettings s;
            s.grid.lo = {0.0, 0.0, 0.0};
            s.grid.hi = {L, L, top + 4.0 * w};
            s.grid.cells = {1, 1, static_cast<std::size_t>(std::ceil((top + 4.0 * w) / (w / 4.0)))};
            s.grid.averaged = {true, true, false};
            s.kernel = CgKernel::lucy;
            s.width = w;
            sum.emplace(s);
        }
        sum->add(state.grains(), state.contacts);
        for (const CgContact& c : state.contacts) {
            if (c.j != CgContact::wall || std::abs(c.branch.z) > 1e-3 * tumble::norm(c.branch)) continue;
            up += c.force.z;
            normal += tumble::dot(c.force, c.branch) / tumble::norm(c.branch);
        }
        for (const Vec3& v : state.velocity) sinking -= v.z;
        grains += state.velocity.size();
        sim.set_contact_recording(false);
        sim.advance(between - 1);
    }
    sinking /= static_cast<double>(grains);
    const Fields f = std::move(*sum).finish();
    const std::size_t n = f.grid.cells[2];
    const double h = f.grid.spacing(2);

    // The weight above each node, g int_z^top rho dz (trapezoids), and
    // Janssen's sigma_zz for a lambda: the slice balance integrated down from
    // the top, d sigma / dz' = rho g - sigma / lambda (exact for rho
    // piecewise linear between the nodes, to O(h^2)).
    std::vector<double> weight(n, 0.0);
    for (std::size_t k = n - 1; k-- > 0;) weight[k] = weight[k + 1] + 0.5 * h * g * (f.density[k] + f.density[k + 1]);
    const auto janssen = [&](double lambda) {
        std::vector<double> sigma(n, 0.0);
        const double decay = std::exp(-h / lambda);
        for (std::size_t k = n - 1; k-- > 0;)
            sigma[k] = sigma[k + 1] * decay + 0.5 * h * g * (f.density[k] + f.density[k + 1] * decay);
        return sigma;
    };
    // The nodes fitted: from 3w above the floor (below, the floor's
    // contacts are the stress's source) to the top.
    std::vector<std::size_t> fitted;
    for (std::size_t k = 0; k < n; ++k)
        if (f.grid.node(0, 0, k).z >= 3.0 * w) fitted.push_back(k);
    const auto misfit = [&](double lambda) {
        const std::vector<double> sigma = janssen(lambda);
        double sum = 0.0;
        for (const std::size_t k : fitted) sum += std::pow(f.stress[k](2, 2) - sigma[k], 2);
        return sum;
    };
    // lambda by golden-section search over [L/20, 20 L] in log lambda.
    double a = std::log(L / 20.0), b = std::log(20.0 * L);
    const double r = 0.5 * (std::sqrt(5.0) - 1.0);
    for (int k = 0; k < 80; ++k) {
        const double c = b - r * (b - a), d = a + r * (b - a);
        if (misfit(std::exp(c)) < misfit(std::exp(d))) b = d;
        else a = c;
    }
    const double lambda = std::exp(0.5 * (a + b));
    const std::size_t bottom = fitted.front();
    const double rms = std::sqrt(misfit(lambda) / static_cast<double>(fitted.size()));

    // K = sigma_xx / sigma_zz (the mean of the two horizontal stresses),
    // the stresses summed over the lower half of the column, where sigma_zz
    // is saturated.
    double horizontal = 0.0, vertical = 0.0;
    for (const std::size_t k : fitted)
        if (f.grid.node(0, 0, k).z < 0.5 * top) {
            horizontal += 0.5 * (f.stress[k](0, 0) + f.stress[k](1, 1));
            vertical += f.stress[k](2, 2);
        }
    const double K = horizontal / vertical;
    // The walls' friction as carried: the side walls' upward force over
    // their normal force.
    const double mu_carried = up / normal;
    const double A = L * L, P = 4.0 * L;
    const double lambda_janssen = A / (K * mu_carried * P);
    std::printf("  [measured] the grains sink at %.4g m/s (the floor at %.4g)\n", sinking, sink);
    std::printf("  [measured] %zu grains, top %.4g m; sigma_zz at 3w over the floor %.4g Pa against the weight above "
                "%.4g Pa (%.2f)\n",
                grains / 20, top, f.stress[bottom](2, 2), weight[bottom],
                f.stress[bottom](2, 2) / weight[bottom]);
    std::printf("  [measured] fitted lambda %.4g m (rms misfit %.2e of sigma_zz at the bottom); K = %.3f, walls' "
                "friction carried %.3f (of mu_w = %.1f); A / (K mu P) = %.4g m, ratio %.3f\n",
                lambda, rms / f.stress[bottom](2, 2), K, mu_carried, mu_wall, lambda_janssen,
                lambda / lambda_janssen);

    // Saturation: the walls carry most of the weight: at the bottom sigma_zz
    // lies well below the weight above (without wall friction it would equal
    // it, to 1e-3: the settled column's check, test_fields.cpp). Measured
    // 0.32 of it; Janssen's p_inf / (rho g H) = lambda / H = 0.3 here.
    EXPECT_LT(f.stress[bottom](2, 2), 0.5 * weight[bottom]);
    // Janssen's shape: the fitted solution follows the measured profile, to
    // 4.6 % of sigma_zz at the bottom (rms); tolerance 8 % (the grains'
    // layering over the floor and the heap at the top, which no exponential
    // follows).
    EXPECT_LT(rms, 0.08 * f.stress[bottom](2, 2));
    // lambda agrees with A / (K mu P) for the measured K and the friction
    // the walls carry: measured 29.8 mm against 28.2 mm (ratio 1.057);
    // tolerance 20 %: Janssen takes K and the carried friction the same at
    // every depth, and here they are the means over the lower half (K) and
    // over the whole wall (mu), which vary along the column.
    EXPECT_NEAR(lambda / lambda_janssen, 1.0, 0.2);
    // The column slides down the walls with the floor (measured 5.5 mm/s
    // against 5), and the friction the walls carry cannot exceed Coulomb's
    // mu_w (measured 0.30: the grains at the walls roll as well as slide).
    EXPECT_NEAR(sinking, sink, 0.3 * sink);
    EXPECT_LE(mu_carried, mu_wall + 1e-9);
    EXPECT_GT(mu_carried, 0.1);
}

}  // namespace
