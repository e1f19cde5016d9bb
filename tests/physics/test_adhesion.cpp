// SPDX-License-Identifier: MIT
// Two grains at rest, no gravity: surface attraction pulls them together,
// Hertz elasticity pushes back, internal friction damps the approach. They
// must settle where the two balance (SPEC-NOTES, corrected exponent):
//   4/3 E* sqrt(R*) h^(3/2) = sqrt(4/3 * 8 pi W E*) (R*)^(3/4) h^(3/4)
//   =>  h_eq = (A / (4/3 E*))^(4/3) (R*)^(1/3),  A = sqrt(4/3 * 8 pi W E*).
#include <gtest/gtest.h>

#include <cmath>
#include <ostream>
#include <string>

#include "physics_helpers.hpp"

namespace physics_test {
namespace {

double equilibrium_overlap(double E_star, double W, double R_star) {
    const double A = attraction_prefactor(W, E_star);
    return std::pow(A / (4.0 / 3.0 * E_star), 4.0 / 3.0) * std::cbrt(R_star);
}

struct AdhesionCase {
    int ma, mb;
};

std::ostream& operator<<(std::ostream& out, const AdhesionCase& k) {
    return out << "materials " << k.ma + 1 << " and " << k.mb + 1;
}

class AdhesionEquilibrium : public ::testing::TestWithParam<AdhesionCase> {};

TEST_P(AdhesionEquilibrium, SettlesAtTheHertzAttractionBalance) {
    const AdhesionCase k = GetParam();
    const auto materials = paper_materials();
    const double Ra = materials[k.ma].radius, Rb = materials[k.mb].radius;
    const double E_star = e_star(materials[k.ma], materials[k.mb]);
    const double W = paper_pairs()[k.ma][k.mb].W;
    const double R_star = reduced(Ra, Rb);
    const double h_eq = equilibrium_overlap(E_star, W, R_star);
    // For the paper's grains this is a few per cent of R*, as SPEC-NOTES says
    // (with the printed exponent 1/4 it would exceed the radii).
    ASSERT_GT(h_eq, 0.01 * R_star);
    ASSERT_LT(h_eq, 0.05 * R_star);

    // Every term on (the paper's model); the pair starts at rest at half the
    // equilibrium overlap, along a generic direction.
    const double dt = 2e-6;
    tumble::Scenario s = open_scenario(dt);
    const Vec3 n = (1.0 / std::sqrt(14.0)) * Vec3{1.0, 2.0, 3.0};
    const double distance = Ra + Rb - 0.5 * h_eq;
    s.particles.push_back(sphere((0.5 * distance) * n, Ra, k.ma));
    s.particles.push_back(sphere((-0.5 * distance) * n, Rb, k.mb));
    tumble::Simulation sim(s);

    // Near equilibrium the motion is over-damped (damping ratio ~1.3); its
    // slow mode relaxes with a time of order 2 B*/E* ~ 2 ms. 40 ms is ~20 of
    // those: the remaining offset, 0.5 h_eq e^-20, is far below 1e-6.
    sim.advance(std::lround(0.04 / dt));
    const double h = overlap(sim.particles(), 0, 1);
    const auto& p = sim.particles();
    const double speed = tumble::norm(p.velocity[index_of(p, 0)] - p.velocity[index_of(p, 1)]);

    // The balance point of the discrete scheme is exactly the analytic one
    // (at rest the force does not depend on dt), so what is left is the
    // relaxation (< 1e-6) and the round-off of h = R_a + R_b - |d| (~1e-11
    // relative). The brief suggests 0.1 %; 1e-5 still has a factor 10 of
    // margin and would catch a wrong prefactor (e.g. without 4/3: 10 %).
    report("equilibrium overlap (m)", h, h_eq, 1e-5);
    EXPECT_LT(relative_difference(h, h_eq), 1e-5) << "h = " << h << " vs h_eq = " << h_eq;
    // At rest: the relative speed is well below the speed scale h_eq/(2 ms) ~ 0.02 m/s.
    EXPECT_LT(speed, 1e-7);
}

std::string adhesion_case_name(const ::testing::TestParamInfo<AdhesionCase>& info) {
    return "Material" + std::to_string(info.param.ma + 1) + std::to_string(info.param.mb + 1);
}

INSTANTIATE_TEST_SUITE_P(PaperMaterials, AdhesionEquilibrium,
                         ::testing::Values(AdhesionCase{0, 0}, AdhesionCase{0, 1}, AdhesionCase{1, 1}),
                         adhesion_case_name);

}  // namespace
}  // namespace physics_test
