// SPDX-License-Identifier: MIT
// Choosing and checking the time step from the materials.
//
// For every pair of materials that can touch (each at the smallest radius of
// its free, or of its kinematic, particles; the reduced mass for two free
// grains, the grain's own mass against a kinematic particle or a flat wall,
// whose motion is prescribed; two kinematic particles never touch):
//  - Hertz collision time at the reference impact speed v (no damping):
//      h_max = (15 m* v^2 / (16 E* sqrt(R*)))^(2/5),  t_c = 2.943275 h_max / v;
//  - viscous time m*/c with c = 2 B* sqrt(R* h_max), the Kuwabara-Kono
//    damping at the deepest overlap (the dashpot's time treatment,
//    integrate/dashpot.hpp, keeps a single contact stable at any step; its
//    errors grow with dt / (m*/c); a bed in lasting contact, as in a slow
//    drum, needs 0.7 m*/c for its diffusion to converge);
//  - creep time tau = B*/E* of an over-damped contact (c^2 > 4 m* k with
//    k = 2 E* sqrt(R* h_max) the Hertz stiffness there, i.e. tau > 4 m*/c):
//    after the impact the spheres creep apart as exp(-t/tau) (eq. 4's
//    dashpot against eq. 1's stiffness), and the restitution, set as they
//    part, errs by about (20 dt/tau)^2 %;
//  - the viscous time m*/c of a contact that is damped but not over-damped
//    (it rings once, heavily damped, near critical damping): its
//    restitution errs by about 1.4 % at 0.37 m*/c, so the step keeps below
//    a quarter of it;
//  - the half period of the tangential spring at the deepest overlap,
//      t_t = pi sqrt(2/7 m* / (S sqrt(R* h_max))),
//    with 2/7 m* the mass the contact point moves with (solid spheres
//    rolling on each other: 1/m_t = (1 + R^2 m / I) / m* = 7 / (2 m*)) and
//    S sqrt(R* h) the spring's stiffness (pair_table.hpp); it rings faster
//    than the normal contact, t_c / t_t = 1.28 sqrt(7/2 k_t / k_n) (1.6 for
//    the paper's materials, up to 2.4 for isotropic grains with Mindlin's
//    stiffness); an oblique impact's rebound errs by up to 0.75 % of v_t
//    at t_t/13, and where the spring rings 3.5 times as fast as the normal
//    contact by 1.8 % at t_c/20 and 0.64 % at t_t/10;
// and for every material of free particles the Rayleigh time
//      t_R = pi R sqrt(rho/G) / (0.1631 nu + 0.8766).
// Recommended step: min(t_c/20, 0.7 m*/c, tau/25, 0.25 m*/c ringing, t_t/10, 0.2 t_R).
// Largest step accepted: min(t_c/10, 2 m*/c, t_t/5, 0.5 t_R).
// (The fractions and why: docs/MODEL.md, "Time step".)
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "tumble/materials/pair_table.hpp"

namespace tumble {

struct Scenario;

// What a grain of material a can touch: another free grain, a kinematic
// particle (whose motion is prescribed: infinite mass) or a flat wall
// (infinite radius and mass).
enum class Partner { free, kinematic, flat_wall };

// One kind of contact of a scenario, at the smallest radii that meet in it.
struct ContactPair {
    std::string name;     // "material-1-material-2", "... (kinematic)", "material-1-flat wall"
    std::size_t a = 0;    // material of the free grain
    std::size_t b = 0;    // material of the partner (the wall material for a flat wall)
    Partner partner = Partner::free;
    double R_a = 0.0;     // m, smallest radius of free grains of material a
    double R_b = 0.0;     // m, smallest radius of the partner (infinite for a flat wall)
    double R_star = 0.0;  // m, reduced radius
    double m_star = 0.0;  // kg, reduced mass (the grain's own mass against a kinematic particle or a wall)
    PairCoefficients coefficients;
};

// Every kind of contact that can occur in the scenario, in a fixed order
// (by material a; for each, free partners b >= a, then kinematic ones, then
// the flat wall). Two kinematic particles never touch.
std::vector<ContactPair> contact_pairs(const Scenario& scenario);

// The undamped Hertz collision of reduced mass m* (kg), modulus E* (Pa) and
// radius R* (m) at impact speed v (m/s): deepest overlap h_max (m) and
// duration t_c (s), the formulas at the top of this file.
double hertz_max_overlap(double m_star, double E_star, double R_star, double v);
double hertz_collision_time(double m_star, double E_star, double R_star, double v);

// The times of one kind of contact at impact speed v, s (infinite where
// the term is off, or for the creep time where the contact is not
// over-damped, for the ringing viscous time where it is: no limit): the
// undamped Hertz collision time t_c, the viscous time m*/c at its deepest
// overlap, the creep time B*/E*, and the tangential spring's half period
// t_t there (formulas at the top of this file).
struct PairTimes {
    double collision = std::numeric_limits<double>::infinity();
    double viscous = std::numeric_limits<double>::infinity();
    double creep = std::numeric_limits<double>::infinity();
    double ringing_viscous = std::numeric_limits<double>::infinity();  // m*/c where damped but not over-damped
    double tangential = std::numeric_limits<double>::infinity();      // t_t (infinite without shear or friction)
};
struct ContactModel;
PairTimes pair_times(const ContactPair& pair, const ContactModel& model, double v);

struct TimeStepReport {
    double collision_time = 0.0;  // s, shortest over pairs (0 if elasticity is off)
    double viscous_time = 0.0;    // s, shortest m*/c over pairs (0 if viscosity is off)
    double creep_time = 0.0;      // s, shortest B*/E* over over-damped pairs (0 if none)
    double ringing_viscous_time = 0.0;  // s, shortest m*/c over damped pairs that are not over-damped (0 if none)
    double tangential_time = 0.0;  // s, shortest half period t_t of the tangential spring (0 if no shear)
    double rayleigh_time = 0.0;   // s, shortest over materials
    double recommended = 0.0;     // s
    double maximum = 0.0;         // s
    std::string limiting;         // which criterion and which pair or material sets `maximum`
    std::string recommended_by;   // which criterion and which pair or material sets `recommended`
    double dt = 0.0;              // s, the step in use
    bool automatic = false;       // dt was chosen, not given
};

// Throws tumble::Error if a given dt exceeds the maximum (unless the
// scenario allows unsafe steps) or is not positive.
TimeStepReport assess_time_step(const Scenario& scenario);

}  // namespace tumble
