// SPDX-License-Identifier: MIT
// The drum as tumble drum builds it, and how its bed settles before it
// turns (tumble drum, tumble bench --case long-drum, tumble contact --drum).
#pragma once

#include <cmath>

#include "io/drum_config.hpp"
#include "tumble/core/mpi.hpp"
#include "tumble/particles/particle_store.hpp"
#include "tumble/sim/simulation.hpp"
#include "tumble/setup/drum.hpp"

namespace tumble::experiments {

// The drum's neighbour skin where the settings leave it automatic (0), as a
// fraction of the largest sphere's radius: 0.3, not the engine's 0.2 of any
// scenario (Simulation). A flowing bed rebuilds its list often (every 25
// steps of the long drum at 0.2 R); at 0.3 R it rebuilds less often for
// more candidate pairs, and runs 4 % faster on 1 and 2 threads; 0.35 R is
// no faster (studies/performance/LOG.md, "The drum's own skin").
inline constexpr double drum_skin_per_radius = 0.3;

// The drum of the settings: build_drum_scenario() with the settings' walls,
// fill and materials, step (0: automatic), neighbour skin (0:
// drum_skin_per_radius x the largest radius), shear model, friction normal
// and surface energy (if given, every pair's W).
inline DrumSetup build_drum(const io::DrumSettings& s, bool allow_unsafe_dt = false) {
    DrumSetup setup = build_drum_scenario(s.geometry, s.mode, s.grain_count(), s.seed, s.fill, s.materials);
    if (s.surface_energy)
        for (auto& row : setup.scenario.pair_properties)
            for (PairProperties& pair : row) pair.W = *s.surface_energy;
    if (s.dt > 0.0) setup.scenario.time_step.dt = s.dt;
    setup.scenario.neighbor.skin = s.skin > 0.0 ? s.skin : drum_skin_per_radius * setup.scenario.largest_radius();
    setup.scenario.model.shear = s.shear;
    setup.scenario.model.friction_normal = s.friction_normal;
    setup.scenario.model.tangential_stiffness = s.tangential_stiffness;
    setup.scenario.time_step.allow_unsafe = allow_unsafe_dt;
    return setup;
}

// Root mean square speed of the free particles (the grains), m/s; shared
// among ranks, of every rank's own grains (collective).
inline double rms_grain_speed(const Simulation& sim) {
    const ParticleStore& p = sim.particles();
    double sum = 0.0, n = 0.0;
    for (std::size_t i = 0; i < sim.owned(); ++i)
        if (!p.is_kinematic(i)) {
            sum += norm2(p.velocity[i]);
            n += 1.0;
        }
    if (sim.shared()) {
        sum = mpi::sum(sum);
        n = mpi::sum(n);
    }
    return n > 0.0 ? std::sqrt(sum / n) : 0.0;
}

// The drum's wall turning about the drum's axis (z, through the origin) at
// omega, rad/s (right-handed about +z); motion 0 of the drum's scenario.
inline RigidMotion drum_rotation(double omega) { return {{0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}, omega, {0.0, 0.0, 0.0}}; }

// The bed settles at least this long, s: twice the time to fall the drum's diameter.
inline double drum_fall_time(const io::DrumSettings& s) { return 2.0 * std::sqrt(2.0 * s.geometry.diameter / 9.81); }

}  // namespace tumble::experiments
