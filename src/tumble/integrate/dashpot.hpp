// SPDX-License-Identifier: MIT
// The Kuwabara-Kono dashpot (element 2, paper eq. 4,
// contact/kuwabara_kono.hpp) over one time step.
//
// The paper's damping is strongly over-damped: for the drum's grains the
// viscous time m*/c (c = 2 B* sqrt(R* h), m* the pair's reduced mass) is
// 0.04 to 0.15 ms while a collision lasts 4 to 8 ms. Seen with the
// velocity predicted for t + dt (v(t + dt/2) + dt/2 a(t), velocity_verlet.hpp)
// it is stable for a single contact only while lambda = c dt / m* < 1, and
// the contact time errs by about 1 % per m*/c of step (docs/MODEL.md, "Time
// step"). Here each contact treats its own dashpot as if the rest of the
// motion were frozen over the step:
//
//   v_d = (v_n - dt/2 F_old / m*) psi(lambda),   lambda = c dt / m*,
//   psi(lambda) = (1 + lambda/6) / (1 + 2 lambda/3 + lambda^2/6),
//   F = -c v_d  (eq. 4 with v_d for v_n),
//
// v_n the predicted normal velocity (m/s, along n from j to i, negative
// while approaching), F_old the contact's viscous force of the step before
// (N, on i along +n; ContactHistory::viscous_force): the prediction holds
// dt/2 F_old/m* of it, which is taken out (the contact's own damping is
// not extrapolated), and psi stands for the relaxation of the normal
// velocity by the dashpot alone over the step, (1 - exp(-lambda)) / lambda:
// it agrees with it to second order in lambda, is positive, and lambda psi
// tends to 1 as lambda grows, as 1 - exp(-lambda) does (a stiff dashpot
// stays stiff; no single contact is unstable at any step). Rational, so it
// is computed alike, and vectorised alike, on every instruction set.
// lambda -> 0 gives back the explicit prediction.
// 1/m* = 1/m_i + 1/m_j, the sum of the inverse masses (0 for a kinematic
// particle or a wall). For the drum's pairs this keeps restitution and
// contact time within 1 % of the converged collision up to about 1.3 m*/c
// of step (docs/MODEL.md, "Time step"; `tumble contact`).
#pragma once

#include "tumble/contact/geometry.hpp"
#include "tumble/contact/history.hpp"
#include "tumble/contact/kuwabara_kono.hpp"
#include "tumble/materials/pair_table.hpp"

namespace tumble {

// v_d above, m/s: v_n_predicted (m/s), c (N s/m), inverse_mass_sum = 1/m*
// (1/kg), dt (s), previous_force = F_old (N).
inline double dashpot_normal_velocity(double v_n_predicted, double c, double inverse_mass_sum, double dt,
                                      double previous_force) {
    const double lambda = c * inverse_mass_sum * dt;
    const double psi = (6.0 + lambda) / (6.0 + lambda * (4.0 + lambda));  // psi above, one division
    return (v_n_predicted - 0.5 * dt * inverse_mass_sum * previous_force) * psi;
}

// The contact's geometry as the law is to see it: its predicted v_n
// replaced by v_d (the pair loop and the flat walls call it before
// contact_law(), which records the new force in history.viscous_force).
inline void treat_dashpot(ContactGeometry& g, const PairCoefficients& c, double inverse_mass_sum, double dt,
                          const ContactHistory& history) {
    g.v_n = dashpot_normal_velocity(g.v_n, kuwabara_kono_coefficient(c.B_star, g.contact_radius), inverse_mass_sum,
                                    dt, history.viscous_force);
}

}  // namespace tumble
