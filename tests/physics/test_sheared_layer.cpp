// SPDX-License-Identifier: MIT
// A layer of grains sheared between two rough walls (plane Couette flow, no
// gravity, periodic along the walls), its coarse-grained stress against the
// walls' loads. In a steady shear along x between walls normal to z, the
// momentum balance of the time-averaged fields is d sigma_xz / dz = 0 (the
// divergence over the second index; no gradient along the periodic x and
// y): the shear stress is the same across the gap, and at each wall it is
// the wall's tangential load per area,
//
//     sigma_xz = F_x(top wall) / A = -F_x(bottom wall) / A,
//
// F the force of the grains on the wall (N), A its area (m^2). (Sign: the
// top wall drags the grains along +x, so they pull it back, F_x < 0; the
// traction on the layer's top face, -sigma . e_z with compression
// positive, is -F. A wall contact's share of the stress is f_x b_z with b
// from the contact point to the grain, down from the lid: negative too.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <vector>

#include "physics_helpers.hpp"
#include "tumble/analysis/coarse_grain.hpp"
#include "tumble/analysis/simulation_fields.hpp"
#include "tumble/setup/generators.hpp"

namespace {

using namespace physics_test;
using namespace tumble::analysis;

constexpr double a = 2.0 * R1;      // m: the lattice's spacing, the grains' largest diameter
constexpr int across = 6, high = 8;  // lattice sites along x and y, and across the gap
constexpr double V = 0.2;           // m/s: the top wall's speed along x

// Grains of the paper's material 1 (no attraction, static friction, mu =
// 0.5 among them and with the walls) on a simple cubic lattice of `high`
// layers between two rough walls, periodic along x and y. Each wall is a
// layer of spheres of diameter a on a prescribed motion, set between the
// grains' columns: the floor's centres at z = 0 at rest, the lid's at z =
// (high + 1) a moving along x at V. The grains' radii are drawn from [0.52
// a, 0.56 a], so that they press on each other and on the walls from the
// start, the gap's volume being fixed.
tumble::Simulation sheared_layer() {
    tumble::Scenario s = open_scenario(0.0);
    s.materials = {paper_material("grain", R1), paper_material("wall", R3)};
    s.pair_properties = {{{0.5, 0.0}, {0.5, 0.0}}, {{0.5, 0.0}, {0.5, 0.0}}};
    s.model.shear = tumble::ShearModel::Spring;
    const double L = across * a;
    s.domain.lo = {0.0, 0.0, -a};
    s.domain.hi = {L, L, (high + 2) * a};
    s.domain.periodic = {true, true, false};
    s.motions = {tumble::RigidMotion{}, tumble::RigidMotion{{}, {0.0, 0.0, 1.0}, 0.0, {V, 0.0, 0.0}}};
    s.particles = tumble::lattice({0.5 * a, 0.5 * a, a}, {across, across, high}, a, 0.5 * a, 0);
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> radius(0.52 * a, 0.56 * a);
    for (tumble::ParticleSpec& p : s.particles) p.radius = radius(random);
    for (int wall = 0; wall < 2; ++wall)
        for (tumble::ParticleSpec p : tumble::lattice({0.0, 0.0, wall * (high + 1) * a}, {across, across, 1}, a,
                                                      0.5 * a, 1)) {
            p.motion = wall;
            s.particles.push_back(p);
        }
    return tumble::Simulation(s);
}

TEST(Fields, AShearedLayerCarriesTheWallsShearStressAcrossTheGap) {
    tumble::Simulation sim = sheared_layer();
    // The gap between the walls' tops, (high + 0.5) a - 0.5 a.
    const double L = across * a, H = high * a, A = L * L, w = 0.5 * R1;
    // Sheared to a strain of 2 (V t / H) to leave the lattice's start, then
    // `samples` states 5 ms apart (a strain of 0.018 between them).
    sim.advance(static_cast<std::int64_t>(std::ceil(2.0 * H / V / sim.dt())));
    constexpr int samples = 100;
    const auto between = static_cast<std::int64_t>(std::ceil(0.005 / sim.dt()));
    CgSettings s;
    s.grid.lo = {0.0, 0.0, 0.5 * a};
    s.grid.hi = {L, L, 0.5 * a + H};
    s.grid.cells = {1, 1, static_cast<std::size_t>(std::ceil(H / (w / 2.0)))};
    s.grid.averaged = {true, true, false};
    s.grid.periodic = {true, true, false};
    s.kernel = CgKernel::lucy;
    s.width = w;
    FieldAccumulator sum(s);
    // The shear stress of each wall in each sample: the x force of its
    // contacts on the grains over the area, the lid's (a branch pointing
    // down to the grain) -F_x / A, the floor's F_x / A (Pa).
    std::vector<double> lid, floor;
    for (int k = 0; k < samples; ++k) {
        sim.set_contact_recording(true);
        sim.step();
        const GrainState state = grain_state(sim);
        sum.add(state.grains(), state.contacts);
        double on_lid = 0.0, on_floor = 0.0;
        for (const CgContact& c : state.contacts)
            if (c.j == CgContact::wall) (c.branch.z < 0.0 ? on_lid : on_floor) += c.force.x;
        lid.push_back(-on_lid / A);
        floor.push_back(on_floor / A);
        sim.set_contact_recording(false);
        sim.advance(between - 1);
    }
    const Fields f = std::move(sum).finish();
    const auto mean = [](const std::vector<double>& v) {
        double m = 0.0;
        for (double x : v) m += x;
        return m / static_cast<double>(v.size());
    };
    // The standard error of a sample mean, the samples taken as independent
    // (5 ms apart, several contact times and a strain of 0.018: the forces'
    // correlation time is shorter).
    const auto stderr_of = [&](const std::vector<double>& v) {
        const double m = mean(v);
        double s2 = 0.0;
        for (double x : v) s2 += (x - m) * (x - m);
        return std::sqrt(s2 / static_cast<double>(v.size() - 1) / static_cast<double>(v.size()));
    };
    const double tau_lid = mean(lid), tau_floor = mean(floor);
    const double error = std::hypot(stderr_of(lid), stderr_of(floor));

    // sigma_xz across the gap, 3w and more from each wall's contacts
    // (nearer, they are the stress's source), its mean there and the
    // velocity at the two ends of that range.
    double lo = 1e300, hi = -1e300, across_gap = 0.0, p = 0.0, slowest = 1e300, fastest = -1e300;
    int nodes = 0;
    for (std::size_t k = 0; k < f.grid.cells[2]; ++k) {
        const double z = f.grid.node(0, 0, k).z;
        if (z < 0.5 * a + 3.0 * w || z > 0.5 * a + H - 3.0 * w) continue;
        lo = std::min(lo, f.stress[k](0, 2));
        hi = std::max(hi, f.stress[k](0, 2));
        across_gap += f.stress[k](0, 2);
        p += f.pressure[k];
        slowest = std::min(slowest, f.velocity[k].x);
        fastest = std::max(fastest, f.velocity[k].x);
        ++nodes;
    }
    across_gap /= nodes;
    p /= nodes;
    std::printf("  [measured] lid %.4g Pa, floor %.4g Pa (standard error of their difference %.2g Pa); sigma_xz "
                "across the gap %.4g Pa (from %.4g to %.4g), pressure %.4g Pa, mu = %.3f; velocity %.3g to %.3g "
                "m/s\n",
                tau_lid, tau_floor, error, across_gap, lo, hi, p, across_gap / p, slowest, fastest);
    // The layer is sheared through, not slipping as a plug along the walls
    // (as it does between flat walls): its velocity changes by more than
    // V / 2 across the gap (measured 0.82 V).
    EXPECT_GT(fastest - slowest, 0.5 * V);
    // It carries a shear stress: mu = |sigma_xz| / p between 0.1 and 1 for
    // grains of friction 0.5 (measured 0.33).
    EXPECT_GT(std::abs(across_gap), 0.1 * p);
    EXPECT_LT(std::abs(across_gap), 1.0 * p);
    // Both walls carry the same shear stress, to the sampling's error:
    // measured 0.9 Pa apart; tolerance three standard errors (54 Pa).
    EXPECT_NEAR(tau_lid, tau_floor, 3.0 * error);
    // sigma_xz is the same everywhere across the gap: sigma_xz(z) -
    // sigma_xz(z') is the mean rate of change of the x momentum between z
    // and z' per area, zero in a steady flow to the sampling's error, which
    // is at most the walls' (measured spread 0.8 Pa; tolerance three
    // standard errors); and it is the walls' shear stress (measured 0.2 Pa
    // from their mean; tolerance the same).
    EXPECT_LT(hi - lo, 3.0 * error);
    EXPECT_NEAR(across_gap, 0.5 * (tau_lid + tau_floor), 3.0 * error);
}

}  // namespace
