// SPDX-License-Identifier: MIT
// Blow-up detection: a run whose time step is too large, or whose input is
// unphysical, goes wrong in a few recognisable ways. health_problem() looks
// for them and describes the first it finds, so that the run can stop with
// a diagnostic instead of writing nonsense for hours.
#pragma once

#include <array>
#include <string>

#include "tumble/sim/simulation.hpp"

namespace tumble {

struct HealthLimits {
    // Largest overlap h / min(R_i, R_j) of two touching spheres. A resolved
    // collision at the design impact speed overlaps a few per cent.
    double max_overlap_ratio = 0.5;
    // Fastest free particle, m/s: beyond it the kinetic energy has exploded.
    double max_speed = 0.0;
    // Free particle centres must stay within [lo, hi] on the bounded axes.
    std::array<bool, 3> bounded{false, false, false};
    Vec3 lo, hi;
    const char* region = "the domain";  // for messages: "the domain", "the drum"
};

// The limits for a scenario: max_speed 100 x the time step's reference impact
// speed (10^4 times its kinetic energy); bounded on the walled axes, to the
// walls plus the largest radius (a centre beyond has passed through a wall).
HealthLimits default_health_limits(const Scenario& s);

// A prescribed motion carries the spheres and walls that follow it at up to
// |velocity| + |angular_velocity| x reach (m/s), reach the farthest of their
// surfaces from its axis (m; negative where nothing follows it). Faster than
// the scenario's max_speed (above), a free sphere it struck would be flung
// faster than the blow-up check lets a run go on: the reason, else empty.
// The scenario's reader and Simulation::set_motion() ask it alike.
std::string motion_speed_problem(const Scenario& s, const RigidMotion& m, double reach);

// The farthest point from motion m's axis of the scenario's walls that
// follow motion k, placed where `now` carries them (null: where the
// scenario places them at the start), m; -1 where no wall follows it.
double walls_reach(const Scenario& s, std::size_t k, const RigidMotion& m, const MotionNow* now);

// Empty if the run looks physical, else what is wrong: the step and time,
// which particle (global id) or contact, where, and the limit it broke.
// Checks non-finite positions, velocities and spins; speeds; the region;
// and the overlap of every pair of the neighbour list with a free sphere.
std::string health_problem(const Simulation& sim, const HealthLimits& limits);
// The same without the contacts: the particles' positions, velocities and
// spins, speeds and region, which costs a small part of a step (the
// contacts' overlaps cost about a force evaluation).
std::string particle_health_problem(const Simulation& sim, const HealthLimits& limits);

}  // namespace tumble
