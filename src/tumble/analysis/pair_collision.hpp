// SPDX-License-Identifier: MIT
// What one kind of contact of a scenario does (`tumble contact`): head-on
// collisions at given impact speeds, at the scenario's time step (the
// engine itself, two spheres) and converged (classical RK4 of the 1-D normal
// law at a tiny step); the equilibrium overlap and pull-off force of the
// adhesive law; the impact speed below which grains stick; and the times
// (Hertz, viscous) that set the time step.
//
// The normal law along the line of centres (docs/MODEL.md, elements 1-3),
// with h the overlap and h' its rate (> 0 while the spheres approach):
//   m* h'' = -F(h, h'),  F = 4/3 E* a h + 2 B* a h' - P a^(3/2),  a = sqrt(R* h).
// Restitution e = separation speed when h returns to 0 over the impact
// speed, with the attraction off (with it, the paper's grains do not rebound
// at all; the sticking speed says so); the contact time is the time between
// the two zeros of h.
#pragma once

#include <vector>

#include "tumble/sim/time_step.hpp"
#include "tumble/sim/scenario.hpp"

namespace tumble::analysis {

// The normal law of one kind of contact; a coefficient is 0 where its term
// is off in the model.
struct NormalLaw {
    double m_star = 0.0;      // kg
    double R_star = 0.0;      // m
    double E_star = 0.0;      // Pa (element 1)
    double B_star = 0.0;      // Pa s (element 2)
    double attraction = 0.0;  // N m^-3/2, the prefactor P (element 3)
};
NormalLaw normal_law(const ContactPair& pair, const ContactModel& model);

// F(h, h') of the law above, N (> 0: pushes the spheres apart).
double normal_force(const NormalLaw& law, double overlap, double overlap_rate);

struct Collision {
    bool separated = false;    // false: still in contact at the end (stuck, or not separated in time)
    double restitution = 0.0;  // separation speed / impact speed (0 if not separated)
    double contact_time = 0.0; // s, between the zeros of h (0 if not separated)
};

// The undamped Hertz collision time of the law at impact speed v, s
// (tumble::hertz_collision_time).
double hertz_collision_time(const NormalLaw& law, double v);

// Converged: the law integrated by RK4 at hertz_collision_time(v) / 10^4
// (halving it moves e by < 1e-4), from h = 0 at speed v, for at most 40
// Hertz times. With the attraction on it stops early once the energy
// (kinetic + elastic + attraction) is below 0, its value at h = 0: the
// spheres can then never part.
Collision converged_collision(const NormalLaw& law, double v);

// The engine at step dt: the pair's two spheres (or the sphere and a flat
// wall) of `base`'s materials, meeting head-on at relative speed v, with
// `model` (Simulation of a two-particle scenario). tumble::Error if the
// elastic term is off (nothing would end the contact).
Collision engine_collision(const Scenario& base, const ContactPair& pair, const ContactModel& model, double v,
                           double dt);

// Overlap at which elasticity balances attraction, F(h, 0) = 0, m, found by
// bisection on the law (closed form: (3 P / (4 E*))^(4/3) R*^(1/3)); 0
// without attraction.
double equilibrium_overlap(const NormalLaw& law);

// The largest pull the contact resists at rest, -min over h of F(h, 0), N,
// found by golden-section search on the law (closed form: 2 pi W R*); 0
// without attraction.
double pull_off_force(const NormalLaw& law);

// The speed below which the spheres stick: from 1 mm/s, doubling up to
// max_sticking_speed until a converged collision rebounds, then bisection to
// 1e-6 relative. Returns max_sticking_speed if none rebounds up to it.
inline constexpr double max_sticking_speed = 10.0;  // m/s; the Hertz overlap exceeds R* not far above
// The fastest impact contact_report takes, m/s: far beyond any granular
// flow (a bullet's speed), where even stiff grains pass into each other; a
// larger speed is a slip of the input (1e308 would overflow the collision).
inline constexpr double max_impact_speed = 1000.0;
double sticking_speed(const NormalLaw& law);

struct Impact {
    double speed = 0.0;    // m/s
    Collision at_step;     // engine_collision at the scenario's step
    Collision converged;   // converged_collision
};

struct PairContactReport {
    ContactPair pair;
    NormalLaw law;              // the scenario's model (attraction as it has it)
    PairTimes times;            // at the scenario's reference speed
    std::vector<Impact> impacts;  // attraction off
    double equilibrium_overlap = 0.0;  // m
    double pull_off_force = 0.0;       // N
    double sticking_speed = 0.0;       // m/s; max_sticking_speed: sticks at every speed up to it
};

struct ContactReport {
    TimeStepReport time_step;     // the scenario's
    double reference_speed = 0.0;  // m/s, of the Hertz collision times (the scenario's [time_step])
    TangentialStiffness tangential_stiffness = TangentialStiffness::Paper;  // the scenario's model's
    std::vector<PairContactReport> pairs;
};

// Every kind of contact of the scenario (contact_pairs()) at the given impact
// speeds (m/s, each > 0 and at most max_impact_speed; tumble::Error otherwise).
ContactReport contact_report(const Scenario& scenario, const std::vector<double>& speeds);

}  // namespace tumble::analysis
