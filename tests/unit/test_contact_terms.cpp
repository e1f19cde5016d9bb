// SPDX-License-Identifier: MIT
// The contact kernels, each against its formula (SPEC-NOTES "Forces and
// couple") at a state worked out by hand, with the signs of the convention:
// n from j to i, repulsive positive, attraction negative, viscosity against
// the approach. Then the composition contact_law(): torques that conserve
// angular momentum and terms that switch off one by one.
#include <gtest/gtest.h>

#include <cmath>

#include "tumble/contact/contact_law.hpp"
#include "tumble/core/constants.hpp"
#include "tumble/materials/pair_table.hpp"
#include "tumble/setup/paper_materials.hpp"

namespace tumble {
namespace {

// Kernels and hand formulas differ only in the order of a few multiplications
// and a pow() against a sqrt(): a few ulp. 1e-12 relative leaves room for
// that and nothing else.
constexpr double round_off = 1e-12;

void expect_vec_near(const Vec3& a, const Vec3& b, double tolerance) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

// The paper's material-1 pair: E* = 533333.33 Pa, G* = 85714.29 Pa,
// B* = 571.43 Pa s, mu = 0.1, W = 0.2 J/m^2.
PairCoefficients material_one_pair() {
    return make_pair_coefficients(paper::material_1(), paper::material_1(), paper::pair_properties()[0][0]);
}

// A hand state: R_i = 3.6 mm, R_j = 2.4 mm, so R* = 1.44 mm; h = 0.1 mm.
constexpr double R_i = 3.6e-3, R_j = 2.4e-3, R_star = 1.44e-3, h = 1.0e-4;

TEST(ContactTerms, HertzForceIsFourThirdsEStarSqrtRStarHToThreeHalves) {
    const double E_star = 533333.3333333333;
    const double a = std::sqrt(R_star * h);
    // Independent route: h^(3/2) through pow, sqrt(R*) separately.
    const double expected = 4.0 / 3.0 * E_star * std::sqrt(R_star) * std::pow(h, 1.5);
    EXPECT_NEAR(hertz_force(E_star, a, h), expected, expected * round_off);
    EXPECT_GT(hertz_force(E_star, a, h), 0.0);  // repulsive: along +n on i
    // Energy 8/15 E* sqrt(R*) h^(5/2), whose h-derivative is the force.
    const double energy = 8.0 / 15.0 * E_star * std::sqrt(R_star) * std::pow(h, 2.5);
    EXPECT_NEAR(hertz_energy(E_star, a, h), energy, energy * round_off);
}

TEST(ContactTerms, KuwabaraKonoOpposesTheNormalRelativeVelocity) {
    const double B_star = 571.4285714285714;
    const double a = std::sqrt(R_star * h);
    const double v_n = -0.3;  // approaching
    const double expected = -2.0 * B_star * std::sqrt(R_star) * std::pow(h, 0.5) * v_n;
    EXPECT_NEAR(kuwabara_kono_force(B_star, a, v_n), expected, std::abs(expected) * round_off);
    // Approach (v_n < 0) pushes apart, separation (v_n > 0) pulls together.
    EXPECT_GT(kuwabara_kono_force(B_star, a, -0.3), 0.0);
    EXPECT_LT(kuwabara_kono_force(B_star, a, +0.3), 0.0);
    EXPECT_EQ(kuwabara_kono_force(B_star, a, 0.0), 0.0);
}

TEST(ContactTerms, AttractionUsesRStarToTheThreeQuarters) {
    const PairCoefficients c = material_one_pair();
    const double a = std::sqrt(R_star * h);
    const double prefactor = std::sqrt(4.0 / 3.0 * 8.0 * pi * 0.2 * c.E_star);
    const double expected = -prefactor * std::pow(R_star, 0.75) * std::pow(h, 0.75);
    EXPECT_NEAR(attraction_force(c.attraction, a), expected, std::abs(expected) * round_off);
    EXPECT_LT(attraction_force(c.attraction, a), 0.0);  // attractive: along -n on i
    // The paper's printed (R*)^(1/4) would be larger by (R*)^(-1/2) = 26.4
    // for R* = 1.44 mm; the engine must not use it.
    const double printed = -prefactor * std::pow(R_star, 0.25) * std::pow(h, 0.75);
    EXPECT_GT(std::abs(attraction_force(c.attraction, a) / printed - 1.0), 0.9);
    // Energy -4/7 prefactor (R*)^(3/4) h^(7/4).
    const double energy = -4.0 / 7.0 * prefactor * std::pow(R_star, 0.75) * std::pow(h, 1.75);
    EXPECT_NEAR(attraction_energy(c.attraction, a, h), energy, std::abs(energy) * round_off);
}

TEST(ContactTerms, GeometryOfAHeadOnApproach) {
    // j at the origin, i on the +x axis moving toward it at 0.5 m/s at the
    // half step, predicted to slow by 0.1 m/s by t + dt, and sideways.
    const double distance = R_i + R_j - h;
    const Vec3 d{distance, 0.0, 0.0};
    const ContactGeometry g = make_contact_geometry(d, distance, R_i, R_j, {-0.5, 0, 0}, {0.1, 0.2, 0}, {}, {});
    expect_vec_near(g.n, {1.0, 0.0, 0.0}, 1e-15);  // from j to i
    // h = R_i + R_j - |d| loses the digits of R_i + R_j: 1e-18 m of 1e-4.
    EXPECT_NEAR(g.overlap, h, 1e-17);
    EXPECT_NEAR(g.R_star, R_star, R_star * 1e-15);
    EXPECT_NEAR(g.contact_radius, std::sqrt(R_star * h), 1e-12 * std::sqrt(R_star * h));
    EXPECT_NEAR(g.lever_i, R_i - h / 2, 1e-17);
    EXPECT_NEAR(g.lever_j, R_j - h / 2, 1e-17);
    EXPECT_NEAR(g.v_n, -0.4, 1e-15);  // at t + dt; negative while approaching
    expect_vec_near(g.v_t, {}, 1e-15);  // at the half step
    EXPECT_EQ(g.w_n, 0.0);
}

TEST(ContactTerms, GeometryOfPureRotation) {
    // j at the origin, i on +x, both at rest; i spins about z at 20 rad/s,
    // j about z at -5 rad/s and about x at 7 rad/s.
    const double distance = R_i + R_j - h;
    const Vec3 d{distance, 0.0, 0.0};
    const Vec3 omega_i{0, 0, 20.0}, omega_j{7.0, 0, -5.0};
    const ContactGeometry g = make_contact_geometry(d, distance, R_i, R_j, {}, {}, omega_i, omega_j);
    // Contact point at -L_i x from i and +L_j x from j, L = R - h/2.
    // As part of i it moves at omega_i x (-L_i x) = (0, -20 L_i, 0);
    // as part of j at omega_j x (L_j x) = (0, -5 L_j, 0) (the spin about x
    // moves no point on the x axis). Relative: (0, -20 L_i + 5 L_j, 0).
    const double L_i = R_i - h / 2, L_j = R_j - h / 2;
    expect_vec_near(g.v_t, {0.0, -20.0 * L_i + 5.0 * L_j, 0.0}, 1e-15);
    EXPECT_NEAR(g.v_n, 0.0, 1e-15);
    // w_n = (omega_i - omega_j) . n = -7 rad/s.
    EXPECT_NEAR(g.w_n, -7.0, 1e-14);

    // Rolling without slip: the surfaces move together, v_t = 0, when
    // omega_i L_i = -omega_j L_j about the same axis.
    const ContactGeometry rolling =
        make_contact_geometry(d, distance, R_i, R_j, {}, {}, {0, 0, 10.0}, {0, 0, -10.0 * L_i / L_j});
    expect_vec_near(rolling.v_t, {}, 1e-15);
}

constexpr ShearModel all_shear_models[] = {ShearModel::Paper, ShearModel::Coulomb, ShearModel::Spring};

TEST(ContactTerms, MindlinShearBelowTheStaticLimitIsTheSameSpringInEveryModel) {
    const PairCoefficients c = material_one_pair();
    const double a = std::sqrt(R_star * h);
    const double limit = 0.1;           // N: mu |F_n| with F_n = 1 N, far above the force here
    const Vec3 n{1.0, 0.0, 0.0};
    const Vec3 v_t{0.0, 0.03, -0.04};  // |v_t| = 0.05 m/s, well above v_reg
    const double dt = 1e-5, v_reg = 1e-4;
    for (ShearModel model : all_shear_models) {
        Vec3 slip{0.0, 2e-7, 1e-7};  // slip so far, m, in the contact plane
        const Vec3 F = mindlin_shear_force(model, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), n, v_t, dt, v_reg, slip);
        // The slip grows by v_t dt; the force is -16/3 G* sqrt(R* h) slip.
        const Vec3 expected_slip{0.0, 2e-7 + 3e-7, 1e-7 - 4e-7};
        expect_vec_near(slip, expected_slip, 1e-20);  // 1e-14 relative: one addition's round-off
        const double k = 16.0 / 3.0 * c.G_star * std::sqrt(R_star) * std::pow(h, 0.5);
        ASSERT_LT(k * norm(expected_slip), limit);  // the state really is below the limit
        expect_vec_near(F, -k * expected_slip, k * norm(expected_slip) * round_off);
    }
}

TEST(ContactTerms, MindlinShearRotatesTheSlipIntoTheContactPlaneKeepingItsLength) {
    const PairCoefficients c = material_one_pair();
    const double a = std::sqrt(R_star * h);
    // The normal has turned: the old slip has a component along the new n.
    const Vec3 n = (1.0 / std::sqrt(3.0)) * Vec3{1.0, 1.0, 1.0};
    for (ShearModel model : all_shear_models) {
        Vec3 slip{1e-7, -2e-7, 0.5e-7};
        const double length = norm(slip);
        const Vec3 F = mindlin_shear_force(model, slip_limits(c.shear_stiffness, c.twist_stiffness, a, 0.1), n, {}, 1e-5, 1e-4, slip);
        EXPECT_NEAR(dot(slip, n), 0.0, 1e-22);  // in the plane, to round-off of 1e-7 m
        EXPECT_NEAR(norm(slip), length, length * 1e-14);
        const double k = 16.0 / 3.0 * c.G_star * a;  // far below the limit 0.1 N
        expect_vec_near(F, -k * slip, k * length * round_off);
    }
}

// At the static limit the three models part: the slip restarts from its
// excess (Paper), or is held at the limit along the sliding velocity
// (Coulomb) or along itself (Spring). Here the slip lies along x and the
// contact now slides along y, fast.
TEST(ContactTerms, MindlinShearAtTheStaticLimitRestartsOrHolds) {
    const PairCoefficients c = material_one_pair();
    const double a = std::sqrt(R_star * h);
    const Vec3 n{0.0, 0.0, 1.0};
    const double limit = 2e-4;  // N
    const double k = 16.0 / 3.0 * c.G_star * a, held = limit / k;
    const Vec3 v_t{0.0, 0.1, 0.0};
    const double dt = 1e-5, v_reg = 1e-4;
    const Vec3 start{1.2 * held, 0.0, 0.0};
    const Vec3 trial = start + dt * v_t;
    const double length = norm(trial);
    ASSERT_LT(length, 2.0 * held);  // one tooth past the limit

    Vec3 paper = start;
    const Vec3 F_paper = mindlin_shear_force(ShearModel::Paper, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), n, v_t, dt, v_reg, paper);
    expect_vec_near(paper, {0.0, length - held, 0.0}, held * 1e-12);  // the excess, along v_t
    expect_vec_near(F_paper, -k * paper, limit * round_off);

    Vec3 coulomb = start;
    const Vec3 F_coulomb = mindlin_shear_force(ShearModel::Coulomb, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), n, v_t, dt, v_reg, coulomb);
    expect_vec_near(F_coulomb, {0.0, -limit, 0.0}, limit * round_off);  // mu |F_n| against v_t

    Vec3 spring = start;
    const Vec3 F_spring = mindlin_shear_force(ShearModel::Spring, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), n, v_t, dt, v_reg, spring);
    expect_vec_near(F_spring, (-limit / length) * trial, limit * round_off);  // mu |F_n| against the slip

    // Sustained sliding: Coulomb and Spring stay at the limit.
    for (int step = 0; step < 5; ++step) {
        EXPECT_NEAR(norm(mindlin_shear_force(ShearModel::Coulomb, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), n, v_t, dt, v_reg, coulomb)),
                    limit, limit * round_off);
        EXPECT_NEAR(norm(mindlin_shear_force(ShearModel::Spring, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), n, v_t, dt, v_reg, spring)),
                    limit, limit * round_off);
    }
}

// A contact whose limit has shrunk below its slip (the normal force fell)
// while it moves back against the slip recoils: Coulomb keeps the slip's
// direction as Spring does, so the spring pushes the contact point back
// (the force along v_t); taking v_t's direction would flip the slip and
// oppose the recoil. Moving along its slip, Coulomb slides along v_t.
TEST(ContactTerms, CoulombRecoilsWhenItsLimitShrinksUnderARecedingSlip) {
    const PairCoefficients c = material_one_pair();
    const double a = std::sqrt(R_star * h);
    const Vec3 n{0.0, 0.0, 1.0};
    const double limit = 2e-4, k = 16.0 / 3.0 * c.G_star * a, held = limit / k;
    const double dt = 1e-6, v_reg = 1e-4;  // a step's slip, 1e-7 m, well below the excess 0.5 held = 5.8e-7 m
    const Vec3 back{-0.1, 0.02, 0.0};  // against the slip, and across it
    Vec3 coulomb{1.5 * held, 0.0, 0.0}, spring = coulomb;
    const Vec3 trial = coulomb + dt * back;
    ASSERT_GT(norm(trial), held);
    const Vec3 F_coulomb = mindlin_shear_force(ShearModel::Coulomb, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), n, back, dt, v_reg, coulomb);
    const Vec3 F_spring = mindlin_shear_force(ShearModel::Spring, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), n, back, dt, v_reg, spring);
    expect_vec_near(F_coulomb, (-limit / norm(trial)) * trial, limit * round_off);
    expect_vec_near(F_coulomb, F_spring, limit * round_off);
    expect_vec_near(coulomb, spring, held * round_off);
    // Moving along its slip (faster than v_reg), it slides along v_t.
    const Vec3 ahead{0.1, 0.02, 0.0};
    Vec3 sliding{1.5 * held, 0.0, 0.0};
    const Vec3 F_sliding = mindlin_shear_force(ShearModel::Coulomb, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), n, ahead, dt, v_reg, sliding);
    expect_vec_near(F_sliding, (-limit / norm(ahead)) * ahead, limit * round_off);
}

TEST(ContactTerms, MindlinShearSlowSlipKeepsItsOwnDirectionAndNoLimitLeavesNoSlip) {
    const PairCoefficients c = material_one_pair();
    const double a = std::sqrt(R_star * h);
    const Vec3 n{0.0, 0.0, 1.0};
    const double limit = 2e-4, k = 16.0 / 3.0 * c.G_star * a, held = limit / k;
    // Slower than v_reg: the paper's readings keep the slip's direction too,
    // so a contact that creeps does not flip its force with round-off.
    const Vec3 v_slow{0.0, 2e-5, 0.0};
    for (ShearModel model : {ShearModel::Coulomb, ShearModel::Spring}) {
        Vec3 slip{1.5 * held, 0.0, 0.0};
        const Vec3 trial = slip + 1e-5 * v_slow;
        const Vec3 F = mindlin_shear_force(model, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), n, v_slow, 1e-5, 1e-4, slip);
        expect_vec_near(F, (-limit / norm(trial)) * trial, limit * round_off);
    }
    // No normal force: no friction, no slip kept, no NaN.
    for (ShearModel model : all_shear_models) {
        Vec3 slip{1e-7, 0.0, 0.0};
        const Vec3 F = mindlin_shear_force(model, slip_limits(c.shear_stiffness, c.twist_stiffness, a, 0.0), n, {0.0, 0.1, 0.0}, 1e-5, 1e-4, slip);
        EXPECT_EQ(F, Vec3{});
        EXPECT_EQ(norm(slip), 0.0);
    }
}

TEST(ContactTerms, TwistingCoupleSpringLimitAndSign) {
    const PairCoefficients c = material_one_pair();
    const double a = std::sqrt(R_star * h);
    const double v_reg = 1e-4, dt = 1e-5;
    const double k = 8.0 / 3.0 * c.G_star * std::pow(R_star * h, 1.5);
    const double w_n = 4.0;  // rad/s; the rim slides at w_n a = 1.5 mm/s >> v_reg
    // Below the limit: -8/3 G* (R* h)^(3/2) da, da integrated with its sign.
    for (ShearModel model : all_shear_models) {
        double da = 1e-3;
        const double M = twisting_couple(model, slip_limits(c.shear_stiffness, c.twist_stiffness, a, 0.1), a, w_n, dt, v_reg, da);
        EXPECT_NEAR(da, 1e-3 + 4e-5, 1e-18);
        ASSERT_LT(k * da, 3.0 * pi / 16.0 * a * 0.1);
        EXPECT_NEAR(M, -k * da, k * da * round_off);
        double back = 1e-3;
        twisting_couple(model, slip_limits(c.shear_stiffness, c.twist_stiffness, a, 0.1), a, -w_n, dt, v_reg, back);
        EXPECT_NEAR(back, 1e-3 - 4e-5, 1e-18);  // turning back unloads it
    }
    // Beyond the limit 3 pi/16 sqrt(R* h) mu |F_n| (the limit shrank under
    // the slip), spinning against the slip so far: Coulomb and Spring keep
    // the slip's own sign (the twist recoils; twisting.hpp), Paper restarts
    // from the excess along the spin.
    const double limit = 1e-5;  // N, mu |F_n|
    const double cap = 3.0 * pi / 16.0 * a * limit, held = cap / k;
    double coulomb = 1.5 * held, spring = 1.5 * held, paper = 1.5 * held;
    EXPECT_NEAR(twisting_couple(ShearModel::Coulomb, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), a, -w_n, dt, v_reg, coulomb), -cap,
                cap * round_off);
    // Spinning along the slip, Coulomb slides with the spin: the couple at
    // the limit against it.
    coulomb = -1.5 * held;
    EXPECT_NEAR(twisting_couple(ShearModel::Coulomb, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), a, -w_n, dt, v_reg, coulomb), cap,
                cap * round_off);
    EXPECT_NEAR(twisting_couple(ShearModel::Spring, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), a, -w_n, dt, v_reg, spring), -cap,
                cap * round_off);
    const double excess = 1.5 * held - w_n * dt - held;
    ASSERT_GT(excess, 0.0);
    EXPECT_NEAR(twisting_couple(ShearModel::Paper, slip_limits(c.shear_stiffness, c.twist_stiffness, a, limit), a, -w_n, dt, v_reg, paper), k * excess,
                cap * 1e-9);  // the excess is a difference of two nearly equal numbers
}

// A generic contact: unequal radii, oblique normal, every velocity nonzero.
struct GenericContact {
    Vec3 X_i{1.0e-3, 2.0e-3, -0.5e-3}, X_j;
    ContactGeometry g;
    GenericContact() {
        const Vec3 dir = (1.0 / std::sqrt(1.0 + 4.0 + 0.25)) * Vec3{1.0, -2.0, 0.5};
        X_j = X_i - (R_i + R_j - h) * dir;
        const Vec3 d = X_i - X_j;
        g = make_contact_geometry(d, norm(d), R_i, R_j, Vec3{0.1, -0.2, 0.05} - Vec3{-0.03, 0.07, 0.02},
                                  {1e-4, 2e-4, -1e-4}, {30.0, -12.0, 8.0}, {-5.0, 17.0, 40.0});
    }
};

TEST(ContactTerms, ContactLawConservesAngularMomentum) {
    const PairCoefficients c = material_one_pair();
    const GenericContact contact;
    for (ShearModel shear : all_shear_models) {
        ContactModel model;
        model.shear = shear;
        ContactHistory history;
        history.angular_slip = 2e-3;
        history.slip = Vec3{1e-7, 2e-7, 0.0};
        for (int step = 0; step < 3; ++step) {
            const ContactForces f = contact_law(c, contact.g, model, 1e-5, history);
            ASSERT_GT(norm(f.force_i - dot(f.force_i, contact.g.n) * contact.g.n), 0.0);  // shear present
            ASSERT_NE(f.twisting_couple, 0.0);
            // Total torque about the origin: X_i x F + X_j x (-F) + T_i + T_j.
            const Vec3 total = cross(contact.X_i - contact.X_j, f.force_i) + f.torque_i + f.torque_j;
            // Each term is ~ |F| R ~ 1e-2 N x 4e-3 m; round-off 1e-16 of that.
            const double scale = norm(f.force_i) * R_i + std::abs(f.twisting_couple);
            expect_vec_near(total, {}, 1e-13 * scale);
        }
    }
}

TEST(ContactTerms, ContactLawTorquesFromTheContactPoint) {
    // Torque on i = (contact point - X_i) x F_t + M n, with the contact point
    // at -L_i n from i; on j it is +L_j n from j and the force is -F_t.
    const PairCoefficients c = material_one_pair();
    const GenericContact contact;
    const ContactGeometry& g = contact.g;
    ContactHistory history;
    history.slip = Vec3{1e-7, 2e-7, 0.0};
    history.angular_slip = 2e-3;
    const ContactForces f = contact_law(c, g, ContactModel{}, 1e-5, history);
    const Vec3 F_t = f.force_i - f.normal_force * g.n;
    const double scale = norm(F_t) * R_i + std::abs(f.twisting_couple);
    expect_vec_near(f.torque_i, cross(-g.lever_i * g.n, F_t) + f.twisting_couple * g.n, 1e-13 * scale);
    expect_vec_near(f.torque_j, cross(g.lever_j * g.n, -F_t) - f.twisting_couple * g.n, 1e-13 * scale);
    // The twisting couple on i opposes the angular slip (and here w_n).
    EXPECT_LT(f.twisting_couple * g.w_n, 0.0);
}

TEST(ContactTerms, ContactLawSwitchingATermOffRemovesExactlyIt) {
    const PairCoefficients c = material_one_pair();
    const GenericContact contact;
    const ContactGeometry& g = contact.g;
    const double dt = 1e-5;
    ContactHistory start;  // small slips so that no cap is reached
    start.slip = Vec3{1e-8, 0.0, 0.0};
    start.angular_slip = 1e-5;
    auto run = [&](const ContactModel& model) {
        ContactHistory history = start;
        return contact_law(c, g, model, dt, history);
    };
    const ContactModel all;
    const ContactForces full = run(all);
    const double a = g.contact_radius;
    const double hertz = hertz_force(c.E_star, a, g.overlap);
    const double viscous = kuwabara_kono_force(c.B_star, a, g.v_n);
    const double attraction = attraction_force(c.attraction, a);
    // Every normal term is present in the full model.
    EXPECT_NEAR(full.normal_force, hertz + viscous + attraction, std::abs(hertz) * round_off);

    const Vec3 F_t_full = full.force_i - full.normal_force * g.n;
    // Shear below its cap, so it does not depend on the normal terms.
    ASSERT_LT(norm(F_t_full), 0.5 * c.mu * std::abs(full.normal_force));
    ASSERT_LT(std::abs(full.twisting_couple), 0.5 * 3.0 * pi / 16.0 * a * c.mu * std::abs(full.normal_force));
    const double tol = std::abs(hertz) * round_off;

    ContactModel m = all;
    m.elastic = false;
    ContactForces off = run(m);
    EXPECT_NEAR(off.normal_force, full.normal_force - hertz, tol);
    expect_vec_near(off.force_i - off.normal_force * g.n, F_t_full, tol);

    m = all;
    m.viscous = false;
    off = run(m);
    EXPECT_NEAR(off.normal_force, full.normal_force - viscous, tol);
    expect_vec_near(off.force_i - off.normal_force * g.n, F_t_full, tol);

    m = all;
    m.attraction = false;
    off = run(m);
    EXPECT_NEAR(off.normal_force, full.normal_force - attraction, tol);
    expect_vec_near(off.force_i - off.normal_force * g.n, F_t_full, tol);

    m = all;
    m.shear = ShearModel::Off;
    off = run(m);
    EXPECT_EQ(off.normal_force, full.normal_force);
    expect_vec_near(off.force_i, full.normal_force * g.n, tol);
    // Only the twisting couple is left in the torques.
    expect_vec_near(off.torque_i, full.twisting_couple * g.n, std::abs(full.twisting_couple) * round_off);
    expect_vec_near(off.torque_j, -full.twisting_couple * g.n, std::abs(full.twisting_couple) * round_off);
    EXPECT_EQ(off.twisting_couple, full.twisting_couple);

    m = all;
    m.twisting = false;
    off = run(m);
    EXPECT_EQ(off.twisting_couple, 0.0);
    expect_vec_near(off.force_i, full.force_i, tol);
    const double torque_tol = norm(full.torque_i) * round_off;
    expect_vec_near(off.torque_i, full.torque_i - full.twisting_couple * g.n, torque_tol);
    expect_vec_near(off.torque_j, full.torque_j + full.twisting_couple * g.n, torque_tol);

    // Everything off: nothing at all.
    m.elastic = m.viscous = m.attraction = false;
    m.shear = ShearModel::Off;
    off = run(m);
    EXPECT_EQ(off.force_i, Vec3{});
    EXPECT_EQ(off.torque_i, Vec3{});
    EXPECT_EQ(off.torque_j, Vec3{});
}

TEST(ContactTerms, ContactLawFrictionLimitUsesTheChosenNormalForce) {
    // Net (the paper): mu |F_n|, F_n the sum of elements 1-3. Jkr: mu |F_elastic
    // + F_attraction + 2 F_pull-off|, with F_pull-off = 2 pi W R*. With the
    // slip far past the limit, the Coulomb reading shows the limit itself,
    // against v_t.
    const PairCoefficients c = material_one_pair();
    const GenericContact contact;
    const ContactGeometry& g = contact.g;
    const double a = g.contact_radius;
    const double conservative = hertz_force(c.E_star, a, g.overlap) + attraction_force(c.attraction, a);
    const double pull_off = 2.0 * pi * 0.2 * g.R_star;  // the paper's W = 0.2 J/m^2
    for (FrictionNormal normal : {FrictionNormal::Net, FrictionNormal::Jkr}) {
        ContactModel model;
        model.shear = ShearModel::Coulomb;
        model.friction_normal = normal;
        ContactHistory history;
        history.slip = Vec3{0.0, 0.0, 1.0};  // far past the limit
        const ContactForces f = contact_law(c, g, model, 1e-5, history);
        const Vec3 F_t = f.force_i - f.normal_force * g.n;
        const double limit = c.mu * (normal == FrictionNormal::Net ? std::abs(f.normal_force)
                                                                     : std::abs(conservative + 2.0 * pull_off));
        EXPECT_NEAR(norm(F_t), limit, limit * round_off);
        expect_vec_near(F_t, (-limit / norm(g.v_t)) * g.v_t, limit * round_off);
    }
}

// The pull-off force of eqs. 1 + 7, the deepest pull of 4/3 E* a^3/R* -
// P a^(3/2) over a, is 3 P^2 R* / (16 E*) = 2 pi W R*: the column the Jkr
// limit uses.
TEST(ContactTerms, PullOffIsTheDeepestPullOfTheNormalLaw) {
    const PairCoefficients c = material_one_pair();
    double deepest = 0.0;
    for (int k = 1; k < 200000; ++k) {
        const double a = 1e-8 * k;  // contact radius up to 2 mm
        deepest = std::min(deepest, hertz_force(c.E_star, a, a * a / R_star) + attraction_force(c.attraction, a));
    }
    EXPECT_NEAR(-deepest, c.pull_off * R_star, 1e-6 * c.pull_off * R_star);  // grid of 1e-8 m: 1e-6 relative
    EXPECT_NEAR(c.pull_off, 2.0 * pi * 0.2, 1e-12);
}

TEST(ContactTerms, SwappedHistoryFlipsOnlyTheSlipVector) {
    ContactHistory h;
    h.angular_slip = 3e-3;
    h.slip = {1e-7, -2e-7, 3e-7};
    h.viscous_force = -2e-3;
    const ContactHistory s = h.swapped();
    EXPECT_EQ(s.angular_slip, h.angular_slip);
    EXPECT_EQ(s.viscous_force, h.viscous_force);  // along n on the first particle: the same seen from either
    EXPECT_EQ(s.slip, (Vec3{-1e-7, 2e-7, -3e-7}));
    EXPECT_TRUE(ContactHistory{}.is_zero());
    EXPECT_FALSE(h.is_zero());
}

}  // namespace
}  // namespace tumble
