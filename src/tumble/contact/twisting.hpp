// SPDX-License-Identifier: MIT
// Element 5: the twisting couple about the normal (Mindlin, no partial slip;
// paper eq. 9), with the same readings of the static limit as the shear
// force (mindlin_shear.hpp).
#pragma once

#include <cmath>

#include "tumble/contact/mindlin_shear.hpp"
#include "tumble/core/constants.hpp"

namespace tumble {

// Couple on i about +n, N m (the couple on j is its negative):
//   -k_w da,   |.| <= 3 pi/16 sqrt(R* h) mu |F_n|,   k_w = 8/3 G* (R* h)^(3/2) in the paper,
// where da (rad, `angular_slip`) is the rotation of i relative to j about n
// integrated since the contact began (w_n dt each step, w_n = (omega_i -
// omega_j) . n at the half step). At the limit it restarts from its excess
// (Paper; its saw-tooth seen over the step's window, sawtooth_in_window()) or
// is held there (Coulomb, Spring), with the sign of w_n while the rim of the
// contact slides faster than v_reg (Paper; Coulomb in the sense of the slip
// only, so that a twist recoiling as its limit shrinks springs back:
// mindlin_shear_force()), else its own.
// With da of one sign this is the paper's min(...) (-sign w_n).
// (`limits`: slip_limits() of the contact; a: its radius.)
inline double twisting_couple(ShearModel model, const SlipLimits& limits, double contact_radius, double w_n,
                              double dt, double v_reg, double& angular_slip) {
    angular_slip += w_n * dt;
    const double a = contact_radius;
    const double stiffness = limits.twist_stiffness;  // N m/rad
    const double held = limits.twist_held, per_held = limits.per_twist_held;  // rad
    const double length = std::abs(angular_slip);
    const double spin = model == ShearModel::Coulomb ? (angular_slip < 0.0 ? -w_n : w_n) : std::abs(w_n);
    const bool along_spin = model != ShearModel::Spring && spin * a > v_reg;
    const bool slides = length > held;
    // The sign of the slip after this step: w_n's where it slid along the
    // spin, else the slip's own. (Choices, not branches, as in
    // mindlin_shear.hpp.)
    const double sign = (slides ? (along_spin ? w_n : angular_slip) : angular_slip) < 0.0 ? -1.0 : 1.0;
    const double after = slip_length_after_slipping(model, length, held, per_held);
    angular_slip = slides ? sign * after : angular_slip;
    // The couple's length along `sign`: the paper's reading feels its
    // saw-tooth over the step's window (where the slip is not 0 after
    // restarting; the window's own length away from a tooth's edge, as for
    // the shear), the others the slip's length (after or length).
    const double window = sawtooth_in_window(length, std::abs(w_n) * dt, held, per_held);
    const double slip_length = slides ? after : length;
    const double felt = model == ShearModel::Paper ? (after > 0.0 ? window : slip_length) : slip_length;
    return -stiffness * sign * felt;
}

}  // namespace tumble
