// SPDX-License-Identifier: MIT
// The particle-impact benchmarks DEM codes are verified with (Chung & Ooi,
// Granular Matter 13:643, 2011), run through the engine as a user runs them:
// at the automatic step (for the impact speed, [time_step] reference_speed)
// and at a tenth of it. Against:
//  - an independent integration of the same equations of motion in the
//    plane of the impact (normal Hertz and Kuwabara-Kono force, the
//    tangential spring k_t = S sqrt(R* h) with its slip cut back to the
//    Coulomb limit mu |N| after each step, the two spins), by classical RK4
//    at t_c / 20000;
//  - rigid-body theory where it holds: in gross sliding (the contact slides
//    through the whole impact) the contact point of a sphere on a plane
//    loses 7/2 of the tangential impulse per unit mass, and that impulse is
//    mu (1 + e) m v_n.
// The cases:
//  1. Oblique impacts of an aluminium-oxide sphere on a plane of the same
//     (their test 6: R 2.55 mm, E 380 GPa, nu 0.23, rho 4000 kg/m^3,
//     3.9 m/s, mu 0.092, no damping) from 5 to 85 degrees from the normal,
//     with the paper's stiffness and Mindlin's: tangential restitution of
//     the centre, rebound spin, slip of the contact point after the impact.
//  2. A sphere spinning as it hits the plane (their tests 7-8: topspin and
//     backspin at a constant normal speed).
//  3. Two unequal nylon spheres at a small incidence (v_t / v_n = 0.0875):
//     the tangential spring of two free spheres rings fastest.
//  4. Gross sliding with damping (e = 0.5): the tangential impulse against
//     mu (1 + e) m v_n for each shear reading and friction normal.
//  5. Recoil after slip: a contact that slides and then sticks springs
//     back (coulomb as spring).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include "physics_helpers.hpp"

namespace physics_test {
namespace {

using tumble::ShearModel;
using tumble::TangentialStiffness;
using tumble::FrictionNormal;

// An isotropic elastic material (G = E / (2 (1 + nu))) with the
// Kuwabara-Kono viscosities xi = eta (0: no damping).
tumble::Material solid(const char* name, double E, double nu, double rho, double R, double viscosity = 0.0) {
    return {name, E, E / (2.0 * (1.0 + nu)), nu, viscosity, viscosity, rho, R};
}
tumble::Material alumina(double viscosity = 0.0) { return solid("alumina", 3.8e11, 0.23, 4000.0, 2.55e-3, viscosity); }
tumble::Material nylon(double R) { return solid("nylon", 2.5e9, 0.4, 1000.0, R); }

// One impact in the x-z plane: sphere i (material 0) hits sphere j
// (material 1; a flat wall of material 1 at z = 0 if R_j = 0) at speed v,
// `angle` degrees from the normal, with spin w0 about y.
struct Impact {
    tumble::Material a, b;
    double R_j = 0.0;  // m; 0: a flat wall
    double mu = 0.092;
    double v = 3.9;          // m/s
    double angle = 45.0;     // degrees from the normal
    double w0 = 0.0;         // rad/s, about +y
    ShearModel shear = ShearModel::Spring;
    TangentialStiffness stiffness = TangentialStiffness::Paper;
    FrictionNormal friction_normal = FrictionNormal::Net;

    bool wall() const { return R_j == 0.0; }
    double R_i() const { return a.radius; }
    double v_t() const { return v * std::sin(angle * pi / 180.0); }
    double v_n() const { return v * std::cos(angle * pi / 180.0); }
};

// What the impact leaves: relative tangential velocity of the centres (i
// minus j) and of the contact point, both spins, the normal separation
// speed. All along x / about y.
struct Outcome {
    double v_x = 0.0, slip_velocity = 0.0, w_i = 0.0, w_j = 0.0, v_separation = 0.0;
    double max_overlap = 0.0, contact_time = 0.0;  // m, s (the engine's: from the steps, interpolated at h = 0)
    bool separated = false;
};

tumble::Scenario impact_scenario(const Impact& k, double dt) {
    tumble::Scenario s;
    s.materials = {k.a, k.b};
    s.pair_properties = {{{k.mu, 0.0}, {k.mu, 0.0}}, {{k.mu, 0.0}, {k.mu, 0.0}}};
    s.model.attraction = false;
    s.model.shear = k.shear;
    s.model.tangential_stiffness = k.stiffness;
    s.model.friction_normal = k.friction_normal;
    const double L = 1.0;
    s.domain.lo = {-L, -L, k.wall() ? 0.0 : -L};
    s.domain.hi = {L, L, L};
    if (k.wall()) {
        s.domain.walls = {false, false, true};
        s.domain.wall_material = 1;
    }
    s.time_step.reference_speed = k.v;
    s.time_step.dt = dt;
    const double z = k.wall() ? k.R_i() : k.R_i() + k.R_j;
    s.particles.push_back(sphere({0.0, 0.0, z}, k.R_i(), 0, {k.v_t(), 0.0, -k.v_n()}, {0.0, k.w0, 0.0}));
    if (!k.wall()) s.particles.push_back(sphere({0.0, 0.0, 0.0}, k.R_j, 1));
    return s;
}

double automatic_step(const Impact& k) { return tumble::Simulation(impact_scenario(k, 0.0)).dt(); }

Outcome engine_impact(const Impact& k, double dt) {
    tumble::Simulation sim(impact_scenario(k, dt));
    const auto gap = [&] {
        const auto& p = sim.particles();
        const std::size_t i = index_of(p, 0);
        if (k.wall()) return p.position[i].z - k.R_i();
        const std::size_t j = index_of(p, 1);
        return tumble::norm(p.position[i] - p.position[j]) - k.R_i() - k.R_j;
    };
    bool touched = false;
    Outcome o;
    double before = gap(), t_in = 0.0;
    for (long step = 0; step < 100000; ++step) {
        sim.advance(1);
        const double d = gap();
        o.max_overlap = std::max(o.max_overlap, -d);
        // The gap is linear in t near its zeros (no force there): interpolate.
        const double crossing = sim.time() - sim.dt() * d / (d - before);
        if (!touched && d < 0.0) t_in = crossing;
        touched = touched || d < 0.0;
        if (touched && d > 0.0) {
            o.contact_time = crossing - t_in;
            o.separated = true;
            break;
        }
        before = d;
    }
    const auto& p = sim.particles();
    const std::size_t i = index_of(p, 0);
    const Vec3 vi = p.velocity[i], wi = p.angular_velocity[i];
    Vec3 vj, wj;
    if (!k.wall()) {
        const std::size_t j = index_of(p, 1);
        vj = p.velocity[j], wj = p.angular_velocity[j];
    }
    // The normal at separation (it turns while two spheres roll on each
    // other), the tangent t = (n_z, 0, -n_x).
    Vec3 n{0.0, 0.0, 1.0};
    if (!k.wall()) n = (1.0 / tumble::norm(p.position[i] - p.position[index_of(p, 1)])) *
                       (p.position[i] - p.position[index_of(p, 1)]);
    const Vec3 v = vi - vj;
    o.v_x = v.x;
    o.w_i = wi.y, o.w_j = wj.y;
    o.v_separation = tumble::dot(v, n);
    // The contact point's slip velocity (geometry.hpp, the levers at h = 0):
    // (v_i - v_j) . t - (R_i w_i + R_j w_j).
    o.slip_velocity = v.x * n.z - v.z * n.x - (k.R_i() * o.w_i + k.R_j * o.w_j);
    return o;
}

// ---- The independent integration -----------------------------------------

// The planar equations of the same contact law, written out from
// docs/MODEL.md, in the x-z plane: the position r = (X, Z) and velocity V
// of i relative to j (of i above the wall's plane), the spins w about y,
// and the tangential spring's slip xi along t = (n_z, -n_x), with n = r/|r|
// (+z for the wall) and the overlap h = R_i + R_j - |r| (R_i - Z):
//   m* V'      = F_n n + F_t t,
//   F_n        = K h^(3/2) - C h^(1/2) (V . n),  K = 4/3 E* sqrt(R*), C = 2 B* sqrt(R*)
//   xi'        = u = V . t - (L_i w_i + L_j w_j),  L = R - h/2
//   F_t        = -S sqrt(R* h) xi,  |xi| cut back to mu |N| / (S sqrt(R* h)) after each step
//   I w'       = -L F_t  (for i and j alike)
// with N the net normal force (net) or the elastic one (jkr without
// attraction). The slip is a length along t, which turns with n as the
// engine turns its slip vector. Classical RK4; ends when h returns to 0
// (interpolated). Cutting the slip back after each step makes the scheme
// first order where the contact slides: reference() extrapolates.
Outcome reference_impact(const Impact& k, double step) {
    const tumble::Material &a = k.a, &b = k.b;
    const double E_star = e_star(a, b), G_star = g_star(a, b);
    const double B_star = a.xi > 0.0 ? b_star(a, b) : 0.0;
    const double R_i = k.R_i(), R_j = k.R_j, R_star = k.wall() ? R_i : reduced(R_i, R_j);
    const double m_i = sphere_mass(a.rho, R_i), I_i = 0.4 * m_i * R_i * R_i;
    const double m_j = k.wall() ? 0.0 : sphere_mass(b.rho, R_j), I_j = 0.4 * m_j * R_j * R_j;
    const double inv_I_j = k.wall() ? 0.0 : 1.0 / I_j;
    const double inv_m_star = 1.0 / m_i + (k.wall() ? 0.0 : 1.0 / m_j);
    // The stiffness per contact radius, S (Pa): 16/3 G* or Mindlin's 8 G*.
    const double S = (k.stiffness == TangentialStiffness::Mindlin ? 8.0 : 16.0 / 3.0) * G_star;
    const double K = 4.0 / 3.0 * E_star * std::sqrt(R_star), C = 2.0 * B_star * std::sqrt(R_star);

    struct State {
        double X, Z, VX, VZ, wi, wj, xi;
    };
    struct Contact {
        double nx, nz, h, elastic, F_n, u;
    };
    auto contact = [&](const State& s) {
        Contact c;
        const double distance = k.wall() ? s.Z : std::hypot(s.X, s.Z);
        c.nx = k.wall() ? 0.0 : s.X / distance, c.nz = k.wall() ? 1.0 : s.Z / distance;
        c.h = (k.wall() ? R_i : R_i + R_j) - distance;
        const double hp = std::max(c.h, 0.0);
        c.elastic = K * hp * std::sqrt(hp);
        c.F_n = c.elastic - C * std::sqrt(hp) * (s.VX * c.nx + s.VZ * c.nz);
        const double L_i = R_i - 0.5 * hp, L_j = k.wall() ? 0.0 : R_j - 0.5 * hp;
        c.u = s.VX * c.nz - s.VZ * c.nx - (L_i * s.wi + L_j * s.wj);
        return c;
    };
    auto rate = [&](const State& s) {
        const Contact c = contact(s);
        const double hp = std::max(c.h, 0.0), L_i = R_i - 0.5 * hp, L_j = R_j - 0.5 * hp;
        const double F_t = -S * std::sqrt(R_star * hp) * s.xi;
        const double FX = c.F_n * c.nx + F_t * c.nz, FZ = c.F_n * c.nz - F_t * c.nx;
        return State{s.VX, s.VZ, FX * inv_m_star, FZ * inv_m_star, -L_i * F_t / I_i, -L_j * F_t * inv_I_j, c.u};
    };
    auto add = [](const State& s, const State& d, double f) {
        return State{s.X + f * d.X,   s.Z + f * d.Z,   s.VX + f * d.VX, s.VZ + f * d.VZ,
                     s.wi + f * d.wi, s.wj + f * d.wj, s.xi + f * d.xi};
    };
    State s{0.0, k.wall() ? R_i : R_i + R_j, k.v_t(), -k.v_n(), k.w0, 0.0, 0.0};
    Outcome o;
    for (long n = 0; n < 100'000'000; ++n) {
        const State k1 = rate(s), k2 = rate(add(s, k1, 0.5 * step)), k3 = rate(add(s, k2, 0.5 * step)),
                    k4 = rate(add(s, k3, step));
        State next = add(s, add(add(add(k1, k2, 2.0), k3, 2.0), k4, 1.0), step / 6.0);
        // The Coulomb limit on the slip.
        const Contact c = contact(next);
        const double N = k.friction_normal == FrictionNormal::Jkr ? c.elastic : c.F_n;
        const double k_t = S * std::sqrt(R_star * std::max(c.h, 0.0));
        const double held = k_t > 0.0 ? k.mu * std::abs(N) / k_t : 0.0;
        if (std::abs(next.xi) > held) next.xi = std::copysign(held, next.xi);
        if (n > 0 && c.h <= 0.0) {
            const double h_before = contact(s).h;
            const State at = add(s, add(next, s, -1.0), h_before / (h_before - c.h));  // the crossing inside the step
            const Contact end = contact(at);
            o.separated = true;
            o.v_x = at.VX;
            o.w_i = at.wi, o.w_j = at.wj;
            o.v_separation = at.VX * end.nx + at.VZ * end.nz;
            o.slip_velocity = at.VX * end.nz - at.VZ * end.nx - (R_i * at.wi + (k.wall() ? 0.0 : R_j * at.wj));
            return o;
        }
        s = next;
    }
    return o;
}

// The undamped Hertz collision time of the impact's normal motion, s.
double collision_time(const Impact& k) {
    const double R_star = k.wall() ? k.R_i() : reduced(k.R_i(), k.R_j);
    const double m_i = sphere_mass(k.a.rho, k.R_i());
    const double m_star = k.wall() ? m_i : reduced(m_i, sphere_mass(k.b.rho, k.R_j));
    return hertz_duration_constant() * hertz_max_overlap(m_star, e_star(k.a, k.b), R_star, k.v_n()) / k.v_n();
}

// The largest difference of the tangential outcome (centre velocity,
// contact-point slip, rim speeds R w) from the reference, over the
// incoming tangential speed scale (v_t, or the rim speed R w0 if larger).
double tangential_error(const Impact& k, const Outcome& e, const Outcome& r) {
    const double scale = std::max(k.v_t(), std::abs(k.w0) * k.R_i());
    double error = std::max(std::abs(e.v_x - r.v_x), std::abs(e.slip_velocity - r.slip_velocity));
    error = std::max(error, std::abs(e.w_i - r.w_i) * k.R_i());
    if (!k.wall()) error = std::max(error, std::abs(e.w_j - r.w_j) * k.R_j);
    return error / scale;
}

// The integration at t_c / 40000, extrapolated from t_c / 20000 to step 0
// as a first-order scheme; `spread` gets the tangential difference of the
// two, over v_t (the first order's error bound of the finer one).
Outcome reference(const Impact& k, double* spread = nullptr) {
    const Outcome fine = reference_impact(k, collision_time(k) / 40000.0);
    const Outcome coarse = reference_impact(k, collision_time(k) / 20000.0);
    auto extrapolate = [](double f, double c) { return 2.0 * f - c; };
    Outcome o = fine;
    o.v_x = extrapolate(fine.v_x, coarse.v_x);
    o.slip_velocity = extrapolate(fine.slip_velocity, coarse.slip_velocity);
    o.w_i = extrapolate(fine.w_i, coarse.w_i), o.w_j = extrapolate(fine.w_j, coarse.w_j);
    o.v_separation = extrapolate(fine.v_separation, coarse.v_separation);
    o.separated = fine.separated && coarse.separated;
    if (spread) *spread = tangential_error(k, fine, coarse);
    return o;
}

std::string describe(const Impact& k) {
    std::ostringstream out;
    out << k.a.name << (k.wall() ? " on a plane" : " on a sphere") << " at " << k.angle << " deg, spin " << k.w0
        << " rad/s, " << tumble::keyword_of(tumble::shear_models, k.shear) << " shear, "
        << tumble::keyword_of(tumble::tangential_stiffnesses, k.stiffness) << " stiffness, "
        << tumble::keyword_of(tumble::friction_normals, k.friction_normal) << " friction normal";
    return out.str();
}

// The engine at the automatic step within `at_step` of the reference, and
// within `converged` at a tenth of the step.
void expect_reference(const Impact& k, double at_step, double converged) {
    double spread = 0.0;
    const Outcome r = reference(k, &spread);
    ASSERT_TRUE(r.separated) << describe(k);
    // The reference is far more accurate than the tolerances: its finer
    // integration alone is within 5e-4 of v_t of the coarser (measured: at
    // most 4.6e-4), and the extrapolation removes most of that.
    ASSERT_LT(spread, 5e-4) << describe(k);
    const double dt = automatic_step(k);
    for (const auto& [fraction, tolerance] : {std::pair{1.0, at_step}, std::pair{0.1, converged}}) {
        const Outcome e = engine_impact(k, fraction * dt);
        ASSERT_TRUE(e.separated) << describe(k);
        const double error = tangential_error(k, e, r);
        std::printf("  [measured] %s, dt = %g x %.3g s: v_x %.5f (ref %.5f), slip %.5f (ref %.5f), R w %.5f (ref "
                    "%.5f) m/s; error %.2e of v_t (tolerance %.1e)\n",
                    describe(k).c_str(), fraction, dt, e.v_x, r.v_x, e.slip_velocity, r.slip_velocity,
                    e.w_i * k.R_i(), r.w_i * k.R_i(), error, tolerance);
        EXPECT_LT(error, tolerance) << describe(k) << " at " << fraction << " x the automatic step";
    }
}

// ---- 1. Oblique impacts on a plane -----------------------------------------

struct ObliqueCase {
    double angle;
    TangentialStiffness stiffness;
    ShearModel shear;
};

class ObliqueImpact : public ::testing::TestWithParam<ObliqueCase> {};

TEST_P(ObliqueImpact, MatchesTheIndependentIntegrationAtTheAutomaticStep) {
    const auto [angle, stiffness, shear] = GetParam();
    Impact k{alumina(), alumina()};
    k.angle = angle, k.stiffness = stiffness, k.shear = shear;
    // 1 % of v_t at the automatic step (measured: at most 0.75 %, at the
    // small angles where the contact sticks and rings), 0.03 % at a tenth
    // of it (measured: at most 0.007 %: the step's error falls 100-fold,
    // second order). The paper's stiffness against
    // Mindlin's moves the small-angle outcomes by 30 % of v_t (tangential
    // restitution 0.69 against 0.95 at 5 degrees), so either stiffness
    // taken for the other fails.
    expect_reference(k, 1e-2, 3e-4);
}

std::vector<ObliqueCase> oblique_cases() {
    std::vector<ObliqueCase> cases;
    for (TangentialStiffness stiffness : {TangentialStiffness::Paper, TangentialStiffness::Mindlin})
        for (ShearModel shear : {ShearModel::Spring, ShearModel::Coulomb})
            for (double angle : {5.0, 15.0, 25.0, 35.0, 45.0, 65.0, 85.0}) cases.push_back({angle, stiffness, shear});
    return cases;
}

std::string oblique_name(const ::testing::TestParamInfo<ObliqueCase>& info) {
    return std::string(tumble::keyword_of(tumble::tangential_stiffnesses, info.param.stiffness)) + "Stiffness" +
           std::string(tumble::keyword_of(tumble::shear_models, info.param.shear)) + "At" +
           std::to_string(static_cast<int>(info.param.angle)) + "Degrees";
}

INSTANTIATE_TEST_SUITE_P(AluminaOnAPlane, ObliqueImpact, ::testing::ValuesIn(oblique_cases()), oblique_name);

// Mindlin's stiffness gives the published tangential restitution of the
// benchmark at small incidence; the paper's two thirds of it does not.
TEST(ObliqueImpact, MindlinsStiffnessKeepsTheTangentialVelocityAtFiveDegrees) {
    Impact k{alumina(), alumina()};
    k.angle = 5.0;
    k.stiffness = TangentialStiffness::Mindlin;
    const double dt = automatic_step(k);
    const double mindlin = engine_impact(k, dt).v_x / k.v_t();
    k.stiffness = TangentialStiffness::Paper;
    const double paper = engine_impact(k, dt).v_x / k.v_t();
    std::printf("  [measured] tangential restitution at 5 degrees: Mindlin %.4f, paper %.4f\n", mindlin, paper);
    // The no-slip Mindlin contact rebounds with 0.95 of v_t at 5 degrees
    // (the integration above: 0.953); the paper's stiffness with 0.69.
    EXPECT_NEAR(mindlin, 0.953, 0.01);
    EXPECT_NEAR(paper, 0.690, 0.01);
}

// A material whose shear modulus is large against E (G = E, not an
// isotropic solid's E / (2 (1 + nu))) at 50 m/s: with Mindlin's stiffness
// its tangential spring rings 3.5 times as fast as the normal contact, and
// the step is a tenth of the spring's half period, below t_c/20 and the
// Rayleigh criterion (which a large G also shortens).
TEST(TangentialSpring, SetsTheStepWhereItRingsFastestAndHoldsOnePercent) {
    tumble::Material stiff = alumina();
    stiff.G = stiff.E;
    Impact k{stiff, stiff};
    k.angle = 5.0;
    k.v = 50.0;
    k.stiffness = TangentialStiffness::Mindlin;
    const tumble::TimeStepReport r = tumble::assess_time_step(impact_scenario(k, 0.0));
    EXPECT_NE(r.recommended_by.find("tangential spring"), std::string::npos) << r.recommended_by;
    // t_c / t_t = 1.28 sqrt(7/2 k_t / k_n) = 3.5 here; the step t_t/10 is
    // t_c / 35.
    EXPECT_NEAR(r.collision_time / r.dt, 35.0, 1.0);
    // Within 1 % at the automatic step (measured 0.64 %); at t_c/20, where
    // the step would be without the criterion, not (measured 1.8 %; 1.6 %
    // at t_t/8: the stick-slip transitions make the error uneven in dt).
    expect_reference(k, 1e-2, 3e-4);
    const Outcome reference_outcome = reference(k);
    const double at_twentieth = tangential_error(k, engine_impact(k, r.collision_time / 20.0), reference_outcome);
    const double at_step = tangential_error(k, engine_impact(k, r.dt), reference_outcome);
    std::printf("  [measured] error of the tangential rebound: %.2e of v_t at t_c/20, %.2e at the step\n", at_twentieth,
                at_step);
    EXPECT_LT(at_step, 1e-2);
    EXPECT_GT(at_twentieth, 1e-2);
}

// ---- Normal impacts: Hertz, and restitution from 0.2 to 0.99 -------------

TEST(NormalImpact, HertzPeakOverlapForceAndContactTimeOnAPlane) {
    // The benchmark's first tests: an elastic sphere on a plane (here the
    // alumina sphere at 3.9 m/s): h_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5),
    // F_max = 4/3 E* sqrt(R) h_max^(3/2), t_c = 2.943 h_max / v. 1 % at the
    // automatic step (measured: 0.065 %, 0.097 %, 0.062 %), 0.1 % at a tenth
    // (measured: below 1e-5).
    Impact k{alumina(), alumina()};
    k.angle = 0.0;
    const double m = sphere_mass(k.a.rho, k.R_i()), E_star = e_star(k.a, k.b);
    const double h_max = hertz_max_overlap(m, E_star, k.R_i(), k.v);
    const double F_max = 4.0 / 3.0 * E_star * std::sqrt(k.R_i()) * std::pow(h_max, 1.5);
    const double t_c = collision_time(k);
    const double dt = automatic_step(k);
    for (const auto& [fraction, tolerance] : {std::pair{1.0, 1e-2}, std::pair{0.1, 1e-3}}) {
        const Outcome o = engine_impact(k, fraction * dt);
        ASSERT_TRUE(o.separated);
        const double F = 4.0 / 3.0 * E_star * std::sqrt(k.R_i()) * std::pow(o.max_overlap, 1.5);
        const std::string at = " at " + std::to_string(fraction) + " x the automatic step";
        report("peak overlap" + at, o.max_overlap, h_max, tolerance);
        report("peak force" + at, F, F_max, tolerance);
        report("contact time" + at, o.contact_time, t_c, tolerance);
        EXPECT_LT(relative_difference(o.max_overlap, h_max), tolerance);
        EXPECT_LT(relative_difference(F, F_max), tolerance);
        EXPECT_LT(relative_difference(o.contact_time, t_c), tolerance);
        EXPECT_LT(relative_difference(o.v_separation, k.v), tolerance);  // no damping: e = 1
    }
}

class RestitutionRange : public ::testing::TestWithParam<double> {};

TEST_P(RestitutionRange, MatchesTheIndependentIntegration) {
    // Kuwabara-Kono viscosities xi = eta from 2e3 to 4.5e5 Pa s give e from
    // 0.99 to 0.18 for the alumina sphere on its plane at 3.9 m/s (the
    // benchmark's range). 1 % at the automatic step (measured: at most
    // 0.1 %), 0.1 % at a tenth (measured: at most 0.026 %).
    Impact k{alumina(GetParam()), alumina(GetParam())};
    k.angle = 0.0;
    const Outcome r = reference(k);
    ASSERT_TRUE(r.separated);
    const double e_reference = r.v_separation / k.v, dt = automatic_step(k);
    for (const auto& [fraction, tolerance] : {std::pair{1.0, 1e-2}, std::pair{0.1, 1e-3}}) {
        const Outcome o = engine_impact(k, fraction * dt);
        ASSERT_TRUE(o.separated);
        report("restitution at " + std::to_string(fraction) + " x the automatic step", o.v_separation / k.v,
               e_reference, tolerance);
        EXPECT_LT(relative_difference(o.v_separation / k.v, e_reference), tolerance);
    }
}

INSTANTIATE_TEST_SUITE_P(AluminaOnAPlane, RestitutionRange, ::testing::Values(2e3, 1e4, 5e4, 1.5e5, 4.5e5),
                         [](const auto& info) { return "Viscosity" + std::to_string(static_cast<int>(info.param)); });

// ---- 2. Impacts with spin ------------------------------------------------

class SpinningImpact : public ::testing::TestWithParam<double> {};

TEST_P(SpinningImpact, MatchesTheIndependentIntegration) {
    // Normal speed 3.9 m/s; the rim speed R w0 from -3 to 3 times mu v_n
    // (back- and topspin, sliding and sticking).
    Impact k{alumina(), alumina()};
    k.angle = 0.0;
    k.w0 = GetParam() * k.mu * k.v / k.R_i();
    for (TangentialStiffness stiffness : {TangentialStiffness::Paper, TangentialStiffness::Mindlin}) {
        k.stiffness = stiffness;
        expect_reference(k, 1e-2, 3e-4);
    }
}

INSTANTIATE_TEST_SUITE_P(RimSpeedOverMuVn, SpinningImpact, ::testing::Values(-3.0, -0.5, 0.5, 3.0),
                         [](const auto& info) {
                             return std::string(info.param < 0 ? "Minus" : "Plus") +
                                    std::to_string(static_cast<int>(std::abs(info.param) * 10)) + "Tenths";
                         });

// ---- 3. Two unequal nylon spheres -----------------------------------------

TEST(UnequalSpheres, NylonAtASmallIncidenceConvergesAtTheAutomaticStep) {
    // The tangential spring of two free spheres moves the effective mass
    // 2/7 m* at stiffness k_t: it rings 2 to 2.4 times faster than the
    // normal contact (docs/MODEL.md, "Time step"), which the step now
    // resolves.
    Impact k{nylon(5e-3), nylon(2.5e-3)};
    k.R_j = 2.5e-3;
    k.mu = 0.4;
    k.v = 1.0;
    k.angle = std::atan(0.0875) * 180.0 / pi;
    for (TangentialStiffness stiffness : {TangentialStiffness::Paper, TangentialStiffness::Mindlin}) {
        k.stiffness = stiffness;
        expect_reference(k, 1e-2, 3e-4);
    }
}

// ---- 4. Gross sliding: the tangential impulse ------------------------------

// A damped alumina sphere (e about 0.5 at 3.9 m/s) at 70 degrees: v_t / (mu
// v_n) = 30, far above the 7/2 (1 + e) below which the contact would stop
// sliding, so it slides throughout. The tangential impulse per unit mass,
// v_t - v_x', against the rigid-body mu (1 + e) v_n with e the normal
// restitution the engine gave.
double impulse_over_rigid_body(ShearModel shear, FrictionNormal normal) {
    Impact k{alumina(2.2e5), alumina(2.2e5)};
    k.angle = 70.0, k.shear = shear, k.friction_normal = normal;
    const Outcome o = engine_impact(k, automatic_step(k));
    const double e = o.v_separation / k.v_n();
    const double ratio = (k.v_t() - o.v_x) / (k.mu * (1.0 + e) * k.v_n());
    std::printf("  [measured] %s: e = %.4f, tangential impulse / (mu (1 + e) m v_n) = %.4f\n", describe(k).c_str(), e,
                ratio);
    return ratio;
}

TEST(GrossSliding, TheJkrNormalGivesTheRigidBodyImpulse) {
    // The viscous force integrates to zero over a contact that starts and
    // ends at h = 0 (it is 2 B* sqrt(R* h) dh/dt), so mu times the elastic
    // force's impulse is exactly mu (1 + e) m v_n. Measured: 1.0003 (coulomb
    // and spring alike). 0.3 %: the step's share of the impulse at the
    // crossing of the limit.
    for (ShearModel shear : {ShearModel::Coulomb, ShearModel::Spring})
        EXPECT_NEAR(impulse_over_rigid_body(shear, FrictionNormal::Jkr), 1.0, 3e-3);
}

TEST(GrossSliding, TheNetNormalCountsTheTensileTailOfTheDamping) {
    // While the spheres part, the damping pulls (h > 0, h' < 0) and the net
    // force turns tensile; mu |F_n| counts that tail with the wrong sign.
    // Measured at e = 0.50: 4.1 % above the rigid-body impulse.
    for (ShearModel shear : {ShearModel::Coulomb, ShearModel::Spring})
        EXPECT_NEAR(impulse_over_rigid_body(shear, FrictionNormal::Net), 1.041, 5e-3);
}

TEST(GrossSliding, ThePaperReadingHalvesTheImpulse) {
    // The saw-tooth from 0 to the limit: half the Coulomb impulse by design.
    // Measured: 0.50 to 0.52 (the teeth within one impact are few).
    EXPECT_NEAR(impulse_over_rigid_body(ShearModel::Paper, FrictionNormal::Jkr), 0.5, 0.03);
}

// ---- 5. Recoil after slip ----------------------------------------------------

TEST(RecoilAfterSlip, CoulombSpringsBackAsTheSpringReadingDoes) {
    // Incident slip v_t / (mu v_n) = 5: the contact slides, then sticks as
    // the normal force falls and its tangential spring recoils, leaving the
    // contact point moving backwards (-1.73 mu v_n in the integration). A
    // coulomb contact that took v_t's direction whenever its shrinking limit
    // was exceeded flipped its slip to oppose the recoil and left rolling
    // (slip 0.00 mu v_n). In the plane of the impact the two readings are
    // one law.
    Impact k{alumina(), alumina()};
    k.angle = std::atan(5.0 * k.mu) * 180.0 / pi;
    const Outcome r = reference(k);
    const double dt = automatic_step(k);
    for (ShearModel shear : {ShearModel::Spring, ShearModel::Coulomb}) {
        k.shear = shear;
        const Outcome e = engine_impact(k, dt);
        const double slip = e.slip_velocity / (k.mu * k.v_n()), expected = r.slip_velocity / (k.mu * k.v_n());
        report(describe(k) + ": slip after / (mu v_n)", slip, expected, 0.02);
        EXPECT_LT(std::abs(slip - expected), 0.02 * std::abs(expected));
        EXPECT_LT(slip, -1.5);
    }
}

}  // namespace
}  // namespace physics_test
