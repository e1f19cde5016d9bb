// SPDX-License-Identifier: MIT
// The pair table: effective moduli E*, G*, B* of SPEC-NOTES, computed here by
// hand from the material parameters, for the paper's materials and for a pair
// of two different materials; symmetry; rejection of bad pair properties.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tumble/core/constants.hpp"
#include "tumble/core/error.hpp"
#include "tumble/materials/pair_table.hpp"
#include "tumble/setup/paper_materials.hpp"

namespace tumble {
namespace {

// Every coefficient is a handful of floating-point operations away from the
// parameters, so engine and test may differ only by round-off: a few ulp.
constexpr double round_off = 1e-13;

// Two materials that differ in every parameter, to exercise the mixing rules.
Material soft() { return {"soft", 1.0e6, 0.3e6, 0.25, 500.0, 500.0, 1000.0, 3.6e-3}; }
Material stiff() { return {"stiff", 7.0e7, 2.6e7, 0.35, 2000.0, 300.0, 2500.0, 1.0e-3}; }

// The same quantities as the engine, written the other way round: the mixing
// rule X* = X_i X_j / (X_i f_j + X_j f_i) is 1/X* = f_i/X_i + f_j/X_j.
double hand_E_star(const Material& a, const Material& b) {
    return 1.0 / ((1.0 - a.nu * a.nu) / a.E + (1.0 - b.nu * b.nu) / b.E);
}
double hand_G_star(const Material& a, const Material& b) {
    return 1.0 / ((2.0 - a.nu) / a.G + (2.0 - b.nu) / b.G);
}
double hand_B(const Material& m) { return 9.0 * m.xi * m.eta / (3.0 * m.xi + m.eta); }
// The corrected viscous Poisson ratio (SPEC-NOTES "Corrections").
double hand_s(const Material& m) { return (3.0 * m.xi - 2.0 * m.eta) / (2.0 * (3.0 * m.xi + m.eta)); }
// The ratio as the paper prints it.
double misprinted_s(const Material& m) { return (3.0 * m.xi - 3.0 * m.eta) / (2.0 * (3.0 * m.xi + m.eta)); }
double hand_B_star(double Ba, double sa, double Bb, double sb) {
    return 1.0 / ((1.0 - sa * sa) / Ba + (1.0 - sb * sb) / Bb);
}

TEST(PairTable, PaperMaterialOneMatchesHandValues) {
    const Material m = paper::material_1();
    const PairCoefficients c = make_pair_coefficients(m, m, {0.1, 0.2});

    // E = 1e6 Pa, nu = 0.25: E* = E / (2 (1 - nu^2)) = 1e6 / 1.875.
    EXPECT_NEAR(c.E_star, 533333.3333333333, 533333.33 * round_off);
    // G = 0.3e6 Pa: G* = G / (2 (2 - nu)) = 0.3e6 / 3.5.
    EXPECT_NEAR(c.G_star, 85714.28571428571, 85714.29 * round_off);
    // xi = eta = 500 Pa s: B = 9 * 500^2 / 2000 = 1125 Pa s, s = 500/4000 =
    // 0.125, B* = B / (2 (1 - s^2)) = 1125 / 1.96875.
    EXPECT_NEAR(viscous_modulus(m), 1125.0, 1125.0 * round_off);
    EXPECT_NEAR(viscous_poisson_ratio(m), 0.125, round_off);
    EXPECT_NEAR(c.B_star, 571.4285714285714, 571.43 * round_off);
    EXPECT_EQ(c.mu, 0.1);
    EXPECT_EQ(c.W, 0.2);
    // Attraction prefactor sqrt(4/3 * 8 pi W E*) (paper eq. 7).
    EXPECT_NEAR(c.attraction, std::sqrt(4.0 / 3.0 * 8.0 * pi * 0.2 * 533333.3333333333), 1e-13 * c.attraction);
}

TEST(PairTable, MisprintedViscousPoissonRatioChangesBStarBy1_6Percent) {
    // SPEC-NOTES: the paper's s = (3 xi - 3 eta)/(2 (3 xi + eta)) gives s = 0
    // for xi = eta, so B* = B/2 = 562.5 Pa s instead of 571.43 Pa s: 1.6 %.
    const Material m = paper::material_1();
    const double B = hand_B(m);
    const double corrected = hand_B_star(B, hand_s(m), B, hand_s(m));
    const double printed = hand_B_star(B, misprinted_s(m), B, misprinted_s(m));
    EXPECT_NEAR(printed, 562.5, 562.5 * round_off);
    // 1/(1 - 1/64) - 1 = 1/63 = 1.587 %; the tolerance only absorbs round-off.
    EXPECT_NEAR(corrected / printed - 1.0, 1.0 / 63.0, round_off);

    // The engine uses the corrected value, not the printed one.
    const PairCoefficients c = make_pair_coefficients(m, m, {});
    EXPECT_NEAR(c.B_star, corrected, corrected * round_off);
    EXPECT_GT(std::abs(c.B_star / printed - 1.0), 0.015);
}

TEST(PairTable, TwoDifferentMaterialsMixLikeTheFormulas) {
    const Material a = soft(), b = stiff();
    const PairCoefficients c = make_pair_coefficients(a, b, {0.3, 0.05});
    EXPECT_NEAR(c.E_star, hand_E_star(a, b), hand_E_star(a, b) * round_off);
    EXPECT_NEAR(c.G_star, hand_G_star(a, b), hand_G_star(a, b) * round_off);
    const double B_star = hand_B_star(hand_B(a), hand_s(a), hand_B(b), hand_s(b));
    EXPECT_NEAR(c.B_star, B_star, B_star * round_off);
    EXPECT_NEAR(c.attraction, std::sqrt(4.0 / 3.0 * 8.0 * pi * 0.05 * c.E_star), c.attraction * round_off);

    // A pair is dominated by its softer partner: E* lies below the soft
    // material's own-pair value E/(1 - nu^2) but above half of it.
    const double soft_alone = a.E / (1.0 - a.nu * a.nu);
    EXPECT_LT(c.E_star, soft_alone);
    EXPECT_GT(c.E_star, 0.5 * soft_alone);
}

TEST(PairTable, TableIsSymmetricAndMatchesPairCoefficients) {
    const std::vector<Material> materials = paper::materials();
    const auto properties = paper::pair_properties();
    const PairTable table(materials, properties);
    ASSERT_EQ(table.size(), 3);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            const PairCoefficients& ij = table(i, j);
            const PairCoefficients& ji = table(j, i);
            // The mixing rules are symmetric in exact arithmetic; the two
            // orders of evaluation may differ by an ulp.
            EXPECT_NEAR(ij.E_star, ji.E_star, ij.E_star * round_off);
            EXPECT_NEAR(ij.G_star, ji.G_star, ij.G_star * round_off);
            EXPECT_NEAR(ij.B_star, ji.B_star, ij.B_star * round_off);
            EXPECT_EQ(ij.mu, properties[i][j].mu);
            EXPECT_EQ(ij.W, properties[i][j].W);
        }
    // The paper's friction table: 1-1 0.1, 1-2 0.2, 2-2 0.5, any wall pair 0.2.
    EXPECT_EQ(table(0, 0).mu, 0.1);
    EXPECT_EQ(table(0, 1).mu, 0.2);
    EXPECT_EQ(table(1, 1).mu, 0.5);
    EXPECT_EQ(table(2, 1).mu, 0.2);

    // Mixed table of two different materials, both orders.
    const PairTable mixed({soft(), stiff()}, {{{0.1, 0.2}, {0.3, 0.05}}, {{0.3, 0.05}, {0.4, 0.1}}});
    const double E_ab = hand_E_star(soft(), stiff());
    EXPECT_NEAR(mixed(0, 1).E_star, E_ab, E_ab * round_off);
    EXPECT_NEAR(mixed(1, 0).E_star, E_ab, E_ab * round_off);
    EXPECT_EQ(mixed(1, 0).mu, 0.3);
    EXPECT_EQ(mixed(1, 1).W, 0.1);
}

TEST(PairTable, RejectsAsymmetricOrIncompleteProperties) {
    const std::vector<Material> materials = {soft(), stiff()};
    // mu differs between 0-1 and 1-0.
    EXPECT_THROW(PairTable(materials, {{{0.1, 0.2}, {0.3, 0.2}}, {{0.4, 0.2}, {0.1, 0.2}}}), Error);
    // W differs between 0-1 and 1-0.
    EXPECT_THROW(PairTable(materials, {{{0.1, 0.2}, {0.3, 0.2}}, {{0.3, 0.1}, {0.1, 0.2}}}), Error);
    // A row is short.
    EXPECT_THROW(PairTable(materials, {{{0.1, 0.2}, {0.3, 0.2}}, {{0.3, 0.2}}}), Error);
    // A row is missing.
    EXPECT_THROW(PairTable(materials, {{{0.1, 0.2}, {0.3, 0.2}}}), Error);
    // The complete symmetric table is accepted.
    EXPECT_NO_THROW(PairTable(materials, {{{0.1, 0.2}, {0.3, 0.2}}, {{0.3, 0.2}, {0.1, 0.2}}}));
}

TEST(PairTable, MaterialWithoutViscosityHasNoViscousModulus) {
    // xi = eta = 0 means no internal friction: B* must be 0 (not NaN) for any
    // pair that includes it, so the viscous term vanishes.
    Material dry = soft();
    dry.xi = dry.eta = 0.0;
    EXPECT_EQ(material_problem(dry), "");
    EXPECT_EQ(make_pair_coefficients(dry, dry, {}).B_star, 0.0);
    EXPECT_EQ(make_pair_coefficients(dry, soft(), {}).B_star, 0.0);

    // Impossible materials are reported.
    Material bad = soft();
    bad.nu = 0.5;
    EXPECT_NE(material_problem(bad), "");
    bad = soft();
    bad.eta = 0.0;  // one viscosity without the other
    EXPECT_NE(material_problem(bad), "");
}

}  // namespace
}  // namespace tumble
