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
//    damping at the deepest overlap; with the velocity predicted for
//    t + dt (integrate/velocity_verlet.hpp) the damping is stable only for
//    dt < m*/c;
// and for every material of free particles the Rayleigh time
//      t_R = pi R sqrt(rho/G) / (0.1631 nu + 0.8766).
// Recommended step: min(t_c/50, 0.2 m*/c, 0.2 t_R).
// Largest step accepted: min(t_c/10, 0.5 m*/c, 0.5 t_R).
#pragma once

#include <string>

namespace tumble {

struct Scenario;

struct TimeStepReport {
    double collision_time = 0.0;  // s, shortest over pairs (0 if elasticity is off)
    double viscous_time = 0.0;    // s, shortest m*/c over pairs (0 if viscosity is off)
    double rayleigh_time = 0.0;   // s, shortest over materials
    double recommended = 0.0;     // s
    double maximum = 0.0;         // s
    std::string limiting;         // which criterion and which pair or material sets `maximum`
    double dt = 0.0;              // s, the step in use
    bool automatic = false;       // dt was chosen, not given
};

// Throws tumble::Error if a given dt exceeds the maximum (unless the
// scenario allows unsafe steps) or is not positive.
TimeStepReport assess_time_step(const Scenario& scenario);

}  // namespace tumble
