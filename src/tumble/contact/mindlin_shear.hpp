// SPDX-License-Identifier: MIT
// Element 4: the shear force, Mindlin without partial slip, limited by
// static friction (paper eq. 8), in three readings of what happens when the
// limit is reached (docs/MODEL.md, "Shear models").
#pragma once

#include <algorithm>
#include <cmath>

#include "tumble/core/constants.hpp"
#include "tumble/core/vec3.hpp"

namespace tumble {

// What a contact does at the static limit mu |F_n|:
//   Paper:   the contact slips and the slip restarts, from its excess over
//            the limit (the step's overshoot is carried, so the force
//            saw-tooths from 0 to the limit whatever dt: mean mu |F_n| / 2
//            in sustained sliding);
//   Coulomb: the slip is held at the limit while the contact slides, along
//            the sliding velocity (the paper's direction): mean mu |F_n|;
//   Spring:  the slip is held at the limit along its own direction (the
//            tangential spring of LAMMPS and LIGGGHTS): mean mu |F_n|;
//   Off:     no shear force.
// Below the limit all three are the same elastic contact: the force
// opposes the slip vector, so a contact holds a load below the limit
// without creeping.
enum class ShearModel { Off, Paper, Coulomb, Spring };

// The pair loop runs these on every contact: each division counts (on Intel
// processors the divider, which also takes the square roots, bounds the
// vectorised law: docs/BENCHMARKS.md), so the length at the limit comes with
// its reciprocal, per_held = 1 / held (0 for held = 0, no friction).

// The static limits of the shear force (paper eq. 8) and of the twisting
// couple (eq. 9, element 5, twisting.hpp) as slips, for a contact of radius
// a = sqrt(R* h) whose friction limit is mu |F_n| = f (N):
//   shear: stiffness k_t = S a (N/m), held = f / k_t (m);
//   twist: stiffness k_w = T a^3 (N m/rad), held = 3 pi/16 a f / k_w (rad),
// with S and T (Pa) the pair's shear_stiffness and twist_stiffness
// (materials/pair_table.hpp: 16/3 G* and 8/3 G* in the paper). The four
// lengths and reciprocals come from the one reciprocal r = 1 / (S T a^3 f):
//   held = T a^2 f^2 r,          per_held = S^2 T a^4 r,
//   twist_held = 3 pi/16 S a f^2 r,  per_twist_held = 16/(3 pi) S T^2 a^5 r.
// No friction (f = 0): held = per_held = 0.
struct SlipLimits {
    double stiffness = 0.0, held = 0.0, per_held = 0.0;
    double twist_stiffness = 0.0, twist_held = 0.0, per_twist_held = 0.0;
};
inline SlipLimits slip_limits(double shear_stiffness, double twist_stiffness, double contact_radius,
                              double friction_limit) {
    const double S = shear_stiffness, T = twist_stiffness, a = contact_radius, f = friction_limit;
    const double a2 = a * a, Sa = S * a, Ta2 = T * a2;
    const double denominator = Sa * Ta2 * f;
    const double r = denominator > 0.0 ? 1.0 / denominator : 0.0;  // 1 / (S T a^3 f)
    SlipLimits s;
    s.stiffness = Sa;
    s.held = Ta2 * (f * f * r);
    s.per_held = Sa * (Sa * Ta2 * r);
    s.twist_stiffness = Ta2 * a;
    s.twist_held = 3.0 * pi / 16.0 * Sa * (f * f * r);
    s.per_twist_held = 16.0 / (3.0 * pi) * Ta2 * (Sa * Ta2 * r);
    return s;
}

// Length of the slip after the contact has slipped: `length` (> `held`, the
// length at the limit) wrapped back by whole teeth for Paper, `held`
// otherwise. held = 0 (no normal force) leaves no slip.
inline double slip_length_after_slipping(ShearModel model, double length, double held, double per_held) {
    const double excess = held > 0.0 ? length - std::floor(length * per_held) * held : 0.0;
    return model == ShearModel::Paper ? excess : held;
}

// The step's window [lo, hi] = [x - step/2, x + step/2], not below 0.
struct SlipWindow {
    double lo = 0.0, hi = 0.0, width = 0.0;
};
inline SlipWindow slip_window(double x, double step) {
    const double lo = std::max(x - 0.5 * step, 0.0), hi = x + 0.5 * step;
    return {lo, hi, hi - lo};
}

// The paper's saw-tooth as the force law sees it: the slip length x (the
// force is k (x mod held)) averaged over the step's window [x - step/2,
// x + step/2], step = the slip of one step. Where the window holds no
// tooth's edge that is x mod held itself, the value at the step; where it
// holds one, the window's mean. The windows of consecutive steps tile the
// slip, so the sum of the steps' forces is the saw-tooth's integral exactly
// and sustained sliding feels its mean, held / 2, whatever the step, even
// with a tooth shorter than a step (sampling it at the steps alone aliases:
// 8 % off at the automatic step at 0.1 m/s). Meaningless for held = 0
// (no friction), where the callers use no saw-tooth.
// per_width: 1 / the window's width, from the caller (the shear has it
// from the one division it makes anyway, mindlin_shear_force(): each
// division counts, see above); any value for width 0, which happens only
// at x = step = 0, where mean = 0 = at_step.
inline double sawtooth_in_window(double x, const SlipWindow& w, double per_width, double held, double per_held) {
    // Every value is computed and the result chosen, without branches, so
    // that the pair loop still runs several contacts per instruction.
    // The integral of (y mod held) from 0 to y.
    auto integral = [held, per_held](double y) {
        const double teeth = std::floor(y * per_held), rest = y - teeth * held;
        return 0.5 * (teeth * held * held + rest * rest);
    };
    const double mean = (integral(w.hi) - integral(w.lo)) * per_width;
    const double at_step = x - std::floor(x * per_held) * held;
    return w.hi > held ? mean : at_step;
}
// The same, dividing by the width itself (twisting.hpp).
inline double sawtooth_in_window(double x, double step, double held, double per_held) {
    const SlipWindow w = slip_window(x, step);
    return sawtooth_in_window(x, w, 1.0 / (w.width > 0.0 ? w.width : 1.0), held, per_held);
}

// Tangential force on i, N:
//   -k_t ds,   |.| <= mu |F_n| = friction_limit,   k_t = 16/3 G* sqrt(R* h) in the paper,
// where ds (m, `slip`) is the displacement of i relative to j at the contact
// point integrated since the contact began (v_t dt each step, v_t the
// half-step velocity: a position, integrated like one), kept in the current
// contact plane with its length as the pair rolls and n turns. With the
// slip in one direction this is the paper's min(16/3 G* ds sqrt(R* h),
// mu |F_n|) (-v_t/|v_t|); taking the direction from the slip rather than
// from v_t lets a contact at rest hold its load (SPEC-NOTES, shear
// direction). n points from j to i.
// (`limits`: slip_limits() of the contact.)
inline Vec3 mindlin_shear_force(ShearModel model, const SlipLimits& limits, const Vec3& n, const Vec3& v_t, double dt,
                                double v_reg, Vec3& slip) {
    // Into the contact plane, keeping the length (one square root).
    Vec3 in_plane = slip - dot(slip, n) * n;
    const double old2 = norm2(slip), plane2 = norm2(in_plane);
    in_plane *= plane2 > 0.0 ? std::sqrt(old2 / plane2) : 0.0;
    slip = in_plane + dt * v_t;

    const double stiffness = limits.stiffness;  // N/m
    const double held = limits.held, per_held = limits.per_held;  // slip at the limit, m
    // After slipping the slip is `after` long, along the sliding velocity for
    // the paper's readings while the contact slides faster than v_reg (the
    // paper's direction -v_t/|v_t| then), else along itself. Coulomb counts
    // only the velocity along the slip: a contact whose limit shrinks under
    // it (the normal force falls) while it moves back against its slip is
    // recoiling, not sliding, and keeps its slip's direction, so that it
    // springs back as it sticks again (taking v_t's direction there would
    // flip the slip to oppose the recoil, and the contact would end rolling).
    // The paper's reading keeps the speed: its slip restarts from the
    // excess over the limit, whose direction is the motion's. Written as
    // choices between values rather than branches, so that the pair loop
    // still runs several contacts per instruction.
    const double length = norm(slip), speed = norm(v_t);
    // The step's window of the saw-tooth (the paper's reading).
    const SlipWindow w = slip_window(length, speed * dt);
    // 1/length, 1/speed (0 for 0) and 1 / the window's width from one
    // division (the product stays far above the smallest double for any
    // slip, speed and step a contact has).
    const double length_or_1 = length > 0.0 ? length : 1.0, speed_or_1 = speed > 0.0 ? speed : 1.0;
    const double width_or_1 = w.width > 0.0 ? w.width : 1.0;
    const double per_all = 1.0 / (length_or_1 * speed_or_1 * width_or_1);
    const double per_both = width_or_1 * per_all;  // 1 / (length_or_1 speed_or_1)
    const double per_length = length > 0.0 ? speed_or_1 * per_both : 0.0;
    const double per_speed = speed > 0.0 ? length_or_1 * per_both : 0.0;
    const double per_width = length_or_1 * speed_or_1 * per_all;
    const bool slides = length > held;
    const double sliding_speed = model == ShearModel::Coulomb ? dot(slip, v_t) * per_length : speed;
    const bool along_velocity = model != ShearModel::Spring && sliding_speed > v_reg;
    const double after = slip_length_after_slipping(model, length, held, per_held);
    // The force's length along the same direction: the paper's reading feels
    // its saw-tooth over the step's window (which is the slip's own length
    // away from a tooth's edge), the others the slip.
    const double window = held > 0.0 ? sawtooth_in_window(length, w, per_width, held, per_held) : 0.0;
    const double felt = model == ShearModel::Paper ? window : (slides ? after : length);
    // slip <- keep slip + turn v_t, and the force -stiffness (keep_felt slip +
    // turn_felt v_t); one comparison per choice (GCC 12 does not vectorise a
    // choice on the `&&` of two).
    const double keep = slides ? (along_velocity ? 0.0 : after * per_length) : 1.0;
    const double turn = slides ? (along_velocity ? after * per_speed : 0.0) : 0.0;
    const double keep_felt = along_velocity ? (slides ? 0.0 : felt * per_length) : felt * per_length;
    const double turn_felt = slides ? (along_velocity ? felt * per_speed : 0.0) : 0.0;
    const Vec3 force = -stiffness * (keep_felt * slip + turn_felt * v_t);
    slip = keep * slip + turn * v_t;
    return force;
}

}  // namespace tumble
