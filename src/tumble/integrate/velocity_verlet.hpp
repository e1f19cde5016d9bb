// SPDX-License-Identifier: MIT
// Velocity Verlet (kick-drift-kick) for the translation and rotation of
// spheres. Second order in dt for position-dependent forces. The forces are
// evaluated while the velocities are at the half step v(t + dt/2); the
// slips of the shear and twisting terms integrate those (midpoint rule), and
// the internal friction, which needs v(t + dt), sees it predicted as
// v(t + dt/2) + dt/2 a(t) (ParticleStore::half_kick): second order too.
// Explicit, that damping would be stable only for dt < m*/c; each contact
// therefore solves its own dashpot over the step (dashpot.hpp). With the
// velocity-dependent terms off the scheme is symplectic. Spheres need no
// orientation.
// Each particle is updated on its own: the functions take a range of the
// particles, and the threads that share the particles give the same numbers
// as one.
#pragma once

#include <cstddef>
#include <vector>

#include "tumble/core/parallel.hpp"
#include "tumble/particles/particle_store.hpp"
#include "tumble/particles/rigid_motion.hpp"

namespace tumble {

// Where the particles were when the neighbour list was last built, and the
// square of how far from there one may go before the list must be built
// anew (neighbor/verlet_list.hpp, needs_rebuild()). The loops that move the
// particles count those gone farther as they move them: a pass of its own
// over every particle after them cost 2 % of a step on the long drum
// (studies/performance/LOG.md, "The list's check in the integrator's pass").
// Without positions (at_build null) nothing is counted.
struct DisplacementLimit {
    const Vec3* at_build = nullptr;  // per array index, m
    double limit2 = 0.0;             // m^2
};

// v += half_dt (F/m + g), omega += half_dt T/I, for the free particles of
// range r; half_kick = 0.
void kick(ParticleStore& p, const Vec3& gravity, double half_dt, IndexRange r);

// kick() with half_kick = the velocity change of the kick, then x += dt v
// for free particles (the drift), over range r. The forces and torques are
// then spent and set to zero, ready for the sums of the next evaluation.
// Returns how many free particles of r have gone beyond `limit`.
std::size_t kick_drift(ParticleStore& p, const Vec3& gravity, double half_dt, double dt, IndexRange r,
                       const DisplacementLimit& limit);

// kick(), then kick_drift() with the same forces, in one pass over range r:
// the end of a step and the beginning of the next (the same numbers as the
// two calls, read and written once).
std::size_t kick_kick_drift(ParticleStore& p, const Vec3& gravity, double half_dt, double dt, IndexRange r,
                            const DisplacementLimit& limit);

// The kinematic particles of range r where their motions (now[k] for motion
// k) put them: x, v and omega prescribed; F = T = 0, ready for the sums of
// the grains' forces on them. Returns how many of them have gone beyond
// `limit`.
std::size_t move_kinematic(ParticleStore& p, const std::vector<MotionNow>& now, IndexRange r,
                           const DisplacementLimit& limit = {});

}  // namespace tumble
