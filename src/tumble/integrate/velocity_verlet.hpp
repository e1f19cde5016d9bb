// SPDX-License-Identifier: MIT
// Velocity Verlet (kick-drift-kick) for the translation and rotation of
// spheres. Second order in dt for position-dependent forces. The forces are
// evaluated with the half-step velocities v(t + dt/2), so velocity-dependent
// terms (internal friction, shear, twisting) are first order in dt; with
// those terms off the scheme is symplectic. Spheres need no orientation.
// Each particle is updated on its own, so `chunks` threads give the same
// numbers as one.
#pragma once

#include "tumble/particles/particle_store.hpp"

namespace tumble {

// v += half_dt (F/m + g), omega += half_dt T/I, for free particles.
void kick(ParticleStore& p, const Vec3& gravity, double half_dt, int chunks = 1);

// kick(), then x += dt v for free particles (the drift), in one pass.
void kick_drift(ParticleStore& p, const Vec3& gravity, double half_dt, double dt, int chunks = 1);

}  // namespace tumble
